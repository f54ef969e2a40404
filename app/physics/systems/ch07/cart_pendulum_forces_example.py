"""Worked example ``cart-pendulum-generalized-forces`` (section 7.4): every force on the pendulum hanging from a sprung,
driven cart, sorted by how it enters Lagrange's equations.

The system is :mod:`app.physics.systems.ch07.pendulum_on_cart` (frame N: x along the rail, z up; the cart, mass M, at
x; the bob, mass m, on a massless rod of length l at θ from the downward vertical), at the scene's starting state
(x₀, θ₀, ẋ₀, θ̇₀) and t = 0, where the drive is ``F₀ cos(Ω·0) = F₀``.

Generalized forces ``Q_j = Σ F·∂r/∂q_j``: the drive gives ``Q_x = F``, ``Q_θ = 0``; gravity and the spring give
``−∂V/∂q_j`` with ``V = ½ k x² − m g l cos θ``; the rod's tension S (along the rod, on the bob towards the cart and
back on the cart) and the rail's push give zero for every value of them. Lagrange's equations then give (ẍ, θ̈)
without S, and the bob's Newton's law gives S afterwards. The check: the engine's Newton–Euler equations for the same
system, which carry the tension and the rail's push as unknowns, give the same accelerations.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.mechanics.engine import derived
from app.physics.systems.ch07.pendulum_on_cart import SYSTEM
from app.physics.systems.ch07.pendulum_on_cart_model import CartPendulumMotion

_STATE = ("x0_m", "theta_0_deg", "x_rate_0_m_s", "theta_rate_0_deg_s")
INPUTS = ParameterSet(
    (*SYSTEM.parameters.parameters, *(CartPendulumMotion.parameters.by_name[name] for name in _STATE))
)


def lagrange_accelerations(inputs: Mapping[str, Any], Q_x: float, Q_theta: float) -> np.ndarray:
    """(ẍ, θ̈) from ``[[M + m, m l cos θ], [m l cos θ, m l²]] q̈ = [Q_x + m l sin θ θ̇², Q_θ]`` (m/s², rad/s²), with
    Q the total generalized forces (spring and gravity included)."""
    M, m, l = float(inputs["cart_mass_kg"]), float(inputs["bob_mass_kg"]), float(inputs["length_m"])
    theta, theta_rate = math.radians(float(inputs["theta_0_deg"])), math.radians(float(inputs["theta_rate_0_deg_s"]))
    mass = np.array([[M + m, m * l * math.cos(theta)], [m * l * math.cos(theta), m * l * l]])
    rhs = np.array([Q_x + m * l * math.sin(theta) * theta_rate**2, Q_theta])
    return np.linalg.solve(mass, rhs)


def solve(inputs: Mapping[str, Any]) -> Solution:
    m, l = float(inputs["bob_mass_kg"]), float(inputs["length_m"])
    k, F0, g = float(inputs["stiffness_N_m"]), float(inputs["force_amplitude_N"]), float(inputs["g_m_s2"])
    x, x_rate = float(inputs["x0_m"]), float(inputs["x_rate_0_m_s"])
    theta, theta_rate = math.radians(float(inputs["theta_0_deg"])), math.radians(float(inputs["theta_rate_0_deg_s"]))
    s, c = math.sin(theta), math.cos(theta)
    # ∂r/∂q of the cart and the bob (m per m, m per rad), in (x, z) components of the plane of motion
    cart_x, cart_theta = np.array([1.0, 0.0]), np.array([0.0, 0.0])
    bob_x, bob_theta = np.array([1.0, 0.0]), np.array([l * c, l * s])
    drive = F0  # F₀ cos(Ω t) at t = 0
    Q_drive = np.array([drive * cart_x[0], drive * cart_theta[0]])
    # gravity and the spring, directly as F·∂r/∂q and as −∂V/∂q
    weight = np.array([0.0, -m * g])
    spring = np.array([0.0 - k * x, 0.0])
    Q_weight = np.array([weight @ bob_x, weight @ bob_theta])
    Q_spring = np.array([spring @ cart_x, spring @ cart_theta])
    minus_dV = np.array([0.0 - k * x, -m * g * l * s])
    # the rod's pull per newton of tension: on the bob towards the cart, on the cart towards the bob
    towards_cart = np.array([-s, c])
    per_tension = np.array([towards_cart @ (bob_x - cart_x), towards_cart @ (bob_theta - cart_theta)])
    rail_up = np.array([0.0, 1.0])
    per_rail = np.array([rail_up @ cart_x, rail_up @ cart_theta])
    Q_total = Q_drive + Q_weight + Q_spring
    x_acc, theta_acc = lagrange_accelerations(inputs, float(Q_total[0]), float(Q_total[1]))
    bob_acc = np.array([x_acc + l * c * theta_acc - l * s * theta_rate**2, l * s * theta_acc + l * c * theta_rate**2])
    tension = float((m * bob_acc - weight) @ towards_cart)
    state = np.array([x, theta, x_rate, theta_rate])
    parameters = np.array(SYSTEM.parameter_array(inputs), dtype=float)
    newton_euler = derived(SYSTEM, "newton-euler").state_derivative(0.0, state, parameters)
    force_scale = max(abs(F0), k * abs(x), m * g, m * l * theta_rate**2, 1e-300)
    steps = (
        Step(
            "How each point moves with each coordinate",
            r"\bar r_{\rm cart} = (x,\ 0),\quad \bar r_{\rm bob} = (x + l\sin\theta,\ -l\cos\theta);\quad "
            r"\frac{\partial\bar r_{\rm bob}}{\partial x} = (1,\ 0),\quad \frac{\partial\bar r_{\rm bob}}{\partial"
            r"\theta} = (l\cos\theta,\ l\sin\theta)",
            {"dr_bob/dx": bob_x, "dr_bob/dtheta": bob_theta, "dr_cart/dx": cart_x},
            {"dr_bob/dx": "m/m", "dr_bob/dtheta": "m/rad", "dr_cart/dx": "m/m"},
        ),
        Step(
            "An applied force: the drive on the cart, F₀ cos Ωt at t = 0",
            r"Q_x^{F} = F\,\bar i\cdot\frac{\partial\bar r_{\rm cart}}{\partial x} = F,\quad Q_\theta^{F} = "
            r"F\,\bar i\cdot\frac{\partial\bar r_{\rm cart}}{\partial\theta} = 0",
            {"F": drive, "Q_x^F": float(Q_drive[0]), "Q_theta^F": float(Q_drive[1])},
            {"F": "N", "Q_x^F": "N", "Q_theta^F": "N·m"},
        ),
        Step(
            "Conservative forces: gravity on the bob and the spring on the cart, directly and through V",
            r"Q_j = \bar F\cdot\frac{\partial\bar r}{\partial q_j} = -\frac{\partial V}{\partial q_j},\quad V = "
            r"\tfrac12 k x^2 - m g l\cos\theta:\quad Q_x = -k x,\quad Q_\theta = -m g l\sin\theta",
            {
                "Q_x^spring": float(Q_spring[0]),
                "Q_theta^gravity": float(Q_weight[1]),
                "-dV/dx": float(minus_dV[0]),
                "-dV/dtheta": float(minus_dV[1]),
            },
            {"Q_x^spring": "N", "Q_theta^gravity": "N·m", "-dV/dx": "N", "-dV/dtheta": "N·m"},
        ),
        Step(
            "Constraint forces: the rod's tension S and the rail's push, per newton of each",
            r"Q_j^{S} = S\,\bar e\cdot\Big(\frac{\partial\bar r_{\rm bob}}{\partial q_j} - \frac{\partial\bar "
            r"r_{\rm cart}}{\partial q_j}\Big) = 0,\quad \bar e = (-\sin\theta,\ \cos\theta);\quad Q_j^{\rm rail} = "
            r"N_{\rm rail}\,\bar k\cdot\frac{\partial\bar r_{\rm cart}}{\partial q_j} = 0",
            {"Q^S/S": per_tension, "Q^rail/N_rail": per_rail},
            {"Q^S/S": "m/m, m/rad", "Q^rail/N_rail": "m/m, m/rad"},
            scales={"Q^S/S": l + 1.0, "Q^rail/N_rail": 1.0},
        ),
        Step(
            "Lagrange's equations with these Q: the accelerations, then the tension from the bob's Newton's law",
            r"\begin{bmatrix} M + m & m l\cos\theta\\ m l\cos\theta & m l^2\end{bmatrix}\begin{bmatrix}\ddot x\\ "
            r"\ddot\theta\end{bmatrix} = \begin{bmatrix} F - k x + m l\dot\theta^2\sin\theta\\ -m g l\sin\theta"
            r"\end{bmatrix},\quad S = (m\,\bar a_{\rm bob} - m\bar g)\cdot\bar e",
            {
                "Q_x": float(Q_total[0]),
                "Q_theta": float(Q_total[1]),
                "xddot": float(x_acc),
                "thetaddot": float(theta_acc),
                "S": tension,
            },
            {"Q_x": "N", "Q_theta": "N·m", "xddot": "m/s²", "thetaddot": "rad/s²", "S": "N"},
        ),
        Step(
            "Check: Newton–Euler, derived by the engine with the tension and the rail's push as unknowns",
            r"\ddot x_{\rm Lagrange} = \ddot x_{\rm Newton\text{-}Euler},\quad \ddot\theta_{\rm Lagrange} = "
            r"\ddot\theta_{\rm Newton\text{-}Euler}",
            {
                "xddot_Lagrange": float(x_acc),
                "xddot_Newton_Euler": float(newton_euler[2]),
                "thetaddot_Lagrange": float(theta_acc),
                "thetaddot_Newton_Euler": float(newton_euler[3]),
            },
            {
                "xddot_Lagrange": "m/s²",
                "xddot_Newton_Euler": "m/s²",
                "thetaddot_Lagrange": "rad/s²",
                "thetaddot_Newton_Euler": "rad/s²",
            },
        ),
    )
    outputs = {
        "Q_x_N": float(Q_total[0]),
        "Q_theta_N_m": float(Q_total[1]),
        "x_acceleration_m_s2": float(x_acc),
        "theta_acceleration_rad_s2": float(theta_acc),
        "rod_tension_N": tension,
    }
    return Solution(
        outputs=outputs,
        steps=steps,
        output_scales={"Q_x_N": force_scale, "Q_theta_N_m": force_scale * l},
    )


EXAMPLE = WorkedExample(
    id="cart-pendulum-generalized-forces",
    title="A pendulum on a sprung, driven cart: which forces enter as generalized forces",
    chapter=7,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "Q_x_N": "N",
        "Q_theta_N_m": "N·m",
        "x_acceleration_m_s2": "m/s²",
        "theta_acceleration_rad_s2": "rad/s²",
        "rod_tension_N": "N",
    },
    section="7.4",
    story=ExampleStory(
        situation=(
            "A cart of mass $M$ runs on a smooth horizontal rail, tied to the wall by a spring of stiffness $k$ "
            "(relaxed at $x = 0$) and pushed along the rail by a force $F_0\\cos\\Omega t$. A bob of mass $m$ hangs "
            "from it on a light rod of length $l$. At the instant $t = 0$ the cart is at $x_0$ and the rod at "
            "$\\theta_0$ from the vertical, moving at $\\dot x_0$ and $\\dot\\theta_0$."
        ),
        wanted=(
            "The generalized forces $Q_x$ and $Q_\\theta$ of every force on the system, sorted into applied, "
            "conservative and constraint forces; then the accelerations $\\ddot x$ and $\\ddot\\theta$ they "
            "produce at that instant, and the rod's tension as an afterthought."
        ),
        approach=(
            "With the coordinates $x$ and $\\theta$ we only need to know how each point moves when one coordinate "
            "changes, $\\partial\\bar r/\\partial q_j$; each force then contributes "
            "$\\bar F\\cdot\\partial\\bar r/\\partial q_j$ to $Q_j$. Gravity and the spring can go in either this "
            "way or through $V$, and we do both. The rod's tension pulls the bob and the cart equally and "
            "oppositely along a rod whose length never changes, so it drops out for any size, and the rail pushes "
            "across the only way the cart moves. Newton–Euler has to carry both as unknowns: four scalar "
            "equations instead of two."
        ),
        check=(
            "The app's derivation engine builds the Newton–Euler equations for the same system on its own, with "
            "the tension and the rail's push as unknowns, and evaluates them at the same state. Its $\\ddot x$ and "
            "$\\ddot\\theta$ must equal ours to round-off. If a constraint force really did work in some "
            "virtual displacement, leaving it out of $Q$ would make the two disagree."
        ),
        what_if=(
            "Raise the scene's **F₀** from 0: only $Q_x$ changes, by exactly $F_0$, and $Q_\\theta$ stays "
            "$-mgl\\sin\\theta_0$, because the drive acts on the cart, which does not move when $\\theta$ "
            "changes. Yet $\\ddot\\theta$ changes too, through the coupling term $ml\\cos\\theta$ of the mass "
            "matrix. Then set **x₀** away from 0 and watch the spring's $-kx_0$ join $Q_x$ while the tension "
            "keeps contributing nothing."
        ),
    ),
)
