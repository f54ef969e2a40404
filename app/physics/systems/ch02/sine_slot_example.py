"""Worked example ``pin-in-sine-slot`` (section 2.2): a pin driven through a sine-shaped slot, by components.

Frame: the fixed frame XYZ, +Z up; the slot y = h sin(πx/L) is cut in the horizontal plane z = 0 and the pin is
driven along X at the constant speed ẋ = u (the sine-slot motion of
:class:`~app.physics.systems.ch02.cartesian_components.SineSlot`). Lengths in m, time in s. The instant is given by
where the pin is, x = ``pin_x_m`` (0 ≤ x ≤ 2L, one wavelength), so t = x/u and, with k = π/L::

    ẏ = h k u cos(k x),   ẍ = 0,   ÿ = −h k² u² sin(k x).

The check is a second method: the slot's own curvature, from its shape alone,
κ = |y''(x)|/(1 + y'(x)²)^{3/2}, times v² must equal the normal part a_n = |v × a|/v of the Cartesian acceleration.

Refused (ParameterError naming ``pin_x_m``): a pin beyond the slot's end, x > 2L.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch02.cartesian_components import PARAMETERS as SCENE_PARAMETERS
from app.physics.systems.ch02.cartesian_components import SineSlot


def _check(values: Mapping[str, Any]) -> None:
    end = 2.0 * values["slot_length_m"]
    if values["pin_x_m"] > end:
        raise ParameterError(
            "pin_x_m",
            f"the slot is one wavelength long and ends at x = 2L = {end:g} m, so the pin cannot be at "
            f"x = {values['pin_x_m']:g} m; move it within the slot or lengthen L",
        )


INPUTS = ParameterSet(
    (
        SCENE_PARAMETERS.by_name["slot_amplitude_m"],
        SCENE_PARAMETERS.by_name["slot_length_m"],
        SCENE_PARAMETERS.by_name["drive_speed_m_s"],
        Parameter(
            "pin_x_m",
            "m",
            0.25,
            0.0,
            6.0,
            "Where the pin is along X when v and a are wanted (0 ≤ x ≤ 2L, the slot's length)",
            "x_P",
            step=0.01,
        ),
    ),
    check=_check,
)


def solve(inputs: Mapping[str, Any]) -> Solution:
    _check(inputs)
    h, L, u, x = inputs["slot_amplitude_m"], inputs["slot_length_m"], inputs["drive_speed_m_s"], inputs["pin_x_m"]
    slot = SineSlot(h, L, u)
    t = x / u
    state = slot.at(t)
    r, v, a = state.position_m[0], state.velocity_m_s[0], state.acceleration_m_s2[0]
    k = math.pi / L
    speed = float(np.linalg.norm(v))
    a_size = float(np.linalg.norm(a))
    a_t = float(v @ a) / speed
    a_n = float(np.linalg.norm(np.cross(v, a))) / speed
    slope = h * k * math.cos(k * x)  # y'(x), dimensionless
    bend = -h * k**2 * math.sin(k * x)  # y''(x), 1/m
    kappa = abs(bend) / (1.0 + slope**2) ** 1.5
    steps = (
        Step(
            "Time and position of the pin",
            r"t = \frac{x}{\dot x},\qquad y = h\sin(kx),\quad k = \frac{\pi}{L}",
            {"k": k, "t": t, "r": r},
            {"k": "1/m", "t": "s", "r": "m"},
        ),
        Step(
            "Velocity, component by component (I, J, K never turn)",
            r"\dot y = \frac{dy}{dx}\,\dot x = hk\cos(kx)\,\dot x,\qquad \bar v = \dot x\,\bar I + \dot y\,\bar J,"
            r"\qquad v = \sqrt{\dot x^2 + \dot y^2}",
            {"x_dot": float(v[0]), "y_dot": float(v[1]), "v": v, "speed": speed},
            {"x_dot": "m/s", "y_dot": "m/s", "v": "m/s", "speed": "m/s"},
            scales={"y_dot": speed},
        ),
        Step(
            "Acceleration, component by component (ẋ constant, so ẍ = 0)",
            r"\ddot y = -hk^2\sin(kx)\,\dot x^2,\qquad \bar a = \ddot x\,\bar I + \ddot y\,\bar J = \ddot y\,\bar J",
            {"x_ddot": float(a[0]), "y_ddot": float(a[1]), "a": a, "|a|": a_size},
            {"x_ddot": "m/s²", "y_ddot": "m/s²", "a": "m/s²", "|a|": "m/s²"},
            scales={"x_ddot": a_size, "y_ddot": a_size},
        ),
        Step(
            "Along and across the slot (path variables from the components)",
            r"a_t = \frac{\bar v\cdot\bar a}{v},\qquad a_n = \frac{|\bar v\times\bar a|}{v}",
            {"a_t": a_t, "a_n": a_n},
            {"a_t": "m/s²", "a_n": "m/s²"},
            scales={"a_t": a_size, "a_n": a_size},
        ),
        Step(
            "Check: the slot's own curvature gives the same normal acceleration",
            r"y'(x) = hk\cos(kx),\quad y''(x) = -hk^2\sin(kx),\quad \kappa = \frac{|y''|}{(1 + y'^2)^{3/2}},"
            r"\qquad \kappa\,v^2 = a_n",
            {"y'": slope, "y''": bend, "kappa": kappa, "kappa v²": kappa * speed**2, "a_n": a_n},
            {"y'": "", "y''": "1/m", "kappa": "1/m", "kappa v²": "m/s²", "a_n": "m/s²"},
            scales={"y'": h * k, "y''": h * k**2, "kappa v²": a_size, "a_n": a_size},
        ),
    )
    outputs = {
        "time_s": t,
        "position_m": r,
        "velocity_m_s": v,
        "speed_m_s": speed,
        "acceleration_m_s2": a,
        "a_tangential_m_s2": a_t,
        "a_normal_m_s2": a_n,
        "slot_curvature_1_m": kappa,
    }
    return Solution(
        outputs=outputs,
        steps=steps,
        output_scales={"a_tangential_m_s2": a_size, "a_normal_m_s2": a_size, "slot_curvature_1_m": h * k**2},
    )


EXAMPLE = WorkedExample(
    id="pin-in-sine-slot",
    title="A pin driven through a sine-shaped slot: velocity and acceleration by components",
    chapter=2,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "time_s": "s",
        "position_m": "m",
        "velocity_m_s": "m/s",
        "speed_m_s": "m/s",
        "acceleration_m_s2": "m/s²",
        "a_tangential_m_s2": "m/s²",
        "a_normal_m_s2": "m/s²",
        "slot_curvature_1_m": "1/m",
    },
    section="2.2",
    story=ExampleStory(
        situation=(
            "A pin rides in a slot cut in a horizontal plate along the curve $y = h\\sin(\\pi x/L)$, with "
            "$h = 0.3$ m and $L = 1$ m. A slider pushes the pin along $X$ at a steady $\\dot x = 0.5$ m/s, so "
            "the slot forces it sideways as it goes, like a cam follower. The pin starts at $x = 0$ when "
            "$t = 0$; we look at it when it has reached $x_P = 0.25$ m, a quarter of the way up the first flank."
        ),
        wanted=(
            "The time at which the pin gets there, its velocity and speed, its acceleration, and how that "
            "acceleration splits into a part along the slot (changing the speed) and a part across it "
            "(turning the pin round the bend)."
        ),
        approach=(
            "The slot is fixed on the plate and the drive is along a fixed axis, so the fixed Cartesian axes "
            "$XYZ$ are the natural description: $\\bar I$, $\\bar J$, $\\bar K$ never turn, and the velocity "
            "and acceleration are just the derivatives of $x(t)$ and $y(t)$, found with the chain rule through "
            "$y(x)$. Path variables straight away would need the arc length along a sine, an elliptic integral "
            "with no elementary closed form; instead we get $a_t$ and $a_n$ afterwards from dot and cross "
            "products of the Cartesian vectors."
        ),
        check=(
            "The normal acceleration is also a property of the slot's shape: a particle moving at speed $v$ "
            "on a curve of curvature $\\kappa$ has $a_n = \\kappa v^2$. The last step finds $\\kappa$ from "
            "$y'(x)$ and $y''(x)$ alone, with no time in it, and multiplies by $v^2$: it must agree with the "
            "$a_n$ found from the components, and it does to round-off."
        ),
        what_if=(
            "Move **L** (the half-wavelength) from 1 m down to 0.5 m. The pin's place $x_P = 0.25$ m is now the "
            "first crest: the slot is level there, so $\\dot y = 0$, $a_t = 0$, and the whole acceleration is "
            "$\\ddot y = -h(\\pi/L)^2\\dot x^2 = -2.96$ m/s² across the drive, more than five times the "
            "0.52 m/s² at the defaults. In the scene, watch the red arrow, always straight across the drive, "
            "grow at every crest; doubling **ẋ** makes it four times longer again."
        ),
    ),
)
