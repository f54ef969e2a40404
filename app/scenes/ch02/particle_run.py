"""The shared frame of chapter 2's particle scenes: a particle replayed along a closed-form run, with arrows.

A :class:`ParticleRunScene` draws its path once per parameter change (a grey
polyline over one run, a ground grid under it, short world axes), puts a ball
at the particle and a fixed set of arrows from it (one batched node, so a frame
updates one node however many arrows there are), plus a label at the tip of
each arrow listed in :attr:`ParticleRunScene.labelled_arrows`. The clock only
grows (so the recent motion can be scrubbed); the instant drawn is the clock
modulo the run's duration, so the motion starts again at the end of each run,
and the readout's ``t_s`` is the time within the run, the t of the formulas.

Drawn in metres on XYZ, +Z up. Subclasses give the run (:meth:`run_s`,
:meth:`path_points`) and, for each instant, the arrows (:meth:`arrows_at`).
"""

from __future__ import annotations

import math
from typing import ClassVar

import numpy as np

from app.scenes.kit import Scene, arrow_segments, move_node, update_node

PATH_SAMPLES = 600
PATH_COLOR = (120, 120, 140)


def nice_step(length_m: float) -> float:
    """1, 2 or 5 × 10^k m just below ``length_m``."""
    power = 10.0 ** math.floor(math.log10(length_m))
    return max(m * power for m in (1.0, 2.0, 5.0) if m * power <= length_m)


def display_scale(magnitudes: np.ndarray, *, target_m: float) -> float:
    """Metres of arrow per unit of a vector, so the 90th percentile of ``magnitudes`` is drawn ``target_m`` long
    (the percentile, so that one spike does not shrink every other arrow); 0 where they are all zero."""
    finite = magnitudes[np.isfinite(magnitudes)]
    typical = float(np.percentile(finite, 90)) if finite.size else 0.0
    return target_m / typical if typical > 1e-12 else 0.0


class ParticleRunScene(Scene):
    """A particle on a closed-form run, its path, and arrows drawn from it (see the module docstring)."""

    animated = True
    #: (RGB) colour of each arrow, in the order :meth:`arrows_at` gives them.
    arrow_colors: ClassVar[tuple[tuple[int, int, int], ...]] = ()
    #: Index, text and place (0 tail … 1 tip) of the arrows that carry a label.
    labelled_arrows: ClassVar[tuple[tuple[int, str, float], ...]] = ()
    frame_message_budget = 6.0
    #: The motion is the growing clock; the readout's ``t_s`` is that clock modulo a run.
    motion_attributes = {"t_s": "clock_s"}

    # -- what a subclass gives ------------------------------------------------------------
    def run_s(self) -> float:
        """Duration (s) of one run (after it the motion starts again)."""
        raise NotImplementedError

    def path_points(self) -> np.ndarray:
        """(N, 3) points (m) of the path over one run, drawn as a polyline."""
        raise NotImplementedError

    def prepare(self) -> None:
        """Recompute what depends on the parameters (called before the path is drawn)."""

    def arrows_at(self, t_s: float) -> tuple[np.ndarray, np.ndarray]:
        """Particle position (3,) in m and the arrows from it, (len(arrow_colors), 2, 3) display points in m."""
        raise NotImplementedError

    def after_draw(self, t_s: float) -> None:
        """Per-frame extras (e.g. a triad's attitude) after the particle and arrows moved."""

    # -- building and drawing (the base class steps, scrubs and restarts the motion through ``clock_s``) ------
    def build(self) -> None:
        scene = self.client.scene
        self.clock_s = 0.0
        self.t_s = 0.0
        self._center, self._size = np.zeros(3), 2.0
        self._static: list = []
        self._built = self._reframe_pending = False  # the first drawing is framed by the initial camera
        self.particle = scene.add_frame("/particle", show_axes=False)
        self.ball = scene.add_icosphere("/particle/ball", radius=1.0, color=(30, 30, 30))
        count = len(self.arrow_colors)
        self.arrows = scene.add_arrows(
            "/arrows", np.zeros((count, 2, 3), np.float32), np.array(self.arrow_colors, np.uint8)
        )
        self.arrow_labels = [
            scene.add_label(f"/arrow_labels/{k}", text, anchor="bottom-left", font_screen_scale=0.9)
            for k, text, _ in self.labelled_arrows
        ]

    def update(self) -> None:
        self.prepare()
        points = self.path_points()
        low, high = points.min(axis=0), points.max(axis=0)
        old_center, old_size = self._center, self._size
        self._center = 0.5 * (low + high)
        self._size = max(float(np.linalg.norm(high - low)), 0.5)
        moved = (
            not 0.8 < self._size / old_size < 1.25 or float(np.linalg.norm(self._center - old_center)) > 0.2 * old_size
        )
        reframe = self._built and moved
        self._built = True
        self._draw_static(points, ground_z=float(low[2]))
        self.clock_s = 0.0
        self._draw()
        self._reframe_pending = reframe  # moved on the next drawing, not with this change's initial camera

    def _draw_static(self, points: np.ndarray, *, ground_z: float) -> None:
        scene = self.client.scene
        for node in reversed(self._static):  # children (labels) before their parents
            node.remove()
        size, center = self._size, self._center
        segments = np.stack([points[:-1], points[1:]], axis=1).astype(np.float32)
        self.grid_cell_m = nice_step(size / 8.0)
        width = 2.0 * self.grid_cell_m * math.ceil(0.75 * size / self.grid_cell_m)
        axes = 0.2 * size
        self._static = [
            scene.add_line_segments("/path", segments, PATH_COLOR, thickness=2.0, thickness_units="screen"),
            scene.add_grid(
                "/ground",
                width=width,
                height=width,
                cell_size=self.grid_cell_m,
                section_size=5 * self.grid_cell_m,
                position=(float(center[0]), float(center[1]), ground_z - 0.003 * size),
            ),  # just under a path in the floor
            scene.add_frame("/world_axes", axes_length=axes, axes_radius=0.005 * size),
            *(
                scene.add_label(
                    f"/world_axes/{name}", name, position=tuple(1.08 * axes * np.eye(3)[k]), font_screen_scale=0.8
                )
                for k, name in enumerate("XYZ")
            ),
        ]
        self.ball.scale = 0.02 * size
        shaft = 0.009 * size
        self.arrows.shaft_radius, self.arrows.head_radius, self.arrows.head_length = shaft, 2.5 * shaft, 6.0 * shaft

    @property
    def drawing_size_m(self) -> float:
        """The path's size (m): the diagonal of its bounding box (at least 0.5 m)."""
        return self._size

    def camera_view(self) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        c, size = self._center, self._size
        return (float(c[0] + 0.38 * size), float(c[1] - 0.6 * size), float(c[2] + 0.36 * size)), (
            float(c[0]),
            float(c[1]),
            float(c[2]),
        )

    def _draw(self) -> None:
        if self._reframe_pending:
            self._reframe()
        self.t_s = self.clock_s % self.run_s()
        position, arrows = self.arrows_at(self.t_s)
        move_node(self.particle, position=position)
        update_node(self.arrows, points=arrows.astype(np.float32))
        for label, (k, _, place) in zip(self.arrow_labels, self.labelled_arrows):
            move_node(label, position=(1.0 - place) * arrows[k, 0] + place * arrows[k, 1])
        self.after_draw(self.t_s)

    def _reframe(self) -> None:
        """Move this viewer's camera onto a path that is now a different size or elsewhere.

        Done on the first drawing after the parameter change that queued it (viser coalesces camera messages by
        type, so a move queued with the new initial camera would replace it); a new unit vector or rate leaves the
        student's camera alone.
        """
        self._reframe_pending = False
        position, look_at = self.camera_view()
        self.client.camera.position = position
        self.client.camera.look_at = look_at

    def step_motion(self, dt_s: float) -> bool:
        """The clock only grows (so the scrubber's history is one run after another); :meth:`_draw` takes it modulo a
        run."""
        self.clock_s += dt_s
        return True


def chain_arrows(position: np.ndarray, vector: np.ndarray, parts: np.ndarray, scale: float) -> np.ndarray:
    """The arrow of ``vector`` from ``position`` followed by its ``parts`` (K, 3) laid head to tail (so they visibly
    sum to it): (1 + K, 2, 3) display points (m), lengths × ``scale``."""
    tails = position + scale * np.concatenate([[np.zeros(3)], np.cumsum(parts, axis=0)[:-1]])
    return np.concatenate([arrow_segments(position, vector, scale), arrow_segments(tails, parts, scale)])
