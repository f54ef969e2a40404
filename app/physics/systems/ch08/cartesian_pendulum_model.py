"""The Cartesian pendulum as an integrated model: every DAE algorithm, and the minimal-coordinate reference.

State ``(x, y, ẋ, ẏ)`` (m, m/s; y up, pivot at the origin; see :mod:`.cartesian_pendulum`);
with the method ``minimal`` the state is (θ, θ̇) (rad, rad/s) of the chapter 7 engine's
simple pendulum (θ from the downward vertical), mapped back to x, y for every series.
The requested start ``x0_m, y0_m, vx0_m_s, vy0_m_s`` is moved the least distance onto
the circle and its velocity onto the tangent (the change is reported); a start at the
pivot has no nearest point on the circle and is refused.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.constrained.model import ConstrainedModel
from app.physics.core.energy import EnergyParts
from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.mechanics.engine import derived
from app.physics.solvers.system import OdeSystem
from app.physics.systems.ch07.simple_pendulum import SYSTEM as SIMPLE_PENDULUM
from app.physics.systems.ch08.cartesian_pendulum import angle_and_rate, cartesian_states, pendulum_system


def _m_l_g(params: Mapping[str, Any]) -> tuple[float, float, float]:
    return float(params["mass_kg"]), float(params["length_m"]), float(params["g_m_s2"])


def _start_is_consistent(values: Mapping[str, Any]) -> None:
    """Refuse (ValueError naming the fields) a start that cannot be made consistent."""
    CartesianPendulum().consistent_start(values)


class CartesianPendulum(ConstrainedModel):
    """A bob on a rod in Cartesian coordinates (x, y) with the rod as the constraint x² + y² = L²."""

    parameters = ParameterSet(
        (
            Parameter("mass_kg", "kg", 1.0, 0.01, 100.0, "Mass of the bob", "m"),
            Parameter("length_m", "m", 1.0, 0.05, 10.0, "Length of the rod", "L"),
            Parameter("g_m_s2", "m/s²", 9.81, 0.0, 100.0, "Gravitational acceleration (along −y)", "g"),
            Parameter(
                "x0_m",
                "m",
                0.8,
                -10.0,
                10.0,
                "Requested start: bob's horizontal position (made consistent with the rod)",
                "x₀",
            ),
            Parameter(
                "y0_m",
                "m",
                -0.6,
                -10.0,
                10.0,
                "Requested start: bob's height above the pivot (y up; made consistent)",
                "y₀",
            ),
            Parameter(
                "vx0_m_s",
                "m/s",
                0.0,
                -50.0,
                50.0,
                "Requested start: horizontal velocity (its part along the rod is removed)",
                "ẋ₀",
            ),
            Parameter(
                "vy0_m_s",
                "m/s",
                0.0,
                -50.0,
                50.0,
                "Requested start: vertical velocity (its part along the rod is removed)",
                "ẏ₀",
            ),
        ),
        check=_start_is_consistent,
    )
    start_parameters = ("x0_m", "y0_m", "vx0_m_s", "vy0_m_s")
    series_units = {
        "x_m": "m",
        "y_m": "m",
        "vx_m_s": "m/s",
        "vy_m_s": "m/s",
        "multiplier": "N/m",
        "theta_rad": "rad",
        "tension_N": "N",
    }
    invariant_units = {"energy": "J", "constraint_position": "m²", "constraint_velocity": "m²/s"}

    def constrained_system(self, params: Mapping[str, Any]):
        return pendulum_system(*_m_l_g(params))

    def energy_J(self, params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
        """E = ½ m (ẋ² + ẏ²) + m g y (J; zero potential at the pivot's height)."""
        m, _, g = _m_l_g(params)
        states = np.atleast_2d(states)
        with np.errstate(over="ignore", invalid="ignore"):  # a run that blew up: inf, reported as null
            return self.constrained_energy_parts(params, states).total_J

    def constrained_energy_parts(self, params: Mapping[str, Any], states: np.ndarray) -> EnergyParts:
        """The bob is a particle: ½ m (ẋ² + ẏ²) translational, no rotation; m g y."""
        m, _, g = _m_l_g(params)
        states = np.atleast_2d(states)
        with np.errstate(over="ignore", invalid="ignore"):
            kinetic = 0.5 * m * (states[:, 2] ** 2 + states[:, 3] ** 2)
            return EnergyParts(
                m * g * states[:, 1], translational_kinetic_J=kinetic, rotational_kinetic_J=np.zeros_like(kinetic)
            )

    def energy_scale_J(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """2 m g L (the potential energy's whole range) or the kinetic energy if larger (J)."""
        m, l, g = _m_l_g(params)
        kinetic = 0.5 * m * float(state[2] ** 2 + state[3] ** 2)
        return max(2.0 * m * g * l, kinetic, 1e-12)

    def residual_scales(self, params: Mapping[str, Any]) -> tuple[float, float]:
        """L² (m²) for g (0.2 L²: the rod ≈ 10% off its length) and L·(√(gL) or the top speed) (m²/s) for C v."""
        _, l, g = _m_l_g(params)
        start = self.consistent_start(params).state
        return l * l, l * max(math.sqrt(g * l), self._top_speed_m_s(params, start), 1e-6)

    def _top_speed_m_s(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """Speed at the lowest point the energy of ``state`` (4,) allows (m/s)."""
        _, l, g = _m_l_g(params)
        return math.sqrt(max(float(state[2] ** 2 + state[3] ** 2) + 2.0 * g * (float(state[1]) + l), 0.0))

    def fastest_rate_rad_s(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """√(g/L) plus the top speed over L (rad/s), at least 0.1."""
        _, l, g = _m_l_g(params)
        return max(math.sqrt(g / l) + self._top_speed_m_s(params, state) / l, 0.1)

    def constrained_series(self, params, t_s, states, multipliers):
        _, l, _ = _m_l_g(params)
        theta, _ = angle_and_rate(l, states)
        return {
            "x_m": states[:, 0],
            "y_m": states[:, 1],
            "vx_m_s": states[:, 2],
            "vy_m_s": states[:, 3],
            "multiplier": multipliers[:, 0],
            "theta_rad": theta,
            "tension_N": multipliers[:, 0] * l,
        }

    # --- the chapter 7 engine's simple pendulum as the minimal-coordinate reference ---------------------------
    def minimal_system(self, params: Mapping[str, Any]) -> OdeSystem | None:
        return OdeSystem(
            rhs=derived(SIMPLE_PENDULUM, "lagrange").kernel(),
            parameters=np.array(SIMPLE_PENDULUM.parameter_array(params), dtype=float),
            state_names=("theta", "theta_rate"),
        )

    def minimal_state(self, params: Mapping[str, Any], state: np.ndarray) -> np.ndarray:
        theta, rate = angle_and_rate(float(params["length_m"]), state[None, :])
        return np.array([theta[0], rate[0]])

    def constrained_states(self, params: Mapping[str, Any], minimal_states: np.ndarray) -> np.ndarray:
        minimal_states = np.atleast_2d(minimal_states)
        return cartesian_states(float(params["length_m"]), minimal_states[:, 0], minimal_states[:, 1])
