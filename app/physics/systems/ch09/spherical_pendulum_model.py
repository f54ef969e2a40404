"""The spherical pendulum integrated from its derived equations, and Routh's one-degree-of-freedom picture of it.

State (rad, rad/s): (θ, φ, θ̇, φ̇), θ from the downward vertical, φ the azimuth
(see :mod:`.spherical_pendulum` for the frame). φ is ignorable, so its
momentum β = m l² sin²θ φ̇ (kg·m²/s, the angular momentum about the vertical)
is conserved, and the energy E = ½ m l² θ̇² + V_eff(θ) with the effective
potential V_eff(θ) = β²/(2 m l² sin²θ) − m g l cos θ (J, V = 0 at the pivot's
height). θ stays between the turning angles where V_eff(θ) = E.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter
from app.physics.mechanics.model import DerivedModel, derived_parameters
from app.physics.systems.ch09.spherical_pendulum import SYSTEM


def _m_l_g(params: Mapping[str, Any]) -> tuple[float, float, float]:
    return float(params["mass_kg"]), float(params["length_m"]), float(params["g_m_s2"])


def azimuthal_momentum_kg_m2_s(params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
    """β = m l² sin²θ φ̇ (kg·m²/s) along ``states`` (N, 4)."""
    m, l, _ = _m_l_g(params)
    return m * l * l * np.sin(states[:, 0]) ** 2 * states[:, 3]


def effective_potential_J(params: Mapping[str, Any], beta_kg_m2_s: float, theta_rad: np.ndarray | float) -> np.ndarray:
    """V_eff(θ) = β²/(2 m l² sin²θ) − m g l cos θ (J) over ``theta_rad`` (any shape, 0 < θ < π)."""
    m, l, g = _m_l_g(params)
    theta = np.asarray(theta_rad, dtype=float)
    with np.errstate(divide="ignore"):
        return beta_kg_m2_s**2 / (2.0 * m * l * l * np.sin(theta) ** 2) - m * g * l * np.cos(theta)


def energy_J(params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
    """E = ½ m l² θ̇² + V_eff(θ) = T + V (J) along ``states`` (N, 4)."""
    m, l, g = _m_l_g(params)
    theta, phi_rate = states[:, 0], states[:, 3]
    return 0.5 * m * l * l * (states[:, 2] ** 2 + np.sin(theta) ** 2 * phi_rate**2) - m * g * l * np.cos(theta)


def turning_angles_rad(params: Mapping[str, Any], state: np.ndarray) -> tuple[float, float]:
    """(θ_min, θ_max) in rad: where V_eff(θ) equals the energy of ``state`` (4,).

    With u = cos θ the condition θ̇ = 0 is the cubic
    F(u) = (2/(m l²)) (E + m g l u)(1 − u²) − β²/(m l²)² = u̇² = 0, which is
    positive at −∞ and ≤ 0 at u = ±1: its two largest roots lie in [−1, 1]
    and are cos θ_max ≤ cos θ_min. Each root is polished by Newton's method.
    """
    m, l, g = _m_l_g(params)
    beta = float(azimuthal_momentum_kg_m2_s(params, state[None, :])[0])
    energy = float(energy_J(params, state[None, :])[0])
    a, k, c = 2.0 / (m * l * l), m * g * l, (beta / (m * l * l)) ** 2
    cubic = np.array([-a * k, -a * energy, a * k, a * energy - c])
    roots = np.roots(cubic)
    real = np.sort(roots.real[np.abs(roots.imag) <= 1e-7 * max(1.0, float(np.max(np.abs(roots))))])
    derivative = np.polyder(cubic)
    polished = []
    for u in real[-2:]:
        for _ in range(3):
            slope = np.polyval(derivative, u)
            if slope == 0.0:
                break
            u -= np.polyval(cubic, u) / slope
        polished.append(min(max(float(u), -1.0), 1.0))
    if len(polished) < 2:  # a steady cone: a double root that rounding pushed off the real axis
        polished = [math.cos(float(state[0]))] * 2
    return math.acos(polished[1]), math.acos(polished[0])


def conical_rate_rad_s(params: Mapping[str, Any], theta_rad: float) -> float | None:
    """φ̇ of steady conical motion at θ (rad/s, the positive root of φ̇² = g/(l cos θ)); None for θ ≥ 90°."""
    _, l, g = _m_l_g(params)
    cosine = math.cos(theta_rad)
    return math.sqrt(g / (l * cosine)) if cosine > 0.0 else None


class SphericalPendulumMotion(DerivedModel):
    """The spherical pendulum started from the angle and rates the controls give (default: Routh's equations)."""

    description = SYSTEM
    parameters = derived_parameters(
        SYSTEM,
        Parameter("theta_0_deg", "deg", 60.0, 1.0, 179.0, "Initial angle of the rod from the downward vertical", "θ₀"),
        Parameter("theta_rate_0_deg_s", "deg/s", 0.0, -720.0, 720.0, "Initial rate of θ", "θ̇₀"),
        Parameter(
            "phi_rate_0_deg_s",
            "deg/s",
            120.0,
            -1080.0,
            1080.0,
            "Initial rate of the azimuth φ about the vertical",
            "φ̇₀",
        ),
        default_formulation="routh",
    )
    series_units = {"theta_rad": "rad", "phi_rad": "rad", "beta_kg_m2_s": "kg·m²/s", "energy_J": "J"}
    invariant_units = {"energy": "J", "azimuthal_momentum": "kg·m²/s"}

    def initial_state(self, params: Mapping[str, Any]) -> np.ndarray:
        theta0, theta_rate0, phi_rate0 = (
            float(params[n]) for n in ("theta_0_deg", "theta_rate_0_deg_s", "phi_rate_0_deg_s")
        )
        return np.radians([theta0, 0.0, theta_rate0, phi_rate0])

    def series(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> dict[str, np.ndarray]:
        return {
            "theta_rad": states[:, 0],
            "phi_rad": states[:, 1],
            "beta_kg_m2_s": azimuthal_momentum_kg_m2_s(params, states),
            "energy_J": energy_J(params, states),
        }

    def invariants(self, params: Mapping[str, Any], states: np.ndarray) -> dict[str, np.ndarray]:
        return {"energy": energy_J(params, states), "azimuthal_momentum": azimuthal_momentum_kg_m2_s(params, states)}

    def invariant_scales(self, params: Mapping[str, Any], state: np.ndarray) -> dict[str, float]:
        """Energy: 2 m g l or the kinetic energy if larger (J); β: its value or m l √(g l) if larger (kg·m²/s)."""
        m, l, g = _m_l_g(params)
        one = state[None, :]
        kinetic = float(energy_J(params, one)[0]) + m * g * l * math.cos(float(state[0]))
        beta = abs(float(azimuthal_momentum_kg_m2_s(params, one)[0]))
        return {
            "energy": max(2.0 * m * g * l, kinetic, 1e-12),
            "azimuthal_momentum": max(beta, m * l * math.sqrt(g * l), 1e-12),
        }
