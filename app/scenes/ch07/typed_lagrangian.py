"""Scene: a Lagrangian the student types, run live; each coordinate a dial, the state a point in configuration space.

Drawn in display units in the world xz plane (x right, z up), seen from −y.
Left: one dial per coordinate, side by side: a ring, a hub and a rod at the
angle q_i from the downward vertical (a length coordinate turns the rod by
its value in metres, read as radians). Right: a box of configuration space —
for one coordinate the phase plane (q1 across, q̇1 up), for two (q1 across,
q2 up), for three a cube (q1 across, q2 in depth, q3 up) — where the state's
point (orange) moves and leaves a short trail. Each axis spans ±its range
(shown on the box); when the point leaves the box the range doubles and the
trail starts again.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, cast

import numpy as np
import viser

from app.physics.mechanics.typed import COORDINATE_NAMES
from app.physics.systems.ch07.typed_lagrangian_model import (
    DEFAULT_KINETIC_ENERGY,
    DEFAULT_PARAMETERS,
    DEFAULT_POTENTIAL_ENERGY,
    TypedLagrangianMotion,
    initial_state,
)
from app.scenes.kit import LabelAnchor, Preset, Quantity, Readout, Trail, circle_segments, move_node, update_node
from app.scenes.kit.derived_system_scene import DerivedSystemScene

DIAL_RADIUS = 0.45
DIAL_SPACING = 1.1
BOX_CENTER = np.array([3.75, 0.0, 0.0])
BOX_HALF = 0.8
DIAL_COLORS = np.array([[40, 100, 220], [40, 150, 70], [170, 60, 170]], np.uint8)
TRAIL_CHUNK_FRAMES = 5
TRAIL_CHUNKS = 24  # 4 s of trail at 30 Hz
#: A new axis range is at least this (rad, m or rad/s), and starts this many times the initial value.
MIN_RANGE, RANGE_MARGIN = 1.0, 1.5


def typed_values(kinetic_energy: str, potential_energy: str, constants: str, q0: list[float], qd0: list[float]) -> dict:
    """A preset's values: T, V and constants as typed, q₀ and q̇₀ (their length is the number of coordinates)."""
    n = len(q0)
    pad = [0.0] * (3 - n)
    return {
        "coordinates": n,
        "kinetic_energy": kinetic_energy,
        "potential_energy": potential_energy,
        "parameters": constants,
        "q0_rad": [*q0, *pad],
        "qd0_rad_s": [*qd0, *pad],
    }


PENDULUM = typed_values("m*l^2*q1d^2/2", "-m*g*l*cos(q1)", "m = 1, l = 1, g = 9.81", [1.0], [0.0])
DOUBLE_PENDULUM = typed_values(
    DEFAULT_KINETIC_ENERGY, DEFAULT_POTENTIAL_ENERGY, DEFAULT_PARAMETERS, [1.0, 0.0], [0.0, 0.0]
)
SPRING_PENDULUM = typed_values(
    "m*(q1d^2 + (l + q1)^2*q2d^2)/2",
    "k*q1^2/2 - m*g*(l + q1)*cos(q2)",
    "m = 1, l = 1, k = 40, g = 9.81",
    [0.1, 0.8],
    [0.0, 0.0],
)
#: Started on the bounded solution q1 = g/(2w²) sin wt: q1 = 0, q̇1 = g/(2w) = 2.4525 m/s.
SPUN_WIRE = typed_values("m*(q1d^2 + w^2*q1^2)/2", "m*g*q1*sin(w*t)", "m = 1, w = 2, g = 9.81", [0.0], [2.4525])
LISSAJOUS = typed_values(
    "m*(q1d^2 + q2d^2 + q3d^2)/2",
    "(k1*q1^2 + k2*q2^2 + k3*q3^2)/2",
    "m = 1, k1 = 1, k2 = 4, k3 = 9",
    [1.0, 0.5, 0.3],
    [0.0, 0.5, 0.0],
)


def box_edges(dimensions: int) -> np.ndarray:
    """(S, 2, 3) float32 edges of the configuration box: a square in xz for 1–2 dimensions, a cube for 3."""
    corners = [(-1, -1), (1, -1), (1, 1), (-1, 1)]
    if dimensions < 3:
        square = [(BOX_CENTER + BOX_HALF * np.array([a, 0.0, b])) for a, b in corners]
        return np.array([[square[k], square[(k + 1) % 4]] for k in range(4)], np.float32)
    edges = []
    for depth in (-1.0, 1.0):
        face = [BOX_CENTER + BOX_HALF * np.array([a, depth, b]) for a, b in corners]
        edges += [[face[k], face[(k + 1) % 4]] for k in range(4)]
    for a, b in corners:
        edges.append([BOX_CENTER + BOX_HALF * np.array([a, -1.0, b]), BOX_CENTER + BOX_HALF * np.array([a, 1.0, b])])
    return np.array(edges, np.float32)


def dial_center(index: int) -> np.ndarray:
    return np.array([index * DIAL_SPACING, 0.0, 0.0])


class TypedLagrangianScene(DerivedSystemScene):
    id = "typed-lagrangian"
    #: The rods and the state's point each frame; a trail chunk every 5th frame.
    frame_message_budget = 3.0
    title = "A Lagrangian you type: its equations derived, then run live"
    chapter = 7
    model = TypedLagrangianMotion
    run_model: TypedLagrangianMotion
    camera_position = (2.1, -4.4, 1.0)
    camera_look_at = (2.1, 0.0, -0.05)
    presets = (
        Preset("pendulum", "Pendulum", PENDULUM, "T = ½ m l² q̇₁², V = −m g l cos q₁: expect m l² q̈₁ = −m g l sin q₁."),
        Preset(
            "double-pendulum",
            "Double pendulum",
            DOUBLE_PENDULUM,
            "Two equal bobs on equal rods: the catalogue's double pendulum with m₁ = m₂ = m and l₁ = l₂ = l.",
        ),
        Preset(
            "spring-pendulum",
            "Spring pendulum",
            SPRING_PENDULUM,
            "q₁ = stretch (m), q₂ = angle: the spring and the swing trade energy; T + V stays put.",
        ),
        Preset(
            "spun-wire",
            "Bead on a spun wire (t explicit)",
            SPUN_WIRE,
            "A wire turning at w in a vertical plane: V holds t, so the energy is not conserved. Started on the "
            "bounded "
            "solution q₁ = g/(2w²) sin wt, rounding slowly throws the bead off it.",
        ),
        Preset(
            "lissajous",
            "Three springs (3 coordinates)",
            LISSAJOUS,
            "Three independent oscillators at 1, 2 and 3 rad/s: the point draws a Lissajous curve in the cube.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.rods: viser.LineSegmentsHandle | None = None  # drawn by _draw_fixed: one segment per coordinate
        self.state_point = scene.add_icosphere("/box/state", radius=0.045, color=(235, 120, 20))
        self.trail = Trail(
            scene, "/box/trail", color=(235, 120, 20), chunk_frames=TRAIL_CHUNK_FRAMES, max_chunks=TRAIL_CHUNKS
        )
        self._fixed: list = []
        self._range_labels: list = []
        self._dimensions = 0

    def update(self) -> None:
        self.restart()
        n = int(self.params["coordinates"])
        start = initial_state(self.physical_params())
        box_values = start if n == 1 else start[:n]
        self._ranges = np.maximum(MIN_RANGE, RANGE_MARGIN * np.abs(box_values))
        if n != self._dimensions:
            self._draw_fixed(n)
        self._label_ranges()
        self.trail.clear()
        self._draw()

    def _draw_fixed(self, n: int) -> None:
        """The dials' rings, hubs and names and the configuration box for ``n`` coordinates."""
        scene = self.client.scene
        for handle in self._fixed:
            handle.remove()
        rings = np.concatenate(
            [
                circle_segments(radius=DIAL_RADIUS, center=dial_center(i), normal=(0.0, 1.0, 0.0), segments=64)
                for i in range(n)
            ]
        )
        if self.rods is not None:
            self.rods.remove()
        colors = np.repeat(DIAL_COLORS[:n, None, :], 2, axis=1)
        self.rods = scene.add_line_segments("/rods", np.zeros((n, 2, 3), np.float32), colors, thickness=0.03)
        self._fixed = [
            scene.add_line_segments("/dials/rings", rings, (150, 150, 150), thickness=1.5, thickness_units="screen"),
            scene.add_point_cloud(
                "/dials/hubs",
                np.array([dial_center(i) for i in range(n)], np.float32),
                (40, 40, 40),
                point_size=0.07,
                point_shape="circle",
            ),
            scene.add_line_segments(
                "/box/edges", box_edges(n), (120, 120, 120), thickness=1.5, thickness_units="screen"
            ),
        ]
        for i in range(n):
            label = scene.add_label(f"/dials/name{i}", COORDINATE_NAMES[i], anchor="top-center")
            label.position = dial_center(i) + np.array([0.0, 0.0, -DIAL_RADIUS - 0.08])
            self._fixed.append(label)
        title = "phase plane (q1, q1d)" if n == 1 else "configuration space (" + ", ".join(COORDINATE_NAMES[:n]) + ")"
        heading = scene.add_label("/box/title", title, anchor="bottom-center")
        heading.position = BOX_CENTER + np.array([0.0, 0.0, BOX_HALF + 0.1])
        self._fixed.append(heading)
        axes = ["q1", "q1d"] if n == 1 else list(COORDINATE_NAMES[:n])
        places = [
            np.array([0.0, -BOX_HALF if n == 3 else 0.0, -BOX_HALF - 0.08]),
            np.array([-BOX_HALF - 0.08, 0.0, 0.0]),
        ]
        if n == 3:
            places = [
                places[0],
                np.array([BOX_HALF + 0.08, 0.0, -BOX_HALF]),
                np.array([-BOX_HALF - 0.08, -BOX_HALF, 0.0]),
            ]
        anchors: list[LabelAnchor] = ["top-center", "center-left" if n == 3 else "center-right", "center-right"]
        self._range_labels = []
        for k, (axis, place) in enumerate(zip(axes, places, strict=True)):
            label = scene.add_label(f"/box/axis{k}", axis, anchor=anchors[k])
            label.position = BOX_CENTER + place
            self._range_labels.append(label)
        self._fixed += self._range_labels
        self._dimensions = n

    def _label_ranges(self) -> None:
        n = int(self.params["coordinates"])
        names = ["q1", "q1d"] if n == 1 else list(COORDINATE_NAMES[:n])
        for label, name, span in zip(self._range_labels, names, self._ranges, strict=True):
            update_node(label, text=f"{name}: ±{span:.3g}")

    def _rod_segments(self) -> np.ndarray:
        n = int(self.params["coordinates"])
        segments = np.empty((n, 2, 3), np.float32)
        for i in range(n):
            q = float(self.run.y[i])
            center = dial_center(i)
            segments[i] = [center, center + DIAL_RADIUS * np.array([math.sin(q), 0.0, -math.cos(q)])]
        return segments

    def _box_values(self) -> np.ndarray:
        n = int(self.params["coordinates"])
        return self.run.y[:2] if n == 1 else self.run.y[:n]

    def _draw(self) -> None:
        update_node(cast(viser.LineSegmentsHandle, self.rods), points=self._rod_segments())  # drawn by _draw_fixed
        values = self._box_values()
        if np.any(np.abs(values) > self._ranges):
            while np.any(np.abs(values) > self._ranges):
                self._ranges = np.where(np.abs(values) > self._ranges, 2.0 * self._ranges, self._ranges)
            self._label_ranges()
            self.trail.clear()
        scaled = BOX_HALF * values / self._ranges
        offset = np.array([scaled[0], 0.0, scaled[1]]) if len(scaled) == 2 else scaled
        point = BOX_CENTER + offset
        move_node(self.state_point, position=point)
        self.trail.add(point)

    def motion_state(self) -> dict[str, Any]:
        """The run's ``t_s`` and ``y``, and ``box_ranges``: the box's half-widths per axis (coordinate units),
        which double whenever the motion leaves the box."""
        return super().motion_state() | {"box_ranges": [float(v) for v in self._ranges]}

    def resume_from(self, motion: Mapping[str, Any]) -> None:
        try:
            ranges = np.array(motion["box_ranges"], dtype=float)
        except (KeyError, TypeError, ValueError):
            raise ValueError("motion: needs box_ranges (the box's half-widths)") from None
        if ranges.shape != self._ranges.shape or not np.all(np.isfinite(ranges)) or not np.all(ranges > 0.0):
            raise ValueError(f"motion: box_ranges must be {self._ranges.size} finite positive numbers")
        super().resume_from(motion)
        self._ranges = ranges

    def redraw(self) -> None:
        self._label_ranges()
        self._draw()

    def derivation_status(self) -> str:
        prepared = self.run_model.prepared(self.physical_params())
        derived_text = (
            "from the derivation cache" if prepared.cached else f"derived by sympy in {prepared.derive_s:.2f} s"
        )
        return (
            f"Lagrange's equations {derived_text}, in a bounded process; compiled by numba in "
            f"{prepared.compile_s:.2f} s"
        )

    def readout(self) -> Readout:
        params = self.physical_params()
        model = self.run_model
        prepared = model.prepared(params)
        n = len(prepared.system.coordinates)
        y, t_s = self.run.y, self.run.t_s
        kinetic, potential, jacobi = (
            float(v[0]) for v in model.energies_and_jacobi_J(params, np.array([t_s]), y[None, :])
        )
        quantities = [Quantity("t_s", "time t", t_s, "s")]
        for i, coordinate in enumerate(prepared.system.coordinates):
            quantities.append(
                Quantity(f"{coordinate.name}_rad", f"coordinate {coordinate.name}", float(y[i]), coordinate.unit)
            )
            quantities.append(
                Quantity(
                    f"{coordinate.name}_rate_rad_s", f"rate {coordinate.name}d", float(y[n + i]), coordinate.rate_unit
                )
            )
        quantities += [
            Quantity("kinetic_energy_J", "kinetic energy T", kinetic, "J"),
            Quantity("potential_energy_J", "potential energy V", potential, "J"),
            Quantity("energy_J", "T + V", kinetic + potential, "J"),
            Quantity("jacobi_integral_J", "energy function h = Σ q̇ ∂L/∂q̇ − L", jacobi, "J"),
            self._drift_row(prepared.explicit_time, abs(jacobi - kinetic - potential) <= 1e-9 * max(abs(jacobi), 1.0)),
            Quantity.word("derivation", "derivation", self.derivation_status()),
        ]
        equations = "".join(f"$${latex}$$" for latex in prepared.derived.equations_latex)
        return Readout(
            quantities, message=self.status or f"Lagrange's equations, derived from what you typed:{equations}"
        )

    def _drift_row(self, explicit_time: bool, h_is_energy: bool) -> Quantity:
        if explicit_time:
            return Quantity.word(
                "energy_drift",
                "energy",
                "not conserved: t appears explicitly in T or V, so neither T + V nor h stays constant",
            )
        label = (
            "drift of T + V (= h here) |Δh| / scale"
            if h_is_energy
            else "drift of h (T + V is not conserved: T has terms not quadratic in the rates)"
        )
        return self.drift_quantity("jacobi_integral", label)
