"""Worked example ``disk-on-turntable-point``: velocity and acceleration of a point on a disk spinning on a
turntable's shaft, by the two general equations, checked by treating the turntable as a moving frame.

The system, frame and names are those of :mod:`app.physics.systems.ch04.rigid_body_points` (world XYZ, +Z up, O the
shaft's bearing on the turntable's axis), and the inputs are that scene's parameters. The instant solved is t = 0 of
the scene: the shaft lies in the XZ plane, n̂ = (cos β, 0, sin β). Vectors are world [X, Y, Z] components.

Every in-range combination of the inputs is a possible motion (the shaft's elevation stays within ±75°), so nothing
is refused beyond the ranges.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch04.rigid_body_points import PARAMETERS, DiskOnTurntable

INPUTS = PARAMETERS
K = np.array([0.0, 0.0, 1.0])


def solve(inputs: Mapping[str, Any]) -> Solution:
    system = DiskOnTurntable.from_params(inputs)
    state = system.at(np.zeros(1))
    w1, w1_dot = system.turntable_rate_rad_s, system.turntable_acceleration_rad_s2
    w2, w2_dot = system.spin_rate_rad_s, system.spin_acceleration_rad_s2
    n_hat = state.center[0] / system.shaft_length_m
    r_a, r_ba = state.center[0], state.point_from_center[0]
    omega, alpha = state.angular_velocity[0], state.angular_acceleration[0]
    v_a, a_a = state.center_velocity[0], state.center_acceleration[0]
    w_x_r, v_b = state.relative_velocity[0], state.point_velocity[0]
    tangential, centripetal, a_b = (
        state.tangential_acceleration[0],
        state.centripetal_acceleration[0],
        state.point_acceleration[0],
    )
    # Second method: the turntable as a moving frame (rate ω₁K, acceleration ω̇₁K about the fixed point O). Seen
    # from it, B goes round the fixed shaft at ω₂ (speeding up at ω̇₂).
    r_b = r_a + r_ba
    v_rel = w2 * np.cross(n_hat, r_ba)
    a_rel = w2_dot * np.cross(n_hat, r_ba) + w2 * np.cross(n_hat, v_rel)
    frame_rate, frame_acceleration = w1 * K, w1_dot * K
    v_b_frame = v_rel + np.cross(frame_rate, r_b)
    a_b_frame = (
        a_rel
        + np.cross(frame_acceleration, r_b)
        + np.cross(frame_rate, np.cross(frame_rate, r_b))
        + 2.0 * np.cross(frame_rate, v_rel)
    )
    steps = (
        Step(
            "The shaft's direction, the centre A and the point B at t = 0",
            r"\bar n = (\cos\beta,\ 0,\ \sin\beta),\quad \bar r_{A/O} = L\,\bar n,\quad "
            r"\bar r_{B/A} = \rho\,(\cos\gamma\,\bar j + \sin\gamma\,\bar k)\ \text{(disk axes } \bar j, \bar "
            r"k\text{)}",
            {"n": n_hat, "r_A/O": r_a, "r_B/A": r_ba},
            {"n": "", "r_A/O": "m", "r_B/A": "m"},
        ),
        Step(
            "The disk's angular velocity and acceleration (the spin axis is carried round by the turntable)",
            r"\bar\omega = \omega_1\bar K + \omega_2\bar n,\qquad "
            r"\bar\alpha = \dot\omega_1\bar K + \dot\omega_2\bar n + \omega_1\bar K\times\omega_2\bar n",
            {"omega": omega, "alpha": alpha},
            {"omega": "rad/s", "alpha": "rad/s²"},
        ),
        Step(
            "The centre A: the general equations on the shaft, from the fixed point O",
            r"\bar v_A = \omega_1\bar K\times\bar r_{A/O},\qquad "
            r"\bar a_A = \dot\omega_1\bar K\times\bar r_{A/O} + \omega_1\bar K\times(\omega_1\bar K\times\bar r_{A/O})",
            {"v_A": v_a, "a_A": a_a},
            {"v_A": "m/s", "a_A": "m/s²"},
        ),
        Step(
            "Velocity of B from A",
            r"\bar v_B = \bar v_A + \bar\omega\times\bar r_{B/A}",
            {"omega x r_B/A": w_x_r, "v_B": v_b, "|v_B|": float(np.linalg.norm(v_b))},
            {"omega x r_B/A": "m/s", "v_B": "m/s", "|v_B|": "m/s"},
        ),
        Step(
            "Acceleration of B from A",
            r"\bar a_B = \bar a_A + \bar\alpha\times\bar r_{B/A} + \bar\omega\times(\bar\omega\times\bar r_{B/A})",
            {
                "alpha x r_B/A": tangential,
                "omega x (omega x r_B/A)": centripetal,
                "a_B": a_b,
                "|a_B|": float(np.linalg.norm(a_b)),
            },
            {"alpha x r_B/A": "m/s²", "omega x (omega x r_B/A)": "m/s²", "a_B": "m/s²", "|a_B|": "m/s²"},
        ),
        Step(
            "Check: the turntable as a moving frame gives the same v_B and a_B; A and B never approach along AB",
            r"\bar v_B = \bar v_{\rm rel} + \omega_1\bar K\times\bar r_{B/O},\quad "
            r"\bar a_B = \bar a_{\rm rel} + \dot\omega_1\bar K\times\bar r_{B/O} + "
            r"\omega_1\bar K\times(\omega_1\bar K\times\bar r_{B/O}) + 2\,\omega_1\bar K\times\bar v_{\rm rel},"
            r"\quad (\bar v_B - \bar v_A)\cdot\bar r_{B/A} = 0",
            {
                "v_rel": v_rel,
                "a_rel": a_rel,
                "v_B (moving frame)": v_b_frame,
                "v_B (general equation)": v_b,
                "a_B (moving frame)": a_b_frame,
                "a_B (general equation)": a_b,
                "(v_B - v_A)·r_B/A": float((v_b - v_a) @ r_ba),
            },
            {
                "v_rel": "m/s",
                "a_rel": "m/s²",
                "v_B (moving frame)": "m/s",
                "v_B (general equation)": "m/s",
                "a_B (moving frame)": "m/s²",
                "a_B (general equation)": "m/s²",
                "(v_B - v_A)·r_B/A": "m²/s",
            },
            scales={
                "(v_B - v_A)·r_B/A": float(np.linalg.norm(v_b - v_a) * np.linalg.norm(r_ba)),
            },
        ),
    )
    outputs = {
        "angular_velocity_rad_s": omega,
        "angular_acceleration_rad_s2": alpha,
        "center_velocity_m_s": v_a,
        "center_acceleration_m_s2": a_a,
        "point_velocity_m_s": v_b,
        "point_acceleration_m_s2": a_b,
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="disk-on-turntable-point",
    title="A point on a disk spinning on a turntable: v_B and a_B from the two general equations",
    chapter=4,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "angular_velocity_rad_s": "rad/s",
        "angular_acceleration_rad_s2": "rad/s²",
        "center_velocity_m_s": "m/s",
        "center_acceleration_m_s2": "m/s²",
        "point_velocity_m_s": "m/s",
        "point_acceleration_m_s2": "m/s²",
    },
    section="4.1",
    story=ExampleStory(
        situation=(
            "A turntable turns about the vertical at $\\omega_1 = 1.2$ rad/s and is speeding up at 0.3 rad/s². From "
            "a bearing $O$ on its axis a shaft rises at $\\beta = 30°$, and 0.8 m along it sits the centre $A$ of a "
            "disk of radius 0.3 m. The disk spins on the shaft, relative to the turntable, at $\\omega_2 = 4$ rad/s "
            "while slowing at 0.5 rad/s². The point $B$ is on the rim at the top of the disk (the default controls)."
        ),
        wanted=(
            "The velocity $\\bar v_B$ and the acceleration $\\bar a_B$ of the point $B$ at this instant, term by "
            "term, together with the disk's angular velocity $\\bar\\omega$ and angular acceleration "
            "$\\bar\\alpha$ that those terms need."
        ),
        approach=(
            "The general equations need one point whose motion we know and the body's $\\bar\\omega$ and "
            "$\\bar\\alpha$. The disk's centre $A$ is the natural point: it rides on the shaft, a body turning about "
            "the fixed point $O$, so the same equations applied to the shaft give $\\bar v_A$ and $\\bar a_A$ "
            "first. $\\bar\\omega$ is the sum of the turntable's rate and the spin relative to it; $\\bar\\alpha$ "
            "needs one extra term, because the spin axis $\\bar n$ is carried round by the turntable. Everything "
            "is written in the fixed frame. Tracking $B$'s position as a function of time and differentiating it "
            "twice would also work, but needs the whole attitude as a function of time, where these equations "
            "need only the rates at one instant."
        ),
        check=(
            "The check solves the problem again by another route: it rides on the turntable. Seen from there the "
            "shaft is fixed and $B$ simply goes round it at $\\omega_2$; the turntable's own motion is then added "
            "back with the moving-frame formulas of chapter 3, including the Coriolis term "
            "$2\\omega_1\\bar K\\times\\bar v_{\\rm rel}$. Both routes must give the same $\\bar v_B$ and $\\bar a_B$ "
            "to round-off. It also shows $(\\bar v_B - \\bar v_A)\\cdot\\bar r_{B/A} = 0$: two points of a rigid "
            "body never approach along the line joining them."
        ),
        what_if=(
            "Press **Turntable stopped** (it sets $\\omega_1$ and $\\dot\\omega_1$ to zero) and compare the steps. "
            "$\\bar v_A$ and $\\bar a_A$ vanish, $\\bar\\alpha$ loses its cross term "
            "$\\omega_1\\omega_2\\,\\bar K\\times\\bar n$, and the Coriolis term of the check is gone. In the "
            "scene the acceleration arrows at $B$ shrink to one, the spin's centripetal term $\\omega_2^2\\rho$ "
            "towards the centre. Then raise $\\omega_1$ step by step: the turntable carries the top of the disk "
            "forwards while the spin carries it backwards, and near $\\omega_1 = 2.2$ rad/s $\\bar v_B$ is zero "
            "for an instant."
        ),
    ),
)
