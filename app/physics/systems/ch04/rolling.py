"""Steady rolling without slip on a horizontal plane: a disk round a circle, a cone about its apex.

Frame (world, m, +Z up, ground z = 0). The contact point C travels round a
circle of radius ρ about the origin O: C = ρ ê_r(ψ) with ê_r = (cos ψ, sin ψ, 0),
ê_ψ = (−sin ψ, cos ψ, 0) and heading angle ψ = v t / ρ, so C moves at speed v
along ê_ψ (counterclockwise from above when v > 0). The rolling rim is a circle
of radius R whose plane is tilted by θ from the vertical, leaning towards O:

    d̂ = cos θ Z − sin θ ê_r      (from C up the rim's plane to its centre G = C + R d̂),
    n̂ = cos θ ê_r + sin θ Z      (the body's symmetry axis, outwards and up).

The body turns about Z with the heading (rate Ω = v/ρ) and spins about n̂ at the
rate σ̇ fixed by the no-slip condition, σ̇ = −v/R, so ω = Ω Z + σ̇ n̂. The
velocity of the material point at C is *computed* as v_C = v_G + ω × (r_C − r_G)
with v_G the time derivative of the centre's position formula; it comes out
zero to round-off. Every point on the line through C along ω is at rest: the
instantaneous axis. It passes through O' = (0, 0, (R − ρ sin θ)/cos θ), where
the symmetry axis meets the vertical through O.

A **cone** of base radius R and half-angle θ rolling on its side about its apex
at O is the special case ρ = R / sin θ (its slant length): then O' = O and the
instantaneous axis is the cone's line of contact with the ground.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution
from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.math.rotations import quaternion_from_axis_angle, quaternion_multiply

BODIES = ("disk", "cone")
Z = np.array([0.0, 0.0, 1.0])
MIN_CONE_HALF_ANGLE_DEG = 5.0


@dataclass(frozen=True)
class RollingState:
    """At N instants (vectors (N, 3) on the world frame): heading ψ and spin σ (rad), contact
    point C and rim centre G (m), symmetry axis n̂, the rim-plane directions d̂ (from C up to G)
    and ê_ψ (direction of travel), angular velocity ω (rad/s), velocity of G and of the material
    point at C (m/s), and the body's attitude as wxyz quaternions (rotation to world from the
    body frame: body z = n̂, and at σ = 0 body x = d̂, body y = −ê_ψ)."""

    t_s: np.ndarray
    heading: np.ndarray
    spin: np.ndarray
    contact_point: np.ndarray
    center: np.ndarray
    axis: np.ndarray
    rim_up: np.ndarray
    travel: np.ndarray
    angular_velocity: np.ndarray
    center_velocity: np.ndarray
    contact_point_velocity: np.ndarray
    wxyz: np.ndarray


@dataclass(frozen=True)
class SteadyRolling:
    """A rim of radius R (m) tilted θ (rad) from vertical, rolling at speed v (m/s) with its contact
    point on a circle of radius ρ (m) about the origin; ``body`` only says what carries the rim."""

    body: str
    rim_radius_m: float
    tilt_rad: float
    path_radius_m: float
    speed_m_s: float

    def __post_init__(self) -> None:
        if self.body not in BODIES:
            raise ValueError(f"body must be one of {', '.join(BODIES)} (got {self.body!r})")
        if not (self.rim_radius_m > 0.0 and self.path_radius_m > 0.0):
            raise ValueError("the rim radius and the path radius must be positive")
        if not 0.0 <= self.tilt_rad < math.pi / 2:
            raise ValueError("the tilt must lie in [0°, 90°)")

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> SteadyRolling:
        """From scene/API parameters. For the cone the path radius is its slant length R / sin θ."""
        body, radius, tilt = params["body"], params["rim_radius_m"], math.radians(params["tilt_deg"])
        if body == "cone":
            if params["tilt_deg"] < MIN_CONE_HALF_ANGLE_DEG:
                raise ValueError(
                    f"a cone needs a half-angle (tilt) of at least {MIN_CONE_HALF_ANGLE_DEG:g}° "
                    f"(got {params['tilt_deg']:g}°); at 0° it would be a cylinder with no apex to roll about"
                )
            return cls(body, radius, tilt, radius / math.sin(tilt), params["speed_m_s"])
        return cls(body, radius, tilt, params["path_radius_m"], params["speed_m_s"])

    @property
    def turn_rate_rad_s(self) -> float:
        """Ω = v/ρ: rate at which the contact point's heading turns about Z."""
        return self.speed_m_s / self.path_radius_m

    @property
    def spin_rate_rad_s(self) -> float:
        """σ̇ = −v/R: spin about the symmetry axis required by rolling without slip."""
        return -self.speed_m_s / self.rim_radius_m

    @property
    def axis_point(self) -> np.ndarray:
        """O' (m): where the symmetry axis meets the vertical through O; at rest, on the instantaneous axis."""
        return np.array(
            [0.0, 0.0, (self.rim_radius_m - self.path_radius_m * math.sin(self.tilt_rad)) / math.cos(self.tilt_rad)]
        )

    @property
    def cone_height_m(self) -> float:
        """Distance (m) from the rim's centre back along the axis to the cone's apex (cone only)."""
        return self.rim_radius_m / math.tan(self.tilt_rad)

    def at(self, t_s: np.ndarray) -> RollingState:
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        R, theta, rho, v = self.rim_radius_m, self.tilt_rad, self.path_radius_m, self.speed_m_s
        omega_turn, sigma_dot = self.turn_rate_rad_s, self.spin_rate_rad_s
        psi = omega_turn * t
        sigma = sigma_dot * t + 0.0  # + 0.0 turns -0.0 into 0.0
        zeros = np.zeros_like(t)
        e_r = np.stack([np.cos(psi), np.sin(psi), zeros], axis=-1)
        e_psi = np.stack([-np.sin(psi), np.cos(psi), zeros], axis=-1)
        cos_t = math.cos(theta)
        sin_t = math.sin(theta)
        rim_up = cos_t * Z - sin_t * e_r  # d̂
        axis = cos_t * e_r + sin_t * Z  # n̂
        contact = rho * e_r
        center = contact + R * rim_up
        # d/dt of G = ρ ê_r + R (cos θ Z − sin θ ê_r), with dê_r/dt = Ω ê_ψ.
        center_velocity = (v - R * omega_turn * sin_t) * e_psi
        omega = omega_turn * Z + sigma_dot * axis
        contact_velocity = center_velocity + np.cross(omega, contact - center)
        wxyz = _turn_about_z(self._attitude_at_rest, psi, sigma)
        return RollingState(
            t, psi, sigma, contact, center, axis, rim_up, e_psi, omega, center_velocity, contact_velocity, wxyz
        )

    @cached_property
    def _attitude_at_rest(self) -> np.ndarray:
        """wxyz attitude at ψ = σ = 0: body axes onto d̂, −ê_ψ, n̂, i.e. a half turn about x followed by a
        turn of −(90° + θ) about y."""
        return quaternion_multiply(
            quaternion_from_axis_angle(np.array([0.0, 1.0, 0.0]), -0.5 * math.pi - self.tilt_rad),
            quaternion_from_axis_angle(np.array([1.0, 0.0, 0.0]), math.pi),
        )

    def rim_points(self, state: RollingState, index: int, count: int) -> np.ndarray:
        """(count, 3) world positions (m) of ``count`` body-fixed points equally spaced on the rim at instant
        ``index``; the first is the one touching the ground at σ = 0. A rim point at body angle a (from body x)
        sits at r_G + R (cos(a + σ) d̂ − sin(a + σ) ê_ψ)."""
        angles = np.linspace(0.0, 2.0 * math.pi, count, endpoint=False) + math.pi + state.spin[index]
        return state.center[index] + self.rim_radius_m * (
            np.cos(angles)[:, None] * state.rim_up[index] - np.sin(angles)[:, None] * state.travel[index]
        )

    def velocity_of(self, state: RollingState, index: int, points: np.ndarray) -> np.ndarray:
        """Velocity (m/s, (M, 3)) of body points at world positions ``points`` (M, 3) at instant ``index``:
        v_P = v_G + ω × (r_P − r_G)."""
        return state.center_velocity[index] + np.cross(
            state.angular_velocity[index], np.asarray(points) - state.center[index]
        )

    def axis_misalignment(self, state: RollingState) -> np.ndarray:
        """Angle (rad) between ω and the line from C to O' (for the cone, the contact line); zero when
        the instantaneous axis passes through O'. NaN when the body is at rest (ω = 0)."""
        line = self.axis_point - state.contact_point
        w = state.angular_velocity
        cross = np.linalg.norm(np.cross(w, line), axis=-1)
        dot = np.abs(np.einsum("ij,ij->i", w, line))
        with np.errstate(invalid="ignore"):
            return np.where(np.linalg.norm(w, axis=-1) > 0.0, np.arctan2(cross, dot), np.nan)


def _turn_about_z(q: np.ndarray, before_rad: np.ndarray, after_rad: np.ndarray) -> np.ndarray:
    """(N, 4) wxyz products q_z(before) ⊗ q ⊗ q_z(after) for one quaternion q: the attitude q turned
    about the world z axis by ``before`` and about its own z axis by ``after`` (rad). Written out
    because both outer factors are turns about z (a per-frame cost, unlike the general product)."""
    cb, sb = np.cos(0.5 * before_rad), np.sin(0.5 * before_rad)
    ca, sa = np.cos(0.5 * after_rad), np.sin(0.5 * after_rad)
    w, x, y, z = q
    # q ⊗ q_z(after)
    w1, x1, y1, z1 = w * ca - z * sa, x * ca + y * sa, y * ca - x * sa, w * sa + z * ca
    # q_z(before) ⊗ (…)
    return np.stack([cb * w1 - sb * z1, cb * x1 - sb * y1, cb * y1 + sb * x1, cb * z1 + sb * w1], axis=-1)


PARAMETERS = ParameterSet(
    (
        Parameter(
            "body",
            "",
            "disk",
            description="What rolls: a thin disk, or a cone rolling on its side about its apex",
            label="body",
            kind="choice",
            choices=BODIES,
        ),
        Parameter(
            "rim_radius_m",
            "m",
            0.4,
            0.05,
            2.0,
            "Radius R of the rolling rim (the disk, or the cone's base)",
            "R",
            step=0.01,
        ),
        Parameter(
            "tilt_deg",
            "deg",
            20.0,
            0.0,
            60.0,
            "Tilt θ of the rim's plane from vertical, leaning in; for the cone this is its half-angle",
            "θ",
            step=1,
        ),
        Parameter(
            "path_radius_m",
            "m",
            1.5,
            0.2,
            20.0,
            "Disk only: radius ρ of the contact point's circle (a cone's is fixed at R/sin θ)",
            "ρ",
            step=0.05,
        ),
        Parameter("speed_m_s", "m/s", 0.8, -5.0, 5.0, "Speed v of the contact point along its circle", "v", step=0.05),
    ),
    check=lambda params: SteadyRolling.from_params(params),
)


class SteadyRollingMotion(ClosedFormModel):
    """A disk or cone rolling steadily without slip: pose and velocities in closed form."""

    parameters = PARAMETERS
    series_units = {
        "heading_angle": "rad",
        "spin_angle": "rad",
        "angular_velocity_x": "rad/s",
        "angular_velocity_y": "rad/s",
        "angular_velocity_z": "rad/s",
        "center_speed": "m/s",
        "contact_point_speed": "m/s",
        "axis_misalignment": "rad",
    }
    invariant_units = {"contact_point_speed": "m/s"}
    description = "steady rolling: ω = Ω Z − (v/R) n̂; v_C = v_G + ω × (r_C − r_G) evaluated, not assumed"

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        rolling = SteadyRolling.from_params(params)
        state = rolling.at(t_s)
        contact_speed = np.linalg.norm(state.contact_point_velocity, axis=-1)
        series = {
            "heading_angle": state.heading,
            "spin_angle": state.spin,
            "angular_velocity_x": state.angular_velocity[:, 0],
            "angular_velocity_y": state.angular_velocity[:, 1],
            "angular_velocity_z": state.angular_velocity[:, 2],
            "center_speed": np.linalg.norm(state.center_velocity, axis=-1),
            "contact_point_speed": contact_speed,
            "axis_misalignment": rolling.axis_misalignment(state),
        }
        return ClosedFormSolution(series, {"contact_point_speed": contact_speed})

    def invariant_scales(self, params: Mapping[str, Any], invariants: Mapping[str, np.ndarray]) -> dict[str, float]:
        """Contact-point speed relative to the rolling speed (1 m/s when at rest)."""
        return {"contact_point_speed": max(abs(float(params["speed_m_s"])), 1.0)}
