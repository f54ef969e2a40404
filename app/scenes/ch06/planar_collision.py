"""Scene for the worked example ``planar-collision``: two disks before, at and after impact.

The plane of motion (x right, y up) is the world xz plane at y = 0, seen from −y. Disk 1 blue,
disk 2 orange; a spoke on each shows its spin. Faint outlines mark where they touch. The
animation runs the time t from before the impact (t < 0, velocities before) to after it
(t > 0, velocities after) and repeats. Arrows: momenta m v before (light, at the contact
outlines' centres) and after (dark, on the moving disks), and the impulse on disk 2 (red, at the
contact point). All arrows share one scale. Every number comes from the example's ``collide``.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.systems.ch06 import planar_collision as physics
from app.scenes.kit import Preset, Quantity, Readout, Scene, arrow_segments, circle_segments
from app.scenes.kit.planar import to_world

DISK_COLORS = ((40, 100, 220), (230, 130, 30))
ARROW_COLORS = np.array([[150, 180, 240], [245, 195, 140], [30, 70, 180], [200, 100, 10], [215, 40, 40]], np.uint8)
PLANE_NORMAL = (0.0, 1.0, 0.0)  # the world normal of the plane of motion
LOOP_S = 4.0  # wall-clock seconds for one pass from before to after
GRAZING_RATIO = 0.05  # normal approach below this fraction of the contact speed: call it grazing


class PlanarCollisionScene(Scene):
    id = "planar-collision"
    title = "Two disks collide"
    chapter = 6
    example = physics.EXAMPLE
    animated = True
    slider_ranges = {
        "m1_kg": (0.1, 10.0, 0.1),
        "m2_kg": (0.1, 10.0, 0.1),
        "r1_m": (0.05, 1.0, 0.01),
        "r2_m": (0.05, 1.0, 0.01),
        "omega1_rad_s": (-50.0, 50.0, 0.5),
        "omega2_rad_s": (-50.0, 50.0, 0.5),
        "friction_coefficient": (0.0, 2.0, 0.01),
    }
    presets = (
        Preset(
            "head-on-elastic",
            "Head-on, elastic",
            {
                "line_of_centres_deg": 0.0,
                "restitution": 1.0,
                "friction_coefficient": 0.0,
                "omega1_rad_s": 0.0,
                "omega2_rad_s": 0.0,
            },
            "e = 1, μ = 0: no energy is lost and no disk starts to spin.",
        ),
        Preset(
            "plastic",
            "Plastic (e = 0)",
            {"restitution": 0.0},
            "The contact points leave with no normal separation speed: the most energy the normal impulse can take.",
        ),
        Preset(
            "oblique-sticks",
            "Oblique, high friction",
            {"line_of_centres_deg": 60.0, "friction_coefficient": 1.5},
            "Friction is strong enough to stop the sliding during the impact: the contact sticks and both disks "
            "spin up.",
        ),
        Preset(
            "spin-kick",
            "A spinning disk",
            {"line_of_centres_deg": 0.0, "omega2_rad_s": 30.0, "friction_coefficient": 0.3},
            "A head-on hit, but disk 2 spins: friction turns spin into sideways motion of both disks.",
        ),
        Preset(
            "grazing",
            "Grazing",
            {"line_of_centres_deg": 88.0, "friction_coefficient": 0.3},
            "The disks barely touch: the normal approach speed is small, and so are the impulse and the loss.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.elapsed_s = 0.0
        self._span = 1.0
        self._center = np.zeros(3)
        self.backdrop = scene.add_grid(
            "/backdrop", width=4.0, height=4.0, plane="xz", cell_size=0.1, section_size=0.5, position=(0.0, 0.05, 0.0)
        )
        self.ghosts = scene.add_line_segments(
            "/ghosts", np.zeros((2, 2, 3), np.float32), (170, 170, 170), thickness=1.5, thickness_units="screen"
        )
        self.rims = [
            scene.add_line_segments(
                f"/disk{i + 1}", np.zeros((1, 2, 3), np.float32), color, thickness=3.0, thickness_units="screen"
            )
            for i, color in enumerate(DISK_COLORS)
        ]
        self.spokes = scene.add_line_segments(
            "/spokes",
            np.zeros((2, 2, 3), np.float32),
            np.array(DISK_COLORS, np.uint8)[:, None, :].repeat(2, 1),
            thickness=3.0,
            thickness_units="screen",
        )
        self.contact = scene.add_point_cloud(
            "/contact", np.zeros((1, 3), np.float32), (215, 40, 40), point_size=0.03, point_shape="circle"
        )
        self.arrows = scene.add_arrows(
            "/arrows",
            np.zeros((5, 2, 3), np.float32),
            ARROW_COLORS,
            shaft_radius=0.01,
            head_radius=0.025,
            head_length=0.05,
        )
        self.labels = [scene.add_label(f"/arrows/label{i}", "", anchor="center-left") for i in range(5)]
        self.legend = scene.add_label("/legend", "", anchor="bottom-left")

    def camera_view(self):
        c, span = self._center, self._span
        return (float(c[0]), float(-0.95 * span), float(c[2] + 0.05 * span)), (float(c[0]), 0.0, float(c[2]))

    def update(self) -> None:
        self.collision = physics.collide(self.params)
        c = self.collision
        (d1, d2), (a1, a2) = c.before, c.after
        reach = d1.radius_m + d2.radius_m
        speeds = [float(np.linalg.norm(d.velocity_m_s)) for d in (d1, d2, a1, a2)]
        # Show the time window in which the fastest disk moves one sum of radii.
        self._window_s = reach / max(max(speeds), 1e-9)
        self.elapsed_s = 0.0
        low = np.minimum(-d1.radius_m * np.ones(2), d2.centre_m[:2] - d2.radius_m) - reach
        high = np.maximum(d1.radius_m * np.ones(2), d2.centre_m[:2] + d2.radius_m) + reach
        self._span = float(max(high - low))
        self._center = to_world(0.5 * (low + high))
        span = self._span
        self.backdrop.width = self.backdrop.height = 1.2 * span
        self.backdrop.position = (float(self._center[0]), 0.05 * span, float(self._center[2]))
        self.backdrop.cell_size = 10 ** math.floor(math.log10(span / 4.0))
        self.backdrop.section_size = 5 * self.backdrop.cell_size
        self.ghosts.points = np.concatenate(
            [circle_segments(radius=d.radius_m, center=to_world(d.centre_m[:2]), normal=PLANE_NORMAL) for d in (d1, d2)]
        )
        self.contact.points = to_world(c.contact_point_m[:2])[None, :].astype(np.float32)
        self.contact.point_size = 0.02 * span
        momenta = [d.momentum_N_s for d in (d1, d2, a1, a2)]
        largest = max(max(float(np.linalg.norm(p)) for p in momenta), float(np.linalg.norm(c.impulse_N_s)), 1e-12)
        self._arrow_scale = 0.9 * reach / largest  # m of arrow per N·s
        self.arrows.shaft_radius = 0.005 * span
        self.arrows.head_radius = 0.012 * span
        self.arrows.head_length = 0.025 * span
        self.legend.position = (float(low[0]), 0.0, float(high[1]))
        self.legend.text = "light: m v before · dark: m v after · red: impulse on disk 2 (same scale, N·s)"
        self._draw()

    def _disk_at(self, t_s: float) -> list[tuple[np.ndarray, float]]:
        """Centre (m, (3,) plane) and spoke angle (rad) of each disk at time t_s from the impact."""
        c = self.collision
        states = c.before if t_s < 0.0 else c.after
        return [(d.centre_m + d.velocity_m_s * t_s, d.spin_rad_s * t_s) for d in states]

    def _draw(self) -> None:
        c = self.collision
        placed = self._disk_at(self.t_s)
        spokes = []
        for rim, disk, (centre, angle) in zip(self.rims, c.before, placed):
            world = to_world(centre[:2])
            rim.points = circle_segments(radius=disk.radius_m, center=world, normal=PLANE_NORMAL)
            spokes.append([world, world + disk.radius_m * np.array([math.cos(angle), 0.0, math.sin(angle)])])
        self.spokes.points = np.array(spokes, np.float32)
        (d1, d2), (a1, a2) = c.before, c.after
        tails = np.array(
            [
                to_world(d1.centre_m[:2]),
                to_world(d2.centre_m[:2]),
                to_world(placed[0][0][:2]),
                to_world(placed[1][0][:2]),
                to_world(c.contact_point_m[:2]),
            ]
        )
        vectors = np.array(
            [
                to_world(v[:2])
                for v in (d1.momentum_N_s, d2.momentum_N_s, a1.momentum_N_s, a2.momentum_N_s, c.impulse_N_s)
            ]
        )
        self.arrows.points = arrow_segments(tails, vectors, self._arrow_scale)
        after = self.t_s >= 0.0
        texts = (
            "" if after else f"m₁v₁ = {np.linalg.norm(d1.momentum_N_s):.3g} N·s",
            "" if after else f"m₂v₂ = {np.linalg.norm(d2.momentum_N_s):.3g} N·s",
            f"m₁v₁' = {np.linalg.norm(a1.momentum_N_s):.3g} N·s" if after else "",
            f"m₂v₂' = {np.linalg.norm(a2.momentum_N_s):.3g} N·s" if after else "",
            f"P = {np.linalg.norm(c.impulse_N_s):.3g} N·s",
        )
        for label, tail, vector, text in zip(self.labels, tails, vectors, texts):
            label.position = tuple(tail + 1.05 * self._arrow_scale * vector)
            label.text = text

    #: The motion's clock is the simulated time since the pass began (≥ 0), not the time from impact.
    motion_attributes = {"t_s": "elapsed_s"}

    # Read-only where Scene keeps a writable clock: this scene overrides step_motion, which alone writes it.
    @property
    def t_s(self) -> float:  # type: ignore[override]
        """Simulated time from the impact (s): negative before it."""
        return self.elapsed_s - self._window_s

    def step_motion(self, dt_s: float) -> bool:
        """One pass from ``window`` before the impact to ``window`` after takes :data:`LOOP_S` of wall-clock time."""
        self.elapsed_s = (self.elapsed_s + dt_s * 2.0 * self._window_s / LOOP_S) % (2.0 * self._window_s)
        return True

    def step_without_drawing(self, t_s: float) -> None:
        """A closed form: the pass at ``t_s`` simulated seconds from its start (passes repeat)."""
        self.elapsed_s = t_s % (2.0 * self._window_s)

    def readout(self) -> Readout:
        c = self.collision
        (_, _), (a1, a2) = c.before, c.after
        p_n, p_t = c.impact.impulse_N_s
        vn, vt = c.contact_velocity_m_s
        quantities = [
            Quantity("t_s", "time from impact t", self.t_s, "s"),
            Quantity("v1_after_x", "disk 1 velocity after, x", float(a1.velocity_m_s[0]), "m/s"),
            Quantity("v1_after_y", "disk 1 velocity after, y", float(a1.velocity_m_s[1]), "m/s"),
            Quantity("v2_after_x", "disk 2 velocity after, x", float(a2.velocity_m_s[0]), "m/s"),
            Quantity("v2_after_y", "disk 2 velocity after, y", float(a2.velocity_m_s[1]), "m/s"),
            Quantity("omega1_after", "disk 1 spin after ω₁'", a1.spin_rad_s, "rad/s"),
            Quantity("omega2_after", "disk 2 spin after ω₂'", a2.spin_rad_s, "rad/s"),
            Quantity("impulse_x", "impulse on disk 2, x", float(c.impulse_N_s[0]), "N·s"),
            Quantity("impulse_y", "impulse on disk 2, y", float(c.impulse_N_s[1]), "N·s"),
            Quantity("impulse_normal", "normal impulse Pₙ", float(p_n), "N·s"),
            Quantity("impulse_tangential", "tangential (friction) impulse Pₜ", float(p_t), "N·s"),
            Quantity("approach_speed", "normal approach speed −vₙ", float(-vn), "m/s"),
            Quantity("energy_before", "kinetic energy before T", c.energy_before_J, "J"),
            Quantity("energy_loss", "energy lost ΔT", c.impact.energy_loss_J, "J"),
            Quantity.word("slip_state", "contact", c.impact.slip_state),
        ]
        words = {
            "slid throughout": "The contact points slid over each other for the whole impact; friction took μ Pₙ.",
            "stuck": (
                "Friction stopped the sliding during the impact and the contact points then moved together (stuck)."
            ),
            "reversed": "The sliding stopped and started again the other way.",
        }
        message = words[c.impact.slip_state]
        if -vn < GRAZING_RATIO * math.hypot(vn, vt):
            message += (
                f" Grazing: the normal approach speed is only {100 * -vn / math.hypot(vn, vt):.2g}% of the "
                "contact speed. "
                "A rigid-body impact assumes the contact lasts an instant; for real bodies this glancing a touch "
                "may roll or rub instead."
            )
        return Readout(quantities, message=message)
