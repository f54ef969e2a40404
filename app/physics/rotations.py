"""Rotations: quaternions, rotation matrices and 3-1-3 Euler angles.

Conventions used everywhere in Dynamics Lab (and by viser):

* quaternions are ``wxyz`` (scalar first), unit length;
* ``q_world_body`` rotates *body* components into *world* components:
  ``v_world = R(q_world_body) @ v_body``;
* the world frame has +Z up;
* 3-1-3 Euler angles (precession ``phi`` about world Z, nutation ``theta``
  about the line of nodes, spin ``psi`` about body 3) compose as
  ``R = Rz(phi) @ Rx(theta) @ Rz(psi)``.

Scalar kernels (``*_inplace``) are numba-compilable and used inside the
integrators; the array functions are their numpy counterparts for callers.
"""

from __future__ import annotations

import math

import numpy as np


def quaternion_multiply(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Hamilton product ``a ⊗ b`` of ``wxyz`` quaternions (broadcasts over leading axes)."""
    a = np.asarray(a, dtype=float)
    b = np.asarray(b, dtype=float)
    aw, ax, ay, az = np.moveaxis(a, -1, 0)
    bw, bx, by, bz = np.moveaxis(b, -1, 0)
    return np.stack(
        [
            aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
        ],
        axis=-1,
    )


def quaternion_conjugate(q: np.ndarray) -> np.ndarray:
    """Conjugate (the inverse rotation for a unit quaternion), ``wxyz``."""
    q = np.asarray(q, dtype=float)
    return q * np.array([1.0, -1.0, -1.0, -1.0])


def quaternion_from_axis_angle(axis: np.ndarray, angle_rad: float) -> np.ndarray:
    """Unit ``wxyz`` quaternion for a right-handed rotation of ``angle_rad`` about ``axis``."""
    axis = np.asarray(axis, dtype=float)
    norm = float(np.linalg.norm(axis))
    if norm == 0.0:
        raise ValueError("rotation axis must be non-zero")
    half = 0.5 * angle_rad
    return np.concatenate([[math.cos(half)], math.sin(half) * axis / norm])


def rotation_matrix(q: np.ndarray) -> np.ndarray:
    """``R_world_body`` (shape (..., 3, 3)) of a ``wxyz`` quaternion (normalised first)."""
    q = np.asarray(q, dtype=float)
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    w, x, y, z = np.moveaxis(q, -1, 0)
    return np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], axis=-1),
            np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], axis=-1),
            np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], axis=-1),
        ],
        axis=-2,
    )


def rotate_vector(q: np.ndarray, v_body: np.ndarray) -> np.ndarray:
    """World components of the body vector ``v_body`` for attitude ``q`` (broadcasts)."""
    return np.einsum("...ij,...j->...i", rotation_matrix(q), np.asarray(v_body, dtype=float))


def quaternion_from_euler_313(phi_rad: float, theta_rad: float, psi_rad: float) -> np.ndarray:
    """``q_world_body`` for 3-1-3 angles: ``Rz(phi) Rx(theta) Rz(psi)``."""
    # Rz(a) Rx(b) Rz(c) in closed form: (phi+psi) and (phi-psi) half angles.
    c = math.cos(0.5 * theta_rad)
    s = math.sin(0.5 * theta_rad)
    sum_half = 0.5 * (phi_rad + psi_rad)
    diff_half = 0.5 * (phi_rad - psi_rad)
    return np.array([c * math.cos(sum_half), s * math.cos(diff_half), s * math.sin(diff_half), c * math.sin(sum_half)])


def euler_313_from_quaternion(q: np.ndarray) -> np.ndarray:
    """3-1-3 angles ``(phi, theta, psi)`` in rad (shape (..., 3)) of ``wxyz`` quaternions.

    Well defined through gimbal lock: ``theta = 2·atan2(|(x, y)|, |(w, z)|)`` never
    takes ``acos`` of a rounded value, and at ``theta = 0`` (or π) only ``phi + psi``
    (or ``phi − psi``) is determined, so the free difference is set to zero instead
    of becoming NaN. ``phi`` and ``psi`` are wrapped to (−π, π]; unwrap a time series
    with ``numpy.unwrap``.
    """
    q = np.asarray(q, dtype=float)
    w, x, y, z = np.moveaxis(q, -1, 0)
    theta = 2.0 * np.arctan2(np.hypot(x, y), np.hypot(w, z))
    sum_half = np.arctan2(z, w)  # (phi + psi)/2
    diff_half = np.arctan2(y, x)  # (phi - psi)/2
    phi = sum_half + diff_half
    psi = sum_half - diff_half
    wrap = lambda a: np.mod(a + np.pi, 2.0 * np.pi) - np.pi  # noqa: E731
    return np.stack([wrap(phi), theta, wrap(psi)], axis=-1)


def body_rates_from_euler_313_rates(
    theta_rad: float, psi_rad: float, phi_dot: float, theta_dot: float, psi_dot: float
) -> np.ndarray:
    """Body-frame angular velocity (rad/s) from 3-1-3 angle rates."""
    st, ct = math.sin(theta_rad), math.cos(theta_rad)
    sp, cp = math.sin(psi_rad), math.cos(psi_rad)
    return np.array(
        [phi_dot * st * sp + theta_dot * cp, phi_dot * st * cp - theta_dot * sp, phi_dot * ct + psi_dot]
    )
