"""Scene: the four-bar linkage in both assemblies, its coupler curve and transmission angle.

The linkage's plane (x along the ground link, y up) is drawn as the world xz
plane at y = 0, seen from −y. Links: crank blue, coupler green (with the coupler
point P on a triangle), rocker red; the other assembly at the same crank angle
is a grey ghost. The coupler curve of P is orange for the assembly shown and
faint grey for the other one. Every frame evaluates the closed form at the
scene's time (no integration, so no drift) and moves two nodes.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.systems.ch04 import four_bar as physics
from app.scenes.kit import Mark, Preset, Quantity, Readout, Scene, update_node
from app.scenes.kit.planar import polyline_segments, to_world

LINK_COLORS = np.array([[40, 100, 220], [40, 150, 70], [210, 70, 50], [120, 190, 130], [120, 190, 130]], np.uint8)
GHOST_COLOR = (175, 175, 185)
CURVE_COLOR = (235, 140, 30)
#: Transmission angles outside [40°, 140°] transmit force poorly (a common design rule).
GOOD_TRANSMISSION_DEG = (40.0, 140.0)
TOGGLE_WINDOW_DEG = 3.0


class FourBarScene(Scene):
    id = "four-bar"
    #: Links, joints and the other assembly: three batched nodes.
    frame_message_budget = 3.0
    title = "The four-bar linkage"
    chapter = 4
    model = physics.FourBarLinkage
    animated = True
    presets = (
        Preset(
            "crank-rocker",
            "Crank-rocker",
            {"ground_m": 1.0, "crank_m": 0.3, "coupler_m": 1.0, "rocker_m": 0.9, "crank_angle0_deg": 60.0},
            "Shortest link is the crank: it turns fully and the rocker rocks.",
        ),
        Preset(
            "double-crank",
            "Double crank",
            {"ground_m": 0.3, "crank_m": 0.7, "coupler_m": 0.9, "rocker_m": 0.8, "crank_angle0_deg": 60.0},
            "Shortest link is the ground: both crank and rocker turn fully (a drag link).",
        ),
        Preset(
            "double-rocker",
            "Double rocker",
            {"ground_m": 1.0, "crank_m": 0.8, "coupler_m": 0.35, "rocker_m": 0.9, "crank_angle0_deg": 60.0},
            "Shortest link is the coupler: the crank only rocks, between two toggle positions.",
        ),
        Preset(
            "parallelogram",
            "Parallelogram (change point)",
            {"ground_m": 1.0, "crank_m": 0.4, "coupler_m": 1.0, "rocker_m": 0.4, "crank_angle0_deg": 60.0},
            "s + l = p + q: twice a turn all links fall in line and the assembly is ambiguous.",
        ),
        Preset(
            "triple-rocker",
            "Non-Grashof",
            {"ground_m": 1.2, "crank_m": 0.9, "coupler_m": 0.7, "rocker_m": 0.6, "crank_angle0_deg": 0.0},
            "s + l > p + q: no link turns fully; the crank rocks between toggle positions.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.t_s = 0.0
        self._t_drawn = 0.0
        self._span = 1.0
        self._center = np.zeros(3)
        self.backdrop = scene.add_grid(
            "/backdrop", width=4.0, height=4.0, plane="xz", cell_size=0.1, section_size=0.5, position=(0.5, 0.05, 0.0)
        )
        self.ground = scene.add_line_segments("/ground", np.zeros((1, 2, 3), np.float32), (80, 80, 80), thickness=0.01)
        self.pivots = scene.add_point_cloud(
            "/pivots", np.zeros((2, 3), np.float32), (40, 40, 40), point_size=0.05, point_shape="circle"
        )
        self.pivot_labels = [scene.add_label(f"/pivots/{name}", name, anchor="top-center") for name in ("O₂", "O₄")]
        self.curve = scene.add_line_segments(
            "/curve/current", np.zeros((1, 2, 3), np.float32), CURVE_COLOR, thickness=2.5, thickness_units="screen"
        )
        self.ghost_curve = scene.add_line_segments(
            "/curve/other", np.zeros((1, 2, 3), np.float32), GHOST_COLOR, thickness=1.5, thickness_units="screen"
        )
        self.ghost = scene.add_line_segments("/ghost", np.zeros((2, 2, 3), np.float32), GHOST_COLOR, thickness=0.01)
        self.links = scene.add_line_segments(
            "/links", np.zeros((5, 2, 3), np.float32), np.repeat(LINK_COLORS[:, None, :], 2, axis=1), thickness=0.02
        )
        self.joints = scene.add_point_cloud(
            "/joints",
            np.zeros((3, 3), np.float32),
            np.array([[30, 30, 30], [30, 30, 30], [235, 140, 30]], np.uint8),
            point_size=0.04,
            point_shape="circle",
        )
        self.legend = scene.add_label("/legend", "", anchor="bottom-left")

    def camera_view(self):
        c, span = self._center, self._span
        return (float(c[0] + 0.08 * span), float(-1.1 * span), float(c[2] + 0.12 * span)), (
            float(c[0]),
            0.0,
            float(c[2]),
        )

    def update(self) -> None:
        self.motion = physics.FourBarMotion.from_params(self.params)
        self.t_s = 0.0
        linkage = self.motion.linkage
        d = linkage.ground_m
        curve = self.motion.coupler_curve()
        other = self.motion.coupler_curve(self.motion.other_branch)
        # Frame everything any joint reaches in either assembly, and both pivots.
        travels = [self.motion.travel_positions(branch, 181) for branch in physics.BRANCHES]
        pts = np.concatenate(
            [curve, other, *[np.concatenate([t.crank_pin, t.rocker_pin]) for t in travels], [[0.0, 0.0], [d, 0.0]]]
        )
        pts = pts[np.isfinite(pts).all(axis=1)]
        low, high = pts.min(axis=0), pts.max(axis=0)
        self._span = float(max(high[0] - low[0], high[1] - low[1], 0.2))
        self._center = to_world(0.5 * (low + high))
        span = self._span
        width = 0.016 * span
        self.links.thickness = width
        self.ghost.thickness = 0.5 * width
        self.ground.thickness = 1.6 * width
        self.pivots.point_size = 0.028 * span
        self.joints.point_size = 0.022 * span
        self.ground.points = np.array([[[0.0, 0.0, 0.0], [d, 0.0, 0.0]]], np.float32)
        self.pivots.points = np.array([[0.0, -0.01 * span, 0.0], [d, -0.01 * span, 0.0]], np.float32)
        for label, x in zip(self.pivot_labels, (0.0, d)):
            label.position = (x, 0.0, -0.05 * span)
        self.curve.points = polyline_segments(curve)
        self.ghost_curve.points = polyline_segments(other)
        grid_size = 2.0 * span
        self.backdrop.width = grid_size
        self.backdrop.height = grid_size
        self.backdrop.position = (float(self._center[0]), 0.05 * span, float(self._center[2]))
        self.backdrop.cell_size = 10 ** math.floor(math.log10(span / 4.0))
        self.backdrop.section_size = 5 * self.backdrop.cell_size
        grashof = linkage.grashof()
        self.legend.position = (float(low[0]), 0.0, float(high[1] + 0.08 * span))
        self.legend.text = f"{grashof.name} · orange: path of P · grey: {self.motion.other_branch} assembly"
        self._draw()

    def _draw(self) -> None:
        """Per frame: the crank angle at the scene's time and both assemblies there (positions only;
        the rates the readout needs are evaluated when it is polled)."""
        motion = self.motion
        theta2 = motion.drive.angle(np.array([self.t_s]))
        assemblies = motion.linkage.assemblies(theta2)
        pos, ghost = assemblies[motion.branch], assemblies[motion.other_branch]
        a, b = pos.crank_pin[0], pos.rocker_pin[0]
        p = physics.coupler_point(pos, distance_m=motion.coupler_point_m, angle_rad=motion.coupler_point_rad)[0]
        if not np.all(np.isfinite([*a, *b, *p])):
            return  # an undetermined instant (A on O₄): keep the last picture
        self._t_drawn = self.t_s
        o2, o4 = np.zeros(2), np.array([motion.linkage.ground_m, 0.0])
        planar = np.array([[o2, a], [a, b], [o4, b], [a, p], [b, p]])
        update_node(self.links, points=to_world(planar))
        update_node(self.joints, points=to_world(np.array([a, b, p])))
        gb = ghost.rocker_pin[0]
        if np.all(np.isfinite(gb)):
            update_node(self.ghost, points=to_world(np.array([[a, gb], [o4, gb]])))

    def readout(self) -> Readout:
        motion = self.motion
        state = motion.at(np.array([self._t_drawn]))  # the full state at the instant on screen
        grashof = motion.linkage.grashof()
        mu = math.degrees(float(state.transmission_angle[0]))
        rocker_rate = float(state.rocker_rate[0])
        quantities = [
            Quantity.word("grashof_class", "Grashof class", grashof.name),
            Quantity.word("crank_travel", "crank travel", motion.crank_range.describe().removeprefix("the crank ")),
            Quantity("t_s", "time t", float(state.t_s[0]), "s"),
            Quantity(
                "crank_angle",
                "crank angle θ₂",
                math.degrees(math.remainder(float(state.crank_angle[0]), 2 * math.pi)),
                "deg",
            ),
            Quantity("transmission_angle", "transmission angle μ", mu, "deg"),
            Quantity.or_text("rocker_rate", "rocker rate ω₄", rocker_rate, "rad/s", "unbounded"),
            Quantity.or_text("coupler_rate", "coupler rate ω₃", float(state.coupler_rate[0]), "rad/s", "undefined"),
        ]
        marks: dict[str, list[Mark]] = {}
        if motion.drive.limits_rad is not None:  # the crank rocks between two limits
            lower, upper = motion.drive.limits_rad
            marks["crank_angle0_deg"] = [
                Mark(math.degrees(math.remainder(angle, 2 * math.pi)), "toggle") for angle in (lower, upper)
            ]
        if bool(state.singular[0]) or min(mu, 180.0 - mu) < TOGGLE_WINDOW_DEG:
            message = "toggle position: rocker rate is unbounded here (coupler and rocker are in line)"
        elif not GOOD_TRANSMISSION_DEG[0] <= mu <= GOOD_TRANSMISSION_DEG[1]:
            message = (
                f"poor transmission: μ = {mu:.0f}°, so a push along the coupler mostly loads the rocker's "
                "pivot instead of turning it"
            )
        elif not motion.drive.turns_fully:
            message = (
                f"The crank cannot turn fully ({motion.crank_range.describe()}); it reverses at each toggle position."
            )
        else:
            message = ""
        return Readout(quantities, marks=marks, message=message)
