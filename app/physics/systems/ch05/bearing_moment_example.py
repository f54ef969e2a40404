"""Worked example ``skewed-rotor-bearings``: the rate of change of angular momentum of a body spun steadily on a
shaft that is not a principal axis, and the bearing forces that supply it.

The system, frame and names are those of :mod:`app.physics.systems.ch05.angular_momentum` (the shaft is the world Z
axis through G, bearing A at Z = −span/2 and B at +span/2, the body turned by ``tilt`` about its own x axis, ω = Ω Z),
and the inputs are that scene's parameters, so the lesson's controls drive the example. The instant solved is t = 0,
when the body's x axis lies along world X. Vectors are world [X, Y, Z] components (kg·m²/s, N·m, N). Gravity is left
out, as in the scene: on a vertical shaft the weight is an axial thrust and changes none of these moments. A constant
v_G (the particles view) changes nothing here either: the shaft's frame is then inertial too.

Every in-range combination is a possible motion, so nothing is refused beyond the ranges.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch05.angular_momentum import PARAMETERS, SHAFT_AXIS, ShaftSpin

INPUTS = PARAMETERS


def solve(inputs: Mapping[str, Any]) -> Solution:
    motion = ShaftSpin.from_params(inputs)
    body = motion.body
    spin, span = motion.spin_rate_rad_s, motion.bearing_span_m
    omega = motion.omega_rad_s
    tensor_world = body.inertia_world0_kg_m2
    h_g = tensor_world @ omega
    omega_body = body.mounting.T @ omega  # constant: the shaft is fixed in the body
    rate = np.cross(omega, h_g)  # δH/δt = 0
    h_across = float(math.hypot(h_g[0], h_g[1]))
    force_b = np.cross(rate, SHAFT_AXIS) / span
    force_a = -force_b
    couple = np.cross(0.5 * span * SHAFT_AXIS, force_b) + np.cross(-0.5 * span * SHAFT_AXIS, force_a)
    # Second method: Euler's form in the body's principal axes (x is the tilt axis, so only M_x survives).
    ixx, iyy, izz = np.diag(body.inertia_body_kg_m2)
    tilt = math.radians(inputs["tilt_deg"])
    euler_body = np.array([(izz - iyy) * omega_body[1] * omega_body[2], 0.0, 0.0])
    euler_closed_form = float((izz - iyy) * spin**2 * math.sin(tilt) * math.cos(tilt))
    euler_world = body.mounting @ euler_body
    moment_scale = float(np.linalg.norm(rate)) + abs(spin) ** 2 * float(np.trace(tensor_world))
    steps = (
        Step(
            "Angular momentum about G at t = 0 (world axes)",
            r"[I_G]_{XYZ} = R_x(\text{tilt})\,[I_G]_{xyz}\,R_x(\text{tilt})^{\mathsf T},\qquad "
            r"\bar H_G = [I_G]\,\Omega\bar K",
            {"I_G": tensor_world, "H_G": h_g},
            {"I_G": "kg·m²", "H_G": "kg·m²/s"},
        ),
        Step(
            "Seen from the body, ω does not change, so neither does H_G",
            r"\bar\omega_{xyz} = \Omega\,(0,\ \sin(\text{tilt}),\ \cos(\text{tilt})) \text{ constant}\ "
            r"\Rightarrow\ \frac{\delta\bar H_G}{\delta t} = [I_G]_{xyz}\frac{\delta\bar\omega}{\delta t} = \bar 0",
            {"omega_body": omega_body, "dH/dt (relative)": np.zeros(3)},
            {"omega_body": "rad/s", "dH/dt (relative)": "N·m"},
        ),
        Step(
            "The rate of H_G is the transport term alone: H_G sweeps a cone about the shaft",
            r"\dot{\bar H}_G = \frac{\delta\bar H_G}{\delta t} + \bar\omega\times\bar H_G = \bar\omega\times\bar H_G,"
            r"\qquad |\dot{\bar H}_G| = |\Omega|\,|\bar H_{G,\perp}|",
            {"H_G,perp": h_across, "dH_G/dt": rate, "|dH_G/dt|": float(np.linalg.norm(rate))},
            {"H_G,perp": "kg·m²/s", "dH_G/dt": "N·m", "|dH_G/dt|": "N·m"},
        ),
        Step(
            "The bearings supply that moment as a couple: two equal and opposite forces a span apart",
            r"(s\,\bar K)\times\bar F_B = \dot{\bar H}_G\ \Rightarrow\ \bar F_B = \frac{\dot{\bar H}_G\times\bar K}{s},"
            r"\quad \bar F_A = -\bar F_B,\qquad M_Z = \dot{\bar H}_G\cdot\bar K = 0\ \text{(no motor torque)}",
            {"s": span, "F_B": force_b, "F_A": force_a, "|F|": float(np.linalg.norm(force_b))},
            {"s": "m", "F_B": "N", "F_A": "N", "|F|": "N"},
        ),
        Step(
            "Check: Euler's form in the principal axes gives the same moment; the couple's moment equals it",
            r"M_x = (I_{zz} - I_{yy})\,\omega_y\omega_z = (I_{zz} - "
            r"I_{yy})\,\Omega^2\sin(\text{tilt})\cos(\text{tilt}),"
            r"\ M_y = M_z = 0;\qquad \bar r_B\times\bar F_B + \bar r_A\times\bar F_A = \dot{\bar H}_G",
            {
                "M_x (closed form)": euler_closed_form,
                "M (Euler, world)": euler_world,
                "dH_G/dt": rate,
                "couple": couple,
            },
            {"M_x (closed form)": "N·m", "M (Euler, world)": "N·m", "dH_G/dt": "N·m", "couple": "N·m"},
            scales={"M (Euler, world)": moment_scale, "dH_G/dt": moment_scale, "couple": moment_scale},
        ),
    )
    outputs = {
        "angular_momentum_G_kg_m2_s": h_g,
        "angular_momentum_rate_N_m": rate,
        "bearing_moment_N_m": float(np.linalg.norm(rate)),
        "bearing_force_B_N": force_b,
        "bearing_force_magnitude_N": float(np.linalg.norm(force_b)),
    }
    return Solution(
        outputs=outputs,
        steps=steps,
        output_scales={"angular_momentum_rate_N_m": moment_scale, "bearing_force_B_N": moment_scale / span},
    )


EXAMPLE = WorkedExample(
    id="skewed-rotor-bearings",
    title="A skewed rotor: the rate of change of H and the bearing forces it needs",
    chapter=5,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "angular_momentum_G_kg_m2_s": "kg·m²/s",
        "angular_momentum_rate_N_m": "N·m",
        "bearing_moment_N_m": "N·m",
        "bearing_force_B_N": "N",
        "bearing_force_magnitude_N": "N",
    },
    section="5.3",
    story=ExampleStory(
        situation=(
            "The 4 kg plate of section 5.1, 0.5 m by 0.4 m, is mounted through its centre of mass on a vertical "
            "shaft but tilted 30° about its own $x$ axis, and spun at a steady $\\Omega = 4$ rad/s. The shaft runs "
            "in two short bearings, $A$ below and $B$ above, $s = 0.8$ m apart and symmetric about $G$ (the default "
            "controls). The plate is statically balanced: $G$ is on the axis."
        ),
        wanted=(
            "How fast the plate's angular momentum $\\bar H_G$ changes, $\\dot{\\bar H}_G$, which is the moment "
            "the shaft must apply to it, and the forces the two bearings carry to supply that moment; also "
            "whether the motor must supply any torque to keep $\\Omega$ constant."
        ),
        approach=(
            "Euler's moment equation $\\sum\\bar M_G = \\dot{\\bar H}_G$ needs the rate seen from the fixed frame. "
            "$\\bar H_G = [I_G]\\bar\\omega$ is easiest on **body axes**, where the tensor is constant, so we "
            "differentiate there and add the axes' own turning: $\\dot{\\bar H}_G = \\delta\\bar H_G/\\delta t + "
            "\\bar\\omega\\times\\bar H_G$. The shaft is fixed in the body, so $\\bar\\omega$ has constant body "
            "components and the first term is zero; only the transport term is left. Writing $\\bar H_G(t)$ on "
            "world axes and differentiating would also work, but the tensor's world components change with the "
            "spin angle, so every entry would have to be differentiated."
        ),
        check=(
            "The check writes Euler's equations on the plate's principal axes. Because the tilt is a turn about "
            "the principal axis $x$, only $M_x = (I_{zz}-I_{yy})\\,\\Omega^2\\sin(\\text{tilt})\\cos(\\text{tilt})$ "
            "survives, a one-line closed form, and turned onto world axes it must equal $\\bar\\omega\\times\\bar "
            "H_G$. It also adds up the moments of the two bearing forces about $G$: the couple must reproduce "
            "$\\dot{\\bar H}_G$ exactly, or the forces are wrong."
        ),
        what_if=(
            "Move the **tilt** from 0° to 90°. The bearing moment is zero at 0° (the shaft along the plate's "
            "normal) and at 90° (along a side), both principal axes, and largest near 45°, following "
            "$\\sin\\cos$. Then double the **spin rate** $\\Omega$: the moment and the bearing forces grow four "
            "times, and in the scene the green $\\dot{\\bar H}_G$ and orange forces turn with the plate at the "
            "new rate."
        ),
    ),
)
