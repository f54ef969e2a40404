"""The offset slider-crank: loop closure for the slider, rates from the differentiated loop.

Frame (planar, m): crank pivot O at the origin, the slider's line of travel is
y = e (the offset), and the slider stays on the +x side of the crank pin. Crank
r (OA) at angle θ (rad, counterclockwise from +x), connecting rod l (AB) at
angle φ. The loop ``r e^{iθ} + l e^{iφ} = x + i e`` gives

    sin φ = (e − r sin θ) / l,      x = r cos θ + l cos φ   (cos φ > 0).

The crank turns fully only when l > r + |e|; shorter rods are refused. The
once- and twice-differentiated loop equations are linear in (ẋ, φ̇) and
(ẍ, φ̈), with determinant −l cos φ, which never vanishes when the crank turns
fully, so the slider-crank has no toggle position when driven by its crank.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution
from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.systems.ch04.crank_drive import CrankDrive
from app.physics.systems.ch04.planar_loop import solve_2x2


@dataclass(frozen=True)
class SliderCrankState:
    """At N instants: crank angle θ and rate (rad, rad/s), rod angle φ, rate and acceleration
    (rad, rad/s, rad/s²), slider position, velocity and acceleration along x (m, m/s, m/s²),
    crank pin A and slider pin B as (N, 2) arrays (m)."""

    t_s: np.ndarray
    crank_angle: np.ndarray
    crank_rate: np.ndarray
    rod_angle: np.ndarray
    rod_rate: np.ndarray
    rod_acceleration: np.ndarray
    slider_position_m: np.ndarray
    slider_velocity_m_s: np.ndarray
    slider_acceleration_m_s2: np.ndarray
    crank_pin: np.ndarray
    slider_pin: np.ndarray


@dataclass(frozen=True)
class SliderCrank:
    """Crank r, connecting rod l and offset e (m) of an offset slider-crank."""

    crank_m: float
    rod_m: float
    offset_m: float = 0.0

    def __post_init__(self) -> None:
        if not (self.crank_m > 0.0 and self.rod_m > 0.0 and math.isfinite(self.offset_m)):
            raise ValueError("the crank and the connecting rod must have positive lengths")
        reach = self.crank_m + abs(self.offset_m)
        if self.rod_m <= reach * (1.0 + 1e-9):
            raise ValueError(
                f"the connecting rod ({self.rod_m:g} m) must be longer than crank + |offset| ({reach:g} m), "
                f"or the slider cannot follow the crank all the way round"
            )

    def positions(self, crank_angle_rad: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Slider position x (m) and rod angle φ (rad) by closed-form loop closure."""
        r, l, e = self.crank_m, self.rod_m, self.offset_m
        theta = np.asarray(crank_angle_rad, dtype=float)
        sin_phi = (e - r * np.sin(theta)) / l
        cos_phi = np.sqrt(1.0 - sin_phi**2)
        return r * np.cos(theta) + l * cos_phi, np.arctan2(sin_phi, cos_phi)

    def rates(self, theta: np.ndarray, phi: np.ndarray, omega: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Slider velocity ẋ (m/s) and rod rate φ̇ (rad/s):
        ``[-1, -l sinφ; 0, l cosφ] [ẋ, φ̇] = [r ω sinθ, -r ω cosθ]``."""
        r, l = self.crank_m, self.rod_m
        xdot, phidot, _ = solve_2x2(
            -1.0,
            -l * np.sin(phi),
            0.0,
            l * np.cos(phi),
            r * omega * np.sin(theta),
            -r * omega * np.cos(theta),
            singular_below=0.0,
        )
        return xdot, phidot

    def accelerations(
        self, theta: np.ndarray, phi: np.ndarray, omega: np.ndarray, phidot: np.ndarray, alpha: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """Slider acceleration ẍ (m/s²) and rod acceleration φ̈ (rad/s²): same matrix, centripetal terms on the
        right."""
        r, l = self.crank_m, self.rod_m
        r1 = r * alpha * np.sin(theta) + r * omega**2 * np.cos(theta) + l * phidot**2 * np.cos(phi)
        r2 = -r * alpha * np.cos(theta) + r * omega**2 * np.sin(theta) + l * phidot**2 * np.sin(phi)
        xddot, phiddot, _ = solve_2x2(-1.0, -l * np.sin(phi), 0.0, l * np.cos(phi), r1, r2, singular_below=0.0)
        return xddot, phiddot

    @property
    def stroke_limits_m(self) -> tuple[float, float]:
        """Slider positions (m) at the two dead centres, where crank and rod are in line."""
        r, l, e = self.crank_m, self.rod_m, self.offset_m
        return math.sqrt((l - r) ** 2 - e * e), math.sqrt((l + r) ** 2 - e * e)

    @property
    def dead_centre_angles_rad(self) -> tuple[float, float]:
        """Crank angles (rad, in [0, 2π)) at the outer and inner dead centres.

        Outer: crank and rod point the same way, so A lies on the line from O to
        B at x_max. Inner: the crank points back, away from B at x_min.
        """
        x_min, x_max = self.stroke_limits_m
        e = self.offset_m
        outer = math.atan2(e, x_max) % (2.0 * math.pi)
        inner = (math.atan2(e, x_min) + math.pi) % (2.0 * math.pi)
        return outer, inner

    def stroke_time_ratio(self, *, counterclockwise: bool = True) -> float:
        """Duration of the outward stroke over the return stroke at constant crank speed.

        Outward (x_min → x_max) a counterclockwise crank turns from the inner
        to the outer dead centre; a clockwise one covers the other arc. An
        offset makes the two arcs unequal (a quick return); without one the
        ratio is 1.
        """
        outer, inner = self.dead_centre_angles_rad
        outward = (outer - inner) % (2.0 * math.pi)
        if not counterclockwise:
            outward = 2.0 * math.pi - outward
        return outward / (2.0 * math.pi - outward)

    def loop_residual(self, theta: np.ndarray, phi: np.ndarray, x: np.ndarray) -> np.ndarray:
        """|r e^{iθ} + l e^{iφ} − (x + i e)| (m): zero when the loop closes."""
        r, l, e = self.crank_m, self.rod_m, self.offset_m
        return np.hypot(r * np.cos(theta) + l * np.cos(phi) - x, r * np.sin(theta) + l * np.sin(phi) - e)


@dataclass(frozen=True)
class SliderCrankMotion:
    """A slider-crank driven by its crank at constant speed."""

    mechanism: SliderCrank
    drive: CrankDrive

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> SliderCrankMotion:
        mechanism = SliderCrank(params["crank_m"], params["rod_m"], params["offset_m"])
        return cls(
            mechanism, CrankDrive(math.radians(params.get("crank_angle0_deg", 0.0)), params["crank_speed_rad_s"])
        )

    def at(self, t_s: np.ndarray) -> SliderCrankState:
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        theta, omega, alpha = self.drive.angle(t), self.drive.rate(t), self.drive.acceleration(t)
        mech = self.mechanism
        x, phi = mech.positions(theta)
        xdot, phidot = mech.rates(theta, phi, omega)
        xddot, phiddot = mech.accelerations(theta, phi, omega, phidot, alpha)
        crank_pin = mech.crank_m * np.stack([np.cos(theta), np.sin(theta)], axis=-1)
        slider_pin = np.stack([x, np.full_like(x, mech.offset_m)], axis=-1)
        return SliderCrankState(t, theta, omega, phi, phidot, phiddot, x, xdot, xddot, crank_pin, slider_pin)


def _check(params: Mapping[str, Any]) -> None:
    SliderCrankMotion.from_params(params)


PARAMETERS = ParameterSet(
    (
        Parameter("crank_m", "m", 0.3, 0.02, 5.0, "Crank r (OA)", "crank r", step=0.01),
        Parameter("rod_m", "m", 1.0, 0.05, 20.0, "Connecting rod l (AB)", "rod l", step=0.01),
        Parameter(
            "offset_m",
            "m",
            0.0,
            -5.0,
            5.0,
            "Offset e of the slider's line above the crank pivot",
            "offset e",
            step=0.01,
        ),
        Parameter(
            "crank_speed_rad_s",
            "rad/s",
            2.0,
            -20.0,
            20.0,
            "Constant crank speed ω (counterclockwise positive)",
            "ω",
            step=0.1,
        ),
        Parameter("crank_angle0_deg", "deg", 0.0, -180.0, 180.0, "Crank angle θ at t = 0", "θ(0)", step=1),
    ),
    check=_check,
)


class SliderCrankMechanism(ClosedFormModel):
    """Offset slider-crank driven at constant crank speed, evaluated by loop closure at each instant."""

    parameters = PARAMETERS
    series_units = {
        "crank_angle": "rad",
        "slider_position_m": "m",
        "slider_velocity_m_s": "m/s",
        "slider_acceleration_m_s2": "m/s²",
        "rod_angle": "rad",
        "rod_rate": "rad/s",
        "rod_acceleration": "rad/s²",
    }
    invariant_units = {"loop_closure_residual": "m"}
    description = (
        "loop closure for the slider position; differentiated loop equations (2×2 linear solves) for "
        "velocity and acceleration"
    )

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        motion = SliderCrankMotion.from_params(params)
        state = motion.at(t_s)
        series = {name: getattr(state, name) for name in self.series_units}
        residual = motion.mechanism.loop_residual(state.crank_angle, state.rod_angle, state.slider_position_m)
        return ClosedFormSolution(series, {"loop_closure_residual": residual})

    def invariant_scales(self, params: Mapping[str, Any], invariants: Mapping[str, np.ndarray]) -> dict[str, float]:
        return {"loop_closure_residual": float(params["rod_m"])}
