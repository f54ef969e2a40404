"""The 3-1-3 names the tops and gyroscopes use: thin uses of the general sequence functions.

3-1-3 angles: precession ``phi`` about the fixed Z axis, nutation ``theta``
about the line of nodes (x′), spin ``psi`` about the body's own z axis;
``R_world_body = Rz(phi) Rx(theta) Rz(psi)``. Angles in rad, rates in rad/s.
"""

from __future__ import annotations

import numpy as np

from app.physics.math.rotations.angular_velocity import angular_velocity_body
from app.physics.math.rotations.sequences import angles_from_quaternion, quaternion_from_angles

EULER_313 = "3-1-3"


def quaternion_from_euler_313(
    phi_rad: float | np.ndarray, theta_rad: float | np.ndarray, psi_rad: float | np.ndarray
) -> np.ndarray:
    """``q_world_body`` (``wxyz``) for 3-1-3 angles: ``Rz(phi) Rx(theta) Rz(psi)``; broadcasts."""
    angles = np.stack(np.broadcast_arrays(phi_rad, theta_rad, psi_rad), axis=-1)
    return quaternion_from_angles(angles, EULER_313)


def euler_313_from_quaternion(q: np.ndarray) -> np.ndarray:
    """3-1-3 angles ``(phi, theta, psi)`` in rad (shape (..., 3)) of ``wxyz`` quaternions.

    Well defined through gimbal lock: ``theta = 2·atan2(|(x, y)|, |(w, z)|)`` never
    takes ``acos`` of a rounded value, and at ``theta = 0`` (or π) only ``phi + psi``
    (or ``phi − psi``) is determined, so the free difference (or sum) is set to
    zero instead of becoming NaN. ``phi`` and ``psi`` are wrapped to [−π, π);
    unwrap a time series with ``numpy.unwrap``.
    """
    return angles_from_quaternion(q, EULER_313).angles_rad


def body_rates_from_euler_313_rates(
    theta_rad: float | np.ndarray,
    psi_rad: float | np.ndarray,
    phi_dot: float | np.ndarray,
    theta_dot: float | np.ndarray,
    psi_dot: float | np.ndarray,
) -> np.ndarray:
    """Body-frame angular velocity (rad/s) from 3-1-3 angle rates (it does not depend on ``phi``)."""
    angles = np.stack(np.broadcast_arrays(0.0, theta_rad, psi_rad), axis=-1)
    rates = np.stack(np.broadcast_arrays(phi_dot, theta_dot, psi_dot), axis=-1)
    return angular_velocity_body(angles, rates, EULER_313)
