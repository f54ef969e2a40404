"""Scene: the Foucault pendulum, integrated live in the Earth's frame, with its rosette on the floor.

Drawn in metres in the local frame (x east, y north, z up); the camera frames the
floor under the pivot, where the bob's path is traced. The grey line is the first
swing's plane; the orange line turns clockwise (north of the equator) at the
predicted Ω sin λ, and the bob's swings should follow it. The Earth's rotation is
multiplied by ``earth_rate_factor`` (labelled in the scene) so the turning shows in
minutes; the readout gives the real Earth's figures beside the scene's.
"""

from __future__ import annotations

import math

import numpy as np
import viser

from app.physics.systems.ch03 import foucault_pendulum as physics
from app.physics.systems.earth import (
    EARTH_RATE_RAD_S,
    SECONDS_PER_HOUR,
    direction_from_bearing,
    vertical_earth_rate_rad_s,
)
from app.scenes.kit import IntegratedScene, Mark, Preset, Quantity, Readout, Trail

TRAIL_CHUNK_FRAMES = 15
TRAIL_CHUNKS = 360  # 360 × 15 frames = 180 s of path at 30 Hz
FLOOR_LIFT_M = 0.002  # the path is drawn just above the floor grid


class FoucaultPendulumScene(IntegratedScene):
    id = "foucault-pendulum"
    title = "The Foucault pendulum: a swing plane that turns with the latitude"
    chapter = 3
    model = physics.FoucaultPendulum
    presets = (
        Preset(
            "paris",
            "Paris, exaggerated ×1000",
            {"latitude_deg": 48.85, "earth_rate_factor": 1000.0, "release": "from rest"},
            "Foucault's city; the rate is a thousand times the Earth's so one turn takes about two minutes.",
        ),
        Preset(
            "north-pole",
            "North Pole",
            {"latitude_deg": 90.0, "earth_rate_factor": 1000.0},
            "The plane stays fixed against the stars while the floor turns under it once a (scaled) day.",
        ),
        Preset(
            "equator",
            "Equator: no turning",
            {"latitude_deg": 0.0, "earth_rate_factor": 1000.0},
            "Ω is horizontal here: Ω sin λ = 0 and the swing plane does not turn.",
        ),
        Preset(
            "sydney",
            "Sydney (southern hemisphere)",
            {"latitude_deg": -33.87, "earth_rate_factor": 1000.0},
            "South of the equator the plane turns counterclockwise seen from above.",
        ),
        Preset(
            "through-centre",
            "Pushed through the centre",
            {"release": "from the centre", "earth_rate_factor": 1000.0},
            "Started with a push from the rest position: the rosette's loops all pass through the centre.",
        ),
        Preset(
            "real-earth",
            "Real Earth, Panthéon size",
            {"latitude_deg": 48.85, "earth_rate_factor": 1.0, "length_m": 67.0, "amplitude_m": 3.0},
            "The true rate: about 11° an hour. Nothing visible happens in a lesson, which is the point.",
        ),
    )

    def camera_view(self):
        a = max(self.params["amplitude_m"], 0.05)
        return (0.8 * a, -1.9 * a, 1.5 * a), (0.0, 0.1 * a, 0.1 * a)

    def build(self) -> None:
        scene = self.client.scene
        self.floor: viser.GridHandle | None = None
        self.compass: list = []
        self.pivot = scene.add_icosphere("/pivot", radius=0.05, color=(40, 40, 40))
        self.string = scene.add_line_segments(
            "/string", np.zeros((1, 2, 3), np.float32), (60, 60, 60), thickness=1.5, thickness_units="screen"
        )
        self.bob = scene.add_icosphere("/bob", radius=0.05, color=(190, 150, 40))
        self.first_plane = scene.add_line_segments(
            "/first_plane", np.zeros((1, 2, 3), np.float32), (150, 150, 150), thickness=2.0, thickness_units="screen"
        )
        self.predicted_plane = scene.add_line_segments(
            "/predicted_plane", np.zeros((1, 2, 3), np.float32), (240, 130, 20), thickness=3.0, thickness_units="screen"
        )
        self.predicted_label = scene.add_label(
            "/predicted_plane/label", "predicted plane (Ω sin λ)", anchor="bottom-left"
        )
        self.rate_label = scene.add_label("/rate_note", "", anchor="top-left")
        self.trail = Trail(
            scene,
            "/trail",
            color=(40, 90, 200),
            chunk_frames=TRAIL_CHUNK_FRAMES,
            max_chunks=TRAIL_CHUNKS,
            thickness=2.0,
        )

    def update(self) -> None:
        params = self.physical_params()
        self.restart()
        scene = self.client.scene
        L, a = params["length_m"], params["amplitude_m"]
        size = max(a, 0.05)
        for node in ([self.floor] if self.floor is not None else []) + self.compass:
            node.remove()
        self.floor = scene.add_grid(
            "/floor", width=3.0 * size, height=3.0 * size, cell_size=size / 4.0, section_size=size
        )
        self.compass = [
            scene.add_label(
                f"/compass/{name}", name, position=(1.35 * size * dx, 1.35 * size * dy, 0.0), anchor="center-center"
            )
            for name, dx, dy in (("N", 0, 1), ("E", 1, 0), ("S", 0, -1), ("W", -1, 0))
        ]
        self.pivot.position = (0.0, 0.0, L)
        self.pivot.scale = 0.03 * size / 0.05
        self.bob.scale = max(0.06 * size, 0.004) / 0.05
        bearing0 = params["swing_bearing_deg"]
        self._plane_half_m = 1.2 * size
        self.first_plane.points = self._plane_segment(bearing0)
        factor = params["earth_rate_factor"]
        self.rate_label.position = (-1.45 * size, 1.45 * size, 0.0)
        self.rate_label.text = (
            "real Earth rate (factor 1)" if factor == 1.0 else f"Earth's rotation EXAGGERATED ×{factor:g}"
        )
        self._bearing0 = bearing0
        self._rate = physics.clockwise_precession_rate_rad_s(params)
        self._tracker = physics.ApexTracker()
        self.trail.clear()
        self._draw()

    def _plane_segment(self, bearing_deg: float) -> np.ndarray:
        d = direction_from_bearing(bearing_deg) * self._plane_half_m
        lift = np.array([0.0, 0.0, FLOOR_LIFT_M])
        return np.array([[lift - d, lift + d]], np.float32)

    def _draw(self) -> None:
        y = self.run.y
        L = self.params["length_m"]
        self.bob.position = y[0:3]
        self.string.points = np.array([[[0.0, 0.0, L], y[0:3]]], np.float32)
        predicted = self._bearing0 + math.degrees(self._rate * self.run.t_s)
        segment = self._plane_segment(predicted)
        self.predicted_plane.points = segment
        self.predicted_label.position = segment[0, 1]
        self._tracker.add(self.run.t_s, float(y[0]), float(y[1]))
        self.trail.add(np.array([y[0], y[1], FLOOR_LIFT_M], np.float32))

    def readout(self) -> Readout:
        params = self.physical_params()
        factor = params["earth_rate_factor"]
        real_rate = vertical_earth_rate_rad_s(params["latitude_deg"], EARTH_RATE_RAD_S)
        real_deg_h = math.degrees(real_rate) * SECONDS_PER_HOUR
        measured = self._tracker.clockwise_rate_rad_s()
        omega0 = physics.natural_frequency_rad_s(params)
        quantities = [
            Quantity("t_s", "t", self.run.t_s, "s"),
            Quantity("real_rate_deg_h", "Ω sin λ, real Earth (clockwise from above)", real_deg_h, "deg/h"),
            Quantity(
                "real_full_turn_h",
                "one full turn of the plane, real Earth",
                360.0 / abs(real_deg_h) if abs(real_rate) > 1e-12 else None,
                "h",
                "" if abs(real_rate) > 1e-12 else "never (equator)",
            ),
            Quantity(
                "scene_rate_deg_s", f"Ω sin λ in this scene (Earth rate ×{factor:g})", math.degrees(self._rate), "deg/s"
            ),
            Quantity(
                "measured_rate_deg_s",
                "measured from the swings' turning points",
                math.degrees(measured) if measured is not None else None,
                "deg/s",
                "" if measured is not None else "waiting for 3 turning points",
            ),
            Quantity(
                "measured_real_deg_h",
                f"measured ÷ {factor:g} (as on the real Earth)",
                math.degrees(measured) * SECONDS_PER_HOUR / factor if measured is not None else None,
                "deg/h",
                "" if measured is not None else "waiting",
            ),
            Quantity("turning_points", "turning points measured", self._tracker.count, ""),
            Quantity("period_s", "swing period 2π/ω₀", 2.0 * math.pi / omega0, "s"),
        ]
        expected = physics.expected_clockwise_rate_rad_s(params)
        lag = 1.0 - expected / self._rate if self._rate != 0.0 else 0.0
        quantities.append(
            Quantity(
                "expected_rate_deg_s", "expected with the finite-swing correction", math.degrees(expected), "deg/s"
            )
        )
        message = (
            "Positive rates turn clockwise seen from above. A finite swing turns its own ellipse a little "
            f"(Airy): here the plane should lag Ω sin λ by about {100 * lag:.2g}%."
        )
        if self.status:
            message = self.status
        return Readout(quantities, marks={"earth_rate_factor": [Mark(1.0, "real Earth")]}, message=message)
