"""Scene: the unsteady rolling disk, its no-slip rows kept as multiplier constraints by the chosen DAE algorithm.

World frame (m, +Z up, floor z = 0), true scale: the disk is its rim (blue) and
three spokes (red, so the spin shows), posed by R_NB = Rz(ψ) Rx(θ) Ry(φ) about
its centre (the chapter-9 drawing); the orange trail is the contact point's path.
The readout gives the energy drift, the contact point's slip speed |A v| (the
nonholonomic residual) and whether upright rolling at the start's spin is above
the critical spin the linearisation finds, and the floor's normal force. A disk that
has fallen or would lift off stops there with the model's message (chapter 9's rule,
:mod:`app.physics.systems.ch09.rolling_disk_contact`); a disk that rolls off the drawn
floor starts over. Each frame sends at most two
messages (the disk, a trail chunk every few frames).
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.constrained.residuals import multipliers
from app.physics.systems.ch08.rolling_disk_constrained_model import UnsteadyRollingDisk
from app.physics.systems.ch08.rolling_disk_stability import stability_sentence
from app.physics.systems.ch09.rolling_disk_contact import normal_force_N
from app.physics.systems.ch09.rolling_disk_model import disk_pose
from app.scenes.kit import IntegratedScene, Preset, Quantity, Readout, Trail, update_node
from app.scenes.kit.drawing import disk_outline_colors, disk_outline_segments

TRAIL_CHUNK_FRAMES = 3
TRAIL_CHUNKS = 150  # 15 s of path at 30 Hz
#: Half the drawn floor's width (m): a disk that rolls further starts over from the beginning.
FLOOR_HALF_WIDTH_M = 3.0
FLOOR_CENTRE = (0.0, -0.5, 0.0)
#: The disk's rim and spokes (screen pixels): thick enough to read the 0.2 m disk across its 2 m path.
DISK_LINE_PX = 7.0
CIRCLE = {"lean_0_deg": 30.0, "spin_rate_0_rad_s": 15.0, "heading_rate_0_rad_s": -2.723, "lean_rate_0_rad_s": 0.0}


class UnsteadyRollingDiskScene(IntegratedScene):
    id = "unsteady-rolling-disk"
    title = "The unsteady rolling disk: rolling without slip as nonholonomic constraints"
    chapter = 8
    model = UnsteadyRollingDisk
    run_model: UnsteadyRollingDisk
    frame_message_budget = 2.0
    #: 0.75 m up, just outside the default start's 2 m circle (centre (0, −1) m) beside where the disk starts,
    #: looking across it: with viser's 75° field of view the circle fills the view and the 0.2 m disk is never
    #: more than 2.6 m away.
    camera_position = (0.3, 0.45, 0.75)
    camera_look_at = (0.0, -1.0, 0.0)
    presets = (
        Preset(
            "stable",
            "Upright above the threshold",
            {
                "radius_m": 0.1,
                "lean_0_deg": 2.0,
                "spin_rate_0_rad_s": 12.0,
                "heading_rate_0_rad_s": 0.0,
                "lean_rate_0_rad_s": 0.0,
                "method": "auto",
            },
            "Ω = 12 rad/s is above the critical spin √(g/(3r)) = 5.72 rad/s (r = 0.1 m): the lean stays between "
            "2.0° and 3.2° and the path is a wide curve (the run starts over when the disk leaves the floor).",
        ),
        Preset(
            "falls",
            "Below the threshold: it falls over",
            {
                "radius_m": 0.1,
                "lean_0_deg": 2.0,
                "spin_rate_0_rad_s": 2.0,
                "heading_rate_0_rad_s": 0.0,
                "lean_rate_0_rad_s": 0.0,
                "method": "auto",
            },
            "Ω = 2 rad/s is below 5.72 rad/s: the lean grows from 2° to 75° while the path curls tightly. Set "
            "the spin to 0 and the disk topples: near 60° the floor would have to pull (N < 0), so it lifts off "
            "and the run stops.",
        ),
        Preset(
            "circle",
            "Leaning circle",
            {"radius_m": 0.1, **CIRCLE, "method": "auto"},
            "Leaning 30° at 15 rad/s with ψ̇ = −2.723 rad/s: the steady turn, a circle of radius r φ̇/|ψ̇| = "
            "0.55 m with the lean constant (to 0.001°).",
        ),
        Preset(
            "drift",
            "Uncorrected, coarse step",
            {
                "radius_m": 0.1,
                "lean_0_deg": 20.0,
                "spin_rate_0_rad_s": 20.0,
                "heading_rate_0_rad_s": 5.0,
                "method": "uncorrected",
                "integrator": "rk4",
                "steps_per_frame": 4,
            },
            "Index reduction alone with 4 RK4 steps per frame: the contact point's slip speed |A v| (about 5e-5 "
            "m/s) is never fed back; pick projection and it drops to round-off.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        scene.add_grid("/floor", width=6.0, height=6.0, cell_size=0.1, section_size=0.5, position=FLOOR_CENTRE)
        colors = disk_outline_colors()
        self.disk = scene.add_line_segments(
            "/disk", np.zeros(colors.shape, np.float32), colors, thickness=DISK_LINE_PX, thickness_units="screen"
        )
        self.trail = Trail(
            scene, "/contact-path", color=(235, 120, 20), chunk_frames=TRAIL_CHUNK_FRAMES, max_chunks=TRAIL_CHUNKS
        )

    def update(self) -> None:
        self.restart()
        params = self.physical_params()
        self._radius_m = float(params["radius_m"])
        self._outline = disk_outline_segments(self._radius_m)
        self._critical_spin = self.run_model.critical_spin_rad_s(params)
        self._stability = stability_sentence(float(params["spin_rate_0_rad_s"]), self._critical_spin)
        self.trail.clear()
        self._draw()

    def step_motion(self, dt_s: float) -> bool:
        off_floor = (
            max(abs(float(self.run.y[0]) - FLOOR_CENTRE[0]), abs(float(self.run.y[1]) - FLOOR_CENTRE[1]))
            > FLOOR_HALF_WIDTH_M
        )
        if off_floor:  # rolled out of view: replay from the start (drift and residuals start again with it)
            self.restart()
            self.trail.clear()
            return True
        return self.step_physics()  # a fall or a lift-off stops the run on the last frame the model describes

    def _draw(self) -> None:
        centre, rotation = disk_pose(self._radius_m, self.run.y)
        update_node(self.disk, points=(centre + self._outline @ rotation.T).astype(np.float32))
        self.trail.add(np.array([float(self.run.y[0]), float(self.run.y[1]), 0.002]))

    def readout(self) -> Readout:
        params = self.physical_params()
        y = self.run.y
        now = self.current_invariants()
        friction = multipliers(self.run_model.constrained_system(params), np.array([self.run.t_s]), y[None, :])[0]
        quantities = [
            Quantity("t_s", "time t", self.run.t_s, "s"),
            Quantity.word("algorithm", "DAE algorithm", f"{self.run_model.algorithm()} ({self.description})"),
            Quantity("lean_deg", "lean θ from the vertical", math.degrees(float(y[3])), "deg"),
            Quantity("heading_deg", "heading ψ", math.degrees(math.remainder(float(y[2]), 2 * math.pi)), "deg"),
            Quantity("spin_rate_rad_s", "spin rate φ̇", float(y[9]), "rad/s"),
            Quantity("heading_rate_rad_s", "heading rate ψ̇", float(y[7]), "rad/s"),
            Quantity(
                "constraint_velocity_m_s",
                "contact point's slip speed max|A v| (0 when rolling)",
                now["constraint_velocity"],
                "m/s",
            ),
            Quantity(
                "friction_N", "floor's friction on the disk |λ| (the multipliers)", float(np.hypot(*friction)), "N"
            ),
            Quantity(
                "normal_force_N",
                "floor's normal force N = m (g + z̈_G) (a floor can only push: N ≥ 0)",
                float(normal_force_N(params, y[None, :])[0]),
                "N",
            ),
            Quantity("energy_J", "energy T + V (V = 0 with the centre on the floor)", now["energy"], "J"),
            Quantity("energy_drift", "energy drift |ΔE| / scale", self.current_drift()["energy"]),
            Quantity(
                "critical_spin_rad_s", "critical spin Ω_c (linearised upright rolling)", self._critical_spin, "rad/s"
            ),
            Quantity.word("upright_stability", "at the start's spin", self._stability),
        ]
        return Readout(quantities, message=self.status)
