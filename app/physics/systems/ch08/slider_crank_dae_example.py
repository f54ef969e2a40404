"""Worked example ``slider-crank-multipliers``: Lagrange's equations with multipliers for the slider-crank.

System, frame and inputs: :mod:`app.physics.systems.ch08.slider_crank_dae` (the lesson 8.1 scene's model), the
slider-crank of lesson 6.3 in absolute coordinates: three bodies, each (x_G, y_G, φ), nine coordinates, eight
constraint rows (pins O, A, B: two rows each; the guide; the slider's angle). At the crank angle
``crank_angle0_deg`` and speed ``crank_speed_rad_s`` (a consistent state by loop closure) under the constant torque
``drive_torque_N_m``, the equations ``M v̇ = f + Cᵀλ`` with the constraints differentiated twice, ``C v̇ = c``,
are one linear system of 9 + 8 unknowns: the accelerations and the multipliers.

Check: chapter 6's Newton–Euler (one coordinate θ, the eight pin and guide forces as unknowns,
:func:`~app.physics.systems.ch06.mechanism_kinetics.newton_euler`) must give the same crank acceleration and the
same forces: each multiplier is, by the joint's definition, the force the chapter-6 free-body diagram names.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch06.mechanism_kinetics import newton_euler
from app.physics.systems.ch08.slider_crank_dae import (
    INDEPENDENT,
    PARAMETERS,
    chapter6_links,
    slider_crank_initial_state,
    slider_crank_linkage,
)


def _check(values: Mapping[str, Any]) -> None:
    """The scene model's check, its refusal named as the rod's length (so the API answers 422, not 500)."""
    try:
        chapter6_links(values)
    except ValueError as exc:
        raise ParameterError("rod_m", str(exc)) from None


INPUTS = ParameterSet(PARAMETERS.parameters, check=_check)


def solve(inputs: Mapping[str, Any]) -> Solution:
    linkage = slider_crank_linkage(inputs)
    system = linkage.system(independent=INDEPENDENT)
    q, v = slider_crank_initial_state(inputs)
    mass, forces = system.mass_and_forces(0.0, q, v)
    residual, jacobian, convective = system.constraint_terms(q, v)
    n, m = system.n_coordinates, system.n_constraints
    augmented = np.block([[mass, -jacobian.T], [jacobian, np.zeros((m, m))]])
    solution = np.linalg.solve(augmented, np.concatenate([forces, convective]))
    acceleration, multipliers = solution[:n], solution[n:]
    rows = linkage.multiplier_rows()
    lam = {name: multipliers[rows[name]] for name in rows}

    links = chapter6_links(inputs)
    theta, omega = math.radians(inputs["crank_angle0_deg"]), float(inputs["crank_speed_rad_s"])
    chapter6 = newton_euler(
        links, np.array([theta]), np.array([omega]), drive_torque_N_m=np.array([float(inputs["drive_torque_N_m"])])
    )
    r, l = links.mechanism.crank_m, links.mechanism.rod_m
    total_mass = links.crank_mass_kg + links.rod_mass_kg + links.slider_mass_kg
    force_scale = total_mass * (links.g_m_s2 + r * omega**2 * (1 + r / l)) + abs(inputs["drive_torque_N_m"]) / r
    length_scale = r + l
    alpha_scale = force_scale * r / (linkage.mass_diagonal[2] + links.rod_mass_kg * r * r)

    names = ("crank", "rod", "slider")
    steps = (
        Step(
            "Nine absolute coordinates, made consistent by loop closure",
            r"\bar q = (x_1, y_1, \phi_1,\ x_2, y_2, \phi_2,\ x_3, y_3, \phi_3),\quad \phi_1 = \theta,\ \dot\phi_1 = "
            r"\omega;\quad \max|g(\bar q)|,\ \max|C\bar v| \approx 0",
            {
                **{f"q_{name}": q[3 * i : 3 * i + 3] for i, name in enumerate(names)},
                **{f"v_{name}": v[3 * i : 3 * i + 3] for i, name in enumerate(names)},
                "max_g": float(np.max(np.abs(residual))),
                "max_Cv": float(np.max(np.abs(jacobian @ v))),
            },
            {
                **{f"q_{name}": "m, m, rad" for name in names},
                **{f"v_{name}": "m/s, m/s, rad/s" for name in names},
                "max_g": "m",
                "max_Cv": "m/s",
            },
            scales={"max_g": length_scale, "max_Cv": length_scale * max(abs(omega), 1.0)},
        ),
        Step(
            "Constraint rows: two per pin, one for the guide, one for the slider's angle",
            r"O:\ \bar r_1(-\tfrac r2) = 0,\quad A:\ \bar r_2(-\tfrac l2) - \bar r_1(\tfrac r2) = 0,\quad B:\ \bar r_3 "
            r"- \bar r_2(\tfrac l2) = 0,\quad y_3 - e = 0,\quad \phi_3 = 0;\qquad C = \frac{\partial g}{\partial "
            r"\bar q}\ (8\times 9),\quad c = -\dot C\bar v",
            {
                "rows": m,
                "coordinates": n,
                "rank_C": int(np.linalg.matrix_rank(jacobian)),
                "degrees_of_freedom": n - m,
                "c": convective,
            },
            {"rows": "", "coordinates": "", "rank_C": "", "degrees_of_freedom": "", "c": "m/s², rad/s²"},
        ),
        Step(
            "Mass matrix and applied forces (gravity on each body, the torque on the crank)",
            r"M = \operatorname{diag}(m_k, m_k, I_{G,k}),\quad "
            r"\bar f = (0, -m_1 g, \tau,\ 0, -m_2 g, 0,\ 0, -m_3 g, 0)",
            {"diag_M": np.diag(mass), "f": forces},
            {"diag_M": "kg, kg, kg·m²", "f": "N, N, N·m"},
        ),
        Step(
            "Lagrange's equations with multipliers and the twice-differentiated constraints: one 17 × 17 solve",
            r"\begin{bmatrix} M & -C^{\mathsf T}\\ C & 0\end{bmatrix}\begin{bmatrix}\dot{\bar v}\\ \bar\lambda"
            r"\end{bmatrix} = \begin{bmatrix}\bar f\\ c\end{bmatrix}",
            {
                "theta_ddot": float(acceleration[2]),
                "phi_rod_ddot": float(acceleration[5]),
                "x_B_ddot": float(acceleration[6]),
                "a_G_rod": acceleration[3:5],
            },
            {"theta_ddot": "rad/s²", "phi_rod_ddot": "rad/s²", "x_B_ddot": "m/s²", "a_G_rod": "m/s²"},
            scales={"theta_ddot": alpha_scale, "phi_rod_ddot": alpha_scale},
        ),
        Step(
            "The multipliers are the joint forces",
            r"\bar\lambda_O = \text{ground on crank},\ \bar\lambda_A = \text{crank on rod},\ \bar\lambda_B = "
            r"\text{rod on slider},\ \lambda_{\rm guide} = N,\ \lambda_\phi = \text{guide's moment on the slider}",
            {
                "lambda_O": lam["O"],
                "lambda_A": lam["A"],
                "lambda_B": lam["B"],
                "lambda_guide": float(lam["guide"][0]),
                "lambda_phi": float(lam["slider angle"][0]),
            },
            {"lambda_O": "N", "lambda_A": "N", "lambda_B": "N", "lambda_guide": "N", "lambda_phi": "N·m"},
            scales={
                "lambda_O": force_scale,
                "lambda_A": force_scale,
                "lambda_B": force_scale,
                "lambda_guide": force_scale,
                "lambda_phi": force_scale * r,
            },
        ),
        Step(
            "Check: chapter 6's Newton–Euler in the one coordinate θ gives the same α and forces",
            r"\text{8 equations in } (\bar O, \bar A, \bar B, N, \alpha) \text{ with } \tau \text{ given}:\quad "
            r"\alpha = \ddot\theta,\ \bar O = \bar\lambda_O,\ \bar A = \bar\lambda_A,\ \bar B = \bar\lambda_B,\ "
            r"N = \lambda_{\rm guide}",
            {
                "alpha_ch6": float(chapter6.crank_acceleration_rad_s2[0]),
                "O_ch6": chapter6.pivot_O_N[0],
                "A_ch6": chapter6.crank_pin_A_N[0],
                "B_ch6": chapter6.wrist_pin_B_N[0],
                "N_ch6": float(chapter6.guide_force_N[0]),
            },
            {"alpha_ch6": "rad/s²", "O_ch6": "N", "A_ch6": "N", "B_ch6": "N", "N_ch6": "N"},
            scales={
                "alpha_ch6": alpha_scale,
                "O_ch6": force_scale,
                "A_ch6": force_scale,
                "B_ch6": force_scale,
                "N_ch6": force_scale,
            },
        ),
    )
    outputs = {
        "crank_acceleration_rad_s2": float(acceleration[2]),
        "slider_acceleration_m_s2": float(acceleration[6]),
        "pin_O_N": lam["O"],
        "pin_A_N": lam["A"],
        "pin_B_N": lam["B"],
        "guide_force_N": float(lam["guide"][0]),
        "slider_moment_N_m": float(lam["slider angle"][0]),
    }
    return Solution(
        outputs=outputs,
        steps=steps,
        output_scales={
            "crank_acceleration_rad_s2": alpha_scale,
            "slider_acceleration_m_s2": alpha_scale * length_scale,
            "pin_O_N": force_scale,
            "pin_A_N": force_scale,
            "pin_B_N": force_scale,
            "guide_force_N": force_scale,
            "slider_moment_N_m": force_scale * r,
        },
    )


EXAMPLE = WorkedExample(
    id="slider-crank-multipliers",
    title="The slider-crank in nine coordinates: accelerations and multipliers from one linear solve",
    chapter=8,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "crank_acceleration_rad_s2": "rad/s²",
        "slider_acceleration_m_s2": "m/s²",
        "pin_O_N": "N",
        "pin_A_N": "N",
        "pin_B_N": "N",
        "guide_force_N": "N",
        "slider_moment_N_m": "N·m",
    },
    section="8.1",
    story=ExampleStory(
        situation=(
            "This is lesson 6.3's slider-crank: a 0.3 m, 1 kg crank, a 1 m, 2 kg connecting rod and a 3 kg slider "
            "in a vertical plane. A constant torque of 2 N·m drives the crank. At this instant the crank is at "
            "$\\theta = 0°$ and turns at 10 rad/s. This time every body gets its own three coordinates $(x_G, "
            "y_G, \\phi)$, nine in all, and every joint is written as its own constraint equations."
        ),
        wanted=(
            "The crank's angular acceleration and the slider's acceleration at this instant, and the eight "
            "Lagrange multipliers: what they are physically and how large they are."
        ),
        approach=(
            "In absolute coordinates the mass matrix is constant and diagonal, and each joint contributes a small, "
            "standard set of rows to the constraint Jacobian $C$. No loop-closure solution is needed to set up the "
            "equations. Lagrange's equations gain the term $C^{\\mathsf T}\\bar\\lambda$, and we add the "
            "constraints differentiated twice, $C\\dot{\\bar v} = c$. That gives 17 linear equations for 9 "
            "accelerations and 8 multipliers, all solved at once. One generalized coordinate ($\\theta$, "
            "chapter 7) would give a single equation instead, but it needs the mechanism's own kinematic "
            "coefficients and yields no joint forces; here the multipliers *are* the joint forces."
        ),
        check=(
            "Chapter 6 solved the same mechanism with one coordinate and eight unknown forces, by free-body "
            "diagrams (lesson 6.3). Each joint's multiplier is defined as the force that diagram names: "
            "$\\bar\\lambda_A$ is the crank's force on the rod, $\\lambda_{\\rm guide}$ is the guide force $N$. "
            "So the last step's chapter-6 numbers must equal the multipliers and $\\ddot\\theta$ to round-off. "
            "The slider's moment multiplier is zero because every force on the slider acts at its centre."
        ),
        what_if=(
            "Set the **torque τ** to 0 and move **θ(0)** around the turn. The multipliers change size and "
            "direction with the crank angle, just as the arrows at the pins do in the scene. Then raise the "
            "**crank speed**: the inertial part of the pin forces grows like $\\omega^2$, while the first step's "
            "constraint residuals stay at round-off, because the start is built on the constraints by loop closure."
        ),
    ),
)
