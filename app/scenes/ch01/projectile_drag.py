"""Scene for the work–energy lesson: a projectile with drag, replayed in real time.

The flight is integrated once per parameter change (``app.physics.systems.ch01.projectile``)
and replayed frame by frame; arrows show the velocity (0.25 m per m/s), the
weight and the drag force (scaled so the weight is a tenth of the range).
"""

from __future__ import annotations

import numpy as np

from app.physics.systems.ch01 import projectile as physics
from app.scenes.kit import Scene, arrow_segments

VELOCITY_SCALE = 0.25  # m of arrow per m/s
PAUSE_AT_LANDING_S = 1.5


class ProjectileDragScene(Scene):
    id = "projectile-drag"
    title = "A projectile with air drag: work and energy"
    chapter = 1
    example = physics.EXAMPLE
    animated = True

    def camera_view(self):
        span = max(self._span_m, 10.0)
        return (0.5 * span, -0.62 * span, 0.3 * span), (0.5 * span, 0.0, 0.12 * span)

    def build(self) -> None:
        scene = self.client.scene
        self.t_s = 0.0
        self._span_m = 100.0
        self.ground = scene.add_grid("/ground", width=200.0, height=60.0, cell_size=5.0, section_size=10.0, position=(100.0, 0.0, 0.0))
        self.path = scene.add_line_segments("/path", np.zeros((1, 2, 3), np.float32), (120, 120, 160), thickness=0.25)
        self.ball = scene.add_icosphere("/ball", radius=1.0, color=(200, 60, 40))
        self.label = scene.add_label("/readout", "", anchor="bottom-left")
        self.arrows = scene.add_arrows(
            "/forces",
            np.zeros((3, 2, 3), np.float32),
            np.array([[30, 110, 220], [30, 150, 60], [220, 60, 40]], np.uint8),
            shaft_radius=0.3,
            head_radius=0.8,
            head_length=1.6,
        )
        self.status_label = scene.add_label("/status", "", position=(0.0, 0.0, -3.0))

    def update(self) -> None:
        try:
            self.trajectory = physics.simulate(self.params)
        except ValueError as exc:
            self.status = str(exc)
            self.status_label.text = f"Cannot fly: {exc}"
            return
        self.status = ""
        self.status_label.text = ""
        pos = self.trajectory.position_m
        self._span_m = float(max(pos[:, 0].max(), pos[:, 2].max()))
        size = max(self._span_m / 60.0, 0.05)
        self.ball.scale = size
        self.path.points = np.stack([pos[:-1], pos[1:]], axis=1).astype(np.float32)
        self.path.thickness = size * 0.25
        weight = self.params["mass_kg"] * self.params["g_m_s2"]
        self._force_scale = 0.1 * self._span_m / weight
        self.label.position = (0.0, 0.0, 1.25 * float(pos[:, 2].max()) + size)
        # Everything a frame draws, one row per sample: position (3), velocity (3), drag (3), drag work (1).
        traj = self.trajectory
        self._frame_table = np.column_stack([traj.position_m, traj.velocity_m_s, traj.drag_force_N, traj.work_drag_J])
        self.t_s = 0.0
        self._draw()

    def _draw(self) -> None:
        t_samples = self.trajectory.t_s
        t = min(self.t_s, float(t_samples[-1]))
        # Linear interpolation between the 241 uniform samples (smooth at 30 fps): one lookup per frame.
        i = min(int(np.searchsorted(t_samples, t, side="right")) - 1, len(t_samples) - 2)
        blend = (t - t_samples[i]) / (t_samples[i + 1] - t_samples[i])
        row = (1.0 - blend) * self._frame_table[i] + blend * self._frame_table[i + 1]
        position, velocity, drag, work_drag = row[0:3], row[3:6], row[6:9], float(row[9])
        weight = np.array([0.0, 0.0, -self.params["mass_kg"] * self.params["g_m_s2"]])
        self.ball.position = position
        tails = np.repeat(position[None, :], 3, axis=0)
        self.arrows.points = arrow_segments(
            tails, np.array([velocity * VELOCITY_SCALE, weight * self._force_scale, drag * self._force_scale]), 1.0
        )
        kinetic = 0.5 * self.params["mass_kg"] * float(velocity @ velocity)
        self.label.text = f"t = {t:5.2f} s   T = {kinetic:8.2f} J   W_drag = {work_drag:8.2f} J"

    def advance(self, dt_s: float) -> None:
        self.t_s += dt_s
        if self.t_s > float(self.trajectory.t_s[-1]) + PAUSE_AT_LANDING_S:
            self.t_s = 0.0
        self._draw()
