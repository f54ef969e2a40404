"""Scene: a thin disk rolling without slipping, its contact path traced on the floor.

World frame (m, +Z up, floor z = 0), drawn at true scale: the disk is its rim
and three spokes (so the spin shows), posed by R_NB = Rz(ψ) Rx(θ) Ry(φ) about
its centre; the orange trail is the contact point's path. A disk that has fallen
or would lift off (the model keeps it on the floor as if glued, which a real disk
would not be) stops there with the model's message
(:mod:`app.physics.systems.ch09.rolling_disk_contact`). Each frame
sends at most three messages (the disk, a trail chunk, and the pause).
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.systems.ch09.rolling_disk_contact import normal_force_N
from app.physics.systems.ch09.rolling_disk_model import RollingDiskMotion, contact_speed_m_s, disk_pose
from app.scenes.kit import Preset, Quantity, Readout, Trail, update_node
from app.scenes.kit.derived_system_scene import DerivedSystemScene
from app.scenes.kit.drawing import disk_outline_colors, disk_outline_segments

TRAIL_CHUNK_FRAMES = 3
TRAIL_CHUNKS = 150  # 15 s of path at 30 Hz


class RollingDiskScene(DerivedSystemScene):
    id = "rolling-disk"
    frame_message_budget = 3.0
    title = "Kane and Gibbs–Appell: a disk rolling without slipping"
    chapter = 9
    model = RollingDiskMotion
    run_model: RollingDiskMotion
    camera_position = (0.3, -3.3, 1.9)
    camera_look_at = (0.0, -0.7, 0.0)
    presets = (
        Preset(
            "fast-upright",
            "Fast and nearly upright",
            {"radius_m": 0.1, "lean_0_deg": 3.0, "spin_rate_0_rad_s": 20.0, "heading_rate_0_rad_s": 0.0},
            "Ω = 20 rad/s is far above the threshold √(g/(3r)) = 5.72 rad/s (r = 0.1 m): the lean wobbles by a "
            "few degrees and the path is a gentle curve.",
        ),
        Preset(
            "slow-wobble",
            "Below the threshold",
            {"radius_m": 0.1, "lean_0_deg": 3.0, "spin_rate_0_rad_s": 4.0, "heading_rate_0_rad_s": 0.0},
            "Ω = 4 rad/s is below 5.72 rad/s: upright rolling is unstable, the lean grows to tens of degrees and "
            "the path curls tightly.",
        ),
        Preset(
            "turning",
            "Leaning into a turn",
            {"lean_0_deg": 20.0, "spin_rate_0_rad_s": 20.0, "heading_rate_0_rad_s": 5.0},
            "A large lean with a heading rate: the contact point runs round loops while the energy stays constant.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        scene.add_grid("/floor", width=4.0, height=4.0, cell_size=0.1, section_size=0.5, position=(0.0, -0.8, 0.0))
        outline_colors = disk_outline_colors()
        self.disk = scene.add_line_segments(
            "/disk", np.zeros(outline_colors.shape, np.float32), outline_colors, thickness=3.0, thickness_units="screen"
        )
        self.trail = Trail(
            scene, "/contact-path", color=(235, 120, 20), chunk_frames=TRAIL_CHUNK_FRAMES, max_chunks=TRAIL_CHUNKS
        )

    def update(self) -> None:
        self.restart()
        self._radius_m = float(self.params["radius_m"])
        self._outline = disk_outline_segments(self._radius_m)
        self._critical_spin = self.run_model.upright_critical_spin_rad_s(self.physical_params())
        self.trail.clear()
        self._draw()

    def _draw(self) -> None:
        centre, rotation = disk_pose(self._radius_m, self.run.y)
        update_node(self.disk, points=(centre + self._outline @ rotation.T).astype(np.float32))
        self.trail.add(np.array([float(self.run.y[0]), float(self.run.y[1]), 0.002]))

    def readout(self) -> Readout:
        y = self.run.y
        spin = float(y[9])
        stable = abs(spin) > self._critical_spin
        quantities = [
            Quantity("t_s", "time t", self.run.t_s, "s"),
            Quantity("lean_deg", "lean θ from the vertical", math.degrees(float(y[3])), "deg"),
            Quantity("heading_deg", "heading ψ", math.degrees(math.remainder(float(y[2]), 2 * math.pi)), "deg"),
            Quantity("spin_rate_rad_s", "spin rate φ̇", spin, "rad/s"),
            Quantity(
                "contact_speed_m_s", "contact point's speed |(ẋ, ẏ)|", float(contact_speed_m_s(y[None, :])[0]), "m/s"
            ),
            Quantity("rolling_speed_m_s", "r |φ̇| (equal when rolling without slip)", self._radius_m * abs(spin), "m/s"),
            Quantity(
                "energy_J",
                "energy T + V (V = 0 with the centre on the floor)",
                self.current_invariants()["energy"],
                "J",
            ),
            Quantity(
                "normal_force_N",
                "floor's normal force N = m (g + z̈_G) (a floor can only push: N ≥ 0)",
                float(normal_force_N(self.physical_params(), y[None, :])[0]),
                "N",
            ),
            self.drift_quantity("energy", "energy drift |ΔE| / scale"),
            Quantity(
                "critical_spin_rad_s",
                "upright rolling is stable above |φ̇| = Ω_c (linearised)",
                self._critical_spin,
                "rad/s",
            ),
            Quantity.word("upright_stability", "upright rolling at this spin", "stable" if stable else "unstable"),
            *self.agreement_quantities(),
        ]
        return Readout(quantities, message=self.status)
