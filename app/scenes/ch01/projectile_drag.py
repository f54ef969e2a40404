"""Scene for the work–energy lesson: a projectile with drag, replayed in real time.

The flight is integrated once per parameter change (``app.physics.systems.ch01.projectile``)
and replayed frame by frame; arrows show the velocity (0.25 m per m/s), the
weight and the drag force (scaled so the weight is a tenth of the range).
The readout sets the flight beside the same launch in a vacuum
(``physics.vacuum_flight``): range, time of flight, highest point, and which leg
of the flight, the climb or the fall, takes longer.
"""

from __future__ import annotations

import numpy as np

from app.physics.systems.ch01 import projectile as physics
from app.scenes.kit import Preset, Quantity, Readout, Scene, arrow_segments

VELOCITY_SCALE = 0.25  # m of arrow per m/s
PAUSE_AT_LANDING_S = 1.5
#: A baseball hit hard: 145 g at 40 m/s, 35° up, quadratic drag c = 7.6e-4 kg/m (the defaults).
BASEBALL = {
    "mass_kg": 0.145,
    "speed0_m_s": 40.0,
    "elevation_deg": 35.0,
    "height0_m": 0.0,
    "linear_drag_kg_s": 0.0,
    "quadratic_drag_kg_m": 7.6e-4,
    "g_m_s2": 9.807,
}


class ProjectileDragScene(Scene):
    id = "projectile-drag"
    title = "A projectile with air drag: work and energy"
    chapter = 1
    example = physics.EXAMPLE
    animated = True
    presets = (
        Preset(
            "baseball",
            "Baseball through air",
            BASEBALL,
            "145 g at 40 m/s, 35° up, with quadratic drag: it carries about 100 m, two thirds of the vacuum range.",
        ),
        Preset(
            "vacuum",
            "The same hit in a vacuum",
            {**BASEBALL, "quadratic_drag_kg_m": 0.0},
            "No drag: the parabola, range v₀² sin 2α / g = 153 m; the climb and the fall take equally long.",
        ),
    )

    def camera_view(self):
        span = max(self._span_m, 10.0)
        return (0.5 * span, -0.62 * span, 0.3 * span), (0.5 * span, 0.0, 0.12 * span)

    def build(self) -> None:
        scene = self.client.scene
        self.t_s = 0.0
        self._t_drawn, self._row_drawn = 0.0, np.zeros(12)
        self._span_m = 100.0
        self.ground = scene.add_grid(
            "/ground", width=200.0, height=60.0, cell_size=5.0, section_size=10.0, position=(100.0, 0.0, 0.0)
        )
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
            self.vacuum = physics.vacuum_flight(self.params)
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
        # Everything a frame draws and reads, one row per sample: position (3), velocity (3), drag (3),
        # drag work (1), kinetic energy (1), gravity's work (1).
        traj = self.trajectory
        self._frame_table = np.column_stack(
            [
                traj.position_m,
                traj.velocity_m_s,
                traj.drag_force_N,
                traj.work_drag_J,
                traj.kinetic_energy_J,
                traj.work_gravity_J,
            ]
        )
        self.t_s = 0.0
        self._draw()

    def _draw(self) -> None:
        t_samples = self.trajectory.t_s
        t = min(self.t_s, float(t_samples[-1]))
        # Linear interpolation between the 241 uniform samples (smooth at 30 fps): one lookup per frame.
        i = min(int(np.searchsorted(t_samples, t, side="right")) - 1, len(t_samples) - 2)
        blend = (t - t_samples[i]) / (t_samples[i + 1] - t_samples[i])
        row = (1.0 - blend) * self._frame_table[i] + blend * self._frame_table[i + 1]
        self._t_drawn, self._row_drawn = t, row
        position, velocity, drag, work_drag, kinetic = row[0:3], row[3:6], row[6:9], float(row[9]), float(row[10])
        weight = np.array([0.0, 0.0, -self.params["mass_kg"] * self.params["g_m_s2"]])
        self.ball.position = position
        tails = np.repeat(position[None, :], 3, axis=0)
        self.arrows.points = arrow_segments(
            tails, np.array([velocity * VELOCITY_SCALE, weight * self._force_scale, drag * self._force_scale]), 1.0
        )
        self.label.text = f"t = {t:5.2f} s   T = {kinetic:8.2f} J   W_drag = {work_drag:8.2f} J"

    def step_motion(self, dt_s: float) -> bool:
        """The flight replays from t = 0 a moment after landing."""
        self.t_s += dt_s
        if self.t_s > float(self.trajectory.t_s[-1]) + PAUSE_AT_LANDING_S:
            self.t_s = 0.0
        return True

    def readout(self) -> Readout:
        """The instant on screen (time, speed, energy and work so far), then the whole flight beside the vacuum's."""
        t, row = self._t_drawn, self._row_drawn
        now = [Quantity("t_s", "time t", t, "s")]
        if self.status:
            return Readout(now, message=f"Cannot fly: {self.status}")
        traj, vacuum = self.trajectory, self.vacuum
        range_m = float(traj.position_m[-1, 0])
        kinetic_launch, work_drag_total = float(traj.kinetic_energy_J[0]), float(traj.work_drag_J[-1])
        now += [
            Quantity("speed_m_s", "speed |v|", float(np.linalg.norm(row[3:6])), "m/s"),
            Quantity("kinetic_energy_J", "kinetic energy T", float(row[10]), "J"),
            Quantity("work_gravity_J", "work done by gravity so far W_g", float(row[11]), "J"),
            Quantity("work_drag_J", "work done by drag so far W_d", float(row[9]), "J"),
        ]
        flight = [
            Quantity("range_m", "range", range_m, "m"),
            Quantity("vacuum_range_m", "range in a vacuum", vacuum.range_m, "m"),
            Quantity.or_text(
                "range_percent_of_vacuum",
                "range as a share of the vacuum range",
                physics.range_percent_of_vacuum(traj, vacuum),
                "%",
                "none: a vertical launch has no range",
            ),
            Quantity("flight_time_s", "time of flight", float(traj.t_s[-1]), "s"),
            Quantity("vacuum_flight_time_s", "time of flight in a vacuum", vacuum.flight_time_s, "s"),
            Quantity("apex_height_m", "highest point", float(traj.apex_position_m[2]), "m"),
            Quantity("vacuum_apex_height_m", "highest point in a vacuum", vacuum.apex_height_m, "m"),
            Quantity("climb_time_s", "climb to the highest point", traj.climb_time_s, "s"),
            Quantity("fall_time_s", "fall from the highest point", traj.fall_time_s, "s"),
            Quantity.word("longer_leg", "which takes longer", physics.longer_leg(traj)),
        ]
        if work_drag_total == 0.0:
            message = "No drag: the flight is the vacuum parabola, and T − T₀ = W_g at every instant."
        else:
            message = (
                f"Drag takes {-work_drag_total:.1f} J of the {kinetic_launch:.1f} J at launch: "
                f"T − T₀ = W_g + W_d at every instant, and the fall takes {traj.fall_time_s - traj.climb_time_s:.2f} s "
                f"longer than the climb."
            )
        return Readout(now + flight, message=message)
