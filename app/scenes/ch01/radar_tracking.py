"""Scene for Example 1.2: the radar, the aircraft's path and its velocity.

Drawn in kilometres (1 scene unit = 1 km) so the 2 km range fits the view;
velocity arrows are drawn at 1 km per 100 m/s. The readout is what the radar
measures as the aircraft flies (r, θ, β and their rates) with the speed and
acceleration they give, then the worked example at the chosen instant t_s.
"""

from __future__ import annotations

import numpy as np

from app.physics.systems.ch01 import radar_tracking as physics
from app.scenes.kit import Mark, Quantity, Readout, Scene, arrow_segments

KM = 1e-3  # scene units per metre
VELOCITY_SCALE = 0.01  # km of arrow per m/s
PATH_T_S = np.linspace(0.0, 60.0, 301)
LOOP_S = 30.0  # the aircraft's animation replays its first 30 s


class RadarTrackingScene(Scene):
    id = "radar-tracking"
    title = "Example 1.2 — radar tracking an aircraft"
    chapter = 1
    example = physics.EXAMPLE
    animated = True
    camera_position = (3.6, -1.6, 2.6)
    camera_look_at = (0.6, 2.0, 1.2)

    def build(self) -> None:
        scene = self.client.scene
        self.t_s = 0.0
        scene.add_grid("/ground", width=6.0, height=10.0, cell_size=0.5, section_size=1.0, position=(1.0, 3.0, 0.0))
        scene.add_label("/ground/note", "grid: 1 km squares", position=(-2.0, -2.0, 0.0))
        scene.add_cylinder("/radar", radius=0.08, height=0.16, color=(70, 70, 70), position=(0, 0, 0.08))
        scene.add_label("/radar/label", "radar", position=(0, 0, 0.2), anchor="bottom-center")
        path = physics.position(PATH_T_S) * KM
        scene.add_line_segments(
            "/path", np.stack([path[:-1], path[1:]], axis=1).astype(np.float32), (120, 120, 160), thickness=0.012
        )
        self.aircraft = scene.add_icosphere("/aircraft", radius=0.09, color=(20, 90, 200))
        self.aircraft_label = scene.add_label("/aircraft/label", "", position=(0.0, 0.0, 0.12), anchor="bottom-left")
        self.sight = scene.add_line_segments("/sight", np.zeros((2, 2, 3), np.float32), (60, 160, 60), thickness=0.006)
        # 0: live velocity of the aircraft; 1: exact velocity at t_s; 2: finite-difference velocity at t_s.
        self.arrows = scene.add_arrows(
            "/velocity",
            np.zeros((3, 2, 3), np.float32),
            np.array([[20, 90, 200], [30, 150, 60], [220, 60, 40]], np.uint8),
            shaft_radius=0.012,
            head_radius=0.035,
            head_length=0.09,
        )
        self.marker = scene.add_icosphere("/evaluation", radius=0.07, color=(30, 150, 60))
        self.marker_label = scene.add_label("/evaluation/label", "", position=(0.0, 0.0, -0.1), anchor="top-left")

    def update(self) -> None:
        # The worked example at the chosen instant: position, exact and finite-difference velocity, the error.
        self.instant = out = physics.solve(self.params).outputs
        p, v_exact, v_fd = out["position_m"] * KM, out["velocity_exact_m_s"], out["velocity_fd_m_s"]
        self.marker.position = p
        self.marker_label.text = (
            f"t = {self.params['t_s']:g} s: |v| = {np.linalg.norm(v_exact):.3f} m/s, "
            f"finite-difference error = {out['fd_error_m_s']:.2e} m/s"
        )
        self._v_pair = (p, v_exact, v_fd)
        self._draw()

    def _draw(self) -> None:
        p_now = physics.position(self.t_s) * KM
        v_now = physics.velocity_exact(max(self.t_s, 1e-6))
        p_eval, v_exact, v_fd = self._v_pair
        self.aircraft.position = p_now
        self.aircraft_label.text = f"t = {self.t_s:4.1f} s  speed {np.linalg.norm(v_now):.1f} m/s"
        self.arrows.points = arrow_segments(
            np.array([p_now, p_eval, p_eval]), np.array([v_now, v_exact, v_fd]), VELOCITY_SCALE
        )
        self.sight.points = np.array([[[0, 0, 0], p_now], [[0, 0, 0], p_eval]], dtype=np.float32)

    def step_motion(self, dt_s: float) -> bool:
        self.t_s = (self.t_s + dt_s) % LOOP_S
        return True

    def readout(self) -> Readout:
        """The radar's readings now (t_s of the flight on screen) and the worked example at the chosen instant."""
        t = self.t_s
        r, theta, beta = (float(v) for v in physics.radar_measurements(t))
        quantities = [
            Quantity("t_s", "time t", t, "s"),
            Quantity("range_m", "range r", r, "m"),
            Quantity("azimuth_deg", "azimuth θ", np.degrees(theta), "deg"),
            Quantity("elevation_deg", "elevation β", np.degrees(beta), "deg"),
        ]
        try:
            velocity = physics.velocity_radar_components(t)
            acceleration = physics.acceleration_radar_components(t)
        except ValueError as exc:  # at t = 0 the elevation rate is infinite
            velocity, acceleration, undefined = None, None, str(exc)
        else:
            undefined = ""
        r_dot, theta_dot, beta_dot = physics.radar_rates(t)
        quantities += [
            Quantity("range_rate_m_s", "range rate ṙ", r_dot, "m/s"),
            Quantity("azimuth_rate_rad_s", "azimuth rate θ̇", theta_dot, "rad/s"),
            Quantity.or_text(
                "elevation_rate_rad_s", "elevation rate β̇", beta_dot, "rad/s", "infinite at t = 0 (β̇ = −0.05/√t)"
            ),
            Quantity.or_text(
                "speed_m_s",
                "speed |v|",
                None if velocity is None else float(np.linalg.norm(velocity)),
                "m/s",
                undefined,
            ),
            Quantity.or_text(
                "acceleration_m_s2",
                "acceleration |a|",
                None if acceleration is None else float(np.linalg.norm(acceleration)),
                "m/s²",
                undefined,
            ),
        ]
        chosen = self.params["t_s"]
        out = self.instant
        quantities += [
            Quantity(
                "instant_speed_m_s",
                f"speed at the chosen t = {chosen:g} s",
                float(np.linalg.norm(out["velocity_exact_m_s"])),
                "m/s",
            ),
            Quantity(
                "fd_error_m_s",
                f"finite-difference error at Δt = {self.params['dt_s']:.3g} s",
                out["fd_error_m_s"],
                "m/s",
            ),
            Quantity("optimal_dt_s", "best Δt of the error model", out["optimal_dt_s"], "s"),
        ]
        marks = {"dt_s": [Mark(out["optimal_dt_s"], "best Δt")]}
        message = (
            "The radar reads r, θ, β: v² = ṙ² + (r cos β θ̇)² + (r β̇)². "
            "Green arrow: the exact velocity at the chosen instant; red: its finite-difference estimate."
        )
        return Readout(quantities, marks=marks, message=message)
