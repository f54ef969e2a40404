"""Scene: Euler's theorem — a sequence of three turns ends where one turn about one axis ends.

The attitude A is set like the rotation-sequence scene (same controls). The body (a flat box with
its own axes, red/green/blue for x/y/z) sweeps from the fixed frame's attitude to A by the single
equivalent turn, about the orange axis n through the fixed point; the tip of its x axis traces the
arc of that turn, and a faint ghost holds the final attitude. With a second turn B (β ≠ 0, about a
fixed axis) two copies are drawn side by side: on the left A then B, on the right B then A, each
sweeping its two turns in order; they end in different attitudes unless the turns share an axis.

Display units: the fixed axes are 1.2 long, the body's 0.7. The sweep is a drawing device; every
number in the readout is from :mod:`app.physics.systems.ch03.finite_rotation`.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.core.parameters import Parameter
from app.physics.math.rotations import matrix_from_axis_angle, quaternion_from_axis_angle, quaternion_multiply
from app.physics.systems.ch03 import finite_rotation as physics
from app.scenes.ch03.labelled_axes import add_labelled_axes, components_text
from app.scenes.ch03.rotation_sequence import CONTROLS as SEQUENCE_CONTROLS
from app.scenes.kit import Preset, Quantity, Readout, Scene

CONTROLS = (
    *(p for p in SEQUENCE_CONTROLS if p.name != "stage"),
    Parameter(
        "second_axis",
        "",
        "Z",
        kind="choice",
        choices=physics.FIXED_AXES,
        label="B about",
        description="Fixed axis of the second turn B",
    ),
    Parameter(
        "second_angle_deg",
        "deg",
        0.0,
        -180.0,
        180.0,
        label="β",
        step=1.0,
        description="Angle of the second turn B about its fixed axis (0: no second turn, Euler's theorem alone)",
    ),
)

BODY_AXIS_LENGTH = 0.7
FIXED_AXIS_LENGTH = 1.2
EQUIVALENT_AXIS_HALF_LENGTH = 1.4
BODY_DIMENSIONS = (0.8, 0.5, 0.12)
AXIS_A_COLOR, AXIS_B_COLOR = (240, 140, 20), (190, 60, 200)
BODY_COLOR = (90, 120, 170)
#: Where the two copies stand when B is shown: ∓ this, across the initial view (A then B on the left, B then A on the
#: right).
ORDER_OFFSET = np.array([0.95, 0.7, 0.0])
ARC_SAMPLES = 48
# Animation (s): rest, first turn, pause, second turn, hold. A drawing device only.
REST_S, SWEEP_S, PAUSE_S, HOLD_S = 0.6, 2.5, 0.4, 2.0
CYCLE_S = REST_S + SWEEP_S + PAUSE_S + SWEEP_S + HOLD_S
#: Below this equivalent angle (rad) there is no turn and no axis to speak of.
NO_TURN_RAD = 1e-9


def sweep_fractions(t_s: float) -> tuple[float, float]:
    """Eased fractions (0–1) of the first and second turns done at ``t_s`` into the loop."""
    t = t_s % CYCLE_S

    def ease(x: float) -> float:
        x = min(max(x, 0.0), 1.0)
        return x * x * (3.0 - 2.0 * x)

    return ease((t - REST_S) / SWEEP_S), ease((t - REST_S - SWEEP_S - PAUSE_S) / SWEEP_S)


class FiniteRotationScene(Scene):
    id = "finite-rotation"
    title = "Finite rotations: Euler's theorem and the order of turns"
    chapter = 3
    controls = CONTROLS
    animated = True
    #: Up to two bodies turning and two arcs growing: four messages a frame at most.
    frame_message_budget = 4.0
    camera_position = (1.7, -2.3, 1.45)
    camera_look_at = (0.0, 0.0, 0.0)
    presets = (
        Preset(
            "classic-euler",
            "Three turns, one axis (3-1-3)",
            {"sequence": "3-1-3", "angle1_deg": 80.0, "angle2_deg": 35.0, "angle3_deg": 60.0, "second_angle_deg": 0.0},
            "Precession 80°, nutation 35°, spin 60°: the same attitude as one turn of 141.92° about n",
        ),
        Preset(
            "quarter-turns",
            "Quarter turns do not commute",
            {
                "sequence": "1-2-3",
                "angle1_deg": 90.0,
                "angle2_deg": 0.0,
                "angle3_deg": 0.0,
                "second_axis": "Z",
                "second_angle_deg": 90.0,
            },
            "A = 90° about X, B = 90° about Z: A then B and B then A are both 120° turns, about different axes",
        ),
        Preset(
            "same-axis",
            "Turns about one axis commute",
            {
                "sequence": "3-2-1",
                "angle1_deg": 50.0,
                "angle2_deg": 0.0,
                "angle3_deg": 0.0,
                "second_axis": "Z",
                "second_angle_deg": 70.0,
            },
            "A and B both about Z: the order does not matter, the angles just add",
        ),
        Preset(
            "small-turns",
            "Small turns nearly commute",
            {
                "sequence": "1-2-3",
                "angle1_deg": 5.0,
                "angle2_deg": 0.0,
                "angle3_deg": 0.0,
                "second_axis": "Z",
                "second_angle_deg": 5.0,
            },
            "5° about X and 5° about Z: the orders differ by only about 0.44°, the product of the two angles",
        ),
    )

    def camera_view(self):
        """Closer for one body, farther back when the two orders stand side by side."""
        if getattr(self, "compare", False):
            return (2.3, -3.1, 1.9), (0.0, 0.0, -0.1)
        return self.camera_position, self.camera_look_at

    # -- building -----------------------------------------------------------------------------------
    def build(self) -> None:
        scene = self.client.scene
        add_labelled_axes(
            scene, "/fixed", length=FIXED_AXIS_LENGTH, labels="XYZ", axes_radius=0.012, origin_radius=0.04
        )
        self.bodies = []
        self.ghosts = []
        for n in range(2):
            body = scene.add_frame(f"/body{n}", axes_length=BODY_AXIS_LENGTH, axes_radius=0.022, origin_radius=0.04)
            scene.add_box(
                f"/body{n}/plate",
                color=BODY_COLOR,
                dimensions=BODY_DIMENSIONS,
                opacity=0.8,
                cast_shadow=False,
                receive_shadow=False,
            )
            ghost = scene.add_frame(f"/ghost{n}", axes_length=BODY_AXIS_LENGTH, axes_radius=0.008, origin_radius=0.01)
            scene.add_box(
                f"/ghost{n}/plate",
                color=BODY_COLOR,
                dimensions=BODY_DIMENSIONS,
                opacity=0.18,
                cast_shadow=False,
                receive_shadow=False,
            )
            self.bodies.append(body)
            self.ghosts.append(ghost)
        self.axes = scene.add_line_segments(
            "/turn_axes", np.zeros((1, 2, 3), np.float32), AXIS_A_COLOR, thickness=4.0, thickness_units="screen"
        )
        self.axis_labels = [scene.add_label(f"/turn_axes/label{n}", "", anchor="bottom-left") for n in range(4)]
        self.arcs = [
            scene.add_line_segments(
                f"/arc{n}", np.zeros((1, 2, 3), np.float32), AXIS_A_COLOR, thickness=3.0, thickness_units="screen"
            )
            for n in range(2)
        ]
        self.order_labels = [
            scene.add_label(f"/order_label{n}", "", anchor="top-center", font_screen_scale=1.2) for n in range(2)
        ]
        self.t_s = 0.0

    # -- parameters → geometry ------------------------------------------------------------------------
    def update(self) -> None:
        angles = np.radians([self.params[f"angle{k}_deg"] for k in (1, 2, 3)])
        self.result = physics.finite_rotation(
            angles,
            self.params["sequence"],
            second_axis=self.params["second_axis"],
            second_angle_rad=math.radians(self.params["second_angle_deg"]),
        )
        self.compare = abs(self.params["second_angle_deg"]) > 0.0
        a = self.result.turn_a
        b_axis = np.eye(3)[physics.fixed_axis_index(self.params["second_axis"])]
        # Each copy: pivot, then its two turns (axis, angle) about fixed lines, in order.
        finals: tuple[physics.EquivalentTurn, ...]
        titles: tuple[str, ...]
        if self.compare:
            self.copies = [
                (-ORDER_OFFSET, [(a.axis_world, a.angle_rad), (b_axis, math.radians(self.params["second_angle_deg"]))]),
                (ORDER_OFFSET, [(b_axis, math.radians(self.params["second_angle_deg"])), (a.axis_world, a.angle_rad)]),
            ]
            finals = (self.result.a_then_b, self.result.b_then_a)
            titles = ("A then B", "B then A")
        else:
            self.copies = [(np.zeros(3), [(a.axis_world, a.angle_rad), (a.axis_world, 0.0)])]
            finals = (a,)
            titles = ("",)
        segments, labels = [], []
        for pivot, turns in self.copies:
            for (axis, angle), name in zip(turns, ("A", "B") if pivot[0] <= 0.0 else ("B", "A")):
                if angle == 0.0 or (name == "A" and a.angle_rad < NO_TURN_RAD):
                    continue
                segments.append(
                    [pivot - EQUIVALENT_AXIS_HALF_LENGTH * axis, pivot + EQUIVALENT_AXIS_HALF_LENGTH * axis]
                )
                labels.append(
                    (
                        pivot + EQUIVALENT_AXIS_HALF_LENGTH * axis,
                        f"{name}: {math.degrees(angle):.4g}° about "
                        f"{'n' if name == 'A' else self.params['second_axis']}",
                    )
                )
        points = np.array(segments, np.float32).reshape(-1, 2, 3) if segments else np.zeros((1, 2, 3), np.float32)
        colors = np.array(
            [AXIS_A_COLOR if text.startswith("A") else AXIS_B_COLOR for _, text in labels] or [AXIS_A_COLOR], np.uint8
        )
        self.axes.points = points
        self.axes.colors = np.repeat(colors[:, None, :], 2, axis=1)
        self.axes.visible = bool(segments)
        for n, label in enumerate(self.axis_labels):
            label.visible = n < len(labels)
            if n < len(labels):
                label.position, label.text = tuple(labels[n][0]), labels[n][1]
        for n in range(2):
            shown = n < len(self.copies)
            for node in (self.bodies[n], self.ghosts[n], self.arcs[n], self.order_labels[n]):
                node.visible = shown
            if shown:
                pivot = self.copies[n][0]
                self.bodies[n].position = tuple(pivot)
                self.ghosts[n].position = tuple(pivot)
                self.ghosts[n].wxyz = tuple(finals[n].q_world_body)
                self.order_labels[n].position = tuple(pivot + np.array([0.0, 0.0, -1.0]))
                self.order_labels[n].text = titles[n]
        self._prepare_arcs()
        self.t_s = 0.0
        self._draw()

    def _prepare_arcs(self) -> None:
        """Per copy, the path of its body-x tip through both turns (ARC_SAMPLES per turn, relative to the pivot)."""
        self._arc_paths = []
        tip = np.array([BODY_AXIS_LENGTH, 0.0, 0.0])
        for _, turns in self.copies:
            paths, R_before = [], np.eye(3)
            for axis, angle in turns:
                fractions = np.linspace(0.0, 1.0, ARC_SAMPLES)
                turning = matrix_from_axis_angle(axis, fractions * angle)
                paths.append(np.einsum("nij,j->ni", turning @ R_before, tip))
                R_before = turning[-1] @ R_before
            self._arc_paths.append(paths)

    def _attitude(self, turns, done: tuple[float, float]) -> np.ndarray:
        """``wxyz`` after the fractions ``done`` of the copy's two turns (about fixed axes: each composes on the
        left)."""
        q = np.array([1.0, 0.0, 0.0, 0.0])
        for (axis, angle), fraction in zip(turns, done):
            q = quaternion_multiply(quaternion_from_axis_angle(axis, fraction * angle), q)
        return q

    def _draw(self) -> None:
        done = sweep_fractions(self.t_s)
        for n, (pivot, turns) in enumerate(self.copies):
            self.bodies[n].wxyz = tuple(self._attitude(turns, done))
            samples = []
            for path, fraction in zip(self._arc_paths[n], done):
                count = int(round(fraction * (ARC_SAMPLES - 1)))
                if count:
                    samples.append(path[: count + 1])
            if samples:
                path = pivot + np.concatenate(samples)
                self.arcs[n].points = np.stack([path[:-1], path[1:]], axis=1).astype(np.float32)
            else:
                self.arcs[n].points = (
                    np.zeros((1, 2, 3), np.float32)
                    + pivot.astype(np.float32)
                    + np.array([BODY_AXIS_LENGTH, 0, 0], np.float32)
                )

    def advance(self, dt_s: float) -> None:
        before = sweep_fractions(self.t_s)
        self.t_s = (self.t_s + dt_s) % CYCLE_S
        if sweep_fractions(self.t_s) != before:  # nothing moves while the body rests or holds
            self._draw()

    # -- numbers beside the scene ---------------------------------------------------------------------
    def readout(self) -> Readout:
        """Axis, matrix rows and the orders' axes are text (XYZ components); angles and quaternion are numbers."""
        r = self.result
        a = r.turn_a
        has_axis = a.angle_rad >= NO_TURN_RAD
        quantities = [
            Quantity.word("sequence", "sequence of A", f"{r.sequence.name} ({r.sequence.kind})"),
            *(
                Quantity(
                    f"R_row{i + 1}",
                    f"[R] row {i + 1} (v_XYZ = [R] v_xyz)",
                    None,
                    "",
                    "  ".join(f"{v:+.4f}" for v in a.R_world_body[i]),
                )
                for i in range(3)
            ),
            *(Quantity(f"q_{c}", f"quaternion {c}", float(v), "") for c, v in zip("wxyz", a.q_world_body)),
            *(
                Quantity.or_text(
                    f"axis_{c}",
                    f"axis n, {c.upper()} component",
                    float(v) if has_axis else None,
                    "",
                    "undefined: no turn",
                )
                for c, v in zip("xyz", a.axis_world)
            ),
            Quantity("rotation_angle_deg", "angle φ of the one turn about n", math.degrees(a.angle_rad), "deg"),
            Quantity(
                "rodrigues_mismatch",
                "largest |[R] from Rodrigues (n, φ) − [R] from the sequence|",
                r.rodrigues_mismatch,
                "",
            ),
        ]
        if self.compare:
            for name, label, turn in (("a_then_b", "A then B", r.a_then_b), ("b_then_a", "B then A", r.b_then_a)):
                quantities.append(
                    Quantity(
                        f"{name}_angle_deg", f"{label}: angle of the one turn", math.degrees(turn.angle_rad), "deg"
                    )
                )
                quantities.append(
                    Quantity(
                        f"{name}_axis", f"{label}: its axis (X, Y, Z)", None, "", components_text(turn.axis_world, 4)
                    )
                )
            quantities.append(
                Quantity("order_gap_deg", "turn between the two results", math.degrees(r.order_gap_rad), "deg")
            )
        quantities.append(Quantity("t_s", "time into the animation loop", self.t_s, "s"))
        return Readout(quantities, message=self.message())

    def message(self) -> str:
        r, a = self.result, self.result.turn_a
        if a.angle_rad < NO_TURN_RAD:
            text = "A is no turn at all: the body stays as the fixed frame, and the axis n is undefined."
        else:
            text = (
                f"Euler's theorem: the {r.sequence.name} turns end where one turn of φ = "
                f"{math.degrees(a.angle_rad):.2f}° "
                f"about n = {components_text(a.axis_world, 4)} ends; Rodrigues' formula with that n and φ gives "
                "[R] again."
            )
        if self.compare:
            gap = math.degrees(r.order_gap_rad)
            if gap < 1e-7:
                text += (
                    " A then B and B then A end in the same attitude: these two turns commute (they share an "
                    "axis, or one is no turn)."
                )
            else:
                text += f" A then B and B then A end {gap:.4g}° apart: finite rotations do not commute."
        return text
