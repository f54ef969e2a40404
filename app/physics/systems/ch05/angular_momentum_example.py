"""Worked example ``skewed-plate-momentum``: linear momentum, angular momentum about G and about a fixed point, and
kinetic energy of a body spun on a shaft that is not a principal axis.

The system, frame and names are those of :mod:`app.physics.systems.ch05.angular_momentum` (the shaft is the world Z
axis through G, the body turned by ``tilt`` about its own x axis, ω = Ω Z), and the inputs are that scene's
parameters, so the lesson's controls drive the example. In the ``particles`` view the shaft (with G) travels at the
constant velocity v_G from r_G(0); in the ``rigid body`` view G stays at the origin, as in the scene. The instant solved
is t = 0. Vectors are world [X, Y, Z] components (kg·m/s, kg·m²/s); the tensor is in kg·m².

Every in-range combination is a possible motion, so nothing is refused beyond the ranges; without spin (Ω = 0) the
angle between ω and H_G has no meaning and is given as None.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch05.angular_momentum import PARAMETERS, ShaftSpin

INPUTS = PARAMETERS


def solve(inputs: Mapping[str, Any]) -> Solution:
    motion = ShaftSpin.from_params(inputs)
    body = motion.body
    state = motion.at(np.zeros(1))
    mass, spin = body.mass_kg, motion.spin_rate_rad_s
    omega = motion.omega_rad_s
    tensor_body = body.inertia_body_kg_m2
    tensor_world = body.inertia_world0_kg_m2
    h_g = tensor_world @ omega
    r_g, v_g = state.centre_m[0], state.centre_velocity_m_s
    p = mass * v_g
    h_o = h_g + np.cross(r_g, p)
    t_centre = 0.5 * mass * float(v_g @ v_g)
    t_about = 0.5 * float(omega @ h_g)
    angle = None if spin == 0.0 else math.degrees(math.atan2(float(np.linalg.norm(np.cross(omega, h_g))), omega @ h_g))
    # The same sums over point masses that stand in for the body (same mass, centre and centroidal tensor).
    particles = motion.particles_at(state)
    p_particles = particles.linear_momentum()[0]
    h_o_particles = particles.angular_momentum(np.zeros(3))[0]
    t_particles = float(particles.kinetic_energy()[0])
    h_scale = float(np.linalg.norm(h_g)) + float(np.linalg.norm(r_g) * np.linalg.norm(p))
    steps = (
        Step(
            f"Inertia of the {body.shape} about G on its own axes",
            r"[I_G]_{xyz} = \mathrm{diag}(I_{xx},\ I_{yy},\ I_{zz})"
            + (
                r"\quad(\text{plate: } \tfrac{m}{12}b^2,\ \tfrac{m}{12}a^2,\ \tfrac{m}{12}(a^2+b^2))"
                if body.shape == "plate"
                else ""
            ),
            {"m": mass, "I_body": np.diag(tensor_body)},
            {"m": "kg", "I_body": "kg·m²"},
        ),
        Step(
            "Turned by the tilt about x: the tensor on world axes at t = 0",
            r"[I_G]_{XYZ} = R_x(\text{tilt})\,[I_G]_{xyz}\,R_x(\text{tilt})^{\mathsf T}",
            {"I_G": tensor_world},
            {"I_G": "kg·m²"},
        ),
        Step(
            "Angular momentum about G, and how far it leans off ω",
            r"\bar H_G = [I_G]\,\Omega\bar K = \Omega\,(-I_{XZ},\ -I_{YZ},\ I_{ZZ}),\qquad "
            r"\angle(\bar\omega, \bar H_G) = \operatorname{atan2}(|\bar\omega\times\bar H_G|,\ \bar\omega\cdot\bar "
            r"H_G)",
            {"omega": omega, "H_G": h_g, "|H_G|": float(np.linalg.norm(h_g)), "angle": angle},
            {"omega": "rad/s", "H_G": "kg·m²/s", "|H_G|": "kg·m²/s", "angle": "deg"},
        ),
        Step(
            "Linear momentum, and angular momentum about the fixed origin O",
            r"\bar p = m\,\bar v_G,\qquad \bar H_O = \bar H_G + \bar r_G\times m\,\bar v_G",
            {"r_G": r_g, "v_G": v_g, "p": p, "H_O": h_o},
            {"r_G": "m", "v_G": "m/s", "p": "kg·m/s", "H_O": "kg·m²/s"},
        ),
        Step(
            "Kinetic energy: the motion of G plus the motion about G",
            r"T = \tfrac12 m\,|\bar v_G|^2 + \tfrac12\,\bar\omega\cdot\bar H_G",
            {"T_G": t_centre, "T_rel": t_about, "T": t_centre + t_about},
            {"T_G": "J", "T_rel": "J", "T": "J"},
        ),
        Step(
            "Check: the definitions summed over point masses that stand in for the body",
            r"\bar p = \sum m_i\bar v_i,\quad \bar H_O = \sum \bar r_i\times m_i\bar v_i,\quad "
            r"T = \sum\tfrac12 m_i|\bar v_i|^2,\quad \bar v_i = \bar v_G + \bar\omega\times(\bar r_i - \bar r_G)",
            {
                "particles": len(particles.masses_kg),
                "p (sum)": p_particles,
                "H_O (sum)": h_o_particles,
                "H_O (formula)": h_o,
                "T (sum)": t_particles,
                "T (formula)": t_centre + t_about,
            },
            {
                "particles": "",
                "p (sum)": "kg·m/s",
                "H_O (sum)": "kg·m²/s",
                "H_O (formula)": "kg·m²/s",
                "T (sum)": "J",
                "T (formula)": "J",
            },
            scales={"p (sum)": mass * float(np.linalg.norm(v_g)), "H_O (sum)": h_scale, "H_O (formula)": h_scale},
        ),
    )
    outputs = {
        "inertia_world_kg_m2": tensor_world,
        "angular_momentum_G_kg_m2_s": h_g,
        "angle_omega_H_deg": angle,
        "linear_momentum_kg_m_s": p,
        "angular_momentum_O_kg_m2_s": h_o,
        "kinetic_energy_J": t_centre + t_about,
    }
    return Solution(
        outputs=outputs,
        steps=steps,
        output_scales={
            "angular_momentum_O_kg_m2_s": h_scale,
            "linear_momentum_kg_m_s": mass * float(np.linalg.norm(v_g)),
        },
    )


EXAMPLE = WorkedExample(
    id="skewed-plate-momentum",
    title="A skewed plate on a spinning shaft: momentum, angular momentum and kinetic energy",
    chapter=5,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "inertia_world_kg_m2": "kg·m²",
        "angular_momentum_G_kg_m2_s": "kg·m²/s",
        "angle_omega_H_deg": "deg",
        "linear_momentum_kg_m_s": "kg·m/s",
        "angular_momentum_O_kg_m2_s": "kg·m²/s",
        "kinetic_energy_J": "J",
    },
    section="5.1",
    story=ExampleStory(
        situation=(
            "A thin rectangular plate, 4 kg and 0.5 m by 0.4 m, is fixed to a vertical shaft through its centre of "
            "mass $G$, but tilted 30° about its own $x$ axis, so the shaft is not perpendicular to the plate. The "
            "shaft turns at a steady $\\Omega = 4$ rad/s (the default controls). In the **particles** view the "
            "whole shaft also travels at a constant velocity $\\bar v_G$, starting from $\\bar r_G(0)$."
        ),
        wanted=(
            "The plate's angular momentum $\\bar H_G$ about its centre of mass and the angle by which it leans off "
            "$\\bar\\omega$; its linear momentum $\\bar p$ and its angular momentum $\\bar H_O$ about the fixed "
            "origin; and its kinetic energy $T$, split into the motion of $G$ and the motion about $G$."
        ),
        approach=(
            "A rigid body's particles all move with one $\\bar\\omega$, so the sum $\\sum \\bar\\rho_i\\times "
            "m_i\\bar v_i$ collapses to $[I_G]\\bar\\omega$. We take the plate's inertia on its own axes, where it "
            "is a diagonal table of three textbook numbers, and turn it onto the world axes with the tilt; there "
            "$\\bar\\omega = \\Omega\\bar K$ is simplest, and $\\bar H_G$ is $\\Omega$ times the tensor's last "
            "column. Then the two splits about $G$, $\\bar H_O = \\bar H_G + \\bar r_G\\times m\\bar v_G$ and "
            "$T = \\tfrac12 m v_G^2 + \\tfrac12\\bar\\omega\\cdot\\bar H_G$, add the motion of the centre. "
            "Summing over the particles directly would need the plate divided into many pieces, and only agrees "
            "with the tensor in the limit."
        ),
        check=(
            "The check goes back to the definitions. It replaces the plate by a few point masses chosen to have "
            "the same mass, centre of mass and inertia tensor, gives each the velocity $\\bar v_G + "
            "\\bar\\omega\\times(\\bar r_i - \\bar r_G)$, and adds up $\\sum m_i\\bar v_i$, $\\sum \\bar r_i\\times "
            "m_i\\bar v_i$ and $\\sum \\tfrac12 m_i v_i^2$ with no inertia tensor and no split. They must equal "
            "the formulas to round-off, because the splits are exact consequences of the definition of $G$."
        ),
        what_if=(
            "Switch **view** to particles, then change $\\bar v_G$. Watch $\\bar p$, $\\bar H_O$ and "
            "$\\tfrac12 m v_G^2$ change in the steps, while $\\bar H_G$ and $\\tfrac12\\bar\\omega\\cdot\\bar H_G$ "
            "stay exactly as they were: the motion of the centre and the motion about it add without mixing. "
            "Then set the **tilt** to 0° and see the angle between $\\bar\\omega$ and $\\bar H_G$ drop to zero, "
            "as the red and blue arrows in the scene line up."
        ),
    ),
)
