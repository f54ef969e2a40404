"""Scene: the double pendulum, and beside it its configuration space, the torus of the two angles.

Left: the pendulum in the world xz plane (x right, z up), seen from −y, drawn
in display units (l1 + l2 is PENDULUM_REACH units). Right: a torus facing the camera;
going round its big circle is θ1 (0 at the bottom, as the upper rod), going
round its tube is θ2. The state's point (orange) moves on the torus and leaves
a short trail; the two circles θ1 = 0 and θ2 = 0 are drawn darker.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.systems.ch07.double_pendulum_model import DoublePendulumMotion, normal_mode_frequencies_rad_s
from app.scenes.kit import Preset, Quantity, Readout, Trail, move_node, update_node
from app.scenes.kit.derived_system_scene import DerivedSystemScene

TORUS_CENTER = np.array([2.9, 0.0, -0.1])
#: The pendulum's full reach l1 + l2 is drawn this many display units long.
PENDULUM_REACH = 1.3
TORUS_MAJOR, TORUS_MINOR = 0.8, 0.32
TRAIL_CHUNK_FRAMES = 5
TRAIL_CHUNKS = 24  # 4 s of trail at 30 Hz
SLOW_MODE_RATIO = math.sqrt(2.0)  # θ2/θ1 of the slow mode when m1 = m2 and l1 = l2


def torus_point(theta1_rad, theta2_rad) -> np.ndarray:
    """(…, 3) world points on the configuration torus for angles (…) in rad."""
    theta1, theta2 = np.asarray(theta1_rad), np.asarray(theta2_rad)
    ring = TORUS_MAJOR + TORUS_MINOR * np.cos(theta2)
    return TORUS_CENTER + np.stack(
        [ring * np.sin(theta1), -TORUS_MINOR * np.sin(theta2), -ring * np.cos(theta1)], axis=-1
    )


def torus_wireframe(*, rings: int = 24, tubes: int = 12, segments: int = 72) -> tuple[np.ndarray, np.ndarray]:
    """Line segments (S, 2, 3) of the torus's coordinate circles and a colour per segment (S, 2, 3) uint8."""
    s = np.linspace(0.0, 2.0 * math.pi, segments + 1)
    lines, colors = [], []
    for k, theta2 in enumerate(np.linspace(0.0, 2.0 * math.pi, tubes, endpoint=False)):  # circles of constant θ2
        path = torus_point(s, np.full_like(s, theta2))
        lines.append(np.stack([path[:-1], path[1:]], axis=1))
        colors.append(np.full((segments, 2, 3), 60 if k == 0 else 175, np.uint8))
    for k, theta1 in enumerate(np.linspace(0.0, 2.0 * math.pi, rings, endpoint=False)):  # circles of constant θ1
        path = torus_point(np.full_like(s, theta1), s)
        lines.append(np.stack([path[:-1], path[1:]], axis=1))
        colors.append(np.full((segments, 2, 3), 60 if k == 0 else 175, np.uint8))
    return np.concatenate(lines).astype(np.float32), np.concatenate(colors)


class DoublePendulumScene(DerivedSystemScene):
    id = "double-pendulum"
    #: Rods, bobs and the torus point each frame; a trail chunk every 5th frame.
    frame_message_budget = 4.0
    title = "The double pendulum and its configuration torus"
    chapter = 7
    model = DoublePendulumMotion
    camera_position = (1.45, -5.6, 0.7)
    camera_look_at = (1.45, 0.0, -0.2)
    presets = (
        Preset(
            "slow-mode",
            "Slow normal mode",
            {
                "m1_kg": 1.0,
                "m2_kg": 1.0,
                "l1_m": 1.0,
                "l2_m": 1.0,
                "theta1_0_deg": 5.0,
                "theta2_0_deg": round(5.0 * SLOW_MODE_RATIO, 4),
                "theta1_rate_0_deg_s": 0.0,
                "theta2_rate_0_deg_s": 0.0,
            },
            "θ₂ = √2 θ₁, in step: both rods swing together at ω = √((2 − √2) g/l); the point draws one closed "
            "loop on the torus.",
        ),
        Preset(
            "fast-mode",
            "Fast normal mode",
            {
                "m1_kg": 1.0,
                "m2_kg": 1.0,
                "l1_m": 1.0,
                "l2_m": 1.0,
                "theta1_0_deg": 5.0,
                "theta2_0_deg": round(-5.0 * SLOW_MODE_RATIO, 4),
                "theta1_rate_0_deg_s": 0.0,
                "theta2_rate_0_deg_s": 0.0,
            },
            "θ₂ = −√2 θ₁, opposed: ω = √((2 + √2) g/l), 2.4 times the slow mode's frequency.",
        ),
        Preset(
            "chaotic",
            "Large swing (chaotic)",
            {
                "theta1_0_deg": 120.0,
                "theta2_0_deg": -30.0,
                "theta1_rate_0_deg_s": 0.0,
                "theta2_rate_0_deg_s": 200.0,
                "steps_per_frame": 0,
            },
            "Far from the bottom the motion never repeats: the point wanders over the whole torus, and the "
            "energy stays put.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        segments, colors = torus_wireframe()
        self.torus = scene.add_line_segments("/torus", segments, colors, thickness=1.2, thickness_units="screen")
        self.torus_label = scene.add_label(
            "/torus/label", "configuration space: θ₁ round the ring, θ₂ round the tube", anchor="bottom-center"
        )
        self.torus_label.position = TORUS_CENTER + np.array([0.0, 0.0, TORUS_MAJOR + TORUS_MINOR + 0.12])
        self.pivot = scene.add_icosphere("/pivot", radius=0.035, color=(40, 40, 40))
        self.rods = scene.add_line_segments(
            "/rods",
            np.zeros((2, 2, 3), np.float32),
            np.array([[[40, 100, 220]] * 2, [[40, 150, 70]] * 2], np.uint8),
            thickness=0.02,
        )
        self.bobs = scene.add_point_cloud(
            "/bobs",
            np.zeros((2, 3), np.float32),
            np.array([[40, 100, 220], [40, 150, 70]], np.uint8),
            point_size=0.09,
            point_shape="circle",
        )
        self.state_point = scene.add_icosphere("/torus/state", radius=0.045, color=(235, 120, 20))
        self.trail = Trail(
            scene, "/torus/trail", color=(235, 120, 20), chunk_frames=TRAIL_CHUNK_FRAMES, max_chunks=TRAIL_CHUNKS
        )

    def update(self) -> None:
        self.restart()
        params = self.physical_params()
        self._display_scale = PENDULUM_REACH / (float(params["l1_m"]) + float(params["l2_m"]))
        self.trail.clear()
        self._draw()

    def _draw(self) -> None:
        params = self.physical_params()
        theta1, theta2 = float(self.run.y[0]), float(self.run.y[1])
        l1, l2 = float(params["l1_m"]) * self._display_scale, float(params["l2_m"]) * self._display_scale
        upper = np.array([l1 * math.sin(theta1), 0.0, -l1 * math.cos(theta1)])
        lower = upper + np.array([l2 * math.sin(theta2), 0.0, -l2 * math.cos(theta2)])
        update_node(self.rods, points=np.array([[np.zeros(3), upper], [upper, lower]], np.float32))
        update_node(self.bobs, points=np.array([upper, lower], np.float32))
        on_torus = torus_point(theta1, theta2)
        move_node(self.state_point, position=on_torus)
        self.trail.add(on_torus)

    def readout(self) -> Readout:
        params = self.physical_params()
        y = self.run.y
        energy = self.current_invariants()["energy"]
        slow, fast = normal_mode_frequencies_rad_s(params)
        quantities = [
            Quantity("t_s", "time t", self.run.t_s, "s"),
            Quantity("theta1_deg", "upper angle θ₁", math.degrees(math.remainder(float(y[0]), 2 * math.pi)), "deg"),
            Quantity("theta2_deg", "lower angle θ₂", math.degrees(math.remainder(float(y[1]), 2 * math.pi)), "deg"),
            Quantity("theta1_rate_rad_s", "upper rate θ̇₁", float(y[2]), "rad/s"),
            Quantity("theta2_rate_rad_s", "lower rate θ̇₂", float(y[3]), "rad/s"),
            Quantity("energy_J", "energy T + V (V = 0 at the pivot)", energy, "J"),
            self.drift_quantity("energy", "energy drift |ΔE| / scale"),
            Quantity("slow_mode_rad_s", "slow normal mode ω₁ (small swings)", slow, "rad/s"),
            Quantity("fast_mode_rad_s", "fast normal mode ω₂ (small swings)", fast, "rad/s"),
            *self.agreement_quantities(),
        ]
        return Readout(quantities, message=self.status)
