"""Worked example ``bead-on-hoop-small-oscillations`` (section 7.6): where the bead on the spinning hoop can rest, which
rest is stable, and how fast it swings about it.

The system is :mod:`app.physics.systems.ch07.bead_on_hoop` (θ from the bottom of a hoop of radius R spun at the
prescribed rate Ω about its vertical diameter). Lagrange's equation is ``θ̈ = sin θ (Ω² cos θ − g/R)``; its
equilibria are θ = 0, θ = π and, once Ω exceeds ``Ω_c = √(g/R)``, the pair ``cos θ* = g/(R Ω²)``
(:func:`~app.physics.systems.ch07.bead_on_hoop_model.hoop_equilibria`). Linearised about θₑ,
``δθ̈ + k δθ = 0`` with ``k = (g/R) cos θₑ − Ω² cos 2θₑ``: k > 0 is a small oscillation at ``ω_n = √k``.

The stable equilibrium studied is the bottom below Ω_c and the one of ±θ* on the side of the scene's starting angle
above it. Exactly at the critical spin (or with neither gravity nor spin) k = 0 and there is no oscillation to
find: a ParameterError (a ValueError) naming ``hoop_speed_rad_s``, from the inputs' check and from :func:`solve`.
The check evaluates the engine's Newton–Euler equation at θₑ: θ̈ must vanish there, and its
slope −∂θ̈/∂θ (central difference) must equal k.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.mechanics.engine import derived
from app.physics.systems.ch07.bead_on_hoop import SYSTEM
from app.physics.systems.ch07.bead_on_hoop_model import BeadOnHoopMotion, critical_spin_rad_s, hoop_equilibria

#: A linearised stiffness within this fraction of g/R + Ω² of zero is the critical spin itself: no oscillation.
CRITICAL_ROUND_OFF = 1e-12
#: The step (rad) of the central difference that measures the derived equation's slope at the equilibrium; its
#: error is about h²/6 of the third derivative (≈ 1e-11 of k), far above round-off (≈ 1e-16/h ≈ 1e-11 of k).
SLOPE_STEP_RAD = 1e-5

INPUTS = ParameterSet(
    tuple(
        BeadOnHoopMotion.parameters.by_name[name]
        for name in ("hoop_radius_m", "hoop_speed_rad_s", "g_m_s2", "bead_mass_kg", "theta_0_deg")
    ),
    check=lambda values: _stiffness_or_refusal(values),
)


def stiffness_1_s2(g_over_R: float, spin: float, theta: float) -> float:
    """k = (g/R) cos θ − Ω² cos 2θ (1/s²): minus the slope of θ̈ = sin θ (Ω² cos θ − g/R) at an equilibrium θ."""
    return g_over_R * math.cos(theta) - spin * spin * math.cos(2.0 * theta)


def studied_equilibrium(inputs: Mapping[str, Any]) -> float:
    """θₑ (rad): the bottom at or below the critical spin, else the stable ±θ* on the side of θ₀ (+θ* for θ₀ = 0)."""
    stable = [e.theta_rad for e in hoop_equilibria(inputs) if e.stable]
    if not stable:  # at most the bottom, stable only below the critical spin
        return 0.0
    if len(stable) == 1:
        return stable[0]
    return stable[0] if float(inputs["theta_0_deg"]) >= 0.0 else stable[1]


def _stiffness_or_refusal(inputs: Mapping[str, Any]) -> float:
    """k (1/s²) about the studied equilibrium; a :class:`ParameterError` (a ValueError) naming ``hoop_speed_rad_s``
    where it is zero (the critical spin, or neither gravity nor spin)."""
    R, spin, g = float(inputs["hoop_radius_m"]), float(inputs["hoop_speed_rad_s"]), float(inputs["g_m_s2"])
    k = stiffness_1_s2(g / R, spin, studied_equilibrium(inputs))
    if not k > CRITICAL_ROUND_OFF * (g / R + spin * spin):
        raise ParameterError(
            "hoop_speed_rad_s",
            f"no small oscillation: at Ω = {spin:.6g} rad/s the critical spin √(g/R) = "
            f"{critical_spin_rad_s(inputs):.6g} rad/s is met (or there is neither gravity nor spin), so the linearised "
            "stiffness k = g/R − Ω² at the bottom is zero and a small displacement drifts instead of swinging back; "
            "move Ω away from √(g/R)",
        )
    return k


def solve(inputs: Mapping[str, Any]) -> Solution:
    R, spin, g = float(inputs["hoop_radius_m"]), float(inputs["hoop_speed_rad_s"]), float(inputs["g_m_s2"])
    g_over_R = g / R
    critical = critical_spin_rad_s(inputs)
    theta_e = studied_equilibrium(inputs)
    k = _stiffness_or_refusal(inputs)
    scale = g_over_R + spin * spin
    omega_n = math.sqrt(k)
    period = 2.0 * math.pi / omega_n
    theta_0 = math.radians(float(inputs["theta_0_deg"]))
    offset = math.remainder(theta_0 - theta_e, 2.0 * math.pi)
    parameters = np.array(SYSTEM.parameter_array(inputs), dtype=float)
    engine = derived(SYSTEM, "newton-euler")

    def theta_acceleration(theta: float) -> float:
        return float(engine.state_derivative(0.0, np.array([theta, 0.0]), parameters)[1])

    residual = theta_acceleration(theta_e)
    slope_k = -(theta_acceleration(theta_e + SLOPE_STEP_RAD) - theta_acceleration(theta_e - SLOPE_STEP_RAD)) / (
        2.0 * SLOPE_STEP_RAD
    )
    equilibria: dict[str, float] = {"Omega_c": critical, "Omega": spin}
    stiffnesses: dict[str, float] = {
        "k_bottom": stiffness_1_s2(g_over_R, spin, 0.0),
        "k_top": stiffness_1_s2(g_over_R, spin, math.pi),
    }
    units = {"Omega_c": "rad/s", "Omega": "rad/s", "k_bottom": "1/s²", "k_top": "1/s²"}
    if R * spin * spin > g:
        theta_star = math.acos(g / (R * spin * spin))
        equilibria["theta_star"] = theta_star
        stiffnesses["k_star"] = stiffness_1_s2(g_over_R, spin, theta_star)
        units |= {"theta_star": "rad", "k_star": "1/s²"}
    steps = (
        Step(
            "Lagrange's equation of the bead (the hoop's spin prescribed)",
            r"T = \tfrac12 m R^2(\dot\theta^2 + \Omega^2\sin^2\theta),\quad V = -m g R\cos\theta\ \Rightarrow\ "
            r"\ddot\theta = \sin\theta\,\Big(\Omega^2\cos\theta - \frac gR\Big)",
            {"g/R": g_over_R, "Omega^2": spin * spin},
            {"g/R": "1/s²", "Omega^2": "1/s²"},
        ),
        Step(
            "Equilibria: set θ̇ = θ̈ = 0",
            r"\sin\theta_e\Big(\Omega^2\cos\theta_e - \frac gR\Big) = 0:\quad \theta_e = 0,\ \pi,\ \text{and } "
            r"\pm\theta^*,\ \cos\theta^* = \frac{g}{R\Omega^2}\ \text{once}\ \Omega > \Omega_c = \sqrt{g/R}",
            {name: equilibria[name] for name in equilibria},
            {name: units[name] for name in equilibria},
        ),
        Step(
            "Linearise about each: θ = θₑ + δθ",
            r"\delta\ddot\theta + k\,\delta\theta = 0,\quad k = \frac gR\cos\theta_e - \Omega^2\cos 2\theta_e:"
            r"\quad k_{\rm bottom} = \frac gR - \Omega^2,\ k_{\rm top} = -\frac gR - \Omega^2,\ k^* = \Omega^2"
            r"\sin^2\theta^*",
            stiffnesses,
            {name: units[name] for name in stiffnesses},
        ),
        Step(
            "The stable equilibrium the bead starts near, and its natural frequency (k > 0)",
            r"\omega_n = \sqrt{k},\quad f_n = \frac{\omega_n}{2\pi},\quad \tau_n = \frac{2\pi}{\omega_n}",
            {"theta_e": theta_e, "k": k, "omega_n": omega_n, "f_n": omega_n / (2.0 * math.pi), "tau_n": period},
            {"theta_e": "rad", "k": "1/s²", "omega_n": "rad/s", "f_n": "Hz", "tau_n": "s"},
        ),
        Step(
            "The swing from the scene's start, released at rest on the hoop (linear: while |θ₀ − θₑ| is small)",
            r"\theta(t) \approx \theta_e + (\theta_0 - \theta_e)\cos\omega_n t",
            {"theta_0": theta_0, "theta_0-theta_e": offset},
            {"theta_0": "rad", "theta_0-theta_e": "rad"},
        ),
        Step(
            "Check: the engine's Newton–Euler equation at θₑ rests there, and its slope is −k",
            r"\ddot\theta(\theta_e, 0) = 0,\quad -\frac{\ddot\theta(\theta_e + h) - \ddot\theta(\theta_e - h)}{2h}"
            r" = k,\quad h = 10^{-5}\ \text{rad}",
            {"thetaddot_at_theta_e": residual, "k_engine": slope_k, "k": k},
            {"thetaddot_at_theta_e": "rad/s²", "k_engine": "1/s²", "k": "1/s²"},
            scales={"thetaddot_at_theta_e": scale},
        ),
    )
    outputs = {
        "equilibrium_rad": theta_e,
        "stiffness_1_s2": k,
        "natural_frequency_rad_s": omega_n,
        "period_s": period,
        "critical_spin_rad_s": critical,
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="bead-on-hoop-small-oscillations",
    title="The bead on a spinning hoop: its resting places, their stability and the small swing's frequency",
    chapter=7,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "equilibrium_rad": "rad",
        "stiffness_1_s2": "1/s²",
        "natural_frequency_rad_s": "rad/s",
        "period_s": "s",
        "critical_spin_rad_s": "rad/s",
    },
    section="7.6",
    story=ExampleStory(
        situation=(
            "A bead of mass $m$ slides without friction on a circular hoop of radius $R$. A motor spins the hoop "
            "about its vertical diameter at the steady rate $\\Omega$, whatever the bead does. The bead's angle "
            "from the bottom of the hoop is $\\theta$; the scene releases it at $\\theta_0$ with no motion "
            "relative to the hoop."
        ),
        wanted=(
            "Every angle at which the bead can stay at rest relative to the hoop, which of them are stable, and "
            "for the stable one on the bead's side the natural frequency $\\omega_n$ and period of its small "
            "swings, with the swing that the scene's start should produce."
        ),
        approach=(
            "Lagrange's equation in the one coordinate $\\theta$ is already written; the hoop's push on the bead "
            "never appears. We do not solve it in closed form. Setting $\\dot\\theta = \\ddot\\theta = 0$ gives the "
            "equilibria from one algebraic equation. Writing $\\theta = \\theta_e + \\delta\\theta$ and keeping "
            "first-order terms turns the nonlinear equation into $\\delta\\ddot\\theta + k\\,\\delta\\theta = 0$, "
            "whose sign of $k$ decides stability and whose $\\sqrt k$ is the frequency. Integrating the full "
            "equation and timing the swings would give the same frequency, but only for one amplitude at a time "
            "and without saying why."
        ),
        check=(
            "The engine derives the bead's equation on its own by Newton–Euler, with the hoop's push as an "
            "unknown. Evaluated at our equilibrium with the bead at rest it must give $\\ddot\\theta = 0$ to "
            "round-off, and a central difference of its $\\ddot\\theta$ about $\\theta_e$ must reproduce $k$, "
            "agreeing to about ten digits, the size of the difference's own truncation error."
        ),
        what_if=(
            "Slide the scene's **Ω** up through the critical spin $\\sqrt{g/R}$ (4.43 rad/s with the defaults). "
            "Below it the bottom is stable and $\\omega_n = \\sqrt{g/R - \\Omega^2}$ falls towards zero as you "
            "approach, so the swings get slow and lazy. Above it the bottom turns unstable, the bead settles "
            "at $\\pm\\theta^*$, and $\\omega_n = \\Omega\\sin\\theta^*$ grows again. Watch the bead's swing period "
            "in the scene stretch near the critical spin."
        ),
    ),
)
