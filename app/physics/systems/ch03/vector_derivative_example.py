"""Worked example ``turret-boom-tip-velocity``: the rate of one vector seen from the ground and from a turning turret.

The system is :mod:`app.physics.systems.ch03.vector_derivative` (the lesson's scene), read as a telescoping camera
boom on a turret: the turret (frame xyz) turns at Ω about the fixed axis ``n = (sin β, 0, cos β)``; the boom
``A`` runs from its pivot, fixed on the turret's axis, to its tip, with length ``L(t) = L₀ + a sin 2πft``, elevation
``e`` above the turret's xy plane and azimuth ``ψ = ψ̇ t`` on the turret. The pivot does not move, so the tip's
velocity over the ground is ``(dA/dt)_fixed = (dA/dt)_rel + ω × A`` (m/s, XYZ components).

The instant is the scene's: ``t = time_s`` modulo ``replay_s`` (the scene replays its motion from t = 0).
Inputs are refused as the scene refuses them (a stretch at least as long as the boom: ParameterError).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch03.vector_derivative import PARAMETERS, VectorMotion

#: Step (s) of the fourth-order central difference in the check: its truncation error h⁴|A⁽⁵⁾|/30 is below 1e-10 of
#: the rates at the default motion, its round-off about ε|A|/h ≈ 2e-13 m/s.
DIFFERENCE_STEP_S = 1e-3


def _check(values: Mapping[str, Any]) -> None:
    """The scene's own refusals (the stretch must be shorter than the boom)."""
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
            "Instant t at which the rates are worked out (the scene's instant)",
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
    motion = VectorMotion.from_params(inputs)
    t = float(inputs["time_s"]) % float(inputs["replay_s"])
    rates = motion.rates(np.array([t]))
    omega = motion.omega_world_rad_s
    w = 2.0 * math.pi * motion.stretch_frequency_hz
    length = motion.length_m + motion.stretch_amplitude_m * math.sin(w * t)
    length_rate = motion.stretch_amplitude_m * w * math.cos(w * t)
    psi = motion.relative_turn_rate_rad_s * t
    A_frame, A_frame_rate = rates.vector_frame_m[0], rates.rate_frame_m_s[0]
    R = motion.attitude(np.array([t]))[0]
    A = rates.vector_world_m[0]
    relative = rates.terms_m_s["relative"][0]
    transport = rates.terms_m_s["transport"][0]
    fixed = rates.terms_m_s["fixed"][0]

    h = DIFFERENCE_STEP_S
    times = t + h * np.array([-2.0, -1.0, 1.0, 2.0])
    A_near = motion.vector_world(times)
    difference = (A_near[0] - 8.0 * A_near[1] + 8.0 * A_near[2] - A_near[3]) / (12.0 * h)
    steps = (
        Step(
            "The instant and the turret's angular velocity",
            r"t = t_{\rm shown} \bmod T_{\rm replay},\quad \bar\omega = \Omega\,\bar n = "
            r"\Omega\,(\sin\beta\,\bar I + \cos\beta\,\bar K)",
            {"t": t, "omega": omega},
            {"t": "s", "omega": "rad/s"},
        ),
        Step(
            "The boom on the turret: its components and their rates, as a rider on the turret writes them",
            r"L = L_0 + a\sin 2\pi f t,\quad \psi = \dot\psi\,t,\quad "
            r"\{A\}_{xyz} = L\,(\cos e\cos\psi,\ \cos e\sin\psi,\ \sin e),\quad "
            r"\frac{d\{A\}_{xyz}}{dt} = \frac{\dot L}{L}\{A\}_{xyz} + "
            r"L\dot\psi\,(-\cos e\sin\psi,\ \cos e\cos\psi,\ 0)",
            {"L": length, "L_dot": length_rate, "psi": math.degrees(psi), "A_xyz": A_frame, "dA_xyz": A_frame_rate},
            {"L": "m", "L_dot": "m/s", "psi": "deg", "A_xyz": "m", "dA_xyz": "m/s"},
        ),
        Step(
            "Both into fixed components with the turret's attitude",
            r"[R] = [I] + \sin\Omega t\,[\tilde n] + (1-\cos\Omega t)\,[\tilde n]^2,\quad "
            r"\bar A = [R]\{A\}_{xyz},\quad \left(\frac{d\bar A}{dt}\right)_{\rm rel} = [R]\,\frac{d\{A\}_{xyz}}{dt}",
            {"R": R, "A": A, "dA_rel": relative},
            {"R": "", "A": "m", "dA_rel": "m/s"},
        ),
        Step(
            "What the turning of the turret adds",
            r"\bar\omega\times\bar A",
            {"omega_x_A": transport},
            {"omega_x_A": "m/s"},
        ),
        Step(
            "The tip's velocity over the ground",
            r"\left(\frac{d\bar A}{dt}\right)_{XYZ} = \left(\frac{d\bar A}{dt}\right)_{\rm rel} + "
            r"\bar\omega\times\bar A,\quad v_{\rm tip} = \left|\left(\frac{d\bar A}{dt}\right)_{XYZ}\right|",
            {"dA_fixed": fixed, "v_tip": float(np.linalg.norm(fixed))},
            {"dA_fixed": "m/s", "v_tip": "m/s"},
        ),
        Step(
            "Check: both observers agree on how fast the boom lengthens, and differencing A gives the same rate",
            r"\frac{\bar A\cdot(d\bar A/dt)_{XYZ}}{|\bar A|} = \dot L \ \ (\text{because } \bar\omega\times\bar A"
            r"\perp\bar A),\quad \frac{\bar A(t-2h) - 8\bar A(t-h) + 8\bar A(t+h) - \bar A(t+2h)}{12h}",
            {
                "L_dot": length_rate,
                "A_dot_dA_over_A": float(A @ fixed) / float(np.linalg.norm(A)),
                "dA_fixed": fixed,
                "dA_differenced": difference,
                "h": h,
            },
            {"L_dot": "m/s", "A_dot_dA_over_A": "m/s", "dA_fixed": "m/s", "dA_differenced": "m/s", "h": "s"},
        ),
    )
    outputs = {
        "t_s": t,
        "omega_rad_s": omega,
        "A_m": A,
        "dA_relative_m_s": relative,
        "omega_cross_A_m_s": transport,
        "dA_fixed_m_s": fixed,
        "tip_speed_m_s": float(np.linalg.norm(fixed)),
        "length_rate_m_s": length_rate,
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="turret-boom-tip-velocity",
    title="A telescoping boom on a turning turret: the tip's velocity from the ground and from the turret",
    chapter=3,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "t_s": "s",
        "omega_rad_s": "rad/s",
        "A_m": "m",
        "dA_relative_m_s": "m/s",
        "omega_cross_A_m_s": "m/s",
        "dA_fixed_m_s": "m/s",
        "tip_speed_m_s": "m/s",
        "length_rate_m_s": "m/s",
    },
    section="3.3",
    story=ExampleStory(
        situation=(
            "A survey vehicle parked on a slope carries a camera boom on a turret. The turret turns at "
            "$\\Omega = 0.8$ rad/s about its own axis, which leans $\\beta = 20°$ from the vertical because of "
            "the slope. On the turret the boom slews at $\\dot\\psi = 0.5$ rad/s, is raised $e = 30°$ and "
            "telescopes in and out, $L = 1.0 + 0.3\\sin(2\\pi\\cdot 0.2\\,t)$ m. The boom's pivot sits on the "
            "turret's axis and does not move."
        ),
        wanted=(
            "At the instant $t$ (1.5 s by default), the velocity of the boom tip over the ground, that is the "
            "rate of the vector $\\bar A$ from the pivot to the tip as seen from the fixed frame, its speed, and "
            "how much of it the turret's turning contributes on top of what a rider on the turret sees."
        ),
        approach=(
            "The boom is described most simply on the turret, where its length, slew angle and elevation "
            "are three plain functions of time; so we differentiate its turret components, which is the rate a "
            "rider sees, and add $\\bar\\omega\\times\\bar A$ for the turning of the turret's unit vectors. "
            "Since the turret turns about a fixed axis at a steady rate, $\\bar\\omega$ is simply $\\Omega\\bar n$. "
            "The alternative, writing $\\bar A$ in ground components through the rotation matrix and "
            "differentiating every entry of $[R(t)]$, reaches the same vector with a page of product-rule "
            "algebra and hides which part comes from which motion."
        ),
        check=(
            "Two checks. First, $\\bar\\omega\\times\\bar A$ is perpendicular to $\\bar A$, so it cannot change "
            "the boom's length: the component of the ground rate along $\\bar A$ must equal $\\dot L$, the "
            "telescoping speed the rider measures. Second, a fourth-order central difference of $\\bar A(t)$, "
            "composed from the attitude and the turret components with no derivative taken, must reproduce "
            "the formula's vector to about ten significant figures."
        ),
        what_if=(
            "Set the **stretch** $a$ and the **turn in the frame** $\\dot\\psi$ to zero: the boom is then fixed "
            "on the turret, the rider's rate vanishes and the ground rate is $\\bar\\omega\\times\\bar A$ alone, "
            "square to both $\\bar\\omega$ and the boom. In the scene the relative arrow shrinks to nothing and "
            "the other two coincide. Then bring the stretch back and set the **frame rate** Ω to zero instead: "
            "the turret stands still, $\\bar\\omega\\times\\bar A$ vanishes and both observers see the same rate."
        ),
    ),
)
