"""Worked example ``free-axisymmetric-precession``: a spinning cylindrical probe coasts with a wobble.

The body is axisymmetric (transverse moment ``I_t``, axial moment ``I_a`` about its centre of mass G) and no moment
acts about G. Frames as in :mod:`app.physics.systems.ch10.torque_free_axisymmetric`: the fixed ``XYZ`` with Z along
the angular momentum ``H_G``, body axes ``xyz`` with z along the symmetry axis ``k``; the attitude is the 3-1-3
sequence (precession φ, nutation θ, spin ψ). Given the spin ω₃ (the body component of ω along k) and the nutation θ
(the constant angle between k and ``H_G``), the example finds the transverse angular velocity, ``H_G``, the
precession and relative spin rates, the two cones and the energy, using the project's closed form
:class:`~app.physics.systems.ch10.torque_free_axisymmetric.AxisymmetricFreeMotion`. Its check assembles ω a second
way, from the Euler-angle rates, and computes the kinetic energy both as ½ ω·[I]ω and as ½ H_G·ω.

The inputs carry the names of the scene ``torque-free-axisymmetric``'s controls, so that lesson drives them. The
default body is a uniform cylinder of 30 kg, 0.33 m across and 0.57 m long (I_a = 0.4 kg·m², I_t = 1.0 kg·m²), a
small spin-stabilised probe; ``I_a > 2 I_t`` is no real body and is refused.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch10.torque_free_axisymmetric import AxisymmetricFreeMotion, check_inputs


def _check(values: Mapping[str, Any]) -> None:
    check_inputs(
        I_transverse=values["I_transverse"],
        I_axial=values["I_axial"],
        spin_rad_s=values["spin_rad_s"],
        nutation_deg=values["nutation_deg"],
    )


INPUTS = ParameterSet(
    (
        Parameter(
            "I_transverse",
            "kg·m²",
            1.0,
            0.5,
            2.0,
            "Moment of inertia I_t about a transverse axis through the centre of mass",
            "I_t",
            step=0.01,
        ),
        Parameter(
            "I_axial",
            "kg·m²",
            0.4,
            0.02,
            1.0,
            "Moment of inertia I_a about the symmetry axis (at most 2 I_t)",
            "I_a",
            step=0.01,
        ),
        Parameter(
            "spin_rad_s", "rad/s", 3.0, 0.1, 5.0, "Spin ω₃: the body's angular velocity along its symmetry axis", "ω₃"
        ),
        Parameter(
            "nutation_deg", "deg", 25.0, 0.0, 70.0, "Nutation θ: the angle between the symmetry axis and H_G", "θ"
        ),
    ),
    check=_check,
)


def motion(inputs: Mapping[str, Any]) -> AxisymmetricFreeMotion:
    """The closed-form motion for the inputs (raises ParameterError for a body that cannot exist)."""
    _check(inputs)
    return AxisymmetricFreeMotion(
        I_transverse_kg_m2=float(inputs["I_transverse"]),
        I_axial_kg_m2=float(inputs["I_axial"]),
        spin_rad_s=float(inputs["spin_rad_s"]),
        nutation_rad=math.radians(float(inputs["nutation_deg"])),
    )


def solve(inputs: Mapping[str, Any]) -> Solution:
    body = motion(inputs)
    I_t, I_a, w3 = body.I_transverse_kg_m2, body.I_axial_kg_m2, body.spin_rad_s
    theta = body.nutation_rad
    w_t = I_a * w3 * math.tan(theta) / I_t  # transverse angular velocity from tan θ = I_t ω_t / (I_a ω₃)
    H = body.angular_momentum_kg_m2_s
    phi_dot, psi_dot = body.precession_rate_rad_s, body.spin_rate_rad_s
    lam = body.body_frame_precession_rate_rad_s
    beta, gamma = body.body_cone_half_angle_rad, body.space_cone_half_angle_rad
    # Second method: ω = φ̇ K + ψ̇ k, resolved on k and across it (body axes with ω_t along x at this instant).
    w3_from_rates = phi_dot * math.cos(theta) + psi_dot
    wt_from_rates = phi_dot * math.sin(theta)
    omega = np.array([w_t, 0.0, w3])
    T_inertia = 0.5 * float(omega @ (np.array([I_t, I_t, I_a]) * omega))
    T_momentum = 0.5 * H * (phi_dot + psi_dot * math.cos(theta))  # ½ H K·(φ̇ K + ψ̇ k)
    steps = (
        Step(
            "Angular momentum along Z: its body components fix the transverse angular velocity",
            r"\bar H_G = I_t\omega_t\,\bar\imath + I_a\omega_3\,\bar k = H\bar K,\quad \tan\theta = "
            r"\frac{I_t\,\omega_t}{I_a\,\omega_3}\ \Rightarrow\ \omega_t = \frac{I_a}{I_t}\,\omega_3\tan\theta,"
            r"\quad H = \frac{I_a\,\omega_3}{\cos\theta}",
            {"ω_3": w3, "θ": math.degrees(theta), "ω_t": w_t, "H": H},
            {"ω_3": "rad/s", "θ": "deg", "ω_t": "rad/s", "H": "kg·m²/s"},
        ),
        Step(
            "Euler's equations with I_x = I_y: ω₃ is constant, so θ is constant; the precession rate",
            r"I_a\dot\omega_3 = 0,\qquad \omega_t = \dot\phi\sin\theta\ \Rightarrow\ \dot\phi = \frac{H}{I_t},"
            r"\qquad T_{\rm prec} = \frac{2\pi}{\dot\phi}",
            {"φ̇": phi_dot, "T_prec": body.precession_period_s},
            {"φ̇": "rad/s", "T_prec": "s"},
        ),
        Step(
            "Spin relative to the precessing plane, and the rate at which ω circles k as seen from the body",
            r"\dot\psi = \omega_3 - \dot\phi\cos\theta = \frac{I_t - I_a}{I_t}\,\omega_3,\qquad \lambda = "
            r"\frac{I_a - I_t}{I_t}\,\omega_3 = -\dot\psi",
            {"ψ̇": psi_dot, "λ": lam},
            {"ψ̇": "rad/s", "λ": "rad/s"},
        ),
        Step(
            f"Body cone rolling on the space cone ({body.sense} precession)",
            r"\tan\beta = \frac{\omega_t}{\omega_3} = \frac{I_a}{I_t}\tan\theta\ \ (\bar\omega\text{ from }\bar k),"
            r"\qquad \gamma = |\theta - \beta|\ \ (\bar\omega\text{ from }\bar H_G)",
            {"I_a/I_t": body.inertia_ratio, "β": math.degrees(beta), "γ": math.degrees(gamma)},
            {"I_a/I_t": "", "β": "deg", "γ": "deg"},
        ),
        Step(
            "Check: ω from the Euler-angle rates, and the energy two ways",
            r"\bar\omega = \dot\phi\,\bar K + \dot\psi\,\bar k:\ \ \omega_3 = \dot\phi\cos\theta + \dot\psi,\ \ "
            r"\omega_t = \dot\phi\sin\theta;\qquad T = \tfrac12\,\bar\omega\cdot[I]\bar\omega = "
            r"\tfrac12\,H\bar K\cdot(\dot\phi\bar K + \dot\psi\bar k) = \tfrac12 H(\dot\phi + \dot\psi\cos\theta)",
            {
                "ω_3 (given)": w3,
                "φ̇ cos θ + ψ̇": w3_from_rates,
                "ω_t (step 1)": w_t,
                "φ̇ sin θ": wt_from_rates,
                "½ ω·[I]ω": T_inertia,
                "½ H (φ̇ + ψ̇ cos θ)": T_momentum,
            },
            {
                "ω_3 (given)": "rad/s",
                "φ̇ cos θ + ψ̇": "rad/s",
                "ω_t (step 1)": "rad/s",
                "φ̇ sin θ": "rad/s",
                "½ ω·[I]ω": "J",
                "½ H (φ̇ + ψ̇ cos θ)": "J",
            },
        ),
    )
    outputs = {
        "transverse_rate_rad_s": w_t,
        "angular_momentum_kg_m2_s": H,
        "precession_rate_rad_s": phi_dot,
        "precession_period_s": body.precession_period_s,
        "relative_spin_rate_rad_s": psi_dot,
        "body_frame_rate_rad_s": lam,
        "body_cone_deg": math.degrees(beta),
        "space_cone_deg": math.degrees(gamma),
        "energy_J": body.energy_J,
        "sense": body.sense,
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="free-axisymmetric-precession",
    title="A spinning probe coasts with a wobble: torque-free precession",
    chapter=10,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "transverse_rate_rad_s": "rad/s",
        "angular_momentum_kg_m2_s": "kg·m²/s",
        "precession_rate_rad_s": "rad/s",
        "precession_period_s": "s",
        "relative_spin_rate_rad_s": "rad/s",
        "body_frame_rate_rad_s": "rad/s",
        "body_cone_deg": "deg",
        "space_cone_deg": "deg",
        "energy_J": "J",
        "sense": "",
    },
    section="10.1",
    story=ExampleStory(
        situation=(
            "A small probe, a uniform cylinder of 30 kg, 0.33 m across and 0.57 m long, has been released from its "
            "carrier spinning about its long axis at $\\omega_3 = 3$ rad/s, but with a wobble: its axis is tilted "
            "$\\theta = 25°$ from its angular momentum. About its centre of mass $I_a = 0.4$ kg·m² along the axis "
            "and $I_t = 1.0$ kg·m² across it. No moment acts about the centre of mass."
        ),
        wanted=(
            "How fast the axis swings round its cone in space, how fast the probe turns about its own axis "
            "relative to that swing, the half-angles of the body and space cones, the angular momentum and the "
            "kinetic energy, and whether the precession is direct or retrograde."
        ),
        approach=(
            "With no moment about $G$, $\\bar H_G$ is fixed in space, so we point $Z$ along it and describe the "
            "attitude by the 3-1-3 Euler angles: precession $\\phi$ about $Z$, nutation $\\theta$, spin $\\psi$. "
            "Euler's equations in body axes show at once that $\\omega_3$ is constant when $I_x = I_y$; then the "
            "body components of $\\bar H_G$ tie $\\theta$ to the transverse rate, and the Euler-angle rates follow "
            "by algebra, with no integration. Integrating Euler's equations numerically would give the same motion "
            "as a list of numbers but hide the two constant rates and the rolling cones that explain it."
        ),
        check=(
            "The angular velocity must be the sum of the two Euler-angle rates, $\\dot\\phi$ about $\\bar K$ and "
            "$\\dot\\psi$ about $\\bar k$ ($\\dot\\theta = 0$). The check resolves that sum on the symmetry axis and "
            "across it and sets it beside $\\omega_3$ and $\\omega_t$ from the first step. It also computes the "
            "kinetic energy as $\\frac12\\bar\\omega\\cdot[I]\\bar\\omega$ and as "
            "$\\frac12\\bar H_G\\cdot\\bar\\omega$ with $\\bar H_G = H\\bar K$ and $\\bar\\omega$ from the "
            "rates, $\\frac12 H(\\dot\\phi + \\dot\\psi\\cos\\theta)$: for any rigid body the two must agree."
        ),
        what_if=(
            "Move **I_a** from 0.4 up to 1.0 kg·m², making the cigar rounder. $\\dot\\psi$ shrinks in proportion "
            "to $I_t - I_a$, the space cone narrows, and at $I_a = I_t$ it becomes a line: $\\bar\\omega$ lies along "
            "$\\bar H_G$ and the body simply turns about it. Then lower **I_t** to 0.6 kg·m² so that the body is "
            "a lentil: $\\dot\\psi$ turns negative, the sense reads *retrograde*, and in the scene the body cone now "
            "rolls round a space cone that sits inside it, instead of rolling on the space cone's outside."
        ),
    ),
)
