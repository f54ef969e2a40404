"""Scene: the rattleback, spun on a floor, rocks, stops and spins the other way.

World frame (m, +Z up, floor z = 0), true scale: the body is drawn as the model's own ellipsoid; a dark line over its
top marks the long principal axis of inertia, turned δ (under a degree for Kane and Levinson's body) from the
ellipsoid's long axis. The touching point leaves an orange trail on the floor, and a blue bar from under the floor
up to it shows the floor's upward push. Each frame sends the body's pose, the arrow and a trail chunk every few frames.

The readout says, from the engine's own linearisation about steady upright spinning at the start's spin, whether that
spin is stable, and how fast the rocking that reverses it grows.
"""

from __future__ import annotations

import math

import numpy as np
import viser

from app.physics.math.rotations import quaternion_from_matrix
from app.physics.mechanics.multibody.linearise import eigenvalues, state_matrix
from app.physics.systems.ch08.rattleback import REFERENCE
from app.physics.systems.ch08.rattleback_model import (
    GRIP_NEEDED,
    PITCH,
    ROLL,
    YAW,
    N,
    RattlebackMotion,
    Z,
    orientation,
    rattleback_model,
    system_params,
    touching_point,
)
from app.scenes.kit import IntegratedScene, Preset, Quantity, Readout, Trail, update_node
from app.scenes.viser_boundary import move_node

TRAIL_CHUNK_FRAMES = 3
TRAIL_CHUNKS = 200  # 20 s of the touching point's path at 30 Hz
BODY_COLOR = (200, 150, 60)
AXIS_COLOR = (40, 40, 50)
FORCE_COLOR = (40, 110, 220)
#: The force arrow's length per newton (m/N): the weight of the default 1 kg body is a 5 cm arrow.
FORCE_M_PER_N = 0.005


def ellipsoid_mesh(semi_axes: np.ndarray, centre: np.ndarray, *, rings: int = 16, around: int = 48):
    """Vertices (V, 3) and faces (F, 3) of the ellipsoid with these semi-axes (m) about ``centre`` (m)."""
    vertices = [centre + np.array([0.0, 0.0, -semi_axes[2]])]
    for k in range(1, rings):
        polar = math.pi * k / rings
        angles = np.linspace(0.0, 2 * math.pi, around, endpoint=False)
        ring = np.stack(
            [np.sin(polar) * np.cos(angles), np.sin(polar) * np.sin(angles), np.full(around, -math.cos(polar))], axis=1
        )
        vertices.extend(centre + ring * semi_axes)
    vertices.append(centre + np.array([0.0, 0.0, semi_axes[2]]))
    top = len(vertices) - 1
    faces = [(0, 1 + (j + 1) % around, 1 + j) for j in range(around)]
    for k in range(rings - 2):
        inner, outer = 1 + k * around, 1 + (k + 1) * around
        for j in range(around):
            jn = (j + 1) % around
            faces += [(inner + j, inner + jn, outer + jn), (inner + j, outer + jn, outer + j)]
    last = 1 + (rings - 2) * around
    faces += [(top, last + j, last + (j + 1) % around) for j in range(around)]
    return np.array(vertices, dtype=np.float32), np.array(faces, dtype=np.uint32)


def principal_axis_line(params, *, pieces: int = 24) -> np.ndarray:
    """Segments (K, 2, 3), body axes from G: the long principal axis of inertia, drawn over the ellipsoid's top."""
    block = np.array(
        [
            [float(params["inertia_xx_kg_m2"]), float(params["inertia_xy_kg_m2"])],
            [float(params["inertia_xy_kg_m2"]), float(params["inertia_yy_kg_m2"])],
        ]
    )
    direction = np.linalg.eigh(block)[1][:, 0]  # the smallest moment's axis: the long one
    a, b, c, h = (float(params[k]) for k in ("semi_axis_a_m", "semi_axis_b_m", "semi_axis_c_m", "mass_centre_drop_m"))
    reach = 0.9 / math.hypot(direction[0] / a, direction[1] / b)
    s = np.linspace(-reach, reach, pieces + 1)
    x, y = s * direction[0], s * direction[1]
    z = h + c * np.sqrt(np.clip(1 - (x / a) ** 2 - (y / b) ** 2, 0.0, 1.0)) + 5e-4
    points = np.stack([x, y, z], axis=1)
    return np.stack([points[:-1], points[1:]], axis=1).astype(np.float32)


class RattlebackScene(IntegratedScene):
    id = "rattleback"
    title = "The rattleback: a spin that reverses itself"
    chapter = 8
    model = RattlebackMotion
    run_model: RattlebackMotion
    frame_message_budget = 4.5
    camera_position = (0.24, -0.34, 0.20)
    camera_look_at = (0.0, 0.0, 0.0)
    presets = (
        Preset(
            "reverses",
            "Spun anticlockwise: it rattles and reverses",
            {"spin_0_rad_s": 5.0, "roll_0_deg": 0.5, "pitch_0_deg": -0.5, "roll_rate_0_rad_s": 0.0,
             "pitch_rate_0_rad_s": 0.0},
            "Kane and Levinson's start: 5 rad/s anticlockwise (seen from above), tilted half a degree. The tilt grows "
            "into a pitching rattle (about 17 Hz) that takes the spin's energy: the spin passes through zero at "
            "2.35 s and the body settles spinning clockwise at about 5.2 rad/s.",
        ),
        Preset(
            "slow-reversal",
            "Spun clockwise: ten seconds, then it reverses too",
            {"spin_0_rad_s": -5.0, "roll_0_deg": 0.5, "pitch_0_deg": -0.5, "roll_rate_0_rad_s": 0.0,
             "pitch_rate_0_rad_s": 0.0},
            "Clockwise is the preferred sense: the pitching dies away. What grows instead is a slow roll about the "
            "long axis (ten times slower), and with no friction to drain it, it too reverses the spin, after about "
            "11 s. A real rattleback loses that energy to friction first, so it seems to have one good direction.",
        ),
        Preset(
            "tapped",
            "Tapped at one end: it starts to spin clockwise",
            {"spin_0_rad_s": 0.0, "roll_0_deg": 0.0, "pitch_0_deg": 0.0, "roll_rate_0_rad_s": 0.0,
             "pitch_rate_0_rad_s": 1.0},
            "A tap on one end sets it pitching with no spin at all; the misaligned axes turn the pitching into a "
            "spin, clockwise, which reaches about 1 rad/s in 5 s.",
        ),
        Preset(
            "rocked",
            "Rocked on its side: it creeps round anticlockwise",
            {"spin_0_rad_s": 0.0, "roll_0_deg": 0.0, "pitch_0_deg": 0.0, "roll_rate_0_rad_s": 3.0,
             "pitch_rate_0_rad_s": 0.0},
            "Rocked about its long axis instead, it turns the other way, anticlockwise, and far more slowly.",
        ),
    )  # fmt: skip

    def build(self) -> None:
        scene = self.client.scene
        scene.add_grid("/floor", width=0.6, height=0.6, cell_size=0.02, section_size=0.1)
        self.body = scene.add_frame("/rattleback", show_axes=False)
        self.mesh: viser.MeshHandle | None = None
        self.principal_axis = scene.add_line_segments(
            "/rattleback/principal-axis",
            np.zeros((24, 2, 3), np.float32),
            np.full((24, 2, 3), AXIS_COLOR, np.uint8),
            thickness=3.0,
            thickness_units="screen",
        )
        self.force = scene.add_line_segments(
            "/floor-force",
            np.zeros((1, 2, 3), np.float32),
            np.array([[FORCE_COLOR, FORCE_COLOR]], np.uint8),
            thickness=4.0,
            thickness_units="screen",
        )
        self.path = Trail(
            scene, "/touching-path", color=(235, 120, 20), chunk_frames=TRAIL_CHUNK_FRAMES, max_chunks=TRAIL_CHUNKS
        )

    def drawn_trails(self) -> list[Trail]:
        return [self.path]

    def update(self) -> None:
        self.restart()
        params = self.physical_params()
        semi_axes = np.array([float(params[k]) for k in ("semi_axis_a_m", "semi_axis_b_m", "semi_axis_c_m")])
        vertices, faces = ellipsoid_mesh(semi_axes, np.array([0.0, 0.0, float(params["mass_centre_drop_m"])]))
        if self.mesh is not None:
            self.mesh.remove()
        self.mesh = self.client.scene.add_mesh_simple(
            "/rattleback/body", vertices, faces, color=BODY_COLOR, flat_shading=False
        )
        update_node(self.principal_axis, points=principal_axis_line(params))
        self._linear_at_spin(params)
        self.clear_trails()
        self._draw()

    def _linear_at_spin(self, params) -> None:
        """The eigenvalues about steady upright spinning at the start's spin."""
        values = eigenvalues(state_matrix(rattleback_model(), system_params(params), REFERENCE))
        self._growth_1_s = float(np.max(values.real))

    def _draw(self) -> None:
        params = self.physical_params()
        y = self.run.y
        q = y[:N]
        R = orientation(q)
        centre = np.array([float(q[0]), float(q[1]), float(q[Z])])
        move_node(self.body, position=centre, wxyz=quaternion_from_matrix(R))
        contact = centre + R @ touching_point(params, q)
        self.path.add(np.array([contact[0], contact[1], 5e-4]))
        normal = float(self.run_model.normal_force_N(params, np.array([self.run.t_s]), y[None, :])[0])
        # The floor's push, drawn under the floor (where it comes from) up to the touching point it acts at.
        tail = contact - np.array([0.0, 0.0, normal * FORCE_M_PER_N])
        update_node(self.force, points=np.array([[tail, contact]], np.float32))

    def readout(self) -> Readout:
        params = self.physical_params()
        y = self.run.y
        now = self.current_invariants()
        normal = float(self.run_model.normal_force_N(params, np.array([self.run.t_s]), y[None, :])[0])
        spin0 = float(params["spin_0_rad_s"])
        grip = self.run_model.grip_needed(params, y)
        grip_words = "rolls, as the model assumes" if grip <= GRIP_NEEDED else "a real one would skid here"
        if spin0 == 0.0:
            verdict = "at rest: any rocking feeds a spin in the preferred direction"
        elif self._growth_1_s > 1e-9:
            verdict = f"unstable: rocking grows at {self._growth_1_s:.3g} 1/s"
        else:
            verdict = "stable: rocking dies away"
        quantities = [
            Quantity("t_s", "time t", self.run.t_s, "s"),
            Quantity("spin_rad_s", "spin ψ̇ (positive: anticlockwise from above)", float(y[N + YAW]), "rad/s"),
            Quantity("roll_deg", "roll φ about the long axis", math.degrees(float(y[ROLL])), "deg"),
            Quantity("pitch_deg", "pitch θ about the short axis", math.degrees(float(y[PITCH])), "deg"),
            Quantity("energy_J", "energy T + V", now["energy"], "J"),
            Quantity("energy_drift", "energy drift |ΔE| / scale", self.current_drift()["energy"]),
            Quantity("normal_force_N", "floor's push up (≥ 0 while it touches)", normal, "N"),
            Quantity("grip_needed", "friction needed to stop slip, |F_horizontal| / N", grip),
            Quantity.word("grip", f"a toy on a table grips to about {GRIP_NEEDED:g}", grip_words),
            Quantity("constraint_position_m", "underside off the floor max|g|", now["constraint_position"], "m"),
            Quantity("constraint_velocity_m_s", "slip at the contact max|C v|", now["constraint_velocity"], "m/s"),
            Quantity("largest_growth_rate_1_s", "largest Re λ, steady spin at the start", self._growth_1_s, "1/s"),
            Quantity.word("spin_stability", f"steady spin at {spin0:g} rad/s", verdict),
            Quantity.word("algorithm", "DAE algorithm", f"{self.run_model.algorithm()} ({self.description})"),
        ]  # fmt: skip
        return Readout(quantities, message=self.status)
