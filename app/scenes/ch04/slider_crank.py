"""Scene: the offset slider-crank with the slider's velocity and acceleration as arrows.

The mechanism's plane (x along the slider's line, y up) is the world xz plane
at y = 0, seen from −y. Crank blue, connecting rod green, slider block grey on
its rail; the crank pin's circle is faint. Arrows on the slider: velocity
(green) and acceleration (red), each scaled to its largest value over a turn so
both stay readable. Every frame evaluates the closed form at the scene's time.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.systems.ch04 import slider_crank as physics
from app.scenes.kit import Preset, Quantity, Readout, Scene
from app.scenes.kit.planar import polyline_segments, to_world

LINK_COLORS = np.array([[40, 100, 220], [40, 150, 70]], np.uint8)


class SliderCrankScene(Scene):
    id = "slider-crank"
    title = "The slider-crank"
    chapter = 4
    model = physics.SliderCrankMechanism
    animated = True
    presets = (
        Preset(
            "in-line",
            "In line",
            {"crank_m": 0.3, "rod_m": 1.0, "offset_m": 0.0},
            "No offset: both strokes take the same time.",
        ),
        Preset(
            "short-rod",
            "Short rod (l = 2r)",
            {"crank_m": 0.3, "rod_m": 0.6, "offset_m": 0.0},
            "A short rod makes the motion far from harmonic: compare the accelerations at the two dead centres.",
        ),
        Preset(
            "quick-return",
            "Offset (quick return)",
            {"crank_m": 0.3, "rod_m": 0.8, "offset_m": 0.25},
            "An offset makes one stroke take longer than the other.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.t_s = 0.0
        self._span = 1.0
        self._center = np.zeros(3)
        self.backdrop = scene.add_grid(
            "/backdrop", width=4.0, height=4.0, plane="xz", cell_size=0.1, section_size=0.5, position=(0.5, 0.05, 0.0)
        )
        self.rail = scene.add_line_segments("/rail", np.zeros((1, 2, 3), np.float32), (110, 110, 110), thickness=0.01)
        self.crank_circle = scene.add_line_segments(
            "/crank_circle", np.zeros((1, 2, 3), np.float32), (150, 170, 210), thickness=1.5, thickness_units="screen"
        )
        self.pivot = scene.add_point_cloud(
            "/pivot", np.zeros((1, 3), np.float32), (40, 40, 40), point_size=0.05, point_shape="circle"
        )
        self.pivot_label = scene.add_label("/pivot/label", "O", anchor="top-center")
        self.links = scene.add_line_segments(
            "/links", np.zeros((2, 2, 3), np.float32), np.repeat(LINK_COLORS[:, None, :], 2, axis=1), thickness=0.02
        )
        self.joints = scene.add_point_cloud(
            "/joints", np.zeros((2, 3), np.float32), (30, 30, 30), point_size=0.04, point_shape="circle"
        )
        self.slider = scene.add_box("/slider", color=(150, 150, 160), dimensions=(0.2, 0.1, 0.1))
        self.arrows = scene.add_arrows(
            "/arrows",
            np.zeros((2, 2, 3), np.float32),
            np.array([[30, 150, 60], [220, 60, 40]], np.uint8),
            shaft_radius=0.01,
            head_radius=0.025,
            head_length=0.05,
        )
        self.legend = scene.add_label("/legend", "", anchor="bottom-left")

    def camera_view(self):
        c, span = self._center, self._span
        return (float(c[0] + 0.08 * span), float(-0.75 * span), float(c[2] + 0.12 * span)), (
            float(c[0]),
            0.0,
            float(c[2]),
        )

    def update(self) -> None:
        self.motion = physics.SliderCrankMotion.from_params(self.params)
        self.t_s = 0.0
        mech = self.motion.mechanism
        r, l, e = mech.crank_m, mech.rod_m, mech.offset_m
        x_min, x_max = mech.stroke_limits_m
        low = np.array([-r, min(-r, e)])
        high = np.array([x_max + 0.15 * l, max(r, e)])
        self._span = float(max(high[0] - low[0], high[1] - low[1]))
        span = self._span
        self._center = to_world(0.5 * (low + high))
        block = (0.22 * span * 0.5, 0.06 * span, 0.1 * span * 0.5)
        self.slider.dimensions = block
        self.links.thickness = 0.016 * span
        self.rail.thickness = 0.008 * span
        self.pivot.point_size = 0.025 * span
        self.joints.point_size = 0.02 * span
        self.pivot_label.position = (0.0, 0.0, -0.04 * span)
        rail_z = e - 0.5 * block[2]
        self.rail.points = np.array(
            [[[x_min - 0.15 * span, 0.0, rail_z], [x_max + 0.15 * span, 0.0, rail_z]]], np.float32
        )
        circle = np.linspace(0.0, 2.0 * math.pi, 121)
        self.crank_circle.points = polyline_segments(r * np.stack([np.cos(circle), np.sin(circle)], axis=-1))
        self.arrows.shaft_radius = 0.006 * span
        self.arrows.head_radius = 0.015 * span
        self.arrows.head_length = 0.03 * span
        self.backdrop.width = self.backdrop.height = 2.0 * span
        self.backdrop.position = (float(self._center[0]), 0.05 * span, float(self._center[2]))
        self.backdrop.cell_size = 10 ** math.floor(math.log10(span / 4.0))
        self.backdrop.section_size = 5 * self.backdrop.cell_size
        # Arrow scales: the largest velocity / acceleration over a turn is drawn 0.25 span long.
        turn = self.motion.at(
            np.linspace(0.0, self.motion.drive.period_s if math.isfinite(self.motion.drive.period_s) else 1.0, 361)
        )
        self._velocity_scale = 0.25 * span / max(float(np.max(np.abs(turn.slider_velocity_m_s))), 1e-12)
        self._acceleration_scale = 0.25 * span / max(float(np.max(np.abs(turn.slider_acceleration_m_s2))), 1e-12)
        self.legend.position = (float(low[0]), 0.0, float(high[1] + 0.2 * span))
        self.legend.text = "green: slider velocity · red: slider acceleration"
        self._draw()

    def _draw(self) -> None:
        state = self.motion.at(np.array([self.t_s]))
        self._state = state
        a, b = state.crank_pin[0], state.slider_pin[0]
        self.links.points = to_world(np.array([[[0.0, 0.0], a], [a, b]])).astype(np.float32)
        self.joints.points = to_world(np.array([a, b])).astype(np.float32)
        slider_world = to_world(b)
        self.slider.position = tuple(slider_world)
        lift = np.array([0.0, -0.05 * self._span, 0.09 * self._span])
        tails = np.array([slider_world + lift, slider_world + 1.6 * lift])
        vectors = np.array(
            [
                [state.slider_velocity_m_s[0] * self._velocity_scale, 0.0, 0.0],
                [state.slider_acceleration_m_s2[0] * self._acceleration_scale, 0.0, 0.0],
            ]
        )
        self.arrows.points = np.stack([tails, tails + vectors], axis=1).astype(np.float32)

    def readout(self) -> Readout:
        state = self._state
        mech = self.motion.mechanism
        x_min, x_max = mech.stroke_limits_m
        counterclockwise = self.motion.drive.speed_rad_s >= 0.0
        ratio = mech.stroke_time_ratio(counterclockwise=counterclockwise)
        quantities = [
            Quantity("t_s", "time t", float(state.t_s[0]), "s"),
            Quantity("crank_angle", "crank angle θ", math.degrees(float(state.crank_angle[0])) % 360.0, "deg"),
            Quantity("slider_position", "slider position x", float(state.slider_position_m[0]), "m"),
            Quantity("slider_velocity", "slider velocity ẋ", float(state.slider_velocity_m_s[0]), "m/s"),
            Quantity("slider_acceleration", "slider acceleration ẍ", float(state.slider_acceleration_m_s2[0]), "m/s²"),
            Quantity("rod_angle", "rod angle φ", math.degrees(float(state.rod_angle[0])), "deg"),
            Quantity("stroke", "stroke x_max − x_min", float(x_max - x_min), "m"),
            Quantity("stroke_time_ratio", "outward / return stroke time", float(ratio), ""),
        ]
        message = ""
        if mech.offset_m != 0.0:
            sense = "counterclockwise" if counterclockwise else "clockwise"
            message = (
                f"With the offset the strokes take unequal times: turning {sense}, the outward stroke "
                f"lasts {ratio:.3f} times the return stroke."
            )
        return Readout(quantities, message=message)
