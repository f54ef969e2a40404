"""Worked example ``spherical-pendulum-routh``: Hamilton's equations, the conserved p_φ and Routh's reduction.

The system is :mod:`app.physics.systems.ch09.spherical_pendulum`: a bob of mass m on a light rod of length l about a
fixed pivot, θ the rod's angle from the downward vertical, φ its azimuth about the vertical (rad). With
L = ½ m l² (θ̇² + sin²θ φ̇²) + m g l cos θ the momenta are p_θ = m l² θ̇ and p_φ = m l² sin²θ φ̇, and

    H = p_θ²/(2 m l²) + p_φ²/(2 m l² sin²θ) − m g l cos θ.

φ is ignorable, so p_φ is constant; Routh's function R = L − p_φ φ̇ leaves the one-degree-of-freedom θ motion in the
effective potential V_eff(θ) = p_φ²/(2 m l² sin²θ) − m g l cos θ. The turning angles are the project's
(:func:`~app.physics.systems.ch09.spherical_pendulum_model.turning_angles_rad`, the two upper roots of a cubic in
u = cos θ); the period of θ between them is the complete elliptic integral T_θ = 4 K(k) √(l / (2 g (u_c − u_a))),
k² = (u_c − u_b)/(u_c − u_a) over the cubic's roots u_a < u_b ≤ u_c (with g = 0 the cubic is a quadratic and
T_θ = 2π l / v). The check integrates Hamilton's four equations (scipy's DOP853, rtol 1e-12) for one T_θ: H and p_φ
must keep their values and θ, p_θ must come back to theirs.

The inputs carry the names of the scenes' controls on the 9.2 lesson (``spherical-pendulum``; ``phase-portrait``
shares all but φ̇₀). φ̇₀ = 0 is refused: the bob then swings in a vertical plane through the lowest point, where θ = 0
and the azimuth is undefined, and there is nothing for Routh's reduction to remove (that motion is the planar
pendulum of the phase portrait).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from scipy.special import ellipk

from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch09.spherical_pendulum_model import effective_potential_J, turning_angles_rad

#: Relative tolerance of the check's integration of Hamilton's equations over one period of θ.
CHECK_RTOL = 1e-12


def _m_l_g(inputs: Mapping[str, Any]) -> tuple[float, float, float]:
    return float(inputs["mass_kg"]), float(inputs["length_m"]), float(inputs["g_m_s2"])


def _check(values: Mapping[str, Any]) -> None:
    if values["phi_rate_0_deg_s"] == 0.0:
        raise ParameterError(
            "phi_rate_0_deg_s",
            "must not be zero: with φ̇₀ = 0 the bob swings in a vertical plane through the lowest point, where θ = 0 "
            "and the azimuth is undefined, and p_φ = 0 leaves nothing for Routh's reduction to remove (that motion "
            "is the planar pendulum of the phase portrait); give the bob some azimuthal rate",
        )


INPUTS = ParameterSet(
    (
        Parameter("mass_kg", "kg", 1.0, 0.01, 100.0, "Mass m of the bob", "m", scale="log"),
        Parameter("length_m", "m", 1.0, 0.05, 10.0, "Length l of the rod", "l", scale="log"),
        Parameter("g_m_s2", "m/s²", 9.81, 0.0, 100.0, "Gravitational acceleration", "g", step=0.01),
        Parameter(
            "theta_0_deg", "deg", 60.0, 1.0, 179.0, "Initial angle θ₀ of the rod from the downward vertical", "θ₀"
        ),
        Parameter("theta_rate_0_deg_s", "deg/s", 0.0, -720.0, 720.0, "Initial rate θ̇₀ of the angle", "θ̇₀"),
        Parameter(
            "phi_rate_0_deg_s",
            "deg/s",
            120.0,
            -1080.0,
            1080.0,
            "Initial rate φ̇₀ of the azimuth about the vertical (not zero)",
            "φ̇₀",
        ),
    ),
    check=_check,
)


def initial_state(inputs: Mapping[str, Any]) -> np.ndarray:
    """(θ, φ, θ̇, φ̇) at t = 0 (rad, rad/s), as the spherical-pendulum model orders its state."""
    return np.array(
        [
            math.radians(inputs["theta_0_deg"]),
            0.0,
            math.radians(inputs["theta_rate_0_deg_s"]),
            math.radians(inputs["phi_rate_0_deg_s"]),
        ]
    )


def hamiltonian_J(inputs: Mapping[str, Any], theta: float, p_theta: float, p_phi: float) -> float:
    m, l, g = _m_l_g(inputs)
    return (
        p_theta**2 / (2.0 * m * l * l)
        + p_phi**2 / (2.0 * m * l * l * math.sin(theta) ** 2)
        - m * g * l * math.cos(theta)
    )


def hamilton_rates(inputs: Mapping[str, Any], y: np.ndarray) -> np.ndarray:
    """(θ̇, φ̇, ṗ_θ, ṗ_φ) from Hamilton's equations at y = (θ, φ, p_θ, p_φ)."""
    m, l, g = _m_l_g(inputs)
    theta, _, p_theta, p_phi = y
    s, c = math.sin(theta), math.cos(theta)
    ml2 = m * l * l
    return np.array([p_theta / ml2, p_phi / (ml2 * s * s), p_phi**2 * c / (ml2 * s**3) - m * g * l * s, 0.0])


def theta_period_s(inputs: Mapping[str, Any], energy_J: float, u_low: float, u_high: float) -> float:
    """Time for θ to go from one turning angle to the other and back (s); ``u_low ≤ u_high`` are their cosines."""
    m, l, g = _m_l_g(inputs)
    if g == 0.0:  # u̇² = (v²/l²)(u_m² − u²): u is harmonic at the angular rate v/l
        speed = math.sqrt(2.0 * energy_J / m)
        return 2.0 * math.pi * l / speed
    u_a = -energy_J / (m * g * l) - u_low - u_high  # the roots of the cubic sum to −E/(m g l)
    k2 = (u_high - u_low) / (u_high - u_a)
    return 4.0 * float(ellipk(k2)) * math.sqrt(l / (2.0 * g * (u_high - u_a)))


def cone_angle_rad(inputs: Mapping[str, Any], p_phi: float) -> float:
    """θ_c (rad) of the minimum of V_eff: the steady cone for this p_φ (dV_eff/dθ = 0)."""
    m, l, g = _m_l_g(inputs)
    ml2 = m * l * l
    if g == 0.0:
        return 0.5 * math.pi
    slope = lambda t: p_phi**2 * math.cos(t) / (ml2 * math.sin(t) ** 3) - m * g * l * math.sin(t)  # noqa: E731
    return float(brentq(lambda t: -slope(t), 1e-9, 0.5 * math.pi, xtol=1e-15, rtol=4.0 * np.finfo(float).eps))


def solve(inputs: Mapping[str, Any]) -> Solution:
    _check(inputs)
    m, l, g = _m_l_g(inputs)
    ml2 = m * l * l
    state = initial_state(inputs)
    theta0, _, theta_rate0, phi_rate0 = (float(v) for v in state)
    p_theta0 = ml2 * theta_rate0
    p_phi = ml2 * math.sin(theta0) ** 2 * phi_rate0
    H0 = hamiltonian_J(inputs, theta0, p_theta0, p_phi)
    rates0 = hamilton_rates(inputs, np.array([theta0, 0.0, p_theta0, p_phi]))
    theta_c = cone_angle_rad(inputs, p_phi)
    theta_min, theta_max = turning_angles_rad(inputs, state)
    period = theta_period_s(inputs, H0, math.cos(theta_max), math.cos(theta_min))
    phi_rate_at = {name: p_phi / (ml2 * math.sin(t) ** 2) for name, t in (("min", theta_min), ("max", theta_max))}
    momentum_scale = max(abs(p_phi), abs(p_theta0), ml2 * math.sqrt(g / l))
    run = solve_ivp(
        lambda _t, y: hamilton_rates(inputs, y),
        (0.0, period),
        np.array([theta0, 0.0, p_theta0, p_phi]),
        method="DOP853",
        rtol=CHECK_RTOL,
        atol=CHECK_RTOL * np.array([1.0, 1.0, momentum_scale, momentum_scale]),
    )
    end = run.y[:, -1]
    H_end = hamiltonian_J(inputs, end[0], end[2], end[3])
    steps = (
        Step(
            "Momenta and the Hamiltonian (T quadratic in the rates, so H = T + V)",
            r"p_\theta = \frac{\partial L}{\partial\dot\theta} = ml^2\dot\theta,\quad p_\phi = "
            r"\frac{\partial L}{\partial\dot\phi} = ml^2\sin^2\theta\,\dot\phi,\quad H = \frac{p_\theta^2}{2ml^2} + "
            r"\frac{p_\phi^2}{2ml^2\sin^2\theta} - mgl\cos\theta",
            {"p_θ": p_theta0, "p_φ": p_phi, "H": H0},
            {"p_θ": "kg·m²/s", "p_φ": "kg·m²/s", "H": "J"},
        ),
        Step(
            "Hamilton's equations: φ is ignorable, so p_φ is constant",
            r"\dot\theta = \frac{p_\theta}{ml^2},\quad \dot\phi = \frac{p_\phi}{ml^2\sin^2\theta},\quad "
            r"\dot p_\theta = \frac{p_\phi^2\cos\theta}{ml^2\sin^3\theta} - mgl\sin\theta,\quad "
            r"\dot p_\phi = -\frac{\partial H}{\partial\phi} = 0",
            {"φ̇(0)": float(rates0[1]), "ṗ_θ(0)": float(rates0[2])},
            {"φ̇(0)": "rad/s", "ṗ_θ(0)": "N·m"},
        ),
        Step(
            "Routh's function: θ alone, in an effective potential; its minimum is the steady cone for this p_φ",
            r"R = L - p_\phi\dot\phi = \tfrac12 ml^2\dot\theta^2 - V_{\rm eff}(\theta),\quad V_{\rm eff} = "
            r"\frac{p_\phi^2}{2ml^2\sin^2\theta} - mgl\cos\theta,\quad V_{\rm eff}'(\theta_c) = 0",
            {
                "V_eff(θ₀)": float(effective_potential_J(inputs, p_phi, theta0)),
                "θ_c": math.degrees(theta_c),
                "V_eff(θ_c)": float(effective_potential_J(inputs, p_phi, theta_c)),
            },
            {"V_eff(θ₀)": "J", "θ_c": "deg", "V_eff(θ_c)": "J"},
        ),
        Step(
            "Turning angles: V_eff(θ) = H, a cubic in u = cos θ; the azimuth rate there",
            r"\dot u^2 = \frac{2}{ml^2}(H + mglu)(1 - u^2) - \left(\frac{p_\phi}{ml^2}\right)^2 = 0,\quad "
            r"\dot\phi = \frac{p_\phi}{ml^2\sin^2\theta}",
            {
                "θ_min": math.degrees(theta_min),
                "θ_max": math.degrees(theta_max),
                "φ̇ at θ_min": phi_rate_at["min"],
                "φ̇ at θ_max": phi_rate_at["max"],
            },
            {"θ_min": "deg", "θ_max": "deg", "φ̇ at θ_min": "rad/s", "φ̇ at θ_max": "rad/s"},
        ),
        Step(
            "Period of θ between the turning angles: a complete elliptic integral over the cubic's roots",
            r"T_\theta = 2\int_{u_b}^{u_c}\frac{du}{\sqrt{\dot u^2}} = 4K(k)\sqrt{\frac{l}{2g(u_c - u_a)}},\quad "
            r"k^2 = \frac{u_c - u_b}{u_c - u_a},\quad u_a + u_b + u_c = -\frac{H}{mgl}",
            {"T_θ": period},
            {"T_θ": "s"},
        ),
        Step(
            "Check: Hamilton's equations integrated over one T_θ conserve H and p_φ and bring θ, p_θ back",
            r"H(T_\theta) = H(0),\quad p_\phi(T_\theta) = p_\phi(0),\quad \theta(T_\theta) = \theta_0,\quad "
            r"p_\theta(T_\theta) = p_\theta(0)",
            {
                "H(0)": H0,
                "H(T_θ)": H_end,
                "p_φ(0)": p_phi,
                "p_φ(T_θ)": float(end[3]),
                "θ(0)": math.degrees(theta0),
                "θ(T_θ)": math.degrees(float(end[0])),
                "p_θ(0)": p_theta0,
                "p_θ(T_θ)": float(end[2]),
            },
            {
                "H(0)": "J",
                "H(T_θ)": "J",
                "p_φ(0)": "kg·m²/s",
                "p_φ(T_θ)": "kg·m²/s",
                "θ(0)": "deg",
                "θ(T_θ)": "deg",
                "p_θ(0)": "kg·m²/s",
                "p_θ(T_θ)": "kg·m²/s",
            },
        ),
    )
    outputs = {
        "p_theta_kg_m2_s": p_theta0,
        "p_phi_kg_m2_s": p_phi,
        "hamiltonian_J": H0,
        "cone_angle_deg": math.degrees(theta_c),
        "theta_min_deg": math.degrees(theta_min),
        "theta_max_deg": math.degrees(theta_max),
        "phi_rate_at_theta_min_rad_s": phi_rate_at["min"],
        "phi_rate_at_theta_max_rad_s": phi_rate_at["max"],
        "theta_period_s": period,
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="spherical-pendulum-routh",
    title="The spherical pendulum: Hamilton's equations, a conserved momentum and Routh's reduction",
    chapter=9,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "p_theta_kg_m2_s": "kg·m²/s",
        "p_phi_kg_m2_s": "kg·m²/s",
        "hamiltonian_J": "J",
        "cone_angle_deg": "deg",
        "theta_min_deg": "deg",
        "theta_max_deg": "deg",
        "phi_rate_at_theta_min_rad_s": "rad/s",
        "phi_rate_at_theta_max_rad_s": "rad/s",
        "theta_period_s": "s",
    },
    section="9.2",
    story=ExampleStory(
        situation=(
            "A 1 kg bob hangs from a pivot on a light 1 m rod. We pull it out to $\\theta_0 = 60°$ from the "
            "downward vertical and flick it sideways, so that it starts with no rate in $\\theta$ but sweeps round "
            "the vertical at $\\dot\\phi_0 = 120°$/s. That is slower than the $254°$/s a conical pendulum at "
            "$60°$ needs, so the bob sinks as it goes round."
        ),
        wanted=(
            "The momenta and the Hamiltonian at the start, the steady cone angle for the bob's angular momentum "
            "about the vertical, the lowest and highest angles $\\theta$ reaches, how fast it sweeps round at each, "
            "and the time $\\theta$ takes to go from one to the other and back."
        ),
        approach=(
            "In Hamilton's form the coordinate $\\phi$ is absent from $H$, so its momentum $p_\\phi$, the angular "
            "momentum about the vertical, is a constant fixed by the start. Routh's method folds that constant into "
            "an effective potential, and $\\theta$ moves like a one-degree-of-freedom system: its turning angles "
            "come from one energy equation and its period from one integral, with no integration in time. "
            "Lagrange's two coupled second-order equations give the same motion, but only as numbers from a "
            "time-stepping run, which hide why the bob stays between two cones."
        ),
        check=(
            "The check runs Hamilton's four first-order equations forward in time, for exactly the period $T_\\theta$ "
            "found from the elliptic integral. $H$ must keep its value because nothing depends on time, and $p_\\phi$ "
            "because $\\phi$ is ignorable. If the period is right, $\\theta$ and $p_\\theta$ must also be back where "
            "they started. All four pairs agree to about ten figures."
        ),
        what_if=(
            "Switch the lesson to its spherical-pendulum scene and raise **φ̇₀** from 120°/s towards 254°/s, the "
            "conical rate at 60°. The lower turning angle climbs towards 60°, the band between the two cones "
            "narrows round $\\theta_c$, and $T_\\theta$ settles near 1.07 s, the period of small oscillations "
            "about the steady cone. Go past 254°/s and the bob rises instead of sinking: $\\theta_0$ becomes the "
            "lower turning angle. In the scene, watch the bob's path close in on a circle."
        ),
    ),
)
