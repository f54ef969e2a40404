"""Scene: the simple pendulum beside its phase plane (θ, p_θ), with level sets of H and the live state on them.

Left: the pendulum in the world xz plane (x right, z up), seen from −y, its rod
:data:`PENDULUM_REACH` display units long. Right: the phase plane, θ from −180°
to 180° across (wrapped), p_θ up, scaled so that the current orbit and the
separatrix fit. Grey lines are level sets of H at fixed fractions of m g l; the
red one is the separatrix H = m g l. The orange point is the running state:
Hamilton's equations move it along its level set, which it never leaves.
Each frame sends three messages (rod, bob, state point).
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.systems.ch09.pendulum_phase_model import (
    PendulumPhaseMotion,
    conjugate_momentum_kg_m2_s,
    hamiltonian_J,
    level_set_momentum_kg_m2_s,
    separatrix_energy_J,
)
from app.scenes.kit import Preset, Quantity, Readout, move_node, update_node
from app.scenes.kit.derived_system_scene import DerivedSystemScene

PENDULUM_REACH = 1.0
PLANE_CENTER = np.array([2.9, 0.0, 0.0])
PLANE_HALF_WIDTH = 1.6  # display units for θ = π
PLANE_HALF_HEIGHT = 1.1  # display units for the largest |p_θ| drawn
#: Level sets drawn, as multiples of m g l (1 is the separatrix).
LEVELS = (-0.9, -0.6, -0.2, 0.3, 0.7, 1.0, 1.4, 2.0)
LEVEL_COLOR, SEPARATRIX_COLOR, AXIS_COLOR = (165, 165, 170), (215, 45, 45), (60, 60, 60)
SAMPLES = 241


def _polyline_segments(points: np.ndarray) -> np.ndarray:
    """(N, 3) points → (N − 1, 2, 3) segments between consecutive ones."""
    return np.stack([points[:-1], points[1:]], axis=1)


class PhasePortraitScene(DerivedSystemScene):
    id = "phase-portrait"
    frame_message_budget = 3.5
    title = "Hamilton's equations: the pendulum's phase portrait"
    chapter = 9
    model = PendulumPhaseMotion
    camera_position = (1.45, -4.4, 0.1)
    camera_look_at = (1.45, 0.0, -0.1)
    presets = (
        Preset(
            "small-swing",
            "Small swing",
            {"theta_0_deg": 15.0, "theta_rate_0_deg_s": 0.0},
            "H = −m g l cos 15°: the state goes round a small, nearly elliptical level set (a harmonic oscillator).",
        ),
        Preset(
            "near-separatrix",
            "Near the separatrix",
            {"theta_0_deg": 175.0, "theta_rate_0_deg_s": 0.0},
            "Released 5° from upright: the orbit hugs the separatrix and lingers near θ = ±180°; the period "
            "grows without bound as the release nears 180°.",
        ),
        Preset(
            "over-the-top",
            "Going over the top",
            {"theta_0_deg": 0.0, "theta_rate_0_deg_s": 420.0},
            "θ̇₀ = 420°/s at the bottom exceeds 2√(g/l) = 359°/s (l = 1 m): H > m g l, the pendulum rotates and "
            "p_θ never changes sign.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.levels = scene.add_line_segments(
            "/phase/levels",
            np.zeros((1, 2, 3), np.float32),
            np.zeros((1, 2, 3), np.uint8),
            thickness=1.5,
            thickness_units="screen",
        )
        self.plane_label = scene.add_label(
            "/phase/label",
            "phase plane: θ across (−180° to 180°), p_θ up; red: separatrix H = m g l",
            anchor="bottom-center",
        )
        self.plane_label.position = PLANE_CENTER + np.array([0.0, 0.0, PLANE_HALF_HEIGHT + 0.12])
        self.pivot = scene.add_icosphere("/pivot", radius=0.035, color=(40, 40, 40))
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
        self.state_point = scene.add_icosphere("/phase/state", radius=0.045, color=(235, 120, 20))

    def update(self) -> None:
        self.restart()
        params = self.physical_params()
        unit = max(separatrix_energy_J(params), 1e-12)
        energy0 = float(self.current_invariants()["hamiltonian"])
        m, l = float(params["mass_kg"]), float(params["length_m"])
        largest = max(2.0 * unit, energy0) + unit  # kinetic energy at the bottom of the highest orbit drawn
        self._p_scale = PLANE_HALF_HEIGHT / math.sqrt(2.0 * m * l * l * largest)
        segments, colors = [], []
        for fraction in LEVELS:
            energy = fraction * unit
            if energy < unit:  # a closed orbit between the turning angles ±θ_t
                turning = math.acos(max(-1.0, min(1.0, -energy / unit)))
                theta = turning * np.sin(np.linspace(-0.5 * math.pi, 0.5 * math.pi, SAMPLES))
            else:
                theta = np.linspace(-math.pi, math.pi, SAMPLES)
            momentum = np.nan_to_num(level_set_momentum_kg_m2_s(params, energy, theta))
            color = SEPARATRIX_COLOR if fraction == 1.0 else LEVEL_COLOR
            for sign in (1.0, -1.0):
                segments.append(_polyline_segments(self._plane_point(theta, sign * momentum)))
                colors.append(np.full((SAMPLES - 1, 2, 3), color, np.uint8))
        p_top = PLANE_HALF_HEIGHT / self._p_scale
        for theta_ends, p_ends in (
            ([-math.pi, math.pi], [0.0, 0.0]),
            ([0.0, 0.0], [-p_top, p_top]),
        ):  # θ axis, p_θ axis
            segments.append(_polyline_segments(self._plane_point(np.array(theta_ends), np.array(p_ends))))
            colors.append(np.full((1, 2, 3), AXIS_COLOR, np.uint8))
        update_node(self.levels, points=np.concatenate(segments).astype(np.float32), colors=np.concatenate(colors))
        self._display_scale = PENDULUM_REACH / l
        self._draw()

    def _plane_point(self, theta_rad: np.ndarray, p_theta_kg_m2_s: np.ndarray) -> np.ndarray:
        """(N, 3) world points of phase-plane states (θ wrapped to (−π, π])."""
        theta = np.asarray(theta_rad, dtype=float)
        theta = np.where(np.abs(theta) <= math.pi, theta, np.remainder(theta + math.pi, 2.0 * math.pi) - math.pi)
        across = PLANE_HALF_WIDTH * theta / math.pi
        up = self._p_scale * np.asarray(p_theta_kg_m2_s, dtype=float)
        return PLANE_CENTER + np.stack([across, np.zeros_like(across), up], axis=-1)

    def _draw(self) -> None:
        theta, rate = float(self.run.y[0]), float(self.run.y[1])
        bob = PENDULUM_REACH * np.array([math.sin(theta), 0.0, -math.cos(theta)])
        update_node(self.rod, points=np.array([[np.zeros(3), bob]], np.float32))
        update_node(
            self.bob, points=bob[None, :].astype(np.float32)
        )  # the same kind of update as the rod: they arrive together
        momentum = float(conjugate_momentum_kg_m2_s(self.physical_params(), rate))
        move_node(self.state_point, position=self._plane_point(np.array([theta]), np.array([momentum]))[0])

    def readout(self) -> Readout:
        params = self.physical_params()
        theta, rate = float(self.run.y[0]), float(self.run.y[1])
        momentum = float(conjugate_momentum_kg_m2_s(params, rate))
        hamiltonian = float(hamiltonian_J(params, theta, momentum))
        separatrix = separatrix_energy_J(params)
        motion = "rotating (H > m g l)" if hamiltonian > separatrix else "swinging (H < m g l)"
        quantities = [
            Quantity("t_s", "time t", self.run.t_s, "s"),
            Quantity("theta_deg", "angle θ (wrapped)", math.degrees(math.remainder(theta, 2 * math.pi)), "deg"),
            Quantity("p_theta_kg_m2_s", "momentum p_θ = m l² θ̇", momentum, "kg·m²/s"),
            Quantity("hamiltonian_J", "Hamiltonian H = p_θ²/(2 m l²) − m g l cos θ", hamiltonian, "J"),
            Quantity("hamiltonian_initial_J", "H at the start", self._invariants0["hamiltonian"], "J"),
            self.drift_quantity("hamiltonian", "H drift |ΔH| / scale"),
            Quantity("separatrix_J", "separatrix level m g l", separatrix, "J"),
            Quantity.word("motion", "kind of motion", motion),
            *self.agreement_quantities(),
        ]
        return Readout(quantities, message=self.status)
