"""Scene: the torque-free axisymmetric body, its body cone rolling on the space cone.

Drawn in display units with the centre of mass at the origin and the fixed
angular momentum ``L`` up the world +Z axis. The body is the uniform spheroid
with the same inertia ratio (a lentil or coin when oblate, a cigar or rod when
prolate), painted in sectors so its spin shows. Things fixed in space are blue
(``L``, the space cone), things fixed in the body red (the symmetry axis, the
body cone), and ω orange: it is the line along which the two cones touch.

Every frame is the closed form at the frame time (no integration, no drift):
ω and the symmetry axis are constant on the *nodal frame* ``Rz(φ)``, so they are
children of one node whose orientation is the only thing that precesses, and
the body is a child of it turned by ``Rx(θ) Rz(ψ)``. A frame therefore costs
two orientation updates whatever the parameters.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from app.physics.systems.ch10 import torque_free_axisymmetric as physics
from app.scenes.kit import Mark, Preset, Quantity, Readout, Scene, arrow_segments

BODY_SIZE = 0.7  # display units: the body's largest semi-axis
MIN_THICKNESS = 0.05  # the flattest body is drawn this thick (relative to its radius) so a disc stays visible
CONE_SLANT = 1.3  # display units from the apex (centre of mass) to a cone's rim
AXIS_ARROW = CONE_SLANT + 0.35  # past the body cone's rim, so its label stands clear
OMEGA_ARROW = CONE_SLANT + 0.3  # its tip stands just beyond the point where the rims touch
L_ARROW = CONE_SLANT + 0.75
HIDDEN_CONE_RAD = math.radians(0.2)  # narrower cones than this are not drawn

SPACE_BLUE = (50, 110, 220)
BODY_RED = (205, 55, 70)
OMEGA_ORANGE = (240, 140, 20)
BODY_LIGHT = (236, 232, 224)
BODY_DARK = (60, 70, 90)

#: Slider ranges (min, max, step): within them every combination is a real body, so the lesson's
#: controls cannot produce an invalid one (I_axial ≤ 1 ≤ 2·I_transverse, spin > 0, θ ≤ 70°).
SLIDER_RANGES: Mapping[str, tuple[float, float, float]] = {
    "I_transverse": (0.5, 2.0, 0.01),
    "I_axial": (0.02, 1.0, 0.01),
    "spin_rad_s": (0.1, 5.0, 0.05),
    "nutation_deg": (0.0, 70.0, 0.5),
}


def spheroid_sectors(
    *, axial: float, transverse: float, sectors: int = 8, rings: int = 24, segments: int = 64
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A spheroid about +z (semi-axes ``transverse``, ``transverse``, ``axial``) as one vertex array and two face
    arrays.

    The faces are split into ``sectors`` alternating longitude sectors so that the two
    halves can be drawn in two colours and the spin is visible.
    """
    polar = np.linspace(0.0, math.pi, rings + 1)
    azimuth = np.linspace(0.0, 2.0 * math.pi, segments, endpoint=False)
    sp, cp = np.sin(polar)[:, None], np.cos(polar)[:, None]
    vertices = np.stack(
        [
            transverse * sp * np.cos(azimuth),
            transverse * sp * np.sin(azimuth),
            np.broadcast_to(axial * cp, (rings + 1, segments)),
        ],
        axis=-1,
    ).reshape(-1, 3)
    faces: list[list[tuple[int, int, int]]] = [[], []]
    per_sector = segments // sectors
    for i in range(rings):
        for j in range(segments):
            jn = (j + 1) % segments
            a, b, c, d = i * segments + j, i * segments + jn, (i + 1) * segments + j, (i + 1) * segments + jn
            colour = (j // per_sector) % 2
            faces[colour].append((a, c, d))
            faces[colour].append((a, d, b))
    return vertices.astype(np.float32), np.asarray(faces[0], np.uint32), np.asarray(faces[1], np.uint32)


def cone_mesh(
    half_angle_rad: float, *, slant: float = CONE_SLANT, segments: int = 96
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A cone with its apex at the origin and axis +z: vertices, faces and its rim points (display units)."""
    azimuth = np.linspace(0.0, 2.0 * math.pi, segments, endpoint=False)
    radius, height = slant * math.sin(half_angle_rad), slant * math.cos(half_angle_rad)
    rim = np.stack([radius * np.cos(azimuth), radius * np.sin(azimuth), np.full(segments, height)], axis=1)
    vertices = np.vstack([np.zeros((1, 3)), rim]).astype(np.float32)
    faces = np.array([(0, 1 + j, 1 + (j + 1) % segments) for j in range(segments)], np.uint32)
    return vertices, faces, rim


def _ring_segments(points: np.ndarray) -> np.ndarray:
    """(N, 2, 3) segments joining the closed loop of ``points`` (N, 3)."""
    return np.stack([points, np.roll(points, -1, axis=0)], axis=1).astype(np.float32)


def _rulings(rim: np.ndarray, count: int) -> np.ndarray:
    """(count, 2, 3) segments from the apex (origin) to ``count`` evenly spaced rim points."""
    picks = rim[:: max(1, len(rim) // count)][:count]
    return np.stack([np.zeros_like(picks), picks], axis=1).astype(np.float32)


class TorqueFreeAxisymmetricScene(Scene):
    id = "torque-free-axisymmetric"
    title = "Torque-free axisymmetric body: body and space cones"
    chapter = 10
    animated = True
    model = physics.TorqueFreeAxisymmetric
    slider_ranges = SLIDER_RANGES
    presets = (
        Preset(
            "football",
            "Football (prolate)",
            {"I_transverse": 1.0, "I_axial": 0.4, "spin_rad_s": 3.0, "nutation_deg": 25.0},
            "A spheroid twice as long as it is wide, I_a/I_t = 0.4: direct precession, the body cone rolls round "
            "the outside of the space cone.",
        ),
        Preset(
            "pencil",
            "Tumbling rod (prolate)",
            {"I_transverse": 2.0, "I_axial": 0.1, "spin_rad_s": 4.0, "nutation_deg": 65.0},
            "A slender body, I_a/I_t = 0.05, thrown with its axis far from L: a thin body cone rolls round a "
            "wide space cone.",
        ),
        Preset(
            "coin",
            "Wobbling coin (oblate)",
            {"I_transverse": 0.5, "I_axial": 0.99, "spin_rad_s": 1.0, "nutation_deg": 15.0},
            "A thin disc, I_a/I_t = 1.98: retrograde precession nearly twice as fast as the spin; the space cone "
            "sits inside the body cone.",
        ),
        Preset(
            "near-sphere",
            "Nearly a sphere (oblate)",
            {"I_transverse": 0.95, "I_axial": 1.0, "spin_rad_s": 2.0, "nutation_deg": 20.0},
            "I_a/I_t = 1.053, like a slightly flattened planet: ω stays within about 1° of L and circles the "
            "axis slowly, seen from the body.",
        ),
    )
    camera_position = (1.6, -2.0, 1.65)
    camera_look_at = (0.0, 0.0, 0.5)

    def build(self) -> None:
        scene = self.client.scene
        scene.add_grid("/ground", width=2.5, height=2.5, cell_size=0.25, section_size=1.25, position=(0.0, 0.0, -0.9))
        scene.add_icosphere("/centre_of_mass", radius=0.03, color=(30, 30, 30))
        scene.add_arrows(
            "/L",
            arrow_segments(np.zeros(3), np.array([0.0, 0.0, L_ARROW]), 1.0),
            np.array([SPACE_BLUE], np.uint8),
            shaft_radius=0.02,
            head_radius=0.055,
            head_length=0.11,
        )
        scene.add_label("/L/label", "L (fixed)", position=(0.0, 0.0, L_ARROW + 0.05), anchor="bottom-center")
        self.nodal = scene.add_frame("/nodal", show_axes=False)
        self.body = scene.add_frame("/nodal/body", show_axes=False)
        # ω and the symmetry axis are constant on the nodal frame: placed in update(), never per frame.
        self.vectors = scene.add_arrows(
            "/nodal/vectors",
            np.zeros((2, 2, 3), np.float32),
            np.array([BODY_RED, OMEGA_ORANGE], np.uint8),
            shaft_radius=0.02,
            head_radius=0.055,
            head_length=0.11,
        )
        # The symmetry axis continues below the centre of mass as a thin line, labelled at its far
        # end, where the label never meets ω's (ω is always within 90° of the upper half of k).
        self.axis_tail = scene.add_line_segments(
            "/nodal/axis_tail", np.zeros((1, 2, 3), np.float32), BODY_RED, thickness=2.0, thickness_units="screen"
        )
        self.axis_label = scene.add_label("/nodal/axis_label", "symmetry axis", anchor="top-center")
        self.omega_label = scene.add_label("/nodal/omega_label", "ω", anchor="center-left")
        self.t_s = 0.0

    def update(self) -> None:
        """Redraw for new parameters: the meshes are replaced under the same names, the rest moved."""
        self.motion = motion = physics.motion_from_params(self.params)
        self.t_s = 0.0
        scene = self.client.scene

        # The body: a uniform spheroid with these moments, largest semi-axis BODY_SIZE.
        aspect = max(physics.spheroid_aspect_ratio(motion.inertia_ratio), MIN_THICKNESS)
        axial, transverse = (BODY_SIZE, BODY_SIZE / aspect) if aspect >= 1.0 else (BODY_SIZE * aspect, BODY_SIZE)
        vertices, light, dark = spheroid_sectors(axial=axial, transverse=transverse)
        scene.add_mesh_simple("/nodal/body/light", vertices, light, color=BODY_LIGHT)
        scene.add_mesh_simple("/nodal/body/dark", vertices, dark, color=BODY_DARK)

        # The cones: body cone fixed in the body (about k), space cone fixed in space (about L = +Z).
        for path, half_angle, colour in (
            ("/nodal/body/cone", motion.body_cone_half_angle_rad, BODY_RED),
            ("/space_cone", motion.space_cone_half_angle_rad, SPACE_BLUE),
        ):
            shown = half_angle >= HIDDEN_CONE_RAD
            cone_vertices, cone_faces, rim = cone_mesh(half_angle)
            scene.add_mesh_simple(
                path,
                cone_vertices,
                cone_faces,
                color=colour,
                opacity=0.28,
                side="double",
                cast_shadow=False,
                receive_shadow=False,
                visible=shown,
            )
            scene.add_line_segments(
                f"{path}_rim", _ring_segments(rim), colour, thickness=2.5, thickness_units="screen", visible=shown
            )
            scene.add_line_segments(
                f"{path}_rulings", _rulings(rim, 12), colour, thickness=1.2, thickness_units="screen", visible=shown
            )

        k = motion.symmetry_axis_nodal()
        omega = motion.angular_velocity_nodal_rad_s()
        omega_dir = omega / np.linalg.norm(omega)
        self.vectors.points = arrow_segments(np.zeros((2, 3)), np.array([AXIS_ARROW * k, OMEGA_ARROW * omega_dir]), 1.0)
        tail = -(BODY_SIZE + 0.25) * k
        self.axis_tail.points = np.array([[np.zeros(3), tail]], np.float32)
        self.axis_label.position = tuple(tail)
        self.omega_label.position = tuple((OMEGA_ARROW + 0.06) * omega_dir)

        # The circle the tip of the symmetry axis sweeps round L (dashed).
        theta = motion.nutation_rad
        azimuth = np.linspace(0.0, 2.0 * math.pi, 96, endpoint=False)
        r, h = AXIS_ARROW * math.sin(theta), AXIS_ARROW * math.cos(theta)
        ring = np.stack([r * np.cos(azimuth), r * np.sin(azimuth), np.full(96, h)], axis=1)
        scene.add_line_segments(
            "/axis_path",
            _ring_segments(ring)[::2],
            BODY_RED,
            thickness=1.5,
            thickness_units="screen",
            visible=theta >= HIDDEN_CONE_RAD,
        )
        self._draw()

    def _draw(self) -> None:
        self.nodal.wxyz, self.body.wxyz = self.motion.nodal_and_body_quaternions(self.t_s)

    def readout(self) -> Readout:
        m = self.motion
        quantities = [
            Quantity("precession_rate", "precession rate φ̇", m.precession_rate_rad_s, "rad/s"),
            Quantity("spin_rate", "spin rate ψ̇ (relative to the line of nodes)", m.spin_rate_rad_s, "rad/s"),
            Quantity.word("sense", "precession sense", m.sense),
            Quantity("body_cone_half_angle", "body cone half-angle β", math.degrees(m.body_cone_half_angle_rad), "deg"),
            Quantity(
                "space_cone_half_angle", "space cone half-angle γ", math.degrees(m.space_cone_half_angle_rad), "deg"
            ),
            Quantity("angular_momentum", "angular momentum |L|", m.angular_momentum_kg_m2_s, "kg·m²/s"),
            Quantity("energy", "kinetic energy T", m.energy_J, "J"),
            Quantity("angular_speed", "angular speed |ω|", m.angular_speed_rad_s, "rad/s"),
            Quantity(
                "body_frame_precession_rate",
                "λ: ω round the axis, seen from the body",
                m.body_frame_precession_rate_rad_s,
                "rad/s",
            ),
            Quantity.or_text(
                "precession_period", "precession period 2π/φ̇", m.precession_period_s, "s", "no precession"
            ),
            Quantity("t_s", "time t", self.t_s, "s"),
        ]
        marks = {
            "I_axial": [
                Mark(self.params["I_transverse"], "sphere"),
                Mark(2.0 * self.params["I_transverse"], "flat disc"),
            ]
        }
        return Readout(quantities, marks=marks, message=_sense_message(m))


def _sense_message(motion: physics.AxisymmetricFreeMotion) -> str:
    if motion.sense == "direct":
        return "Prolate (I_a < I_t): direct precession. The body cone rolls round the outside of the space cone."
    if motion.sense == "retrograde":
        return (
            "Oblate (I_a > I_t): retrograde precession. The space cone sits inside the body cone, which rolls round it."
        )
    return "I_a = I_t: every axis is principal, ω lies along L and the body simply turns about it."
