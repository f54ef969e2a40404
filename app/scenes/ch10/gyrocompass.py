"""Scene: the gyrocompass, its spin axis held level and free in azimuth on the rotating Earth.

World frame = the local site frame: x east, y north, z up (a compass card marks
N, E, S, W). The housing (orange ring on a vertical shaft) turns about the
vertical by the azimuth α of the spin axis; the rotor (blue) spins in it. The
reduced equation of :mod:`app.physics.systems.ch10.gyrocompass` is integrated live
(:class:`~app.scenes.kit.integrated.IntegratedScene`), and because the north-seeking
swing takes minutes the scene runs ``time_scale`` simulated seconds per second
shown. Arrows: spin angular momentum ``H`` (blue, fixed length), the Earth's
angular velocity (green, direction only, with its horizontal part ``Ω cos λ``),
the azimuth rate ``α̇`` of the housing (orange, about the vertical, scaled to its
largest value), the north-seeking gyroscopic moment ``−K sin α`` (red, about the
vertical) and the bearing torque that keeps the axis level (purple, horizontal;
each torque scaled to its own largest value).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import cast

import numpy as np

from app.physics.core.parameters import Parameter
from app.physics.solvers import LiveRun
from app.physics.systems.ch10 import gyrocompass as physics
from app.scenes.ch10.free_gyroscope import COLOR_H, COLOR_PRECESSION, COLOR_RATE, COLOR_TORQUE
from app.scenes.kit import FRAME_DT_S, IntegratedScene, LabelAnchor, Preset, Quantity, Readout, arrow_segments
from app.scenes.kit.rotor import add_rotor, drawn_spin_angle, ring_mesh, spin_quaternion

CARD_RADIUS = 1.3
HOUSING_RADIUS = 0.72
ROTOR_RADIUS = 0.45
H_ARROW_LENGTH = 1.15
EARTH_ARROW_LENGTH = 0.9
RATE_ARROW_MAX = 0.6
TORQUE_ARROW_MAX = 0.7
EARTH_ARROW_TAIL = np.array([-0.5, -1.95, -0.74])  # south of the card, clear of the housing
MOMENT_ARROW_TAIL = np.array([0.5, -0.85, -0.74])  # on the card's south-east quarter, in front of the rotor
COLOR_LEVELLING = (150, 70, 190)
COLOR_EARTH_HORIZONTAL = (130, 200, 140)

#: Label texts (numbers) are refreshed every this many frames (5 Hz): each assignment is sent to the browser.
LABEL_TEXT_EVERY = 6

TIME_SCALE = Parameter(
    "time_scale",
    "s/s",
    10.0,
    1.0,
    2000.0,
    "Simulated seconds shown per second of wall-clock time (the north-seeking swing takes minutes)",
    "time scale",
    scale="log",
)


@dataclass
class ScaledLiveRun(LiveRun):
    """A :class:`LiveRun` that advances ``time_scale`` simulated seconds per second it is asked for."""

    time_scale: float = field(default=1.0)

    def advance(self, frame_dt_s: float) -> bool:
        return super().advance(frame_dt_s * self.time_scale)


class GyrocompassScene(IntegratedScene):
    id = "gyrocompass"
    title = "The gyrocompass: a level spin axis that seeks north"
    chapter = 10
    model = physics.Gyrocompass
    controls = (TIME_SCALE,)
    camera_position = (2.45, -1.2, 1.35)  # from the east-south-east: an axis near north is seen side-on
    camera_look_at = (0.0, 0.1, -0.15)
    presets = (
        Preset(
            "swing",
            "Undamped swing",
            {"damping_N_m_s_rad": 0.0, "alpha0_deg": 40.0, "latitude_deg": 45.0},
            "Released 40° east of north: the axis swings through north to 40° west and back, for ever.",
        ),
        Preset(
            "damped",
            "Damped compass",
            {"damping_N_m_s_rad": 0.01, "alpha0_deg": 60.0, "latitude_deg": 45.0},
            "A little damping about the vertical: the swing dies away and the axis settles on north.",
        ),
        Preset(
            "high-latitude",
            "Near the pole",
            {"latitude_deg": 80.0, "damping_N_m_s_rad": 0.0, "alpha0_deg": 40.0},
            "At 80° latitude Ω cos λ is small: the compass is weak and slow.",
        ),
        Preset(
            "large",
            "Released 170° off",
            {"alpha0_deg": 170.0, "damping_N_m_s_rad": 0.0, "latitude_deg": 45.0},
            "Almost pointing south: the swing lingers near the top and the period is far longer than the "
            "small-angle one.",
        ),
    )

    # -- integration with a time scale -----------------------------------------------------
    @property
    def time_scale(self) -> float:
        return float(self.params[TIME_SCALE.name])

    @classmethod
    def frame_dt_for(cls, params) -> float:
        """Each displayed frame covers ``time_scale`` frames of simulated time."""
        return FRAME_DT_S * float(params[TIME_SCALE.name])

    def new_run(self, system, integrator, y0) -> ScaledLiveRun:
        return ScaledLiveRun(system, integrator, y0, time_scale=self.time_scale)

    def describe(self, integrator) -> str:
        return f"{integrator.describe(self.frame_dt_s)}, {self.time_scale:g}× real time"

    # -- drawing ---------------------------------------------------------------------------
    def build(self) -> None:
        scene = self.client.scene
        scene.add_cylinder(
            "/card",
            radius=CARD_RADIUS,
            height=0.02,
            color=(235, 232, 220),
            position=(0.0, 0.0, -0.76),
            radial_segments=64,
        )
        ticks = []
        for k in range(36):
            a = math.radians(10 * k)
            inner = CARD_RADIUS - (0.16 if k % 9 == 0 else 0.08)
            ticks.append(
                [
                    [inner * math.sin(a), inner * math.cos(a), -0.745],
                    [CARD_RADIUS * math.sin(a), CARD_RADIUS * math.cos(a), -0.745],
                ]
            )
        scene.add_line_segments(
            "/card/ticks", np.asarray(ticks, np.float32), (60, 60, 60), thickness=2.0, thickness_units="screen"
        )
        for text, (x, y) in {"N": (0, 1), "E": (1, 0), "S": (0, -1), "W": (-1, 0)}.items():
            scene.add_label(
                f"/card/{text}",
                text,
                position=(1.1 * CARD_RADIUS * x, 1.1 * CARD_RADIUS * y, -0.74),
                anchor="center-center",
                font_screen_scale=1.4,
            )
        scene.add_cylinder("/shaft", radius=0.03, height=1.75, color=(110, 110, 110), position=(0.0, 0.0, 0.11))
        self.housing = scene.add_frame("/housing", show_axes=False)
        vertices, faces = ring_mesh(
            HOUSING_RADIUS, 0.03, normal="x"
        )  # the ring's plane holds the spin axis (y) and the vertical
        scene.add_mesh_simple("/housing/ring", vertices, faces, color=(225, 135, 45), flat_shading=False)
        self.rotor = add_rotor(
            scene, "/housing/rotor", radius=ROTOR_RADIUS, thickness=0.14, axle_length=2 * HOUSING_RADIUS
        )
        self.arrows = scene.add_arrows(
            "/vectors",
            np.zeros((6, 2, 3), np.float32),
            np.array(
                [COLOR_H, COLOR_RATE, COLOR_EARTH_HORIZONTAL, COLOR_PRECESSION, COLOR_TORQUE, COLOR_LEVELLING], np.uint8
            ),
            shaft_radius=0.016,
            head_radius=0.04,
            head_length=0.09,
        )
        self.labels = {
            name: scene.add_label(f"/vectors/{name}", "", anchor=cast(LabelAnchor, anchor))
            for name, anchor in (
                ("H", "bottom-left"),
                ("earth", "bottom-right"),
                ("earth_h", "top-left"),
                ("rate", "bottom-left"),
                ("moment", "top-center"),
                ("level", "bottom-left"),
            )
        }

    def update(self) -> None:
        params = self.physical_params()
        self.restart()
        lam = math.radians(params["latitude_deg"])
        omega = params["earth_rate_rad_s"]
        self._k = physics.restoring_moment_N_m(params)
        self._h = physics.spin_momentum_N_m_s(params)
        energy = float(physics.swing_energy_J(params, self.run.y[0], self.run.y[1]))
        inertia = params["vertical_inertia_kg_m2"]
        # Largest azimuth rate the swing can reach (all its energy kinetic), and the largest moments.
        self._rate_max = max(math.sqrt(2.0 * energy / inertia), 1e-12)
        self._moment_max = max(abs(self._k), 1e-300)
        self._level_max = max(abs(self._h) * (abs(omega * math.sin(lam)) + self._rate_max), 1e-300)
        earth = np.array([0.0, math.cos(lam), math.sin(lam)])
        self._earth_segments = np.concatenate(
            [
                arrow_segments(EARTH_ARROW_TAIL, EARTH_ARROW_LENGTH * earth, 1.0),
                arrow_segments(EARTH_ARROW_TAIL, EARTH_ARROW_LENGTH * earth * [0, 1, 0], 1.0),
            ]
        )
        self.labels["earth"].text = f"Ω Earth = {omega:.4g} rad/s"
        self.labels["earth"].position = tuple(EARTH_ARROW_TAIL + 1.04 * EARTH_ARROW_LENGTH * earth)
        self.labels["earth_h"].text = f"Ω cos λ = {omega * math.cos(lam):.3g} rad/s (north)"
        self.labels["earth_h"].position = tuple(
            EARTH_ARROW_TAIL + np.array([0.03, EARTH_ARROW_LENGTH * math.cos(lam), 0.0])
        )
        self.labels["H"].text = f"H = {abs(self._h):.3g} N·m·s"
        self.labels["rate"].position = (0.05, 0.0, 1.0)
        self.labels["moment"].position = tuple(MOMENT_ARROW_TAIL + np.array([0.0, 0.0, -0.03]))
        self._frame = 0
        self._draw()

    def _draw(self) -> None:
        params = self.physical_params()
        alpha, alpha_rate = float(self.run.y[0]), float(self.run.y[1])
        lam = math.radians(params["latitude_deg"])
        self.housing.wxyz = np.array(
            [math.cos(-0.5 * alpha), 0.0, 0.0, math.sin(-0.5 * alpha)]
        )  # a turn of −α about up
        self.rotor.wxyz = spin_quaternion(drawn_spin_angle(self.params["spin_rad_s"], self.run.t_s / self.time_scale))
        axis = np.array([math.sin(alpha), math.cos(alpha), 0.0])
        across = np.array([-math.cos(alpha), math.sin(alpha), 0.0])  # up × axis
        h_vector = math.copysign(H_ARROW_LENGTH, self._h) * axis
        rate_vector = -alpha_rate * np.array([0.0, 0.0, 1.0])  # α grows toward east: a turn about −z
        moment = -self._k * math.sin(alpha)  # about −z as well (it drives α̈)
        level = self._h * (params["earth_rate_rad_s"] * math.sin(lam) - alpha_rate)
        # Moments are free vectors: the α̇ and levelling arrows start at the top of the shaft and ring,
        # the gyroscopic moment on the card in front of the rotor, so none hides inside it.
        top, ring_top, bottom = np.array([0.0, 0.0, 0.95]), np.array([0.0, 0.0, HOUSING_RADIUS]), MOMENT_ARROW_TAIL
        segments = np.concatenate(
            [
                arrow_segments(np.zeros(3), h_vector, 1.0),
                self._earth_segments,
                arrow_segments(top, rate_vector * RATE_ARROW_MAX / self._rate_max, 1.0),
                arrow_segments(bottom, -moment * np.array([0.0, 0.0, 1.0]) * TORQUE_ARROW_MAX / self._moment_max, 1.0),
                arrow_segments(ring_top, level * across * TORQUE_ARROW_MAX / self._level_max, 1.0),
            ]
        )
        self.arrows.points = segments
        self.labels["H"].position = tuple(1.03 * h_vector)
        self.labels["level"].position = tuple(segments[5, 1] + 0.05 * (segments[5, 1] - segments[5, 0]))
        if self._frame % LABEL_TEXT_EVERY == 0:
            self.labels["rate"].text = f"α̇ = {alpha_rate:.3g} rad/s"
            self.labels["moment"].text = f"gyroscopic moment {abs(moment):.3g} N·m"
            self.labels["level"].text = f"levelling torque {abs(level):.3g} N·m"
        self._frame += 1

    def readout(self) -> Readout:
        params = self.physical_params()
        alpha, alpha_rate = float(self.run.y[0]), float(self.run.y[1])
        amplitude = physics.amplitude_rad(params)
        period = (
            physics.large_amplitude_period_s(params, amplitude)
            if amplitude is not None and amplitude < math.pi
            else None
        )
        quantities = [
            Quantity("t_s", "simulated time t", self.run.t_s, "s"),
            Quantity("time_scale", "time scale", self.time_scale, "simulated s per s"),
            Quantity(
                "alpha_deg",
                "azimuth α of the spin axis (east of north)",
                math.degrees(math.remainder(alpha, 2 * math.pi)),
                "deg",
            ),
            Quantity("alpha_rate_rad_s", "azimuth rate α̇", alpha_rate, "rad/s"),
            Quantity("horizontal_earth_rate_rad_s", "Ω cos λ", physics.horizontal_earth_rate_rad_s(params), "rad/s"),
            Quantity("restoring_moment_N_m", "K = I_a ω_s Ω cos λ", physics.restoring_moment_N_m(params), "N·m"),
            Quantity(
                "small_angle_period_s", "small-swing period 2π√(I_t/K)", physics.small_angle_period_s(params), "s"
            ),
            Quantity.or_text("swing_period_s", "period of this swing (elliptic)", period, "s", "goes right round"),
            Quantity("damping_ratio", "damping ratio ζ", physics.damping_ratio(params), ""),
            Quantity(
                "spin_to_swing_ratio",
                "spin rate / swing rate ω_s/ω_n",
                abs(params["spin_rad_s"]) / physics.natural_frequency_rad_s(params),
                "",
            ),
            Quantity(
                "full_model_steps_per_period",
                "RK4 steps per period if the spin were integrated",
                physics.full_model_steps_per_period(params),
                "",
            ),
        ]
        return Readout(quantities, message=self.status)
