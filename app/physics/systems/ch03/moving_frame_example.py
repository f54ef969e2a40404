"""Worked example ``sorting-table-carriage``: the five terms of a carriage's acceleration on a moving turntable.

The system is :mod:`app.physics.systems.ch03.moving_frame` (the lesson's scene), read as a sorting machine: a small
carriage P runs back and forth in a straight guide across a turntable, ``s = A_s sin 2π f_s t`` along body x at
the offset ``d`` from the centre; the table spins at ``θ̇ = ω₀ + α₀ t`` about its own axis, which may be tilted by
β and precess about the vertical at Ω_p; the whole machine stands on a cart that shakes along X,
``X_O = A_c sin 2π f_c t``. At the instant ``t = time_s`` modulo ``replay_s`` (the scene's instant),

``a_P = a_O + α × r + ω × (ω × r) + 2 ω × v_rel + a_rel``  (m/s², XYZ components).

Inputs are refused as the scene refuses them (a carriage that would leave the table: ParameterError).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch03.moving_frame import PARAMETERS, TERM_NAMES, MovingFrameMotion

#: Step (s) of the fourth-order second difference in the check: truncation h⁴|r⁽⁶⁾|/90 ≤ 1e-12·(7 rad/s)⁶·3 m/90
#: ≈ 4e-9 m/s² at the fastest controls, round-off ≈ 5 ε |r| / h² ≈ 4e-9 m/s² for |r| ≈ 3 m.
DIFFERENCE_STEP_S = 1e-3


def _check(values: Mapping[str, Any]) -> None:
    """The scene's own refusals (the carriage must stay on the table)."""
    if PARAMETERS.check is not None:
        PARAMETERS.check(values)


INPUTS = ParameterSet(
    (
        *PARAMETERS.parameters,
        Parameter(
            "time_s",
            "s",
            1.5,
            0.0,
            60.0,
            "Instant t at which the acceleration is worked out (the scene's instant)",
            "instant t",
            step=0.05,
        ),
        Parameter(
            "replay_s",
            "s",
            10.0,
            2.0,
            60.0,
            "The scene replays the motion from t = 0 after this long",
            "replay length",
            step=1.0,
        ),
    ),
    check=_check,
)


def solve(inputs: Mapping[str, Any]) -> Solution:
    _check(inputs)
    motion = MovingFrameMotion.from_params(inputs)
    t = float(inputs["time_s"]) % float(inputs["replay_s"])
    at = np.array([t])
    k = motion.kinematics(at)
    spin_axis = motion.spin_axis_world(at)[0]
    omega, alpha = k.omega_rad_s[0], k.alpha_rad_s2[0]
    _, v_origin, a_origin = motion.origin(at)
    r_body, v_body, a_body = (x[0] for x in motion.relative_body(at))
    R = motion.attitude(at)[0]
    r, v_rel, a_rel = R @ r_body, R @ v_body, R @ a_body
    terms = {name: k.terms_m_s2[name][0] for name in (*TERM_NAMES, "total")}
    total = terms["total"]
    # What a zero is measured against (a term at a turning point of the guide is 1e-17 of these, not a number):
    # the carriage's largest speed along the guide with the table's speed under it, and the chain of the five terms.
    speed_scale = 2.0 * math.pi * motion.slider_frequency_hz * motion.slider_amplitude_m + float(
        np.linalg.norm(omega) * np.linalg.norm(r)
    )
    chain_scale = sum(float(np.linalg.norm(terms[name])) for name in TERM_NAMES)

    h = DIFFERENCE_STEP_S
    near = motion.position_world(t + h * np.array([-2.0, -1.0, 0.0, 1.0, 2.0]))
    differenced = (-near[0] + 16.0 * near[1] - 30.0 * near[2] + 16.0 * near[3] - near[4]) / (12.0 * h * h)
    steps = (
        Step(
            "The instant, and the table's angular velocity and acceleration",
            r"\bar\omega = \Omega_p\bar K + \dot\theta\,\bar k,\quad "
            r"\bar\alpha = \ddot\theta\,\bar k + \dot\theta\,\Omega_p\,\bar K\times\bar k,\quad "
            r"\dot\theta = \omega_0 + \alpha_0 t",
            {"t": t, "k": spin_axis, "omega": omega, "alpha": alpha},
            {"t": "s", "k": "", "omega": "rad/s", "alpha": "rad/s²"},
        ),
        Step(
            "The reference point O rides on the shaking cart",
            r"X_O = A_c\sin 2\pi f_c t,\quad \bar v_O = 2\pi f_c A_c\cos(2\pi f_c t)\,\bar I,\quad "
            r"\bar a_O = -(2\pi f_c)^2 A_c\sin(2\pi f_c t)\,\bar I",
            {"v_O": v_origin[0], "a_O": a_origin[0]},
            {"v_O": "m/s", "a_O": "m/s²"},
        ),
        Step(
            "The carriage as seen on the table, turned into fixed components",
            r"\{r\}_{xyz} = (s, d, 0),\ s = A_s\sin 2\pi f_s t,\quad \bar r = [R]\{r\}_{xyz},\ "
            r"\bar v_{\rm rel} = [R]\{\dot s, 0, 0\},\ \bar a_{\rm rel} = [R]\{\ddot s, 0, 0\}",
            {"r_xyz": r_body, "r": r, "v_rel": v_rel, "a_rel": a_rel},
            {"r_xyz": "m", "r": "m", "v_rel": "m/s", "a_rel": "m/s²"},
            {"v_rel": speed_scale, "a_rel": chain_scale},
        ),
        Step(
            "The five terms",
            r"\bar a_O,\quad \bar\alpha\times\bar r,\quad \bar\omega\times(\bar\omega\times\bar r),\quad "
            r"2\,\bar\omega\times\bar v_{\rm rel},\quad \bar a_{\rm rel}",
            {
                "a_O": terms["reference"],
                "alpha_x_r": terms["angular"],
                "omega_x_omega_x_r": terms["centripetal"],
                "coriolis": terms["coriolis"],
                "a_rel": terms["relative"],
            },
            {
                "a_O": "m/s²",
                "alpha_x_r": "m/s²",
                "omega_x_omega_x_r": "m/s²",
                "coriolis": "m/s²",
                "a_rel": "m/s²",
            },
            {
                "a_O": chain_scale,
                "alpha_x_r": chain_scale,
                "omega_x_omega_x_r": chain_scale,
                "coriolis": chain_scale,
                "a_rel": chain_scale,
            },
        ),
        Step(
            "Their sum: the carriage's absolute acceleration",
            r"\bar a_P = \bar a_O + \bar\alpha\times\bar r + \bar\omega\times(\bar\omega\times\bar r) + "
            r"2\,\bar\omega\times\bar v_{\rm rel} + \bar a_{\rm rel}",
            {"a_P": total, "|a_P|": float(np.linalg.norm(total))},
            {"a_P": "m/s²", "|a_P|": "m/s²"},
        ),
        Step(
            "Check: differencing the carriage's position twice gives the same acceleration",
            r"\bar r_P(t) = \bar r_O(t) + [R(t)]\{r(t)\}_{xyz},\quad \ddot{\bar r}_P \approx "
            r"\frac{-\bar r_P(t-2h) + 16\bar r_P(t-h) - 30\bar r_P(t) + 16\bar r_P(t+h) - \bar r_P(t+2h)}{12h^2}",
            {"a_P": total, "a_P_differenced": differenced, "h": h},
            {"a_P": "m/s²", "a_P_differenced": "m/s²", "h": "s"},
        ),
    )
    outputs = {
        "t_s": t,
        "omega_rad_s": omega,
        "alpha_rad_s2": alpha,
        "position_m": k.position_m[0],
        **{f"a_{name}_m_s2": terms[name] for name in (*TERM_NAMES, "total")},
    }
    scales = {f"a_{name}_m_s2": chain_scale for name in (*TERM_NAMES, "total")}
    return Solution(outputs=outputs, steps=steps, output_scales=scales)


EXAMPLE = WorkedExample(
    id="sorting-table-carriage",
    title="A carriage in a guide across a spinning, shaking table: its acceleration term by term",
    chapter=3,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "t_s": "s",
        "omega_rad_s": "rad/s",
        "alpha_rad_s2": "rad/s²",
        "position_m": "m",
        **{f"a_{name}_m_s2": "m/s²" for name in (*TERM_NAMES, "total")},
    },
    section="3.5",
    story=ExampleStory(
        situation=(
            "In a parcel-sorting machine a small carriage runs back and forth in a straight guide cut across a "
            "turntable of radius 1 m, 0.3 m from the centre, with $s = 0.6\\sin(2\\pi\\cdot0.25\\,t)$ m. The "
            "table spins at 1 rad/s. The controls can also make it spin up, tilt its axis and let that axis "
            "precess about the vertical, and set the cart it stands on shaking along $X$."
        ),
        wanted=(
            "The carriage's acceleration relative to the floor at the instant $t$ (1.5 s by default), and each "
            "of the five parts it is made of: the acceleration of the table's centre, the angular-acceleration "
            "and centripetal terms of the table point under the carriage, the Coriolis term, and the "
            "acceleration along the guide."
        ),
        approach=(
            "The carriage's motion is simple only on the table, where it is a sine along a straight line, and "
            "the table's motion is simple only as a rotation about its centre plus the cart's shaking. So we "
            "attach the moving frame $xyz$ to the table with its origin at the centre $O$ and use the "
            "moving-frame formula, which needs only $\\bar\\omega$, $\\bar\\alpha$, $\\bar a_O$ and the motion "
            "seen on the table. Writing the floor position of the carriage and differentiating it twice would "
            "give the same vector, but as one long expression in which the five physical effects cannot be "
            "told apart; we keep that route for the check."
        ),
        check=(
            "The carriage's floor position $\\bar r_P = \\bar r_O + [R]\\{r\\}_{xyz}$ is composed directly from "
            "the cart, the table's attitude and the guide coordinate, with no derivatives. The last step "
            "differences it twice in time with a fourth-order formula and prints the result beside the sum of "
            "the five terms: they agree to about nine significant figures, the accuracy of the difference."
        ),
        what_if=(
            "Set the **slider amplitude** to 0, so the carriage stays put in its guide: the Coriolis and "
            "relative terms vanish and the carriage accelerates like any point of the table. Then raise the "
            "**spin-up** $\\alpha_0$: the $\\bar\\alpha\\times\\bar r$ arrow appears, tangent to the "
            "circle that point rides on. Finally set the **cart amplitude** and frequency above zero and watch "
            "$\\bar a_O$ join the head-to-tail chain of arrows in the scene, the same for every point of the table."
        ),
    ),
)
