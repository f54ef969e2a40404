"""A disk spinning on a shaft carried by a turntable: velocity and acceleration of any point of the disk.

Frames: world ``XYZ`` (m, +Z up), origin at the shaft's bearing O on the turntable's axis.
The turntable turns about Z through φ with rate ω₁ and angular acceleration ω̇₁ (constant).
Its shaft leaves O at elevation β above the horizontal; the disk's centre A is at distance L
along it. The disk turns about the shaft, relative to the turntable, through ψ with rate ω₂
and constant acceleration ω̇₂. Its attitude is the 3-2-1 sequence (φ, −β, ψ), so body x is the
shaft n̂, and

    ω = ω₁ K + ω₂ n̂,    α = ω̇₁ K + ω̇₂ n̂ + ω₁ K × ω₂ n̂        (rad/s, rad/s²)

(both from :mod:`app.physics.math.rotations`, through the constant-acceleration angles of
:class:`~app.physics.systems.ch03.angle_rates.AngleMotion`). The point B is fixed on the disk at distance ρ
from A and angle γ round the disk from body y: ``r_B/A = ρ (cos γ ĵ + sin γ k̂)``.

The two rigid-body formulas are applied twice, as the lesson does: to the shaft (a body turning
at ω₁ K about the fixed point O) for A, then to the disk for B:

    v_B = v_A + ω × r_B/A,    a_B = a_A + α × r_B/A + ω × (ω × r_B/A).

:meth:`DiskOnTurntable.point_position` gives B's position from the attitude alone, with no
velocity formula in it, so a test can differentiate it numerically.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution
from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.math.rotations import elementary_quaternion, rotation_sequence
from app.physics.systems.ch03.angle_rates import AngleKinematics, AngleMotion

Z = np.array([0.0, 0.0, 1.0])


def velocity_on_body(reference_velocity: np.ndarray, angular_velocity: np.ndarray, offset: np.ndarray) -> np.ndarray:
    """v_B = v_A + ω × r_B/A (m/s, (..., 3)) from v_A (m/s), ω (rad/s) and r_B/A (m), all on one frame."""
    return reference_velocity + np.cross(angular_velocity, offset)


def acceleration_on_body(
    reference_acceleration: np.ndarray,
    angular_velocity: np.ndarray,
    angular_acceleration: np.ndarray,
    offset: np.ndarray,
) -> np.ndarray:
    """a_B = a_A + α × r_B/A + ω × (ω × r_B/A) (m/s², (..., 3)), all vectors on one frame."""
    return (
        reference_acceleration
        + np.cross(angular_acceleration, offset)
        + np.cross(angular_velocity, np.cross(angular_velocity, offset))
    )


@dataclass(frozen=True)
class PointKinematics:
    """At N instants, vectors (N, 3) on the world frame: the disk centre A and point B (m), r_B/A (m), the disk's
    ω (rad/s) and α (rad/s²), and every term of the two formulas: v_A, ω × r_B/A, v_B (m/s); a_A, α × r_B/A,
    ω × (ω × r_B/A), a_B (m/s²). ``turntable_wxyz`` and ``disk_wxyz`` (N, 4) are the attitudes of the turntable
    (after the turn φ) and of the disk (rotation to world from body; body x along the shaft)."""

    t_s: np.ndarray
    turntable_wxyz: np.ndarray
    disk_wxyz: np.ndarray
    center: np.ndarray
    point: np.ndarray
    point_from_center: np.ndarray
    angular_velocity: np.ndarray
    angular_acceleration: np.ndarray
    center_velocity: np.ndarray
    relative_velocity: np.ndarray
    point_velocity: np.ndarray
    center_acceleration: np.ndarray
    tangential_acceleration: np.ndarray
    centripetal_acceleration: np.ndarray
    point_acceleration: np.ndarray


@dataclass(frozen=True)
class DiskOnTurntable:
    """Rates (rad/s) and accelerations (rad/s²) at t = 0 of the turntable (ω₁, ω̇₁) and of the disk's spin on
    its shaft (ω₂, ω̇₂); shaft elevation β (rad) and length L (m); disk radius R (m); the point B at angle γ (rad)
    round the disk and distance ρ = fraction · R from its centre."""

    turntable_rate_rad_s: float
    turntable_acceleration_rad_s2: float
    spin_rate_rad_s: float
    spin_acceleration_rad_s2: float
    shaft_elevation_rad: float
    shaft_length_m: float
    disk_radius_m: float
    point_angle_rad: float
    point_radius_fraction: float

    def __post_init__(self) -> None:
        if not (self.shaft_length_m > 0.0 and self.disk_radius_m > 0.0):
            raise ValueError(
                f"the shaft length L and disk radius R must be positive (got L = {self.shaft_length_m:g} m, R = "
                f"{self.disk_radius_m:g} m)"
            )
        if not abs(self.shaft_elevation_rad) < 0.5 * math.pi:
            raise ValueError(
                "the shaft elevation β must lie strictly between −90° and 90° (got "
                f"{math.degrees(self.shaft_elevation_rad):g}°)"
            )
        if not 0.0 <= self.point_radius_fraction <= 1.0:
            raise ValueError(f"ρ/R must lie in [0, 1]: the point B is on the disk (got {self.point_radius_fraction:g})")

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> DiskOnTurntable:
        return cls(
            turntable_rate_rad_s=float(params["turntable_rate_rad_s"]),
            turntable_acceleration_rad_s2=float(params["turntable_acceleration_rad_s2"]),
            spin_rate_rad_s=float(params["spin_rate_rad_s"]),
            spin_acceleration_rad_s2=float(params["spin_acceleration_rad_s2"]),
            shaft_elevation_rad=math.radians(params["shaft_elevation_deg"]),
            shaft_length_m=float(params["shaft_length_m"]),
            disk_radius_m=float(params["disk_radius_m"]),
            point_angle_rad=math.radians(params["point_angle_deg"]),
            point_radius_fraction=float(params["point_radius_fraction"]),
        )

    @property
    def angles(self) -> AngleMotion:
        """The disk's 3-2-1 angles (φ, −β, ψ), starting at φ = ψ = 0, each at a constant angular acceleration."""
        return AngleMotion(
            sequence=rotation_sequence("3-2-1"),
            angles0_rad=np.array([0.0, -self.shaft_elevation_rad, 0.0]),
            rates0_rad_s=np.array([self.turntable_rate_rad_s, 0.0, self.spin_rate_rad_s]),
            accelerations_rad_s2=np.array([self.turntable_acceleration_rad_s2, 0.0, self.spin_acceleration_rad_s2]),
        )

    @property
    def point_body(self) -> np.ndarray:
        """r_B/A in body components (m): (0, ρ cos γ, ρ sin γ)."""
        rho = self.point_radius_fraction * self.disk_radius_m
        return np.array([0.0, rho * math.cos(self.point_angle_rad), rho * math.sin(self.point_angle_rad)])

    def point_position(self, t_s: np.ndarray) -> np.ndarray:
        """(N, 3) world position of B (m) from the attitude alone: r_B = L n̂ + [R] r_B/A (body)."""
        R = self.angles.kinematics(t_s).R_world_body
        return self.shaft_length_m * R[:, :, 0] + R @ self.point_body

    def at(self, t_s: np.ndarray) -> PointKinematics:
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        disk: AngleKinematics = self.angles.kinematics(t)
        R = disk.R_world_body
        omega, alpha = disk.omega_world_rad_s, disk.alpha_world_rad_s2
        # The shaft: a body turning at ω₁ K about the fixed point O (origin), carrying A.
        turntable_rate = disk.rates_rad_s[:, :1] * Z
        turntable_acceleration = self.turntable_acceleration_rad_s2 * np.broadcast_to(Z, (t.size, 3))
        center = self.shaft_length_m * R[:, :, 0]
        still = np.zeros_like(center)
        center_velocity = velocity_on_body(still, turntable_rate, center)
        center_acceleration = acceleration_on_body(still, turntable_rate, turntable_acceleration, center)
        # The disk: the same two formulas from A to B.
        offset = R @ self.point_body
        return PointKinematics(
            t_s=t,
            turntable_wxyz=elementary_quaternion(2, disk.angles_rad[:, 0]),
            disk_wxyz=disk.q_world_body,
            center=center,
            point=center + offset,
            point_from_center=offset,
            angular_velocity=omega,
            angular_acceleration=alpha,
            center_velocity=center_velocity,
            relative_velocity=np.cross(omega, offset),
            point_velocity=velocity_on_body(center_velocity, omega, offset),
            center_acceleration=center_acceleration,
            tangential_acceleration=np.cross(alpha, offset),
            centripetal_acceleration=np.cross(omega, np.cross(omega, offset)),
            point_acceleration=acceleration_on_body(center_acceleration, omega, alpha, offset),
        )


PARAMETERS = ParameterSet(
    (
        Parameter(
            "turntable_rate_rad_s",
            "rad/s",
            1.2,
            -5.0,
            5.0,
            "Rate ω₁ at which the turntable turns about the vertical Z axis, at t = 0",
            "ω₁",
            step=0.05,
        ),
        Parameter(
            "turntable_acceleration_rad_s2",
            "rad/s²",
            0.3,
            -2.0,
            2.0,
            "Angular acceleration ω̇₁ of the turntable (constant)",
            "ω̇₁",
            step=0.05,
        ),
        Parameter(
            "spin_rate_rad_s",
            "rad/s",
            4.0,
            -20.0,
            20.0,
            "Rate ω₂ at which the disk spins about its shaft relative to the turntable, at t = 0",
            "ω₂",
            step=0.1,
        ),
        Parameter(
            "spin_acceleration_rad_s2",
            "rad/s²",
            -0.5,
            -5.0,
            5.0,
            "Angular acceleration ω̇₂ of the spin relative to the turntable (constant)",
            "ω̇₂",
            step=0.05,
        ),
        Parameter(
            "shaft_elevation_deg",
            "deg",
            30.0,
            -75.0,
            75.0,
            "Elevation β of the shaft above the horizontal",
            "β",
            step=1.0,
        ),
        Parameter(
            "shaft_length_m",
            "m",
            0.8,
            0.2,
            2.0,
            "Length L from the bearing O on the turntable's axis to the disk's centre A",
            "L",
            step=0.01,
        ),
        Parameter("disk_radius_m", "m", 0.3, 0.05, 1.0, "Radius R of the disk", "R", step=0.01),
        Parameter(
            "point_angle_deg",
            "deg",
            90.0,
            -180.0,
            180.0,
            "Where B is round the disk: angle γ from the disk's y axis towards its z axis",
            "γ",
            step=1.0,
        ),
        Parameter(
            "point_radius_fraction",
            "",
            1.0,
            0.0,
            1.0,
            "How far B is from the centre A, as a fraction ρ/R of the disk's radius",
            "ρ/R",
            step=0.05,
        ),
    ),
    check=lambda params: DiskOnTurntable.from_params(params),
)


class DiskOnTurntableMotion(ClosedFormModel):
    """Velocity and acceleration of a point on a disk spinning on a turntable's shaft, term by term."""

    parameters = PARAMETERS
    series_units = {
        "point_velocity_x": "m/s",
        "point_velocity_y": "m/s",
        "point_velocity_z": "m/s",
        "point_speed": "m/s",
        "point_acceleration_x": "m/s²",
        "point_acceleration_y": "m/s²",
        "point_acceleration_z": "m/s²",
        "point_acceleration_magnitude": "m/s²",
        "center_speed": "m/s",
        "angular_speed": "rad/s",
        "angular_acceleration_magnitude": "rad/s²",
    }
    description = "rigid-body formulas applied twice: v_B = v_A + ω × r_B/A, a_B = a_A + α × r_B/A + ω × (ω × r_B/A)"

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        state = DiskOnTurntable.from_params(params).at(t_s)
        v, a = state.point_velocity, state.point_acceleration
        series = {
            **{f"point_velocity_{c}": v[:, i] for i, c in enumerate("xyz")},
            "point_speed": np.linalg.norm(v, axis=-1),
            **{f"point_acceleration_{c}": a[:, i] for i, c in enumerate("xyz")},
            "point_acceleration_magnitude": np.linalg.norm(a, axis=-1),
            "center_speed": np.linalg.norm(state.center_velocity, axis=-1),
            "angular_speed": np.linalg.norm(state.angular_velocity, axis=-1),
            "angular_acceleration_magnitude": np.linalg.norm(state.angular_acceleration, axis=-1),
        }
        return ClosedFormSolution(series)
