"""The double pendulum integrated from its derived equations, and its two small-oscillation frequencies.

State (rad, rad/s): (θ1, θ2, θ̇1, θ̇2), the rods' angles from the downward
vertical (see :mod:`.double_pendulum` for the frame). The system is
conservative and autonomous, so T + V is the invariant.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter
from app.physics.mechanics.model import DerivedModel, derived_parameters
from app.physics.systems.ch07.double_pendulum import SYSTEM


def normal_mode_frequencies_rad_s(params: Mapping[str, Any]) -> tuple[float, float]:
    """(ω_slow, ω_fast) in rad/s of the linearised motion about the bottom, from det(K − ω² M) = 0.

    With μ = m2/(m1 + m2): (1 − μ) l1 l2 ω⁴ − g (l1 + l2) ω² + g² = 0; for
    m1 = m2 and l1 = l2 = l this gives ω² = (g/l)(2 ∓ √2).
    """
    m1, m2, l1, l2, g = (float(params[n]) for n in ("m1_kg", "m2_kg", "l1_m", "l2_m", "g_m_s2"))
    mu = m2 / (m1 + m2)
    a, b = (1.0 - mu) * l1 * l2, g * (l1 + l2)
    root = math.sqrt(b * b - 4.0 * a * g * g)
    slow_sq = 2.0 * g * g / (b + root)  # the smaller root, written to avoid cancellation
    fast_sq = (b + root) / (2.0 * a)
    return math.sqrt(slow_sq), math.sqrt(fast_sq)


class DoublePendulumMotion(DerivedModel):
    """The double pendulum started from the angles and rates the controls give."""

    description = SYSTEM
    parameters = derived_parameters(
        SYSTEM,
        Parameter(
            "theta1_0_deg",
            "deg",
            60.0,
            -180.0,
            180.0,
            "Initial angle of the upper rod from the downward vertical",
            "θ₁₀",
        ),
        Parameter(
            "theta2_0_deg",
            "deg",
            0.0,
            -180.0,
            180.0,
            "Initial angle of the lower rod from the downward vertical",
            "θ₂₀",
        ),
        Parameter("theta1_rate_0_deg_s", "deg/s", 0.0, -720.0, 720.0, "Initial rate of the upper angle", "θ̇₁₀"),
        Parameter("theta2_rate_0_deg_s", "deg/s", 0.0, -720.0, 720.0, "Initial rate of the lower angle", "θ̇₂₀"),
        default_formulation="lagrange",
    )
    series_units = {
        "theta1_rad": "rad",
        "theta2_rad": "rad",
        "theta1_rate_rad_s": "rad/s",
        "theta2_rate_rad_s": "rad/s",
        "energy_J": "J",
    }
    invariant_units = {"energy": "J"}

    def initial_state(self, params: Mapping[str, Any]) -> np.ndarray:
        names = ("theta1_0_deg", "theta2_0_deg", "theta1_rate_0_deg_s", "theta2_rate_0_deg_s")
        return np.radians([float(params[n]) for n in names])

    def energy_J(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> np.ndarray:
        """T + V (J) along ``states`` (N, 4); V is zero at the pivot's height."""
        kinetic, potential = self.energies(params, t_s, states)
        return kinetic + potential

    def series(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> dict[str, np.ndarray]:
        return {
            "theta1_rad": states[:, 0],
            "theta2_rad": states[:, 1],
            "theta1_rate_rad_s": states[:, 2],
            "theta2_rate_rad_s": states[:, 3],
            "energy_J": self.energy_J(params, t_s, states),
        }

    def invariants(self, params: Mapping[str, Any], states: np.ndarray) -> dict[str, np.ndarray]:
        return {"energy": self.energy_J(params, np.zeros(len(states)), states)}

    def invariant_scales(self, params: Mapping[str, Any], state: np.ndarray) -> dict[str, float]:
        """The energy's scale: the swing from hanging to both bobs up, 2 g (m1 (l1) + m2 (l1 + l2)) (J)."""
        m1, m2, l1, l2, g = (float(params[n]) for n in ("m1_kg", "m2_kg", "l1_m", "l2_m", "g_m_s2"))
        kinetic, _ = self.energies(params, np.zeros(1), state[None, :])
        return {"energy": max(2.0 * g * (m1 * l1 + m2 * (l1 + l2)), float(kinetic[0]), 1e-12)}
