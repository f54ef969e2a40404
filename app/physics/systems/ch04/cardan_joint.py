"""The cardan (Hooke, universal) joint: output angle and speed ratio of two shafts at an angle β.

Frame (world, +Z up): the joint's centre is the origin; the input shaft lies
along +x, the output shaft along e₂ = (cos β, sin β, 0), both horizontal, so
the plane of the shafts is the xy plane. The input yoke's pin direction is
u = R_x(φ₁) ŷ (φ₁ = 0: the pin lies in the plane of the shafts); the output
yoke's pin is v = cos φ₂ ẑ + sin φ₂ (e₂ × ẑ) (φ₂ = 0: the pin is perpendicular
to that plane). The cross holds the two pins perpendicular, u · v = 0, which
gives

    tan φ₂ = tan φ₁ / cos β,
    ω₂ / ω₁ = cos β / (1 − sin²β cos²φ₁),

so the output turns exactly once per input turn but unevenly: the speed ratio
swings between cos β (φ₁ = 90°, 270°) and 1/cos β (φ₁ = 0°, 180°) twice a turn.
At β = 90° the joint locks (cos β = 0) and is refused.
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
from app.physics.systems.ch04.planar_loop import wrap_angle


@dataclass(frozen=True)
class CardanJoint:
    """A cardan joint with shafts at ``shaft_angle_rad`` (0 ≤ β < π/2)."""

    shaft_angle_rad: float

    def __post_init__(self) -> None:
        beta = self.shaft_angle_rad
        if not (math.isfinite(beta) and 0.0 <= beta):
            raise ValueError("the shaft angle must be a finite angle of at least 0°")
        if math.cos(beta) <= 1e-9:
            raise ValueError(
                f"a cardan joint cannot turn with its shafts at {math.degrees(beta):.1f}°: at 90° the cross locks "
                f"(the speed ratio cos β / (1 − sin²β cos²φ₁) would be 0 or unbounded); use a shaft angle below 90°"
            )

    def output_angle(self, input_angle_rad: np.ndarray) -> np.ndarray:
        """φ₂ (rad) from tan φ₂ = tan φ₁ / cos β, continuous in φ₁ (|φ₂ − φ₁| < π/2, one turn per turn)."""
        phi1 = np.asarray(input_angle_rad, dtype=float)
        c = math.cos(self.shaft_angle_rad)
        # atan2 gives the quadrant of φ₂; adding φ₁ back keeps whole turns, so φ₂ is continuous.
        return phi1 + wrap_angle(np.arctan2(np.sin(phi1), c * np.cos(phi1)) - phi1)

    def speed_ratio(self, input_angle_rad: np.ndarray) -> np.ndarray:
        """ω₂/ω₁ = cos β / (1 − sin²β cos²φ₁) (dimensionless)."""
        beta = self.shaft_angle_rad
        return math.cos(beta) / (1.0 - math.sin(beta) ** 2 * np.cos(np.asarray(input_angle_rad, dtype=float)) ** 2)

    def speed_ratio_slope(self, input_angle_rad: np.ndarray) -> np.ndarray:
        """d(ω₂/ω₁)/dφ₁ (1/rad) = −cos β sin²β sin 2φ₁ / (1 − sin²β cos²φ₁)²."""
        beta = self.shaft_angle_rad
        phi1 = np.asarray(input_angle_rad, dtype=float)
        s2 = math.sin(beta) ** 2
        return -math.cos(beta) * s2 * np.sin(2.0 * phi1) / (1.0 - s2 * np.cos(phi1) ** 2) ** 2

    @property
    def speed_ratio_span(self) -> tuple[float, float]:
        """(min, max) of ω₂/ω₁ over a turn: (cos β, 1/cos β)."""
        c = math.cos(self.shaft_angle_rad)
        return c, 1.0 / c

    @property
    def output_axis(self) -> np.ndarray:
        """Unit vector e₂ along the output shaft (world)."""
        beta = self.shaft_angle_rad
        return np.array([math.cos(beta), math.sin(beta), 0.0])

    def input_pin(self, input_angle_rad: np.ndarray | float) -> np.ndarray:
        """Unit vector(s) u along the input yoke's pin of the cross, shape (..., 3) (world)."""
        phi1 = np.asarray(input_angle_rad, dtype=float)
        return np.stack([np.zeros_like(phi1), np.cos(phi1), np.sin(phi1)], axis=-1)

    def output_pin(self, output_angle_rad: np.ndarray | float) -> np.ndarray:
        """Unit vector(s) v along the output yoke's pin of the cross, shape (..., 3) (world)."""
        phi2 = np.asarray(output_angle_rad, dtype=float)
        across = np.cross(self.output_axis, [0.0, 0.0, 1.0])  # e₂ × ẑ, horizontal
        return np.cos(phi2)[..., None] * np.array([0.0, 0.0, 1.0]) + np.sin(phi2)[..., None] * across


@dataclass(frozen=True)
class CardanState:
    """At N instants: shaft angles (rad, continuous), rates (rad/s), output acceleration (rad/s²), speed ratio."""

    t_s: np.ndarray
    input_angle: np.ndarray
    output_angle: np.ndarray
    input_rate: np.ndarray
    output_rate: np.ndarray
    output_acceleration: np.ndarray
    speed_ratio: np.ndarray


@dataclass(frozen=True)
class CardanMotion:
    """A cardan joint whose input shaft turns at constant speed from φ₁ = 0."""

    joint: CardanJoint
    drive: CrankDrive

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> CardanMotion:
        return cls(CardanJoint(math.radians(params["shaft_angle_deg"])), CrankDrive(0.0, params["input_speed_rad_s"]))

    def at(self, t_s: np.ndarray) -> CardanState:
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        phi1, omega1 = self.drive.angle(t), self.drive.rate(t)
        ratio = self.joint.speed_ratio(phi1)
        # ω₂ = r(φ₁) ω₁, so α₂ = r'(φ₁) ω₁² (the input turns at constant speed).
        return CardanState(
            t,
            phi1,
            self.joint.output_angle(phi1),
            omega1,
            ratio * omega1,
            self.joint.speed_ratio_slope(phi1) * omega1**2,
            ratio,
        )


def _check(params: Mapping[str, Any]) -> None:
    CardanMotion.from_params(params)


PARAMETERS = ParameterSet(
    (
        Parameter(
            "shaft_angle_deg",
            "deg",
            30.0,
            0.0,
            90.0,
            "Angle β between the input and output shafts (below 90°)",
            "β",
            step=1,
        ),
        Parameter("input_speed_rad_s", "rad/s", 1.0, -10.0, 10.0, "Constant input shaft speed ω₁", "ω₁", step=0.05),
    ),
    check=_check,
)


class CardanJointDrive(ClosedFormModel):
    """Cardan joint with a constant-speed input shaft: the output angle is a closed form in time."""

    parameters = PARAMETERS
    series_units = {
        "input_angle": "rad",
        "output_angle": "rad",
        "speed_ratio": "",
        "output_rate": "rad/s",
        "output_acceleration": "rad/s²",
    }
    invariant_units = {"cross_pin_dot_product": ""}
    description = "tan φ₂ = tan φ₁ / cos β with the quadrant kept continuous; ω₂/ω₁ = cos β / (1 − sin²β cos²φ₁)"

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        motion = CardanMotion.from_params(params)
        state = motion.at(t_s)
        series = {name: getattr(state, name) for name in self.series_units}
        joint = motion.joint
        # The cross's constraint u · v = 0, evaluated from the two angles: zero to round-off.
        dot = np.einsum("ij,ij->i", joint.input_pin(state.input_angle), joint.output_pin(state.output_angle))
        return ClosedFormSolution(series, {"cross_pin_dot_product": dot})

    def invariant_scales(self, params: Mapping[str, Any], invariants: Mapping[str, np.ndarray]) -> dict[str, float]:
        return {"cross_pin_dot_product": 1.0}
