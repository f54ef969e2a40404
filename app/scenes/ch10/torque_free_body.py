"""Scene: the torque-free body of arbitrary inertia and Poinsot's construction (chapter 10.1).

Drawn in ω-space, in display units: the largest semi-axis of the energy ellipsoid
``ωᵀ I ω = 2T`` is one unit, so 1 rad/s of angular velocity is ``self.scale`` units.
The centre of mass is at the origin; the body (a uniform box with the same principal
moments) and its energy ellipsoid turn together, and the ellipsoid rolls on the
invariable plane, which is horizontal because the closed form is started with L along
world −Z. ω is drawn from the origin to its tip, which is the point of contact; its tip
leaves the polhode on the ellipsoid (a trail fixed in the body) and the herpolhode on the
plane (fixed in space). Faint curves on the ellipsoid are the other polhodes at this
energy, including the two separatrices through the intermediate axis.

Every frame is 1/30 s of motion taken from the closed form (evaluated 30 frames at a
time); the optional "ghost" is the same body integrated by the solver core's RK4 beside it,
drawn as an outline: lines are drawn in the opaque pass, so the translucent ellipsoid
around it cannot hide it the way it hides a translucent box.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter
from app.physics.solvers import LiveRun
from app.physics.systems.ch10 import torque_free_body as physics
from app.scenes.kit import FRAME_DT_S, Mark, Preset, Quantity, Readout, Scene, Trail

ELLIPSOID_SIZE = 1.0  # display units: the largest semi-axis of the energy ellipsoid
BOX_FILL = 0.8  # the box's corners sit at this fraction of the way out to the ellipsoid
THINNEST_SIDE = 0.04  # a flat plate is still drawn with this fraction of its longest side
BATCH_FRAMES = 30  # closed-form frames evaluated per call (one second)
TRAIL_CHUNK_FRAMES = 10  # a trail grows by one line node every 1/3 s
HERPOLHODE_CHUNKS = 60  # the last 20 s of herpolhode (longer fills its annulus solid)
POLHODE_CHUNKS = 180  # cap when ω never repeats (separatrix); otherwise one period is drawn
# Curves on a surface are drawn a hair off it so the translucent surface does not hide them.
ON_ELLIPSOID = 1.006
ABOVE_PLANE = 0.004

AXIS_COLORS = np.array([[220, 60, 60], [40, 170, 70], [50, 90, 220]], np.uint8)  # body axes 1, 2, 3
MOMENTUM_COLOR = (120, 40, 170)
OMEGA_COLOR = (235, 110, 20)
POLHODE_COLOR = (245, 150, 20)
HERPOLHODE_COLOR = (200, 30, 70)
GHOST_COLOR = (30, 190, 120)
HERPOLHODE_LABEL_SIDE = np.array([-0.8, -0.6, 0.0])  # a horizontal direction on the camera's left
POLHODE_LABEL_SIDE = -HERPOLHODE_LABEL_SIDE  # the camera's right: the two curves' names never meet

GHOST = Parameter(
    "ghost",
    "",
    "off",
    kind="choice",
    choices=("off", "on"),
    label="numerical ghost",
    description="Also integrate the same body numerically (RK4 on the solver core) and draw it as a green "
    "see-through outline; the readout shows the angle between the two attitudes",
)

_BOOK = dict(physics.BOOK_INERTIA_KG_M2)
PRESETS = (
    Preset(
        "tennis-racket",
        "Tennis racket: spin about the intermediate axis",
        {**_BOOK, "omega0_rad_s": [0.1, 4.0, 0.1]},
        "The book spun about axis 2 (the middle moment) with a tiny wobble: it turns over every few seconds "
        "(Dzhanibekov effect).",
    ),
    Preset(
        "major-axis",
        "Near the major axis (stable)",
        {**_BOOK, "omega0_rad_s": [0.3, 0.3, 4.0]},
        "Spin about axis 3, the largest moment: the polhode is a small loop and the wobble stays small.",
    ),
    Preset(
        "minor-axis",
        "Near the minor axis (stable)",
        {**_BOOK, "omega0_rad_s": [4.0, 0.3, 0.3]},
        "Spin about axis 1, the smallest moment: also stable in the torque-free ideal.",
    ),
)

_AXIS_RANK = ("min I", "mid I", "max I")


def box_edges(sides: np.ndarray) -> np.ndarray:
    """The 12 edges (12, 2, 3) of a box centred on the origin with these sides along x, y, z."""
    corners = np.array([[i, j, k] for i in (-0.5, 0.5) for j in (-0.5, 0.5) for k in (-0.5, 0.5)]) * sides
    pairs = [(a, b) for a in range(8) for b in range(a + 1, 8) if bin(a ^ b).count("1") == 1]
    return np.array([[corners[a], corners[b]] for a, b in pairs], np.float32)


class TorqueFreeBodyScene(Scene):
    id = "torque-free-body"
    title = "The torque-free body and Poinsot's construction"
    chapter = 10
    model = physics.TorqueFreeBody
    controls = (GHOST,)
    presets = PRESETS
    animated = True
    camera_position = (1.25, -1.7, 1.05)
    camera_look_at = (0.0, 0.0, -0.3)

    # -- building ------------------------------------------------------------------------------
    def build(self) -> None:
        scene = self.client.scene
        self.body_frame = scene.add_frame("/body", show_axes=False)
        self.ellipsoid = scene.add_icosphere(
            "/body/ellipsoid",
            radius=1.0,
            color=(250, 215, 110),
            subdivisions=5,
            opacity=0.3,
            cast_shadow=False,
            receive_shadow=False,
        )
        self.axis_labels = [
            scene.add_label(f"/body/axis_label_{k + 1}", "", anchor="center-left", font_screen_scale=0.85)
            for k in range(3)
        ]
        self.ghost_frame = scene.add_frame("/ghost", show_axes=False, visible=False)
        self.arrows = scene.add_arrows(
            "/vectors",
            np.zeros((2, 2, 3), np.float32),
            np.array([MOMENTUM_COLOR, OMEGA_COLOR], np.uint8),
            shaft_radius=0.013,
            head_radius=0.036,
            head_length=0.08,
        )
        self.momentum_label = scene.add_label("/vectors/L", "L (fixed)", anchor="center-left")
        # The contact point carries its marker and ω's label: one pose message per frame moves both.
        self.contact = scene.add_frame("/contact", show_axes=False)
        scene.add_icosphere("/contact/marker", radius=0.022, color=HERPOLHODE_COLOR, cast_shadow=False)
        scene.add_label("/contact/omega_label", "ω", position=(0.03, 0.0, 0.05), anchor="bottom-left")
        self.plane_label = scene.add_label("/plane_label", "invariable plane (⊥ L, fixed in space)", anchor="top-left")
        self.herpolhode_label = scene.add_label(
            "/herpolhode_label", "herpolhode (red, on the plane)", anchor="center-right", font_screen_scale=0.85
        )
        self.polhode_label = scene.add_label(
            "/polhode_label", "polhode (orange, on the ellipsoid)", anchor="center-left", font_screen_scale=0.85
        )
        self.polhode_trail = Trail(
            scene, "/body/polhode", color=POLHODE_COLOR, chunk_frames=TRAIL_CHUNK_FRAMES, max_chunks=POLHODE_CHUNKS
        )
        self.herpolhode_trail = Trail(
            scene, "/herpolhode", color=HERPOLHODE_COLOR, chunk_frames=TRAIL_CHUNK_FRAMES, max_chunks=HERPOLHODE_CHUNKS
        )

    def update(self) -> None:
        self.body = physics.motion(self.params)
        self.plane_normal, self.plane_distance_rad_s = physics.invariable_plane(self.body)
        semi_axes = physics.energy_ellipsoid_semi_axes_rad_s(self.body)
        self.scale = ELLIPSOID_SIZE / float(semi_axes.max())  # display units per rad/s
        shown_axes = semi_axes * self.scale
        scene = self.client.scene

        # The body: a uniform box with these principal moments, inside its energy ellipsoid.
        sides = physics.uniform_box_sides(self.body.inertia)
        sides = np.maximum(sides, THINNEST_SIDE * sides.max())
        sides *= BOX_FILL / math.sqrt(float(np.sum((0.5 * sides / shown_axes) ** 2)))
        scene.add_box("/body/box", color=(70, 100, 165), dimensions=tuple(sides), flat_shading=True)
        semi_a, semi_b, semi_c = shown_axes
        self.ellipsoid.scale = (float(semi_a), float(semi_b), float(semi_c))
        ends = np.zeros((3, 2, 3), np.float32)
        for k in range(3):
            ends[k, 0, k], ends[k, 1, k] = -1.12 * shown_axes[k], 1.12 * shown_axes[k]
        scene.add_line_segments(
            "/body/axes", ends, np.repeat(AXIS_COLORS[:, None, :], 2, axis=1), thickness=2.0, thickness_units="screen"
        )
        rank = np.argsort(np.argsort(self.body.inertia, kind="stable"), kind="stable")
        for k, label in enumerate(self.axis_labels):
            label.text = f"{k + 1} ({_AXIS_RANK[rank[k]]})"
            label.position = tuple(ends[k, 1] * 1.02)
        family = physics.polhode_family(self.body, loops_per_axis=3)
        segments = (
            np.concatenate([np.stack([c[:-1], c[1:]], axis=1) for c in family]) if family else np.zeros((1, 2, 3))
        )
        scene.add_line_segments(
            "/body/polhode_family",
            (segments * self.scale * ON_ELLIPSOID).astype(np.float32),
            (185, 160, 110),
            thickness=1.0,
            thickness_units="screen",
        )

        # The invariable plane: horizontal (L is along −Z), below the centre by 2T/|L|.
        plane_z = -self.plane_distance_rad_s * self.scale
        reach = float(np.linalg.norm(physics.omega_amplitudes_rad_s(self.body))) * self.scale
        half_width = max(1.1, math.ceil(1.15 * reach / 0.25) * 0.25)
        scene.add_grid(
            "/plane",
            width=2 * half_width,
            height=2 * half_width,
            cell_size=0.1,
            section_size=0.5,
            position=(0.0, 0.0, plane_z),
            plane_color=(215, 228, 245),
            plane_opacity=0.45,
            cell_color=(185, 200, 225),
            section_color=(130, 150, 190),
        )
        self.plane_label.position = (-half_width, -half_width, plane_z)
        arrow_length = -plane_z + 0.4
        self._momentum_segment = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, -arrow_length]], np.float32)
        self.momentum_label.position = (0.03, 0.0, -arrow_length)

        # Clock, closed-form playback, trails and the ghost all start again at t = 0.
        self.frame_index = 0
        self._batch = physics.poinsot_frames(self.body, np.zeros(1))
        self._batch_start = 0
        self._clear_trails()
        # The polhode turns with the body, so a name riding on it would cross the herpolhode's as the body turns. Its
        # name stays in space instead, just outside the ellipsoid on the camera's right, level with the centre: the
        # herpolhode's is on the left and below, on the plane, so the two never meet.
        self.polhode_label.position = tuple(
            (ELLIPSOID_SIZE + 0.08) * POLHODE_LABEL_SIDE / np.linalg.norm(POLHODE_LABEL_SIDE)
        )
        # The herpolhode stays within its largest radius of the foot of L: its label goes just outside, to the viewer's
        # left.
        _, widest = physics.herpolhode_radii_rad_s(self.body)
        self.herpolhode_label.position = tuple(
            (widest * self.scale + 0.06) * HERPOLHODE_LABEL_SIDE + np.array([0.0, 0.0, plane_z])
        )
        self._setup_ghost(sides)
        self._draw_frame(0)

    def _setup_ghost(self, sides: np.ndarray) -> None:
        self.ghost = None
        self.ghost_status = ""
        on = self.params.get("ghost", "off") == "on"
        if on:
            # An outline: lines are drawn with the opaque pass, so the translucent ellipsoid cannot hide them.
            self.client.scene.add_line_segments(
                "/ghost/outline",
                box_edges(1.03 * sides),
                GHOST_COLOR,
                thickness=2.5,
                thickness_units="screen",
            )
            self.ghost = physics.IntegratedTwin(self.body, frame_dt_s=FRAME_DT_S)
            self.ghost_frame.wxyz = self.body.q0
        self.ghost_frame.visible = on

    def _clear_trails(self) -> None:
        self.polhode_trail.clear()
        self.herpolhode_trail.clear()

    # -- animation -----------------------------------------------------------------------------
    @property
    def t_s(self) -> float:
        """Simulated time (s): a whole number of frames (a time set between frames snaps to the nearest)."""
        return self.frame_index * FRAME_DT_S

    @t_s.setter
    def t_s(self, value: float) -> None:
        self.frame_index = round(value / FRAME_DT_S)

    def _state(self, index: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(q_world_body, ω body, ω world) at frame ``index``, refilling the closed-form batch as needed."""
        offset = index - self._batch_start
        if not 0 <= offset < len(self._batch.t_s):
            self._batch_start = index
            self._batch = physics.poinsot_frames(self.body, FRAME_DT_S * np.arange(index, index + BATCH_FRAMES))
            offset = 0
        return self._batch.q_world_body[offset], self._batch.omega_body[offset], self._batch.omega_world[offset]

    def _draw_frame(self, index: int) -> None:
        q, omega_body, omega_world = self._state(index)
        tip = omega_world * self.scale
        self.body_frame.wxyz = q
        self.arrows.points = np.stack([self._momentum_segment, np.array([[0.0, 0.0, 0.0], tip], np.float32)])
        self.contact.position = tuple(tip)
        # ω_body is periodic: after one period (and a chunk of overlap) the polhode only retraces itself.
        polhode_done = (
            math.isfinite(self.body.period_s) and self.t_s > self.body.period_s + 2 * TRAIL_CHUNK_FRAMES * FRAME_DT_S
        )
        if not polhode_done:
            self.polhode_trail.add(omega_body * self.scale * ON_ELLIPSOID)
        self.herpolhode_trail.add(tip + np.array([0.0, 0.0, ABOVE_PLANE]))

    def step_motion(self, dt_s: float) -> bool:
        """One frame of 1/30 s of motion (the closed form is exact at any t; the ghost steps with it)."""
        self.frame_index += 1
        if self.ghost is not None and not self.ghost_status and not self.ghost.advance():
            self.ghost_status = self.ghost.run.message
        return True

    def redraw(self) -> None:
        self._draw_frame(self.frame_index)
        if self.ghost is not None and not self.ghost_status:
            self.ghost_frame.wxyz = self.ghost.q_world_body

    def motion_state(self) -> dict[str, Any]:
        """``{"t_s"}``, and with the ghost on its integrated state ``ghost_y`` (quaternion wxyz, ω body rad/s)."""
        motion: dict[str, Any] = {"t_s": float(self.t_s)}
        if self.ghost is not None:
            motion["ghost_y"] = [float(v) for v in self.ghost.run.y]
        return motion

    def resume_from(self, motion: Mapping[str, Any]) -> None:
        ghost_y = None
        if self.ghost is not None:
            ghost_y = np.array(motion.get("ghost_y", []) if isinstance(motion, Mapping) else [], dtype=float)
            if ghost_y.shape != self.ghost.run.y.shape or not np.all(np.isfinite(ghost_y)):
                raise ValueError(f"motion: ghost_y must be the ghost's {self.ghost.run.y.size} finite state numbers")
        super().resume_from(motion)
        if self.ghost is not None:
            assert ghost_y is not None  # read above, where there was a ghost
            old = self.ghost.run
            self.ghost.run = LiveRun(old.system, old.integrator, ghost_y)
            self.ghost.run.t_s = self.t_s
            self.ghost_status = ""

    # -- numbers beside the scene --------------------------------------------------------------
    def ghost_attitude_difference_rad(self) -> float:
        """Angle (rad) between the ghost's attitude and the closed form's at the ghost's time."""
        ghost = self.ghost
        assert ghost is not None  # asked only while a ghost runs
        exact = self.body.quaternion(np.array([ghost.t_s]))[0]
        return float(physics.attitude_difference_rad(exact, ghost.q_world_body))

    def readout(self) -> Readout:
        body = self.body
        inertia = body.inertia
        mid = body.intermediate_axis
        quantities = [
            Quantity("t_s", "time t", self.t_s, "s"),
            Quantity("energy", "kinetic energy T", body.energy_J, "J"),
            Quantity("angular_momentum", "|L|", body.angular_momentum_norm, "kg·m²/s"),
            Quantity("plane_distance", "plane distance 2T/|L|", self.plane_distance_rad_s, "rad/s"),
            Quantity.or_text(
                "period",
                "period of ω",
                body.period_s,
                "s",
                "none: ω is constant" if body.kind == "steady" else "infinite (separatrix)",
            ),
            Quantity.word(
                "intermediate_axis", "intermediate axis", f"{mid + 1} (I{mid + 1} = {inertia[mid]:.4g} kg·m²)"
            ),
        ]
        if body.circled_axis is not None:
            rank = "largest" if inertia[body.circled_axis] == inertia.max() else "smallest"
            quantities.append(
                Quantity.word("circled_axis", "polhode circles", f"axis {body.circled_axis + 1} ({rank} I)")
            )
        next_flip = physics.next_flip_s(body, self.t_s)
        quantities.append(
            Quantity.or_text(
                "next_flip",
                "time to next flip",
                None if next_flip is None else next_flip - self.t_s,
                "s",
                "no flips in this motion",
            )
        )
        if self.ghost is not None:
            quantities.append(Quantity.word("ghost_method", "ghost integrator", self.ghost.description))
            quantities.append(
                Quantity(
                    "ghost_attitude_difference",
                    "ghost vs closed form, attitude",
                    self.ghost_attitude_difference_rad(),
                    "rad",
                )
            )
        return Readout(quantities, marks=self._triangle_marks(), message=self._message(next_flip))

    def _triangle_marks(self) -> dict[str, list[Mark]]:
        """On each moment's slider, the largest value the triangle inequality allows."""
        values = [float(self.params[name]) for name in physics.INERTIA_NAMES]
        marks = {}
        for k, name in enumerate(physics.INERTIA_NAMES):
            others = [j for j in range(3) if j != k]
            marks[name] = [Mark(values[others[0]] + values[others[1]], f"I{others[0] + 1}+I{others[1] + 1}")]
        return marks

    def _message(self, next_flip: float | None) -> str:
        body = self.body
        if self.ghost_status:
            return f"Ghost stopped: {self.ghost_status}"
        if body.kind == "steady":
            return (
                "Steady rotation about a principal axis: ω and L are parallel, the polhode and herpolhode are "
                "single points."
            )
        if body.kind == "separatrix":
            return "Exactly on the separatrix: ω creeps towards the intermediate axis and never quite arrives."
        if next_flip is not None:
            return (
                f"Intermediate-axis tumble: axis {body.intermediate_axis + 1} turns over every "
                f"{0.5 * body.period_s:.3g} s "
                "while |L| and T stay fixed."
            )
        if body.circled_axis is not None:
            return f"The polhode circles axis {body.circled_axis + 1}: a bounded wobble, stable for all time."
        return ""
