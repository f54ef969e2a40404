"""Worked example ``double-pendulum-lagrange`` (section 7.5): Lagrange's equations of the double pendulum written by
hand and evaluated at the scene's starting state.

The system is :mod:`app.physics.systems.ch07.double_pendulum` (frame N: x horizontal in the plane, z up, pivot O at
the origin; θ₁, θ₂ the rods' angles from the downward vertical; point bobs m₁, m₂ on massless rods l₁, l₂). With
``Δ = θ₁ − θ₂``:

* ``T = ½(m₁ + m₂) l₁² θ̇₁² + ½ m₂ l₂² θ̇₂² + m₂ l₁ l₂ cos Δ θ̇₁ θ̇₂``, ``V = −(m₁ + m₂) g l₁ cos θ₁ − m₂ g l₂ cos θ₂``;
* θ₁: ``(m₁ + m₂) l₁² θ̈₁ + m₂ l₁ l₂ cos Δ θ̈₂ + m₂ l₁ l₂ sin Δ θ̇₂² + (m₁ + m₂) g l₁ sin θ₁ = 0``;
* θ₂: ``m₂ l₂² θ̈₂ + m₂ l₁ l₂ cos Δ θ̈₁ − m₂ l₁ l₂ sin Δ θ̇₁² + m₂ g l₂ sin θ₂ = 0``.

The check: the engine's Newton–Euler equations (rod tensions and the plane's pushes as unknowns) give the same
accelerations, and with them the energy's rate ``dE/dt = θ̇ᵀ(M θ̈ + ½ Ṁ θ̇) + ∂V/∂θ·θ̇`` is zero.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.mechanics.engine import derived
from app.physics.systems.ch07.double_pendulum import SYSTEM
from app.physics.systems.ch07.double_pendulum_model import DoublePendulumMotion

_STATE = ("theta1_0_deg", "theta2_0_deg", "theta1_rate_0_deg_s", "theta2_rate_0_deg_s")
INPUTS = ParameterSet(
    (*SYSTEM.parameters.parameters, *(DoublePendulumMotion.parameters.by_name[name] for name in _STATE))
)


def state_of(inputs: Mapping[str, Any]) -> np.ndarray:
    """(θ₁, θ₂, θ̇₁, θ̇₂) in rad and rad/s."""
    return np.radians([float(inputs[name]) for name in _STATE])


def mass_matrix_and_forcing(inputs: Mapping[str, Any]) -> tuple[np.ndarray, np.ndarray]:
    """M (kg·m², (2, 2)) and f (N·m, (2,)) with ``M θ̈ = f`` from the two Lagrange equations."""
    m1, m2, l1, l2, g = (float(inputs[n]) for n in ("m1_kg", "m2_kg", "l1_m", "l2_m", "g_m_s2"))
    t1, t2, w1, w2 = state_of(inputs)
    delta = t1 - t2
    coupling = m2 * l1 * l2 * math.cos(delta)
    mass = np.array([[(m1 + m2) * l1 * l1, coupling], [coupling, m2 * l2 * l2]])
    forcing = np.array(
        [
            -m2 * l1 * l2 * math.sin(delta) * w2 * w2 - (m1 + m2) * g * l1 * math.sin(t1),
            m2 * l1 * l2 * math.sin(delta) * w1 * w1 - m2 * g * l2 * math.sin(t2),
        ]
    )
    return mass, forcing


def solve(inputs: Mapping[str, Any]) -> Solution:
    m1, m2, l1, l2, g = (float(inputs[n]) for n in ("m1_kg", "m2_kg", "l1_m", "l2_m", "g_m_s2"))
    state = state_of(inputs)
    t1, t2, w1, w2 = state
    delta = t1 - t2
    mass, forcing = mass_matrix_and_forcing(inputs)
    acc = np.linalg.solve(mass, forcing)
    rates = np.array([w1, w2])
    kinetic = 0.5 * float(rates @ mass @ rates)
    potential = -(m1 + m2) * g * l1 * math.cos(t1) - m2 * g * l2 * math.cos(t2)
    # dE/dt = θ̇ᵀ M θ̈ + ½ θ̇ᵀ Ṁ θ̇ + ∂V/∂θ · θ̇, Ṁ's off-diagonal −m₂ l₁ l₂ sin Δ (θ̇₁ − θ̇₂)
    mass_rate = -m2 * l1 * l2 * math.sin(delta) * (w1 - w2)
    dV = np.array([(m1 + m2) * g * l1 * math.sin(t1), m2 * g * l2 * math.sin(t2)])
    energy_rate = float(rates @ mass @ acc + mass_rate * w1 * w2 + dV @ rates)
    parameters = np.array(SYSTEM.parameter_array(inputs), dtype=float)
    newton_euler = derived(SYSTEM, "newton-euler").state_derivative(0.0, state, parameters)
    power_scale = float(np.abs(rates) @ (np.abs(mass @ acc) + np.abs(dV))) + abs(mass_rate * w1 * w2)
    steps = (
        Step(
            "Kinetic and potential energy in θ₁, θ₂ (bobs at l₁ and l₁ + l₂ along the rods)",
            r"T = \tfrac12(m_1 + m_2) l_1^2\dot\theta_1^2 + \tfrac12 m_2 l_2^2\dot\theta_2^2 + m_2 l_1 l_2"
            r"\cos(\theta_1 - \theta_2)\,\dot\theta_1\dot\theta_2,\quad V = -(m_1 + m_2) g l_1\cos\theta_1 - m_2 g l_2"
            r"\cos\theta_2",
            {"T": kinetic, "V": potential},
            {"T": "J", "V": "J"},
        ),
        Step(
            "Lagrange's equation for θ₁",
            r"\frac{d}{dt}\frac{\partial L}{\partial\dot\theta_1} - \frac{\partial L}{\partial\theta_1} = (m_1 + m_2)"
            r" l_1^2\ddot\theta_1 + m_2 l_1 l_2\cos\Delta\,\ddot\theta_2 + m_2 l_1 l_2\sin\Delta\,\dot\theta_2^2 + "
            r"(m_1 + m_2) g l_1\sin\theta_1 = 0,\quad \Delta = \theta_1 - \theta_2",
            {"M_11": float(mass[0, 0]), "M_12": float(mass[0, 1]), "f_1": float(forcing[0])},
            {"M_11": "kg·m²", "M_12": "kg·m²", "f_1": "N·m"},
        ),
        Step(
            "Lagrange's equation for θ₂",
            r"\frac{d}{dt}\frac{\partial L}{\partial\dot\theta_2} - \frac{\partial L}{\partial\theta_2} = m_2 l_2^2"
            r"\ddot\theta_2 + m_2 l_1 l_2\cos\Delta\,\ddot\theta_1 - m_2 l_1 l_2\sin\Delta\,\dot\theta_1^2 + m_2 g l_2"
            r"\sin\theta_2 = 0",
            {"M_21": float(mass[1, 0]), "M_22": float(mass[1, 1]), "f_2": float(forcing[1])},
            {"M_21": "kg·m²", "M_22": "kg·m²", "f_2": "N·m"},
        ),
        Step(
            "Solve the two equations for the angular accelerations",
            r"\begin{bmatrix}\ddot\theta_1\\ \ddot\theta_2\end{bmatrix} = M^{-1}\begin{bmatrix} f_1\\ f_2"
            r"\end{bmatrix},\quad \det M = m_2 l_1^2 l_2^2\,(m_1 + m_2\sin^2\Delta)",
            {"det_M": float(np.linalg.det(mass)), "thetaddot_1": float(acc[0]), "thetaddot_2": float(acc[1])},
            {"det_M": "kg²·m⁴", "thetaddot_1": "rad/s²", "thetaddot_2": "rad/s²"},
        ),
        Step(
            "Check: the engine's Newton–Euler equations agree, and the energy does not change",
            r"\ddot\theta_{\rm Lagrange} = \ddot\theta_{\rm Newton\text{-}Euler},\quad \frac{dE}{dt} = "
            r"\dot\theta^{\mathsf T}\big(M\ddot\theta + \tfrac12\dot M\dot\theta\big) + \frac{\partial V}{\partial"
            r"\theta}\cdot\dot\theta = 0",
            {
                "thetaddot_Lagrange": acc,
                "thetaddot_Newton_Euler": np.asarray(newton_euler[2:4], dtype=float),
                "dE/dt": energy_rate,
            },
            {"thetaddot_Lagrange": "rad/s²", "thetaddot_Newton_Euler": "rad/s²", "dE/dt": "W"},
            scales={"dE/dt": max(power_scale, 1e-300)},
        ),
    )
    outputs = {
        "theta1_acceleration_rad_s2": float(acc[0]),
        "theta2_acceleration_rad_s2": float(acc[1]),
        "kinetic_energy_J": kinetic,
        "potential_energy_J": potential,
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="double-pendulum-lagrange",
    title="The double pendulum by Lagrange's equations: from T and V to the angular accelerations",
    chapter=7,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "theta1_acceleration_rad_s2": "rad/s²",
        "theta2_acceleration_rad_s2": "rad/s²",
        "kinetic_energy_J": "J",
        "potential_energy_J": "J",
    },
    section="7.5",
    story=ExampleStory(
        situation=(
            "A double pendulum swings in a vertical plane: a bob $m_1$ on a light rod $l_1$ from a fixed pivot, a "
            "second bob $m_2$ on a light rod $l_2$ from the first. The scene releases it from the angles "
            "$\\theta_{10}$, $\\theta_{20}$ (from the downward vertical) with the rates "
            "$\\dot\\theta_{10}$, $\\dot\\theta_{20}$."
        ),
        wanted=(
            "Lagrange's two equations of motion in $\\theta_1$ and $\\theta_2$, and the angular accelerations "
            "$\\ddot\\theta_1$, $\\ddot\\theta_2$ they give at the starting state, together with the kinetic and "
            "potential energy there."
        ),
        approach=(
            "The two angles fix the pendulum and already satisfy the rods' and the plane's constraints, so "
            "Lagrange's method needs nothing but $T$ and $V$ written in them. The rod tensions do no virtual work "
            "and never appear. Differentiating $L = T - V$ gives two equations, linear in the accelerations with "
            "the mass matrix $M$; we solve that $2\\times2$ system. Newton's way would cut the bobs free and carry "
            "both tensions as unknowns, four equations instead of two, and the velocity-dependent terms would "
            "come from relative acceleration formulas instead of from differentiation."
        ),
        check=(
            "The app's engine derives the Newton–Euler equations for the same pendulum independently (tensions "
            "and the plane's pushes kept as unknowns), and the check step evaluates them at the same state: both "
            "accelerations must agree to round-off. Then the energy's rate of change, built from our "
            "accelerations, must be zero, because no force that does work is missing from $V$."
        ),
        what_if=(
            "Move **θ₂₀** away from **θ₁₀** in the scene. With both rods in line ($\\Delta = 0$) the coupling "
            "$M_{12}$ is largest and the upper bob drags the lower one along; as $\\Delta$ grows, $M_{12}$ shrinks "
            "like $\\cos\\Delta$ and changes sign past 90°. Give the upper rod a rate **θ̇₁₀**: the term "
            "$m_2 l_1 l_2\\sin\\Delta\\,\\dot\\theta_1^2$ flings the lower bob outward, and the scene shows it whip."
        ),
    ),
)
