"""Scene: a disk or a cone rolling without slip, with its contact point's velocity computed.

World frame +Z up, ground z = 0; the contact point circles the origin O. Drawn:
the body (a disk, or a cone whose apex sits at O), the contact circle on the
ground, the instantaneous axis (orange: the line of points momentarily at rest,
through the contact point C and O′ on the vertical through O), and arrows for
the centre's velocity (blue), ω (purple, drawn along the instantaneous axis from
C) and the velocities of eight rim points (green). The contact point's own
velocity v_C = v_G + ω × r_GC is evaluated every frame and drawn to scale: its
arrow has zero length, so C carries a dot and the label of its computed speed.
When the path is much wider than the body (ρ > 6R) the camera frames the start
of the path instead of the whole circle and the exact motion over that stretch
(12 rim radii of travel) replays in a loop, so the body never shrinks to a speck.

One scene with a ``body`` choice rather than two scene ids: the disk and the
cone are the same kinematics (a rim rolling round a circle; the cone is the case
whose instantaneous axis lies on the ground), they share one lesson page, and a
second scene class would be a near-copy of this one.
"""

from __future__ import annotations

import math

import numpy as np
import viser

from app.physics.systems.ch04 import rolling as physics
from app.scenes.kit import Preset, Quantity, Readout, Scene

RIM_ARROWS = 8
#: Paths wider than this many rim radii are shown near the body, replaying a stretch of the motion.
WIDE_PATH_RADII = 6.0
#: Length of the replayed stretch, in rim radii travelled by the contact point.
REPLAY_RADII = 12.0
ARROW_COLORS = np.array([[40, 100, 220], [140, 60, 200], *([[40, 160, 70]] * RIM_ARROWS)], np.uint8)


def cone_mesh(*, radius: float, height: float, segments: int = 64) -> tuple[np.ndarray, np.ndarray]:
    """Cone with its base circle (``radius``) at local z = 0 and apex at z = −``height``, base closed."""
    angles = np.linspace(0.0, 2.0 * math.pi, segments, endpoint=False)
    rim = np.stack([radius * np.cos(angles), radius * np.sin(angles), np.zeros(segments)], axis=1)
    vertices = np.vstack([rim, [[0.0, 0.0, -height], [0.0, 0.0, 0.0]]]).astype(np.float32)
    apex, centre = segments, segments + 1
    faces = []
    for j in range(segments):
        k = (j + 1) % segments
        faces.append((j, apex, k))  # side, outward normal
        faces.append((j, k, centre))  # base cap, facing +z
    return vertices, np.asarray(faces, dtype=np.uint32)


class RollingScene(Scene):
    id = "rolling"
    title = "Rolling without slip: a disk and a cone"
    chapter = 4
    model = physics.SteadyRollingMotion
    animated = True
    presets = (
        Preset(
            "upright-disk",
            "Upright disk",
            {"body": "disk", "tilt_deg": 0.0, "path_radius_m": 1.5},
            "A wheel rolling upright round a circle.",
        ),
        Preset(
            "leaning-disk",
            "Leaning disk",
            {"body": "disk", "tilt_deg": 25.0, "path_radius_m": 1.5},
            "A coin leaning into its turn.",
        ),
        Preset(
            "wide-circle",
            "Nearly straight",
            {"body": "disk", "tilt_deg": 0.0, "path_radius_m": 20.0},
            "A very large circle: close to rolling in a straight line.",
        ),
        Preset(
            "cone",
            "Cone about its apex",
            {"body": "cone", "tilt_deg": 20.0},
            "A cone rolling on its side: ω lies along the line of contact.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.t_s = 0.0
        self._view = (1.5, 0.4, (0.0, 0.0))
        self._replay_s: float | None = None
        self.ground = scene.add_grid("/ground", width=6.0, height=6.0, cell_size=0.1, section_size=0.5)
        self.path = scene.add_line_segments(
            "/path", np.zeros((1, 2, 3), np.float32), (150, 150, 170), thickness=1.5, thickness_units="screen"
        )
        self.body = scene.add_frame("/body", show_axes=False)
        self.body_meshes: list = []
        self.instant_axis = scene.add_line_segments(
            "/instant_axis", np.zeros((1, 2, 3), np.float32), (240, 140, 30), thickness=2.0, thickness_units="screen"
        )
        self.axis_point = scene.add_icosphere("/axis_point", radius=0.03, color=(240, 140, 30))
        self.axis_point_label = scene.add_label("/axis_point/label", "O′ (at rest)", anchor="bottom-left")
        self.arrows = scene.add_arrows("/arrows", np.zeros((2 + RIM_ARROWS, 2, 3), np.float32), ARROW_COLORS)
        self.contact_arrow = scene.add_arrows(
            "/contact_arrow", np.zeros((1, 2, 3), np.float32), (220, 40, 40), visible=False
        )
        self.contact_dot = scene.add_icosphere("/contact", radius=0.03, color=(220, 40, 40))
        self.contact_label = scene.add_label("/contact/label", "", anchor="top-left")
        self._contact_text = ""
        self.legend = scene.add_label("/legend", "", anchor="bottom-center")

    def camera_view(self):
        reach, height, (x, y) = self._view
        return (x + 0.2 * reach, y - 1.15 * reach, 0.8 * reach + height), (x, y + 0.05 * reach, 0.2 * height)

    def update(self) -> None:
        self.rolling = physics.SteadyRolling.from_params(self.params)
        self.t_s = 0.0
        rolling = self.rolling
        R, rho = rolling.rim_radius_m, rolling.path_radius_m
        speed = max(abs(rolling.speed_m_s), 1e-9)
        if rho > WIDE_PATH_RADII * R and rolling.speed_m_s != 0.0:
            # A wide circle would make the body a speck: frame a stretch of the path near the start
            # and replay the (exact) motion over it.
            self._replay_s = REPLAY_RADII * R / speed
            start, end = rolling.at(np.array([0.0, self._replay_s])).contact_point[:, :2]
            self._view = (0.6 * REPLAY_RADII * R, R, tuple(0.5 * (start + end)))
            size = rho + 2.0 * R
        else:
            self._replay_s = None
            self._view = (max(rho + R, 4.0 * R), R, (0.0, 0.0))
            size = max(rho + 2.0 * R, 4.0 * R)
        self.ground.width = self.ground.height = 2.0 * size
        self.ground.cell_size = 10 ** math.floor(math.log10(size / 5.0))
        self.ground.section_size = 5 * self.ground.cell_size
        circle = np.linspace(0.0, 2.0 * math.pi, 181)
        ring = np.stack([rho * np.cos(circle), rho * np.sin(circle), np.zeros_like(circle)], axis=-1)
        self.path.points = np.stack([ring[:-1], ring[1:]], axis=1).astype(np.float32)
        self._build_body()
        self.axis_point.radius = 0.06 * R
        self.contact_dot.radius = 0.07 * R
        self.axis_point.position = tuple(rolling.axis_point)
        for arrows in (self.arrows, self.contact_arrow):
            arrows.shaft_radius, arrows.head_radius, arrows.head_length = 0.035 * R, 0.08 * R, 0.15 * R
        self._velocity_scale = 0.5 * R / speed  # the rim's top (about 2v) gets an arrow one radius long
        self._omega_scale = 0.8 * min(max(rho, 2.0 * R), 4.0 * R) / max(speed / R, 1e-9)
        what = "cone rolling on its side, apex fixed at O" if rolling.body == "cone" else "disk rolling round a circle"
        self.legend.position = (
            (0.0, rho + 1.5 * R, 0.0) if self._replay_s is None else (self._view[2][0], self._view[2][1] + 4.0 * R, 0.0)
        )
        self.legend.text = f"{what} · orange: instantaneous axis · purple: ω · blue: v_G · green: rim velocities"
        self._draw()

    def _build_body(self) -> None:
        for node in self.body_meshes:
            node.remove()
        scene = self.client.scene
        rolling = self.rolling
        R = rolling.rim_radius_m
        spokes = np.linspace(0.0, math.pi, 4, endpoint=False)
        ends = R * 0.98 * np.stack([np.cos(spokes), np.sin(spokes), np.zeros(4)], axis=-1)
        if rolling.body == "cone":
            vertices, faces = cone_mesh(radius=R, height=rolling.cone_height_m)
            mesh: viser.MeshHandle | viser.CylinderHandle = scene.add_mesh_simple(
                "/body/cone", vertices, faces, color=(90, 150, 200), opacity=0.6, side="double"
            )
            # Stripes from the apex to the rim show the spin.
            apex = np.array([0.0, 0.0, -rolling.cone_height_m])
            rim = np.vstack([ends, -ends]) * 1.0 / 0.98
            stripes = np.stack([np.repeat(apex[None], len(rim), axis=0), rim], axis=1)
            lines = scene.add_line_segments(
                "/body/stripes", stripes.astype(np.float32), (30, 60, 100), thickness=1.5, thickness_units="screen"
            )
        else:
            mesh = scene.add_cylinder("/body/disk", radius=R, height=0.06 * R, color=(90, 150, 200), opacity=0.6)
            lines = scene.add_line_segments(
                "/body/spokes",
                np.stack([-ends, ends], axis=1).astype(np.float32) + np.array([0.0, 0.0, 0.035 * R], np.float32),
                (30, 60, 100),
                thickness=1.5,
                thickness_units="screen",
            )
        marker = scene.add_icosphere("/body/marker", radius=0.06 * R, color=(240, 200, 40), position=(-R, 0.0, 0.0))
        self.body_meshes = [mesh, lines, marker]

    def _draw(self) -> None:
        rolling = self.rolling
        state = rolling.at(np.array([self.t_s]))
        self._state = state
        contact, center, omega = state.contact_point[0], state.center[0], state.angular_velocity[0]
        self.body.position = tuple(center)
        self.body.wxyz = tuple(state.wxyz[0])
        rim = rolling.rim_points(state, 0, RIM_ARROWS)
        rim_velocity = rolling.velocity_of(state, 0, rim)
        tails = np.vstack([center, contact, rim])
        vectors = np.vstack(
            [
                state.center_velocity[0] * self._velocity_scale,
                omega * self._omega_scale,
                rim_velocity * self._velocity_scale,
            ]
        )
        self.arrows.points = np.stack([tails, tails + vectors], axis=1).astype(np.float32)
        # The contact point's computed velocity, to the same scale as the others: zero length in practice.
        v_c = state.contact_point_velocity[0]
        contact_arrow = np.array([[contact, contact + v_c * self._velocity_scale]], np.float32)
        long_enough = float(np.linalg.norm(v_c)) * self._velocity_scale > self.contact_arrow.head_length
        if long_enough:
            self.contact_arrow.points = contact_arrow
        if self.contact_arrow.visible != long_enough:
            self.contact_arrow.visible = long_enough
        self.contact_dot.position = tuple(contact)
        text = f"C: v_C = {np.linalg.norm(v_c):.3f} m/s"
        if text != self._contact_text:
            self.contact_label.text = self._contact_text = text
        o_prime = rolling.axis_point
        self.instant_axis.points = np.array([[o_prime, contact + 0.25 * (contact - o_prime)]], np.float32)

    def step_motion(self, dt_s: float) -> bool:
        self.t_s += dt_s
        if self._replay_s is not None and self.t_s > self._replay_s:
            self.t_s -= self._replay_s  # back to the start of the framed stretch
        return True

    def readout(self) -> Readout:
        rolling, state = self.rolling, self._state
        v_c = float(np.linalg.norm(state.contact_point_velocity[0]))
        misalignment = float(rolling.axis_misalignment(state)[0])
        omega = state.angular_velocity[0]
        line_name = "the contact line" if rolling.body == "cone" else "the line C–O′"
        quantities = [
            # To the millimetre per second, as a student would measure it; the next row has the computed round-off.
            Quantity(
                "contact_point_velocity", "contact point velocity |v_C| = |v_G + ω × r_GC|", None, "m/s", f"{v_c:.3f}"
            ),
            Quantity("contact_point_speed", "|v_C| unrounded (round-off)", v_c, "m/s"),
            Quantity(
                "center_speed",
                "speed of the rim's centre |v_G|",
                float(np.linalg.norm(state.center_velocity[0])),
                "m/s",
            ),
            Quantity("angular_speed", "|ω|", float(np.linalg.norm(omega)), "rad/s"),
            Quantity("spin_rate", "spin rate about the axis, −v/R", float(rolling.spin_rate_rad_s), "rad/s"),
            Quantity("turn_rate", "turn rate about Z, v/ρ", float(rolling.turn_rate_rad_s), "rad/s"),
            Quantity("path_radius", "contact circle radius ρ", float(rolling.path_radius_m), "m"),
            Quantity("axis_point_height", "height of O′ above the ground", float(rolling.axis_point[2]), "m"),
            Quantity.or_text(
                "axis_misalignment", f"angle between ω and {line_name}", math.degrees(misalignment), "deg", "at rest"
            ),
            Quantity("t_s", "time t", float(self.t_s), "s"),
        ]
        if rolling.body == "cone":
            message = (
                "ω lies along the line of contact: every point of the cone touching the ground is momentarily at rest."
            )
        else:
            message = (
                f"The instantaneous axis runs from C through O′, {rolling.axis_point[2]:.3f} m up the "
                "vertical through the centre of the path."
            )
        return Readout(quantities, message=message)
