"""Worked example ``path-variables-typed-curve`` (section 2.1): the path variables of a typed curve at one instant.

Frame: the fixed frame XYZ, +Z up; positions in m, time t in s. The curve is the one typed in the space-curve
scene, x(t), y(t), z(t) (default: the helix cos t, sin t, 0.2 t, a bead on a helical wire of radius 1 m rising
0.2 m per radian), and the instant is the scene's ``t start``. The derivatives r', r'', r''' are exact (the
curve is differentiated symbolically by :func:`~app.physics.systems.ch02.space_curve.compile_curve`); the path
variables are those of :func:`~app.physics.systems.ch02.space_curve.path_variables`:

    v = |r'|,  e_t = r'/v,  a_t = r'·r''/v,  a_n = |r' × r''|/v,  κ = |r' × r''|/v³,
    e_b = (r' × r'')/|r' × r''|,  e_n = e_b × e_t,  τ = (r' × r'')·r'''/|r' × r''|².

The check rebuilds the acceleration from its two parts, a_t e_t + a_n e_n = r'', and shows that it has no
binormal part and that a_t² + a_n² = |r''|².

Refused (ParameterError naming ``t_start_s``): an instant where a formula has no finite value, where the particle
is at rest (no tangent) or where the path is locally straight (no normal, binormal or torsion).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch02.space_curve import (
    COMPONENTS,
    CurveError,
    PathVariables,
    _check_curve,
    check_curve_span,
    compile_curve,
    curve_parameters,
    path_variables,
    reference_scales,
    undefined_reason,
)

#: The path's scales (what counts as zero speed or zero curvature) are taken over 0 ≤ t ≤ max(t, this) s.
MIN_SCALE_SPAN_S = 1.0


def _instant(values: Mapping[str, Any]) -> PathVariables:
    """The path variables at ``t_start_s``; ParameterError where something there is undefined."""
    _check_curve(values)
    curve = compile_curve(*(values[name] for name in COMPONENTS))
    t = float(values["t_start_s"])
    try:
        check_curve_span(curve, np.array([t]))
    except CurveError as exc:
        raise ParameterError(exc.component, str(exc)) from None
    path = path_variables(curve, t, reference_scales(curve, max(t, MIN_SCALE_SPAN_S)))
    reason = undefined_reason(path)
    if reason:
        raise ParameterError(
            "t_start_s", f"{reason} Pick another instant (t start) or another curve to see the path variables."
        )
    return path


def _check(values: Mapping[str, Any]) -> None:
    _instant(values)


INPUTS = ParameterSet(
    (
        *curve_parameters(),
        Parameter(
            "t_start_s",
            "s",
            0.0,
            0.0,
            600.0,
            "The instant t at which the path variables are wanted (the scene's t start)",
            "t start",
        ),
    ),
    check=_check,
)


def solve(inputs: Mapping[str, Any]) -> Solution:
    p = _instant(inputs)
    r, v, a, j = p.position_m[0], p.velocity_m_s[0], p.acceleration_m_s2[0], p.jerk_m_s3[0]
    speed, a_t, a_n = float(p.speed_m_s[0]), float(p.a_tangential_m_s2[0]), float(p.a_normal_m_s2[0])
    e_t, e_n, e_b = p.tangent[0], p.normal[0], p.binormal[0]
    kappa, tau = float(p.curvature_1_m[0]), float(p.torsion_1_m[0])
    v_cross_a = np.cross(v, a)
    rebuilt = a_t * e_t + a_n * e_n
    a_size = float(np.linalg.norm(a))
    steps = (
        Step(
            "Position and its exact time derivatives at t",
            r"\bar r = x\,\bar I + y\,\bar J + z\,\bar K,\quad \bar r' = \frac{d\bar r}{dt},\quad "
            r"\bar r'' = \frac{d^2\bar r}{dt^2},\quad \bar r''' = \frac{d^3\bar r}{dt^3}",
            {"t": float(p.t_s[0]), "r": r, "r'": v, "r''": a, "r'''": j},
            {"t": "s", "r": "m", "r'": "m/s", "r''": "m/s²", "r'''": "m/s³"},
        ),
        Step(
            "Speed and unit tangent",
            r"v = \dot s = |\bar r'|,\qquad \bar e_t = \frac{\bar r'}{v}",
            {"v": speed, "e_t": e_t},
            {"v": "m/s", "e_t": ""},
        ),
        Step(
            "Tangential and normal acceleration",
            r"a_t = \ddot s = \frac{\bar r'\cdot\bar r''}{v},\qquad a_n = \frac{|\bar r'\times\bar r''|}{v}",
            {"r' x r''": v_cross_a, "a_t": a_t, "a_n": a_n},
            {"r' x r''": "m²/s³", "a_t": "m/s²", "a_n": "m/s²"},
        ),
        Step(
            "Curvature, radius of curvature, binormal and principal normal",
            r"\kappa = \frac{|\bar r'\times\bar r''|}{v^3},\quad \rho = \frac1\kappa,\quad "
            r"\bar e_b = \frac{\bar r'\times\bar r''}{|\bar r'\times\bar r''|},\quad \bar e_n = \bar e_b\times\bar e_t",
            {"kappa": kappa, "rho": 1.0 / kappa, "e_b": e_b, "e_n": e_n},
            {"kappa": "1/m", "rho": "m", "e_b": "", "e_n": ""},
        ),
        Step(
            "Torsion: how fast the osculating plane twists",
            r"\tau = \frac{(\bar r'\times\bar r'')\cdot\bar r'''}{|\bar r'\times\bar r''|^2}",
            {"tau": tau},
            {"tau": "1/m"},
        ),
        Step(
            "Check: the two parts rebuild the acceleration, which has no binormal part",
            r"a_t\,\bar e_t + a_n\,\bar e_n = \bar r'',\qquad \bar r''\cdot\bar e_b = 0,\qquad "
            r"\sqrt{a_t^2 + a_n^2} = |\bar r''|",
            {
                "a_t e_t + a_n e_n": rebuilt,
                "r''": a,
                "a_b": float(a @ e_b),
                "sqrt(a_t² + a_n²)": math.hypot(a_t, a_n),
                "|r''|": a_size,
            },
            {"a_t e_t + a_n e_n": "m/s²", "r''": "m/s²", "a_b": "m/s²", "sqrt(a_t² + a_n²)": "m/s²", "|r''|": "m/s²"},
            scales={"a_b": a_size},
        ),
    )
    outputs = {
        "speed_m_s": speed,
        "tangent": e_t,
        "normal": e_n,
        "binormal": e_b,
        "a_tangential_m_s2": a_t,
        "a_normal_m_s2": a_n,
        "curvature_1_m": kappa,
        "radius_of_curvature_m": 1.0 / kappa,
        "torsion_1_m": tau,
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="path-variables-typed-curve",
    title="A bead on a helical wire: speed, a_t, a_n, curvature and torsion at one instant",
    chapter=2,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "speed_m_s": "m/s",
        "tangent": "",
        "normal": "",
        "binormal": "",
        "a_tangential_m_s2": "m/s²",
        "a_normal_m_s2": "m/s²",
        "curvature_1_m": "1/m",
        "radius_of_curvature_m": "m",
        "torsion_1_m": "1/m",
    },
    section="2.1",
    story=ExampleStory(
        situation=(
            "A bead is pushed along a helical wire of radius 1 m that rises 0.2 m for every radian it turns, so "
            "its position in metres is $x = \\cos t$, $y = \\sin t$, $z = 0.2\\,t$ with $t$ in seconds. These are "
            "the three formulas in the scene's boxes: type any other curve there and this example follows it. "
            "The instant is the scene's **t start** (0 s to begin with)."
        ),
        wanted=(
            "At that instant: the speed $v$, the unit tangent, principal normal and binormal, the split of the "
            "acceleration into its tangential part $a_t$ (how fast the speed changes) and normal part $a_n$ (how "
            "fast the direction turns), the curvature $\\kappa$ with its radius $\\rho = 1/\\kappa$, and the "
            "torsion $\\tau$."
        ),
        approach=(
            "The curve is given as a function of time, not of arc length, so we never find $s$ itself. The time "
            "derivatives $\\bar r'$, $\\bar r''$ and $\\bar r'''$ carry everything: $\\bar r' = \\dot s\\,\\bar e_t$, "
            "$\\bar r''$ lies in the osculating plane, and $\\bar r'\\times\\bar r''$ points along the binormal. "
            "Dot and cross products of them give every path variable directly, with no angle to track. The "
            "alternative, re-parametrising the curve by $s = \\int |\\bar r'|\\,dt$ and differentiating with "
            "respect to $s$, needs that integral in closed form, which even a helix with a varying speed rarely "
            "has."
        ),
        check=(
            "The acceleration of a particle on a curve lies in the osculating plane: its part along the "
            "tangent plus its part along the normal must give back $\\bar r''$ exactly, its binormal component "
            "$a_b$ must be zero, and by Pythagoras $\\sqrt{a_t^2 + a_n^2}$ must equal $|\\bar r''|$. The last step "
            "computes all of them; for the default helix $a_t = 0$ and $a_n = 1$ m/s², so the whole acceleration "
            "is normal, pointing horizontally at the helix's axis."
        ),
        what_if=(
            "Change **z(t)** from `0.2*t` to `0.2*t^2` and move **t start** to 2 s. The bead now climbs faster "
            "and faster: the speed is 1.28 m/s, $a_t = 0.25$ m/s² (the orange $a_t$ arrow appears in the "
            "scene), and the steeper path has a curvature of only 0.64 1/m, so the grey osculating circle is "
            "larger. Then try `-0.2*t` for z(t): $\\kappa$ stays 0.96 1/m but $\\tau$ changes sign, and the "
            "binormal leans the other way."
        ),
    ),
)
