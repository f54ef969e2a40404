"""Scene: a slider on a spinning, tilting, shaking turntable, with each acceleration term as an arrow.

Drawn in metres, world frame +Z up. The five terms of
``a_P = a_O + α × r + ω × (ω × r) + 2 ω × v_rel + a_rel`` are arrows laid head to
tail from the slider P, and the absolute acceleration a_P is drawn from P too: it
ends where the chain ends. All acceleration arrows share one scale (stated in the
readout); ω and α are drawn from the table's centre. The motion replays every
``replay_s`` seconds; a playback speed of 0 holds the instant ``time_s``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any, cast

import numpy as np
import viser

from app.physics.core.parameters import Parameter
from app.physics.systems.ch03 import moving_frame as physics
from app.scenes.kit import FRAME_DT_S, Preset, Quantity, Readout, Scene, move_node
from app.scenes.kit.arrows import LabelledArrows

COLORS = {
    "reference": (120, 80, 180),  # purple
    "angular": (235, 140, 20),  # orange
    "centripetal": (40, 160, 70),  # green
    "coriolis": (215, 40, 40),  # red
    "relative": (30, 110, 220),  # blue
    "total": (25, 25, 25),  # black
}
SHORT_LABELS = {
    "reference": "a_O",
    "angular": "α×r",
    "centripetal": "ω×(ω×r)",
    "coriolis": "2ω×v_rel",
    "relative": "a_rel",
    "total": "a_P",
}
CHAIN_LENGTH_M = 1.5  # three quarters of the replay's head-to-tail chains are drawn at most this long (× table radius)
RATE_COLORS = {"omega": (70, 70, 70), "alpha": (200, 90, 150)}
RATE_ARROW_M_PER_RAD_S = 0.25
PATH_SAMPLES = 400
#: The table's top face is drawn this far below the plane of P's motion, so arrows lying in that plane are not
#: hidden inside the disc (the slider box is tall enough to sit in the groove).
DISC_TOP_BELOW_P_M = 0.04
BATCH_FRAMES = (
    30  # frames evaluated per vectorised call: the per-call overhead shared (docs/bench/live-frame-costs.svg)
)

DISPLAY_PARAMETERS = (
    Parameter(
        "time_s",
        "s",
        0.0,
        0.0,
        60.0,
        "Instant shown when the playback speed is 0 (and where playback starts)",
        "instant t",
        step=0.05,
    ),
    Parameter(
        "playback_speed",
        "× real time",
        0.5,
        0.0,
        2.0,
        "Speed of the replay; 0 holds the instant t still",
        "playback speed",
        step=0.05,
    ),
    Parameter(
        "replay_s", "s", 10.0, 2.0, 60.0, "The motion replays from t = 0 after this long", "replay length", step=1.0
    ),
)


def _nice_scale(value: float) -> float:
    """The largest of 1, 1.5, 2, 3, 4, 5, 6 or 8 × 10^k not above ``value`` (for a readable arrow scale)."""
    exponent = math.floor(math.log10(value))
    for mantissa in (8.0, 6.0, 5.0, 4.0, 3.0, 2.0, 1.5, 1.0):
        if mantissa * 10.0**exponent <= value:
            return mantissa * 10.0**exponent
    return 10.0**exponent


def _vector_text(v: np.ndarray) -> str:
    return "(" + ", ".join(f"{round(float(c), 3) + 0.0:+.3f}" for c in v) + ")"  # + 0.0 turns −0.000 into +0.000


#: Frames between moves of the arrow labels (2: at 15 Hz).
LABEL_MOVE_EVERY_FRAMES = 2


class MovingFrameScene(Scene):
    id = "moving-frame-acceleration"
    #: Table attitude, slider, the two arrow batches, and the labels of the drawn arrows at 15 Hz.
    frame_message_budget = 6.0
    title = "Acceleration seen from a moving frame: the five terms"
    chapter = 3
    model = physics.MovingFrameAcceleration
    controls = DISPLAY_PARAMETERS
    animated = True
    presets = (
        Preset(
            "steady-radial",
            "Steady spin, radial groove",
            {
                "table_radius_m": 1.0,
                "spin_rate_rad_s": 1.5,
                "spin_acceleration_rad_s2": 0.0,
                "tilt_deg": 0.0,
                "precession_rate_rad_s": 0.0,
                "groove_offset_m": 0.0,
                "slider_amplitude_m": 0.7,
                "slider_frequency_hz": 0.2,
                "cart_amplitude_m": 0.0,
            },
            "Only centripetal, Coriolis and relative terms: watch the Coriolis arrow flip as the slider turns back.",
        ),
        Preset(
            "slider-locked",
            "Slider locked, table spinning up",
            {
                "table_radius_m": 1.0,
                "spin_rate_rad_s": 0.5,
                "spin_acceleration_rad_s2": 0.3,
                "tilt_deg": 0.0,
                "precession_rate_rad_s": 0.0,
                "slider_amplitude_m": 0.0,
                "groove_offset_m": 0.6,
                "cart_amplitude_m": 0.0,
            },
            "A point fixed to the body: no Coriolis or relative term; α × r is the tangential part.",
        ),
        Preset(
            "tilted-precessing",
            "Tilted axis that precesses",
            {
                "table_radius_m": 1.0,
                "spin_rate_rad_s": 2.0,
                "spin_acceleration_rad_s2": 0.0,
                "tilt_deg": 30.0,
                "precession_rate_rad_s": 0.8,
                "groove_offset_m": 0.3,
                "slider_amplitude_m": 0.6,
                "slider_frequency_hz": 0.25,
                "cart_amplitude_m": 0.0,
            },
            "Steady spin and steady precession still give α ≠ 0: the spin axis itself turns.",
        ),
        Preset(
            "shaking-cart",
            "On a shaking cart",
            {
                "table_radius_m": 1.0,
                "spin_rate_rad_s": 1.0,
                "spin_acceleration_rad_s2": 0.0,
                "tilt_deg": 0.0,
                "precession_rate_rad_s": 0.0,
                "groove_offset_m": 0.3,
                "slider_amplitude_m": 0.6,
                "slider_frequency_hz": 0.25,
                "cart_amplitude_m": 0.3,
                "cart_frequency_hz": 0.6,
            },
            "The reference point O accelerates: a_O is added to every point of the table alike.",
        ),
        Preset(
            "everything",
            "Everything at once",
            {
                "table_radius_m": 1.0,
                "spin_rate_rad_s": 1.2,
                "spin_acceleration_rad_s2": 0.2,
                "tilt_deg": 25.0,
                "precession_rate_rad_s": 0.6,
                "groove_offset_m": 0.3,
                "slider_amplitude_m": 0.6,
                "slider_frequency_hz": 0.3,
                "cart_amplitude_m": 0.2,
                "cart_frequency_hz": 0.5,
            },
            "All five terms at once; the chain still closes on a_P.",
        ),
    )

    def camera_view(self):
        r = self.params["table_radius_m"]
        return (0.3 + 0.5 * r, -0.4 - 0.75 * r, 1.1 + 0.7 * r), (0.0, 0.1 * r, physics.TABLE_HEIGHT_M - 0.1 * r)

    def physical_params(self) -> dict[str, Any]:
        return {k: v for k, v in self.params.items() if k in physics.PARAMETERS.by_name}

    def build(self) -> None:
        scene = self.client.scene
        scene.add_grid("/floor", width=6.0, height=6.0, cell_size=0.25, section_size=1.0)
        self.cart = scene.add_frame("/cart", show_axes=False)
        scene.add_box("/cart/body", color=(150, 150, 160), dimensions=(0.5, 0.36, 0.18), position=(0.0, 0.0, 0.14))
        for i, (x, y) in enumerate(((-0.18, -0.2), (0.18, -0.2), (-0.18, 0.2), (0.18, 0.2))):
            scene.add_cylinder(
                f"/cart/wheel{i}",
                radius=0.05,
                height=0.04,
                color=(40, 40, 40),
                position=(x, y, 0.05),
                wxyz=(math.sqrt(0.5), math.sqrt(0.5), 0.0, 0.0),
            )
        scene.add_cylinder(
            "/cart/post",
            radius=0.025,
            height=physics.TABLE_HEIGHT_M - 0.23,
            color=(110, 110, 120),
            position=(0.0, 0.0, 0.23 + 0.5 * (physics.TABLE_HEIGHT_M - 0.23)),
        )
        self.table = scene.add_frame("/table", axes_length=0.25, axes_radius=0.008)
        self.disc: viser.CylinderHandle | None = None
        self.groove: viser.LineSegmentsHandle | None = None
        self.slider = scene.add_box(
            "/table/slider", color=(250, 200, 40), dimensions=(0.08, 0.05, 2.0 * DISC_TOP_BELOW_P_M)
        )
        self.path = scene.add_line_segments(
            "/path", np.zeros((1, 2, 3), np.float32), (170, 170, 190), thickness=1.5, thickness_units="screen"
        )
        self.accel = LabelledArrows(scene, "/accel", COLORS, SHORT_LABELS)
        self.rates = LabelledArrows(scene, "/rates", RATE_COLORS, {"omega": "ω", "alpha": "α"})
        self.rates.set_style(shaft_radius=0.01, head_radius=0.03, head_length=0.06)

    def update(self) -> None:
        params = self.physical_params()
        self.motion = physics.MovingFrameMotion.from_params(params)
        scene = self.client.scene
        radius = params["table_radius_m"]
        if self.disc is not None:
            self.disc.remove()
            cast(viser.LineSegmentsHandle, self.groove).remove()  # drawn with the disc
        self.disc = scene.add_cylinder(
            "/table/disc",
            radius=radius,
            height=0.02,
            color=(205, 215, 230),
            position=(0.0, 0.0, -DISC_TOP_BELOW_P_M - 0.01),
        )
        d = params["groove_offset_m"]
        half = math.sqrt(max(radius * radius - d * d, 0.0))
        self.groove = scene.add_line_segments(
            "/table/groove",
            np.array([[[-half, d, -DISC_TOP_BELOW_P_M + 0.001], [half, d, -DISC_TOP_BELOW_P_M + 0.001]]], np.float32),
            (150, 130, 100),
            thickness=2.5,
            thickness_units="screen",
        )
        # Sizes follow the table so every radius gives a readable picture.
        self.accel.set_style(shaft_radius=0.02 * radius, head_radius=0.048 * radius, head_length=0.085 * radius)
        replay = np.linspace(0.0, self.params["replay_s"], PATH_SAMPLES)
        whole = self.motion.kinematics(replay)
        chain = sum(np.linalg.norm(whole.terms_m_s2[name], axis=-1) for name in physics.TERM_NAMES)
        typical = max(float(np.percentile(chain, 75.0)), 1e-9)
        self.arrow_m_per_m_s2 = _nice_scale(min(CHAIN_LENGTH_M * radius / typical, 1e3))  # at rest: no arrows at all
        path = whole.position_m.astype(np.float32)
        self.path.points = np.stack([path[:-1], path[1:]], axis=1)
        self._start_batch(float(self.params["time_s"]) % self.params["replay_s"])
        self._draw()

    # -- per frame ------------------------------------------------------------------------
    def _start_batch(self, t0_s: float) -> None:
        """Evaluate the next BATCH_FRAMES frames at once (one vectorised call instead of one per frame)."""
        step = self.params["playback_speed"] * FRAME_DT_S
        times = np.mod(t0_s + step * np.arange(BATCH_FRAMES), self.params["replay_s"])
        self._batch = self.motion.kinematics(times)
        self._row = 0

    def _draw(self) -> None:
        k, i = self._batch, self._row
        self.t_s = float(k.t_s[i])
        origin = k.origin_m[i]
        move_node(self.cart, position=(float(origin[0]), 0.0, 0.0))
        move_node(self.table, position=origin, wxyz=k.attitude_wxyz[i])
        move_node(self.slider, position=k.slider_body_m[i])
        p = k.position_m[i]
        self._terms = {name: value[i] for name, value in k.terms_m_s2.items()}
        self._omega = k.omega_rad_s[i]
        self._alpha = k.alpha_rad_s2[i]
        scale = self.arrow_m_per_m_s2
        segments: dict[str, tuple[np.ndarray, np.ndarray]] = {}
        tail = p
        for name in physics.TERM_NAMES:  # head to tail, starting at P
            segments[name] = (tail, tail + scale * self._terms[name])
            tail = segments[name][1]
        segments["total"] = (p, p + scale * self._terms["total"])
        # Labels ride along their arrows at 15 Hz (the arrows move at 30): with eight labels that is four messages
        # a frame fewer per student, and a label trails its arrow by at most one frame.
        move_labels = self._row % LABEL_MOVE_EVERY_FRAMES == 0
        self.accel.draw(segments, move_labels=move_labels)
        self.rates.draw(
            {
                "omega": (origin, origin + RATE_ARROW_M_PER_RAD_S * self._omega),
                "alpha": (origin, origin + RATE_ARROW_M_PER_RAD_S * self._alpha),
            },
            label_at=1.0,
            move_labels=move_labels,
        )

    def step_motion(self, dt_s: float) -> bool:
        """One displayed frame: ``playback_speed × FRAME_DT_S`` of motion (the host draws at 30 Hz)."""
        if self.params["playback_speed"] == 0.0:
            return False
        self._row += 1
        if self._row >= BATCH_FRAMES:
            step = self.params["playback_speed"] * FRAME_DT_S
            self._start_batch((self.t_s + step) % self.params["replay_s"])
        self.t_s = float(self._batch.t_s[self._row])
        return True

    def resume_from(self, motion: Mapping[str, Any]) -> None:
        super().resume_from(motion)
        self._start_batch(self.t_s % self.params["replay_s"])

    def step_without_drawing(self, t_s: float) -> None:
        """A closed form: the instant ``t_s`` of the replay (s; the replay repeats every ``replay_s``)."""
        self._start_batch(t_s % self.params["replay_s"])

    def readout(self) -> Readout:
        """Vectors are written out as text (world X, Y, Z components); their magnitudes are numbers."""
        quantities = [
            Quantity("t_s", "t", float(self.t_s), "s"),
            Quantity("omega", "ω (X, Y, Z)", None, "rad/s", _vector_text(self._omega), text_in_unit=True),
            Quantity("alpha", "α (X, Y, Z)", None, "rad/s²", _vector_text(self._alpha), text_in_unit=True),
        ]
        for name in (*physics.TERM_NAMES, "total"):
            vector = self._terms[name]
            quantities.append(
                Quantity(
                    f"a_{name}",
                    physics.TERM_LABELS[name],
                    None,
                    "m/s² (world X, Y, Z)",
                    _vector_text(vector),
                    text_in_unit=True,
                )
            )
            quantities.append(
                Quantity(f"a_{name}_magnitude", f"|{SHORT_LABELS[name]}|", float(np.linalg.norm(vector)), "m/s²")
            )
        quantities.append(Quantity("arrow_scale", "acceleration arrows", self.arrow_m_per_m_s2, "m of arrow per m/s²"))
        return Readout(quantities, message="Terms shorter than their arrowhead are listed here but not drawn.")
