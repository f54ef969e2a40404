"""Geometry helpers for drawing: quaternions that aim +z, arrow and circle segments (float32, m), a disk's outline (body
frame, m)."""

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


#: A drawn disk's rim segments and spokes (the spokes make its spin visible), and their colours (RGB).
DISK_RIM_SEGMENTS = 40
DISK_SPOKES = 3
DISK_RIM_COLOR, DISK_SPOKE_COLOR = (40, 100, 220), (215, 45, 45)


def disk_outline_segments(radius_m: float) -> np.ndarray:
    """(DISK_RIM_SEGMENTS + DISK_SPOKES, 2, 3) segments of a disk's rim then spokes (m), in body components, axis along
    body y."""
    angles = np.linspace(0.0, 2.0 * np.pi, DISK_RIM_SEGMENTS + 1)
    rim = radius_m * np.stack([np.cos(angles), np.zeros_like(angles), np.sin(angles)], axis=-1)
    spoke_angles = np.linspace(0.0, 2.0 * np.pi, DISK_SPOKES, endpoint=False)
    spoke_ends = radius_m * np.stack([np.cos(spoke_angles), np.zeros(DISK_SPOKES), np.sin(spoke_angles)], axis=-1)
    spokes = np.stack([np.zeros((DISK_SPOKES, 3)), spoke_ends], axis=1)
    return np.concatenate([np.stack([rim[:-1], rim[1:]], axis=1), spokes])


def disk_outline_colors() -> np.ndarray:
    """(DISK_RIM_SEGMENTS + DISK_SPOKES, 2, 3) uint8 colours of :func:`disk_outline_segments`: blue rim, red spokes."""
    rim = np.broadcast_to(np.array(DISK_RIM_COLOR, np.uint8), (DISK_RIM_SEGMENTS, 2, 3))
    spokes = np.broadcast_to(np.array(DISK_SPOKE_COLOR, np.uint8), (DISK_SPOKES, 2, 3))
    return np.concatenate([rim, spokes])
