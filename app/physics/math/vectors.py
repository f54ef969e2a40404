"""Vector helpers used across the statics and kinematics lessons.

Arrays are shape (3,) components on one named frame; the caller names the frame.
"""

from __future__ import annotations

import numpy as np


def unit_vector(v: np.ndarray) -> np.ndarray:
    """``v / |v|``; raises ValueError for a (near-)zero vector."""
    v = np.asarray(v, dtype=float)
    norm = float(np.linalg.norm(v))
    if norm < 1e-12:
        raise ValueError("cannot take the direction of a zero-length vector")
    return v / norm


def moment_about_point(point_on_line: np.ndarray, force: np.ndarray, about: np.ndarray) -> np.ndarray:
    """Moment (N·m) of ``force`` (N) acting on a line through ``point_on_line`` about ``about`` (m)."""
    return np.cross(np.asarray(point_on_line) - np.asarray(about), force)


def force_moment_about_axis(
    point_on_line: np.ndarray, force: np.ndarray, axis_point: np.ndarray, axis_direction: np.ndarray
) -> float:
    """Signed moment (N·m) of ``force`` about the axis through ``axis_point`` along ``axis_direction``.

    Positive by the right-hand rule about the axis unit vector.
    """
    return float(np.dot(moment_about_point(point_on_line, force, axis_point), unit_vector(axis_direction)))
