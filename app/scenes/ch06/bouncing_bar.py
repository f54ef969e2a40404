"""Scene: a bar dropped on the floor at an angle, bouncing through a sequence of impacts.

Drawn in metres on the world frame (+Z up, the bar in the xz plane, seen from −y).
The floor is a grid at z = 0; ends A (orange) and B (blue) leave trails; at every
impact an arrow of the floor's impulse on each struck end flashes for
:data:`FLASH_S` (length proportional to the impulse, the largest possible at
the first impact drawn as a quarter of the bar). The physics, the impacts and
the ledger of lost energy are :mod:`app.physics.systems.ch06.bouncing_bar`.
"""

from __future__ import annotations

import math

import numpy as np
import viser

from app.physics.systems.ch06 import bouncing_bar as physics
from app.scenes.kit import (
    IntegratedScene,
    Preset,
    Quantity,
    Readout,
    Trail,
    arrow_segments,
)

FLASH_S = 0.35  # s an impulse arrow stays after its impact
TRAIL_CHUNK_FRAMES = 4
TRAIL_CHUNKS = 60  # 60 × 4 frames = 8 s of trail at 30 Hz
BAR_THICKNESS_FRACTION = 0.03  # of the bar's length


def _bar_wxyz(theta_rad: float) -> tuple[float, float, float, float]:
    """Rotation (wxyz) taking the bar's local +x to (cos θ, 0, sin θ): a turn of −θ about +y."""
    return (math.cos(-0.5 * theta_rad), 0.0, math.sin(-0.5 * theta_rad), 0.0)


def _wrapped_deg(theta_rad: float) -> float:
    """θ in degrees within (−180°, 180°]: the bar's direction from end A to end B, whatever turns it has made."""
    return math.degrees(math.remainder(float(theta_rad), 2.0 * math.pi))


class BouncingBarScene(IntegratedScene):
    id = "bouncing-bar"
    title = "A bar bouncing on the floor: impacts in sequence"
    chapter = 6
    model = physics.BouncingBar
    presets = (
        Preset(
            "flat",
            "Flat landing",
            {"angle0_deg": 0.0, "restitution": 0.6, "friction_coefficient": 0.3},
            "Both ends strike at once: equal impulses, no spin, straight up and down.",
        ),
        Preset(
            "tilted-45",
            "45°",
            {"angle0_deg": 45.0, "restitution": 0.6, "friction_coefficient": 0.3},
            "The lower end strikes first and the bar starts to spin.",
        ),
        Preset(
            "nearly-vertical",
            "Nearly vertical",
            {"angle0_deg": 80.0, "restitution": 0.6, "friction_coefficient": 0.3},
            "An end strike almost through the centre: little spin at first, then the bar topples.",
        ),
        Preset(
            "frictionless",
            "Frictionless",
            {"angle0_deg": 30.0, "restitution": 0.6, "friction_coefficient": 0.0},
            "No tangential impulse: the centre of mass only moves up and down.",
        ),
        Preset(
            "rough",
            "Rough floor",
            {"angle0_deg": 30.0, "restitution": 0.6, "friction_coefficient": 1.0},
            "Friction grips the striking end: the impacts stick and the bar is thrown sideways.",
        ),
    )

    def camera_view(self):
        height = self.params["drop_height_m"]
        length = self.params["length_m"]
        span = max(height + 0.5 * length, 1.2 * length, 0.5)
        return (0.0, -1.45 * span, 0.6 * span), (0.0, 0.0, 0.42 * span)

    def build(self) -> None:
        scene = self.client.scene
        self.floor = scene.add_grid(
            "/floor", width=12.0, height=4.0, cell_size=0.1, section_size=0.5, plane="xy", position=(0.0, 0.0, 0.0)
        )
        self.bar = scene.add_frame("/bar", show_axes=False)
        self.bar_body: viser.BoxHandle | None = None
        self.end_markers = [
            scene.add_icosphere("/bar/end_a", radius=0.02, color=(235, 130, 30)),
            scene.add_icosphere("/bar/end_b", radius=0.02, color=(40, 110, 220)),
        ]
        self.impulse_arrows = scene.add_arrows(
            "/impulses",
            np.zeros((2, 2, 3), np.float32),
            np.array([[200, 40, 40], [200, 40, 40]], np.uint8),
            shaft_radius=0.012,
            head_radius=0.03,
            head_length=0.06,
        )
        self.label = scene.add_label("/readout", "", anchor="bottom-left")
        self.trails = [
            Trail(
                scene,
                "/trail_a",
                color=(235, 130, 30),
                chunk_frames=TRAIL_CHUNK_FRAMES,
                max_chunks=TRAIL_CHUNKS,
                thickness=2.0,
            ),
            Trail(
                scene,
                "/trail_b",
                color=(40, 110, 220),
                chunk_frames=TRAIL_CHUNK_FRAMES,
                max_chunks=TRAIL_CHUNKS,
                thickness=2.0,
            ),
        ]

    def update(self) -> None:
        params = self.physical_params()
        self.restart()
        length = params["length_m"]
        thickness = BAR_THICKNESS_FRACTION * length
        if self.bar_body is not None:
            self.bar_body.remove()
        self.bar_body = self.client.scene.add_box(
            "/bar/body", color=(90, 90, 100), dimensions=(length, thickness, thickness)
        )
        for marker, sign in zip(self.end_markers, (-1.0, 1.0)):
            marker.position = (sign * 0.5 * length, 0.0, 0.0)
            marker.scale = max(thickness, 0.004) / 0.02
        self.impulse_arrows.shaft_radius = 0.4 * thickness
        self.impulse_arrows.head_radius = thickness
        self.impulse_arrows.head_length = 2.0 * thickness
        # The largest impulse possible at the first impact: stopping and reversing m √(2 g h₀) at e = 1.
        first_speed = math.sqrt(2.0 * params["g_m_s2"] * params["drop_height_m"])
        self._impulse_scale = 0.25 * length / max(2.0 * params["mass_kg"] * first_speed, 1e-12)
        self.label.position = (-0.5 * length - 0.2, 0.0, params["drop_height_m"] + 0.5 * length + 0.1)
        for trail in self.trails:
            trail.clear()
        self._draw()

    def _draw(self) -> None:
        y = self.run.y
        length = self.params["length_m"]
        self.bar.position = (float(y[physics.X]), 0.0, float(y[physics.Z]))
        self.bar.wxyz = _bar_wxyz(float(y[physics.THETA]))
        end_a, end_b = (np.array([e[0, 0], 0.0, e[0, 1]]) for e in physics.end_positions_m(y, length))
        self.trails[0].add(end_a)
        self.trails[1].add(end_b)
        flashing = 0.0 <= self.run.t_s - y[physics.LAST_T] <= FLASH_S and y[physics.IMPACTS] > 0
        impulses = np.zeros((2, 3))
        if flashing:
            impulses[0] = (y[physics.PT_A], 0.0, y[physics.PN_A])
            impulses[1] = (y[physics.PT_B], 0.0, y[physics.PN_B])
        # Between flashes (and for an end not struck) there is no impulse: hide the arrows.
        self.impulse_arrows.visible = bool(flashing and np.any(impulses != 0.0))
        self.impulse_arrows.points = arrow_segments(np.array([end_a, end_b]), impulses, self._impulse_scale)
        self.label.text = (
            f"t = {self.run.t_s:5.2f} s   θ = {_wrapped_deg(y[physics.THETA]):6.1f}°   "
            f"impacts {int(y[physics.IMPACTS])}   {physics.MODE_NAMES[float(y[physics.MODE])]}"
        )

    def advance(self, dt_s: float) -> None:
        if self.step_motion(dt_s):
            self._draw()
        else:
            self.label.text = self.status

    def readout(self) -> Readout:
        y = self.run.y
        params = self.physical_params()
        p = physics.parameter_array(params)
        end_a, end_b = physics.end_positions_m(y, params["length_m"])
        mode = float(y[physics.MODE])
        impacts = int(y[physics.IMPACTS])
        quantities = [
            Quantity("t_s", "time t", self.run.t_s, "s"),
            Quantity(
                "angle_deg", "angle of the bar from the floor θ (end A to end B)", _wrapped_deg(y[physics.THETA]), "deg"
            ),
            Quantity("centre_height_m", "height of the centre of mass", y[physics.Z], "m"),
            Quantity("end_a_height_m", "height of end A (orange)", end_a[0, 1], "m"),
            Quantity("end_b_height_m", "height of end B (blue)", end_b[0, 1], "m"),
            Quantity("angular_velocity_rad_s", "angular velocity θ̇", y[physics.OMEGA], "rad/s"),
            Quantity("impact_count", "impacts so far", impacts, "impacts"),
            Quantity.or_text(
                "last_energy_loss_J",
                "energy lost at the last impact",
                y[physics.LAST_LOSS] if impacts else None,
                "J",
                "no impact yet",
            ),
            Quantity.word("slip_state", "slip at the last impact", physics.SLIP_NAMES[int(y[physics.SLIP])]),
            Quantity("energy_J", "kinetic + potential energy", float(physics.mechanical_energy_J(y, p)), "J"),
            Quantity("energy_lost_J", "energy lost so far (impacts, settling, sliding)", y[physics.LOST], "J"),
            Quantity.word("mode", "state of the model", physics.MODE_NAMES[mode]),
        ]
        message = physics.mode_message(params, y)
        return Readout(quantities, message=message)
