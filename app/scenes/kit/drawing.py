"""Geometry helpers for drawing: quaternions that aim +z, arrow and circle segments (float32, m)."""

from __future__ import annotations

import numpy as np


def quaternion_z_to(direction: np.ndarray) -> np.ndarray:
    """Unit quaternion (wxyz) rotating the local +z axis onto ``direction``."""
    d = np.asarray(direction, dtype=float)
    d = d / np.linalg.norm(d)
    z = np.array([0.0, 0.0, 1.0])
    c = float(z @ d)
    if c < -1.0 + 1e-12:
        return np.array([0.0, 1.0, 0.0, 0.0])  # half turn about x
    axis = np.cross(z, d)
    q = np.array([1.0 + c, *axis])
    return q / np.linalg.norm(q)


def arrow_segments(tails: np.ndarray, vectors: np.ndarray, scale: float) -> np.ndarray:
    """(N, 2, 3) start/end points for ``add_arrows`` from tails and vectors (scaled)."""
    tails = np.asarray(tails, dtype=float).reshape(-1, 3)
    heads = tails + scale * np.asarray(vectors, dtype=float).reshape(-1, 3)
    return np.stack([tails, heads], axis=1).astype(np.float32)


def circle_segments(*, radius: float, center=(0.0, 0.0, 0.0), normal=(0.0, 0.0, 1.0), segments: int = 96) -> np.ndarray:
    """(segments, 2, 3) float32 line segments of a circle of ``radius`` about ``normal`` through ``center``."""
    n = np.asarray(normal, dtype=float)
    n = n / np.linalg.norm(n)
    helper = np.array([1.0, 0.0, 0.0]) if abs(n[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    u = np.cross(n, helper)
    u /= np.linalg.norm(u)
    v = np.cross(n, u)
    angles = np.linspace(0.0, 2.0 * np.pi, segments + 1)
    points = np.asarray(center, dtype=float) + radius * (np.cos(angles)[:, None] * u + np.sin(angles)[:, None] * v)
    return np.stack([points[:-1], points[1:]], axis=1).astype(np.float32)
