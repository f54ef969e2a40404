"""Scene: the riderless Whipple bicycle coasting on a floor after a sideways push.

World frame (m, +Z up, floor z = 0), true scale. The bicycle is drawn as lines: the two wheels' rims and spokes, the
rear frame (a triangle from the rear hub to the rider's mass centre and the head tube) and the front frame (the fork
along the steer axis and the handlebar). Everything hangs under ``/world``, which moves so the rear contact stays at
the origin: the camera rides along while the floor grid and the two contact paths (rear orange, front blue) pass by.

The readout says whether upright rolling at this speed is stable, from the eigenvalues of the engine's own
linearisation, and where the self-stable band lies (the weave and capsize speeds, found on the same eigenvalues).
Each frame sends the bicycle and the world's offset (two messages), a trail chunk every few frames, and the floor
when the bicycle crosses a grid cell.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.core.parameters import ParameterError
from app.physics.mechanics.multibody.linearise import eigenvalues, state_matrix
from app.physics.systems.ch09 import whipple_bicycle as bicycle
from app.physics.systems.ch09.whipple_bicycle_model import (
    LEAN,
    STEER,
    YAW,
    N,
    WhippleBicycleMotion,
    X,
    Y,
    bicycle_model,
    forward_speed_m_s,
    mode_shape,
    pose,
)
from app.scenes.kit import IntegratedScene, Preset, Quantity, Readout, Trail, update_node
from app.scenes.kit.drawing import disk_outline_colors, disk_outline_segments

TRAIL_CHUNK_FRAMES = 4
TRAIL_CHUNKS = 150  # 20 s of path at 30 Hz
#: The floor grid's size and cell (m); it is moved under the bicycle a whole cell at a time.
FLOOR_M, FLOOR_CELL_M = 12.0, 1.0
FRAME_COLOR = (60, 60, 70)
FORK_COLOR = (230, 120, 20)
RIDER_COLOR = (120, 60, 160)
LINE_PX = 4.0


def _frame_segments(params, bodies) -> np.ndarray:
    """The frames' lines (K, 2, 3), world coordinates: rear triangle, rider cross, head tube, fork, handlebar."""
    tilt = float(params["steer_axis_tilt_rad"])
    r_rear, r_front = float(params["rear_wheel_radius_m"]), float(params["front_wheel_radius_m"])
    rear_centre, rear_frame = bodies["rear_frame"]
    foot, front_frame = bodies["front_frame"]
    axis = np.array([-math.sin(tilt), 0.0, math.cos(tilt)])
    rider = rear_centre + rear_frame @ np.array(
        [float(params["rear_frame_x_m"]), 0.0, -float(params["rear_frame_z_m"]) - r_rear]
    )
    # The head tube: from level with the front hub to 0.35 m above it, along the steer axis.
    head_low = foot + front_frame @ (axis * (r_front / math.cos(tilt)))
    head_top = head_low + front_frame @ (axis * 0.35)
    front_centre = bodies["front_wheel"][0]
    bar = front_frame @ np.array([0.0, 0.25, 0.0])
    cross = [rear_frame @ np.array(v) for v in ((0.08, 0, 0), (0, 0.08, 0), (0, 0, 0.08))]
    segments = [
        (rear_centre, rider), (rider, head_top), (rear_centre, head_low), (head_low, head_top),
        (head_low, front_centre), (head_top - bar, head_top + bar),
        *((rider - d, rider + d) for d in cross),
    ]  # fmt: skip
    return np.array(segments)


def _frame_colors() -> np.ndarray:
    colors = [FRAME_COLOR] * 4 + [FORK_COLOR] * 2 + [RIDER_COLOR] * 3
    return np.repeat(np.array(colors, dtype=np.uint8)[:, None, :], 2, axis=1)


class WhippleBicycleScene(IntegratedScene):
    id = "whipple-bicycle"
    title = "Kane's equations at work: the bicycle that steers itself upright"
    chapter = 9
    model = WhippleBicycleMotion
    run_model: WhippleBicycleMotion
    frame_message_budget = 3.5
    #: Behind and to the right of the rear wheel, 1.3 m up: the bicycle fills the view, the paths trail off behind.
    camera_position = (-0.9, -2.3, 1.3)
    camera_look_at = (0.6, 0.0, 0.45)
    presets = (
        Preset(
            "self-stable",
            "Pushed at 5 m/s: it recovers",
            {"speed_m_s": 5.0, "push_lean_rate_rad_s": 0.5, "lean_0_deg": 0.0, "steer_0_deg": 0.0, "start": "push"},
            "5 m/s lies inside the self-stable band (4.29–6.02 m/s for the benchmark): the push makes the bicycle "
            "lean, the front wheel steers into the lean, and within a few seconds it rolls upright and straight "
            "again, on a new heading.",
        ),
        Preset(
            "weave",
            "Too slow, 3 m/s: the weave grows",
            {"speed_m_s": 3.0, "push_lean_rate_rad_s": 0.2, "lean_0_deg": 0.0, "steer_0_deg": 0.0, "start": "push"},
            "Below the weave speed the oscillating lean-and-steer mode grows: each swing is larger than the last "
            "until the bicycle falls (the run stops when the model no longer holds).",
        ),
        Preset(
            "capsize",
            "Too fast, 8 m/s: a slow capsize",
            {"speed_m_s": 8.0, "push_lean_rate_rad_s": 0.2, "lean_0_deg": 0.0, "steer_0_deg": 0.0, "start": "push"},
            "Above the capsize speed the steering no longer catches the lean: there is no wobble, but the lean "
            "creeps up over tens of seconds while the bicycle spirals in.",
        ),
        Preset(
            "weave-mode",
            "The weave alone, 4 m/s",
            {
                "speed_m_s": 4.0,
                "start": "weave mode",
                "mode_lean_deg": 3.0,
                "push_lean_rate_rad_s": 0.0,
                "lean_0_deg": 0.0,
                "steer_0_deg": 0.0,
            },
            "Started in the weave's own shape (lean, steer and their rates in the eigenvector's proportions), the "
            "bicycle does nothing but that mode: lean and steer swing together, the steer leading, and just below "
            "the weave speed each swing is a little larger than the last.",
        ),
        Preset(
            "capsize-mode",
            "The capsize alone, 7 m/s",
            {
                "speed_m_s": 7.0,
                "start": "capsize mode",
                "mode_lean_deg": 3.0,
                "push_lean_rate_rad_s": 0.0,
                "lean_0_deg": 0.0,
                "steer_0_deg": 0.0,
            },
            "Started in the capsize mode's shape: a lean with a small steer into it and no oscillation at all, which "
            "above the capsize speed creeps slowly larger.",
        ),
        Preset(
            "standing",
            "Standing still: it falls like a pendulum",
            {"speed_m_s": 0.0, "push_lean_rate_rad_s": 0.0, "lean_0_deg": 2.0, "steer_0_deg": 0.0, "start": "push"},
            "Without speed nothing steers the wheels under the rider: the bicycle topples from 2° like an inverted "
            "pendulum (the eigenvalues at 0 m/s are real, ±3.13 and ±5.53 1/s).",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.world = scene.add_frame("/world", show_axes=False)
        self.floor = scene.add_grid(
            "/world/floor", width=FLOOR_M, height=FLOOR_M, cell_size=0.25, section_size=FLOOR_CELL_M
        )
        self._floor_cell = (0, 0)
        rim_colors = disk_outline_colors()
        self._colors = np.concatenate([rim_colors, rim_colors, _frame_colors()])
        self.bicycle = scene.add_line_segments(
            "/world/bicycle",
            np.zeros(self._colors.shape, np.float32),
            self._colors,
            thickness=LINE_PX,
            thickness_units="screen",
        )
        self.rear_path = Trail(
            scene, "/world/rear-path", color=(235, 120, 20), chunk_frames=TRAIL_CHUNK_FRAMES, max_chunks=TRAIL_CHUNKS
        )
        self.front_path = Trail(
            scene, "/world/front-path", color=(40, 110, 220), chunk_frames=TRAIL_CHUNK_FRAMES, max_chunks=TRAIL_CHUNKS
        )
        self._band_for: tuple | None = None

    def drawn_trails(self) -> list[Trail]:
        return [self.rear_path, self.front_path]

    def update(self) -> None:
        self.restart()
        params = self.physical_params()
        self._rear_rim = disk_outline_segments(float(params["rear_wheel_radius_m"]))
        self._front_rim = disk_outline_segments(float(params["front_wheel_radius_m"]))
        self._linear_at_speed(params)
        self.clear_trails()
        self._draw()

    def _linear_at_speed(self, params) -> None:
        """The eigenvalues at this speed, and the self-stable band for these parameters (found again only when a
        parameter other than the speed changes: it takes about 0.3 s)."""
        model = bicycle_model()
        design = {name: params[name] for name in bicycle.PARAMETERS.by_name}
        values = eigenvalues(state_matrix(model, design, bicycle.REFERENCE))
        self._growth_1_s = float(np.max(values.real))
        self._weave_hz = float(np.max(np.abs(values.imag))) / (2 * math.pi)
        try:
            into_lean = -mode_shape(params, "weave").steer_per_lean  # steer > 0 is to the left, lean > 0 to the right
            phase = math.degrees(math.atan2(into_lean.imag, into_lean.real))
            self._weave_words = (
                f"steer {abs(into_lean):.2f} rad per rad of lean, into the lean, "
                f"{'leading' if phase >= 0 else 'lagging'} it by {abs(phase):.0f}°"
            )
        except ParameterError:
            self._weave_words = "none at this speed (the weave is two real modes)"
        key = tuple(sorted((k, v) for k, v in design.items() if k != "speed_m_s"))
        if key != self._band_for:
            self._band = bicycle.weave_and_capsize(model, design)
            self._band_for = key

    def _draw(self) -> None:
        params = self.physical_params()
        q = self.run.y[:N]
        bodies = pose(params, q)
        rear_centre, rear_spin = bodies["rear_wheel"]
        front_centre, front_spin = bodies["front_wheel"]
        segments = np.concatenate(
            [
                rear_centre + self._rear_rim @ rear_spin.T,
                front_centre + self._front_rim @ front_spin.T,
                _frame_segments(params, bodies),
            ]
        )
        update_node(self.bicycle, points=segments.astype(np.float32))
        x, y = float(q[X]), float(q[Y])
        self.world.position = (-x, -y, 0.0)
        cell = (round(x / FLOOR_CELL_M), round(y / FLOOR_CELL_M))
        if cell != self._floor_cell:  # keep the floor under the bicycle, a whole cell at a time
            self._floor_cell = cell
            self.floor.position = (cell[0] * FLOOR_CELL_M, cell[1] * FLOOR_CELL_M, 0.0)
        self.rear_path.add(np.array([x, y, 0.002]))
        front_contact = front_centre - float(params["front_wheel_radius_m"]) * _down_in_plane(front_spin)
        self.front_path.add(np.array([front_contact[0], front_contact[1], 0.002]))

    def readout(self) -> Readout:
        params = self.physical_params()
        y = self.run.y
        now = self.current_invariants()
        speed = float(forward_speed_m_s(params, y)[0])
        weave, capsize = self._band
        band = (
            f"{weave:.3f}–{capsize:.3f} m/s"
            if weave is not None and capsize is not None and weave < capsize
            else "none between 0 and 10 m/s"
        )
        stable = self._growth_1_s < 0
        normal = float(self.run_model.front_normal_force_N(params, np.array([self.run.t_s]), y[None, :])[0])
        quantities = [
            Quantity("t_s", "time t", self.run.t_s, "s"),
            Quantity("speed_m_s", "forward speed r_R θ̇_R", speed, "m/s"),
            Quantity("lean_deg", "lean φ (positive: to the right)", math.degrees(float(y[LEAN])), "deg"),
            Quantity("steer_deg", "steer δ (positive: to the left)", math.degrees(float(y[STEER])), "deg"),
            Quantity("heading_deg", "heading ψ", math.degrees(math.remainder(float(y[YAW]), 2 * math.pi)), "deg"),
            Quantity("energy_J", "energy T + V", now["energy"], "J"),
            Quantity("energy_drift", "energy drift |ΔE| / scale", self.current_drift()["energy"]),
            Quantity("constraint_position_m", "front wheel off the floor max|g|", now["constraint_position"], "m"),
            Quantity("constraint_velocity_m_s", "contact slip max|C v|", now["constraint_velocity"], "m/s"),
            Quantity("front_normal_force_N", "floor's push on the front wheel (≥ 0 while it touches)", normal, "N"),
            Quantity("largest_growth_rate_1_s", "largest Re λ, upright at this speed", self._growth_1_s, "1/s"),
            Quantity.word(
                "upright_stability",
                f"upright rolling at {float(params['speed_m_s']):g} m/s",
                "stable: a push dies out" if stable else "unstable: a push grows",
            ),
            Quantity.word("self_stable_band", "self-stable speeds (weave to capsize)", band),
            Quantity.word("weave_shape", "the weave's shape (its eigenvector)", self._weave_words),
            Quantity.word("algorithm", "DAE algorithm", f"{self.run_model.algorithm()} ({self.description})"),
        ]  # fmt: skip
        return Readout(quantities, message=self.status)


def _down_in_plane(wheel: np.ndarray) -> np.ndarray:
    """The unit vector from a wheel's centre to its lowest point (world), the wheel's axle being its frame's y."""
    axle = wheel[:, 1]
    down = np.array([0.0, 0.0, -1.0]) - axle * (-axle[2])
    return down / np.linalg.norm(down)
