"""Scene: the inertia explorer — a composite body, its centre of mass, principal axes and inertia ellipsoid.

The reference frame xyz is the world frame (+z up); every body's position and
orientation are given in it (the worked example ``inertia-of-composite-body``).
The student turns a second frame x′y′z′ at the centre of mass G (``frame_sequence``,
``frame_angles_deg``: from xyz to x′y′z′) and reads the tensor's components in
it: they change as the frame turns, the principal moments do not.

Drawn: each primitive in its place (solid parts grey-blue; holes red, drawn a
little proud of the part they are cut from: opaque, because viser draws a
translucent part inside the translucent ellipsoid not at all; a spherical shell
as a wireframe), G (black dot), the
principal axes at G (arrows 1 2 3, red green blue, labelled with their moments),
the inertia ellipsoid ρᵀ I_G ρ = const (translucent, semi-axes ∝ 1/√I along
the principal axes), the turned frame x′y′z′ at G, the reference axes at the
origin and the point P (``about_point_m``).

Nothing is integrated: the composite is recomputed only when ``bodies`` or
``about_point_m`` change, and turning the frame costs one ``R I Rᵀ``.
"""

from __future__ import annotations

import math
from typing import Any, TypedDict

import numpy as np

from app.physics.bodies import inertia
from app.physics.bodies.composite import CompositeBody, Part
from app.physics.core.parameters import Parameter
from app.physics.math.rotations import (
    SEQUENCES,
    matrix_from_angles,
    quaternion_from_matrix,
)
from app.physics.systems.ch05 import composite_body
from app.scenes.kit import Preset, Quantity, Readout, Scene, arrow_segments

#: Two principal moments closer than this fraction of the largest are reported as "nearly equal".
NEARLY_EQUAL_RELATIVE_GAP = 1e-3
#: Tensor components smaller than this fraction of the trace are rounding noise and shown as 0.
ROUNDING_NOISE = 1e-12

SOLID_COLOR = (110, 140, 190)
HOLE_COLOR = (225, 50, 50)


class _PartStyle(TypedDict):
    """What every part's mesh shares: its colour, orientation (wxyz, world from part) and position (m, world)."""

    color: tuple[int, int, int]
    wxyz: np.ndarray
    position: np.ndarray


AXIS_COLORS = np.array([[215, 50, 40], [40, 160, 60], [40, 90, 220]], np.uint8)
TURNED_FRAME_COLORS = np.array([[235, 130, 40], [150, 200, 40], [40, 190, 210]], np.uint8)
SUBSCRIPTS = "₁₂₃"

FRAME_SEQUENCE = Parameter(
    "frame_sequence",
    "",
    "3-2-1",
    description="Rotation sequence from the reference axes xyz to the turned axes x′y′z′",
    label="turned frame: sequence",
    kind="choice",
    choices=tuple(SEQUENCES),
)
FRAME_ANGLES = Parameter(
    "frame_angles_deg",
    "deg",
    [0.0, 0.0, 0.0],
    -360.0,
    360.0,
    "The sequence's three angles; the tensor's components are shown on the turned axes x′y′z′",
    "turned frame: angles",
    kind="vector",
    step=1.0,
)
SHOW_ELLIPSOID = Parameter(
    "show_ellipsoid",
    "",
    "yes",
    description="Draw the inertia ellipsoid at G (semi-axes ∝ 1/√I)",
    label="inertia ellipsoid",
    kind="choice",
    choices=("yes", "no"),
)


def _record(
    shape: str, mass_kg: float, position_m, angles_deg=(0.0, 0.0, 0.0), **dimensions_m: float
) -> dict[str, Any]:
    """One solid body of a preset (3-2-1 angles in deg, m, kg)."""
    return {
        "shape": shape,
        "mass_kg": mass_kg,
        **dimensions_m,
        "position_m": list(position_m),
        "sequence": "3-2-1",
        "angles_deg": list(angles_deg),
        "hole": False,
    }


#: 3-2-1 angles (deg) that turn a shape's own z onto the reference x and y axes.
ALONG_X = (0.0, 90.0, 0.0)
ALONG_Y = (0.0, 0.0, -90.0)

PRESET_BODIES: dict[str, list[dict[str, Any]]] = {
    "bent-bar": [
        _record("rod", 1.2, (0.3, 0.0, 0.0), ALONG_X, length_m=0.6),
        _record("rod", 0.6, (0.6, 0.15, 0.0), ALONG_Y, length_m=0.3),
    ],
    "plate-with-hole": composite_body.DEFAULT_BODIES,
    "skewed-disk": [
        _record("rod", 1.5, (0.0, 0.0, 0.0), ALONG_X, length_m=0.8),
        _record("disk", 6.0, (0.0, 0.0, 0.0), (0.0, 84.0, 0.0), radius_m=0.2),  # normal 6° off the shaft
    ],
    "dumbbell": [
        _record("rod", 0.5, (0.0, 0.0, 0.0), ALONG_X, length_m=0.5),
        _record("sphere", 2.0, (-0.3, 0.0, 0.0), radius_m=0.05),
        _record("sphere", 2.0, (0.3, 0.0, 0.0), radius_m=0.05),
    ],
    "sphere": [_record("sphere", 10.0, (0.0, 0.0, 0.0), radius_m=0.2)],
    "cube": [_record("box", 8.0, (0.0, 0.0, 0.0), (30.0, 20.0, 10.0), length_m=0.3, width_m=0.3, height_m=0.3)],
}


#: Each preset's button label and description (its body is PRESET_BODIES[name]; P at the origin).
PRESET_TEXT: dict[str, tuple[str, str]] = {
    "bent-bar": (
        "Bent bar",
        "Two rods at right angles: a flat body, so I₃ = I₁ + I₂, with a product of inertia in its plane.",
    ),
    "plate-with-hole": (
        "Plate with a hole",
        "The default bracket: a plate with an 80 mm hole (a negative disk) and a rod standing on one edge.",
    ),
    "skewed-disk": (
        "Skewed disk",
        "A disk on a shaft, tilted 6° from square: the shaft is no longer a principal axis (I_xz ≠ 0).",
    ),
    "dumbbell": ("Dumbbell", "Two spheres on a rod: axisymmetric, so every axis across the rod is principal."),
    "sphere": ("Sphere", "Every axis through the centre is principal: the ellipsoid is a sphere."),
    "cube": ("Cube (turned)", "A cube turned 30°, 20°, 10°: still every axis through its centre is principal."),
}


def _tube_mesh(
    radius_m: float, inner_radius_m: float, length_m: float, segments: int = 48
) -> tuple[np.ndarray, np.ndarray]:
    """Vertices (V, 3) and faces (F, 3) of a tube along its own z, centred on its centre of mass (m)."""
    angles = np.linspace(0.0, 2.0 * math.pi, segments, endpoint=False)
    ring = np.column_stack([np.cos(angles), np.sin(angles)])
    rings = [
        np.column_stack([r * ring, np.full(segments, z)])
        for r, z in (
            (radius_m, -length_m / 2),
            (radius_m, length_m / 2),
            (inner_radius_m, length_m / 2),
            (inner_radius_m, -length_m / 2),
        )
    ]
    vertices = np.vstack(rings)
    faces = []
    for k in range(4):  # outer wall, top annulus, inner wall, bottom annulus (outward normals)
        a, b = k * segments, ((k + 1) % 4) * segments
        for i in range(segments):
            j = (i + 1) % segments
            faces += [[a + i, a + j, b + j], [a + i, b + j, b + i]]
    return vertices.astype(np.float32), np.array(faces, np.uint32)


def _cone_mesh(radius_m: float, height_m: float, segments: int = 48) -> tuple[np.ndarray, np.ndarray]:
    """Vertices and faces of a solid cone along its own z about its centre of mass: base at −h/4, apex at 3h/4 (m)."""
    angles = np.linspace(0.0, 2.0 * math.pi, segments, endpoint=False)
    base = np.column_stack([radius_m * np.cos(angles), radius_m * np.sin(angles), np.full(segments, -height_m / 4)])
    vertices = np.vstack([base, [[0.0, 0.0, 3 * height_m / 4]], [[0.0, 0.0, -height_m / 4]]])
    apex, centre = segments, segments + 1
    faces = []
    for i in range(segments):
        j = (i + 1) % segments
        faces += [[i, j, apex], [j, i, centre]]
    return vertices.astype(np.float32), np.array(faces, np.uint32)


def body_span_m(body: CompositeBody) -> float:
    """Twice the largest distance (m) from G to any part's outline: the body's drawing scale."""
    points = np.vstack([part.outline_reference_m() for part in body.parts])
    return max(2.0 * float(np.max(np.linalg.norm(points - body.centre_of_mass_m, axis=1))), 1e-3)


def tensor_in_turned_frame(inertia_kg_m2: np.ndarray, R_reference_turned: np.ndarray) -> np.ndarray:
    """Components on the turned axes of a tensor given on the reference axes: ``Rᵀ I R`` (kg·m²).

    ``R_reference_turned``'s columns are the turned axes in reference components.
    """
    return inertia.rotate_tensor(inertia_kg_m2, np.asarray(R_reference_turned, float).T)


def nearly_equal_pair(principal: inertia.PrincipalAxes) -> tuple[int, int, float] | None:
    """The closest pair of principal moments when they differ but by less than :data:`NEARLY_EQUAL_RELATIVE_GAP`
    of the largest: ``(i, j, relative gap)``; None when the moments are well apart or exactly repeated."""
    if principal.degeneracy != "distinct":
        return None
    moments = principal.moments_kg_m2
    gaps = np.diff(moments) / moments[2]
    k = int(np.argmin(gaps))
    return (k, k + 1, float(gaps[k])) if gaps[k] < NEARLY_EQUAL_RELATIVE_GAP else None


class InertiaExplorerScene(Scene):
    id = "inertia-explorer"
    title = "Inertia explorer: a composite body, its principal axes and inertia ellipsoid"
    chapter = 5
    example = composite_body.EXAMPLE
    controls = (FRAME_SEQUENCE, FRAME_ANGLES, SHOW_ELLIPSOID)
    presets = tuple(
        Preset(name, label, {"bodies": PRESET_BODIES[name], "about_point_m": [0.0, 0.0, 0.0]}, description)
        for name, (label, description) in PRESET_TEXT.items()
    )
    camera_position = (1.2, -1.6, 1.0)
    camera_look_at = (0.0, 0.0, 0.0)

    def build(self) -> None:
        scene = self.client.scene
        self._span = 1.0
        self._centre = np.zeros(3)
        self._drawn_bodies: list[dict[str, Any]] | None = None
        self._part_handles: list[Any] = []
        self.reference_axes = scene.add_line_segments(
            "/reference/axes",
            np.zeros((3, 2, 3), np.float32),
            np.full((3, 2, 3), 120, np.uint8),
            thickness=2.0,
            thickness_units="screen",
        )
        self.reference_labels = [scene.add_label(f"/reference/{n}", n, anchor="center-center") for n in "xyz"]
        self.centre_marker = scene.add_icosphere("/centre_of_mass", radius=0.01, color=(20, 20, 20))
        self.centre_label = scene.add_label("/centre_of_mass/label", "G", anchor="bottom-left")
        self.point_marker = scene.add_icosphere("/point_P", radius=0.008, color=(120, 60, 160))
        self.point_label = scene.add_label("/point_P/label", "P", anchor="top-right")
        self.ellipsoid = scene.add_icosphere(
            "/ellipsoid", radius=1.0, color=(90, 170, 230), subdivisions=4, opacity=0.22
        )
        self.principal_arrows = scene.add_arrows(
            "/principal/arrows",
            np.zeros((3, 2, 3), np.float32),
            AXIS_COLORS,
            shaft_radius=0.004,
            head_radius=0.01,
            head_length=0.025,
        )
        self.principal_labels = [
            scene.add_label(f"/principal/label{k + 1}", str(k + 1), anchor="center-left") for k in range(3)
        ]
        self.turned_axes = scene.add_line_segments(
            "/turned/axes",
            np.zeros((3, 2, 3), np.float32),
            np.repeat(TURNED_FRAME_COLORS[:, None, :], 2, axis=1),
            thickness=3.0,
            thickness_units="screen",
        )
        self.turned_labels = [scene.add_label(f"/turned/{n}", n, anchor="center-center") for n in ("x′", "y′", "z′")]

    # -- parameters -> physics ------------------------------------------------------
    def update(self) -> None:
        bodies = self.params["bodies"]
        if bodies != self._drawn_bodies:
            self.body = composite_body.composite_from_inputs(self.params)
            self._drawn_bodies = [dict(record) for record in bodies]
            self._span = body_span_m(self.body)
            self._centre = self.body.centre_of_mass_m
            self._draw_parts()
            self._draw_principal()
        self._point = np.asarray(self.params["about_point_m"], float)
        self.R_turned = matrix_from_angles(np.radians(self.params["frame_angles_deg"]), self.params["frame_sequence"])
        self.inertia_turned = tensor_in_turned_frame(self.body.inertia_cm_kg_m2, self.R_turned)
        self._draw_frames()

    # -- drawing ------------------------------------------------------------------------
    def camera_view(self):
        c, s = self._centre, self._span
        return (float(c[0] + 0.75 * s), float(c[1] - 1.05 * s), float(c[2] + 0.6 * s)), (
            float(c[0]),
            float(c[1]),
            float(c[2]),
        )

    def _draw_parts(self) -> None:
        for handle in self._part_handles:
            handle.remove()
        thickness = 0.02 * self._span
        self._part_handles = [
            self._add_part(f"/body/part{k}", part, thickness) for k, part in enumerate(self.body.parts)
        ]

    def _add_part(self, name: str, part: Part, thickness_m: float):
        """One primitive as a mesh in its place and orientation; a hole red and a little proud of its part."""
        scene = self.client.scene
        size = dict(part.dimensions_m)
        proud = 1.6 if part.hole else 1.0
        style: _PartStyle = {
            "color": HOLE_COLOR if part.hole else SOLID_COLOR,
            "wxyz": quaternion_from_matrix(part.rotation),
            "position": part.position_m,
        }
        if part.hole:
            # Slightly larger than the material it removes, so it shows through both faces.
            size = {k: v * 1.01 if k != "inner_radius_m" else v * 0.99 for k, v in size.items()}
        shape = part.shape.name
        if shape in ("sphere", "spherical-shell"):
            return scene.add_icosphere(
                name, radius=size["radius_m"], subdivisions=3, wireframe=shape == "spherical-shell", **style
            )
        if shape == "cylinder":
            return scene.add_cylinder(name, radius=size["radius_m"], height=size["length_m"], **style)
        if shape == "tube":
            vertices, faces = _tube_mesh(size["radius_m"], size["inner_radius_m"], size["length_m"])
            return scene.add_mesh_simple(name, vertices, faces, side="double", **style)
        if shape == "box":
            return scene.add_box(name, dimensions=(size["length_m"], size["width_m"], size["height_m"]), **style)
        if shape == "rod":
            return scene.add_cylinder(name, radius=0.5 * thickness_m * proud, height=size["length_m"], **style)
        if shape == "plate":
            return scene.add_box(name, dimensions=(size["length_m"], size["width_m"], thickness_m * proud), **style)
        if shape == "disk":
            return scene.add_cylinder(name, radius=size["radius_m"], height=thickness_m * proud, **style)
        if shape == "cone":
            vertices, faces = _cone_mesh(size["radius_m"], size["height_m"])
            return scene.add_mesh_simple(name, vertices, faces, **style)
        raise ValueError(f"bodies: the scene cannot draw a {shape!r}")

    def _draw_principal(self) -> None:
        principal = self.body.principal
        G, span = self.body.centre_of_mass_m, self._span
        self.centre_marker.position = tuple(G)
        self.centre_marker.radius = 0.025 * span
        self.centre_label.position = tuple(G + 0.03 * span)
        length = 0.75 * span
        self.principal_arrows.points = arrow_segments(np.repeat(G[None, :], 3, axis=0), principal.axes, length)
        self.principal_arrows.shaft_radius = 0.008 * span
        self.principal_arrows.head_radius = 0.02 * span
        self.principal_arrows.head_length = 0.05 * span
        for k, label in enumerate(self.principal_labels):
            label.position = tuple(G + 1.08 * length * principal.axes[k])
            label.text = f"{k + 1}: I{SUBSCRIPTS[k]} = {principal.moments_kg_m2[k]:.4g} kg·m²"
        self.ellipsoid.position = tuple(G)
        self.ellipsoid.wxyz = quaternion_from_matrix(principal.axes.T)
        semi_a, semi_b, semi_c = inertia.inertia_ellipsoid_semi_axes_m(principal.moments_kg_m2, size_m=0.5 * span)
        self.ellipsoid.scale = (float(semi_a), float(semi_b), float(semi_c))
        reference = 0.35 * span * np.eye(3)
        self.reference_axes.points = np.stack([np.zeros((3, 3)), reference], axis=1).astype(np.float32)
        for label, tip in zip(self.reference_labels, reference * 1.15):
            label.position = tuple(tip)

    def _draw_frames(self) -> None:
        G, span = self.body.centre_of_mass_m, self._span
        self.ellipsoid.visible = self.params["show_ellipsoid"] == "yes"
        axes = 0.55 * span * self.R_turned.T  # rows: x′, y′, z′ in reference components
        self.turned_axes.points = np.stack([np.repeat(G[None, :], 3, axis=0), G + axes], axis=1).astype(np.float32)
        for label, tip in zip(self.turned_labels, G + 1.1 * axes):
            label.position = tuple(tip)
        self.point_marker.position = tuple(self._point)
        self.point_marker.radius = 0.015 * span
        self.point_label.position = tuple(self._point)

    # -- numbers ------------------------------------------------------------------------
    def readout(self) -> Readout:
        body, principal = self.body, self.body.principal
        tensor = self.inertia_turned
        noise = ROUNDING_NOISE * float(np.trace(tensor))

        def component(value: float) -> float:
            return 0.0 if abs(value) < noise else float(value)

        inertia_P = tensor_in_turned_frame(body.inertia_about_kg_m2(self._point), self.R_turned)
        quantities = [
            Quantity("mass", "mass m", body.mass_kg, "kg"),
            *(
                Quantity(f"centre_of_mass_{c}", f"centre of mass {c}_G", float(v), "m")
                for c, v in zip("xyz", body.centre_of_mass_m)
            ),
            *(
                Quantity(f"I_{c}{c}", f"moment I_{c}′{c}′ about G", component(tensor[i, i]), "kg·m²")
                for i, c in enumerate("xyz")
            ),
            *(
                Quantity(
                    f"I_{a}{b}",
                    f"product I_{a}′{b}′ = ∫{a}′{b}′ dm (tensor entry −I_{a}′{b}′)",
                    component(-tensor[i, j]),
                    "kg·m²",
                )
                for i, j, a, b in ((0, 1, "x", "y"), (0, 2, "x", "z"), (1, 2, "y", "z"))
            ),
            Quantity("trace", "I_x′x′ + I_y′y′ + I_z′z′ (the same on every frame)", float(np.trace(tensor)), "kg·m²"),
            *(
                Quantity(f"I_{k + 1}", f"principal moment I{SUBSCRIPTS[k]} about G", float(m), "kg·m²")
                for k, m in enumerate(principal.moments_kg_m2)
            ),
            Quantity.word("degeneracy", "principal axes", self._degeneracy_text()),
            *(
                Quantity(f"I_{c}{c}_P", f"moment about P along {c}′", float(inertia_P[i, i]), "kg·m²")
                for i, c in enumerate("xyz")
            ),
        ]
        message = (
            "Products of inertia are I_x′y′ = ∫x′y′ dm; the tensor holds −I_x′y′ off its diagonal. Turn the frame: "
            "the components change, the principal moments and the trace do not. Rods, plates and disks are idealised "
            "as having no thickness (a slender rod has no inertia about its own axis)."
        )
        return Readout(quantities, message=message)

    def _degeneracy_text(self) -> str:
        principal = self.body.principal
        if principal.degeneracy == "spherical":
            return "I₁ = I₂ = I₃: every axis is principal (axes drawn along the reference frame's own)"
        if principal.degeneracy == "axisymmetric":
            i, j = principal.repeated
            return f"I{SUBSCRIPTS[i]} = I{SUBSCRIPTS[j]}: every axis in the plane of {i + 1} and {j + 1} is principal"
        pair = nearly_equal_pair(principal)
        if pair is not None:
            i, j, gap = pair
            return (
                f"distinct, but I{SUBSCRIPTS[i]} and I{SUBSCRIPTS[j]} are nearly equal (they differ by {gap:.1e} "
                "of I₃): "
                f"axes {i + 1} and {j + 1} are well defined, yet swing far for tiny changes of the body"
            )
        return "three distinct moments: the principal axes are unique"
