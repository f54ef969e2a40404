"""Worked example ``sliding-ladder-release``: the ladder of lesson 6.2 at the instant it is let go.

The system and its inputs are :mod:`app.physics.systems.ch06.sliding_ladder` (the scene's model): a uniform bar of
length L and mass m, top end A on the wall x = 0, bottom end B on the floor z = 0, at the angle θ₀ from the floor,
released from rest, with Coulomb coefficients μ_w (wall) and μ_f (floor). +Z is up; θ̈ > 0 turns the bar up.

At rest the ends cannot yet move, so the contacts are about to slide (A down the wall, B away from it) unless
friction holds the ladder: ``μ_f ≥ 1/(2 tan θ₀ + μ_w)``. Sliding, the unknowns are θ̈ and the two normal forces,
with the friction forces at their limits: three linear Newton–Euler equations. Held, the statics alone is
indeterminate; as the scene's model does, each friction force is taken to use the same share of its limit.

Check: at rest the body point at the instantaneous centre I = (L cos θ, L sin θ) (where the normals at A and B
cross) has no acceleration, so the moments about I give θ̈ alone; the normal forces pass through I.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import ParameterError
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch06.sliding_ladder import PARAMETERS

#: The ``held`` output, in words (a verdict the page shows as it is).
HELD, SLIDES = "friction holds it", "it slides"


INPUTS = PARAMETERS


def _ccw(r: np.ndarray, f: np.ndarray) -> float:
    """Moment (N·m) of the force f at the arm r, both (x, z): positive from +x towards +z."""
    return float(r[0] * f[1] - r[1] * f[0])


def solve(inputs: Mapping[str, Any]) -> Solution:
    length, m, g = inputs["length_m"], inputs["mass_kg"], inputs["g_m_s2"]
    mu_w, mu_f = inputs["mu_wall"], inputs["mu_floor"]
    theta = math.radians(inputs["angle0_deg"])
    s, c, half = math.sin(theta), math.cos(theta), 0.5 * length
    inertia = m * length**2 / 12.0
    mu_f_hold = 1.0 / (2.0 * math.tan(theta) + mu_w)
    held = mu_f > 0.0 and mu_f >= mu_f_hold

    steps = [
        Step(
            "Geometry, inertia and the two contact constraints (at rest)",
            r"x_A = 0,\ z_B = 0:\quad \ddot x_G = -\tfrac L2\sin\theta\,\ddot\theta,\quad \ddot z_G = \tfrac L2"
            r"\cos\theta\,\ddot\theta\quad(\dot\theta = 0),\qquad I_G = \tfrac1{12} m L^2",
            {"theta_0": inputs["angle0_deg"], "x_G": half * c, "z_G": half * s, "I_G": inertia},
            {"theta_0": "deg", "x_G": "m", "z_G": "m", "I_G": "kg·m²"},
        ),
        Step(
            "Does friction hold it? (statics at the limit of both friction forces)",
            r"\text{held if } \mu_f \ge \mu_{f,\rm hold} = \frac{1}{2\tan\theta_0 + \mu_w}",
            {"mu_w": mu_w, "mu_f": mu_f, "mu_f_hold": mu_f_hold},
            {"mu_w": "", "mu_f": "", "mu_f_hold": ""},
        ),
    ]
    if held:
        # s_mob² μw μf + 2 s_mob μf tan θ − 1 = 0: the share of each friction limit in use (0 < s_mob ≤ 1).
        a, b = mu_w * mu_f, 2.0 * mu_f * s / c
        share = 1.0 / b if a == 0.0 else 2.0 / (b + math.sqrt(b * b + 4.0 * a))
        normal_floor = m * g / (1.0 + share * share * a)
        normal_wall = share * mu_f * normal_floor
        friction_wall, friction_floor = share * mu_w * normal_wall, -normal_wall
        alpha = 0.0
        steps.append(
            Step(
                "Held: statics, each friction force using the same share s of its limit",
                r"N_A = |F_B| = s\,\mu_f N_B,\quad N_B + s\,\mu_w N_A = m g,\quad "
                r"s^2\mu_w\mu_f + 2 s\,\mu_f\tan\theta_0 - 1 = 0,\quad \ddot\theta = 0",
                {"s": share, "N_A": normal_wall, "N_B": normal_floor, "F_A": friction_wall, "F_B": friction_floor},
                {"s": "", "N_A": "N", "N_B": "N", "F_A": "N", "F_B": "N"},
            )
        )
    else:
        # Unknowns u = [θ̈, N_A, N_B]; rows: x force, z force, moment about G (θ̈ > 0 turns the bar up).
        K = np.array(
            [
                [m * half * s, 1.0, -mu_f],
                [m * half * c, -mu_w, -1.0],
                [inertia, -half * (s + mu_w * c), -half * (mu_f * s - c)],
            ]
        )
        rhs = np.array([0.0, -m * g, 0.0])
        alpha, normal_wall, normal_floor = (float(v) for v in np.linalg.solve(K, rhs))
        friction_wall, friction_floor = mu_w * normal_wall, -mu_f * normal_floor
        if not (alpha <= 1e-12 * g / length and normal_wall >= 0.0 and normal_floor > 0.0):
            raise ParameterError(
                "mu_floor",
                f"no sliding start with both contacts pressing: θ̈ = {alpha:.4g} rad/s², N_A = {normal_wall:.4g} N, "
                f"N_B = {normal_floor:.4g} N",
            )
        steps.append(
            Step(
                "Sliding: Newton–Euler, friction at its limit against the ends' motion",
                r"m\ddot x_G = N_A - \mu_f N_B,\quad m\ddot z_G = N_B + \mu_w N_A - m g,\quad I_G\ddot\theta = "
                r"\tfrac L2\big[(\sin\theta + \mu_w\cos\theta) N_A + (\mu_f\sin\theta - \cos\theta) N_B\big]",
                {"theta_ddot": alpha, "N_A": normal_wall, "N_B": normal_floor},
                {"theta_ddot": "rad/s²", "N_A": "N", "N_B": "N"},
            )
        )
    steps.append(
        Step(
            "Friction forces and the accelerations of G and of the ends",
            r"F_A = \mu_w N_A\,(\uparrow),\ F_B = -\mu_f N_B\,(\text{towards the wall}),\quad "
            r"\ddot z_A = L\cos\theta\,\ddot\theta,\ \ddot x_B = -L\sin\theta\,\ddot\theta",
            {
                "F_A": friction_wall,
                "F_B": friction_floor,
                "a_G": np.array([-half * s * alpha, 0.0, half * c * alpha]),
                "a_A": length * c * alpha,
                "a_B": -length * s * alpha,
            },
            {"F_A": "N", "F_B": "N", "a_G": "m/s²", "a_A": "m/s²", "a_B": "m/s²"},
        )
    )
    # Check: moments about the instantaneous centre I, whose body point has no acceleration at rest.
    centre_i = np.array([length * c, length * s])
    moment = (
        _ccw(np.array([0.0, length * s]) - centre_i, np.array([normal_wall, friction_wall]))
        + _ccw(np.array([length * c, 0.0]) - centre_i, np.array([friction_floor, normal_floor]))
        + _ccw(np.array([half * c, half * s]) - centre_i, np.array([0.0, -m * g]))
    )
    inertia_i = inertia + m * half**2
    alpha_i = -moment / inertia_i  # θ̈ > 0 is clockwise in (x, z)
    steps.append(
        Step(
            "Check: moments about the instantaneous centre I give θ̈ alone",
            r"I_I = I_G + m\big(\tfrac L2\big)^2 = \tfrac13 m L^2,\quad I_I\,\ddot\theta = -\sum M_I"
            r"\ \ (\text{weight and friction; } N_A, N_B \text{ pass through } I)"
            r",\qquad \mu = 0:\ \ddot\theta = -\frac{3g}{2L}\cos\theta_0",
            {
                "I_I": inertia_i,
                "theta_ddot_about_I": alpha_i,
                "theta_ddot_Newton_Euler": alpha,
                "theta_ddot_smooth": -1.5 * g * c / length,
            },
            {
                "I_I": "kg·m²",
                "theta_ddot_about_I": "rad/s²",
                "theta_ddot_Newton_Euler": "rad/s²",
                "theta_ddot_smooth": "rad/s²",
            },
            scales={"theta_ddot_about_I": g / length, "theta_ddot_Newton_Euler": g / length},
        )
    )
    outputs = {
        "angular_acceleration_rad_s2": alpha,
        "wall_force_N": normal_wall,
        "floor_force_N": normal_floor,
        "wall_friction_N": friction_wall,
        "floor_friction_N": friction_floor,
        "mu_floor_to_hold": mu_f_hold,
        "held": HELD if held else SLIDES,
    }
    return Solution(
        outputs=outputs,
        steps=tuple(steps),
        output_scales={"angular_acceleration_rad_s2": g / length, **{k: m * g for k in outputs if k.endswith("_N")}},
    )


EXAMPLE = WorkedExample(
    id="sliding-ladder-release",
    title="The ladder let go: angular acceleration and contact forces at the first instant",
    chapter=6,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "angular_acceleration_rad_s2": "rad/s²",
        "wall_force_N": "N",
        "floor_force_N": "N",
        "wall_friction_N": "N",
        "floor_friction_N": "N",
        "mu_floor_to_hold": "",
        "held": "",
    },
    section="6.2",
    story=ExampleStory(
        situation=(
            "A uniform 4 m ladder of mass 10 kg leans at 60° from the floor, its top end on a wall and its "
            "bottom end on the floor, and is let go from rest. The wall and floor may be rough, with Coulomb "
            "coefficients $\\mu_w$ and $\\mu_f$ (both 0 at first). Length, mass, angle, both coefficients and "
            "$g$ are the scene's controls."
        ),
        wanted=(
            "Whether friction can hold the ladder at all; if it cannot, the angular acceleration $\\ddot\\theta$ "
            "at the instant of release and the four contact forces (two normal forces and two friction forces) "
            "that act on it at that instant."
        ),
        approach=(
            "This is planar Newton–Euler for one body: two force equations for the centre of mass and one moment "
            "equation about it. The two contacts are constraints, and at rest they tie both components of "
            "$\\bar a_G$ to $\\ddot\\theta$, so the unknowns are just $\\ddot\\theta$, $N_A$ and $N_B$ with "
            "friction at its limit. That makes three linear equations. We keep $\\theta$ as the only coordinate and "
            "let the constraints supply the rest. A Lagrange approach would give $\\ddot\\theta$ faster without "
            "friction, but it drops the contact forces, and those are exactly what friction and the question "
            "of leaving the wall depend on."
        ),
        check=(
            "At rest the point where the normals at A and B cross, the instantaneous centre $I$, has zero "
            "acceleration. So moments about $I$ alone give $\\ddot\\theta$, with $I_I = mL^2/3$, and both normal "
            "forces drop out because they pass through $I$. The last step computes $\\ddot\\theta$ this second way "
            "beside the Newton–Euler value. It also shows the smooth-contact closed form $-\\tfrac{3g}{2L}\\cos"
            "\\theta_0$, which equals both when $\\mu_w = \\mu_f = 0$."
        ),
        what_if=(
            "Raise the **floor's friction coefficient $\\mu_f$** slowly from 0. The wall force eases a little and "
            "$|\\ddot\\theta|$ falls towards zero as $\\mu_f$ approaches $\\mu_{f,\\rm hold} = 1/(2\\tan\\theta_0 "
            "+ \\mu_w)$ (0.289 at 60° with a smooth wall). Past that value the steps switch to statics and the "
            "scene's ladder stays put. Try it at a lower **θ₀** too: a flatter ladder needs more friction to stand."
        ),
    ),
)
