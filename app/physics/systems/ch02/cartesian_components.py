"""A particle given by its rectangular Cartesian coordinates x(t), y(t), z(t): v and a by components.

Frame: the fixed frame XYZ, +Z up; lengths in m, time t in s. The unit vectors
I, J, K never turn, so each component is differentiated on its own::

    v = ẋ I + ẏ J + ż K,    a = ẍ I + ÿ J + z̈ K.

Two motions, each a closed form in t:

* ``sine-slot``: a pin driven along X at constant ẋ = u through a slot
  y = h sin(πx/L) cut in the horizontal plane z = 0, over one wavelength
  0 ≤ x ≤ 2L (a run lasts 2L/u)::

      x = u t,  y = h sin(k x),  k = π/L
      ẏ = h k u cos(k x),  ÿ = −h k² u² sin(k x),  ẍ = ż = z̈ = 0

* ``projectile``: launched from the origin at speed v₀, elevation α above the
  horizontal, heading ψ from +X toward +Y, gravity g along −Z, no air; a run
  ends when it lands on z = 0 at t = 2 v₀ sin α / g::

      x = v₀ cos α cos ψ t,  y = v₀ cos α sin ψ t,  z = v₀ sin α t − g t²/2
      ẍ = ÿ = 0,  z̈ = −g

After the landing the formula would carry the projectile below the ground; the
simulate report says so instead of answering "ok".
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution
from app.physics.core.parameters import Parameter, ParameterSet

MOTIONS = ("sine-slot", "projectile")


@dataclass(frozen=True)
class CartesianState:
    """Position (m), velocity (m/s) and acceleration (m/s²) on XYZ at N instants, each (N, 3)."""

    t_s: np.ndarray
    position_m: np.ndarray
    velocity_m_s: np.ndarray
    acceleration_m_s2: np.ndarray


@dataclass(frozen=True)
class SineSlot:
    """A pin driven at ẋ = ``drive_speed_m_s`` along the slot y = h sin(πx/L) in the plane z = 0."""

    amplitude_m: float
    half_wavelength_m: float
    drive_speed_m_s: float

    @property
    def run_s(self) -> float:
        """Time (s) to cross one wavelength, 0 ≤ x ≤ 2L."""
        return 2.0 * self.half_wavelength_m / self.drive_speed_m_s

    def at(self, t_s: np.ndarray | float) -> CartesianState:
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        h, u, k = self.amplitude_m, self.drive_speed_m_s, math.pi / self.half_wavelength_m
        x = u * t
        zeros = np.zeros_like(t)
        position = np.stack([x, h * np.sin(k * x), zeros], axis=1)
        velocity = np.stack([np.full_like(t, u), h * k * u * np.cos(k * x), zeros], axis=1)
        acceleration = np.stack([zeros, -h * k**2 * u**2 * np.sin(k * x), zeros], axis=1)
        return CartesianState(t, position, velocity, acceleration)


@dataclass(frozen=True)
class Projectile:
    """A particle launched from the origin at ``speed_m_s``, elevation and heading in rad, gravity along −Z."""

    speed_m_s: float
    elevation_rad: float
    heading_rad: float
    gravity_m_s2: float

    @property
    def run_s(self) -> float:
        """Time of flight (s) until it is back on z = 0."""
        return 2.0 * self.speed_m_s * math.sin(self.elevation_rad) / self.gravity_m_s2

    def at(self, t_s: np.ndarray | float) -> CartesianState:
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        v0, g = self.speed_m_s, self.gravity_m_s2
        horizontal = v0 * math.cos(self.elevation_rad)
        launch = np.array(
            [
                horizontal * math.cos(self.heading_rad),
                horizontal * math.sin(self.heading_rad),
                v0 * math.sin(self.elevation_rad),
            ]
        )
        gravity = np.array([0.0, 0.0, -g])
        position = t[:, None] * launch + 0.5 * t[:, None] ** 2 * gravity
        velocity = launch + t[:, None] * gravity
        acceleration = np.broadcast_to(gravity, position.shape).copy()
        return CartesianState(t, position, velocity, acceleration)


def cartesian_motion(params: Mapping[str, Any]) -> SineSlot | Projectile:
    """The motion the parameters choose (``motion``: 'sine-slot' or 'projectile')."""
    if params["motion"] == "sine-slot":
        return SineSlot(params["slot_amplitude_m"], params["slot_length_m"], params["drive_speed_m_s"])
    return Projectile(
        params["launch_speed_m_s"],
        math.radians(params["launch_angle_deg"]),
        math.radians(params["launch_heading_deg"]),
        params["gravity_m_s2"],
    )


#: Which controls each motion reads (the others are kept but not used).
CONTROLS_USED = {
    "sine-slot": ("slot_amplitude_m", "slot_length_m", "drive_speed_m_s"),
    "projectile": ("launch_speed_m_s", "launch_angle_deg", "launch_heading_deg", "gravity_m_s2"),
}

PARAMETERS = ParameterSet(
    (
        Parameter(
            "motion",
            "",
            "sine-slot",
            kind="choice",
            choices=MOTIONS,
            label="motion",
            description="A pin driven along a sine-shaped slot, or a projectile without air",
        ),
        Parameter(
            "slot_amplitude_m",
            "m",
            0.3,
            0.0,
            1.0,
            "Sine slot: the slot's amplitude h in y = h sin(πx/L)",
            "h",
            step=0.01,
        ),
        Parameter(
            "slot_length_m",
            "m",
            1.0,
            0.2,
            3.0,
            "Sine slot: half a wavelength L, the x distance from one crossing of y = 0 to the next",
            "L",
            step=0.05,
        ),
        Parameter(
            "drive_speed_m_s",
            "m/s",
            0.5,
            0.05,
            3.0,
            "Sine slot: the constant speed ẋ at which the pin is driven along X",
            "ẋ",
            step=0.05,
        ),
        Parameter("launch_speed_m_s", "m/s", 8.0, 0.5, 30.0, "Projectile: launch speed v₀", "v₀", step=0.1),
        Parameter(
            "launch_angle_deg",
            "deg",
            50.0,
            1.0,
            90.0,
            "Projectile: elevation α of the launch above the horizontal",
            "α",
            step=1,
        ),
        Parameter(
            "launch_heading_deg",
            "deg",
            30.0,
            -180.0,
            180.0,
            "Projectile: heading ψ of the launch, from +X toward +Y",
            "ψ",
            step=1,
        ),
        Parameter(
            "gravity_m_s2",
            "m/s²",
            9.81,
            0.5,
            30.0,
            "Projectile: gravitational acceleration g, along −Z",
            "g",
            step=0.01,
        ),
    )
)


class CartesianParticle(ClosedFormModel):
    """A particle whose x(t), y(t), z(t) are closed forms: components of v and a, speed and |a|."""

    parameters = PARAMETERS
    series_units = {
        "x": "m",
        "y": "m",
        "z": "m",
        "x_dot": "m/s",
        "y_dot": "m/s",
        "z_dot": "m/s",
        "x_ddot": "m/s^2",
        "y_ddot": "m/s^2",
        "z_ddot": "m/s^2",
        "speed": "m/s",
        "acceleration_magnitude": "m/s^2",
    }
    description = (
        "x(t), y(t), z(t) and their derivatives in closed form (sine slot at constant ẋ, or a projectile without air)"
    )

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        motion = cartesian_motion(params)
        state = motion.at(t_s)
        series = {}
        for k, axis in enumerate("xyz"):
            series[axis] = state.position_m[:, k]
            series[f"{axis}_dot"] = state.velocity_m_s[:, k]
            series[f"{axis}_ddot"] = state.acceleration_m_s2[:, k]
        series["speed"] = np.linalg.norm(state.velocity_m_s, axis=1)
        series["acceleration_magnitude"] = np.linalg.norm(state.acceleration_m_s2, axis=1)
        warning = ""
        if isinstance(motion, Projectile) and t_s[-1] > motion.run_s:
            warning = (
                f"The projectile lands on z = 0 at t = {motion.run_s:.4g} s; after that the formula carries it below "
                "the ground, where a real one would have stopped."
            )
        elif isinstance(motion, SineSlot) and t_s[-1] > motion.run_s:
            warning = (
                f"The slot is one wavelength long (x ≤ 2L = {2 * motion.half_wavelength_m:g} m, reached at "
                f"t = {motion.run_s:.4g} s); after that the formula follows the slot's sine on past its "
                "end."
            )
        return ClosedFormSolution(series=series, warning=warning)
