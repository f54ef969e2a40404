"""Worked example ``collar-on-arm-path-variables`` (section 2.4): from the arm's description to the collar's path
variables.

Frame: the fixed frame XYZ, +Z up; the arm turns about Z through the pivot O in the plane z = 0 (the model of
:mod:`~app.physics.systems.ch02.rotating_arm`): θ = Ω t + ½ α t², and the collar's place along the arm is
r = r₀ + b sin(ω_c t). Lengths in m, angles in rad, time in s. The unit vectors ride on the arm,
e_r = (cos θ, sin θ, 0), e_θ = (−sin θ, cos θ, 0), and e_z = K completes the triad::

    v = ṙ e_r + r θ̇ e_θ,    a = (r̈ − r θ̇²) e_r + (r θ̈ + 2 ṙ θ̇) e_θ,
    a_t = v·a/v,   a_n = |v × a|/v = |v_r a_θ − v_θ a_r|/v,   κ = a_n/v².

The polar outputs are components on (e_r, e_θ, e_z) at the instant (the last is 0: the motion stays in z = 0).

The check is a second method: differentiating x = r cos θ, y = r sin θ on XYZ with the chain rule must give the same
v and a, and a_t² + a_n² = |a|².

Refused (ParameterError): a collar that would slide off the arm (the scene's own rule, naming ``collar_amplitude_m``),
and an instant at which the collar is at rest, where no tangent exists (naming ``t_s``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch02.rotating_arm import PARAMETERS as SCENE_PARAMETERS
from app.physics.systems.ch02.rotating_arm import ArmState, RotatingArm
from app.physics.systems.ch02.rotating_arm import _check as _collar_stays_on_arm

#: A speed at most this fraction of the motion's own scale (|ṙ| + |r θ̇| + its rates × 1 s) is the collar at rest:
#: the closed forms are exact to a few ulps (1e-16) of it, and the smallest speed the controls can give at an instant
#: where the collar moves is far above 1e-12 of it.
AT_REST_RTOL = 1e-12
#: An a_n at most this fraction of |a| is a straight path at that instant (κ = 0, no normal).
STRAIGHT_RTOL = 1e-12


def _state(values: Mapping[str, Any]) -> ArmState:
    _collar_stays_on_arm(values)
    state = RotatingArm.from_params(values).at(values["t_s"])
    speed = float(np.linalg.norm(state.velocity_m_s[0]))
    scale = (
        abs(float(state.r_m[0])) * (abs(float(state.theta_dot_rad_s[0])) + 1.0)
        + abs(float(state.r_dot_m_s[0]))
        + abs(float(state.r_ddot_m_s2[0]))
    )
    if speed <= AT_REST_RTOL * scale or speed == 0.0:
        raise ParameterError(
            "t_s",
            f"at t = {values['t_s']:g} s the collar is at rest (ṙ = 0 and r θ̇ = 0): it has no direction of travel, "
            "so the tangent, a_t and a_n are undefined; set the arm turning, or the collar sliding",
        )
    return state


def _check(values: Mapping[str, Any]) -> None:
    _state(values)


INPUTS = ParameterSet(
    (
        *SCENE_PARAMETERS.parameters,
        Parameter("t_s", "s", 0.5, 0.0, 12.57, "Instant at which the collar's motion is wanted", "t", step=0.01),
    ),
    check=_check,
)


def solve(inputs: Mapping[str, Any]) -> Solution:
    s = _state(inputs)
    theta, theta_dot, theta_ddot = (float(x[0]) for x in (s.theta_rad, s.theta_dot_rad_s, s.theta_ddot_rad_s2))
    r, r_dot, r_ddot = (float(x[0]) for x in (s.r_m, s.r_dot_m_s, s.r_ddot_m_s2))
    sliding, centripetal = float(s.sliding_m_s2[0]), float(s.centripetal_m_s2[0])
    angular, coriolis = float(s.angular_m_s2[0]), float(s.coriolis_m_s2[0])
    v_r, v_theta = r_dot, r * theta_dot
    a_r, a_theta = sliding + centripetal, angular + coriolis
    speed = math.hypot(v_r, v_theta)
    a_size = math.hypot(a_r, a_theta)
    a_t = (v_r * a_r + v_theta * a_theta) / speed
    a_n = abs(v_r * a_theta - v_theta * a_r) / speed
    straight = a_n <= STRAIGHT_RTOL * a_size
    if straight:
        a_n = 0.0
    kappa = a_n / speed**2
    c, sn = math.cos(theta), math.sin(theta)
    v_polar = np.array([v_r * c - v_theta * sn, v_r * sn + v_theta * c, 0.0])
    a_polar = np.array([a_r * c - a_theta * sn, a_r * sn + a_theta * c, 0.0])
    v_chain = np.array([r_dot * c - r * theta_dot * sn, r_dot * sn + r * theta_dot * c, 0.0])
    a_chain = np.array(
        [
            r_ddot * c - 2.0 * r_dot * theta_dot * sn - r * theta_ddot * sn - r * theta_dot**2 * c,
            r_ddot * sn + 2.0 * r_dot * theta_dot * c + r * theta_ddot * c - r * theta_dot**2 * sn,
            0.0,
        ]
    )
    a_t_chain = float(v_chain @ a_chain) / float(np.linalg.norm(v_chain))
    a_n_chain = float(np.linalg.norm(np.cross(v_chain, a_chain))) / float(np.linalg.norm(v_chain))
    e_t = np.array([v_r, v_theta, 0.0]) / speed
    curvature_values: dict[str, Any] = {"kappa": kappa}
    curvature_units = {"kappa": "1/m"}
    if not straight:
        e_n = (np.array([a_r, a_theta, 0.0]) - a_t * e_t) / a_n
        curvature_values |= {"rho": 1.0 / kappa, "e_n (on e_r, e_theta, e_z)": e_n}
        curvature_units |= {"rho": "m", "e_n (on e_r, e_theta, e_z)": ""}
    steps = (
        Step(
            "The arm's angle and the collar's place along it, with their rates",
            r"\theta = \Omega t + \tfrac12\alpha t^2,\ \ \dot\theta = \Omega + \alpha t,\ \ \ddot\theta = \alpha;"
            r"\qquad r = r_0 + b\sin\omega_c t,\ \ \dot r = b\omega_c\cos\omega_c t,\ \ "
            r"\ddot r = -b\omega_c^2\sin\omega_c t",
            {
                "theta": theta,
                "theta_dot": theta_dot,
                "theta_ddot": theta_ddot,
                "r": r,
                "r_dot": r_dot,
                "r_ddot": r_ddot,
            },
            {
                "theta": "rad",
                "theta_dot": "rad/s",
                "theta_ddot": "rad/s²",
                "r": "m",
                "r_dot": "m/s",
                "r_ddot": "m/s²",
            },
        ),
        Step(
            "Velocity on the arm's unit vectors",
            r"\bar v = \dot r\,\bar e_r + r\dot\theta\,\bar e_\theta,\qquad v = \sqrt{\dot r^2 + (r\dot\theta)^2}",
            {"v_r": v_r, "v_theta": v_theta, "v": speed},
            {"v_r": "m/s", "v_theta": "m/s", "v": "m/s"},
        ),
        Step(
            "Acceleration: the four terms",
            r"a_r = \underbrace{\ddot r}_{\rm sliding} \underbrace{- r\dot\theta^2}_{\rm centripetal},\qquad "
            r"a_\theta = \underbrace{r\ddot\theta}_{\rm arm's\ \alpha} + \underbrace{2\dot r\dot\theta}_{\rm Coriolis}",
            {
                "r_ddot": sliding,
                "-r theta_dot²": centripetal,
                "r theta_ddot": angular,
                "2 r_dot theta_dot": coriolis,
                "a_r": a_r,
                "a_theta": a_theta,
            },
            {
                "r_ddot": "m/s²",
                "-r theta_dot²": "m/s²",
                "r theta_ddot": "m/s²",
                "2 r_dot theta_dot": "m/s²",
                "a_r": "m/s²",
                "a_theta": "m/s²",
            },
        ),
        Step(
            "Path variables: dot and cross products need no common description",
            r"a_t = \frac{v_r a_r + v_\theta a_\theta}{v},\qquad a_n = \frac{|v_r a_\theta - v_\theta a_r|}{v}",
            {"a_t": a_t, "a_n": a_n},
            {"a_t": "m/s²", "a_n": "m/s²"},
            scales={"a_t": a_size, "a_n": a_size},
        ),
        Step(
            "Curvature of the collar's path, and where its centre lies",
            r"\kappa = \frac{a_n}{v^2},\qquad \rho = \frac1\kappa,\qquad "
            r"\bar e_n = \frac{\bar a - a_t\,\bar e_t}{a_n},\quad \bar e_t = \frac{\bar v}{v}",
            curvature_values,
            curvature_units,
        ),
        Step(
            "Check: differentiating x = r cos θ, y = r sin θ directly gives the same v and a",
            r"\dot x = \dot r\cos\theta - r\dot\theta\sin\theta,\ \ \ddot x = (\ddot r - r\dot\theta^2)\cos\theta "
            r"- (r\ddot\theta + 2\dot r\dot\theta)\sin\theta,\ \ \ldots;\qquad \sqrt{a_t^2 + a_n^2} = |\bar a|",
            {
                "v (polar terms)": v_polar,
                "v (chain rule)": v_chain,
                "a (polar terms)": a_polar,
                "a (chain rule)": a_chain,
                "a_t (chain rule)": a_t_chain,
                "a_n (chain rule)": a_n_chain,
                "sqrt(a_t² + a_n²)": math.hypot(a_t, a_n),
                "|a|": a_size,
            },
            {
                "v (polar terms)": "m/s",
                "v (chain rule)": "m/s",
                "a (polar terms)": "m/s²",
                "a (chain rule)": "m/s²",
                "a_t (chain rule)": "m/s²",
                "a_n (chain rule)": "m/s²",
                "sqrt(a_t² + a_n²)": "m/s²",
                "|a|": "m/s²",
            },
            scales={"a_t (chain rule)": a_size, "a_n (chain rule)": a_size},
        ),
    )
    outputs = {
        "velocity_polar_m_s": np.array([v_r, v_theta, 0.0]),
        "acceleration_polar_m_s2": np.array([a_r, a_theta, 0.0]),
        "coriolis_m_s2": coriolis,
        "speed_m_s": speed,
        "a_tangential_m_s2": a_t,
        "a_normal_m_s2": a_n,
        "curvature_1_m": kappa,
        "velocity_m_s": v_polar,
        "acceleration_m_s2": a_polar,
    }
    return Solution(
        outputs=outputs,
        steps=steps,
        output_scales={"a_tangential_m_s2": a_size, "a_normal_m_s2": a_size, "acceleration_polar_m_s2": a_size},
    )


EXAMPLE = WorkedExample(
    id="collar-on-arm-path-variables",
    title="The gripper of an R–θ robot: from the arm's motion to the path variables",
    chapter=2,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "velocity_polar_m_s": "m/s",
        "acceleration_polar_m_s2": "m/s²",
        "coriolis_m_s2": "m/s²",
        "speed_m_s": "m/s",
        "a_tangential_m_s2": "m/s²",
        "a_normal_m_s2": "m/s²",
        "curvature_1_m": "1/m",
        "velocity_m_s": "m/s",
        "acceleration_m_s2": "m/s²",
    },
    section="2.4",
    story=ExampleStory(
        situation=(
            "A pick-and-place robot of the $R$–$\\theta$ kind has an arm that turns in a horizontal plane about a "
            "vertical axis through its pivot, at $\\dot\\theta = \\Omega + \\alpha t$ with $\\Omega = 1$ rad/s and "
            "$\\alpha = 0$. Its gripper is a collar that slides in and out along the arm, "
            "$r = r_0 + b\\sin\\omega_c t$ with $r_0 = 0.8$ m, $b = 0.6$ m and $\\omega_c = 1.5$ rad/s. We "
            "look at the gripper at $t = 0.5$ s."
        ),
        wanted=(
            "The gripper's velocity and acceleration on the arm's unit vectors, with each of the four "
            "acceleration terms named, and then its path variables: the speed, the tangential and normal "
            "accelerations $a_t$ and $a_n$, the curvature of its path and the direction of the principal normal."
        ),
        approach=(
            "The data describe motion relative to the arm, so we put the unit vectors on the arm: "
            "$\\bar e_r$ along it and $\\bar e_\\theta$ across it. They turn at $\\dot\\theta$, which gives the "
            "polar formulas at once, each term with a meaning. The question is in path variables, and the bridge "
            "is that dot and cross products come out the same on any orthonormal triad, so $a_t$ and $a_n$ follow "
            "from the polar components without ever writing $x(t)$ and $y(t)$. Starting from $x = r\\cos\\theta$, "
            "$y = r\\sin\\theta$ also works, but the second derivatives grow to eight terms and the Coriolis "
            "part hides among them."
        ),
        check=(
            "The last step does take that longer road: it differentiates $x = r\\cos\\theta$ and "
            "$y = r\\sin\\theta$ twice with the chain rule on the fixed axes and compares the result with the "
            "polar components put back on $XYZ$, and recomputes $a_t$ and $a_n$ from it. Both must agree, as "
            "must $\\sqrt{a_t^2 + a_n^2}$ and $|\\bar a|$, because the split into $a_t$ and $a_n$ only rotates the "
            "same vector onto other axes."
        ),
        what_if=(
            "Move **ω_c**, the gripper's in-and-out frequency, from 1.5 rad/s to 3 rad/s. At $t = 0.5$ s the "
            "gripper is then near the end of its stroke and braking hard: the sliding term $\\ddot r$ grows from "
            "−0.92 to −5.39 m/s² while the Coriolis term $2\\dot r\\dot\\theta$ falls from 1.32 to 0.25 m/s². "
            "$a_n$ rises from 2.50 to 6.78 m/s² and the radius of curvature shrinks from 0.76 m to 0.29 m. In "
            "the scene, watch the orange sliding arrow and the teal Coriolis arrow in the red chain."
        ),
    ),
)
