"""Worked example ``inertia-of-composite-body``: mass, centre of mass and inertia of a body built from primitives.

Reference frame xyz (the student's); each body's ``position_m`` is its own
centre of mass and ``sequence``/``angles_deg`` turn the reference axes into the
shape's own axes (see :data:`app.physics.bodies.composite.SHAPES` for which own
axis is which). Holes are negative bodies. Products of inertia follow the sign
convention of :mod:`app.physics.bodies.inertia` (tensor entries ``−I_xy``).

Principal moments and axes (``principal_*``) are those at the centre of mass;
the ones at ``about_point_m`` are given too (``principal_*_point``).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.bodies import inertia
from app.physics.bodies.composite import (
    MAX_PARTS,
    CompositeBody,
    body_place,
    combine,
    parts_from_records,
    shapes_schema,
    validate_records,
)
from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.math.rotations import SEQUENCES

#: A bracket: a 12 kg plate (100 kg/m²) with a 80 mm hole, and a 3 kg handle standing on one edge.
DEFAULT_BODIES: list[dict[str, Any]] = [
    {
        "shape": "plate",
        "mass_kg": 12.0,
        "length_m": 0.4,
        "width_m": 0.3,
        "position_m": [0.0, 0.0, 0.0],
        "sequence": "3-2-1",
        "angles_deg": [0.0, 0.0, 0.0],
        "hole": False,
    },
    {
        "shape": "disk",
        "mass_kg": 2.0106,
        "radius_m": 0.08,
        "position_m": [0.1, 0.05, 0.0],
        "sequence": "3-2-1",
        "angles_deg": [0.0, 0.0, 0.0],
        "hole": True,
    },
    {
        "shape": "rod",
        "mass_kg": 3.0,
        "length_m": 0.5,
        "position_m": [-0.2, 0.0, 0.25],
        "sequence": "3-2-1",
        "angles_deg": [0.0, 0.0, 0.0],
        "hole": False,
    },
]

BODY_FIELDS = {
    "shape": "one of the shapes below",
    "mass_kg": "mass in kg (a hole: the mass removed)",
    "position_m": "[x, y, z] of the shape's own centre of mass in the reference frame, m",
    "sequence": 'rotation sequence from the reference axes to the shape\'s own axes, e.g. "3-2-1"',
    "angles_deg": "the sequence's three angles, deg",
    "hole": "true: the body is removed (a negative body)",
}

BODIES = Parameter(
    "bodies",
    "",
    DEFAULT_BODIES,
    description="The primitive bodies (and holes) the composite is built from",
    label="bodies",
    kind="list",
    parse=validate_records,
    item_place=body_place,
    item_schema={
        "fields": BODY_FIELDS,
        "shapes": shapes_schema(),
        "sequences": list(SEQUENCES),
        "max_items": MAX_PARTS,
    },
)

INPUTS = ParameterSet(
    (
        BODIES,
        Parameter(
            "about_point_m",
            "m",
            [0.0, 0.0, 0.0],
            -100.0,
            100.0,
            "The point the inertia is also wanted about, reference frame",
            "P",
            kind="vector",
            step=0.01,
        ),
    )
)


def _tensor_latex(name: str) -> str:
    return (
        rf"{name} = \begin{{bmatrix}} I_{{xx}} & -I_{{xy}} & -I_{{xz}} \\ -I_{{xy}} & I_{{yy}} & -I_{{yz}} \\"
        rf" -I_{{xz}} & -I_{{yz}} & I_{{zz}} \end{{bmatrix}}"
    )


def composite_from_inputs(inputs: Mapping[str, Any]) -> CompositeBody:
    """The composite body described by validated inputs."""
    return combine(parts_from_records(inputs["bodies"]))


def _check_step(body: CompositeBody, point: np.ndarray, inertia_point: np.ndarray) -> Step:
    """The inertia about P again, each part moved straight from its own centre of mass to P (never through G), and the
    trace of the tensor at G beside the sum of the principal moments (a turn of the axes keeps it)."""
    direct = sum(
        (
            inertia.parallel_axis(p.inertia_cm_reference_kg_m2, p.signed_mass_kg, p.position_m - point)
            for p in body.parts
        ),
        np.zeros((3, 3)),
    )
    scale = float(np.trace(np.abs(inertia_point))) + float(np.trace(np.abs(body.inertia_cm_kg_m2)))
    return Step(
        "Check: I_P part by part, each moved straight to P; the trace at G equals I₁ + I₂ + I₃",
        r"\mathbf{I}_P = \sum_k \left[\mathbf{I}_{G_k} + m_k\left(|\mathbf{e}_k|^2\,\mathbf{1} - "
        r"\mathbf{e}_k\mathbf{e}_k^{\mathsf T}\right)\right],\quad \mathbf{e}_k = \mathbf{r}_{G_k} - "
        r"\mathbf{r}_P;\qquad \operatorname{tr}\mathbf{I}_G = I_1 + I_2 + I_3",
        {
            "I_P (part by part)": direct,
            "I_P (through G)": inertia_point,
            "tr I_G": float(np.trace(body.inertia_cm_kg_m2)),
            "I_1 + I_2 + I_3": float(np.sum(body.principal.moments_kg_m2)),
        },
        {"I_P (part by part)": "kg·m²", "I_P (through G)": "kg·m²", "tr I_G": "kg·m²", "I_1 + I_2 + I_3": "kg·m²"},
        scales={"I_P (part by part)": scale, "I_P (through G)": scale},
    )


def solve(inputs: Mapping[str, Any]) -> Solution:
    body = composite_from_inputs(inputs)
    point = np.asarray(inputs["about_point_m"], float)
    inertia_point = body.inertia_about_kg_m2(point)
    principal_point = inertia.check_inertia_tensor(inertia_point, about="the point P")
    principal = body.principal
    parts = body.parts
    steps = (
        Step(
            "Each body about its own centre of mass, in reference axes",
            r"\mathbf{I}_{G_k} = \pm\,R_k\,\mathbf{I}_k^{\mathrm{own}}\,R_k^{\mathsf T}"
            r"\quad(\text{minus for a hole; } R_k \text{ from the rotation sequence})",
            {f"I_G{k + 1}": p.inertia_cm_reference_kg_m2 for k, p in enumerate(parts)}
            | {f"m_{k + 1}": p.signed_mass_kg for k, p in enumerate(parts)},
            {f"I_G{k + 1}": "kg·m²" for k in range(len(parts))} | {f"m_{k + 1}": "kg" for k in range(len(parts))},
        ),
        Step(
            "Mass and centre of mass",
            r"m = \sum_k m_k, \qquad \mathbf{r}_G = \frac{1}{m}\sum_k m_k\,\mathbf{r}_{G_k}",
            {"m": body.mass_kg, "r_G": body.centre_of_mass_m},
            {"m": "kg", "r_G": "m"},
        ),
        Step(
            "Parallel-axis theorem to the common centre of mass",
            _tensor_latex(r"\mathbf{I}_G")
            + r" = \sum_k \left[\mathbf{I}_{G_k} + m_k\left(|\mathbf{d}_k|^2\,\mathbf{1} - "
            r"\mathbf{d}_k\mathbf{d}_k^{\mathsf T}\right)\right],"
            r"\quad \mathbf{d}_k = \mathbf{r}_{G_k} - \mathbf{r}_G",
            {"I_G": body.inertia_cm_kg_m2},
            {"I_G": "kg·m²"},
        ),
        Step(
            "Inertia about the point P",
            r"\mathbf{I}_P = \mathbf{I}_G + m\left(|\mathbf{d}|^2\,\mathbf{1} - \mathbf{d}\mathbf{d}^{\mathsf "
            r"T}\right),"
            r"\quad \mathbf{d} = \mathbf{r}_G - \mathbf{r}_P",
            {"r_P": point, "I_P": inertia_point},
            {"r_P": "m", "I_P": "kg·m²"},
        ),
        Step(
            "Principal moments and axes at G",
            r"\left(\mathbf{I}_G - I_i\,\mathbf{1}\right)\mathbf{e}_i = \mathbf{0}, \qquad I_1 \le I_2 \le I_3,"
            r"\quad \mathbf{e}_3 = \mathbf{e}_1 \times \mathbf{e}_2",
            {
                "I_1..3": principal.moments_kg_m2,
                "e_1": principal.axes[0],
                "e_2": principal.axes[1],
                "e_3": principal.axes[2],
            },
            {"I_1..3": "kg·m²", "e_1": "", "e_2": "", "e_3": ""},
        ),
        _check_step(body, point, inertia_point),
    )
    outputs = {
        "mass_kg": body.mass_kg,
        "centre_of_mass_m": body.centre_of_mass_m,
        "inertia_cm_kg_m2": body.inertia_cm_kg_m2,
        "inertia_point_kg_m2": inertia_point,
        "principal_moments_kg_m2": principal.moments_kg_m2,
        "principal_axes": principal.axes,
        "principal_degeneracy": principal.degeneracy,
        "principal_note": principal.describe(),
        "principal_moments_point_kg_m2": principal_point.moments_kg_m2,
        "principal_axes_point": principal_point.axes,
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="inertia-of-composite-body",
    title="Inertia of a composite body",
    chapter=5,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "mass_kg": "kg",
        "centre_of_mass_m": "m",
        "inertia_cm_kg_m2": "kg·m²",
        "inertia_point_kg_m2": "kg·m²",
        "principal_moments_kg_m2": "kg·m²",
        "principal_axes": "",
        "principal_degeneracy": "",
        "principal_note": "",
        "principal_moments_point_kg_m2": "kg·m²",
        "principal_axes_point": "",
    },
    section="5.2",
    story=ExampleStory(
        situation=(
            "A bracket is made from a 12 kg steel plate, 0.4 m by 0.3 m, with a hole of 80 mm radius cut through it "
            "(centred 0.1 m along $x$ and 0.05 m along $y$ from the plate's centre), and a 3 kg rod 0.5 m long "
            "standing upright on the middle of one short edge as a handle. Each piece's mass, size, position and "
            "orientation is known in the reference frame $xyz$, "
            "whose origin is the centre of the plate."
        ),
        wanted=(
            "The bracket's mass and centre of mass $G$, its inertia tensor about $G$ on the reference axes, the "
            "tensor about a second point $P$ (the origin, unless you move it), and its principal moments and "
            "principal axes at $G$."
        ),
        approach=(
            "Integrating $\\int(|\\bar d|^2\\mathbf 1 - \\bar d\\bar d^{\\mathsf T})\\,dm$ over a plate with a hole "
            "and a handle is possible but slow, and every new part would need a new integral. Instead each piece is "
            "a shape whose inertia about its own centre of mass, on its own axes, is in a table, and the hole is a "
            "piece with negative mass. We turn each table tensor onto the reference axes, move each one to the "
            "common centre of mass $G$ with the parallel-axis theorem, and add. We go to $G$ first because the "
            "principal moments and axes that describe the body are those at $G$; the tensor at any other point "
            "$P$ is then one more shift. The principal axes are an eigenproblem of one symmetric 3 × 3 matrix."
        ),
        check=(
            "The check builds the tensor about $P$ a second way: each piece is moved straight from its own "
            "centre of mass to $P$, never through $G$, and the pieces are added there. The two routes differ only "
            "by cross terms that are sums of each mass times its offset from $G$, and those add up to zero "
            "because $G$ is the centre of mass, so the two tensors must agree to round-off. The step also compares "
            "the trace of the tensor at $G$ with the sum of the principal moments: turning the axes cannot change "
            "the trace."
        ),
        what_if=(
            "Move the point **P** (m) away from the origin, for example to the top of the handle at "
            "$(-0.2, 0, 0.5)$ m. Every entry of $\\mathbf I_P$ grows or shifts by the parallel-axis terms, while "
            "$\\mathbf I_G$ and its principal moments stay exactly as they were. Then delete the hole from the "
            "body list: the mass rises by 2.01 kg, $G$ moves back towards the plate's centre, and in the scene the "
            "principal axes and the ellipsoid turn."
        ),
    ),
)
