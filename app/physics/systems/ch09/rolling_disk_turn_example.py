"""Worked example ``rolling-disk-steady-turn``: Kane's lean equation for the rolling disk, and its steady turn.

The system and its frame are :mod:`app.physics.systems.ch09.rolling_disk`'s: a uniform thin disk (mass m, radius r;
A = m r²/4 about a diameter, C = m r²/2 about its axis) rolls without slip on the floor z = 0. Coordinates: contact
point (x, y), heading ψ, lean θ from the vertical, spin φ, with R_NB = Rz(ψ) Rx(θ) Ry(φ). The generalized speeds are
the three angle rates u_θ = θ̇, u_ψ = ψ̇, u_φ = φ̇. In the lean frame e₁ (horizontal, along the heading), e₂ (the
disk's axis), e₃ (from the contact point to the centre G)::

    ω = u_θ e₁ + (u_ψ sin θ + u_φ) e₂ + u_ψ cos θ e₃,     v_G = ω × r e₃ = r (u_ψ sin θ + u_φ) e₁ − r u_θ e₂.

Kane's equation for the lean speed u_θ (partial velocities ∂v_G/∂u_θ = −r e₂, ∂ω/∂u_θ = e₁; the contact force has a
zero partial velocity, since the contact point does not move) is

    (5/4) m r² θ̈ = m g r sin θ + (3/2) m r² ψ̇ φ̇ cos θ + (5/4) m r² ψ̇² sin θ cos θ.

With θ̇ = 0 and θ̈ = 0 it is a quadratic in ψ̇ whose smaller root is the steady turn. The check evaluates the
project's Gibbs–Appell equations (its engine derives them from the acceleration energy) at the same state: they give
the same θ̈, and θ̈ = 0 at the steady heading rate.

The inputs carry the names of the scene ``rolling-disk``'s controls. The state starts with θ̇ = 0, as the scene's does.
A state where the floor would have to pull the disk down (N = m (g − r θ̈ sin θ) < 0) cannot roll at all: it is
refused.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample

#: The formulation the check asks the project's derivation engine for (the example itself works Kane's by hand).
CHECK_FORMULATION = "gibbs-appell"


def _m_r_g(inputs: Mapping[str, Any]) -> tuple[float, float, float]:
    return float(inputs["mass_kg"]), float(inputs["radius_m"]), float(inputs["g_m_s2"])


def lean_terms(inputs: Mapping[str, Any], heading_rate_rad_s: float) -> tuple[float, float, float, float]:
    """(gravity, gyroscopic, centrifugal moments (N·m), θ̈ (rad/s²)) of Kane's lean equation at θ̇ = 0."""
    m, r, g = _m_r_g(inputs)
    theta = math.radians(float(inputs["lean_0_deg"]))
    spin = float(inputs["spin_rate_0_rad_s"])
    gravity = m * g * r * math.sin(theta)
    gyroscopic = 1.5 * m * r * r * heading_rate_rad_s * spin * math.cos(theta)
    centrifugal = 1.25 * m * r * r * heading_rate_rad_s**2 * math.sin(theta) * math.cos(theta)
    return gravity, gyroscopic, centrifugal, (gravity + gyroscopic + centrifugal) / (1.25 * m * r * r)


def steady_heading_rates(inputs: Mapping[str, Any]) -> tuple[float, float] | None:
    """The two heading rates ψ̇ (rad/s; the slow one first) that hold the lean steady, or None if there are none.

    θ̈ = 0 at θ̇ = 0 is a ψ̇² + b ψ̇ + c = 0 with a = 5 sin θ cos θ, b = 6 φ̇ cos θ, c = 4 (g/r) sin θ. The slow root
    is c/q with q = −(b + sign(b)√D)/2 (no cancellation); when a = 0 (upright) it is the only root, and the other is
    returned as NaN.
    """
    _, r, g = _m_r_g(inputs)
    theta = math.radians(float(inputs["lean_0_deg"]))
    spin = float(inputs["spin_rate_0_rad_s"])
    a = 5.0 * math.sin(theta) * math.cos(theta)
    b = 6.0 * spin * math.cos(theta)
    c = 4.0 * g / r * math.sin(theta)
    discriminant = b * b - 4.0 * a * c
    if discriminant < 0.0:
        return None
    q = -0.5 * (b + math.copysign(math.sqrt(discriminant), b if b != 0.0 else 1.0))
    slow = c / q + 0.0 if q != 0.0 else 0.0  # + 0.0: an upright disk's 0 is not shown as −0
    fast = q / a if a != 0.0 else math.nan
    return slow, fast


def disk_state(inputs: Mapping[str, Any], heading_rate_rad_s: float) -> np.ndarray:
    """The model's state (10,) at the start: at the origin heading along +x, θ̇ = 0 (as the scene starts it)."""
    _, r, _ = _m_r_g(inputs)
    spin = float(inputs["spin_rate_0_rad_s"])
    lean = math.radians(float(inputs["lean_0_deg"]))
    return np.array([0.0, 0.0, 0.0, lean, 0.0, r * spin, 0.0, heading_rate_rad_s, 0.0, spin])


def derived_lean_acceleration(inputs: Mapping[str, Any], heading_rate_rad_s: float) -> float:
    """θ̈ (rad/s²) from the project's derived equations (:data:`CHECK_FORMULATION`) at the start state."""
    from app.physics.systems.ch09.rolling_disk_model import LEAN_RATE, RollingDiskMotion

    model = RollingDiskMotion()
    params = {**inputs, "formulation": CHECK_FORMULATION}
    derivation = model.derived(params)
    rates = derivation.state_derivative(0.0, disk_state(inputs, heading_rate_rad_s), model.parameter_array(params))
    return float(rates[LEAN_RATE])


def _check(values: Mapping[str, Any]) -> None:
    m, r, g = _m_r_g(values)
    theta = math.radians(float(values["lean_0_deg"]))
    *_, lean_acceleration = lean_terms(values, float(values["heading_rate_0_rad_s"]))
    normal = m * (g - r * lean_acceleration * math.sin(theta))
    if normal < 0.0:
        raise ParameterError(
            "heading_rate_0_rad_s",
            f"the floor would have to pull the disk down (normal force N = m (g − r θ̈ sin θ) = {normal:.4g} N): "
            "with this lean, spin and heading rate the disk leaves the floor at once and cannot roll; reduce the "
            "heading rate or the lean, or raise g",
        )


INPUTS = ParameterSet(
    (
        Parameter("mass_kg", "kg", 1.0, 0.01, 100.0, "Mass m of the disk", "m", scale="log"),
        Parameter("radius_m", "m", 0.1, 0.005, 5.0, "Radius r of the disk", "r", scale="log"),
        Parameter("g_m_s2", "m/s²", 9.81, 0.0, 100.0, "Gravitational acceleration", "g", step=0.01),
        Parameter("lean_0_deg", "deg", 10.0, -60.0, 60.0, "Lean θ of the disk from the vertical", "θ₀", step=0.5),
        Parameter(
            "spin_rate_0_rad_s",
            "rad/s",
            12.0,
            -60.0,
            60.0,
            "Spin rate φ̇ about the disk's axis (rolling speed r φ̇)",
            "φ̇₀",
            step=0.1,
        ),
        Parameter(
            "heading_rate_0_rad_s", "rad/s", 0.0, -20.0, 20.0, "Heading rate ψ̇ about the vertical", "ψ̇₀", step=0.01
        ),
    ),
    check=_check,
)


def solve(inputs: Mapping[str, Any]) -> Solution:
    _check(inputs)
    m, r, g = _m_r_g(inputs)
    theta = math.radians(float(inputs["lean_0_deg"]))
    spin = float(inputs["spin_rate_0_rad_s"])
    heading = float(inputs["heading_rate_0_rad_s"])
    omega = np.array([0.0, heading * math.sin(theta) + spin, heading * math.cos(theta)])
    v_G = np.array([r * omega[1], 0.0, 0.0])
    gravity, gyroscopic, centrifugal, lean_acceleration = lean_terms(inputs, heading)
    steady = steady_heading_rates(inputs)
    steady_values: dict[str, float]
    if steady is None:
        steady_title = "Steady turn: none at this lean and spin (the quadratic has no real root; the disk must fall)"
        steady_values = {
            "discriminant": (6.0 * spin * math.cos(theta)) ** 2 - 80.0 * g / r * math.sin(theta) ** 2 * math.cos(theta)
        }
        steady_units = {"discriminant": "1/s²"}
        check_heading = heading
    else:
        slow, fast = steady
        steady_title = "Steady turn: the heading rates that hold the lean constant (θ̈ = 0 at θ̇ = 0)"
        steady_values = {"ψ̇_steady": slow}
        steady_units = {"ψ̇_steady": "rad/s"}
        if math.isfinite(fast):
            steady_values["ψ̇_fast"] = fast
            steady_units["ψ̇_fast"] = "rad/s"
        if slow != 0.0:
            steady_values["R = r φ̇ / ψ̇"] = abs(r * spin / slow)
            steady_units["R = r φ̇ / ψ̇"] = "m"
        check_heading = slow
    derived_now = derived_lean_acceleration(inputs, heading)
    check_values = {"θ̈ (Kane, by hand)": lean_acceleration, "θ̈ (Gibbs–Appell, derived)": derived_now}
    check_units = {"θ̈ (Kane, by hand)": "rad/s²", "θ̈ (Gibbs–Appell, derived)": "rad/s²"}
    if steady is not None:
        check_values["θ̈ at ψ̇_steady (Gibbs–Appell)"] = derived_lean_acceleration(inputs, check_heading)
        check_units["θ̈ at ψ̇_steady (Gibbs–Appell)"] = "rad/s²"
    steps = (
        Step(
            "Generalized speeds u = (θ̇, ψ̇, φ̇): angular velocity and centre velocity, rolling built in",
            r"\bar\omega = u_\theta\bar e_1 + (u_\psi\sin\theta + u_\phi)\,\bar e_2 + u_\psi\cos\theta\,\bar e_3,"
            r"\quad \bar v_G = \bar\omega\times r\bar e_3 = r(u_\psi\sin\theta + u_\phi)\,\bar e_1"
            r" - r u_\theta\,\bar e_2",
            {"ω (e₁,e₂,e₃)": omega, "v_G (e₁,e₂,e₃)": v_G},
            {"ω (e₁,e₂,e₃)": "rad/s", "v_G (e₁,e₂,e₃)": "m/s"},
        ),
        Step(
            "Partial velocities for the lean speed, and its generalized active force (the contact force drops out)",
            r"\frac{\partial\bar v_G}{\partial u_\theta} = -r\,\bar e_2,\quad \frac{\partial\bar\omega}{\partial "
            r"u_\theta} = \bar e_1,\quad F_\theta = (-mg\bar k)\cdot(-r\bar e_2) = m g r\sin\theta",
            {"F_θ": gravity},
            {"F_θ": "N·m"},
        ),
        Step(
            "Kane's lean equation F_θ + F*_θ = 0 (no θ̇ term appears), evaluated at the start",
            r"\tfrac54 m r^2\,\ddot\theta = m g r\sin\theta + \tfrac32 m r^2\,\dot\psi\dot\phi\cos\theta + "
            r"\tfrac54 m r^2\,\dot\psi^2\sin\theta\cos\theta",
            {
                "m g r sin θ": gravity,
                "3/2 m r² ψ̇ φ̇ cos θ": gyroscopic,
                "5/4 m r² ψ̇² sin θ cos θ": centrifugal,
                "θ̈": lean_acceleration,
            },
            {
                "m g r sin θ": "N·m",
                "3/2 m r² ψ̇ φ̇ cos θ": "N·m",
                "5/4 m r² ψ̇² sin θ cos θ": "N·m",
                "θ̈": "rad/s²",
            },
        ),
        Step(
            steady_title,
            r"5\sin\theta\cos\theta\,\dot\psi^2 + 6\dot\phi\cos\theta\,\dot\psi + \frac{4g}{r}\sin\theta = 0,"
            r"\qquad R = \left|\frac{r\dot\phi}{\dot\psi}\right|",
            steady_values,
            steady_units,
        ),
        Step(
            "Check: the project's Gibbs–Appell equations, derived from the acceleration energy, at the same states",
            r"\frac{\partial S}{\partial\dot u_\theta} = Q_\theta,\qquad S = \tfrac12 m\,\bar a_G\cdot\bar a_G + "
            r"\tfrac12\dot{\bar\omega}\cdot[I]\dot{\bar\omega} + \dot{\bar\omega}\cdot(\bar\omega\times[I]\bar\omega)",
            check_values,
            check_units,
        ),
    )
    outputs: dict[str, Any] = {
        "lean_acceleration_rad_s2": lean_acceleration,
        "steady_heading_rate_rad_s": steady[0] if steady is not None else None,
        "fast_heading_rate_rad_s": steady[1] if steady is not None and math.isfinite(steady[1]) else None,
        "turn_radius_m": abs(r * spin / steady[0]) if steady is not None and steady[0] != 0.0 else None,
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="rolling-disk-steady-turn",
    title="A leaning rolling disk: Kane's lean equation and the steady turn",
    chapter=9,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "lean_acceleration_rad_s2": "rad/s²",
        "steady_heading_rate_rad_s": "rad/s",
        "fast_heading_rate_rad_s": "rad/s",
        "turn_radius_m": "m",
    },
    section="9.3",
    story=ExampleStory(
        situation=(
            "A uniform disk of mass 1 kg and radius 0.1 m, a small steel wheel, rolls without slipping on a level "
            "floor. At the start it leans $\\theta = 10°$ from the vertical, spins at $\\dot\\phi = 12$ rad/s "
            "about its axle (so its contact point moves at 1.2 m/s) and its heading is not yet turning, "
            "$\\dot\\psi = 0$. Nothing but gravity and the floor acts on it."
        ),
        wanted=(
            "The disk's lean acceleration at that instant, and the heading rate $\\dot\\psi$ it would need to roll "
            "round a circle at a constant lean instead: the steady turn, and the radius of the circle its contact "
            "point then traces."
        ),
        approach=(
            "Rolling is a constraint on velocities, not on positions, so Lagrange's equations in independent "
            "coordinates do not apply without multipliers. Kane's method takes the three angle rates as "
            "generalized speeds with the rolling built in: the centre's velocity is $\\bar\\omega\\times r\\bar "
            "e_3$. Projecting forces and inertia forces on the partial velocities of the lean speed leaves out the "
            "contact force, whose point does not move, and gives one scalar equation for $\\ddot\\theta$. "
            "Newton–Euler would need the three contact force components as unknowns and three more equations to "
            "eliminate them."
        ),
        check=(
            "The project's derivation engine builds the Gibbs–Appell equations of the same disk symbolically, "
            "from its acceleration energy $S$, with no use of this hand derivation. The check evaluates them at the "
            "starting state, where their $\\ddot\\theta$ must equal Kane's, and at the steady heading rate, where "
            "$\\ddot\\theta$ must vanish to rounding: the two methods are the same mechanics written differently."
        ),
        what_if=(
            "Set the **heading rate ψ̇₀** to the steady value the fourth step gives (about $-0.97$ rad/s at the "
            "defaults). The disk in the scene then keeps its lean and rolls round a circle of about 1.2 m instead "
            "of falling over. Then lower the **spin rate φ̇₀**: the circle tightens, and below a few rad/s no "
            "heading rate holds the lean at all, and the disk must fall."
        ),
    ),
)
