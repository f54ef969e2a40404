"""Answers of chapter 7's exercises: Lagrange's equations for the systems of the derivation engine's catalogue."""

from __future__ import annotations

import math
from collections.abc import Mapping

import sympy

from app.practice.exercise import PartAnswer

theta, theta_rate, m, R, Omega, g = sympy.symbols("theta thetad m R Omega g", real=True)


def bead_on_hoop_lagrange(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The bead on a hoop spun at a prescribed Ω about its vertical diameter (θ from the bottom): T, V (up to a
    constant), the equation of motion solved for θ̈, and the steady angle off the bottom at the given numbers."""
    kinetic = m * R**2 * (theta_rate**2 + Omega**2 * sympy.sin(theta) ** 2) / 2
    potential = -m * g * R * sympy.cos(theta)
    acceleration = (Omega**2 * sympy.cos(theta) - g / R) * sympy.sin(theta)
    radius, spin, gravity = given["hoop_radius_m"], given["hoop_speed_rad_s"], given["g_m_s2"]
    ratio = gravity / (radius * spin**2)
    if ratio >= 1.0:
        raise ValueError("the hoop turns too slowly for a steady angle off the bottom")
    steady = math.degrees(math.acos(ratio))
    return {
        "kinetic": PartAnswer(
            kinetic,
            r"T = \tfrac12 m \left(R^2\dot\theta^2 + (R\sin\theta)^2\,\Omega^2\right)",
            {
                "no-hoop-spin": m * R**2 * theta_rate**2 / 2,
                "spin-radius-cos": m * R**2 * (theta_rate**2 + Omega**2 * sympy.cos(theta) ** 2) / 2,
            },
        ),
        "potential": PartAnswer(
            potential, r"V = -m g R \cos\theta \quad(\text{zero at the hoop's centre})", {"potential-sign": -potential}
        ),
        "equation": PartAnswer(
            acceleration,
            r"m R^2 \ddot\theta - m R^2 \Omega^2 \sin\theta\cos\theta + m g R \sin\theta = 0"
            r"\ \Rightarrow\ \ddot\theta = \left(\Omega^2\cos\theta - \tfrac{g}{R}\right)\sin\theta",
            {
                "no-centrifugal": -g / R * sympy.sin(theta),
                "gravity-sign": (Omega**2 * sympy.cos(theta) + g / R) * sympy.sin(theta),
            },
        ),
        "steady": PartAnswer(
            steady,
            rf"\cos\theta_s = \frac{{g}}{{R\,\Omega^2}} = {ratio:.4g},\ \theta_s = {steady:.4g}^\circ",
            {"steady-sine": math.degrees(math.asin(ratio))},
        ),
    }
