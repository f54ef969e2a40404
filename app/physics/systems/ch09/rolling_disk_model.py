"""The rolling disk integrated from its derived (nonholonomic) equations, and the upright disk's stability threshold.

State: (x, y, ψ, θ, φ) in (m, m, rad, rad, rad) then their rates (see
:mod:`.rolling_disk` for the frame and angles): the contact point (x, y), the
heading ψ, the lean θ from the vertical and the spin φ about the disk's axis.
The rolling constraint makes the contact point move along the heading at
r φ̇, so ẋ and ẏ follow from the angle rates (the generalized speeds). The
floor's reaction does no work on a disk rolling without slip: T + V is the
invariant. The model holds while the disk stands on its rim and the floor pushes
(:mod:`.rolling_disk_contact`): a run stops where it has fallen or would lift off.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.optimize import brentq

from app.physics.core.parameters import Parameter
from app.physics.math.rotations import elementary_rotation_matrix
from app.physics.mechanics.model import DerivedModel, derived_parameters
from app.physics.solvers.integrated_model import ModelLimit
from app.physics.systems.ch09.rolling_disk import SYSTEM
from app.physics.systems.ch09.rolling_disk_contact import contact_limit, normal_force_N

#: Indices into the state of the lean θ, the heading rate ψ̇ and the lean rate θ̇: the linearised lean equations'
#: variables.
LEAN, HEADING_RATE, LEAN_RATE, SPIN_RATE = 3, 7, 8, 9
#: Central-difference step (rad, rad/s) of the lean equations' Jacobian: truncation ~h², rounding ~ε/h, both < 1e-10
#: relative.
JACOBIAN_STEP = 1e-5


def disk_pose(radius_m: float, state: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(centre (3,) m, R_NB (3, 3)) of the disk at ``state`` (10,): R_NB = Rz(ψ) Rx(θ) Ry(φ), body y the disk's axis."""
    x, y, heading, lean, spin = (float(v) for v in state[:5])
    rotation = (
        elementary_rotation_matrix(2, heading)
        @ elementary_rotation_matrix(0, lean)
        @ elementary_rotation_matrix(1, spin)
    )
    centre = np.array([x, y, 0.0]) + radius_m * np.array(
        [math.sin(heading) * math.sin(lean), -math.cos(heading) * math.sin(lean), math.cos(lean)]
    )
    return centre, rotation


def contact_speed_m_s(states: np.ndarray) -> np.ndarray:
    """|(ẋ, ẏ)| (m/s), the contact point's speed along the floor, along ``states`` (N, 10)."""
    return np.hypot(states[:, 5], states[:, 6])


class RollingDiskMotion(DerivedModel):
    """The disk started upright-ish from the lean, spin and heading rate the controls give (default: Kane's
    equations)."""

    description = SYSTEM
    parameters = derived_parameters(
        SYSTEM,
        Parameter("lean_0_deg", "deg", 10.0, -60.0, 60.0, "Initial lean of the disk from the vertical", "θ₀"),
        Parameter(
            "spin_rate_0_rad_s",
            "rad/s",
            12.0,
            -60.0,
            60.0,
            "Initial spin rate φ̇ about the disk's axis (rolling speed r φ̇)",
            "φ̇₀",
        ),
        Parameter("heading_rate_0_rad_s", "rad/s", 0.0, -20.0, 20.0, "Initial heading rate ψ̇ about the vertical", "ψ̇₀"),
        default_formulation="kane",
    )
    series_units = {
        "x_m": "m",
        "y_m": "m",
        "heading_rad": "rad",
        "lean_rad": "rad",
        "spin_rate_rad_s": "rad/s",
        "energy_J": "J",
        "normal_force_N": "N",
    }
    invariant_units = {"energy": "J"}

    def initial_state(self, params: Mapping[str, Any]) -> np.ndarray:
        """At the origin heading along +x (ψ = 0): ẋ = r φ̇, ẏ = 0, no lean rate."""
        spin, heading_rate = float(params["spin_rate_0_rad_s"]), float(params["heading_rate_0_rad_s"])
        lean = math.radians(float(params["lean_0_deg"]))
        return np.array([0.0, 0.0, 0.0, lean, 0.0, float(params["radius_m"]) * spin, 0.0, heading_rate, 0.0, spin])

    def energy_J(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> np.ndarray:
        """T + V (J) along ``states`` (N, 10); V = 0 with the centre on the floor."""
        kinetic, potential = self.energies(params, t_s, states)
        return kinetic + potential

    def series(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> dict[str, np.ndarray]:
        return {
            "x_m": states[:, 0],
            "y_m": states[:, 1],
            "heading_rad": states[:, 2],
            "lean_rad": states[:, 3],
            "spin_rate_rad_s": states[:, SPIN_RATE],
            "energy_J": self.energy_J(params, t_s, states),
            "normal_force_N": normal_force_N(params, states),
        }

    def model_limit(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> ModelLimit | None:
        """Where the disk has fallen or would lift off (:func:`~.rolling_disk_contact.contact_limit`)."""
        return contact_limit(params, t_s, states)

    def invariants(self, params: Mapping[str, Any], states: np.ndarray) -> dict[str, np.ndarray]:
        return {"energy": self.energy_J(params, np.zeros(len(states)), states)}

    def invariant_scales(self, params: Mapping[str, Any], state: np.ndarray) -> dict[str, float]:
        """The energy's scale: m g r (upright to flat) or the kinetic energy if larger (J)."""
        m, r, g = (float(params[n]) for n in ("mass_kg", "radius_m", "g_m_s2"))
        kinetic, _ = self.energies(params, np.zeros(1), state[None, :])
        return {"energy": max(m * g * r, float(kinetic[0]), 1e-12)}

    # --- steady upright rolling ----------------------------------------------------------------------------------
    def upright_state(self, params: Mapping[str, Any], spin_rate_rad_s: float) -> np.ndarray:
        """Rolling straight along +x, upright, at spin φ̇ = Ω (10,): an equilibrium of the lean equations."""
        state = np.zeros(10)
        state[5], state[SPIN_RATE] = float(params["radius_m"]) * spin_rate_rad_s, spin_rate_rad_s
        return state

    def lean_jacobian(self, params: Mapping[str, Any], spin_rate_rad_s: float) -> np.ndarray:
        """∂(θ̇, θ̈, ψ̈)/∂(θ, θ̇, ψ̇) (3, 3) of the derived equations at upright rolling with spin Ω, by central
        differences."""
        derivation, p = self.derived(params), self.parameter_array(params)
        state = self.upright_state(params, spin_rate_rad_s)
        variables = (LEAN, LEAN_RATE, HEADING_RATE)
        jacobian = np.empty((3, 3))
        for column, index in enumerate(variables):
            up, down = state.copy(), state.copy()
            up[index] += JACOBIAN_STEP
            down[index] -= JACOBIAN_STEP
            change = derivation.state_derivative(0.0, up, p) - derivation.state_derivative(0.0, down, p)
            jacobian[:, column] = change[list(variables)] / (2.0 * JACOBIAN_STEP)
        return jacobian

    def lean_stiffness_1_s2(self, params: Mapping[str, Any], spin_rate_rad_s: float) -> float:
        """k = −½ Σ λ² (1/s²) over the lean Jacobian's eigenvalues λ (one is 0, the others ±√(−k)).

        k > 0: the lean oscillates about upright (stable); k < 0: it grows.
        """
        eigenvalues = np.linalg.eigvals(self.lean_jacobian(params, spin_rate_rad_s))
        return float(-0.5 * np.sum(eigenvalues**2).real)

    def upright_critical_spin_rad_s(self, params: Mapping[str, Any]) -> float:
        """The spin Ω_c (rad/s) above which steady upright rolling is stable: the root of k(Ω) = 0."""
        if self.lean_stiffness_1_s2(params, 0.0) >= 0.0:
            return 0.0
        high = 1.0
        while self.lean_stiffness_1_s2(params, high) < 0.0:
            high *= 2.0
            if high > 1e8:
                raise ValueError("radius_m, mass_kg, g_m_s2: no spin makes the upright disk stable")
        return float(brentq(lambda spin: self.lean_stiffness_1_s2(params, spin), 0.0, high, xtol=1e-13, rtol=1e-14))
