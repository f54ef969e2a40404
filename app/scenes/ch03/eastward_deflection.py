"""Scene: a body dropped from a tower on the rotating Earth lands east of the plumb line.

Drawn in metres in the local frame (x east, y north, z up). The deflection is a
few millimetres against a height of a hundred metres, so the path's sideways
deviation from where the body would go if the Earth did not turn is drawn
multiplied by a round factor N, stated in the scene and the readout; heights and
the throw itself are drawn true to scale.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.systems.ch03 import eastward_deflection as physics
from app.physics.systems.earth import EARTH_RATE_RAD_S
from app.scenes.kit import Preset, Quantity, Readout, Scene

PATH_SAMPLES = 240
PAUSE_AT_LANDING_S = 1.5
DEVIATION_ON_SCREEN = 0.12  # the largest drawn deviation, as a fraction of the scene's size
MAX_EXAGGERATION = 1e6


def _round_factor(value: float) -> float:
    """The largest 1, 2 or 5 × 10^k not above ``value`` (at least 1)."""
    if value <= 1.0:
        return 1.0
    exponent = math.floor(math.log10(value))
    for mantissa in (5.0, 2.0, 1.0):
        if mantissa * 10.0**exponent <= value:
            return mantissa * 10.0**exponent
    return 10.0**exponent


def _landing_text(deflection_m: np.ndarray) -> str:
    """'lands 15.52 mm east, 0.0018 mm south' with the directions named by sign."""
    east_mm, north_mm = 1000.0 * float(deflection_m[0]), 1000.0 * float(deflection_m[1])
    return (
        f"lands {abs(east_mm):.2f} mm {'east' if east_mm >= 0 else 'west'}, "
        f"{abs(north_mm):.4f} mm {'north' if north_mm > 0 else 'south'}"
    )


class EastwardDeflectionScene(Scene):
    id = "eastward-deflection"
    title = "Dropped from a tower: the eastward deflection"
    chapter = 3
    model = physics.EastwardDeflection
    animated = True
    presets = (
        Preset(
            "drop-100m",
            "Drop 100 m at 45°",
            {"height_m": 100.0, "latitude_deg": 45.0, "launch_velocity_m_s": [0.0, 0.0, 0.0]},
            "About 15 mm east; the second-order southward part is about 2 µm.",
        ),
        Preset(
            "reich-mine",
            "Mine shaft, 158 m at 51° N",
            {"height_m": 158.0, "latitude_deg": 50.9, "launch_velocity_m_s": [0.0, 0.0, 0.0]},
            "The depth of the Freiberg mine shaft where Ferdinand Reich measured the deflection in 1831; this "
            "model gives 27.5 mm.",
        ),
        Preset(
            "equator",
            "Equator, 100 m",
            {"height_m": 100.0, "latitude_deg": 0.0, "launch_velocity_m_s": [0.0, 0.0, 0.0]},
            "cos λ = 1: the largest eastward deflection, and no southward part.",
        ),
        Preset(
            "pole",
            "North Pole, 100 m",
            {"height_m": 100.0, "latitude_deg": 90.0, "launch_velocity_m_s": [0.0, 0.0, 0.0]},
            "Ω is vertical, parallel to the fall: no deflection at all.",
        ),
        Preset(
            "thrown-up",
            "Thrown straight up",
            {"height_m": 1.0, "latitude_deg": 45.0, "launch_velocity_m_s": [0.0, 0.0, 40.0]},
            "Going up it is pushed west, coming down east; the westward push wins and it lands west.",
        ),
    )

    def camera_view(self):
        lo, hi = self._bounds
        centre = 0.5 * (lo + hi)
        size = float(max(np.max(hi - lo), 1.0))
        return tuple(centre + size * np.array([0.45, -0.85, 0.1])), tuple(centre)

    def build(self) -> None:
        scene = self.client.scene
        self.t_s = 0.0
        self._bounds = (np.zeros(3), np.ones(3))
        self._static: list = []
        self.ball = scene.add_icosphere("/ball", radius=1.0, color=(210, 60, 40))
        self.caption = scene.add_label("/caption", "", anchor="bottom-left")

    def update(self) -> None:
        params = self.params
        self.flight = physics.Flight.from_params(params)
        self.t_land = self.flight.landing_time_s()
        t = np.linspace(0.0, self.t_land, PATH_SAMPLES)
        actual, _ = self.flight.state(t)
        plain = self.flight.position_without_rotation(t)
        h = params["height_m"]
        extent = max(h, float(np.max(np.abs(plain[:, :2]))), float(np.max(plain[:, 2])))
        deviation = actual - plain
        largest = float(np.max(np.linalg.norm(deviation[:, :2], axis=-1)))
        # At the poles the deviation is round-off (~1e-16 of the height): draw it unenlarged rather than blow that up.
        resolvable = largest > 1e-12 * extent
        self.exaggeration = (
            min(_round_factor(DEVIATION_ON_SCREEN * extent / largest), MAX_EXAGGERATION) if resolvable else 1.0
        )
        # Drawn path: the non-rotating path plus N × the deviation from it (heights kept true).
        drawn = plain + self.exaggeration * deviation
        self._drawn_t = t
        self._drawn = drawn
        self.deflection = self.flight.deflection()
        self.deflection_first = self.flight.deflection(order=1)
        self.deflection_second = self.flight.deflection(order=2)
        for node in self._static:
            node.remove()
        self._static = self._draw_static(h, extent, plain, drawn)
        self.ball.scale = 0.012 * extent
        lo = np.minimum(drawn.min(axis=0), [-0.3 * extent, -0.3 * extent, 0.0])
        hi = np.maximum(drawn.max(axis=0), [0.15 * extent, 0.1 * extent, h])
        self._bounds = (lo, hi)
        self.caption.position = (lo[0], 0.0, hi[2] * 1.08)
        self.caption.text = f"sideways deviation drawn ×{self.exaggeration:g}; heights true to scale"
        self.t_s = 0.0
        self._draw()

    def _draw_static(self, h: float, extent: float, plain: np.ndarray, drawn: np.ndarray) -> list:
        scene = self.client.scene
        width = 0.08 * extent
        nodes = [
            scene.add_grid(
                "/ground", width=1.2 * extent, height=1.2 * extent, cell_size=extent / 20.0, section_size=extent / 4.0
            ),
            scene.add_box(
                "/tower",
                color=(185, 175, 160),
                dimensions=(width, width, h),
                position=(-0.5 * width - 0.06 * extent, 0.0, 0.5 * h),
            ),
            scene.add_line_segments(
                "/arm",
                np.array([[[-0.06 * extent, 0.0, h], [0.0, 0.0, h]]], np.float32),
                (90, 90, 90),
                thickness=3.0,
                thickness_units="screen",
            ),
            scene.add_line_segments(
                "/plumb",
                np.array([[[0.0, 0.0, h], [0.0, 0.0, 0.0]]], np.float32),
                (60, 60, 60),
                thickness=1.5,
                thickness_units="screen",
            ),
            scene.add_label("/plumb_label", "foot of the plumb line", position=(0.0, 0.0, 0.0), anchor="top-right"),
            scene.add_icosphere("/plumb_foot", radius=0.008 * extent, color=(90, 90, 90)),
            scene.add_line_segments(
                "/path",
                np.stack([drawn[:-1], drawn[1:]], axis=1).astype(np.float32),
                (210, 60, 40),
                thickness=2.5,
                thickness_units="screen",
            ),
            scene.add_icosphere("/landing", radius=0.01 * extent, color=(210, 60, 40), position=drawn[-1]),
            scene.add_label(
                "/landing_label",
                _landing_text(self.deflection),
                position=drawn[-1] + np.array([0.02 * extent, 0.0, 0.0]),
                anchor="center-left",
            ),
        ]
        if np.max(np.abs(plain[:, :2])) > 1e-9:  # a throw: show the path the body would take on a non-turning Earth
            nodes.append(
                scene.add_line_segments(
                    "/plain_path",
                    np.stack([plain[:-1], plain[1:]], axis=1).astype(np.float32),
                    (150, 150, 150),
                    thickness=1.0,
                    thickness_units="screen",
                )
            )
        # A small compass at the tower's foot: east and north, each a tenth of the scene.
        base, arm = np.array([-0.3 * extent, -0.3 * extent, 0.0]), 0.1 * extent
        nodes.append(
            scene.add_arrows(
                "/compass",
                np.array([[base, base + [arm, 0.0, 0.0]], [base, base + [0.0, arm, 0.0]]], np.float32),
                np.array([(200, 70, 70), (70, 140, 70)], np.uint8),
                shaft_radius=0.003 * extent,
                head_radius=0.008 * extent,
                head_length=0.02 * extent,
            )
        )
        nodes.append(
            scene.add_label("/compass_east", "east", position=base + [1.1 * arm, 0.0, 0.0], anchor="center-left")
        )
        nodes.append(
            scene.add_label("/compass_north", "north", position=base + [0.0, 1.1 * arm, 0.0], anchor="bottom-center")
        )
        return nodes

    def _draw(self) -> None:
        t = min(self.t_s, self.t_land)
        i = min(int(np.searchsorted(self._drawn_t, t, side="right")) - 1, len(self._drawn_t) - 2)
        blend = (t - self._drawn_t[i]) / (self._drawn_t[i + 1] - self._drawn_t[i])
        self.ball.position = (1.0 - blend) * self._drawn[i] + blend * self._drawn[i + 1]

    def step_motion(self, dt_s: float) -> bool:
        """The drop replays from t = 0 a moment after landing."""
        self.t_s += dt_s
        if self.t_s > self.t_land + PAUSE_AT_LANDING_S:
            self.t_s = 0.0
        return True

    def readout(self) -> Readout:
        params = self.params
        lam = params["latitude_deg"]
        dropped = not any(params["launch_velocity_m_s"])
        quantities = [
            Quantity("t_s", "time since release", min(self.t_s, self.t_land), "s"),
            Quantity("time_of_fall_s", "time of flight (exact)", float(self.t_land), "s"),
            Quantity(
                "time_without_rotation_s",
                "time of flight without the Earth's rotation",
                float(self.flight.fall_time_without_rotation_s()),
                "s",
            ),
            Quantity("east_mm", "east deflection (exact)", 1000.0 * float(self.deflection[0]), "mm"),
            Quantity(
                "east_first_order_mm",
                "east, first order in Ω" + (" (⅓ Ω g t³ cos λ)" if dropped else ""),
                1000.0 * float(self.deflection_first[0]),
                "mm",
            ),
            Quantity("south_mm", "south deflection (exact, uniform g)", -1000.0 * float(self.deflection[1]), "mm"),
            Quantity(
                "south_second_order_mm",
                "south, second order in Ω" + (" (⅙ Ω² g t⁴ sin λ cos λ)" if dropped else ""),
                -1000.0 * float(self.deflection_second[1]),
                "mm",
            ),
            Quantity("exaggeration", "sideways deviation drawn enlarged by", self.exaggeration, "×"),
            Quantity("earth_rate", "Earth's rotation rate Ω", EARTH_RATE_RAD_S, "rad/s"),
        ]
        message = (
            f"At latitude {lam:g}° the Earth turns about the local vertical at Ω sin λ and about the north axis "
            "at Ω cos λ; "
            "only the north part acts on a vertical fall, which is why the deflection goes as cos λ."
        )
        return Readout(quantities, message=message)
