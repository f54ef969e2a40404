"""The simple pendulum in its phase plane (θ, p_θ): Hamilton's equations, H's level sets and its conservation.

State (rad, rad/s): (θ, θ̇), θ from the downward vertical (see
:mod:`app.physics.systems.ch07.simple_pendulum` for the frame). The momentum
conjugate to θ is p_θ = m l² θ̇ (kg·m²/s) and the Hamiltonian, the energy with
V = 0 at the pivot's height, is H = p_θ²/(2 m l²) − m g l cos θ (J). The
separatrix is the level H = m g l through the upright equilibrium: below it the
pendulum swings, above it it goes over the top.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter
from app.physics.mechanics.model import DerivedModel, derived_parameters
from app.physics.systems.ch07.simple_pendulum import SYSTEM


def _m_l_g(params: Mapping[str, Any]) -> tuple[float, float, float]:
    return float(params["mass_kg"]), float(params["length_m"]), float(params["g_m_s2"])


def conjugate_momentum_kg_m2_s(params: Mapping[str, Any], theta_rate_rad_s: np.ndarray | float) -> np.ndarray:
    """p_θ = m l² θ̇ (kg·m²/s) for rates θ̇ (any shape, rad/s)."""
    m, l, _ = _m_l_g(params)
    return m * l * l * np.asarray(theta_rate_rad_s, dtype=float)


def hamiltonian_J(
    params: Mapping[str, Any], theta_rad: np.ndarray | float, p_theta_kg_m2_s: np.ndarray | float
) -> np.ndarray:
    """H(θ, p_θ) = p_θ²/(2 m l²) − m g l cos θ (J), elementwise."""
    m, l, g = _m_l_g(params)
    return np.asarray(p_theta_kg_m2_s) ** 2 / (2.0 * m * l * l) - m * g * l * np.cos(theta_rad)


def separatrix_energy_J(params: Mapping[str, Any]) -> float:
    """m g l (J): the level of H through the upright equilibrium (θ = π, p_θ = 0)."""
    m, l, g = _m_l_g(params)
    return m * g * l


def level_set_momentum_kg_m2_s(params: Mapping[str, Any], energy_J: float, theta_rad: np.ndarray) -> np.ndarray:
    """The upper branch p_θ ≥ 0 of the level set H = ``energy_J`` over ``theta_rad`` (N,); NaN where unreachable.

    The lower branch is its mirror image, −p_θ.
    """
    m, l, g = _m_l_g(params)
    kinetic = energy_J + m * g * l * np.cos(np.asarray(theta_rad, dtype=float))
    with np.errstate(invalid="ignore"):
        return np.where(kinetic >= 0.0, np.sqrt(2.0 * m * l * l * np.maximum(kinetic, 0.0)), np.nan)


class PendulumPhaseMotion(DerivedModel):
    """The simple pendulum started from the angle and rate the controls give (default: Hamilton's equations)."""

    description = SYSTEM
    parameters = derived_parameters(
        SYSTEM,
        Parameter(
            "theta_0_deg", "deg", 60.0, -180.0, 180.0, "Initial angle of the rod from the downward vertical", "θ₀"
        ),
        Parameter("theta_rate_0_deg_s", "deg/s", 0.0, -1080.0, 1080.0, "Initial rate of the angle", "θ̇₀"),
        default_formulation="hamilton",
    )
    series_units = {"theta_rad": "rad", "p_theta_kg_m2_s": "kg·m²/s", "hamiltonian_J": "J"}
    invariant_units = {"hamiltonian": "J"}

    def initial_state(self, params: Mapping[str, Any]) -> np.ndarray:
        return np.radians([float(params["theta_0_deg"]), float(params["theta_rate_0_deg_s"])])

    def series(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> dict[str, np.ndarray]:
        momentum = conjugate_momentum_kg_m2_s(params, states[:, 1])
        return {
            "theta_rad": states[:, 0],
            "p_theta_kg_m2_s": momentum,
            "hamiltonian_J": hamiltonian_J(params, states[:, 0], momentum),
        }

    def invariants(self, params: Mapping[str, Any], states: np.ndarray) -> dict[str, np.ndarray]:
        return {"hamiltonian": hamiltonian_J(params, states[:, 0], conjugate_momentum_kg_m2_s(params, states[:, 1]))}

    def invariant_scales(self, params: Mapping[str, Any], state: np.ndarray) -> dict[str, float]:
        """H's scale: the swing from hanging to upright, 2 m g l, or the kinetic energy if larger (J)."""
        kinetic = float(conjugate_momentum_kg_m2_s(params, state[1]) ** 2) / (
            2.0 * float(params["mass_kg"]) * float(params["length_m"]) ** 2
        )
        return {"hamiltonian": max(2.0 * separatrix_energy_J(params), kinetic, 1e-12)}
