"""Scene: the unbalanced rotor, with the bearing reactions drawn as arrows that turn with it (section 6.1).

World frame (m, +Z up): the shaft runs along +X from bearing A (origin) to bearing B at X = L, gravity
along −Z. The rotor frame (``/rotor``) turns about X by the spin angle φ; in it the disk (blue) sits at
``(a, e, 0)`` with its axis tilted by the skew towards rotor z, its centre of mass is the red dot G and a
red line marks the direction of the eccentricity. Faint circles show the two correction planes at radius
ρ; with the correction fitted, the two masses are orange spheres. Arrows (world frame) at A and B are the
forces of the bearings on the shaft (red A, purple B), scaled so the largest over a turn is 0.45 of the
span. The spin is drawn slowed to at most ``DRAWN_SPIN_RAD_S``; the forces are those at the true speed.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.math.rotations.axis_angle import quaternion_from_axis_angle
from app.physics.systems.ch06 import unbalanced_rotor as physics
from app.scenes.kit import (
    Preset,
    Quantity,
    Readout,
    Scene,
    arrow_segments,
    circle_segments,
    quaternion_z_to,
)
from app.scenes.kit.rotor import DRAWN_SPIN_RAD_S, drawn_spin_angle

AXIS_X = np.array([1.0, 0.0, 0.0])
COLOR_A = (220, 50, 40)
COLOR_B = (140, 60, 200)
#: A correction mass lighter than this fraction of the disk's is "none needed" (its angle is then undefined).
NEGLIGIBLE_CORRECTION = 1e-9


class UnbalancedRotorScene(Scene):
    id = "unbalanced-rotor"
    title = "The unbalanced rotor: bearing reactions and two-plane balancing"
    chapter = 6
    model = physics.UnbalancedRotorModel
    animated = True
    slider_ranges = {
        "shaft_speed_rad_s": (-300.0, 300.0, 1.0),
        "disk_mass_kg": (0.5, 50.0, 0.5),
        "disk_radius_m": (0.05, 0.5, 0.01),
        "eccentricity_m": (0.0, 0.01, 0.0005),
        "skew_deg": (-20.0, 20.0, 0.5),
        "bearing_span_m": (0.2, 2.0, 0.01),
        "disk_position_m": (0.0, 2.0, 0.01),
        "g_m_s2": (0.0, 20.0, 0.01),
        "correction_plane_1_m": (0.0, 2.0, 0.01),
        "correction_plane_2_m": (0.0, 2.0, 0.01),
        "correction_radius_m": (0.02, 0.5, 0.01),
    }
    presets = (
        Preset(
            "static",
            "Static imbalance",
            {"eccentricity_m": 0.002, "skew_deg": 0.0, "balanced": "off"},
            "Centre of mass 2 mm off the shaft, disk square to it: each bearing carries its beam share of m e ω² "
            "plus the weight.",
        ),
        Preset(
            "dynamic",
            "Dynamic imbalance",
            {"eccentricity_m": 0.0, "skew_deg": 3.0, "balanced": "off"},
            "Centre of mass on the shaft, disk tilted 3°: a turning couple, equal and opposite forces at A and B.",
        ),
        Preset(
            "both",
            "Both",
            {"eccentricity_m": 0.001, "skew_deg": 2.0, "balanced": "off"},
            "The general case: a static and a couple imbalance at once.",
        ),
        Preset(
            "balance-it",
            "Balance it",
            {"eccentricity_m": 0.001, "skew_deg": 2.0, "balanced": "on"},
            "Fit the two correction masses: the rotating reactions fall to zero, only the weight is left.",
        ),
        Preset(
            "weightless",
            "Balanced, no gravity",
            {"eccentricity_m": 0.001, "skew_deg": 2.0, "balanced": "on", "g_m_s2": 0.0},
            "Without gravity the balanced rotor loads its bearings not at all.",
        ),
        Preset(
            "at-rest",
            "At rest",
            {"shaft_speed_rad_s": 0.0, "eccentricity_m": 0.002, "skew_deg": 2.0, "balanced": "off"},
            "No speed: only the weight, and the drive holds the rotor against gravity's moment m g e.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.t_s = 0.0
        self.spin_angle = 0.0
        self._span = 1.0
        self.ground = scene.add_grid("/ground", width=3.0, height=3.0, cell_size=0.1, section_size=0.5)
        self.shaft = scene.add_cylinder(
            "/shaft", radius=0.01, height=1.0, color=(110, 110, 115), wxyz=quaternion_z_to(AXIS_X)
        )
        self.housings = [
            scene.add_cylinder(
                f"/bearing_{name}", radius=0.03, height=0.05, color=(60, 60, 65), wxyz=quaternion_z_to(AXIS_X)
            )
            for name in ("A", "B")
        ]
        self.pedestals = [
            scene.add_box(f"/pedestal_{name}", color=(150, 150, 155), dimensions=(0.05, 0.05, 0.2))
            for name in ("A", "B")
        ]
        self.bearing_labels = [
            scene.add_label(f"/bearing_{name}/label", name, anchor="bottom-center") for name in ("A", "B")
        ]
        self.plane_circles = scene.add_line_segments(
            "/correction_planes",
            np.zeros((1, 2, 3), np.float32),
            (230, 160, 60),
            thickness=1.5,
            thickness_units="screen",
        )
        self.rotor = scene.add_frame("/rotor", show_axes=False)
        self.disk = scene.add_cylinder("/rotor/disk", radius=0.2, height=0.01, color=(70, 120, 190), radial_segments=64)
        self.centre = scene.add_icosphere("/rotor/centre", radius=0.01, color=(220, 30, 30))
        self.centre_label = scene.add_label("/rotor/centre/label", "G", anchor="bottom-left")
        self.eccentricity_line = scene.add_line_segments(
            "/rotor/eccentricity",
            np.zeros((1, 2, 3), np.float32),
            (220, 30, 30),
            thickness=3.0,
            thickness_units="screen",
        )
        self.corrections = [
            scene.add_icosphere(f"/rotor/correction_{i}", radius=0.02, color=(240, 150, 30), visible=False)
            for i in (1, 2)
        ]
        self.arrows = scene.add_arrows(
            "/reactions",
            np.zeros((2, 2, 3), np.float32),
            np.array([COLOR_A, COLOR_B], np.uint8),
            shaft_radius=0.008,
            head_radius=0.02,
            head_length=0.04,
        )
        self.force_labels = [scene.add_label(f"/reactions/{name}", "", anchor="bottom-left") for name in ("A", "B")]
        self.legend = scene.add_label("/legend", "", anchor="top-center")

    def camera_view(self):
        L, span = self.rotor_model.disk.bearing_span_m, self._span
        return (0.5 * L - 0.45 * span, -0.9 * span, 0.45 * span), (0.5 * L, 0.0, 0.0)

    def update(self) -> None:
        self.rotor_model = physics.UnbalancedRotor.from_params(self.params)
        self.steady = self.rotor_model.steady_loads()
        disk = self.rotor_model.disk
        L, r, a, e = disk.bearing_span_m, disk.disk_radius_m, disk.disk_position_m, disk.eccentricity_m
        span = self._span = max(L, 2.5 * r)
        shaft_radius = 0.012 * span
        self.shaft.radius, self.shaft.height, self.shaft.position = shaft_radius, 1.2 * L, (0.5 * L, 0.0, 0.0)
        floor = -(r + 0.15 * span)
        self.ground.position = (0.5 * L, 0.0, floor)
        self.ground.width = self.ground.height = 2.5 * span
        self.ground.cell_size = 10 ** math.floor(math.log10(span / 4.0))
        self.ground.section_size = 5 * self.ground.cell_size
        for x, housing, pedestal, label in zip(
            (0.0, L), self.housings, self.pedestals, self.bearing_labels, strict=True
        ):
            housing.radius, housing.height, housing.position = 2.5 * shaft_radius, 0.06 * span, (x, 0.0, 0.0)
            pedestal.dimensions = (0.05 * span, 0.08 * span, -floor - 2.5 * shaft_radius)
            pedestal.position = (x, 0.0, 0.5 * (floor - 2.5 * shaft_radius))
            label.position = (0.0, 0.0, 3.0 * shaft_radius)
        # The disk in the rotor frame: centre (a, e, 0), axis (cos β, 0, sin β).
        self.disk.radius, self.disk.height = r, max(0.03 * r, 0.004 * span)
        self.disk.position, self.disk.wxyz = (a, e, 0.0), quaternion_z_to(disk.normal)
        self.centre.position = (a, e, 0.0)
        self.centre.radius = 0.018 * span
        self.centre_label.position = (0.0, 0.0, 0.03 * span)
        marker_x = a - 0.6 * self.disk.height  # just in front of the disk's face seen from A
        self.eccentricity_line.points = np.array([[[marker_x, 0.0, 0.0], [marker_x, 1.02 * r, 0.0]]], np.float32)
        correction = self.rotor_model.correction
        rho = correction.radius_m
        self.plane_circles.points = np.concatenate(
            [circle_segments(radius=rho, center=(x, 0.0, 0.0), normal=AXIS_X, segments=64) for x in correction.planes_m]
        )
        for sphere, part in zip(self.corrections, correction.parts(), strict=True):
            sphere.position, sphere.radius = tuple(part.centre_m), 0.02 * span
            sphere.visible = self.rotor_model.balanced
        # Arrow scale: the largest reaction over a turn is drawn 0.45 span long.
        turn = self.steady.at_spin_angle(np.linspace(0.0, 2.0 * math.pi, 73))
        largest = max(float(np.max(turn.bearing_A_force_N)), float(np.max(turn.bearing_B_force_N)))
        self._force_scale = 0.45 * span / largest if largest > 0.0 else 0.0
        self.arrows.shaft_radius, self.arrows.head_radius, self.arrows.head_length = (
            0.014 * span,
            0.032 * span,
            0.06 * span,
        )
        self.legend.position = (0.5 * L, 0.0, floor)  # on the floor, clear of the arrows above the shaft
        self.legend.text = "arrows: force of each bearing on the shaft (red A, purple B) · red dot G: centre of mass"
        self._draw()

    def _draw(self) -> None:
        self.spin_angle = drawn_spin_angle(self.rotor_model.shaft_speed_rad_s, self.t_s)
        self.rotor.wxyz = quaternion_from_axis_angle(AXIS_X, self.spin_angle)
        self.loads = self.steady.at_spin_angle(np.array([self.spin_angle]))
        L = self.rotor_model.disk.bearing_span_m
        tails = np.array([[0.0, 0.0, 0.0], [L, 0.0, 0.0]])
        vectors = np.array([self.loads.bearing_A_N[0], self.loads.bearing_B_N[0]])
        self.arrows.points = arrow_segments(tails, vectors, self._force_scale)
        for label, tail, vector, name in zip(self.force_labels, tails, vectors, ("A", "B"), strict=True):
            label.position = tuple(tail + self._force_scale * vector + np.array([0.0, 0.0, 0.02 * self._span]))
            label.text = f"R_{name} = {np.linalg.norm(vector):.1f} N"

    def readout(self) -> Readout:
        model, loads = self.rotor_model, self.loads
        disk, correction = model.disk, model.correction
        parts = (disk.part(),)
        quantities = [
            Quantity("t_s", "time t", self.t_s, "s"),
            Quantity("spin_angle_deg", "spin angle φ (G from +Y towards +Z)", math.degrees(self.spin_angle), "deg"),
            Quantity("bearing_A_force_N", "bearing force |R_A|", float(np.linalg.norm(loads.bearing_A_N[0])), "N"),
            Quantity("bearing_B_force_N", "bearing force |R_B|", float(np.linalg.norm(loads.bearing_B_N[0])), "N"),
            Quantity(
                "bearing_A_rotating_force_N",
                "rotating part at A (speed-dependent)",
                float(np.linalg.norm(loads.bearing_A_rotating_N[0])),
                "N",
            ),
            Quantity(
                "bearing_B_rotating_force_N",
                "rotating part at B (speed-dependent)",
                float(np.linalg.norm(loads.bearing_B_rotating_N[0])),
                "N",
            ),
            Quantity("driving_torque_Nm", "driving torque T", float(loads.driving_torque_Nm[0]), "N·m"),
            Quantity.word("imbalance_class", "imbalance", model.imbalance),
            Quantity(
                "static_imbalance_kg_m",
                "static imbalance m e (disk)",
                float(np.hypot(*physics.first_moment_kg_m(parts))),
                "kg·m",
            ),
            Quantity(
                "couple_imbalance_kg_m2",
                "couple imbalance |I_xy, I_xz| at G (disk)",
                float(np.hypot(*physics.couple_imbalance_kg_m2(parts))),
                "kg·m²",
            ),
        ]
        for index, (mass, angle) in enumerate(zip(correction.masses_kg, correction.angles_rad, strict=True), start=1):
            needed = mass > NEGLIGIBLE_CORRECTION * disk.disk_mass_kg
            quantities.append(Quantity(f"correction_mass_{index}_kg", f"correction mass {index}", float(mass), "kg"))
            quantities.append(
                Quantity.or_text(
                    f"correction_angle_{index}_deg",
                    "its angle from G's direction (about +X)",
                    math.degrees(angle) if needed else None,
                    "deg",
                    "none needed",
                )
            )
        return Readout(quantities, message=self._message())

    def _message(self) -> str:
        model, steady = self.rotor_model, self.steady
        speed = model.shaft_speed_rad_s
        torque_amplitude = steady.driving_torque_amplitude_Nm
        if torque_amplitude > 0.0:
            torque = (
                f"The drive torque is gravity's moment about the shaft, T = {torque_amplitude:.3g} N·m × cos φ: "
                "the drive must cancel it to keep the speed constant, and it averages to zero over a turn."
            )
        else:
            torque = (
                "The drive torque is zero: at constant speed, with the centre of mass on the shaft or no "
                "gravity, a rigid rotor needs none (no friction is modelled)."
            )
        if speed == 0.0:
            return "At rest: the bearings carry only the weight. " + torque
        parts = [torque]
        rotating = float(np.linalg.norm(steady.bearing_A_rotating_rotor_N))
        weight_share = steady.weight_shares_N[0]
        if rotating > weight_share > 0.0:
            parts.append(
                "At A the rotating force exceeds the weight: the reaction turns right round once a turn (a "
                "bearing with play would knock)."
            )
        if abs(speed) > DRAWN_SPIN_RAD_S:
            parts.append(
                f"The spin is drawn slowed to {DRAWN_SPIN_RAD_S:g} rad/s; the forces are those at ω = {speed:g} rad/s."
            )
        return " ".join(parts)
