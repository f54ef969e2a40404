"""The bead on the spinning hoop integrated from its derived equations; its equilibria and the Jacobi integral.

State (rad, rad/s): (θ, θ̇), θ from the bottom of the hoop (see
:mod:`.bead_on_hoop`). The hoop's spin is prescribed, so the system is
rheonomic: the energy T + V changes (the motor that holds Ω does work) while
the Jacobi integral h = T₂ − T₀ + V stays constant.

Equilibria relative to the hoop: θ = 0 and θ = π always; cos θ* = g/(RΩ²)
(a pair ±θ*) once Ω exceeds the critical spin √(g/R). Linearised about
θ = 0, δθ̈ = −(g/R − Ω²) δθ; about θ*, δθ̈ = −Ω² sin²θ* δθ.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter
from app.physics.mechanics.model import DerivedModel, derived_parameters
from app.physics.systems.ch07.bead_on_hoop import SYSTEM


@dataclass(frozen=True)
class HoopEquilibrium:
    """A relative equilibrium: the angle from the bottom (rad) and whether small motions about it stay small."""

    theta_rad: float
    stable: bool


def critical_spin_rad_s(params: Mapping[str, Any]) -> float:
    """√(g/R) in rad/s: above it the bottom is unstable and the off-bottom pair exists."""
    return math.sqrt(float(params["g_m_s2"]) / float(params["hoop_radius_m"]))


def hoop_equilibria(params: Mapping[str, Any]) -> tuple[HoopEquilibrium, ...]:
    """The relative equilibria in (−π, π], bottom first, with their stability from the linearised equation."""
    g, R, spin = float(params["g_m_s2"]), float(params["hoop_radius_m"]), float(params["hoop_speed_rad_s"])
    below_critical = R * spin * spin <= g
    found = [HoopEquilibrium(0.0, below_critical), HoopEquilibrium(math.pi, False)]
    if not below_critical:
        off_bottom = math.acos(g / (R * spin * spin))
        found += [HoopEquilibrium(off_bottom, True), HoopEquilibrium(-off_bottom, True)]
    return tuple(found)


class BeadOnHoopMotion(DerivedModel):
    """The bead started at θ₀ with rate θ̇₀ relative to the hoop."""

    description = SYSTEM
    parameters = derived_parameters(
        SYSTEM,
        Parameter(
            "theta_0_deg", "deg", 20.0, -180.0, 180.0, "Initial angle of the bead from the bottom of the hoop", "θ₀"
        ),
        Parameter(
            "theta_rate_0_deg_s", "deg/s", 0.0, -720.0, 720.0, "Initial rate of that angle (relative to the hoop)", "θ̇₀"
        ),
        default_formulation="lagrange",
    )
    series_units = {"theta_rad": "rad", "theta_rate_rad_s": "rad/s", "energy_J": "J", "jacobi_integral_J": "J"}
    invariant_units = {"jacobi_integral": "J"}

    def initial_state(self, params: Mapping[str, Any]) -> np.ndarray:
        return np.radians([float(params["theta_0_deg"]), float(params["theta_rate_0_deg_s"])])

    def energy_and_jacobi_J(
        self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """(T + V, T₂ − T₀ + V) in J along ``states`` (N, 2) at ``t_s`` (N,).

        T splits by degree in the rates: T₂ = (T(q̇) + T(−q̇))/2 − T₀ with T₀ = T(0),
        so h = (T(q̇) + T(−q̇))/2 − 2 T₀ + V.
        """
        n = len(self.description.coordinates)
        reversed_rates, at_rest = states.copy(), states.copy()
        reversed_rates[:, n:] *= -1.0
        at_rest[:, n:] = 0.0
        kinetic, potential = self.energies(params, t_s, states)
        kinetic_reversed, _ = self.energies(params, t_s, reversed_rates)
        kinetic_at_rest, _ = self.energies(params, t_s, at_rest)
        jacobi = 0.5 * (kinetic + kinetic_reversed) - 2.0 * kinetic_at_rest + potential
        return kinetic + potential, jacobi

    def series(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> dict[str, np.ndarray]:
        energy, jacobi = self.energy_and_jacobi_J(params, t_s, states)
        return {
            "theta_rad": states[:, 0],
            "theta_rate_rad_s": states[:, 1],
            "energy_J": energy,
            "jacobi_integral_J": jacobi,
        }

    def energy_note(self, params: Mapping[str, Any]) -> str | None:
        if float(params["hoop_speed_rad_s"]) == 0.0:
            return None
        return (
            "the motor that holds the hoop's spin does work that is not tracked: dissipated shows E(0) − "
            "E(t), not a loss"
        )

    def invariants(self, params: Mapping[str, Any], states: np.ndarray) -> dict[str, np.ndarray]:
        """The Jacobi integral (J); T and V do not depend on t itself here, so t = 0 is used."""
        _, jacobi = self.energy_and_jacobi_J(params, np.zeros(len(states)), states)
        return {"jacobi_integral": jacobi}

    def invariant_scales(self, params: Mapping[str, Any], state: np.ndarray) -> dict[str, float]:
        """The Jacobi integral's scale: m R (2 g + R Ω²) plus the relative kinetic energy at the start (J)."""
        m, R = float(params["bead_mass_kg"]), float(params["hoop_radius_m"])
        g, spin = float(params["g_m_s2"]), float(params["hoop_speed_rad_s"])
        relative_kinetic = 0.5 * m * (R * float(state[1])) ** 2
        return {"jacobi_integral": max(m * R * (2.0 * g + R * spin * spin) + relative_kinetic, 1e-12)}
