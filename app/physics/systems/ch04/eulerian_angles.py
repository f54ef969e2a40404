"""Eulerian angles of a body: precession φ, nutation θ and spin ψ (the 3-1-3 sequence), with ω and α.

Frames: world ``XYZ`` (+Z up); the *nutation frame* ``x′y′z′`` is the frame after the first two
turns (φ about Z, then θ about the line of nodes): x′ is the line of nodes, z′ is the body's
z axis, and the frame does not spin. The body frame ``xyz`` follows by the spin ψ about z′.
``R_world_body = Rz(φ) Rx(θ) Rz(ψ)``. Each angle moves at a constant acceleration
(:class:`~app.physics.systems.ch03.angle_rates.AngleMotion`, the motion of lesson 3.4).

ω is the sum of the three rates along their three turn axes, ``ω = φ̇ K + θ̇ i′ + ψ̇ k``; on the
nutation frame ``ω = θ̇ i′ + φ̇ sin θ j′ + (φ̇ cos θ + ψ̇) k′``. At θ = 0 or 180° the spin axis lies
on Z: φ and ψ turn about one line, only φ ± ψ is fixed by the attitude, the line of nodes is
not, and ω no longer determines φ̇ and ψ̇ apart (the angles are singular, the motion is not).
Angles in rad, rates rad/s, accelerations rad/s².
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution
from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.math.rotations import (
    GIMBAL_LOCK_TOLERANCE_RAD,
    gimbal_lock_distance_rad,
    intermediate_frames,
    rotation_sequence,
)
from app.physics.systems.ch03.angle_rates import AngleKinematics, AngleMotion

EULER_SEQUENCE = "3-1-3"
#: Within this angle of θ = 0 or 180° the readout warns that φ and ψ are nearly indistinguishable.
NEAR_SINGULAR_DEG = 5.0


@dataclass(frozen=True)
class EulerState:
    """At N instants: ``kinematics`` (angles (φ, θ, ψ), rates, attitude, the turn axes Z, line of nodes and body z,
    ω and α on the world and body frames, θ's distance from 0 or 180°) and, on the nutation frame x′y′z′, its
    attitude (N, 4) wxyz and ω (rad/s) and α (rad/s²) components (N, 3)."""

    kinematics: AngleKinematics
    nutation_frame_wxyz: np.ndarray
    angular_velocity_nutation: np.ndarray
    angular_acceleration_nutation: np.ndarray


@dataclass(frozen=True)
class EulerianAngleMotion:
    """φ, θ, ψ moving with constant accelerations from their values and rates at t = 0."""

    angles: AngleMotion

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> EulerianAngleMotion:
        names = ("precession", "nutation", "spin")
        return cls(
            AngleMotion(
                sequence=rotation_sequence(EULER_SEQUENCE),
                angles0_rad=np.radians([params[f"{n}_deg"] for n in names]),
                rates0_rad_s=np.array([params[f"{n}_rate_rad_s"] for n in names], dtype=float),
                accelerations_rad_s2=np.array([params[f"{n}_acceleration_rad_s2"] for n in names], dtype=float),
            )
        )

    def at(self, t_s: np.ndarray) -> EulerState:
        k = self.angles.kinematics(t_s)
        frames = intermediate_frames(k.angles_rad, EULER_SEQUENCE)
        nutation_R = frames.R_world_frame[:, 2]

        def on_nutation_frame(v: np.ndarray) -> np.ndarray:
            return np.einsum("nji,nj->ni", nutation_R, v)  # [R]ᵀ v: world components to x′y′z′

        return EulerState(
            kinematics=k,
            nutation_frame_wxyz=frames.q_world_frame[:, 2],
            angular_velocity_nutation=on_nutation_frame(k.omega_world_rad_s),
            angular_acceleration_nutation=on_nutation_frame(k.alpha_world_rad_s2),
        )


def rates_from_angular_velocity(state: EulerState, index: int) -> np.ndarray | None:
    """(φ̇, θ̇, ψ̇) (rad/s) recovered from the body components of ω at instant ``index``; None at θ = 0 or 180°,
    where ω fixes only φ̇ ± ψ̇."""
    return state.kinematics.recovered_rates(index)[0]


def singularity_note(nutation_rad: float) -> str:
    """What the readout says about the θ = 0 / 180° singularity at nutation θ (rad): always a sentence."""
    distance = math.degrees(float(gimbal_lock_distance_rad(np.array([0.0, nutation_rad, 0.0]), EULER_SEQUENCE)))
    theta = math.degrees(nutation_rad)
    if distance <= math.degrees(GIMBAL_LOCK_TOLERANCE_RAD):
        return (
            f"θ = {theta:.1f}°: the spin axis z lies on Z, so φ and ψ turn about the same line. The attitude "
            "fixes only "
            "φ ± ψ, the line of nodes is undefined, and ω cannot be turned back into φ̇ and ψ̇ (the angles are "
            "singular, the body is not)."
        )
    if distance < NEAR_SINGULAR_DEG:
        return (
            f"θ = {theta:.1f}° is {distance:.2f}° from the singularity at θ = 0 or 180°: recovering φ̇ and ψ̇ from ω "
            f"divides by sin θ = {math.sin(nutation_rad):.4f}, so small errors in ω become large errors in the rates."
        )
    return (
        f"θ = {theta:.1f}°, {distance:.1f}° away from the singularity at θ = 0 or 180° (where z lies on Z and "
        "only φ ± ψ is defined)."
    )


PARAMETERS = ParameterSet(
    (
        Parameter(
            "precession_deg",
            "deg",
            30.0,
            -180.0,
            180.0,
            "Precession φ at t = 0: turn about the fixed Z axis",
            "φ",
            step=1.0,
        ),
        Parameter(
            "nutation_deg",
            "deg",
            35.0,
            0.0,
            180.0,
            "Nutation θ at t = 0: tilt of the body's z axis from Z, a turn about the line of nodes",
            "θ",
            step=1.0,
        ),
        Parameter(
            "spin_deg", "deg", 0.0, -180.0, 180.0, "Spin ψ at t = 0: turn about the body's own z axis", "ψ", step=1.0
        ),
        Parameter("precession_rate_rad_s", "rad/s", 0.8, -10.0, 10.0, "Precession rate φ̇ at t = 0", "φ̇", step=0.05),
        Parameter("nutation_rate_rad_s", "rad/s", 0.15, -5.0, 5.0, "Nutation rate θ̇ at t = 0", "θ̇", step=0.05),
        Parameter("spin_rate_rad_s", "rad/s", 4.0, -30.0, 30.0, "Spin rate ψ̇ at t = 0", "ψ̇", step=0.1),
        Parameter(
            "precession_acceleration_rad_s2",
            "rad/s²",
            0.0,
            -3.0,
            3.0,
            "Precession acceleration φ̈ (constant)",
            "φ̈",
            step=0.05,
        ),
        Parameter(
            "nutation_acceleration_rad_s2",
            "rad/s²",
            0.0,
            -3.0,
            3.0,
            "Nutation acceleration θ̈ (constant)",
            "θ̈",
            step=0.05,
        ),
        Parameter(
            "spin_acceleration_rad_s2", "rad/s²", 0.0, -10.0, 10.0, "Spin acceleration ψ̈ (constant)", "ψ̈", step=0.1
        ),
    ),
    check=lambda params: EulerianAngleMotion.from_params(params),
)


class EulerianAngleKinematics(ClosedFormModel):
    """ω and α of a body whose Eulerian angles move with constant accelerations, on the body and nutation frames."""

    parameters = PARAMETERS
    series_units = {
        "precession_angle": "rad",
        "nutation_angle": "rad",
        "spin_angle": "rad",
        **{f"angular_velocity_body_{c}": "rad/s" for c in "xyz"},
        **{f"angular_velocity_nutation_{c}": "rad/s" for c in "xyz"},
        **{f"angular_acceleration_body_{c}": "rad/s²" for c in "xyz"},
        "angular_speed": "rad/s",
    }
    description = "ω = φ̇ K + θ̇ i′ + ψ̇ k (3-1-3 turn axes); α = dω/dt with the axes carried by the earlier turns"

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        state = EulerianAngleMotion.from_params(params).at(t_s)
        k = state.kinematics
        series = {
            "precession_angle": k.angles_rad[:, 0],
            "nutation_angle": k.angles_rad[:, 1],
            "spin_angle": k.angles_rad[:, 2],
            **{f"angular_velocity_body_{c}": k.omega_body_rad_s[:, i] for i, c in enumerate("xyz")},
            **{f"angular_velocity_nutation_{c}": state.angular_velocity_nutation[:, i] for i, c in enumerate("xyz")},
            **{f"angular_acceleration_body_{c}": k.alpha_body_rad_s2[:, i] for i, c in enumerate("xyz")},
            "angular_speed": np.linalg.norm(k.omega_world_rad_s, axis=-1),
        }
        return ClosedFormSolution(series)
