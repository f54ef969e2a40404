"""Worked example ``camera-gimbal-sequence``: a camera on a three-axis gimbal, set by a rotation sequence.

Frames: the fixed frame XYZ (+Z up) and the camera's body frame xyz, turned from XYZ by the sequence
``a1-a2-a3`` (conventions of :mod:`app.physics.math.rotations`): ``[R] = R_a1(θ1) R_a2(θ2) R_a3(θ3)``
takes body components to fixed components, ``{v}_XYZ = [R]{v}_xyz``. The camera looks along the body
direction ``sight_body`` (unit vector after normalising). Its line of sight is read as an azimuth
(from +X towards +Y) and an elevation (above the XY plane). The same attitude is then described by the
angles of a second sequence, read back from ``[R]`` through its quaternion (no arcsine of a rounded
number, valid at gimbal lock). Angles in degrees where a name ends in ``_deg``.

A line of sight of zero length has no direction: it is refused with a ParameterError naming ``sight_body``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.math.rotations import (
    SEQUENCES,
    angles_from_matrix,
    elementary_rotation_matrix,
    matrix_from_angles,
    rotation_sequence,
)

#: The ``readback_at_gimbal_lock`` output, in words (a verdict the page shows as it is).
AT_GIMBAL_LOCK, CLEAR_OF_GIMBAL_LOCK = "at gimbal lock", "clear of gimbal lock"


#: A line of sight shorter than this (dimensionless, in body components) is taken as no direction at all.
SHORTEST_SIGHT = 1e-9


def _check(values: Mapping[str, Any]) -> None:
    length = float(np.linalg.norm(values["sight_body"]))
    if not length > SHORTEST_SIGHT:
        raise ParameterError(
            "sight_body",
            f"the line of sight has length {length:.3g}: a zero vector points nowhere, so it has no azimuth or "
            "elevation; give the camera's viewing direction in body components, e.g. [1, 0, 0]",
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
            description=(
                "Axes of the gimbal's three turns (1 = x, 2 = y, 3 = z), each about an axis of the frame the turns "
                "before it left"
            ),
        ),
        Parameter(
            "angle1_deg",
            "deg",
            80.0,
            -180.0,
            180.0,
            "First turn θ1, about axis a1 of the fixed frame XYZ",
            "θ1",
            step=1,
        ),
        Parameter(
            "angle2_deg", "deg", 35.0, -180.0, 180.0, "Second turn θ2, about axis a2 of the frame x′y′z′", "θ2", step=1
        ),
        Parameter(
            "angle3_deg", "deg", 60.0, -180.0, 180.0, "Third turn θ3, about axis a3 of the frame x″y″z″", "θ3", step=1
        ),
        Parameter(
            "sight_body",
            "",
            (1.0, 0.0, 0.0),
            -1.0,
            1.0,
            "Direction the camera looks along, in its own body components (normalised; not zero)",
            "line of sight (x, y, z)",
            kind="vector",
            step=0.05,
        ),
        Parameter(
            "readback_sequence",
            "",
            "3-2-1",
            kind="choice",
            choices=tuple(SEQUENCES),
            label="Read back as",
            description="A second sequence whose angles describe the same attitude (read back from [R])",
        ),
    ),
    check=_check,
)


def _axis_name(axis: int) -> str:
    return str(axis + 1)


def solve(inputs: Mapping[str, Any]) -> Solution:
    _check(inputs)
    seq = rotation_sequence(inputs["sequence"])
    other = rotation_sequence(inputs["readback_sequence"])
    angles_deg = np.array([inputs[f"angle{k}_deg"] for k in (1, 2, 3)], dtype=float)
    angles = np.radians(angles_deg)
    turns = [elementary_rotation_matrix(seq.axes[k], angles[k]) for k in range(3)]
    R = turns[0] @ turns[1] @ turns[2]

    sight_body = np.asarray(inputs["sight_body"], dtype=float)
    sight_body = sight_body / np.linalg.norm(sight_body)
    sight = R @ sight_body
    azimuth_deg = math.degrees(math.atan2(sight[1], sight[0]))
    elevation_deg = math.degrees(math.atan2(sight[2], math.hypot(sight[0], sight[1])))

    readback = angles_from_matrix(R, other)
    other_deg = np.degrees(readback.angles_rad)
    own = angles_from_matrix(R, seq)
    rebuilt_other = matrix_from_angles(readback.angles_rad, other)
    rebuilt_own = matrix_from_angles(own.angles_rad, seq)
    orthogonality = float(np.max(np.abs(R.T @ R - np.eye(3))))
    a1, a2, a3 = (_axis_name(a) for a in seq.axes)
    b1, b2, b3 = (_axis_name(a) for a in other.axes)
    steps = (
        Step(
            "The three elementary turns, each about a coordinate axis of the frame before it",
            rf"[R_{{{a1}}}(\theta_1)],\ [R_{{{a2}}}(\theta_2)],\ [R_{{{a3}}}(\theta_3)],\quad "
            r"[R_1(\theta)] = \begin{bmatrix}1&0&0\\0&\cos\theta&-\sin\theta\\0&\sin\theta&\cos\theta\end{bmatrix}"
            r"\text{ (and cyclically for axes 2, 3)}",
            {
                "theta_1": angles_deg[0],
                "theta_2": angles_deg[1],
                "theta_3": angles_deg[2],
                "R_a1": turns[0],
                "R_a2": turns[1],
                "R_a3": turns[2],
            },
            {"theta_1": "deg", "theta_2": "deg", "theta_3": "deg", "R_a1": "", "R_a2": "", "R_a3": ""},
        ),
        Step(
            "Multiply in the order of the turns: later turns on the right",
            rf"[R] = [R_{{{a1}}}(\theta_1)]\,[R_{{{a2}}}(\theta_2)]\,[R_{{{a3}}}(\theta_3)],\quad "
            r"\{v\}_{XYZ} = [R]\,\{v\}_{xyz}",
            {"R": R},
            {"R": ""},
        ),
        Step(
            "The line of sight in fixed components",
            r"\hat s_{xyz} = \frac{\{s\}_{xyz}}{|\{s\}_{xyz}|},\quad \{\hat s\}_{XYZ} = [R]\,\{\hat s\}_{xyz}",
            {"s_xyz": sight_body, "s_XYZ": sight},
            {"s_xyz": "", "s_XYZ": ""},
        ),
        Step(
            "Azimuth and elevation of the line of sight",
            r"\psi = \operatorname{atan2}(\hat s_Y, \hat s_X),\quad "
            r"\varepsilon = \operatorname{atan2}\!\left(\hat s_Z, \sqrt{\hat s_X^2 + \hat s_Y^2}\right)",
            {"psi": azimuth_deg, "epsilon": elevation_deg},
            {"psi": "deg", "epsilon": "deg"},
        ),
        Step(
            f"The same attitude read back as a {other.name} sequence",
            rf"[R_{{{b1}}}(\phi_1)]\,[R_{{{b2}}}(\phi_2)]\,[R_{{{b3}}}(\phi_3)] = [R]"
            r"\ \text{solved for }\phi_1,\phi_2,\phi_3\text{ (through the quaternion of }[R])",
            {
                "phi_1": other_deg[0],
                "phi_2": other_deg[1],
                "phi_3": other_deg[2],
                "lock_distance": math.degrees(float(readback.lock_distance_rad)),
            },
            {"phi_1": "deg", "phi_2": "deg", "phi_3": "deg", "lock_distance": "deg"},
        ),
        Step(
            "Check: [R] is a rotation, and both sets of angles rebuild it",
            r"\max|[R]^{\mathsf T}[R] - [I]| \approx 0,\quad \det[R] = 1,\quad "
            r"\max\big|[R(\phi)] - [R]\big| \approx 0,\quad \max\big|[R(\theta_{\rm back})] - [R]\big| \approx 0",
            {
                "orthogonality_error": orthogonality,
                "det_R": float(np.linalg.det(R)),
                "rebuilt_error_other": float(np.max(np.abs(rebuilt_other - R))),
                "rebuilt_error_own": float(np.max(np.abs(rebuilt_own - R))),
            },
            {"orthogonality_error": "", "det_R": "", "rebuilt_error_other": "", "rebuilt_error_own": ""},
        ),
    )
    outputs = {
        "R_world_body": R,
        "sight_world": sight,
        "azimuth_deg": azimuth_deg,
        "elevation_deg": elevation_deg,
        "readback_angles_deg": other_deg,
        "readback_at_gimbal_lock": AT_GIMBAL_LOCK if readback.degenerate else CLEAR_OF_GIMBAL_LOCK,
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="camera-gimbal-sequence",
    title="A camera on a three-axis gimbal: the rotation matrix, where it looks, and the angles of another sequence",
    chapter=3,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "R_world_body": "",
        "sight_world": "",
        "azimuth_deg": "deg",
        "elevation_deg": "deg",
        "readback_angles_deg": "deg",
        "readback_at_gimbal_lock": "",
    },
    section="3.1",
    story=ExampleStory(
        situation=(
            "An inspection camera hangs from a drone on a three-axis gimbal. Its motors turn it from the fixed "
            "frame $XYZ$ ($Z$ up) by three angles of a rotation sequence, $\\theta_1 = 80°$, $\\theta_2 = 35°$, "
            "$\\theta_3 = 60°$ of a 3-1-3 sequence by default, each turn about an axis of the frame the turns "
            "before it left behind. The camera looks along its own body axis $x$."
        ),
        wanted=(
            "The rotation matrix $[R]$ that takes the camera's body components to fixed components; the "
            "direction the camera looks, as fixed components and as an azimuth (from $X$ towards $Y$) and an "
            "elevation above the ground plane; and the angles of a different sequence, 3-2-1 (yaw, pitch, roll), "
            "that put the camera in the very same attitude, as a flight controller would report it."
        ),
        approach=(
            "Each turn is about a coordinate axis of the frame it starts from, so each is one elementary matrix "
            "with a single $\\cos$ and $\\sin$ pair. Because every later turn is about an axis the earlier turns "
            "have already carried along, the matrices multiply in the order of the turns, later ones on the "
            "right. The sight line is then a single matrix product. The alternative, chasing the unit vectors "
            "through three frames by hand, gives the same numbers with many more chances to drop a sign. To read "
            "another sequence's angles back we go through the quaternion of $[R]$: an arcsine of a matrix entry "
            "would lose accuracy near $\\pm 90°$ and fail at gimbal lock."
        ),
        check=(
            "A rotation matrix must have orthonormal columns, $[R]^{\\mathsf T}[R] = [I]$, and determinant "
            "$+1$; the last step prints the largest entry of $[R]^{\\mathsf T}[R] - [I]$ and $\\det[R]$. Then "
            "both the read-back angles of the second sequence and the original sequence's angles read back "
            "from $[R]$ are multiplied out again: each must rebuild $[R]$ entry by entry, so both differences "
            "are zero up to round-off (about $10^{-16}$)."
        ),
        what_if=(
            "Move **θ2** towards 0°. For a 3-1-3 sequence that is gimbal lock: the third turn's axis falls onto "
            "the line of the first, and in the scene the first and third turn axes turn red. The matrix and the "
            "line of sight stay perfectly well defined, but only $\\theta_1 + \\theta_3$ matters any more. Then "
            "try the sequence 3-2-1 with θ2 near ±90° and watch the read-back pitch $\\phi_2$ and the "
            "lock distance in the steps."
        ),
    ),
)
