"""Angular velocity from the rates of a sequence's angles, and back.

Each angle turns about its own axis, so the angular velocity is the vector sum
of the three rates along the three turn axes (these are not orthogonal):

``ω = θ̇1 a1 + θ̇2 a2′ + θ̇3 a3″`` with ``a1`` the fixed axis, ``a2′`` axis ``a2``
of ``x′y′z′`` and ``a3″`` axis ``a3`` of ``x″y″z″``. In matrix form ``ω = J(θ) θ̇``;
the columns of ``J`` are those axes in world components (``J_world``) or body
components (``J_body = Rᵀ J_world``). ``|det J| = |sin θ2|`` (proper) or ``|cos θ2|``
(Tait–Bryan): at gimbal lock ``a1`` and ``a3″`` are parallel and the rates can
no longer be found from ω. Angles in rad, rates in rad/s, ω in rad/s; arrays
broadcast over leading axes.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.math.rotations.sequences import (
    GIMBAL_LOCK_TOLERANCE_RAD,
    RotationSequence,
    elementary_rotation_matrix,
    gimbal_lock_distance_rad,
    intermediate_frames,
    rotation_sequence,
)


def angle_rate_matrix_world(angles_rad: np.ndarray, sequence: str | RotationSequence) -> np.ndarray:
    """``J_world`` (..., 3, 3): column ``k`` is the axis of turn ``k+1`` in world components."""
    return np.swapaxes(intermediate_frames(angles_rad, sequence).rotation_axes_world, -1, -2)


def angle_rate_matrix_body(angles_rad: np.ndarray, sequence: str | RotationSequence) -> np.ndarray:
    """``J_body`` (..., 3, 3): column ``k`` is the axis of turn ``k+1`` in body components.

    Turn 3's axis is body axis ``a3``; turn 2's is ``R_a3(θ3)ᵀ e_a2``; turn 1's is
    ``(R_a2(θ2) R_a3(θ3))ᵀ e_a1``. It does not depend on ``θ1``.
    """
    seq = rotation_sequence(sequence)
    angles = np.asarray(angles_rad, dtype=float)
    R3 = elementary_rotation_matrix(seq.axes[2], angles[..., 2])
    R23 = elementary_rotation_matrix(seq.axes[1], angles[..., 1]) @ R3
    third = np.zeros(angles.shape[:-1] + (3,))
    third[..., seq.axes[2]] = 1.0
    return np.stack([R23[..., seq.axes[0], :], R3[..., seq.axes[1], :], third], axis=-1)


def angular_velocity_world(
    angles_rad: np.ndarray, angle_rates_rad_s: np.ndarray, sequence: str | RotationSequence
) -> np.ndarray:
    """ω (rad/s, world components, shape (..., 3)) from the angles and their rates."""
    J = angle_rate_matrix_world(angles_rad, sequence)
    return np.einsum("...ij,...j->...i", J, np.asarray(angle_rates_rad_s, dtype=float))


def angular_velocity_body(
    angles_rad: np.ndarray, angle_rates_rad_s: np.ndarray, sequence: str | RotationSequence
) -> np.ndarray:
    """ω (rad/s, body components, shape (..., 3)) from the angles and their rates."""
    J = angle_rate_matrix_body(angles_rad, sequence)
    return np.einsum("...ij,...j->...i", J, np.asarray(angle_rates_rad_s, dtype=float))


def angular_acceleration_world(
    angles_rad: np.ndarray,
    angle_rates_rad_s: np.ndarray,
    angle_accelerations_rad_s2: np.ndarray,
    sequence: str | RotationSequence,
) -> np.ndarray:
    """α = dω/dt (rad/s², world components, shape (..., 3)).

    Differentiating ``ω = Σ θ̇k nk``: each turn axis ``nk`` is carried round by the
    turns before it, ``ṅ2 = θ̇1 n1 × n2`` and ``ṅ3 = (θ̇1 n1 + θ̇2 n2) × n3``, so
    ``α = Σ θ̈k nk + θ̇1 n1 × θ̇2 n2 + (θ̇1 n1 + θ̇2 n2) × θ̇3 n3``.
    """
    axes = intermediate_frames(angles_rad, sequence).rotation_axes_world
    rates = np.asarray(angle_rates_rad_s, dtype=float)
    accelerations = np.asarray(angle_accelerations_rad_s2, dtype=float)
    turn1, turn2, turn3 = (rates[..., k, None] * axes[..., k, :] for k in range(3))
    along_axes = np.einsum("...ki,...k->...i", axes, accelerations)
    return along_axes + np.cross(turn1, turn2) + np.cross(turn1 + turn2, turn3)


def angular_acceleration_body(
    angles_rad: np.ndarray,
    angle_rates_rad_s: np.ndarray,
    angle_accelerations_rad_s2: np.ndarray,
    sequence: str | RotationSequence,
) -> np.ndarray:
    """α (rad/s², body components): ``Rᵀ α_world`` (ω × ω = 0, so both frames see the same dω/dt)."""
    R = intermediate_frames(angles_rad, sequence).R_world_frame[..., 3, :, :]
    alpha = angular_acceleration_world(angles_rad, angle_rates_rad_s, angle_accelerations_rad_s2, sequence)
    return np.einsum("...ji,...j->...i", R, alpha)


def _check_not_locked(angles_rad: np.ndarray, seq: RotationSequence) -> None:
    distance = gimbal_lock_distance_rad(angles_rad, seq)
    locked = distance <= GIMBAL_LOCK_TOLERANCE_RAD
    if np.any(locked):
        theta2 = float(np.asarray(angles_rad, dtype=float)[..., 1][locked].flat[0])
        first, third = seq.axis_label(1), seq.axis_label(3)
        raise ValueError(
            f"the angle rates are undefined at gimbal lock: θ2 = {math.degrees(theta2):.6g}° in the {seq.name} "
            f"sequence puts the third turn's axis {third} on the line of the first turn's axis {first}, so ω fixes "
            "only the sum or difference of the first and third rates. Follow the attitude with a quaternion "
            "(or a rotation matrix) through this point, or use another sequence."
        )


def angle_rates_from_angular_velocity_body(
    angles_rad: np.ndarray, omega_body_rad_s: np.ndarray, sequence: str | RotationSequence
) -> np.ndarray:
    """Angle rates (rad/s, shape (..., 3)) that produce body-frame ω; ValueError at gimbal lock."""
    seq = rotation_sequence(sequence)
    _check_not_locked(angles_rad, seq)
    J = angle_rate_matrix_body(angles_rad, seq)
    return np.linalg.solve(J, np.asarray(omega_body_rad_s, dtype=float)[..., None])[..., 0]


def angle_rates_from_angular_velocity_world(
    angles_rad: np.ndarray, omega_world_rad_s: np.ndarray, sequence: str | RotationSequence
) -> np.ndarray:
    """Angle rates (rad/s, shape (..., 3)) that produce world-frame ω; ValueError at gimbal lock."""
    seq = rotation_sequence(sequence)
    _check_not_locked(angles_rad, seq)
    J = angle_rate_matrix_world(angles_rad, seq)
    return np.linalg.solve(J, np.asarray(omega_world_rad_s, dtype=float)[..., None])[..., 0]
