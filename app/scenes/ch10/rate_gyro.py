"""Scene: the single-axis rate gyro on a turntable (section 10.3).

World frame: +Z up. The case (a translucent box) stands on a turntable that
turns about Z, the gyro's input axis. The gimbal (teal ring) pivots in the
case about the case's x axis (output axis), restrained by a spring and a
damper; the rotor (blue) spins about the gimbal's y axis. A pointer on the
gimbal shows the deflection β in the case. As in a real rate gyro, a pickoff on
the output axis repeats β on an indicator that stands beside the turntable and
does not turn with it: its needle turns by the same β against a scale
calibrated in rad/s of input rate (β = G Ω in the steady state, G = I_a ω_s / k).
The dial faces the default camera, so its numbers are never seen edge-on.

For a step input the turntable runs at Ω₀ for ``hold`` seconds, stops for as
long, and repeats; by linearity β is the step response minus the step response
delayed by ``hold`` (superposition of :func:`app.physics.systems.ch10.rate_gyro.gimbal_response`).
A sine input simply runs on. Arrows: spin angular momentum ``H`` (blue, fixed
length), input rate ``Ω`` (green, scaled to Ω₀), and the spring-plus-damper
moment on the gimbal (red, scaled to its steady value H Ω₀) — the moment that
turns ``H`` with the case.
"""

from __future__ import annotations

import math

import numpy as np
import viser

from app.physics.math.rotations import quaternion_from_matrix
from app.physics.systems.ch10 import rate_gyro as physics
from app.scenes.ch10.free_gyroscope import COLOR_H, COLOR_RATE, COLOR_TORQUE
from app.scenes.kit import LabelAnchor, Mark, Preset, Quantity, Readout, Scene, arrow_segments
from app.scenes.kit.rotor import add_rotor, drawn_spin_angle, ring_mesh, spin_quaternion

GIMBAL_RADIUS = 0.55
ROTOR_RADIUS = 0.34
CASE_SIZE = (1.5, 1.5, 1.2)
POINTER_LENGTH = 0.62
POINTER_X = 0.75  # the gimbal's pointer stands just inside the case's +x wall
#: The indicator (display units): its centre lies this far to the left of the look-at point across the default
#: view and this far above it, clear of the turntable (radius 1.25) and of the labels, which run to the right.
INDICATOR_SIDE = 2.05
INDICATOR_LIFT = 0.15
DIAL_RADIUS = 0.55
#: The indicator's needle: its tip sweeps the scale's inner edge; ticks run 0.07 beyond it, numbers SCALE_LABEL_GAP.
NEEDLE_LENGTH = 0.4
SCALE_LABEL_GAP = 0.12
SCALE_LABEL_SIZE = 1.0
#: Needle, ticks and numbers lie this far in front of the dial's face (the indicator's x points away from the camera).
DIAL_FACE_X = -0.03
DIAL_FACE_X_VECTOR = np.array([DIAL_FACE_X, 0.0, 0.0])
H_ARROW_LENGTH = 0.95
RATE_ARROW_MAX = 0.7
MOMENT_ARROW_MAX = 0.6
MAX_SCALE_RAD = math.radians(60.0)
#: The numbered ends of the scale are at least this far from zero on the dial, so "0" and "+1 rad/s" stay apart.
MIN_SCALE_RAD = math.radians(15.0)
#: Label texts (numbers) are refreshed every this many frames (5 Hz): each assignment is sent to the browser.
LABEL_TEXT_EVERY = 6
RATE_ARROW_TAIL = np.array([0.0, 0.0, 0.5 * CASE_SIZE[2] + 0.25])
MOMENT_ARROW_TAIL = np.array([-0.5 * CASE_SIZE[0] - 0.05, 0.0, -0.15])


def hold_time_s(params) -> float:
    """How long the turntable runs (and then rests) in the step demonstration: ~6 time constants, 3–20 s."""
    decay = physics.damping_ratio(params) * physics.natural_frequency_rad_s(params)
    return float(np.clip(6.0 / decay, 3.0, 20.0)) if decay > 0.0 else 10.0


def indicator_pose(camera_position, camera_look_at) -> tuple[np.ndarray, np.ndarray]:
    """``(position (3,), wxyz (4,))`` of the indicator, fixed in the world frame: beside the turntable, its face square
    to the line of sight from ``camera_position``. The indicator's x axis points from the camera through the dial's
    centre, its z axis is the world's up as seen on the face, so a turn of +β about x swings the needle clockwise on
    the screen, as the gimbal turns +β about the case's x."""
    camera, look_at = np.asarray(camera_position, float), np.asarray(camera_look_at, float)
    across = np.cross(look_at - camera, [0.0, 0.0, 1.0])
    centre = look_at - INDICATOR_SIDE * across / np.linalg.norm(across) + np.array([0.0, 0.0, INDICATOR_LIFT])
    x_axis = (centre - camera) / np.linalg.norm(centre - camera)
    z_axis = np.array([0.0, 0.0, 1.0]) - x_axis[2] * x_axis
    z_axis /= np.linalg.norm(z_axis)
    return centre, quaternion_from_matrix(np.column_stack([x_axis, np.cross(z_axis, x_axis), z_axis]))


def needle_direction(beta_rad: float) -> np.ndarray:
    """Unit vector (3,), indicator frame, along the needle turned by ``beta_rad`` about x from straight up."""
    return np.array([0.0, -math.sin(beta_rad), math.cos(beta_rad)])


def nice_step(value: float) -> float:
    """The smallest of 1, 2, 2.5, 5 × 10ⁿ at or above ``value`` (> 0)."""
    exponent = math.floor(math.log10(value))
    for mantissa in (1.0, 2.0, 2.5, 5.0, 10.0):
        if mantissa * 10.0**exponent >= value * (1 - 1e-12):
            return mantissa * 10.0**exponent
    return 10.0 ** (exponent + 1)


class RateGyroScene(Scene):
    id = "rate-gyro"
    title = "The single-axis rate gyro"
    chapter = 10
    model = physics.RateGyro
    animated = True
    camera_position = (2.05, -1.75, 1.25)
    camera_look_at = (0.1, 0.0, -0.05)
    presets = (
        Preset(
            "underdamped",
            "Under-damped (ζ ≈ 0.2)",
            {"damping_N_m_s_rad": 0.02, "input_kind": "step"},
            "The pointer overshoots and rings before it settles on the input rate.",
        ),
        Preset(
            "critical",
            "Critically damped (ζ = 1)",
            {"damping_N_m_s_rad": 0.1, "input_kind": "step", "stiffness_N_m_rad": 0.5, "gimbal_inertia_kg_m2": 5e-3},
            "The fastest approach without overshoot.",
        ),
        Preset(
            "overdamped",
            "Over-damped (ζ = 3)",
            {"damping_N_m_s_rad": 0.3, "input_kind": "step"},
            "Sluggish: the pointer creeps up to the reading.",
        ),
        Preset(
            "sine",
            "Oscillating input",
            {"input_kind": "sine", "input_frequency_rad_s": 5.0, "damping_N_m_s_rad": 0.03},
            "The case rocks back and forth; the pointer follows with a gain and a lag set by ω/ω_n and ζ.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.t_s = 0.0
        lx, ly, lz = CASE_SIZE
        scene.add_grid(
            "/ground", width=4.0, height=4.0, cell_size=0.25, section_size=1.0, position=(0.0, 0.0, -0.5 * lz - 0.12)
        )
        self.table = scene.add_frame("/table", show_axes=False)
        scene.add_cylinder(
            "/table/top",
            radius=1.25,
            height=0.06,
            color=(150, 150, 155),
            position=(0.0, 0.0, -0.5 * lz - 0.06),
            radial_segments=64,
        )
        scene.add_box(
            "/table/mark", color=(235, 200, 40), dimensions=(0.25, 0.08, 0.065), position=(1.1, 0.0, -0.5 * lz - 0.06)
        )
        scene.add_box(
            "/table/case",
            color=(180, 190, 210),
            dimensions=CASE_SIZE,
            opacity=0.18,
            side="double",
            cast_shadow=False,
            receive_shadow=False,
        )
        scene.add_box("/table/case_edges", color=(90, 100, 120), dimensions=CASE_SIZE, wireframe=True)
        for sign in (-1.0, 1.0):  # the output-axis bearings in the case walls
            scene.add_cylinder(
                f"/table/bearing{int(sign)}",
                radius=0.03,
                height=0.5 * lx - GIMBAL_RADIUS,
                color=(110, 110, 110),
                position=(sign * 0.5 * (0.5 * lx + GIMBAL_RADIUS), 0.0, 0.0),
                wxyz=np.array([math.cos(math.pi / 4), 0.0, math.sin(math.pi / 4), 0.0]),
            )
        scene.add_label(
            "/table/output_axis", "output axis x", position=(-0.5 * lx - 0.05, 0.0, 0.1), anchor="bottom-right"
        )
        self.gimbal = scene.add_frame("/table/gimbal", show_axes=False)
        vertices, faces = ring_mesh(
            GIMBAL_RADIUS, 0.028, normal="z"
        )  # holds the output pivots (±x) and the rotor bearings (±y)
        scene.add_mesh_simple("/table/gimbal/ring", vertices, faces, color=(40, 160, 160), flat_shading=False)
        scene.add_box(
            "/table/gimbal/pointer",
            color=(200, 40, 40),
            dimensions=(0.02, 0.02, POINTER_LENGTH),
            position=(POINTER_X, 0.0, 0.5 * POINTER_LENGTH),
        )
        self.rotor = add_rotor(
            scene, "/table/gimbal/rotor", radius=ROTOR_RADIUS, thickness=0.12, axle_length=2 * GIMBAL_RADIUS
        )
        self._build_indicator()
        self.scale_nodes: list = []
        self.arrows = scene.add_arrows(
            "/table/vectors",
            np.zeros((3, 2, 3), np.float32),
            np.array([COLOR_H, COLOR_RATE, COLOR_TORQUE], np.uint8),
            shaft_radius=0.016,
            head_radius=0.04,
            head_length=0.09,
        )
        self.labels = {
            name: scene.add_label(f"/table/vectors/{name}", "", anchor="bottom-left")
            for name in ("H", "rate", "moment")
        }

    def _build_indicator(self) -> None:
        """The dial, its needle and its caption, fixed in space (the scale's ticks and numbers follow the
        parameters)."""
        scene = self.client.scene
        centre, wxyz = indicator_pose(*self.camera_view())
        scene.add_frame("/indicator", show_axes=False, position=tuple(centre), wxyz=tuple(wxyz))
        face_normal = np.array([math.cos(math.pi / 4), 0.0, math.sin(math.pi / 4), 0.0])  # cylinder axis z → x
        scene.add_cylinder(
            "/indicator/dial",
            radius=DIAL_RADIUS,
            height=0.03,
            color=(245, 245, 240),
            wxyz=face_normal,
            radial_segments=48,
        )
        scene.add_cylinder(
            "/indicator/hub",
            radius=0.03,
            height=0.02,
            color=(60, 60, 60),
            position=tuple(1.2 * DIAL_FACE_X_VECTOR),
            wxyz=face_normal,
        )
        self.needle = scene.add_frame("/indicator/needle", show_axes=False)
        scene.add_box(
            "/indicator/needle/bar",
            color=(200, 40, 40),
            dimensions=(0.01, 0.02, NEEDLE_LENGTH),
            position=(DIAL_FACE_X, 0.0, 0.5 * NEEDLE_LENGTH),
        )
        scene.add_label(
            "/indicator/caption",
            "indicator: β read as Ω",
            position=(DIAL_FACE_X, 0.0, -DIAL_RADIUS - 0.04),
            anchor="top-center",
        )

    def update(self) -> None:
        params = self.params
        self.t_s = 0.0
        self._hold_s = hold_time_s(params)
        self._gain = physics.steady_gain_s(params)
        self._h = physics.angular_momentum_N_m_s(params)
        self._draw_scale()
        self.labels["H"].text = f"H = {abs(self._h):.3g} N·m·s"
        self.labels["rate"].position = tuple(RATE_ARROW_TAIL + np.array([0.05, 0.0, 0.0]))
        self.labels["moment"].position = tuple(MOMENT_ARROW_TAIL + np.array([0.0, 0.0, 0.06]))
        self._frame = 0
        self._outside_model: tuple[float, float] | None = None  # (first time, largest |β|) beyond the small-angle limit
        self._draw()

    def _draw_scale(self) -> None:
        """Ticks on the indicator's dial at β = G Ω for round input rates Ω (every half of |Ω₀|, up to ±2|Ω₀| and at
        most ±60° of deflection). Only the two ends ("+1 rad/s") and zero are numbered, in full-size type: numbers on
        every other tick of so short an arc ran into each other and could not be read. The end numbers run outwards
        from their ticks (left of the left one, right of the right one), so they stay clear of the "0"; where the
        ends would fall within MIN_SCALE_RAD of zero (a small gain) the scale is widened to four round steps
        reaching at least that far, and the needle then uses only the middle of it."""
        for node in self.scale_nodes:
            node.remove()
        scene = self.client.scene
        full_rate = abs(self.params["input_rate_rad_s"]) or 1.0
        step = nice_step(0.5 * full_rate)
        count = int(min(2.0 * full_rate / step, MAX_SCALE_RAD / (abs(self._gain) * step), 8))
        if count * step * abs(self._gain) < MIN_SCALE_RAD:
            step, count = (
                nice_step(MIN_SCALE_RAD / (4.0 * abs(self._gain))),
                4,
            )  # at most 2 MIN_SCALE_RAD < MAX_SCALE_RAD
        segments: list[list[np.ndarray]] = []
        nodes: list[viser.SceneNodeHandle] = []
        for k in range(-count, count + 1):
            beta = self._gain * k * step
            direction = needle_direction(beta)  # where the needle's tip stops for this Ω
            segments.append(
                [
                    DIAL_FACE_X_VECTOR + direction * NEEDLE_LENGTH,
                    DIAL_FACE_X_VECTOR + direction * (NEEDLE_LENGTH + 0.07),
                ]
            )
            if k in (-count, 0, count):
                rate = k * step
                text = "0" if k == 0 else f"{rate:+g} rad/s".replace("-", "−")
                anchor: LabelAnchor = (
                    "bottom-center" if k == 0 else ("bottom-left" if direction[1] < 0.0 else "bottom-right")
                )  # −y is the screen's right
                nodes.append(
                    scene.add_label(
                        f"/indicator/scale/t{k + count}",
                        text,
                        position=tuple(DIAL_FACE_X_VECTOR + direction * (NEEDLE_LENGTH + SCALE_LABEL_GAP)),
                        anchor=anchor,
                        font_screen_scale=SCALE_LABEL_SIZE,
                    )
                )
        nodes.append(
            scene.add_line_segments(
                "/indicator/scale/ticks",
                np.asarray(segments, np.float32),
                (40, 40, 40),
                thickness=2.0,
                thickness_units="screen",
            )
        )
        self.scale_nodes = nodes

    def demonstration(self, t_s: float) -> tuple[float, float, float, float]:
        """``(β, β̇, Ω, case angle)`` at scene time ``t_s``: the step on/off cycle or the running sine."""
        params = self.params
        if params["input_kind"] == "sine":
            response = physics.gimbal_response(params, t_s)
            return (
                float(response.beta_rad[0]),
                float(response.beta_rate_rad_s[0]),
                float(response.input_rate_rad_s[0]),
                float(physics.case_angle_rad(params, t_s)),
            )
        hold = self._hold_s
        cycle = math.floor(t_s / (2.0 * hold))
        local = t_s - 2.0 * hold * cycle
        on = physics.gimbal_response(params, local)
        beta, beta_rate = float(on.beta_rad[0]), float(on.beta_rate_rad_s[0])
        rate = params["input_rate_rad_s"]
        if local >= hold:  # the table stopped at t = hold: subtract the delayed step response
            off = physics.gimbal_response(params, local - hold)
            beta -= float(off.beta_rad[0])
            beta_rate -= float(off.beta_rate_rad_s[0])
            rate = 0.0
        angle = params["input_rate_rad_s"] * (hold * cycle + min(local, hold))
        return beta, beta_rate, rate, angle

    def _draw(self) -> None:
        beta, beta_rate, rate, angle = self.demonstration(self.t_s)
        self._state = (beta, beta_rate, rate)
        if abs(beta) > physics.SMALL_ANGLE_LIMIT_RAD:
            first = self._outside_model[0] if self._outside_model else self.t_s
            self._outside_model = (first, max(abs(beta), self._outside_model[1] if self._outside_model else 0.0))
        self.table.wxyz = np.array([math.cos(0.5 * angle), 0.0, 0.0, math.sin(0.5 * angle)])
        deflection = np.array([math.cos(0.5 * beta), math.sin(0.5 * beta), 0.0, 0.0])  # a turn of β about x
        self.gimbal.wxyz = deflection
        self.needle.wxyz = deflection  # the pickoff repeats β on the indicator
        self.rotor.wxyz = spin_quaternion(drawn_spin_angle(self.params["spin_rad_s"], self.t_s))
        params = self.params
        spin_axis = np.array([0.0, math.cos(beta), math.sin(beta)])  # gimbal y in case components
        h_vector = math.copysign(H_ARROW_LENGTH, self._h) * spin_axis
        full_rate = max(abs(params["input_rate_rad_s"]), 1e-12)
        rate_tail = RATE_ARROW_TAIL
        rate_vector = np.array([0.0, 0.0, rate / full_rate * RATE_ARROW_MAX])
        moment = -(
            params["stiffness_N_m_rad"] * beta + params["damping_N_m_s_rad"] * beta_rate
        )  # on the gimbal, about +x
        moment_scale = MOMENT_ARROW_MAX / max(abs(self._h) * full_rate, 1e-300)
        moment_tail = MOMENT_ARROW_TAIL
        moment_vector = np.array([moment * moment_scale, 0.0, 0.0])
        self.arrows.points = np.concatenate(
            [
                arrow_segments(np.zeros(3), h_vector, 1.0),
                arrow_segments(rate_tail, rate_vector, 1.0),
                arrow_segments(moment_tail, moment_vector, 1.0),
            ]
        )
        self.labels["H"].position = tuple(1.03 * h_vector)
        if self._frame % LABEL_TEXT_EVERY == 0:
            self.labels["rate"].text = f"Ω = {rate:.3g} rad/s (input axis z)"
            self.labels["moment"].text = f"spring + damper {abs(moment):.3g} N·m"
        self._frame += 1

    def readout(self) -> Readout:
        params = self.params
        beta, beta_rate, rate = self._state
        quantities = [
            Quantity("t_s", "time t", self.t_s, "s"),
            Quantity("input_rate_rad_s", "input rate Ω now", float(rate), "rad/s"),
            Quantity("beta_rad", "gimbal deflection β", float(beta), "rad"),
            Quantity("beta_deg", "gimbal deflection β", math.degrees(beta), "deg"),
            Quantity("indicated_rate_rad_s", "indicated rate β/G", float(beta / self._gain), "rad/s"),
            Quantity("steady_gain_s", "steady-state gain G = I_a ω_s/k", float(self._gain), "rad per rad/s"),
            Quantity(
                "natural_frequency_rad_s",
                "natural frequency ω_n = √(k/I_g)",
                physics.natural_frequency_rad_s(params),
                "rad/s",
            ),
            Quantity("damping_ratio", "damping ratio ζ = c/(2√(k I_g))", physics.damping_ratio(params), ""),
        ]
        if params["input_kind"] == "sine":
            ratio, lag = physics.frequency_response(params, params["input_frequency_rad_s"])
            quantities += [
                Quantity.or_text(
                    "amplitude_ratio_s",
                    "steady amplitude ratio |β|/|Ω|",
                    float(ratio),
                    "rad per rad/s",
                    "none: grows without bound",
                ),
                Quantity("phase_lag_deg", "phase lag of β behind Ω", math.degrees(lag), "deg"),
            ]
            message = (
                "Undamped and driven at its natural frequency: resonance. β = (G Ω₀/2)(sin ω_n t − ω_n t cos ω_n "
                "t) grows in proportion to t."
                if physics.resonant(params)
                else "The case rocks at the input frequency; after the start-up transient β is a sine with the "
                "gain and lag above."
            )
        else:
            quantities.append(Quantity("hold_s", "turntable runs, then rests, for", self._hold_s, "s"))
            message = ""
        if self._outside_model is not None:
            message = " ".join(m for m in (physics.small_angle_warning(*self._outside_model), message) if m)
        marks = {"damping_N_m_s_rad": [Mark(physics.critical_damping_N_m_s_rad(params), "critical (ζ = 1)")]}
        return Readout(quantities, marks=marks, message=message)
