"""Scene: the heavy symmetric top, integrated live, with its axis locus and invariants.

Drawn in display units: the pivot is at the origin and the symmetry axis is one
display unit long whatever ``cg_distance_m`` is, so tops of every size fill the
view. Arrows: angular momentum about the pivot (blue) and the gravity torque
(red), each scaled to its own maximum. The tip of the symmetry axis leaves a
trail on the unit sphere (its locus: waves, loops or cusps).

The quadrature solution is drawn alongside the integration: two green rings on
the sphere bound the nutation band (θ_min, θ_max from the cubic in cos θ) and a
small white sphere marks where the quadrature puts the axis tip now; the
readout compares the band the integration has swept with the predicted one.
"""

from __future__ import annotations

import math

import numpy as np
import viser

from app.physics.math.rotations import rotation_matrix
from app.physics.systems.ch10 import heavy_top as physics
from app.physics.systems.ch10.heavy_top_quadrature import HeavyTopQuadrature
from app.scenes.kit import (
    FRAME_DT_S,
    IntegratedScene,
    Mark,
    Quantity,
    Readout,
    Trail,
    circle_segments,
    move_node,
    update_node,
)

AXIS_LENGTH = 1.0  # display units from pivot to the tip of the axis
TRAIL_CHUNK_FRAMES = 6
TRAIL_CHUNKS = 90  # 90 × 6 frames = 18 s of trail at 30 Hz
#: The in-scene text line is rewritten at 5 Hz (every 6th frame): readable, and one message less on most frames.
LABEL_EVERY_FRAMES = 6
#: Frames of the quadrature reference tip evaluated at once (2 s at 30 Hz).
REFERENCE_BLOCK_FRAMES = 60


def top_mesh(*, radius: float, height_cg: float, segments: int = 48) -> tuple[np.ndarray, np.ndarray]:
    """A top-shaped solid of revolution about +Z (display units): tip at the origin.

    Profile: cone from the tip out to ``radius`` at ``height_cg``, a rounded
    crown above it, and a stem to the axis tip.
    """
    profile = np.array(
        [
            [0.0, 0.0],
            [0.35 * radius, 0.35 * height_cg],
            [radius, height_cg],
            [0.95 * radius, height_cg + 0.06],
            [0.6 * radius, height_cg + 0.12],
            [0.06, height_cg + 0.14],
            [0.04, AXIS_LENGTH],
            [0.0, AXIS_LENGTH],
        ]
    )
    angles = np.linspace(0.0, 2.0 * math.pi, segments, endpoint=False)
    rings = [np.stack([r * np.cos(angles), r * np.sin(angles), np.full(segments, z)], axis=1) for r, z in profile]
    vertices = np.concatenate(rings).astype(np.float32)
    faces = []
    for k in range(len(profile) - 1):
        a, b = k * segments, (k + 1) * segments
        for j in range(segments):
            jn = (j + 1) % segments
            faces.append((a + j, b + j, b + jn))
            faces.append((a + j, b + jn, a + jn))
    return vertices, np.asarray(faces, dtype=np.uint32)


class HeavyTopScene(IntegratedScene):
    id = "heavy-top"
    #: Attitude, the two arrows, their labels, the reference tip, the trail (a chunk every 6 frames), the text at 5 Hz.
    frame_message_budget = 6.0
    title = "The heavy symmetric top"
    chapter = 10
    model = physics.HeavyTop
    camera_position = (1.35, -1.65, 1.05)
    camera_look_at = (0.0, 0.0, 0.35)

    def build(self) -> None:
        scene = self.client.scene
        scene.add_grid("/ground", width=3.0, height=3.0, cell_size=0.1, section_size=0.5, position=(0.0, 0.0, 0.0))
        scene.add_icosphere("/pivot", radius=0.025, color=(40, 40, 40))
        scene.add_icosphere(
            "/locus_sphere",
            radius=AXIS_LENGTH,
            color=(150, 170, 200),
            opacity=0.12,
            subdivisions=4,
            cast_shadow=False,
            receive_shadow=False,
        )
        self.body = scene.add_frame("/top", show_axes=False)
        self.mesh: viser.MeshHandle | None = None
        self.spin_marker = scene.add_icosphere("/top/marker", radius=0.03, color=(240, 190, 40))
        self.arrows = scene.add_arrows(
            "/vectors",
            np.zeros((2, 2, 3), np.float32),
            np.array([[40, 100, 220], [220, 50, 40]], np.uint8),
            shaft_radius=0.012,
            head_radius=0.03,
            head_length=0.07,
        )
        self.arrow_labels = [
            scene.add_label("/vectors/L", "L (angular momentum)", anchor="center-left"),
            scene.add_label("/vectors/tau", "τ (gravity torque)", anchor="center-left"),
        ]
        self.readout_label = scene.add_label("/readout", "", position=(-0.6, 0.0, 1.25), anchor="bottom-left")
        self.band_rings = scene.add_line_segments(
            "/nutation_band", np.zeros((1, 2, 3), np.float32), (40, 160, 80), thickness=2.5, thickness_units="screen"
        )
        self.reference_tip = scene.add_icosphere("/reference_tip", radius=0.022, color=(250, 250, 250))
        self.trail = Trail(
            scene,
            "/trail",
            color=(230, 120, 30),
            chunk_frames=TRAIL_CHUNK_FRAMES,
            max_chunks=TRAIL_CHUNKS,
            thickness=3.0,
        )

    def update(self) -> None:
        params = self.physical_params()
        self.restart()
        m, l = params["mass_kg"], params["cg_distance_m"]
        radius_m = math.sqrt(2.0 * params["I_axial"] / m)  # a uniform disc with the same axial moment
        # Display: pivot-to-CM distance l maps to 0.55 of the axis; the crown radius follows in proportion.
        height_cg = 0.55
        radius = float(np.clip(radius_m / l * height_cg, 0.08, 0.8))
        vertices, faces = top_mesh(radius=radius, height_cg=height_cg)
        if self.mesh is not None:
            self.mesh.remove()
        self.mesh = self.client.scene.add_mesh_simple(
            "/top/body", vertices, faces, color=(70, 130, 180), flat_shading=False
        )
        self.spin_marker.position = (radius, 0.0, height_cg)
        self.trail.clear()
        body = physics.rigid_body(params)
        self._momentum_scale = 0.8 / max(float(np.linalg.norm(body.angular_momentum_world(self.run.y))), 1e-12)
        self._torque_scale = 0.6 / max(body.gravity_moment_N_m, 1e-12)
        self._body_model = body
        self._inertia_pivot = np.asarray(body.inertia_pivot_kg_m2, dtype=float)
        self._update_reference(params)
        self._reference_block: tuple[float, np.ndarray] | None = None
        self._frame_index = 0
        self._draw()

    def _update_reference(self, params) -> None:
        """Quadrature solution for these parameters: nutation band rings and the reference tip."""
        self.reference: HeavyTopQuadrature | None
        self.reference, self.reference_message = physics.reference_or_none(params)
        self._theta_swept = [math.inf, -math.inf]
        rings = []
        if self.reference is not None:
            for theta in {self.reference.theta_min_rad, self.reference.theta_max_rad}:
                height = AXIS_LENGTH * 1.004 * math.cos(theta)
                rings.append(circle_segments(radius=AXIS_LENGTH * 1.004 * math.sin(theta), center=(0.0, 0.0, height)))
        self.band_rings.points = np.concatenate(rings).astype(np.float32) if rings else np.zeros((1, 2, 3), np.float32)
        self.band_rings.visible = bool(rings)
        self.reference_tip.visible = self.reference is not None

    def _draw(self) -> None:
        # Per frame, for every student: one rotation matrix and a few 3-vectors, no general-purpose helpers.
        y = self.run.y
        R = rotation_matrix(y[0:4])  # R_world_body, the quaternion normalised inside
        move_node(self.body, wxyz=y[0:4] / math.sqrt(float(y[0:4] @ y[0:4])))
        axis = R[:, 2]  # the symmetry axis (body 3) in world components
        momentum = R @ (self._inertia_pivot * y[4:7])  # L = R (I ω_body) about the pivot
        # τ = r_G × (−m g Z) = m g l (axis × −Z) = m g l (−axis_y, axis_x, 0)
        torque = self._body_model.gravity_moment_N_m * np.array([-axis[1], axis[0], 0.0])
        heads = np.array([momentum * self._momentum_scale, torque * self._torque_scale])
        segments = np.zeros((2, 2, 3), np.float32)
        segments[:, 1, :] = heads
        update_node(self.arrows, points=segments)
        move_node(self.arrow_labels[0], position=heads[0] * 1.05)
        move_node(self.arrow_labels[1], position=heads[1] * 1.05)
        self.trail.add(axis * AXIS_LENGTH)
        theta_rad = math.acos(max(-1.0, min(1.0, axis[2])))
        self._theta_swept = [min(self._theta_swept[0], theta_rad), max(self._theta_swept[1], theta_rad)]
        if self.reference is not None:
            move_node(self.reference_tip, position=self._reference_tip_position(self.run.t_s))
        if self._frame_index % LABEL_EVERY_FRAMES == 0:
            drift = self._drift_max[-1] if self._drift_max else max(self.current_drift().values(), default=0.0)
            update_node(
                self.readout_label,
                text=f"t = {self.run.t_s:6.2f} s   θ = {math.degrees(theta_rad):5.2f}°   largest drift {drift:.1e}",
            )
        self._frame_index += 1

    def _reference_tip_position(self, t_s: float) -> tuple[float, float, float]:
        """Where the quadrature solution puts the axis tip at ``t_s`` (display units).

        Evaluated for the next :data:`REFERENCE_BLOCK_FRAMES` frames in one vectorised call
        and looked up after that: the same numbers at a tenth of the cost per frame.
        """
        assert self.reference is not None
        block = self._reference_block
        if block is not None:
            index = round((t_s - block[0]) / FRAME_DT_S)
            if 0 <= index < len(block[1]) and abs(block[0] + index * FRAME_DT_S - t_s) < 1e-9:
                return tuple(block[1][index])
        times = t_s + FRAME_DT_S * np.arange(REFERENCE_BLOCK_FRAMES)
        self._reference_block = (t_s, self.reference.symmetry_axis(times) * AXIS_LENGTH)
        return tuple(self._reference_block[1][0])

    def advance(self, dt_s: float) -> None:
        if self.step_motion(dt_s):
            self._draw()
        else:
            self.readout_label.text = self.status

    def readout(self) -> Readout:
        """Quadrature predictions beside what the integration has done so far; the sleeping threshold mark."""
        params = self.physical_params()
        critical = physics.critical_spin_rad_s(params)
        low, high = self._theta_swept
        swept = (low, high) if low <= high else None  # the band the integration has swept (none before a frame)
        quantities = [
            Quantity("t_s", "time t", self.run.t_s, "s"),
            *physics.readout_quantities(params, self.reference, swept),
        ]
        spin = abs(params["spin_rad_s"])
        if params["g_m_s2"] == 0.0:
            message = self.reference_message or (
                "g = 0: no gravity, so no torque about the pivot; the top moves as a torque-free body and any "
                "spin, even none, keeps an upright top up."
            )
            return Readout(quantities, marks={}, message=message)
        message = self.reference_message or (
            f"|ω₃| = {spin:.4g} rad/s is above the sleeping threshold {critical:.4g} rad/s: started upright, "
            "this top would stay up."
            if spin > critical
            else f"|ω₃| = {spin:.4g} rad/s is below the sleeping threshold {critical:.4g} rad/s: an upright "
            "start is unstable."
        )
        marks = {"spin_rad_s": [Mark(critical, "sleeping threshold"), Mark(-critical, "sleeping threshold")]}
        return Readout(quantities, marks=marks, message=message)
