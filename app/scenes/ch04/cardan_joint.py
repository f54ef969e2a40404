"""Scene: a cardan (Hooke) joint, and a graph of its speed ratio over one input turn.

World frame +Z up: the joint's centre is the origin, the input shaft (blue)
lies along −x → 0, the output shaft (red) leaves along e₂ = (cos β, sin β, 0).
The cross (yellow) carries the input yoke's pin u and the output yoke's pin v.
Above the joint, in the xz plane, a line graph shows ω₂/ω₁ against the input
angle φ₁ over one turn (0 to 360° left to right), with its bounds cos β and
1/cos β; a dot rides the curve at the current φ₁. Per frame: three attitudes
and one dot move.
"""

from __future__ import annotations

import math
from typing import cast

import numpy as np
from scipy.spatial.transform import Rotation

from app.physics.systems.ch04 import cardan_joint as physics
from app.scenes.kit import LabelAnchor, Preset, Quantity, Readout, Scene

SHAFT_LENGTH = 1.2
YOKE_RADIUS = 0.22  # distance of each yoke arm (and pin end) from the shaft axis
YOKE_DEPTH = 0.3  # axial length of the fork
GRAPH_WIDTH = 2.4
GRAPH_HEIGHT = 0.9
GRAPH_BASE_Z = 0.7
Z_TO_X = (math.cos(math.pi / 4), 0.0, math.sin(math.pi / 4), 0.0)  # a cylinder's local z onto local x
Z_TO_Y = (math.cos(math.pi / 4), -math.sin(math.pi / 4), 0.0, 0.0)  # a cylinder's local z onto local y


def _wxyz(rotation: Rotation) -> np.ndarray:
    return rotation.as_quat(scalar_first=True)


class CardanJointScene(Scene):
    id = "cardan-joint"
    title = "The cardan (Hooke) joint"
    chapter = 4
    model = physics.CardanJointDrive
    animated = True
    camera_position = (0.45, -2.0, 1.05)
    camera_look_at = (0.05, 0.2, 0.5)
    presets = (
        Preset(
            "straight", "Straight (β = 0°)", {"shaft_angle_deg": 0.0}, "In line: the output follows the input exactly."
        ),
        Preset(
            "car-driveshaft",
            "Drive shaft (β = 15°)",
            {"shaft_angle_deg": 15.0},
            "A typical drive-shaft angle: a few per cent of speed fluctuation.",
        ),
        Preset(
            "steep",
            "Steep (β = 50°)",
            {"shaft_angle_deg": 50.0},
            "A large angle: the output speed swings between 0.64 and 1.56 of the input.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.t_s = 0.0
        scene.add_grid("/ground", width=4.0, height=3.0, cell_size=0.1, section_size=0.5, position=(0.0, 0.3, -0.45))
        # Input side: shaft along local x, fork opening towards +x, pin along local y (= u).
        self.input = scene.add_frame("/input", show_axes=False)
        self._add_yoke("/input", side=-1.0, arm_axis="y", color=(50, 110, 210))
        # Output side: the frame's x is e₂ and its pin is along local z (= v).
        self.output_mount = scene.add_frame("/output_mount", show_axes=False)
        self.output = scene.add_frame("/output_mount/output", show_axes=False)
        self._add_yoke("/output_mount/output", side=1.0, arm_axis="z", color=(210, 70, 50))
        self.cross = scene.add_frame("/cross", show_axes=False)
        for name, wxyz in (("u", Z_TO_Y), ("v", (1.0, 0.0, 0.0, 0.0))):
            scene.add_cylinder(
                f"/cross/{name}", radius=0.035, height=2 * YOKE_RADIUS + 0.06, color=(235, 190, 40), wxyz=wxyz
            )
        scene.add_icosphere("/cross/hub", radius=0.06, color=(235, 190, 40))
        scene.add_label(
            "/input/label", "input shaft (ω₁ constant)", position=(-SHAFT_LENGTH, 0.0, 0.1), anchor="bottom-left"
        )
        self.output_label = scene.add_label(
            "/output_mount/label", "output shaft", position=(SHAFT_LENGTH, 0.0, 0.1), anchor="bottom-right"
        )
        # Speed-ratio graph in the plane y = 0 above the joint.
        self.graph_axes = scene.add_line_segments(
            "/graph/axes", np.zeros((1, 2, 3), np.float32), (90, 90, 90), thickness=1.5, thickness_units="screen"
        )
        self.graph_bounds = scene.add_line_segments(
            "/graph/bounds", np.zeros((2, 2, 3), np.float32), (150, 150, 150), thickness=1.0, thickness_units="screen"
        )
        self.graph_curve = scene.add_line_segments(
            "/graph/curve", np.zeros((1, 2, 3), np.float32), (200, 60, 40), thickness=2.5, thickness_units="screen"
        )
        self.graph_dot = scene.add_icosphere("/graph/dot", radius=0.035, color=(200, 60, 40))
        self.graph_labels = {
            name: scene.add_label(f"/graph/{name}", "", anchor=cast(LabelAnchor, anchor))
            for name, anchor in (
                ("title", "bottom-left"),
                ("max", "center-right"),
                ("min", "center-right"),
                ("start", "top-center"),
                ("end", "top-center"),
            )
        }

    def _add_yoke(self, parent: str, *, side: float, arm_axis: str, color: tuple[int, int, int]) -> None:
        """Shaft, fork base and two arms in the parent's frame; ``side`` −1 puts the shaft on −x."""
        scene = self.client.scene
        x_base = side * YOKE_DEPTH
        scene.add_cylinder(
            f"{parent}/shaft",
            radius=0.05,
            height=SHAFT_LENGTH,
            color=color,
            wxyz=Z_TO_X,
            position=(side * (YOKE_DEPTH + 0.5 * SHAFT_LENGTH), 0.0, 0.0),
        )
        across = (0.06, 2 * YOKE_RADIUS + 0.06, 0.06) if arm_axis == "y" else (0.06, 0.06, 2 * YOKE_RADIUS + 0.06)
        scene.add_box(f"{parent}/fork_base", color=color, dimensions=across, position=(x_base, 0.0, 0.0))
        for k, sign in enumerate((-1.0, 1.0)):
            offset = (0.0, sign * YOKE_RADIUS, 0.0) if arm_axis == "y" else (0.0, 0.0, sign * YOKE_RADIUS)
            scene.add_box(
                f"{parent}/arm{k}",
                color=color,
                dimensions=(YOKE_DEPTH, 0.05, 0.05),
                position=(0.5 * x_base + offset[0], offset[1], offset[2]),
            )

    def update(self) -> None:
        self.motion = physics.CardanMotion.from_params(self.params)
        self.t_s = 0.0
        joint = self.motion.joint
        beta = joint.shaft_angle_rad
        self.output_mount.wxyz = _wxyz(Rotation.from_rotvec([0.0, 0.0, beta]))
        low, high = joint.speed_ratio_span
        margin = max(0.1, 0.15 * (high - low))
        self._graph_range = (low - margin, high + margin)
        phi = np.linspace(0.0, 2.0 * math.pi, 361)
        points = self._graph_points(phi, joint.speed_ratio(phi))
        self.graph_curve.points = np.stack([points[:-1], points[1:]], axis=1).astype(np.float32)
        x0, x1 = -0.5 * GRAPH_WIDTH, 0.5 * GRAPH_WIDTH
        z_low, z_high = GRAPH_BASE_Z, GRAPH_BASE_Z + GRAPH_HEIGHT
        self.graph_axes.points = np.array(
            [[[x0, 0, z_low], [x1, 0, z_low]], [[x0, 0, z_low], [x0, 0, z_high]]], np.float32
        )
        bounds = [self._graph_points(np.array([0.0, 2 * math.pi]), np.array([r, r])) for r in (high, low)]
        self.graph_bounds.points = np.array(bounds, np.float32)
        labels = self.graph_labels
        labels["title"].position = (x0, 0.0, z_high + 0.03)
        labels["title"].text = f"speed ratio ω₂/ω₁ over one input turn (β = {math.degrees(beta):.1f}°)"
        labels["max"].position = tuple(bounds[0][0] - np.array([0.03, 0.0, 0.0]))
        labels["max"].text = f"1/cos β = {high:.4f}"
        labels["min"].position = tuple(bounds[1][0] - np.array([0.03, 0.0, 0.0]))
        labels["min"].text = f"cos β = {low:.4f}"
        labels["start"].position = (x0, 0.0, z_low - 0.03)
        labels["start"].text = "φ₁ = 0°"
        labels["end"].position = (x1, 0.0, z_low - 0.03)
        labels["end"].text = "360°"
        self._draw()

    def _graph_points(self, phi1: np.ndarray, ratio: np.ndarray) -> np.ndarray:
        lo, hi = self._graph_range
        x = -0.5 * GRAPH_WIDTH + GRAPH_WIDTH * np.asarray(phi1) / (2.0 * math.pi)
        z = GRAPH_BASE_Z + GRAPH_HEIGHT * (np.asarray(ratio) - lo) / (hi - lo)
        return np.stack([x, np.zeros_like(x), z], axis=-1)

    def _draw(self) -> None:
        state = self.motion.at(np.array([self.t_s]))
        self._state = state
        joint = self.motion.joint
        phi1, phi2 = float(state.input_angle[0]), float(state.output_angle[0])
        self.input.wxyz = _wxyz(Rotation.from_rotvec([phi1, 0.0, 0.0]))
        self.output.wxyz = _wxyz(Rotation.from_rotvec([phi2, 0.0, 0.0]))
        u, v = joint.input_pin(phi1), joint.output_pin(phi2)
        # Cross: local y along u, local z along v (perpendicular by the joint's constraint).
        self.cross.wxyz = _wxyz(Rotation.from_matrix(np.column_stack([np.cross(u, v), u, v])))
        self.graph_dot.position = tuple(self._graph_points(np.array([phi1 % (2.0 * math.pi)]), state.speed_ratio)[0])

    def readout(self) -> Readout:
        state = self._state
        low, high = self.motion.joint.speed_ratio_span
        return Readout(
            [
                Quantity("t_s", "time t", float(state.t_s[0]), "s"),
                Quantity("input_angle", "input angle φ₁", math.degrees(float(state.input_angle[0])) % 360.0, "deg"),
                Quantity("output_angle", "output angle φ₂", math.degrees(float(state.output_angle[0])) % 360.0, "deg"),
                Quantity("speed_ratio", "speed ratio ω₂/ω₁ now", float(state.speed_ratio[0]), ""),
                Quantity("speed_ratio_min", "smallest ratio, cos β", float(low), ""),
                Quantity("speed_ratio_max", "largest ratio, 1/cos β", float(high), ""),
                Quantity("output_rate", "output speed ω₂", float(state.output_rate[0]), "rad/s"),
            ]
        )
