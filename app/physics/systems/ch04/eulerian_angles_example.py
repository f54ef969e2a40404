"""Worked example ``heavy-top-euler-rates``: a top's Eulerian angles and their rates give its ω and α on the nutation
frame, and the velocity and acceleration of its centre of mass.

The angles are those of :mod:`app.physics.systems.ch04.eulerian_angles` and of the heavy top of chapters 9 and 10
(:mod:`app.physics.systems.ch10.heavy_top`): the 3-1-3 sequence ``R = Rz(φ) Rx(θ) Rz(ψ)``, +Z up, the pivot O at the
origin, the centre of mass G on the body's z axis at ``cg_distance_m`` (the heavy top's parameter) from O. The inputs
are the eulerian-angles scene's parameters (so the lesson's controls drive the example) plus that distance. The
instant solved is t = 0. Vectors are given on the nutation frame x′y′z′ (x′ the line of nodes, z′ the top's axis;
rad/s, rad/s², m/s, m/s²).

Every in-range combination is a possible motion; θ = 0 or 180° is a singularity of the angles, not of the motion,
and the forward formulas used here stay finite there, so nothing is refused beyond the ranges.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch04.eulerian_angles import PARAMETERS
from app.physics.systems.ch10.heavy_top import PARAMETERS as HEAVY_TOP

INPUTS = ParameterSet((*PARAMETERS.parameters, HEAVY_TOP.by_name["cg_distance_m"]), check=PARAMETERS.check)


def solve(inputs: Mapping[str, Any]) -> Solution:
    phi, theta, psi = (math.radians(inputs[f"{n}_deg"]) for n in ("precession", "nutation", "spin"))
    phi_d, theta_d, psi_d = (inputs[f"{n}_rate_rad_s"] for n in ("precession", "nutation", "spin"))
    phi_dd, theta_dd, psi_dd = (inputs[f"{n}_acceleration_rad_s2"] for n in ("precession", "nutation", "spin"))
    length = inputs["cg_distance_m"]
    st, ct, sp, cp = math.sin(theta), math.cos(theta), math.sin(psi), math.cos(psi)
    # The three turn axes on the nutation frame: K = sin θ j′ + cos θ k′, i′, k = k′.
    K_n = np.array([0.0, st, ct])
    i_n = np.array([1.0, 0.0, 0.0])
    k_n = np.array([0.0, 0.0, 1.0])
    # Their world components, for the reader: i′ = (cos φ, sin φ, 0), k = (sin φ sin θ, −cos φ sin θ, cos θ).
    i_world = np.array([math.cos(phi), math.sin(phi), 0.0])
    k_world = np.array([math.sin(phi) * st, -math.cos(phi) * st, ct])
    omega = np.array([theta_d, phi_d * st, phi_d * ct + psi_d])
    omega_body = np.array([phi_d * st * sp + theta_d * cp, phi_d * st * cp - theta_d * sp, phi_d * ct + psi_d])
    frame_rate = np.array([theta_d, phi_d * st, phi_d * ct])  # Ω′ = φ̇ K + θ̇ i′: ω without the spin
    component_rates = np.array(
        [theta_dd, phi_dd * st + phi_d * theta_d * ct, phi_dd * ct - phi_d * theta_d * st + psi_dd]
    )
    alpha = component_rates + np.cross(frame_rate, omega)
    # Second method: differentiate ω = φ̇ K + θ̇ i′ + ψ̇ k term by term, each axis turned by the earlier turns.
    alpha_terms = (
        phi_dd * K_n
        + theta_dd * i_n
        + psi_dd * k_n
        + np.cross(phi_d * K_n, theta_d * i_n)
        + np.cross(phi_d * K_n + theta_d * i_n, psi_d * k_n)
    )
    r_g = length * k_n
    v_g = np.cross(omega, r_g)
    a_g = np.cross(alpha, r_g) + np.cross(omega, np.cross(omega, r_g))
    steps = (
        Step(
            "The turn axes: fixed K, the line of nodes i′ and the top's axis k (world components)",
            r"\bar i' = (\cos\varphi,\ \sin\varphi,\ 0),\quad "
            r"\bar k = (\sin\varphi\sin\theta,\ -\cos\varphi\sin\theta,\ \cos\theta),\quad "
            r"\bar K = \sin\theta\,\bar j' + \cos\theta\,\bar k'",
            {"i'": i_world, "k": k_world},
            {"i'": "", "k": ""},
        ),
        Step(
            "ω as the sum of the three rates, on the nutation frame",
            r"\bar\omega = \dot\varphi\bar K + \dot\theta\bar i' + \dot\psi\bar k = "
            r"\dot\theta\,\bar i' + \dot\varphi\sin\theta\,\bar j' + (\dot\varphi\cos\theta + \dot\psi)\,\bar k'",
            {"omega": omega, "|omega|": float(np.linalg.norm(omega))},
            {"omega": "rad/s", "|omega|": "rad/s"},
        ),
        Step(
            "The same ω on the body axes (turned through the spin ψ)",
            r"\omega_x = \dot\varphi\sin\theta\sin\psi + \dot\theta\cos\psi,\quad "
            r"\omega_y = \dot\varphi\sin\theta\cos\psi - \dot\theta\sin\psi,\quad "
            r"\omega_z = \dot\varphi\cos\theta + \dot\psi",
            {"omega_body": omega_body},
            {"omega_body": "rad/s"},
        ),
        Step(
            "α on the nutation frame: rates of the components plus Ω′ × ω (Ω′ = φ̇K + θ̇i′, the frame's own rate)",
            r"\bar\alpha = \frac{\delta\bar\omega}{\delta t} + \bar\Omega'\times\bar\omega,\quad "
            r"\frac{\delta\bar\omega}{\delta t} = \big(\ddot\theta,\ \ddot\varphi\sin\theta + "
            r"\dot\varphi\dot\theta\cos\theta,\ \ddot\varphi\cos\theta - \dot\varphi\dot\theta\sin\theta + "
            r"\ddot\psi\big)",
            {"Omega'": frame_rate, "delta omega/delta t": component_rates, "alpha": alpha},
            {"Omega'": "rad/s", "delta omega/delta t": "rad/s²", "alpha": "rad/s²"},
        ),
        Step(
            "The centre of mass G, a distance l up the axis from the fixed pivot O",
            r"\bar r_{G/O} = l\,\bar k',\quad \bar v_G = \bar\omega\times\bar r_{G/O},\quad "
            r"\bar a_G = \bar\alpha\times\bar r_{G/O} + \bar\omega\times(\bar\omega\times\bar r_{G/O})",
            {"l": length, "v_G": v_g, "a_G": a_g},
            {"l": "m", "v_G": "m/s", "a_G": "m/s²"},
        ),
        Step(
            "Check: α again, differentiating φ̇K + θ̇i′ + ψ̇k term by term; and G keeps its distance from O",
            r"\bar\alpha = \ddot\varphi\bar K + \ddot\theta\bar i' + \ddot\psi\bar k + "
            r"\dot\varphi\bar K\times\dot\theta\bar i' + (\dot\varphi\bar K + \dot\theta\bar i')\times\dot\psi\bar k,"
            r"\qquad \bar r_{G/O}\cdot\bar v_G = 0",
            {
                "alpha (term by term)": alpha_terms,
                "alpha (frame rates)": alpha,
                "r_G·v_G": float(r_g @ v_g),
            },
            {"alpha (term by term)": "rad/s²", "alpha (frame rates)": "rad/s²", "r_G·v_G": "m²/s"},
            scales={"r_G·v_G": length * float(np.linalg.norm(v_g))},
        ),
    )
    outputs = {
        "angular_velocity_nutation_rad_s": omega,
        "angular_velocity_body_rad_s": omega_body,
        "angular_acceleration_nutation_rad_s2": alpha,
        "centre_velocity_nutation_m_s": v_g,
        "centre_acceleration_nutation_m_s2": a_g,
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="heavy-top-euler-rates",
    title="A top's Eulerian angles: ω, α and the motion of its centre of mass",
    chapter=4,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "angular_velocity_nutation_rad_s": "rad/s",
        "angular_velocity_body_rad_s": "rad/s",
        "angular_acceleration_nutation_rad_s2": "rad/s²",
        "centre_velocity_nutation_m_s": "m/s",
        "centre_acceleration_nutation_m_s2": "m/s²",
    },
    section="4.2",
    story=ExampleStory(
        situation=(
            "A top spins on a fixed pivot $O$; its centre of mass $G$ is $l = 0.05$ m up its axis, as in the heavy "
            "top of chapters 9 and 10. At this instant its axis leans $\\theta = 35°$ from the vertical and the "
            "line of nodes points $\\varphi = 30°$ from $X$. It precesses at $\\dot\\varphi = 0.8$ rad/s, nods at "
            "$\\dot\\theta = 0.15$ rad/s and spins at $\\dot\\psi = 4$ rad/s (the default controls), with no "
            "angular accelerations of the angles."
        ),
        wanted=(
            "The top's angular velocity $\\bar\\omega$ and angular acceleration $\\bar\\alpha$, on the nutation "
            "frame and for $\\bar\\omega$ also on the body axes, and then the velocity and acceleration of its "
            "centre of mass $G$: the quantities chapter 10's equations of motion are built from."
        ),
        approach=(
            "Each angle's rate is an angular velocity about that angle's own axis, so $\\bar\\omega$ is a sum of "
            "three vectors along $\\bar K$, the line of nodes $\\bar i'$ and the axis $\\bar k$. We resolve it on "
            "the **nutation frame**: it follows the axis but not the spin, so its components do not depend on "
            "$\\psi$, and the top's inertia, symmetric about $\\bar k$, is constant on it. For $\\bar\\alpha$ we "
            "differentiate those components and add $\\bar\\Omega'\\times\\bar\\omega$, with $\\bar\\Omega'$ the "
            "frame's own rate. Body axes would work too, but every component would carry $\\sin\\psi$ and "
            "$\\cos\\psi$, which change at the fast spin rate. $G$ is then a point of a body turning about a fixed "
            "point, so the general equations of 4.1 from $O$ give its motion."
        ),
        check=(
            "The check differentiates $\\bar\\omega = \\dot\\varphi\\bar K + \\dot\\theta\\bar i' + "
            "\\dot\\psi\\bar k$ a second way: term by term, letting the precession turn $\\bar i'$ and both "
            "precession and nutation turn $\\bar k$. This route never uses the frame's rate $\\bar\\Omega'$, yet "
            "both must give the same $\\bar\\alpha$ to round-off. It also shows $\\bar r_{G/O}\\cdot\\bar v_G = 0$: "
            "$G$ stays on a sphere of radius $l$ about the pivot, so its velocity can have no part along $OG$."
        ),
        what_if=(
            "Set the **nutation rate** $\\dot\\theta$ to zero, so the top precesses steadily. $\\bar\\alpha$ is "
            "then entirely along the line of nodes, $\\dot\\varphi\\dot\\psi\\sin\\theta$: the spin axis is "
            "being swung round the vertical. Raise the **spin rate** $\\dot\\psi$ and watch that component, and "
            "the blue $\\bar\\alpha$ arrow in the scene, grow in proportion, while $\\bar v_G$ does not change at "
            "all: spinning about its own axis does not move $G$."
        ),
    ),
)
