"""Scene: a free gyroscope in two gimbals on a turning vehicle (section 10.3).

The world frame is inertial (+Z up). The vehicle (a grey platform with a yellow
nose on its roll axis x) turns at its constant rate; the outer ring (orange)
pivots on it about the vehicle's z axis, the inner ring (teal) on the outer ring
about the ring's x axis, and the rotor (blue) spins in the inner ring. The ring
angles come from :mod:`app.physics.systems.ch10.free_gyroscope` (closed form): the
rotor's axis never turns in the world. Arrows (world frame): the spin angular
momentum ``H`` (blue, fixed length) and the vehicle's angular velocity (green,
direction only, drawn off to one side; its size is in the label). The rotor's spin is drawn slowed down
to at most :data:`~app.scenes.kit.rotor.DRAWN_SPIN_RAD_S`; the ring and rotor meshes come from
:mod:`app.scenes.kit.rotor`.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.math.rotations import quaternion_from_axis_angle
from app.physics.systems.ch10 import free_gyroscope as physics
from app.scenes.kit import Preset, Quantity, Readout, Scene, arrow_segments
from app.scenes.kit.rotor import add_rotor, drawn_spin_angle, ring_mesh, spin_quaternion

OUTER_RADIUS = 0.8  # display units (the scene is drawn at an arbitrary size)
INNER_RADIUS = 0.62
ROTOR_RADIUS = 0.4
H_ARROW_LENGTH = 1.25
RATE_ARROW_LENGTH = 0.8
#: World-fixed places (display units) for the inertial axes and the vehicle-rate arrow, clear of the rings.
INERTIAL_AXES_AT = (1.6, 1.1, -1.45)
RATE_ARROW_TAIL = (-1.55, -0.7, -1.05)

#: What a gimbal rate reads where gimbal lock leaves it undefined.
LOCKED = "undefined (gimbal lock)"

COLOR_H = (40, 100, 220)
COLOR_RATE = (40, 160, 70)
COLOR_TORQUE = (220, 50, 40)
COLOR_PRECESSION = (240, 150, 30)


class FreeGyroscopeScene(Scene):
    id = "free-gyroscope"
    title = "The free gyroscope: a rotor in two gimbals on a turning vehicle"
    chapter = 10
    model = physics.FreeGyroscope
    animated = True
    camera_position = (2.6, -1.35, 0.95)  # mostly from +x: the default spin axis (+y) is seen side-on
    camera_look_at = (0.0, 0.1, -0.15)
    presets = (
        Preset(
            "yaw",
            "Yaw turn",
            {"vehicle_rate_rad_s": [0.0, 0.0, 0.3], "inner_gimbal0_deg": 0.0},
            "The vehicle turns about its vertical axis: only the outer ring moves, by the heading change.",
        ),
        Preset(
            "roll-lock",
            "Roll into gimbal lock",
            {"vehicle_rate_rad_s": [0.3, 0.0, 0.0], "inner_gimbal0_deg": 0.0, "outer_gimbal0_deg": 0.0},
            "Rolling the vehicle tips the inner ring until, after a quarter turn, both rings lie in one plane.",
        ),
        Preset(
            "tumble",
            "Tumbling vehicle",
            {"vehicle_rate_rad_s": [0.3, 0.2, 0.4], "inner_gimbal0_deg": 15.0, "outer_gimbal0_deg": 25.0},
            "Roll, pitch and yaw at once: both rings move, the rotor's axis still never turns.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.t_s = 0.0
        scene.add_grid("/ground", width=5.0, height=5.0, cell_size=0.25, section_size=1.0, position=(0.0, 0.0, -1.45))
        scene.add_frame("/inertial", axes_length=0.3, axes_radius=0.012, position=INERTIAL_AXES_AT)
        scene.add_label("/inertial/label", "inertial axes", position=(0.0, 0.0, 0.34), anchor="bottom-center")
        self.vehicle = scene.add_frame("/vehicle", show_axes=False)
        self._build_vehicle(scene)
        self.outer = scene.add_frame("/vehicle/outer", show_axes=False)
        vertices, faces = ring_mesh(OUTER_RADIUS, 0.03, normal="y")
        scene.add_mesh_simple("/vehicle/outer/ring", vertices, faces, color=(225, 135, 45), flat_shading=False)
        for sign in (-1.0, 1.0):  # the inner ring's pivots on the outer ring's x axis
            scene.add_cylinder(
                f"/vehicle/outer/pin{int(sign)}",
                radius=0.025,
                height=OUTER_RADIUS - INNER_RADIUS + 0.04,
                color=(120, 120, 120),
                position=(sign * 0.5 * (OUTER_RADIUS + INNER_RADIUS), 0.0, 0.0),
                wxyz=quaternion_from_axis_angle(np.array([0.0, 1.0, 0.0]), 0.5 * math.pi),
            )
        self.inner = scene.add_frame("/vehicle/outer/inner", show_axes=False)
        vertices, faces = ring_mesh(INNER_RADIUS, 0.026, normal="z")
        scene.add_mesh_simple("/vehicle/outer/inner/ring", vertices, faces, color=(40, 160, 160), flat_shading=False)
        self.rotor = add_rotor(
            scene, "/vehicle/outer/inner/rotor", radius=ROTOR_RADIUS, thickness=0.12, axle_length=2 * INNER_RADIUS
        )
        self.arrows = scene.add_arrows(
            "/vectors",
            np.zeros((2, 2, 3), np.float32),
            np.array([COLOR_H, COLOR_RATE], np.uint8),
            shaft_radius=0.018,
            head_radius=0.045,
            head_length=0.1,
        )
        self.h_label = scene.add_label("/vectors/H", "", anchor="bottom-left")
        self.rate_label = scene.add_label("/vectors/rate", "", anchor="bottom-center")
        self.lock_label = scene.add_label(
            "/lock",
            "GIMBAL LOCK: both rings in one plane",
            position=(0.0, 0.0, 1.15),
            anchor="bottom-center",
            visible=False,
        )

    def _build_vehicle(self, scene) -> None:
        """Platform, nose marker on the roll axis, bottom pedestal and a yoke to the top pivot (vehicle frame)."""
        base_z = -OUTER_RADIUS - 0.25
        scene.add_box(
            "/vehicle/platform", color=(150, 150, 155), dimensions=(2.2, 1.3, 0.08), position=(0.0, 0.0, base_z)
        )
        scene.add_box(
            "/vehicle/nose",
            color=(235, 200, 40),
            dimensions=(0.3, 0.3, 0.09),
            position=(1.2, 0.0, base_z),
            wxyz=quaternion_from_axis_angle(np.array([0.0, 0.0, 1.0]), 0.25 * math.pi),
        )
        scene.add_label("/vehicle/nose/label", "vehicle x", position=(0.1, 0.0, 0.0), anchor="center-left")
        scene.add_cylinder(
            "/vehicle/pedestal", radius=0.035, height=0.25, color=(110, 110, 110), position=(0.0, 0.0, base_z + 0.125)
        )
        post_x, top_z = -1.0, OUTER_RADIUS + 0.12
        scene.add_box(
            "/vehicle/post",
            color=(110, 110, 110),
            dimensions=(0.06, 0.06, top_z - base_z),
            position=(post_x, 0.0, 0.5 * (top_z + base_z)),
        )
        scene.add_box(
            "/vehicle/beam",
            color=(110, 110, 110),
            dimensions=(-post_x, 0.06, 0.06),
            position=(0.5 * post_x, 0.0, top_z),
        )
        scene.add_cylinder(
            "/vehicle/top_pin", radius=0.03, height=0.12, color=(110, 110, 110), position=(0.0, 0.0, top_z - 0.06)
        )

    def update(self) -> None:
        params = self.params
        self.t_s = 0.0
        omega = physics.vehicle_rate(params)
        rate = float(np.linalg.norm(omega))
        s_world = physics.spin_axis_inertial(params)
        rate_direction = omega / rate if rate > 0.0 else np.zeros(3)
        # Both vectors are fixed in the world: H because no torque reaches the rotor, ω because the
        # vehicle turns about a fixed axis. Drawn once per parameter change.
        h_vector = math.copysign(H_ARROW_LENGTH, params["spin_rad_s"]) * s_world
        rate_tail = np.array(RATE_ARROW_TAIL)
        self.arrows.points = np.concatenate(
            [
                arrow_segments(np.zeros(3), h_vector, 1.0),
                arrow_segments(rate_tail, RATE_ARROW_LENGTH * rate_direction, 1.0),
            ]
        )
        h = physics.angular_momentum_N_m_s(params)
        self.h_label.text = f"H = {h:.3g} N·m·s"
        self.h_label.position = tuple(1.03 * h_vector)
        self.rate_label.text = f"ω vehicle = {rate:.3g} rad/s" if rate > 0.0 else "vehicle not turning"
        self.rate_label.anchor = "bottom-center" if rate_direction[2] >= 0.0 else "top-center"
        self.rate_label.position = tuple(rate_tail + 1.03 * RATE_ARROW_LENGTH * rate_direction)
        self._draw()

    def _draw(self) -> None:
        motion = physics.gimbal_motion(self.params, self.t_s)
        self._motion = motion
        self.vehicle.wxyz = motion.q_world_vehicle[0]
        outer = float(motion.outer_rad[0]) if math.isfinite(motion.outer_rad[0]) else 0.0
        self.outer.wxyz = np.array([math.cos(0.5 * outer), 0.0, 0.0, math.sin(0.5 * outer)])
        inner = float(motion.inner_rad[0])
        self.inner.wxyz = np.array([math.cos(0.5 * inner), math.sin(0.5 * inner), 0.0, 0.0])
        self.rotor.wxyz = spin_quaternion(drawn_spin_angle(self.params["spin_rad_s"], self.t_s))
        locked = float(motion.lock_angle_rad[0]) < math.radians(physics.LOCK_WARNING_DEG)
        if self.lock_label.visible != locked:
            self.lock_label.visible = locked

    def readout(self) -> Readout:
        motion = self._motion
        params = self.params
        lock_deg = math.degrees(float(motion.lock_angle_rad[0]))
        outer = motion.outer_rad[0]
        rate = float(np.linalg.norm(physics.vehicle_rate(params)))
        quantities = [
            Quantity("t_s", "time t", self.t_s, "s"),
            Quantity("vehicle_turn_deg", "vehicle has turned", math.degrees(rate * self.t_s), "deg"),
            Quantity.or_text("outer_gimbal_deg", "outer gimbal φ_o", math.degrees(outer), "deg", "undefined"),
            Quantity("inner_gimbal_deg", "inner gimbal φ_i", math.degrees(float(motion.inner_rad[0])), "deg"),
            Quantity.or_text(
                "outer_gimbal_rate_rad_s", "outer gimbal rate φ̇_o", float(motion.outer_rate_rad_s[0]), "rad/s", LOCKED
            ),
            Quantity.or_text(
                "inner_gimbal_rate_rad_s", "inner gimbal rate φ̇_i", float(motion.inner_rate_rad_s[0]), "rad/s", LOCKED
            ),
            Quantity("lock_angle_deg", "spin axis to outer gimbal axis", lock_deg, "deg"),
            Quantity(
                "angular_momentum_N_m_s", "spin angular momentum H", physics.angular_momentum_N_m_s(params), "N·m·s"
            ),
            Quantity("torque_on_rotor_N_m", "torque reaching the rotor", 0.0, "N·m"),
            Quantity("axis_drift_rad_s", "drift of the spin axis", 0.0, "rad/s"),
        ]
        message = ""
        if lock_deg < physics.LOCK_WARNING_DEG:
            needed = float(motion.outer_rate_rad_s[0])
            needed_text = f"{abs(needed):.3g} rad/s" if math.isfinite(needed) else "an unbounded rate"
            message = (
                f"Near gimbal lock: the spin axis is {lock_deg:.1f}° from the outer gimbal axis, so the two "
                "rings are almost "
                f"in one plane; the outer ring must turn at {needed_text} to keep the rotor free of torque."
            )
        return Readout(quantities, message=message)
