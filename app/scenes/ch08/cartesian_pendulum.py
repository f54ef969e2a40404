"""Scene: the pendulum in Cartesian coordinates, integrated by the DAE algorithm the student picks.

The pendulum's plane is the world x–z plane at y = 0, seen from −y (the model's y up is
world z), drawn ``PENDULUM_REACH`` display units per rod length with the pivot at
:data:`PIVOT`. The grey circle is the constraint x² + y² = L²: an algorithm that lets the
residual drift shows the bob leaving it. The faint grey dot is the exact motion (Jacobi
elliptic functions, from the same consistent start) while the bob librates, so phase
error is visible too; the orange trail is the bob's recent path. Each frame sends three
messages at most (rod, the two dots, a trail chunk every few frames).
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.constrained.algorithms import current_partition
from app.physics.constrained.residuals import multipliers
from app.physics.systems.ch08.cartesian_pendulum import exact_states
from app.physics.systems.ch08.cartesian_pendulum_model import CartesianPendulum
from app.scenes.kit import IntegratedScene, Preset, Quantity, Readout, Trail, circle_segments, update_node

PIVOT = np.array([0.0, 0.0, 1.2])
PENDULUM_REACH = 1.0
BOB_COLOR, GHOST_COLOR, ROD_COLOR = (40, 100, 220), (170, 170, 170), (60, 60, 60)
TRAIL_CHUNK_FRAMES = 3
TRAIL_CHUNKS = 60  # 6 s of path at 30 Hz
UNIT = {"mass_kg": 1.0, "length_m": 1.0, "g_m_s2": 1.0, "x0_m": 1.0, "y0_m": 0.0, "vx0_m_s": 0.0, "vy0_m_s": 0.0}


class CartesianPendulumScene(IntegratedScene):
    id = "cartesian-pendulum"
    title = "The pendulum in Cartesian coordinates: DAE algorithms side by side"
    chapter = 8
    model = CartesianPendulum
    run_model: CartesianPendulum
    frame_message_budget = 3.0
    camera_position = (0.0, -3.6, 0.9)
    camera_look_at = (0.0, 0.0, 0.8)
    presets = (
        Preset(
            "unit",
            "Unit pendulum (m = L = g = 1)",
            {**UNIT, "method": "auto", "steps_per_frame": 0},
            "The classic test problem: released level with the pivot, at rest; period 7.42 s.",
        ),
        Preset(
            "drift",
            "Uncorrected: watch the drift",
            {**UNIT, "g_m_s2": 9.81, "method": "uncorrected", "integrator": "rk4", "steps_per_frame": 1},
            "Index reduction alone, one RK4 step per frame: the residuals are never fed back and grow run after run.",
        ),
        Preset(
            "baumgarte",
            "Baumgarte, α = β = 5/s",
            {
                **UNIT,
                "g_m_s2": 9.81,
                "method": "baumgarte",
                "integrator": "rk4",
                "steps_per_frame": 1,
                "baumgarte_alpha_1_s": 5.0,
                "baumgarte_beta_1_s": 5.0,
            },
            "The same step with the residual fed back as a critically damped oscillator: it stays small.",
        ),
        Preset(
            "bad-gains",
            "Baumgarte, gains too large",
            {
                **UNIT,
                "g_m_s2": 9.81,
                "method": "baumgarte",
                "integrator": "rk4",
                "steps_per_frame": 1,
                "baumgarte_alpha_1_s": 200.0,
                "baumgarte_beta_1_s": 200.0,
            },
            "h·α = 6.7 with h = 33 ms: the error's own dynamics are too fast for the step and the run blows up.",
        ),
        Preset(
            "inconsistent",
            "Inconsistent start",
            {**UNIT, "g_m_s2": 9.81, "x0_m": 1.2, "y0_m": 0.4, "vx0_m_s": 1.0, "vy0_m_s": 1.0, "method": "auto"},
            "(1.2, 0.4) m is off the circle and the velocity has a part along the rod: the nearest consistent "
            "start is used.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.circle = scene.add_line_segments(
            "/constraint",
            circle_segments(radius=PENDULUM_REACH, center=tuple(PIVOT), normal=(0.0, 1.0, 0.0)).astype(np.float32),
            (200, 200, 200),
            thickness=1.5,
            thickness_units="screen",
        )
        self.pivot = scene.add_icosphere("/pivot", radius=0.035, color=(40, 40, 40))
        self.pivot.position = PIVOT
        self.rod = scene.add_line_segments("/rod", np.zeros((1, 2, 3), np.float32), ROD_COLOR, thickness=0.015)
        self.dots = scene.add_point_cloud(
            "/bob",
            np.zeros((2, 3), np.float32),
            np.array([GHOST_COLOR, BOB_COLOR], np.uint8),
            point_size=0.12,
            point_shape="circle",
        )
        self.trail = Trail(
            scene, "/path", color=(235, 120, 20), chunk_frames=TRAIL_CHUNK_FRAMES, max_chunks=TRAIL_CHUNKS
        )
        self.legend = scene.add_label(
            "/legend", "grey circle: x² + y² = L² · blue: the bob · grey dot: exact motion", anchor="bottom-center"
        )
        self.legend.position = (0.0, 0.0, float(PIVOT[2]) + 1.15 * PENDULUM_REACH)

    def update(self) -> None:
        self.restart()
        params = self.physical_params()
        self._start = self.run_model.consistent_start(params)
        self._scale = PENDULUM_REACH / float(params["length_m"])
        try:
            exact_states(float(params["length_m"]), float(params["g_m_s2"]), self._start.state, np.zeros(1))
            self._exact = True
        except ValueError:  # over the top, or no gravity: no libration closed form
            self._exact = False
        self.trail.clear()
        self._draw()

    def state(self) -> np.ndarray:
        """The bob's (x, y, ẋ, ẏ) (m, m/s) now, whatever the algorithm integrates."""
        return self.run_model.constrained_view(self.physical_params(), self.run.y)[0]

    def exact_state(self) -> np.ndarray | None:
        if not self._exact:
            return None
        params = self.physical_params()
        return exact_states(
            float(params["length_m"]), float(params["g_m_s2"]), self._start.state, np.array([self.run.t_s])
        )[0]

    def _world(self, x_m: float, y_m: float) -> np.ndarray:
        return PIVOT + self._scale * np.array([x_m, 0.0, y_m])

    def _draw(self) -> None:
        x, y = (float(v) for v in self.state()[:2])
        bob = self._world(x, y)
        exact = self.exact_state()
        ghost = self._world(float(exact[0]), float(exact[1])) if exact is not None else bob
        update_node(self.rod, points=np.array([[PIVOT, bob]], np.float32))
        update_node(self.dots, points=np.array([ghost, bob], np.float32))
        self.trail.add(bob)

    def readout(self) -> Readout:
        params = self.physical_params()
        x, y, vx, vy = (float(v) for v in self.state())
        now = self.current_invariants()
        series = self.run_model.constrained_series(
            params, np.array([self.run.t_s]), self.state()[None, :], self._multipliers()
        )
        exact = self.exact_state()
        algorithm = self.run_model.algorithm()
        quantities = [
            Quantity("t_s", "time t", self.run.t_s, "s"),
            Quantity.word("algorithm", "DAE algorithm", f"{algorithm} ({self.description})"),
            Quantity("x_m", "bob x", x, "m"),
            Quantity("y_m", "bob y (up)", y, "m"),
            Quantity("distance_m", "distance from the pivot √(x² + y²) (rod: L)", math.hypot(x, y), "m"),
            Quantity(
                "constraint_position_m2", "position residual |g| = |L² − x² − y²|/2", now["constraint_position"], "m²"
            ),
            Quantity(
                "constraint_velocity_m2_s", "velocity residual |C v| = |x ẋ + y ẏ|", now["constraint_velocity"], "m²/s"
            ),
            Quantity("energy_J", "energy ½ m v² + m g y", now["energy"], "J"),
            Quantity("energy_drift", "energy drift |ΔE| / (2 m g L)", self.current_drift()["energy"]),
            Quantity(
                "multiplier_N_m",
                "multiplier λ (force per unit length, + = tension)",
                float(series["multiplier"][0]),
                "N/m",
            ),
            Quantity("tension_N", "rod tension λ L", float(series["tension_N"][0]), "N"),
            Quantity.or_text(
                "exact_distance_m",
                "distance from the exact bob (phase error)",
                math.hypot(x - exact[0], y - exact[1]) if exact is not None else None,
                "m",
                "no closed form: the bob goes over the top (or g = 0)",
            ),
            Quantity.word("start", "start", self._start.summary()),
        ]
        if algorithm == "partitioning":
            names = ("x", "y")
            dependent, _ = current_partition(self.run.system.parameters, 2, 1)
            quantities.append(
                Quantity.word("dependent", "dependent coordinate (solved by Newton)", names[dependent[0]])
            )
        return Readout(quantities, message=self.status)

    def _multipliers(self) -> np.ndarray:
        """λ (1, 1) N/m at the current state."""
        params = self.physical_params()
        return multipliers(self.run_model.constrained_system(params), np.array([self.run.t_s]), self.state()[None, :])
