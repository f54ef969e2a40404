"""Euler's theorem: any displacement of a body about a fixed point is one turn about one axis.

The attitude ``A`` is set by a rotation sequence (conventions of
:mod:`app.physics.math.rotations`: ``R_world_body = R_a1(θ1) R_a2(θ2) R_a3(θ3)``,
taking body components to world components). Its equivalent turn is a unit axis
``n`` (world XYZ components) and an angle ``φ`` in [0, π], read from the
quaternion; Rodrigues' formula ``R = I + sin φ [n]× + (1 − cos φ) [n]×²`` rebuilt
from them gives the sequence's matrix back.

A second turn ``B``, by ``β`` about a fixed axis (X, Y or Z), shows that finite
rotations do not commute. Turns described about *fixed* axes compose on the left:
``A then B`` is ``R_B R_A`` and ``B then A`` is ``R_A R_B`` (``A`` here is its
equivalent turn about the fixed line ``n``). The two results differ by the turn
``R_AB R_BAᵀ``, whose angle is :attr:`FiniteRotation.order_gap_rad`.
Angles in rad.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from app.physics.math.rotations import (
    RotationSequence,
    axis_angle_from_matrix,
    elementary_rotation_matrix,
    matrix_from_angles,
    matrix_from_axis_angle,
    quaternion_from_matrix,
    rotation_sequence,
)

#: The fixed axes a second turn may be about, in the order of their coordinate index.
FIXED_AXES = ("X", "Y", "Z")


@dataclass(frozen=True)
class EquivalentTurn:
    """One attitude as a matrix, a ``wxyz`` quaternion (``w ≥ 0``) and Euler's axis and angle.

    ``R_world_body`` (3, 3); ``q_world_body`` (4,); ``axis_world`` (3,) unit, world
    components (+Z for the identity, whose axis is undefined); ``angle_rad`` in [0, π].
    """

    R_world_body: np.ndarray
    q_world_body: np.ndarray
    axis_world: np.ndarray
    angle_rad: float


def equivalent_turn(R_world_body: np.ndarray) -> EquivalentTurn:
    """Euler's axis and angle of the rotation matrix ``R_world_body`` (3, 3)."""
    R = np.asarray(R_world_body, dtype=float)
    q = quaternion_from_matrix(R)
    q = -q if q[0] < 0.0 else q
    axis, angle = axis_angle_from_matrix(R)
    return EquivalentTurn(R_world_body=R, q_world_body=q, axis_world=np.asarray(axis, float), angle_rad=float(angle))


@dataclass(frozen=True)
class FiniteRotation:
    """Attitude ``A`` from a sequence, its equivalent turn, and the two orders of ``A`` and a second turn ``B``.

    ``rodrigues_R`` (3, 3) is Rodrigues' formula evaluated with ``A``'s axis and angle;
    ``a_then_b`` is ``R_B R_A``, ``b_then_a`` is ``R_A R_B``; ``order_gap_rad`` (in [0, π])
    is the angle of the turn that takes one result to the other (0 when they commute).
    """

    sequence: RotationSequence
    turn_a: EquivalentTurn
    rodrigues_R: np.ndarray
    turn_b: EquivalentTurn
    a_then_b: EquivalentTurn
    b_then_a: EquivalentTurn
    order_gap_rad: float

    @property
    def rodrigues_mismatch(self) -> float:
        """Largest entry of ``|R_Rodrigues − R_sequence|`` (dimensionless; rounding only, about 1e-16)."""
        return float(np.max(np.abs(self.rodrigues_R - self.turn_a.R_world_body)))


def fixed_axis_index(name: str) -> int:
    """0, 1, 2 for ``"X"``, ``"Y"``, ``"Z"``; ValueError names the choices."""
    try:
        return FIXED_AXES.index(name)
    except ValueError:
        raise ValueError(f"second turn axis must be one of {', '.join(FIXED_AXES)} (got {name!r})") from None


def finite_rotation(
    angles_rad: np.ndarray, sequence: str | RotationSequence, *, second_axis: str, second_angle_rad: float
) -> FiniteRotation:
    """Euler's theorem for the attitude ``angles_rad`` (3,) of ``sequence``, and its two orders with a turn
    of ``second_angle_rad`` about the fixed axis ``second_axis`` (``"X"``, ``"Y"`` or ``"Z"``)."""
    seq = rotation_sequence(sequence)
    angles = np.asarray(angles_rad, dtype=float)
    if angles.shape != (3,) or not np.all(np.isfinite(angles)):
        raise ValueError(f"angles_rad must be three finite angles (got {angles!r})")
    if not np.isfinite(second_angle_rad):
        raise ValueError("second_angle_rad must be finite")
    R_a = matrix_from_angles(angles, seq)
    turn_a = equivalent_turn(R_a)
    R_b = elementary_rotation_matrix(fixed_axis_index(second_axis), float(second_angle_rad))
    R_ab, R_ba = R_b @ R_a, R_a @ R_b
    _, gap = axis_angle_from_matrix(R_ab @ R_ba.T)
    return FiniteRotation(
        sequence=seq,
        turn_a=turn_a,
        rodrigues_R=matrix_from_axis_angle(turn_a.axis_world, turn_a.angle_rad),
        turn_b=equivalent_turn(R_b),
        a_then_b=equivalent_turn(R_ab),
        b_then_a=equivalent_turn(R_ba),
        order_gap_rad=float(gap),
    )
