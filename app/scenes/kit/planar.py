"""A mechanism's plane drawn in the world: its x axis along world x, its y axis up (world z), on the plane y = 0.

The planar scenes (linkages, the slider-crank, a ladder, colliding disks) are seen from −y.
"""

from __future__ import annotations

import numpy as np


def to_world(points_xy: np.ndarray) -> np.ndarray:
    """Planar (…, 2) points (m) to world (…, 3): x → x, y → z, on the plane y = 0."""
    p = np.asarray(points_xy, dtype=float)
    return np.stack([p[..., 0], np.zeros(p.shape[:-1]), p[..., 1]], axis=-1)


def polyline_segments(points_xy: np.ndarray) -> np.ndarray:
    """(N−1, 2, 3) float32 segments joining consecutive finite planar points."""
    world = to_world(points_xy)
    segments = np.stack([world[:-1], world[1:]], axis=1)
    keep = np.all(np.isfinite(segments), axis=(1, 2))
    out = segments[keep]
    return out.astype(np.float32) if len(out) else np.zeros((1, 2, 3), np.float32)
