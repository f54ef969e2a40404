"""The twelve rotation sequences: three body-fixed (intrinsic) rotations in turn.

A sequence ``a1-a2-a3`` (axes numbered 1 = x, 2 = y, 3 = z) turns a frame that
starts aligned with the fixed frame ``XYZ``:

1. by ``θ1`` about its axis ``a1`` (still the fixed axis), giving ``x′y′z′``;
2. by ``θ2`` about axis ``a2`` of ``x′y′z′``, giving ``x″y″z″``;
3. by ``θ3`` about axis ``a3`` of ``x″y″z″``, giving the body frame ``xyz``.

So ``R_world_body = R_a1(θ1) R_a2(θ2) R_a3(θ3)``, where ``R_k(θ)`` is the
elementary right-handed rotation about coordinate axis ``k`` (its columns are the
turned axes in the old components). Reading the same product right to left is
the same attitude reached by turning about the *fixed* axes ``a3``, ``a2``, ``a1``.

*Proper Euler* sequences repeat the first axis (3-1-3, 3-2-3, 1-2-1, 1-3-1,
2-1-2, 2-3-2); *Tait–Bryan* sequences use all three (1-2-3, 1-3-2, 2-1-3,
2-3-1, 3-1-2, 3-2-1). Gimbal lock is where axis ``a3`` of the body lines up
with the fixed axis ``a1``: ``θ2 = 0`` or ``π`` (proper), ``θ2 = ±π/2``
(Tait–Bryan). There only ``θ1 ± θ3`` is determined.

Angles are in radians, shape ``(..., 3)``; recovered angles have ``θ1, θ3`` in
[−π, π) and ``θ2`` in [0, π] (proper) or [−π/2, π/2] (Tait–Bryan).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np

from app.physics.math.rotations.quaternions import quaternion_from_matrix, quaternion_multiply

AXIS_NAMES = ("x", "y", "z")
FIXED_AXIS_NAMES = ("X", "Y", "Z")
PRIMES = ("", "′", "″")  # frame after 0, 1, 2 rotations: XYZ is written in capitals instead

#: Within this distance (rad) of gimbal lock the first and third angles are
#: reported as degenerate: rounding alone moves them apart by more than 1e-8 rad.
GIMBAL_LOCK_TOLERANCE_RAD = 1e-8


COMMON_NAMES: dict[str, tuple[str, str, str]] = {
    "3-1-3": ("precession", "nutation", "spin"),
    "3-2-1": ("yaw (heading)", "pitch (elevation)", "roll (bank)"),
}


@dataclass(frozen=True)
class RotationSequence:
    """One of the twelve sequences, e.g. ``3-2-1``; ``axes`` are 0-based (0 = x)."""

    name: str
    axes: tuple[int, int, int]

    @property
    def kind(self) -> Literal["proper Euler", "Tait–Bryan"]:
        return "proper Euler" if self.axes[0] == self.axes[2] else "Tait–Bryan"

    @property
    def is_proper(self) -> bool:
        return self.axes[0] == self.axes[2]

    @property
    def parity(self) -> int:
        """+1 if (a1, a2, the third axis) is a cyclic order of (x, y, z), else −1."""
        i, j = self.axes[0], self.axes[1]
        return 1 if (j - i) % 3 == 1 else -1

    @property
    def lock_angles_rad(self) -> tuple[float, ...]:
        """Values of ``θ2`` in [−π, π] at which the sequence is in gimbal lock."""
        return (-math.pi, 0.0, math.pi) if self.is_proper else (-0.5 * math.pi, 0.5 * math.pi)

    def axis_label(self, step: int) -> str:
        """Name of the axis turned about at ``step`` (1, 2, 3), e.g. ``Z``, ``x′``, ``z″``."""
        axis = self.axes[step - 1]
        return FIXED_AXIS_NAMES[axis] if step == 1 else AXIS_NAMES[axis] + PRIMES[step - 1]

    def angle_meanings(self) -> tuple[str, str, str]:
        """One sentence per angle saying which axis it turns about."""
        names = COMMON_NAMES.get(self.name, ("", "", ""))
        frames = ("the fixed frame XYZ", "the once-turned frame x′y′z′", "the twice-turned frame x″y″z″")
        first, second, third = (
            f"θ{k}{' (' + names[k - 1] + ')' if names[k - 1] else ''}: turn about {self.axis_label(k)}, "
            f"axis {self.axes[k - 1] + 1} of {frames[k - 1]}"
            for k in (1, 2, 3)
        )
        return first, second, third

    def lock_combination_sign(self, theta2_rad: float | np.ndarray) -> np.ndarray:
        """``s`` such that only ``θ1 + s·θ3`` is determined at the gimbal lock nearest ``θ2``.

        Proper: ``+1`` near ``θ2 = 0`` (the two turns add), ``−1`` near ``π``.
        Tait–Bryan: ``parity·sign(sin θ2)``, from ``R_a2(±π/2) R_a3(θ) = R_a1(±parity·θ) R_a2(±π/2)``.
        """
        theta2 = np.asarray(theta2_rad, dtype=float)
        if self.is_proper:
            return np.where(np.cos(theta2) >= 0.0, 1.0, -1.0)
        return self.parity * np.where(np.sin(theta2) >= 0.0, 1.0, -1.0)


PROPER_EULER = ("3-1-3", "3-2-3", "1-2-1", "1-3-1", "2-1-2", "2-3-2")
TAIT_BRYAN = ("1-2-3", "1-3-2", "2-1-3", "2-3-1", "3-1-2", "3-2-1")
SEQUENCES: dict[str, RotationSequence] = {
    name: RotationSequence(name, tuple(int(a) - 1 for a in name.split("-")))  # type: ignore[arg-type]
    for name in PROPER_EULER + TAIT_BRYAN
}


def rotation_sequence(sequence: str | RotationSequence) -> RotationSequence:
    """The sequence named ``sequence`` (e.g. ``"3-2-1"``); ValueError names the twelve choices."""
    if isinstance(sequence, RotationSequence):
        return sequence
    try:
        return SEQUENCES[sequence]
    except (KeyError, TypeError):
        raise ValueError(
            f"unknown rotation sequence {sequence!r}; use one of {', '.join(SEQUENCES)} "
            "(axes 1 = x, 2 = y, 3 = z, turned in that order about the body's own axes)"
        ) from None


def _angles_array(angles_rad: np.ndarray) -> np.ndarray:
    angles = np.asarray(angles_rad)
    angles = angles.astype(np.result_type(angles, float), copy=False)  # complex stays complex
    if angles.shape[-1:] != (3,):
        raise ValueError(f"a rotation sequence takes 3 angles (got shape {angles.shape})")
    return angles


def elementary_rotation_matrix(axis: int, angle_rad: float | np.ndarray) -> np.ndarray:
    """``R_axis(angle)`` (shape angle.shape + (3, 3)): right-handed turn about coordinate axis ``axis`` (0 = x)."""
    angle = np.asarray(angle_rad)
    c, s = np.cos(angle), np.sin(angle)
    R = np.zeros(angle.shape + (3, 3), dtype=np.result_type(angle, float))
    j, k = (axis + 1) % 3, (axis + 2) % 3
    R[..., axis, axis] = 1.0
    R[..., j, j] = c
    R[..., k, k] = c
    R[..., k, j] = s
    R[..., j, k] = -s
    return R


def elementary_quaternion(axis: int, angle_rad: np.ndarray) -> np.ndarray:
    """``wxyz`` quaternion of a turn by ``angle`` about coordinate axis ``axis`` (0 = x)."""
    half = 0.5 * np.asarray(angle_rad)
    q = np.zeros(half.shape + (4,), dtype=np.result_type(half, float))
    q[..., 0] = np.cos(half)
    q[..., 1 + axis] = np.sin(half)
    return q


def matrix_from_angles(angles_rad: np.ndarray, sequence: str | RotationSequence) -> np.ndarray:
    """``R_world_body = R_a1(θ1) R_a2(θ2) R_a3(θ3)`` (shape (..., 3, 3)); complex angles allowed."""
    seq = rotation_sequence(sequence)
    angles = _angles_array(angles_rad)
    R = elementary_rotation_matrix(seq.axes[0], angles[..., 0])
    for step in (1, 2):
        R = R @ elementary_rotation_matrix(seq.axes[step], angles[..., step])
    return R


def quaternion_from_angles(angles_rad: np.ndarray, sequence: str | RotationSequence) -> np.ndarray:
    """``q_world_body = q_a1(θ1) ⊗ q_a2(θ2) ⊗ q_a3(θ3)``, ``wxyz`` (shape (..., 4))."""
    seq = rotation_sequence(sequence)
    angles = _angles_array(angles_rad)
    q = elementary_quaternion(seq.axes[0], angles[..., 0])
    for step in (1, 2):
        q = quaternion_multiply(q, elementary_quaternion(seq.axes[step], angles[..., step]))
    return q


def wrap_angle_rad(angle_rad: np.ndarray) -> np.ndarray:
    """Angles wrapped to [−π, π)."""
    wrapped = np.mod(np.asarray(angle_rad, dtype=float) + np.pi, 2.0 * np.pi) - np.pi
    return np.where(wrapped >= np.pi, wrapped - 2.0 * np.pi, wrapped)  # mod can round up to 2π


def gimbal_lock_distance_rad(angles_rad: np.ndarray, sequence: str | RotationSequence) -> np.ndarray:
    """How far (rad, in [0, π/2]) the middle angle is from the nearest gimbal lock (shape (...)).

    Proper: distance of ``θ2`` from a multiple of π; Tait–Bryan: from an odd
    multiple of π/2. It equals the angle between body axis ``a3`` and the line
    of fixed axis ``a1``, so it does not depend on which angle set is used.
    """
    seq = rotation_sequence(sequence)
    theta2 = _angles_array(angles_rad)[..., 1].real
    s, c = np.abs(np.sin(theta2)), np.abs(np.cos(theta2))
    return np.arctan2(s, c) if seq.is_proper else np.arctan2(c, s)


@dataclass(frozen=True)
class SequenceAngles:
    """Angles of one sequence recovered from an attitude, and how close it is to gimbal lock.

    ``angles_rad`` (..., 3) always reproduce the attitude. Where ``degenerate``
    (within :data:`GIMBAL_LOCK_TOLERANCE_RAD` of lock) only ``θ1 + s·θ3`` with
    ``s = lock_sign`` is determined; any split of it gives the same attitude.
    """

    sequence: RotationSequence
    angles_rad: np.ndarray
    lock_distance_rad: np.ndarray

    @property
    def degenerate(self) -> np.ndarray:
        return self.lock_distance_rad <= GIMBAL_LOCK_TOLERANCE_RAD

    @property
    def lock_sign(self) -> np.ndarray:
        return self.sequence.lock_combination_sign(self.angles_rad[..., 1])


def angles_from_quaternion(q: np.ndarray, sequence: str | RotationSequence) -> SequenceAngles:
    """Angles of ``sequence`` for ``wxyz`` attitudes ``q`` (shape (..., 4)), valid at and near gimbal lock.

    Proper ``i-j-i`` (``k`` the third axis, ``ε`` the parity): multiplying out
    ``q_i(θ1) ⊗ q_j(θ2) ⊗ q_i(θ3)`` gives components ``(w, q_i, q_j, ε q_k) =
    (cos½θ2 cos Σ, cos½θ2 sin Σ, sin½θ2 cos Δ, sin½θ2 sin Δ)`` with
    ``Σ = (θ1+θ3)/2`` and ``Δ = (θ1−θ3)/2``; so ``θ2 = 2·atan2(|(q_j, εq_k)|, |(w, q_i)|)``
    and Σ, Δ are two ``atan2`` calls. A Tait–Bryan ``i-j-k`` is reduced to ``i-j-i`` by
    ``q ⊗ q_j(π/2)`` (which maps ``R_k(θ3)`` to ``R_i(−εθ3)`` and adds π/2 to
    ``θ2``). No ``acos``/``asin`` of a rounded value is taken anywhere, and at
    lock the undetermined half is set to zero instead of becoming noise or NaN.
    """
    seq = rotation_sequence(sequence)
    q = np.asarray(q, dtype=float)
    if q.shape[-1:] != (4,):
        raise ValueError(f"a quaternion has 4 components wxyz (got shape {q.shape})")
    i, j = seq.axes[0], seq.axes[1]
    k = 3 - i - j
    eps = seq.parity
    if np.any(np.linalg.norm(q, axis=-1) == 0.0):
        raise ValueError("the zero quaternion is not an attitude")
    w, qi, qj, qk = q[..., 0], q[..., 1 + i], q[..., 1 + j], q[..., 1 + k]
    if seq.is_proper:
        a, b, c, d = w, qi, qj, eps * qk
    else:  # components of q ⊗ q_j(π/2) (times √2), read as the proper sequence i-j-i
        a, b, c, d = w - qj, qi - eps * qk, qj + w, qi + eps * qk
    norm_ab, norm_cd = np.hypot(a, b), np.hypot(c, d)
    theta2 = 2.0 * np.arctan2(norm_cd, norm_ab)
    # Exactly at lock one half is (±0, ±0): its angle is set to zero, splitting the
    # determined combination θ1 ± θ3 equally, rather than left to the signs of zeros.
    half_sum = np.where(norm_ab > 0.0, np.arctan2(b, a), 0.0)
    half_diff = np.where(norm_cd > 0.0, np.arctan2(d, c), 0.0)
    theta1 = wrap_angle_rad(half_sum + half_diff)
    theta3 = wrap_angle_rad(half_sum - half_diff)
    if not seq.is_proper:
        theta2 = theta2 - 0.5 * np.pi
        theta3 = wrap_angle_rad(-eps * theta3)
    angles = np.stack([theta1, theta2, theta3], axis=-1)
    return SequenceAngles(seq, angles, gimbal_lock_distance_rad(angles, seq))


def angles_from_matrix(R: np.ndarray, sequence: str | RotationSequence) -> SequenceAngles:
    """Angles of ``sequence`` for rotation matrices ``R_world_body`` (..., 3, 3); see :func:`angles_from_quaternion`."""
    return angles_from_quaternion(quaternion_from_matrix(R), sequence)


@dataclass(frozen=True)
class SequenceFrames:
    """The frames a sequence passes through, for drawing.

    ``R_world_frame[..., n, :, :]`` is the frame after ``n`` turns (0: XYZ,
    1: x′y′z′, 2: x″y″z″, 3: xyz); ``q_world_frame`` the same as ``wxyz``;
    ``rotation_axes_world[..., k, :]`` the unit axis (world components) of turn ``k+1``.
    """

    R_world_frame: np.ndarray
    q_world_frame: np.ndarray
    rotation_axes_world: np.ndarray


def intermediate_frames(angles_rad: np.ndarray, sequence: str | RotationSequence) -> SequenceFrames:
    """Frames after 0, 1, 2 and 3 turns of ``sequence`` and each turn's axis, world components."""
    seq = rotation_sequence(sequence)
    angles = _angles_array(angles_rad).real
    frames = [np.broadcast_to(np.eye(3), angles.shape[:-1] + (3, 3))]
    axes = []
    for step in range(3):
        axes.append(frames[-1][..., :, seq.axes[step]])  # the axis being turned about stays put
        frames.append(frames[-1] @ elementary_rotation_matrix(seq.axes[step], angles[..., step]))
    R = np.stack(frames, axis=-3)
    return SequenceFrames(
        R_world_frame=R, q_world_frame=quaternion_from_matrix(R), rotation_axes_world=np.stack(axes, axis=-2)
    )
