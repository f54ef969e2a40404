"""Axis–angle: every rotation is a turn by an angle about one fixed line (Euler's theorem).

A rotation is written as a unit ``axis`` (shape (..., 3), components on the
frame the rotation is expressed in, the world frame for ``q_world_body``) and a
right-handed ``angle_rad`` (shape (...)). Recovered angles lie in [0, π]; the
axis of the identity is undefined and is returned as +Z.
"""

from __future__ import annotations

import numpy as np

from app.physics.math.rotations.quaternions import quaternion_from_matrix

_IDENTITY_AXIS = np.array([0.0, 0.0, 1.0])


def _unit_axis(axis: np.ndarray) -> np.ndarray:
    axis = np.asarray(axis, dtype=float)
    if axis.shape[-1:] != (3,):
        raise ValueError(f"rotation axis must have 3 components (got shape {axis.shape})")
    norm = np.linalg.norm(axis, axis=-1, keepdims=True)
    if np.any(norm == 0.0) or not np.all(np.isfinite(norm)):
        raise ValueError("rotation axis must be a non-zero, finite vector")
    return axis / norm


def quaternion_from_axis_angle(axis: np.ndarray, angle_rad: float | np.ndarray) -> np.ndarray:
    """Unit ``wxyz`` quaternion for a right-handed rotation of ``angle_rad`` about ``axis`` (broadcasts)."""
    unit = _unit_axis(axis)
    half = 0.5 * np.asarray(angle_rad, dtype=float)[..., None]
    return np.concatenate([np.cos(half), np.sin(half) * unit], axis=-1)


def matrix_from_axis_angle(axis: np.ndarray, angle_rad: float | np.ndarray) -> np.ndarray:
    """Rotation matrix (..., 3, 3) of a turn by ``angle_rad`` about ``axis`` (Rodrigues' formula).

    ``R = I + sin α [n]× + (1 − cos α) [n]×²`` with ``n`` the unit axis.
    """
    n = _unit_axis(axis)
    angle = np.asarray(angle_rad, dtype=float)[..., None, None]
    nx, ny, nz = np.moveaxis(n, -1, 0)
    zero = np.zeros_like(nx)
    cross = np.stack([np.stack([zero, -nz, ny], -1), np.stack([nz, zero, -nx], -1), np.stack([-ny, nx, zero], -1)], -2)
    return np.eye(3) + np.sin(angle) * cross + (1.0 - np.cos(angle)) * (cross @ cross)


def axis_angle_from_quaternion(q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(axis, angle_rad)`` of ``wxyz`` quaternions: unit axis (..., 3), angle in [0, π] (...).

    ``angle = 2·atan2(|v|, |w|)`` keeps full precision for tiny turns and for
    half turns alike (no ``acos`` of a rounded number). ``q`` and ``−q`` give the
    same answer. For the identity the axis is undefined; +Z is returned.
    """
    q = np.asarray(q, dtype=float)
    if q.shape[-1:] != (4,):
        raise ValueError(f"a quaternion has 4 components wxyz (got shape {q.shape})")
    q = np.where(q[..., :1] < 0.0, -q, q)
    v = q[..., 1:]
    sin_half = np.linalg.norm(v, axis=-1)
    angle = 2.0 * np.arctan2(sin_half, q[..., 0])
    safe = np.where(sin_half > 0.0, sin_half, 1.0)[..., None]
    axis = np.where(sin_half[..., None] > 0.0, v / safe, _IDENTITY_AXIS)
    return axis, angle


def axis_angle_from_matrix(R: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(axis, angle_rad)`` of a rotation matrix (..., 3, 3), via :func:`quaternion_from_matrix`.

    Reading the axis off the skew part of ``R`` fails near a half turn; going
    through the quaternion does not.
    """
    return axis_angle_from_quaternion(quaternion_from_matrix(R))
