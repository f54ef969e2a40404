"""Worked example ``antenna-boom-finite-rotation``: one turn about one axis, and two turns in two orders.

A satellite's antenna boom is hinged at a fixed point O. Frames: the fixed frame XYZ (+Z up) and the boom's body
frame xyz, which coincide before it moves. The boom runs from O to its tip, ``boom_body_m`` in body components
(m). The deployment mechanism turns it by a rotation sequence (attitude ``A``,
:func:`~app.physics.systems.ch03.finite_rotation.finite_rotation`); Euler's theorem says the same attitude is one
turn by φ about one line n through O. A second turn ``B`` by β about a fixed axis (X, Y or Z) is then made before
or after ``A``: turns about fixed axes compose on the left, ``A then B = [R_B][R_A]``, ``B then A = [R_A][R_B]``.
Angles in degrees where a name ends in ``_deg``. For φ = 0 (no turn) every line through O is an axis; +Z is
reported, as :func:`~app.physics.systems.ch03.finite_rotation.equivalent_turn` does.

A boom of zero length has no tip to follow: it is refused with a ParameterError naming ``boom_body_m``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.math.rotations import SEQUENCES, matrix_from_axis_angle
from app.physics.systems.ch03.finite_rotation import FIXED_AXES, finite_rotation

#: A boom shorter than this (m) is no boom: its tip is the fixed point.
SHORTEST_BOOM_M = 1e-9


def _check(values: Mapping[str, Any]) -> None:
    length = float(np.linalg.norm(values["boom_body_m"]))
    if not length > SHORTEST_BOOM_M:
        raise ParameterError(
            "boom_body_m",
            f"the boom has length {length:.3g} m: its tip would be the fixed point O, which no turn moves, so there "
            "is no tip path to follow; give the boom from O to its tip, e.g. [1.2, 0, 0] m",
        )


INPUTS = ParameterSet(
    (
        Parameter(
            "sequence",
            "",
            "3-1-3",
            kind="choice",
            choices=tuple(SEQUENCES),
            label="Sequence",
            description="Axes of the three body-fixed turns that set attitude A (1 = x, 2 = y, 3 = z)",
        ),
        Parameter(
            "angle1_deg", "deg", 80.0, -180.0, 180.0, "First turn θ1 of attitude A, about axis a1 of XYZ", "θ1", step=1
        ),
        Parameter(
            "angle2_deg",
            "deg",
            35.0,
            -180.0,
            180.0,
            "Second turn θ2 of attitude A, about axis a2 of x′y′z′",
            "θ2",
            step=1,
        ),
        Parameter(
            "angle3_deg",
            "deg",
            60.0,
            -180.0,
            180.0,
            "Third turn θ3 of attitude A, about axis a3 of x″y″z″",
            "θ3",
            step=1,
        ),
        Parameter(
            "second_axis",
            "",
            "Z",
            kind="choice",
            choices=FIXED_AXES,
            label="B about",
            description="Fixed axis of the second turn B",
        ),
        Parameter(
            "second_angle_deg",
            "deg",
            90.0,
            -180.0,
            180.0,
            "Angle β of the second turn B about its fixed axis (0: no second turn)",
            "β",
            step=1,
        ),
        Parameter(
            "boom_body_m",
            "m",
            (1.2, 0.0, 0.0),
            -10.0,
            10.0,
            "The boom from the hinge O to its tip, in the boom's body components (not zero)",
            "boom O→tip (x, y, z)",
            kind="vector",
            step=0.05,
        ),
    ),
    check=_check,
)


def solve(inputs: Mapping[str, Any]) -> Solution:
    _check(inputs)
    angles = np.radians([inputs[f"angle{k}_deg"] for k in (1, 2, 3)])
    beta = math.radians(inputs["second_angle_deg"])
    rot = finite_rotation(angles, inputs["sequence"], second_axis=inputs["second_axis"], second_angle_rad=beta)
    A = rot.turn_a
    R_A, n, phi = A.R_world_body, A.axis_world, A.angle_rad
    boom = np.asarray(inputs["boom_body_m"], dtype=float)

    tip_after_a = R_A @ boom
    along = float(boom @ n)
    radius = float(np.linalg.norm(boom - along * n))
    chord = float(np.linalg.norm(tip_after_a - boom))
    tip_ab = rot.a_then_b.R_world_body @ boom
    tip_ba = rot.b_then_a.R_world_body @ boom
    separation = float(np.linalg.norm(tip_ab - tip_ba))
    rodrigues = matrix_from_axis_angle(n, phi)
    steps = (
        Step(
            "Attitude A from the sequence",
            r"[R_A] = [R_{a_1}(\theta_1)]\,[R_{a_2}(\theta_2)]\,[R_{a_3}(\theta_3)]",
            {"R_A": R_A},
            {"R_A": ""},
        ),
        Step(
            "Euler's angle from the trace, Euler's axis from the skew part",
            r"\cos\phi = \tfrac12(\operatorname{tr}[R_A] - 1),\quad \bar n = \frac{1}{2\sin\phi}"
            r"\begin{bmatrix}R_{32}-R_{23}\\R_{13}-R_{31}\\R_{21}-R_{12}\end{bmatrix}"
            r"\ \text{(read from the quaternion, so it holds up to }\phi = 180°)",
            {"trace": float(np.trace(R_A)), "phi": math.degrees(phi), "n": n},
            {"trace": "", "phi": "deg", "n": ""},
        ),
        Step(
            "The boom tip after A: one arc about n",
            r"\bar r_A = [R_A]\,\bar r_0,\quad \rho = |\bar r_0 - (\bar r_0\cdot\bar n)\,\bar n|,\quad "
            r"|\bar r_A - \bar r_0| = 2\rho\sin\tfrac{\phi}{2}",
            {"r_0": boom, "r_A": tip_after_a, "rho": radius, "chord": chord},
            {"r_0": "m", "r_A": "m", "rho": "m", "chord": "m"},
        ),
        Step(
            "A second turn B about a fixed axis, made after A and before A",
            r"[R_{AB}] = [R_B]\,[R_A],\quad [R_{BA}] = [R_A]\,[R_B],\quad "
            r"\bar r_{AB} = [R_{AB}]\,\bar r_0,\quad \bar r_{BA} = [R_{BA}]\,\bar r_0",
            {
                "beta": inputs["second_angle_deg"],
                "phi_AB": math.degrees(rot.a_then_b.angle_rad),
                "phi_BA": math.degrees(rot.b_then_a.angle_rad),
                "r_AB": tip_ab,
                "r_BA": tip_ba,
            },
            {"beta": "deg", "phi_AB": "deg", "phi_BA": "deg", "r_AB": "m", "r_BA": "m"},
        ),
        Step(
            "How far apart the two orders leave the boom",
            r"|\bar r_{AB} - \bar r_{BA}|,\quad \gamma = \angle\big([R_{AB}][R_{BA}]^{\mathsf T}\big)",
            {"separation": separation, "gamma": math.degrees(rot.order_gap_rad)},
            {"separation": "m", "gamma": "deg"},
        ),
        Step(
            "Check: Rodrigues' formula rebuilds A, n stays put, and the tip moved on a circle about n",
            r"[R] = [I] + \sin\phi\,[\tilde n] + (1-\cos\phi)\,[\tilde n]^2 = [R_A],\quad [R_A]\bar n = \bar n,\quad "
            r"|\bar r_A - \bar r_0| = 2\rho\sin\tfrac{\phi}{2},\quad \bar r_A\cdot\bar n = \bar r_0\cdot\bar n",
            {
                "rodrigues_error": float(np.max(np.abs(rodrigues - R_A))),
                "axis_moved": float(np.max(np.abs(R_A @ n - n))),
                "chord": chord,
                "2_rho_sin_half_phi": 2.0 * radius * math.sin(0.5 * phi),
                "r_0_dot_n": along,
                "r_A_dot_n": float(tip_after_a @ n),
            },
            {
                "rodrigues_error": "",
                "axis_moved": "",
                "chord": "m",
                "2_rho_sin_half_phi": "m",
                "r_0_dot_n": "m",
                "r_A_dot_n": "m",
            },
        ),
    )
    outputs = {
        "axis_world": n,
        "angle_deg": math.degrees(phi),
        "tip_after_a_m": tip_after_a,
        "tip_a_then_b_m": tip_ab,
        "tip_b_then_a_m": tip_ba,
        "tip_separation_m": separation,
        "order_gap_deg": math.degrees(rot.order_gap_rad),
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="antenna-boom-finite-rotation",
    title="An antenna boom turned about a hinge: Euler's axis and angle, and two turns in two orders",
    chapter=3,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "axis_world": "",
        "angle_deg": "deg",
        "tip_after_a_m": "m",
        "tip_a_then_b_m": "m",
        "tip_b_then_a_m": "m",
        "tip_separation_m": "m",
        "order_gap_deg": "deg",
    },
    section="3.2",
    story=ExampleStory(
        situation=(
            "A 1.2 m antenna boom on a small satellite is hinged at a ball joint $O$, which stays put. It starts "
            "along the fixed $X$ axis, and its deployment motors turn it into attitude $A$ by three turns of a "
            "rotation sequence (3-1-3 with $80°$, $35°$, $60°$ by default). A second manoeuvre $B$ turns it by "
            "$\\beta$ about one of the fixed axes, and the operators wonder whether it matters if $B$ is made "
            "before or after $A$."
        ),
        wanted=(
            "The single axis $\\bar n$ and angle $\\phi$ that take the boom from its start straight to attitude "
            "$A$ (Euler's theorem), where the boom tip ends up, and, for the second turn, where the tip ends in "
            "each order, how far apart those two tip positions are in metres, and the angle $\\gamma$ of the turn "
            "that separates the two final attitudes."
        ),
        approach=(
            "The whole attitude is held in one rotation matrix, so every question becomes matrix algebra on "
            "$[R_A]$. Its trace gives $\\phi$ at once and its skew-symmetric part gives $\\bar n$; we read "
            "both from the quaternion, which stays accurate near $\\phi = 180°$ where $\\sin\\phi$ in the skew "
            "formula vanishes. Turns described about fixed axes compose on the left, so the two orders are the "
            "two products $[R_B][R_A]$ and $[R_A][R_B]$. Describing the same thing with three angles per order "
            "would need the angles of a new sequence for each product and says nothing directly about the single "
            "equivalent turn."
        ),
        check=(
            "Rodrigues' formula, built from $\\bar n$ and $\\phi$ alone, must give back the very matrix the "
            "three turns produced, and $[R_A]\\bar n = \\bar n$ because points on the axis do not move; both "
            "differences are round-off. Independently of the matrices, the tip must have moved along a circle "
            "about $\\bar n$: its height along $\\bar n$ is unchanged and the chord it crossed equals "
            "$2\\rho\\sin(\\phi/2)$ for the circle's radius $\\rho$. The last step prints both sides."
        ),
        what_if=(
            "Move **β**. At $\\beta = 0$ the two orders agree exactly and the separation is zero. For small "
            "$\\beta$ the separation grows roughly in proportion to $\\beta$ times the size of attitude A, and it "
            "vanishes again when $B$ is about the same line as $\\bar n$. In the scene the two copies side by side "
            "end in visibly different attitudes as soon as $\\beta$ is a few tens of degrees."
        ),
    ),
)
