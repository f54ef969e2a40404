"""Scene: the Earth's spin axis sweeping its precession cone, with the averaged torques drawn.

World frame: the ecliptic is the XY plane, +Z its north normal, the Earth at the
origin (display units: Earth radius 1). The figure axis s(t) = (sin ε sin φ,
−sin ε cos φ, cos ε) with φ = −Ω t (westward, Ω from the worked example); time
is scaled by ``years_per_second``. The Sun's and the Moon's orbits are drawn as
rings: at these time scales each goes round thousands of times a second, and the
precession comes from their averaged pull, which is what a ring represents.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.core.parameters import Parameter
from app.physics.systems.ch10 import equinox_precession as physics
from app.scenes.kit import Quantity, Readout, Scene, arrow_segments, circle_segments, quaternion_z_to

FLATTENING_SHOWN = 0.1  # the real 1/298 is invisible; the label says so
AXIS_HALF_LENGTH = 1.9
SUN_RING_RADIUS = 5.0
MOON_RING_RADIUS = 3.0
START_YEAR_CE = 2000.0


def turns_and_degrees(angle_deg: float) -> str:
    """An angle of several turns in words, e.g. 725.29 → "2 turns + 5.29°" (under one turn: "5.29°")."""
    turns, rest = divmod(angle_deg, 360.0)
    if round(rest, 2) >= 360.0:  # 719.999… shows as 2 turns + 0.00°, not 1 turn + 360.00°
        turns, rest = turns + 1, 0.0
    if turns < 1:
        return f"{rest:.2f}°"
    return f"{turns:.0f} turn{'s' if turns >= 2 else ''} + {rest:.2f}°"


def ellipsoid_mesh(*, equatorial_radius: float, polar_radius: float, rings: int = 24, segments: int = 48):
    """Vertices and faces of an oblate spheroid about +Z (display units)."""
    polar = np.linspace(0.0, math.pi, rings + 1)
    azimuth = np.linspace(0.0, 2.0 * math.pi, segments, endpoint=False)
    vertices = np.array(
        [
            [
                equatorial_radius * math.sin(p) * math.cos(a),
                equatorial_radius * math.sin(p) * math.sin(a),
                polar_radius * math.cos(p),
            ]
            for p in polar
            for a in azimuth
        ],
        dtype=np.float32,
    )
    faces = []
    for i in range(rings):
        for j in range(segments):
            a, b = i * segments + j, i * segments + (j + 1) % segments
            c, d = a + segments, b + segments
            faces += [(a, c, d), (a, d, b)]
    return vertices, np.asarray(faces, dtype=np.uint32)


class EquinoxPrecessionScene(Scene):
    id = "equinox-precession"
    title = "Precession of the equinoxes"
    chapter = 10
    animated = True
    example = physics.EXAMPLE
    controls = (
        Parameter(
            "years_per_second",
            "yr/s",
            2000.0,
            10.0,
            20000.0,
            "Time scale of the animation: simulated years per second",
            "time scale",
            scale="log",
        ),
    )
    camera_position = (3.4, -4.4, 3.6)
    camera_look_at = (0.0, 0.0, 1.1)

    def build(self) -> None:
        scene = self.client.scene
        scene.add_grid(
            "/ecliptic", width=12.0, height=12.0, cell_size=0.5, section_size=2.0, plane="xy", position=(0.0, 0.0, 0.0)
        )
        scene.add_label("/ecliptic/label", "ecliptic plane", position=(5.5, -5.5, 0.0), anchor="center-left")
        scene.add_line_segments(
            "/ecliptic_normal",
            np.array([[[0, 0, 0], [0, 0, 3.4]]], np.float32),
            (120, 120, 120),
            thickness=2.0,
            thickness_units="screen",
        )
        scene.add_line_segments(
            "/sun_ring",
            circle_segments(radius=SUN_RING_RADIUS, segments=160),
            (235, 180, 40),
            thickness=2.0,
            thickness_units="screen",
        )
        scene.add_icosphere("/sun", radius=0.35, color=(250, 200, 50), position=(SUN_RING_RADIUS, 0.0, 0.0))
        scene.add_label(
            "/labels/sun",
            "Sun's yearly path (averaged: a ring)",
            position=(SUN_RING_RADIUS, 0.0, 0.5),
            anchor="center-left",
        )
        self.moon_ring = scene.add_line_segments(
            "/moon_ring", np.zeros((1, 2, 3), np.float32), (190, 190, 210), thickness=2.0, thickness_units="screen"
        )
        self.moon_label = scene.add_label("/moon_ring/label", "Moon's monthly path (averaged)", anchor="center-left")
        self.earth = scene.add_frame("/earth", show_axes=False)
        vertices, faces = ellipsoid_mesh(equatorial_radius=1.0, polar_radius=1.0 - FLATTENING_SHOWN)
        scene.add_mesh_simple("/earth/body", vertices, faces, color=(60, 110, 190), flat_shading=False)
        scene.add_line_segments(
            "/earth/equator",
            circle_segments(radius=1.003, segments=96),
            (240, 240, 240),
            thickness=2.0,
            thickness_units="screen",
        )
        scene.add_line_segments(
            "/earth/axis",
            np.array([[[0, 0, -AXIS_HALF_LENGTH], [0, 0, AXIS_HALF_LENGTH]]], np.float32),
            (30, 30, 30),
            thickness=3.0,
            thickness_units="screen",
        )
        scene.add_label(
            "/earth/flattening",
            f"flattening shown ×{FLATTENING_SHOWN * 298:.0f}",
            position=(0.0, 1.05, -0.4),
            anchor="center-left",
        )
        self.cone = scene.add_line_segments(
            "/cone", np.zeros((1, 2, 3), np.float32), (200, 160, 200), thickness=1.0, thickness_units="screen"
        )
        self.pole_path = scene.add_line_segments(
            "/pole_path", np.zeros((1, 2, 3), np.float32), (200, 70, 200), thickness=3.0, thickness_units="screen"
        )
        self.arrows = scene.add_arrows(
            "/vectors",
            np.zeros((2, 2, 3), np.float32),
            np.array([[40, 100, 220], [220, 50, 40]], np.uint8),
            shaft_radius=0.03,
            head_radius=0.08,
            head_length=0.18,
        )
        self.momentum_label = scene.add_label("/vectors/L", "L = Cω s (spin)", anchor="center-left")
        self.torque_label = scene.add_label("/vectors/tau", "τ = dL/dt (averaged)", anchor="top-left")
        self.star_today = scene.add_icosphere("/star_today", radius=0.06, color=(255, 255, 255))
        self.star_today_label = scene.add_label(
            "/labels/star_today", "Polaris: pole in 2000 CE", anchor="bottom-center"
        )
        self.star_later = scene.add_icosphere("/star_later", radius=0.06, color=(255, 255, 255))
        self.star_later_label = scene.add_label(
            "/labels/star_later", "near Vega: pole ≈ 14 000 CE", anchor="bottom-center"
        )
        self.time_label = scene.add_label("/time", "", position=(-2.5, 2.5, 3.2), anchor="bottom-left")

    def update(self) -> None:
        inputs = {p.name: self.params[p.name] for p in physics.INPUTS.parameters}
        self.result = physics.equinox_precession(inputs)
        self.obliquity = math.radians(self.params["obliquity_deg"])
        self.t_s = 0.0
        tip = AXIS_HALF_LENGTH * 1.6
        radius, height = tip * math.sin(self.obliquity), tip * math.cos(self.obliquity)
        circle = circle_segments(radius=radius, center=(0.0, 0.0, height), segments=120)
        self.pole_path.points = circle
        spokes = np.zeros((12, 2, 3), np.float32)
        spokes[:, 1, :] = circle[::10, 0, :]
        self.cone.points = spokes
        inclination = math.radians(self.params["moon_inclination_deg"])
        moon_normal = (0.0, -math.sin(inclination), math.cos(inclination))
        self.moon_ring.points = circle_segments(radius=MOON_RING_RADIUS, normal=moon_normal, segments=120)
        self.moon_label.position = (-MOON_RING_RADIUS, 0.0, 0.0)
        self.star_today.position = tuple(self.axis(0.0) * tip)
        self.star_today_label.position = tuple(self.axis(0.0) * tip + np.array([0.0, 0.0, 0.12]))
        self.star_later.position = tuple(self.axis(math.pi) * tip)
        self.star_later_label.position = tuple(self.axis(math.pi) * tip + np.array([0.0, 0.0, 0.12]))
        self._draw()

    def axis(self, phi: float) -> np.ndarray:
        """Unit figure axis at precession angle φ (rad, ecliptic frame)."""
        s = math.sin(self.obliquity)
        return np.array([s * math.sin(phi), -s * math.cos(phi), math.cos(self.obliquity)])

    def precession_angle_rad(self) -> float:
        """φ since 2000 CE: negative, the axis turns westward."""
        return -self.result.rate_rad_s * self.elapsed_years * physics.JULIAN_YEAR_S

    @property
    def elapsed_years(self) -> float:
        """Years since 2000 CE: ``years_per_second`` for each second of the animation's clock ``t_s``.

        The motion's ``t_s`` is that clock, not the 10¹⁰ s of simulated time the readout shows, so the time
        controls and a share link (0–600 s) reach every era of the cycle.
        """
        return self.t_s * self.params["years_per_second"]

    def _draw(self) -> None:
        phi = self.precession_angle_rad()
        s = self.axis(phi)
        # The Earth's daily spin is not drawn (it would turn hundreds of thousands of times a second here).
        self.earth.wxyz = quaternion_z_to(s)
        torque_direction = -np.cross([0.0, 0.0, 1.0], s)
        torque_length = 1.2 * math.sin(self.obliquity) / max(math.sin(math.radians(23.439)), 1e-9)
        tails = np.array([[0.0, 0.0, 0.0], s * AXIS_HALF_LENGTH * 1.6])
        norm = np.linalg.norm(torque_direction)
        vectors = np.array(
            [
                s * AXIS_HALF_LENGTH * 1.6,
                torque_direction / norm * min(torque_length, 1.5) if norm > 1e-12 else np.zeros(3),
            ]
        )
        self.arrows.points = arrow_segments(tails, vectors, 1.0)
        self.momentum_label.position = tuple(s * AXIS_HALF_LENGTH * 0.75 + np.array([0.1, 0.0, 0.0]))
        self.torque_label.position = tuple(tails[1] + vectors[1] * 1.05)
        year = START_YEAR_CE + self.elapsed_years
        era = f"{year:,.0f} CE" if year >= 0.5 else f"{1 - year:,.0f} BCE"
        self.time_label.text = f"{era}   axis turned {turns_and_degrees(math.degrees(-phi))} westward"

    def readout(self) -> Readout:
        result = self.result
        share = result.sun_rate_rad_s / result.rate_rad_s if result.rate_rad_s > 0 else 0.0
        turned_deg = math.degrees(-self.precession_angle_rad())  # unwrapped: whole turns count
        return Readout(
            [
                Quantity("rate_arcsec_per_year", "precession rate", result.rate_arcsec_per_year, "arcsec/yr"),
                Quantity("period_years", "period of one full cone", result.period_years, "yr"),
                Quantity("sun_share", "Sun's share", share, ""),
                Quantity("moon_share", "Moon's share", 1.0 - share if result.rate_rad_s > 0 else 0.0, ""),
                Quantity("t_s", "simulated time since 2000 CE", self.elapsed_years * physics.JULIAN_YEAR_S, "s"),
                Quantity("years_elapsed", "years since 2000 CE", self.elapsed_years, "yr"),
                Quantity(
                    "precession_angle_deg",
                    "axis turned since 2000 CE",
                    turned_deg,
                    "deg",
                    turns_and_degrees(turned_deg) if turned_deg >= 360.0 else "",
                ),
            ],
            message=" ".join(
                m
                for m in (
                    physics.averaged_model_warning(self.params, result),
                    f"Time runs {self.params['years_per_second']:g} years per second; the daily spin and the "
                    "yearly orbit are far too fast to show and appear as their averages.",
                )
                if m
            ),
        )
