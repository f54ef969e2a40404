"""Worked example ``rolling-disk-instant``: a disk (or a cone) rolling without slip round a circle: the spin the
rolling requires, ω and α, the instantaneous axis, the velocity of the rim's top and the acceleration of the material
point in contact.

The body, the frame and the names are those of :mod:`app.physics.systems.ch04.rolling` (world XYZ, +Z up, the contact
point C on a circle of radius ρ about O), and the inputs are that scene's parameters. The instant solved is t = 0 of
the scene: heading ψ = 0, so ê_r = X and the direction of travel ê_ψ = Y. Vectors are world [X, Y, Z] components
(m, m/s, m/s², rad/s, rad/s²). For the cone, ρ is its slant length R / sin θ and "the rim's centre" is the centre of
its base.

A cone with a half-angle below 5° (it has no apex to roll about) is refused with a ParameterError naming ``tilt_deg``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch04.rolling import PARAMETERS, SteadyRolling

Z = np.array([0.0, 0.0, 1.0])


def _check(values: Mapping[str, Any]) -> None:
    try:
        SteadyRolling.from_params(values)
    except ValueError as exc:
        raise ParameterError("tilt_deg", str(exc)) from None


INPUTS = ParameterSet(PARAMETERS.parameters, check=_check)


def solve(inputs: Mapping[str, Any]) -> Solution:
    _check(inputs)
    rolling = SteadyRolling.from_params(inputs)
    R, rho, v, theta = rolling.rim_radius_m, rolling.path_radius_m, rolling.speed_m_s, rolling.tilt_rad
    e_r, e_psi = np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])
    d_hat = math.cos(theta) * Z - math.sin(theta) * e_r
    n_hat = math.cos(theta) * e_r + math.sin(theta) * Z
    r_c = rho * e_r
    r_g = r_c + R * d_hat
    turn = v / rho  # Ω
    v_g = (v - R * turn * math.sin(theta)) * e_psi
    # No slip: v_C = v_G + ω × r_C/G = (v + R σ̇) ê_ψ = 0.
    spin = -v / R
    omega = turn * Z + spin * n_hat
    r_cg = r_c - r_g
    v_c = v_g + np.cross(omega, r_cg)
    o_prime = rolling.axis_point
    v_o_prime = v_g + np.cross(omega, o_prime - r_g)
    r_top = r_g + R * d_hat
    v_top_about_c = np.cross(omega, r_top - r_c)
    v_top_from_g = v_g + np.cross(omega, r_top - r_g)
    # α: Ω and σ̇ are constant; only n̂ changes, carried round Z at Ω.
    alpha = np.cross(turn * Z, spin * n_hat)
    a_g = -turn * (v - R * turn * math.sin(theta)) * e_r  # G goes round a horizontal circle at |v_G|
    a_c = a_g + np.cross(alpha, r_cg) + np.cross(omega, np.cross(omega, r_cg))
    steps = (
        Step(
            "Where everything is at t = 0 (heading ψ = 0, so ê_r = X and ê_ψ = Y)",
            r"\bar r_C = \rho\,\bar e_r,\quad \bar d = \cos\theta\,\bar K - \sin\theta\,\bar e_r,\quad "
            r"\bar n = \cos\theta\,\bar e_r + \sin\theta\,\bar K,\quad \bar r_G = \bar r_C + R\,\bar d",
            {"rho": rho, "r_C": r_c, "d": d_hat, "n": n_hat, "r_G": r_g},
            {"rho": "m", "r_C": "m", "d": "", "n": "", "r_G": "m"},
        ),
        Step(
            "Velocity of the rim's centre G, by differentiating its position",
            r"\Omega = \frac{v}{\rho},\quad \dot{\bar e}_r = \Omega\,\bar e_\psi \;\Rightarrow\; "
            r"\bar v_G = (v - R\,\Omega\sin\theta)\,\bar e_\psi",
            {"Omega": turn, "v_G": v_g},
            {"Omega": "rad/s", "v_G": "m/s"},
        ),
        Step(
            "No slip at C fixes the spin; ω is the turn plus the spin",
            r"\bar v_C = \bar v_G + \bar\omega\times\bar r_{C/G} = (v + R\dot\sigma)\,\bar e_\psi = \bar 0 "
            r"\;\Rightarrow\; \dot\sigma = -\frac{v}{R},\qquad \bar\omega = \Omega\,\bar K + \dot\sigma\,\bar n",
            {"sigma_dot": spin, "omega": omega},
            {"sigma_dot": "rad/s", "omega": "rad/s"},
        ),
        Step(
            "The instantaneous axis: the line through C and O′ (where the axle's line meets the vertical through O)",
            r"O' = \left(0,\ 0,\ \frac{R - \rho\sin\theta}{\cos\theta}\right),\qquad "
            r"\bar v_T = \bar\omega\times\bar r_{T/C}\ \text{ for the rim's top } \bar r_T = \bar r_G + R\,\bar d",
            {"z_O'": float(o_prime[2]), "r_T": r_top, "v_T": v_top_about_c},
            {"z_O'": "m", "r_T": "m", "v_T": "m/s"},
        ),
        Step(
            "Angular acceleration: the axle n̂ is carried round the vertical at Ω",
            r"\bar\alpha = \dot\Omega\,\bar K + \ddot\sigma\,\bar n + \dot\sigma\,\dot{\bar n} = "
            r"\dot\sigma\,(\Omega\bar K\times\bar n)\qquad(\dot\Omega = \ddot\sigma = 0)",
            {"alpha": alpha},
            {"alpha": "rad/s²"},
        ),
        Step(
            "Acceleration of the material point at C: at rest, but not unaccelerated",
            r"\bar a_G = -\Omega\,(v - R\,\Omega\sin\theta)\,\bar e_r,\qquad "
            r"\bar a_C = \bar a_G + \bar\alpha\times\bar r_{C/G} + \bar\omega\times(\bar\omega\times\bar r_{C/G})",
            {"a_G": a_g, "a_C": a_c},
            {"a_G": "m/s²", "a_C": "m/s²"},
        ),
        Step(
            "Check: from G, C and O′ are at rest and the rim's top moves as about the instantaneous axis",
            r"\bar v_C = \bar v_G + \bar\omega\times\bar r_{C/G} = \bar 0,\quad "
            r"\bar v_{O'} = \bar v_G + \bar\omega\times\bar r_{O'/G} = \bar 0,\quad "
            r"\bar v_G + \bar\omega\times\bar r_{T/G} = \bar\omega\times\bar r_{T/C}",
            {
                "v_C": v_c,
                "v_O'": v_o_prime,
                "v_T (from G)": v_top_from_g,
                "v_T (about C)": v_top_about_c,
            },
            {"v_C": "m/s", "v_O'": "m/s", "v_T (from G)": "m/s", "v_T (about C)": "m/s"},
            scales={"v_C": abs(v), "v_O'": abs(v)},
        ),
    )
    outputs = {
        "path_radius_m": rho,
        "center_velocity_m_s": v_g,
        "spin_rate_rad_s": spin,
        "angular_velocity_rad_s": omega,
        "axis_point_height_m": float(o_prime[2]),
        "top_point_velocity_m_s": v_top_about_c,
        "angular_acceleration_rad_s2": alpha,
        "contact_point_acceleration_m_s2": a_c,
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="rolling-disk-instant",
    title="A disk rolling round a circle: the spin it needs, its angular acceleration and the contact point",
    chapter=4,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "path_radius_m": "m",
        "center_velocity_m_s": "m/s",
        "spin_rate_rad_s": "rad/s",
        "angular_velocity_rad_s": "rad/s",
        "axis_point_height_m": "m",
        "top_point_velocity_m_s": "m/s",
        "angular_acceleration_rad_s2": "rad/s²",
        "contact_point_acceleration_m_s2": "m/s²",
    },
    section="4.4",
    story=ExampleStory(
        situation=(
            "A coin of radius $R = 0.4$ m rolls without slipping round a circle on a level floor, leaning "
            "$\\theta = 20°$ into the turn. Its contact point $C$ travels round a circle of radius $\\rho = 1.5$ m "
            "about $O$ at $v = 0.8$ m/s (the default controls). We look at the instant when $C$ is on the $X$ axis "
            "and moving along $+Y$. The same steps serve a cone rolling on its side about its apex, whose $\\rho$ "
            "is its slant length."
        ),
        wanted=(
            "The spin rate $\\dot\\sigma$ that rolling demands, the angular velocity $\\bar\\omega$, where the "
            "instantaneous axis runs, the velocity of the top of the rim, the angular acceleration "
            "$\\bar\\alpha$, and the acceleration of the material point that is touching the floor."
        ),
        approach=(
            "We describe the disk with two turns we can see: the heading, turning about the fixed vertical at "
            "$\\Omega = v/\\rho$, and the spin $\\dot\\sigma$ about the axle $\\bar n$, so $\\bar\\omega = "
            "\\Omega\\bar K + "
            "\\dot\\sigma\\bar n$. The rim's centre $G$ has a position we can write down and differentiate, so we "
            "start from $G$ and apply the general equations of 4.1 to reach $C$. Rolling is one vector condition, "
            "$\\bar v_C = \\bar 0$, and it fixes the one unknown, $\\dot\\sigma$. For $\\bar\\alpha$ we differentiate "
            "$\\bar\\omega$ remembering that $\\bar n$ is carried round by the heading. Eulerian angles would also "
            "work, but they bring a third angle and a sequence to keep track of, for a motion whose two rates are "
            "constant."
        ),
        check=(
            "Two points must be at rest: the material point at $C$ (that is the condition we imposed) and the "
            "point $O'$ where the axle's line meets the vertical through $O$, which we never used. The check "
            "computes both from $G$ with $\\bar v_G + \\bar\\omega\\times\\bar r$, and finds zero to round-off. It "
            "also computes the rim's top twice: from $G$, and as a pure rotation about the instantaneous axis "
            "$CO'$. The two must agree if that line really is the axis."
        ),
        what_if=(
            "Move the **tilt** $\\theta$ from 0° up to 40° and watch $O'$: its height in the steps falls from the "
            "height of the centre ($R$) through zero, where the instantaneous axis lies on the floor, to below "
            "the ground once $\\rho\\sin\\theta > R$; the orange axis in the scene follows it. Then watch "
            "$\\bar a_C$: for an upright disk on a wide circle it points straight up with magnitude close to "
            "$v^2/R$, the contact point's acceleration of a wheel in a straight line."
        ),
    ),
)
