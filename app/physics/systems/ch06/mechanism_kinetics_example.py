"""Worked example ``slider-crank-pin-forces``: the slider-crank with mass at one crank angle, by Newton–Euler.

System, frame and inputs: :mod:`app.physics.systems.ch06.mechanism_kinetics` (the lesson 6.3 scene's model). At the
crank angle θ = ``crank_angle0_deg`` and speed ω = ``crank_speed_rad_s``, the chapter-4 loop closure gives every
link's motion, and one 8×8 linear solve (:func:`~app.physics.systems.ch06.mechanism_kinetics.newton_euler`) gives
the pin forces O, A, B, the guide force N and either the driving torque τ (drive ``speed``: α = 0) or the crank's
angular acceleration α (drive ``torque``: τ given).

Check: the one-degree-of-freedom equation ``M(θ) α + ½ M′(θ) ω² + V′(θ) = τ``, with ``M(θ) = 2T/θ̇²`` from the
kinetic energy and ``M′``, ``V′`` by fourth-order central differences in θ; it contains no pin force at all, so it
is a second method.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch06.mechanism_kinetics import (
    PARAMETERS,
    SliderCrankLinks,
    generalized_inertia_kg_m2,
    link_motion,
    newton_euler,
    potential_energy_J,
)


def _check(values: Mapping[str, Any]) -> None:
    """The scene model's check, its refusal named as the rod's length (so the API answers 422, not 500)."""
    try:
        SliderCrankLinks.from_params(values)
    except ValueError as exc:
        raise ParameterError("rod_m", str(exc)) from None


INPUTS = ParameterSet(PARAMETERS.parameters, check=_check)
#: Step in θ (rad) of the fourth-order central difference for M′ and V′: its truncation error h⁴ |f⁽⁵⁾|/30 is about
#: 1e-13 of f, and its round-off about ε |f| / h ≈ 1e-13 of f: some twelve figures, far beyond the six shown.
DIFFERENCE_STEP_RAD = 1e-3


def _potential(links: SliderCrankLinks, theta: float) -> float:
    return float(potential_energy_J(links, link_motion(links, theta, 0.0, 0.0))[0])


def _slope(f: Callable[[float], float], x: float) -> float:
    """df/dx by the fourth-order central difference with step :data:`DIFFERENCE_STEP_RAD`."""
    h = DIFFERENCE_STEP_RAD
    return (f(x - 2 * h) - 8 * f(x - h) + 8 * f(x + h) - f(x + 2 * h)) / (12 * h)


def solve(inputs: Mapping[str, Any]) -> Solution:
    links = SliderCrankLinks.from_params(inputs)
    mech = links.mechanism
    theta = math.radians(inputs["crank_angle0_deg"])
    omega = float(inputs["crank_speed_rad_s"])
    by_torque = inputs["drive"] == "torque"
    if by_torque:
        forces = newton_euler(links, np.array([theta]), np.array([omega]), drive_torque_N_m=inputs["drive_torque_N_m"])
    else:
        forces = newton_euler(links, np.array([theta]), np.array([omega]), crank_acceleration_rad_s2=0.0)
    alpha, torque = float(forces.crank_acceleration_rad_s2[0]), float(forces.driving_torque_N_m[0])
    motion = link_motion(links, theta, omega, alpha)
    pivot, crank_pin, wrist_pin = forces.pivot_O_N[0], forces.crank_pin_A_N[0], forces.wrist_pin_B_N[0]
    guide = float(forces.guide_force_N[0])

    inertia = float(generalized_inertia_kg_m2(links, theta)[0])
    inertia_slope = _slope(lambda angle: float(generalized_inertia_kg_m2(links, angle)[0]), theta)
    potential_slope = _slope(lambda angle: _potential(links, angle), theta)
    torque_by_energy = inertia * alpha + 0.5 * inertia_slope * omega**2 + potential_slope

    masses = links.crank_mass_kg + links.rod_mass_kg + links.slider_mass_kg
    force_scale = (
        masses * (links.g_m_s2 + mech.crank_m * omega**2 * (1 + mech.crank_m / mech.rod_m)) + abs(torque) / mech.crank_m
    )
    torque_scale = force_scale * mech.crank_m
    solve_step = (
        Step(
            "Newton–Euler for the three links: eight equations, one linear solve (τ given: α found)",
            r"\text{crank: } \bar O - \bar A + m_1\bar g = m_1\bar a_{G1},\ \tau - \bar r_A\times\bar A + \bar r_{G1}"
            r"\times m_1\bar g = I_O\alpha;\ \ \text{rod: } \bar A - \bar B + m_2\bar g = m_2\bar a_{G2},\ "
            r"(\bar r_A - \bar r_{G2})\times\bar A - (\bar r_B - \bar r_{G2})\times\bar B = I_{G2}\ddot\phi;\ \ "
            r"\text{slider: } \bar B + N\bar j + m_3\bar g = m_3\bar a_B",
            {"tau": torque, "alpha": alpha, "O": pivot, "A": crank_pin, "B": wrist_pin, "N": guide},
            {"tau": "N·m", "alpha": "rad/s²", "O": "N", "A": "N", "B": "N", "N": "N"},
        )
        if by_torque
        else Step(
            "Newton–Euler for the three links: eight equations, one linear solve (α = 0: τ found)",
            r"\text{crank: } \bar O - \bar A + m_1\bar g = m_1\bar a_{G1},\ \tau - \bar r_A\times\bar A + \bar r_{G1}"
            r"\times m_1\bar g = I_O\alpha;\ \ \text{rod: } \bar A - \bar B + m_2\bar g = m_2\bar a_{G2},\ "
            r"(\bar r_A - \bar r_{G2})\times\bar A - (\bar r_B - \bar r_{G2})\times\bar B = I_{G2}\ddot\phi;\ \ "
            r"\text{slider: } \bar B + N\bar j + m_3\bar g = m_3\bar a_B",
            {"tau": torque, "alpha": alpha, "O": pivot, "A": crank_pin, "B": wrist_pin, "N": guide},
            {"tau": "N·m", "alpha": "rad/s²", "O": "N", "A": "N", "B": "N", "N": "N"},
        )
    )
    steps = (
        Step(
            "Positions and rates by loop closure (chapter 4)",
            r"l\sin\phi = e - r\sin\theta,\quad x_B = r\cos\theta + l\cos\phi,\quad \dot\phi = -\frac{r\cos\theta}"
            r"{l\cos\phi}\,\omega,\quad \dot x_B = -r\sin\theta\,\omega - l\sin\phi\,\dot\phi",
            {
                "theta": inputs["crank_angle0_deg"],
                "omega": omega,
                "phi": math.degrees(float(motion.rod_angle[0])),
                "x_B": float(motion.slider_pin[0, 0]),
                "phi_dot": float(motion.rod_rate[0]),
                "x_B_dot": float(motion.slider_velocity[0, 0]),
            },
            {"theta": "deg", "omega": "rad/s", "phi": "deg", "x_B": "m", "phi_dot": "rad/s", "x_B_dot": "m/s"},
        ),
        Step(
            "Mass properties: slender rods, the slider a particle",
            r"I_O = \tfrac13 m_1 r^2,\quad I_{G2} = \tfrac1{12} m_2 l^2",
            {"I_O": links.crank_inertia_about_pivot_kg_m2, "I_G2": links.rod_inertia_about_centre_kg_m2},
            {"I_O": "kg·m²", "I_G2": "kg·m²"},
        ),
        Step(
            "Accelerations of the centres of mass (α = 0 under the speed drive; under the torque drive each is "
            "linear in the unknown α and shown at the α found next)",
            r"\bar a_{G1} = \tfrac12\bar a_A,\quad \bar a_A = r(\alpha\,\bar e_{\theta\perp} - \omega^2\bar e_\theta),"
            r"\quad \bar a_{G2} = \bar a_A + \tfrac l2(\ddot\phi\,\bar e_{\phi\perp} - \dot\phi^2\bar e_\phi),\quad "
            r"\bar a_B = \ddot x_B\,\bar i",
            {
                "a_G1": motion.crank_centre_acceleration[0],
                "a_G2": motion.rod_centre_acceleration[0],
                "a_B": motion.slider_acceleration[0],
                "phi_ddot": float(motion.rod_acceleration[0]),
            },
            {"a_G1": "m/s²", "a_G2": "m/s²", "a_B": "m/s²", "phi_ddot": "rad/s²"},
        ),
        solve_step,
        Step(
            "Check: the one-degree-of-freedom equation (no pin forces in it) gives the same τ",
            r"M(\theta) = \frac{2T}{\dot\theta^2},\quad M(\theta)\,\alpha + \tfrac12 M'(\theta)\,\omega^2 + "
            r"V'(\theta) = \tau",
            {
                "M": inertia,
                "M'": inertia_slope,
                "V'": potential_slope,
                "tau_Newton_Euler": torque,
                "tau_energy": torque_by_energy,
            },
            {"M": "kg·m²", "M'": "kg·m²", "V'": "N·m", "tau_Newton_Euler": "N·m", "tau_energy": "N·m"},
            scales={
                "M'": inertia,
                "V'": torque_scale,
                "tau_Newton_Euler": torque_scale,
                "tau_energy": torque_scale,
            },
        ),
    )
    outputs = {
        "driving_torque_N_m": torque,
        "crank_acceleration_rad_s2": alpha,
        "pivot_O_N": pivot,
        "crank_pin_A_N": crank_pin,
        "wrist_pin_B_N": wrist_pin,
        "guide_force_N": guide,
    }
    return Solution(
        outputs=outputs,
        steps=steps,
        output_scales={
            "driving_torque_N_m": torque_scale,
            "crank_acceleration_rad_s2": torque_scale / max(inertia, 1e-300),
            "pivot_O_N": force_scale,
            "crank_pin_A_N": force_scale,
            "wrist_pin_B_N": force_scale,
            "guide_force_N": force_scale,
        },
    )


EXAMPLE = WorkedExample(
    id="slider-crank-pin-forces",
    title="Pin forces and driving torque of the slider-crank at one crank angle",
    chapter=6,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "driving_torque_N_m": "N·m",
        "crank_acceleration_rad_s2": "rad/s²",
        "pivot_O_N": "N",
        "crank_pin_A_N": "N",
        "wrist_pin_B_N": "N",
        "guide_force_N": "N",
    },
    section="6.3",
    story=ExampleStory(
        situation=(
            "The slider-crank of lesson 4.3 now has mass. The crank is 0.3 m long with 1 kg, the connecting rod "
            "1 m long with 2 kg, both uniform rods, and the slider is 3 kg. It works in a vertical plane under "
            "gravity. A motor turns the crank at 10 rad/s, and we look at the instant the crank is at $\\theta = "
            "0°$ (the scene's start angle $\\theta(0)$). With the drive set to *torque* instead, a given torque "
            "$\\tau$ acts and the speed is only the current one."
        ),
        wanted=(
            "The forces at the three pins O, A and B and the guide's force on the slider at that instant. Under "
            "the *speed* drive we also want the torque the motor must supply, and under the *torque* drive the "
            "crank's angular acceleration $\\alpha$ instead."
        ),
        approach=(
            "We draw one free-body diagram per link and write Newton–Euler for each: two force equations and a "
            "moment equation for the crank (about its fixed pivot) and for the rod (about its centre), and two "
            "force equations for the slider, which does not turn. That makes eight equations for eight "
            "unknowns. Loop closure gives every acceleration first, so the equations are *linear* and one matrix "
            "solve does it. Eliminating the pin forces by hand would reach $\\tau$ with less algebra but lose the "
            "forces the pins must carry, and those are what a designer sizes the bearings by."
        ),
        check=(
            "Energy gives the same torque without a single pin force. The mechanism has one degree of freedom, "
            "so $T = \\tfrac12 M(\\theta)\\dot\\theta^2$ and the power balance reads $M\\alpha + \\tfrac12 M'"
            "\\omega^2 + V' = \\tau$. The last step evaluates $M$ from the kinetic energy and $M'$, $V'$ by central "
            "differences. Its torque must match Newton–Euler's to about ten figures, the accuracy of those "
            "differences."
        ),
        what_if=(
            "Move the start angle **θ(0)** around the turn with the speed drive, and watch the torque change "
            "sign: twice a turn the motor must brake the mechanism rather than drive it. Then raise the "
            "**slider mass** to 50 kg. Near $\\theta = 0°$ and $180°$, where the slider's acceleration is largest, "
            "its inertia force $m_3\\ddot x_B$ dominates the pin forces, yet the torque there stays small: the rod "
            "then points straight at the crank's pivot, so that force has no moment arm about O."
        ),
    ),
)
