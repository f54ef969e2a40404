"""Scene: the spherical pendulum with its bob's path, beside Routh's effective potential V_eff(θ).

Left: the pendulum in 3D (world z up), the pivot :data:`PIVOT` and the rod
:data:`PENDULUM_REACH` display units long; the bob leaves a trail. Right, in
the xz plane facing the camera: V_eff(θ) = β²/(2 m l² sin²θ) − m g l cos θ
for θ from 0 to 180° across, with β the run's conserved momentum; the
horizontal line is the energy E, the two grey dots where it meets the curve
are the turning angles θ_min and θ_max, and the orange dot is the running θ
on the curve. Each frame sends four messages at most (rod, bob, the dot, a
trail chunk every few frames).
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.systems.ch09.spherical_pendulum_model import (
    SphericalPendulumMotion,
    azimuthal_momentum_kg_m2_s,
    conical_rate_rad_s,
    effective_potential_J,
    turning_angles_rad,
)
from app.scenes.kit import Preset, Quantity, Readout, Trail, move_node, update_node
from app.scenes.kit.derived_system_scene import DerivedSystemScene

PIVOT = np.array([0.0, 0.0, 1.1])
PENDULUM_REACH = 1.0
PLOT_LEFT, PLOT_WIDTH = 1.7, 2.6  # display x of θ = 0 and the width for θ = π
PLOT_BOTTOM, PLOT_HEIGHT = -0.9, 1.9  # display z of the plot's lowest and the span to its top
CURVE_COLOR, ENERGY_COLOR, AXIS_COLOR = (40, 100, 220), (215, 45, 45), (60, 60, 60)
SAMPLES = 361
TRAIL_CHUNK_FRAMES = 4
TRAIL_CHUNKS = 60  # 8 s of path at 30 Hz


class SphericalPendulumScene(DerivedSystemScene):
    id = "spherical-pendulum"
    frame_message_budget = 4.0
    title = "Routh's method: the spherical pendulum and its effective potential"
    chapter = 9
    model = SphericalPendulumMotion
    camera_position = (1.6, -4.6, 1.0)
    camera_look_at = (1.6, 0.0, 0.2)
    presets = (
        Preset(
            "conical",
            "Steady cone",
            {
                "mass_kg": 1.0,
                "length_m": 1.0,
                "g_m_s2": 9.81,
                "theta_0_deg": 60.0,
                "theta_rate_0_deg_s": 0.0,
                "phi_rate_0_deg_s": round(math.degrees(math.sqrt(9.81 / math.cos(math.radians(60.0)))), 4),
            },
            "φ̇₀ = √(g/(l cos θ₀)) = 6.26 rad/s at 60°: θ sits at the bottom of V_eff and the bob draws a "
            "horizontal circle.",
        ),
        Preset(
            "wide-band",
            "Wide band",
            {"theta_0_deg": 90.0, "theta_rate_0_deg_s": 0.0, "phi_rate_0_deg_s": 60.0},
            "Started level with the pivot and a slow sweep: the bob dips far below and climbs back, θ between "
            "the two crossings of E with V_eff.",
        ),
        Preset(
            "above-pivot",
            "Swinging above the pivot",
            {"theta_0_deg": 135.0, "theta_rate_0_deg_s": 0.0, "phi_rate_0_deg_s": 400.0},
            "Fast enough that the bob stays above the pivot part of the time: V_eff keeps θ away from 180°, "
            "however high it goes.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.curve = scene.add_line_segments(
            "/veff/curve",
            np.zeros((1, 2, 3), np.float32),
            np.zeros((1, 2, 3), np.uint8),
            thickness=2.0,
            thickness_units="screen",
        )
        self.plot_label = scene.add_label(
            "/veff/label", "V_eff(θ) for θ from 0 to 180°; red: the energy E", anchor="bottom-center"
        )
        self.plot_label.position = (PLOT_LEFT + 0.5 * PLOT_WIDTH, 0.0, PLOT_BOTTOM + PLOT_HEIGHT + 0.1)
        self.turning = scene.add_point_cloud(
            "/veff/turning",
            np.zeros((2, 3), np.float32),
            np.full((2, 3), 120, np.uint8),
            point_size=0.07,
            point_shape="circle",
        )
        self.marker = scene.add_icosphere("/veff/theta", radius=0.045, color=(235, 120, 20))
        self.pivot = scene.add_icosphere("/pivot", radius=0.035, color=(40, 40, 40))
        self.pivot.position = PIVOT
        self.rod = scene.add_line_segments(
            "/rod", np.zeros((1, 2, 3), np.float32), np.array([[[40, 100, 220]] * 2], np.uint8), thickness=0.02
        )
        self.bob = scene.add_point_cloud(
            "/bob",
            np.zeros((1, 3), np.float32),
            np.array([[40, 100, 220]], np.uint8),
            point_size=0.14,
            point_shape="circle",
        )
        self.trail = Trail(
            scene, "/path", color=(235, 120, 20), chunk_frames=TRAIL_CHUNK_FRAMES, max_chunks=TRAIL_CHUNKS
        )

    def update(self) -> None:
        self.restart()
        params = self.physical_params()
        state = self.run.y
        self._beta = float(azimuthal_momentum_kg_m2_s(params, state[None, :])[0])
        self._energy = float(self._invariants0["energy"])
        self._turning = turning_angles_rad(params, state)
        theta = np.linspace(0.0, math.pi, SAMPLES)[1:-1]
        potential = effective_potential_J(params, self._beta, theta)
        lowest = float(np.min(potential))
        m, l, g = (float(params[n]) for n in ("mass_kg", "length_m", "g_m_s2"))
        self._v_low = lowest - 0.1 * max(self._energy - lowest, 0.1 * m * g * l, 1e-12)
        self._v_span = 2.0 * max(self._energy - self._v_low, 0.2 * m * g * l, 1e-12)
        points = self._plot_point(theta, potential)
        inside = points[:, 2] <= PLOT_BOTTOM + PLOT_HEIGHT
        keep = inside[:-1] & inside[1:]
        segments = [np.stack([points[:-1], points[1:]], axis=1)[keep]]
        colors = [np.full((int(keep.sum()), 2, 3), CURVE_COLOR, np.uint8)]
        for theta_ends, v_ends, color in (
            ([0.0, math.pi], [self._energy] * 2, ENERGY_COLOR),
            ([0.0, math.pi], [self._v_low] * 2, AXIS_COLOR),
            ([0.0, 0.0], [self._v_low, self._v_low + self._v_span], AXIS_COLOR),
        ):
            segments.append(self._plot_point(np.array(theta_ends), np.array(v_ends))[None, :, :])
            colors.append(np.full((1, 2, 3), color, np.uint8))
        update_node(self.curve, points=np.concatenate(segments).astype(np.float32), colors=np.concatenate(colors))
        update_node(
            self.turning, points=self._plot_point(np.array(self._turning), np.full(2, self._energy)).astype(np.float32)
        )
        self._display_scale = PENDULUM_REACH / l
        self.trail.clear()
        self._draw()

    def _plot_point(self, theta_rad: np.ndarray, potential_J: np.ndarray) -> np.ndarray:
        """(N, 3) world points of the V_eff plot for angles (N,) rad and energies (N,) J."""
        across = PLOT_LEFT + PLOT_WIDTH * np.asarray(theta_rad, dtype=float) / math.pi
        up = PLOT_BOTTOM + PLOT_HEIGHT * (np.asarray(potential_J, dtype=float) - self._v_low) / self._v_span
        return np.stack([across, np.zeros_like(across), up], axis=-1)

    def _draw(self) -> None:
        theta, phi = float(self.run.y[0]), float(self.run.y[1])
        bob = PIVOT + PENDULUM_REACH * np.array(
            [math.sin(theta) * math.cos(phi), math.sin(theta) * math.sin(phi), -math.cos(theta)]
        )
        update_node(self.rod, points=np.array([[PIVOT, bob]], np.float32))
        update_node(
            self.bob, points=bob[None, :].astype(np.float32)
        )  # the same kind of update as the rod: they arrive together
        self.trail.add(bob)
        on_curve = float(effective_potential_J(self.physical_params(), self._beta, theta))
        move_node(self.marker, position=self._plot_point(np.array([theta]), np.array([on_curve]))[0])

    def readout(self) -> Readout:
        params = self.physical_params()
        theta = float(self.run.y[0])
        beta = float(azimuthal_momentum_kg_m2_s(params, self.run.y[None, :])[0])
        conical = conical_rate_rad_s(params, theta)
        quantities = [
            Quantity("t_s", "time t", self.run.t_s, "s"),
            Quantity("theta_deg", "angle θ from the downward vertical", math.degrees(theta), "deg"),
            Quantity("phi_rate_rad_s", "azimuth rate φ̇", float(self.run.y[3]), "rad/s"),
            Quantity("beta_kg_m2_s", "β = m l² sin²θ φ̇ (conserved)", beta, "kg·m²/s"),
            self.drift_quantity("azimuthal_momentum", "β drift |Δβ| / scale"),
            Quantity("energy_J", "energy E = ½ m l² θ̇² + V_eff(θ)", self.current_invariants()["energy"], "J"),
            self.drift_quantity("energy", "energy drift |ΔE| / scale"),
            Quantity("theta_min_deg", "turning angle θ_min (V_eff = E)", math.degrees(self._turning[0]), "deg"),
            Quantity("theta_max_deg", "turning angle θ_max (V_eff = E)", math.degrees(self._turning[1]), "deg"),
            Quantity.or_text(
                "conical_rate_rad_s",
                "steady cone's φ̇ at this θ, √(g/(l cos θ))",
                conical,
                "rad/s",
                "none: no steady cone at or above the pivot's level",
            ),
            *self.agreement_quantities(),
        ]
        return Readout(quantities, message=self.status)
