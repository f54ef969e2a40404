"""Scene: a rotation sequence applied one turn at a time, with every intermediate frame drawn.

Frames (all through the origin, axes red/green/blue for x/y/z): the fixed frame
``XYZ`` (longest axes), ``x′y′z′`` after the first turn, ``x″y″z″`` after the
second, and the body frame ``xyz`` after the third (shortest axes, carrying a
translucent plate). Each turn's axis is an arrow in its own colour, labelled with
its angle, and the tip of one axis of the turning frame leaves an arc showing
the angle swept. In gimbal lock the first and third turn axes turn red.

Axis names sit at the axis tips; frames share the axis of the turn between
them, and an axis can point at the camera, so tips of different axes often
meet on the screen. Each frame drawn, every name's text is put on the side of
its tip (above or below, left or right) where, in the default view, it covers
no other name (:func:`label_anchors`).

Display units: the fixed axes are 1.3 units long. The animation (apply θ1, then
θ2, then θ3, hold, repeat) is a drawing device, not a model in time: every
number in the readout is for the complete sequence and comes from
:mod:`app.physics.math.rotations`.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.core.parameters import Parameter
from app.physics.math.rotations import (
    SEQUENCES,
    angle_rate_matrix_body,
    angles_from_matrix,
    axis_angle_from_quaternion,
    intermediate_frames,
    quaternion_multiply,
    rotate_vector,
    rotation_sequence,
)
from app.scenes.kit import LabelAnchor, Mark, Preset, Quantity, Readout, Scene

STAGES = ("animate", "after turn 1", "after turn 2", "after turn 3")
NEAR_LOCK_DEG = 10.0

CONTROLS = (
    Parameter(
        "sequence",
        "",
        "3-1-3",
        kind="choice",
        choices=tuple(SEQUENCES),
        label="Sequence",
        description=(
            "Axes of the three body-fixed turns (1 = x, 2 = y, 3 = z): proper Euler (first axis "
            "repeated) or Tait–Bryan (all three)"
        ),
    ),
    Parameter(
        "angle1_deg",
        "deg",
        80.0,
        -180.0,
        180.0,
        label="θ1",
        step=1.0,
        description="First turn, about axis a1 of the fixed frame XYZ",
    ),
    Parameter(
        "angle2_deg",
        "deg",
        35.0,
        -180.0,
        180.0,
        label="θ2",
        step=1.0,
        description="Second turn, about axis a2 of the once-turned frame x′y′z′",
    ),
    Parameter(
        "angle3_deg",
        "deg",
        60.0,
        -180.0,
        180.0,
        label="θ3",
        step=1.0,
        description="Third turn, about axis a3 of the twice-turned frame x″y″z″",
    ),
    Parameter(
        "stage",
        "",
        "animate",
        kind="choice",
        choices=STAGES,
        label="Stage",
        description=(
            "animate: sweep θ1, then θ2, then θ3, hold and repeat; or hold the frame reached after one, "
            "two or all three turns"
        ),
    ),
)

# Axis lengths (display units) of the frames after 0, 1, 2, 3 turns: nested so labels never coincide.
FRAME_AXIS_LENGTH = (1.3, 1.1, 0.9, 0.72)
FRAME_AXIS_RADIUS = (0.012, 0.016, 0.02, 0.026)
FRAME_LABELS = (("X", "Y", "Z"), ("x′", "y′", "z′"), ("x″", "y″", "z″"), ("x", "y", "z"))
FRAME_LABEL_SCALE = (1.2, 1.0, 1.0, 1.2)
LABEL_GAP = 0.1  # names this far beyond their axis tips (display units)
TURN_AXIS_LENGTH = (2.0, 1.8, 1.6)
#: The text box of a label as the viewer draws it, in px at font scale 1 (measured on screenshots: 5.3 px a
#: character, 12 px tall), padded to 7 and 15 px; primes are thin and count as half a character.
LABEL_CHAR_PX, LABEL_HEIGHT_PX = 7.0, 15.0
#: px per unit of tangent off the line of sight in the lesson's viewer (520 px tall, vertical field of view 1 rad).
VIEW_PX_PER_TANGENT = 260.0 / math.tan(0.5)
#: The sides of its tip a name may be put on (viser anchors: the text's corner or edge at the tip), corners first.
#: Half-size (px) of the spot around each name's tip that other names' texts keep clear of.
TIP_CLEARANCE_PX = 1.5
LABEL_SIDES: tuple[LabelAnchor, ...] = (
    "bottom-left",
    "bottom-right",
    "top-left",
    "top-right",
    "center-left",
    "center-right",
    "bottom-center",
    "top-center",
)
TURN_COLORS = ((240, 140, 20), (190, 60, 200), (20, 160, 170))
LOCK_COLOR = (225, 25, 25)
ARC_DEGREES_PER_SEGMENT = 4.0

# Animation: (completed turns, turn being swept or 0, seconds). A drawing device only.
TIMELINE = ((0, 0, 0.8), (0, 1, 2.0), (1, 0, 0.6), (1, 2, 2.0), (2, 0, 0.6), (2, 3, 2.0), (3, 0, 3.0))
CYCLE_S = sum(phase[2] for phase in TIMELINE)


def animation_state(t_s: float) -> tuple[int, int, float]:
    """``(turns completed, turn being swept (1–3) or 0, eased fraction swept)`` at ``t_s`` into the loop."""
    t = t_s % CYCLE_S
    for done, sweeping, duration in TIMELINE:
        if t < duration:
            f = t / duration
            return done, sweeping, f * f * (3.0 - 2.0 * f) if sweeping else 0.0
        t -= duration
    return 3, 0, 0.0


def label_box_px(text: str, font_scale: float) -> tuple[float, float]:
    """``(width, height)`` in px of a label's text box (see LABEL_CHAR_PX)."""
    characters = sum(0.5 if c in "′″" else 1.0 for c in text)
    return LABEL_CHAR_PX * characters * font_scale, LABEL_HEIGHT_PX * font_scale


def view_px(camera_position, camera_look_at, points_world: np.ndarray) -> np.ndarray:
    """(n, 2) px (right, up) from the view's centre of ``points_world`` (n, 3) seen from the camera (pinhole)."""
    camera = np.asarray(camera_position, float)
    forward = np.asarray(camera_look_at, float) - camera
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    offsets = np.asarray(points_world, float) - camera
    return (
        VIEW_PX_PER_TANGENT
        * np.column_stack([offsets @ right, offsets @ np.cross(right, forward)])
        / (offsets @ forward)[:, None]
    )


#: Where each LABEL_SIDES anchor puts the text's lower-left corner, in widths and heights of the text from the tip.
SIDE_OFFSETS = np.array(
    [
        [
            -{"left": 0.0, "center": 0.5, "right": 1.0}[side.split("-")[1]],
            -{"bottom": 0.0, "center": 0.5, "top": 1.0}[side.split("-")[0]],
        ]
        for side in LABEL_SIDES
    ]
)


def text_box(point_px: np.ndarray, size_px: tuple[float, float], anchor: str) -> np.ndarray:
    """``[left, bottom, right, top]`` px of a text of ``size_px`` whose ``anchor`` corner (or edge) is at
    ``point_px``."""
    return side_boxes(point_px, size_px)[LABEL_SIDES.index(anchor)]


def side_boxes(point_px: np.ndarray, size_px: tuple[float, float]) -> np.ndarray:
    """(len(LABEL_SIDES), 4) ``[left, bottom, right, top]`` px of the text on each side of ``point_px``."""
    lower_left = np.asarray(point_px, float) + SIDE_OFFSETS * np.asarray(size_px, float)
    return np.concatenate([lower_left, lower_left + np.asarray(size_px, float)], axis=1)


def boxes_overlap(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Area (px²) shared by ``[left, bottom, right, top]`` boxes ``a`` (..., 4) and ``b`` (..., 4), broadcast (0 when
    apart)."""
    a, b = np.asarray(a, float), np.asarray(b, float)
    width = np.minimum(a[..., 2], b[..., 2]) - np.maximum(a[..., 0], b[..., 0])
    height = np.minimum(a[..., 3], b[..., 3]) - np.maximum(a[..., 1], b[..., 1])
    return np.clip(width, 0.0, None) * np.clip(height, 0.0, None)


def label_anchors(points_px: np.ndarray, sizes_px, current: list[LabelAnchor]) -> list[LabelAnchor]:
    """A side (LABEL_SIDES anchor) for each label at ``points_px`` (n, 2) whose text covers no label placed before
    it and no other label's tip (TIP_CLEARANCE_PX around it, so a later name always has room): its ``current``
    side if that is free (so names do not jump about), else the first free side, else the side covering least."""
    points_px = np.asarray(points_px, float)
    tips = np.concatenate([points_px - TIP_CLEARANCE_PX, points_px + TIP_CLEARANCE_PX], axis=1)
    placed = np.empty((0, 4))
    anchors = []
    for i, (point, size, now) in enumerate(zip(points_px, sizes_px, current)):
        others = np.concatenate([placed, tips[:i], tips[i + 1 :]])
        cover = boxes_overlap(side_boxes(point, size)[:, None, :], others[None, :, :]).sum(axis=1)
        kept = LABEL_SIDES.index(now)
        best = kept if cover[kept] <= cover.min() else int(np.argmin(cover))
        anchors.append(LABEL_SIDES[best])
        placed = np.concatenate([placed, side_boxes(point, size)[best][None, :]])
    return anchors


def _fmt(value: float) -> str:
    return f"{value:+.4f}".replace("+", " ").replace("-0.0000", " 0.0000")


class RotationSequenceScene(Scene):
    id = "rotation-sequence"
    title = "Rotation sequences: Euler and Tait–Bryan angles"
    chapter = 3
    controls = CONTROLS
    animated = True
    camera_position = (1.95, -2.55, 2.0)
    camera_look_at = (0.0, 0.0, 0.7)
    presets = (
        Preset(
            "aircraft",
            "Aircraft yaw–pitch–roll (3-2-1)",
            {"sequence": "3-2-1", "angle1_deg": 30.0, "angle2_deg": -20.0, "angle3_deg": 25.0, "stage": "animate"},
            "Yaw 30° about Z, pitch 20° nose-up (θ2 = −20° about y′, because Z points up here), roll 25° about x″",
        ),
        Preset(
            "classic-euler",
            "Classic Euler angles (3-1-3)",
            {"sequence": "3-1-3", "angle1_deg": 80.0, "angle2_deg": 35.0, "angle3_deg": 60.0, "stage": "animate"},
            "Precession 80° about Z, nutation 35° about the line of nodes x′, spin 60° about z″",
        ),
        Preset(
            "gimbal-lock",
            "Gimbal lock (3-2-1, pitch 90°)",
            {"sequence": "3-2-1", "angle1_deg": 30.0, "angle2_deg": 90.0, "angle3_deg": 10.0, "stage": "after turn 3"},
            "Pitch 90°: the roll axis x″ lands on the yaw axis Z, so only yaw − roll is determined",
        ),
    )

    # -- building -----------------------------------------------------------------------------------
    def build(self) -> None:
        scene = self.client.scene
        self.frames = []
        self.axis_labels = []  # (frame index, label handle, text box size px)
        for n, (length, radius, labels) in enumerate(zip(FRAME_AXIS_LENGTH, FRAME_AXIS_RADIUS, FRAME_LABELS)):
            frame = scene.add_frame(f"/frame{n}", axes_length=length, axes_radius=radius, origin_radius=0.05)
            for axis, text in enumerate(labels):
                tip = np.zeros(3)
                tip[axis] = length + LABEL_GAP
                handle = scene.add_label(
                    f"/frame{n}/label_{axis}",
                    text,
                    position=tip,
                    anchor=LABEL_SIDES[n],
                    font_screen_scale=FRAME_LABEL_SCALE[n],
                )
                self.axis_labels.append((n, handle, label_box_px(text, FRAME_LABEL_SCALE[n])))
            self.frames.append(frame)
        scene.add_box(
            "/frame3/plate",
            color=(90, 120, 170),
            dimensions=(0.7, 0.42, 0.06),
            opacity=0.45,
            cast_shadow=False,
            receive_shadow=False,
        )
        self.turn_axes = [
            scene.add_arrows(
                f"/turn{k}/axis",
                np.zeros((1, 2, 3), np.float32),
                TURN_COLORS[k],
                shaft_radius=0.02,
                head_radius=0.06,
                head_length=0.15,
            )
            for k in range(3)
        ]
        self.turn_labels = [scene.add_label(f"/turn{k}/label", "", anchor="bottom-left") for k in range(3)]
        self.arcs = [
            scene.add_line_segments(
                f"/turn{k}/arc",
                np.zeros((1, 2, 3), np.float32),
                TURN_COLORS[k],
                thickness=4.0,
                thickness_units="screen",
            )
            for k in range(3)
        ]
        self.t_s = 0.0
        self._shown: tuple[int, int] | None = None

    # -- parameters → geometry ------------------------------------------------------------------------
    def angles_rad(self) -> np.ndarray:
        return np.radians([self.params["angle1_deg"], self.params["angle2_deg"], self.params["angle3_deg"]])

    def update(self) -> None:
        self.sequence = rotation_sequence(self.params["sequence"])
        self.angles = self.angles_rad()
        self.geometry = intermediate_frames(self.angles, self.sequence)
        R = self.geometry.R_world_frame[3]
        self.decomposition = angles_from_matrix(R, self.sequence)
        self._prepare_turns()
        locked = bool(self.decomposition.degenerate)
        for k in range(3):
            n = self.geometry.rotation_axes_world[k]
            self.turn_axes[k].points = np.array([[np.zeros(3), TURN_AXIS_LENGTH[k] * n]], np.float32)
            self.turn_axes[k].colors = np.array(LOCK_COLOR if locked and k != 1 else TURN_COLORS[k], np.uint8)
            self.turn_labels[k].position = tuple(TURN_AXIS_LENGTH[k] * n + np.array([0.0, 0.0, 0.04 * (1 - k)]))
            text = f"turn {k + 1}: θ{k + 1} = {math.degrees(self.angles[k]):g}° about {self.sequence.axis_label(k + 1)}"
            if locked and k != 1:
                text += f" (on the line of {self.sequence.axis_label(3 - k)}: gimbal lock)"
            self.turn_labels[k].text = text
        self.t_s = 0.0
        self._shown = None
        self._draw()

    def _prepare_turns(self) -> None:
        """Per turn, everything a frame of its sweep needs, so a frame costs a few flops.

        Turning frame ``k`` by ``φ`` about its axis ``a``: ``q(φ) = q_before ⊗ (cos ½φ, sin ½φ e_a)
        = cos ½φ · q_before + sin ½φ · (q_before ⊗ e_a)``. The arc is the path of the tip of the
        axis after ``a`` (display length of the frame being turned): ``start cos φ + (n × start) sin φ``.
        """
        self._turns = []
        for k in range(3):
            q_before = self.geometry.q_world_frame[k]
            e_axis = np.zeros(4)
            e_axis[1 + self.sequence.axes[k]] = 1.0
            q_axis = quaternion_multiply(q_before, e_axis)
            n = self.geometry.rotation_axes_world[k]
            start = self.geometry.R_world_frame[k][:, (self.sequence.axes[k] + 1) % 3] * FRAME_AXIS_LENGTH[k + 1]
            count = max(2, int(math.ceil(abs(math.degrees(self.angles[k])) / ARC_DEGREES_PER_SEGMENT)) + 1)
            phi = np.linspace(0.0, self.angles[k], count)[:, None]
            points = (start * np.cos(phi) + np.cross(n, start) * np.sin(phi)).astype(np.float32)
            self._turns.append((q_before, q_axis, start, np.cross(n, start), points))

    def _turn(self, k: int, fraction: float) -> None:
        """Place frame ``k+1`` partway (``fraction``) through turn ``k`` and grow its arc."""
        q_before, q_axis, start, side, points = self._turns[k]
        phi = fraction * self.angles[k]
        self.frames[k + 1].wxyz = math.cos(0.5 * phi) * q_before + math.sin(0.5 * phi) * q_axis
        tip = (start * math.cos(phi) + side * math.sin(phi)).astype(np.float32)
        whole = int(fraction * (len(points) - 1))  # arc samples already passed
        path = np.concatenate([points[: whole + 1], tip[None, :]])
        self.arcs[k].points = np.stack([path[:-1], path[1:]], axis=1)

    def _draw(self) -> None:
        stage = self.params["stage"]
        if stage == "animate":
            done, sweeping, fraction = animation_state(self.t_s)
        else:
            done, sweeping, fraction = STAGES.index(stage), 0, 0.0
        shown = (done, sweeping)
        if shown != self._shown:  # frames, axes and arcs appear only when a phase starts
            visible_turns = max(done, sweeping)
            for n in (1, 2, 3):
                self.frames[n].visible = n <= visible_turns
            for k in range(3):
                for node in (self.turn_axes[k], self.turn_labels[k], self.arcs[k]):
                    node.visible = k < visible_turns
            for k in range(3):
                self._turn(k, 1.0 if k < done else 0.0)  # turns not yet begun wait at their start (hidden)
            self._shown = shown
        if sweeping:
            self._turn(sweeping - 1, fraction)
        self._place_labels()

    def _place_labels(self) -> None:
        """Put each shown turn label and axis name on a side of its tip where its text covers no other label nor
        another's tip in the default view (see :func:`label_anchors`); only labels whose side changes are sent."""
        shown = [
            (label, np.asarray(label.position, float), label_box_px(label.text, 1.0))
            for label in self.turn_labels
            if label.visible
        ]
        for n, handle, size in self.axis_labels:
            frame = self.frames[n]
            if frame.visible:
                tip = np.asarray(frame.position, float) + rotate_vector(
                    np.asarray(frame.wxyz, float), np.asarray(handle.position, float)
                )
                shown.append((handle, tip, size))
        if not shown:
            return
        points = view_px(*self.camera_view(), np.array([tip for _, tip, _ in shown]))
        anchors = label_anchors(points, [size for *_, size in shown], [label.anchor for label, _, _ in shown])
        for (label, _, _), anchor in zip(shown, anchors):
            if label.anchor != anchor:
                label.anchor = anchor

    def step_motion(self, dt_s: float) -> bool:
        """The clock runs only while the stage is "animate"."""
        if self.params["stage"] != "animate":
            return False
        self.t_s += dt_s
        return True

    def redraw(self) -> None:
        self._shown = None  # the instant may be in another phase than the one drawn: show its frames afresh
        self._draw()

    # -- numbers beside the scene ---------------------------------------------------------------------
    def readout(self) -> Readout:
        """Rows of [R], the axis and the angles read back are written out as text; the rest are numbers."""
        seq, decomposition = self.sequence, self.decomposition
        R = self.geometry.R_world_frame[3]
        q = self.geometry.q_world_frame[3]
        axis, angle = axis_angle_from_quaternion(q)
        lock_deg = math.degrees(float(decomposition.lock_distance_rad))
        singular_values = np.linalg.svd(angle_rate_matrix_body(self.angles, seq), compute_uv=False)
        rate_gain = None if decomposition.degenerate else float(1.0 / singular_values[-1])
        recovered = np.degrees(decomposition.angles_rad)
        quantities = [
            Quantity.word("sequence", "sequence", f"{seq.name} ({seq.kind})"),
            *(
                Quantity(
                    f"R_row{i + 1}", f"[R] row {i + 1} (v_XYZ = [R] v_xyz)", None, "", "  ".join(_fmt(v) for v in R[i])
                )
                for i in range(3)
            ),
            *(Quantity(f"q_{c}", f"quaternion {c}", float(v), "") for c, v in zip("wxyz", q)),
            Quantity("axis", "rotation axis (unit vector, XYZ)", None, "", "  ".join(_fmt(v) for v in axis)),
            Quantity("rotation_angle_deg", "rotation angle about that axis", math.degrees(float(angle)), "deg"),
            Quantity("gimbal_lock_distance_deg", "distance to gimbal lock", lock_deg, "deg"),
            Quantity(
                "recovered_angles_deg",
                "angles read back from [R]",
                None,
                "deg",
                ", ".join(f"{a:.2f}" for a in recovered),
            ),
            Quantity.or_text("rate_gain", "largest angle rate per unit |ω|", rate_gain, "(rad/s)/(rad/s)", "unbounded"),
            Quantity("t_s", "time into the animation loop", self.t_s % CYCLE_S, "s"),
        ]
        marks = {"angle2_deg": [Mark(math.degrees(a), "gimbal lock") for a in seq.lock_angles_rad]}
        return Readout(quantities, marks=marks, message=self.message())

    def message(self) -> str:
        seq, decomposition = self.sequence, self.decomposition
        degrees = np.degrees(self.angles)
        turns = ", then ".join(f"θ{k + 1} = {degrees[k]:g}° about {seq.axis_label(k + 1)}" for k in range(3))
        text = f"{seq.name} is a {seq.kind} sequence: {turns}."
        lock_deg = math.degrees(float(decomposition.lock_distance_rad))
        if decomposition.degenerate:
            s = float(decomposition.lock_sign)
            combination = "θ1 + θ3" if s > 0 else "θ1 − θ3"
            value = math.degrees(self.angles[0] + s * self.angles[2])
            value = (value + 180.0) % 360.0 - 180.0
            text += (
                f" Gimbal lock: θ2 = {degrees[1]:g}° puts the third turn's axis {seq.axis_label(3)} on the line "
                "of the first "
                f"turn's axis {seq.axis_label(1)}, so the first and third turns act about the same line. Only "
                f"{combination} "
                f"= {value:.6g}° is determined; every pair with that {'sum' if s > 0 else 'difference'} gives "
                "the same [R], "
                "and the angle rates can no longer be found from ω."
            )
        elif lock_deg < NEAR_LOCK_DEG:
            text += (
                f" Near gimbal lock ({lock_deg:.3g}° away): small changes of attitude need large, opposite "
                "changes of θ1 and θ3, "
                "and the angle rates for a given ω grow like 1/sin of that distance."
            )
        return text
