"""Scene: a disk on a shaft pivoted at O, turned by its Eulerian angles φ, θ, ψ, with ω built from the three rates.

World frame +Z up, O at the origin (display units, about 1 m). Drawn: the fixed axes X, Y, Z; the
line of nodes x′ (dashed, in the XY plane) and y′ of the nutation frame; the body (shaft along body
z, a disk with spokes, body x and y axes); arcs for the three angles (φ in the XY plane from X to
the line of nodes, θ from Z to the body's z axis, ψ in the disk's plane from the line of nodes to
body x); and arrows from O: φ̇ K, then θ̇ along the line of nodes from its tip, then ψ̇ along body
z, closed by ω, and α. The angles move with constant accelerations and the motion replays from
t = 0 every :data:`CYCLE_S` seconds. Every number comes from
:mod:`app.physics.systems.ch04.eulerian_angles`.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.math.rotations import wrap_angle_rad
from app.physics.systems.ch04 import eulerian_angles as physics
from app.scenes.ch04.cycling import CyclingScene
from app.scenes.kit import Preset, Quantity, Readout, move_node, update_node
from app.scenes.kit.arrows import LabelledArrows

CYCLE_S = 8.0
SCALE_SAMPLES = 81
SHAFT_LENGTH = 1.0
DISK_RADIUS = 0.45
ARC_RADII = {"precession": 0.55, "nutation": 0.4, "spin": 0.3}
ARC_SEGMENTS = 24
RATE_COLORS = {
    "precession": (240, 140, 20),
    "nutation": (190, 60, 200),
    "spin": (20, 160, 170),
    "omega": (200, 30, 60),
    "alpha": (40, 100, 220),
}
RATE_LABELS = {"precession": "φ̇ K", "nutation": "θ̇ (line of nodes)", "spin": "ψ̇ k", "omega": "ω", "alpha": "α"}


def _components(vector: np.ndarray, axes: tuple[str, str, str]) -> str:
    """Components named by their axes, as the readout writes them: 'x +0.123, y −0.456, z +0.000'."""
    return ", ".join(f"{axis} {round(float(c), 3) + 0.0:+.3f}".replace("-", "−") for axis, c in zip(axes, vector))


def _arc(start: np.ndarray, axis: np.ndarray, angle_rad: float, radius: float) -> np.ndarray:
    """(ARC_SEGMENTS, 2, 3) segments of the arc of ``radius`` from unit vector ``start`` turned about unit ``axis``."""
    normal = np.cross(axis, start)
    angles = np.linspace(0.0, angle_rad, ARC_SEGMENTS + 1)[:, None]
    points = radius * (np.cos(angles) * start + np.sin(angles) * normal)
    return np.stack([points[:-1], points[1:]], axis=1)


class EulerianAnglesScene(CyclingScene):
    id = "eulerian-angles"
    title = "Eulerian angles: precession, nutation and spin"
    chapter = 4
    model = physics.EulerianAngleKinematics
    cycle_s = CYCLE_S
    #: Nutation-frame and body attitudes, the arrow batch, the arcs, and five arrow labels moved at 15 Hz.
    frame_message_budget = 7.0
    presets = (
        Preset(
            "steady-precession",
            "Steady precession",
            {
                "nutation_rate_rad_s": 0.0,
                "precession_acceleration_rad_s2": 0.0,
                "nutation_acceleration_rad_s2": 0.0,
                "spin_acceleration_rad_s2": 0.0,
            },
            "θ fixed, φ̇ and ψ̇ constant: ω keeps its length but turns with the line of nodes, so α = φ̇K × ω is "
            "not zero.",
        ),
        Preset(
            "nutation-only",
            "Nutation only",
            {"precession_rate_rad_s": 0.0, "spin_rate_rad_s": 0.0, "nutation_rate_rad_s": 0.5},
            "Only θ changes: ω lies along the line of nodes.",
        ),
        Preset(
            "singular",
            "At θ = 0",
            {"nutation_deg": 0.0, "nutation_rate_rad_s": 0.0, "nutation_acceleration_rad_s2": 0.0},
            "The spin axis on Z: φ and ψ turn about one line, and only φ̇ + ψ̇ can be read from ω.",
        ),
        Preset(
            "through-singular",
            "Passing θ = 0",
            {"nutation_deg": 20.0, "nutation_rate_rad_s": -0.4, "nutation_acceleration_rad_s2": 0.0},
            "θ runs down through 0 at t ≈ 0.87 s: ω stays smooth, the angles' description does not.",
        ),
        Preset(
            "spinning-up",
            "Spinning up",
            {"spin_acceleration_rad_s2": 3.0, "nutation_rate_rad_s": 0.0},
            "ψ̈ adds ψ̈ k to α.",
        ),
    )

    def camera_view(self):
        return (1.45, -2.0, 1.35), (0.0, 0.0, 0.5)

    def build(self) -> None:
        scene = self.client.scene
        self.t_s = 0.0
        scene.add_grid("/ground", width=3.0, height=3.0, cell_size=0.1, section_size=0.5, position=(0.0, 0.0, -0.002))
        fixed = np.array([[(0, 0, 0), (1.3, 0, 0)], [(0, 0, 0), (0, 1.3, 0)], [(0, 0, 0), (0, 0, 1.6)]], np.float32)
        scene.add_line_segments("/fixed_axes", fixed, (120, 120, 130), thickness=2.0, thickness_units="screen")
        for name, position in (("X", (1.35, 0, 0)), ("Y", (0, 1.35, 0)), ("Z", (0, 0, 1.65))):
            scene.add_label(f"/fixed_labels/{name}", name, position=position, anchor="center-left")
        # The nutation frame x′y′z′: x′ the line of nodes (both ways, dashed), y′ thin; z′ is the body's z.
        self.nutation = scene.add_frame("/nutation", show_axes=False)
        dashes = np.linspace(-1.25, 1.25, 26)
        scene.add_line_segments(
            "/nutation/line_of_nodes",
            np.array([[(a, 0, 0), (a + 0.06, 0, 0)] for a in dashes], np.float32),
            (190, 60, 200),
            thickness=2.5,
            thickness_units="screen",
        )
        scene.add_line_segments(
            "/nutation/y_prime",
            np.array([[(0, 0, 0), (0, 0.8, 0)]], np.float32),
            (190, 60, 200),
            thickness=1.0,
            thickness_units="screen",
        )
        scene.add_label("/nutation/line_of_nodes_label", "x′ line of nodes", position=(1.3, 0, 0), anchor="center-left")
        scene.add_label("/nutation/y_prime_label", "y′", position=(0, 0.85, 0), anchor="center-left")
        scene.add_label(
            "/nutation/phi_label", "φ", position=(ARC_RADII["precession"] + 0.03, 0.0, 0.05), anchor="bottom-left"
        )
        scene.add_label(
            "/nutation/theta_label", "θ", position=(0.0, 0.0, ARC_RADII["nutation"] + 0.05), anchor="bottom-right"
        )
        # The body: shaft along z from O to the disk's centre, the disk, body x and y.
        self.body = scene.add_frame("/body", show_axes=False)
        scene.add_line_segments(
            "/body/shaft",
            np.array([[(0, 0, 0), (0, 0, SHAFT_LENGTH)]], np.float32),
            (70, 70, 80),
            thickness=4.0,
            thickness_units="screen",
        )
        scene.add_cylinder(
            "/body/disk",
            radius=DISK_RADIUS,
            height=0.02,
            color=(120, 170, 220),
            opacity=0.55,
            position=(0, 0, SHAFT_LENGTH),
        )
        axes = np.array(
            [
                [(0, 0, SHAFT_LENGTH), (0.6, 0, SHAFT_LENGTH)],
                [(0, 0, SHAFT_LENGTH), (0, 0.6, SHAFT_LENGTH)],
                [(0, 0, SHAFT_LENGTH), (0, 0, SHAFT_LENGTH + 0.35)],
            ],
            np.float32,
        )
        colors = np.array([[[220, 40, 40]] * 2, [[40, 160, 60]] * 2, [[40, 80, 220]] * 2], np.uint8)
        scene.add_line_segments("/body/axes", axes, colors, thickness=3.0, thickness_units="screen")
        for name, tip in (
            ("x", (0.63, 0, SHAFT_LENGTH)),
            ("y", (0, 0.63, SHAFT_LENGTH)),
            ("z", (0, 0, SHAFT_LENGTH + 0.38)),
        ):
            scene.add_label(f"/body/label_{name}", name, position=tip, anchor="center-left")
        scene.add_label(
            "/body/psi_label", "ψ", position=(ARC_RADII["spin"] + 0.03, 0.0, SHAFT_LENGTH), anchor="top-left"
        )
        self.arcs = scene.add_line_segments(
            "/angle_arcs",
            np.zeros((3 * ARC_SEGMENTS, 2, 3), np.float32),
            np.repeat(
                np.array([RATE_COLORS[k] for k in ("precession", "nutation", "spin")], np.uint8), ARC_SEGMENTS, axis=0
            )[:, None, :].repeat(2, axis=1),
            thickness=2.5,
            thickness_units="screen",
        )
        self.arrows = LabelledArrows(scene, "/rates", RATE_COLORS, RATE_LABELS)
        self.arrows.set_style(shaft_radius=0.012, head_radius=0.032, head_length=0.06)
        self.legend = scene.add_label(
            "/legend", "", position=(0.3, -1.8, 0.0), anchor="top-center", font_screen_scale=0.85
        )

    def update(self) -> None:
        self.motion = physics.EulerianAngleMotion.from_params(self.params)
        whole = self.motion.angles.kinematics(np.linspace(0.0, CYCLE_S, SCALE_SAMPLES))
        rates_sum = np.abs(whole.rates_rad_s).sum(axis=-1)  # the tip-to-tail chain is at most this long
        self.omega_scale = float(f"{1.3 / max(float(rates_sum.max()), 1e-9):.2g}")
        self.alpha_scale = float(
            f"{0.9 / max(float(np.linalg.norm(whole.alpha_world_rad_s2, axis=-1).max()), 1e-9):.2g}"
        )
        self.legend.text = (
            f"ω = φ̇K + θ̇i′ + ψ̇k, tip to tail from O · 1 rad/s ↦ {self.omega_scale:g} · α: 1 "
            f"rad/s² ↦ {self.alpha_scale:g}"
        )
        self.t_s = 0.0
        self._draw(move_labels=True)

    def _draw(self, *, move_labels: bool = True) -> None:
        state = self.motion.at(np.array([self.t_s]))
        self._state = state
        k = state.kinematics
        move_node(self.nutation, wxyz=state.nutation_frame_wxyz[0])
        move_node(self.body, wxyz=k.q_world_body[0])
        K, nodes, spin_axis = k.turn_axes_world[0]
        rates = k.rates_rad_s[0]
        phi, theta, psi = (float(a) for a in wrap_angle_rad(k.angles_rad[0]))
        arcs = np.concatenate(
            [
                _arc(np.array([1.0, 0.0, 0.0]), K, phi, ARC_RADII["precession"]),
                _arc(K, nodes, theta, ARC_RADII["nutation"]),
                _arc(nodes, spin_axis, psi, ARC_RADII["spin"]) + SHAFT_LENGTH * spin_axis,
            ]
        )
        update_node(self.arcs, points=arcs)
        s = self.omega_scale
        O = np.zeros(3)
        tip1 = s * rates[0] * K
        tip2 = tip1 + s * rates[1] * nodes
        segments = {
            "precession": (O, tip1),
            "nutation": (tip1, tip2),
            "spin": (tip2, tip2 + s * rates[2] * spin_axis),
            "omega": (O, s * k.omega_world_rad_s[0]),
            "alpha": (O, self.alpha_scale * k.alpha_world_rad_s2[0]),
        }
        self.arrows.draw(segments, move_labels=move_labels)

    def readout(self) -> Readout:
        state = self._state
        k = state.kinematics
        phi, _, psi = (math.degrees(float(a)) for a in wrap_angle_rad(k.angles_rad[0]))
        theta_now = float(k.angles_rad[0, 1])
        rates = k.rates_rad_s[0]
        quantities = [
            Quantity("t_s", "time t", float(self.t_s), "s"),
            Quantity("precession_deg", "precession φ", phi, "deg"),
            Quantity("nutation_deg", "nutation θ", math.degrees(theta_now), "deg"),
            Quantity("spin_deg", "spin ψ", psi, "deg"),
            Quantity("precession_rate", "precession rate φ̇", float(rates[0]), "rad/s"),
            Quantity("nutation_rate", "nutation rate θ̇", float(rates[1]), "rad/s"),
            Quantity("spin_rate", "spin rate ψ̇", float(rates[2]), "rad/s"),
            Quantity(
                "omega_body",
                "ω on the body axes (x, y, z)",
                None,
                "rad/s",
                _components(k.omega_body_rad_s[0], ("x", "y", "z")),
            ),
            Quantity(
                "omega_nutation",
                "ω on the nutation frame (x′ = line of nodes, y′, z′ = z)",
                None,
                "rad/s",
                _components(state.angular_velocity_nutation[0], ("x′", "y′", "z′")),
            ),
            Quantity("angular_speed", "|ω|", float(np.linalg.norm(k.omega_world_rad_s[0])), "rad/s"),
            Quantity(
                "alpha_body",
                "α on the body axes (x, y, z)",
                None,
                "rad/s²",
                _components(k.alpha_body_rad_s2[0], ("x", "y", "z")),
            ),
            Quantity(
                "alpha_nutation",
                "α on the nutation frame (x′, y′, z′)",
                None,
                "rad/s²",
                _components(state.angular_acceleration_nutation[0], ("x′", "y′", "z′")),
            ),
            Quantity("angular_acceleration", "|α|", float(np.linalg.norm(k.alpha_world_rad_s2[0])), "rad/s²"),
            Quantity(
                "singularity_distance",
                "θ's distance from 0 or 180° (the singular nutation)",
                math.degrees(float(k.lock_distance_rad[0])),
                "deg",
            ),
        ]
        recovered = physics.rates_from_angular_velocity(state, 0)
        if recovered is None:
            quantities.append(
                Quantity.word(
                    "rates_from_omega",
                    "φ̇, θ̇, ψ̇ read back from ω",
                    "undefined at θ = 0 or 180°: only φ̇ ± ψ̇ is determined",
                )
            )
        else:
            text = ", ".join(
                f"{name} {value:+.3f}".replace("-", "−") for name, value in zip(("φ̇", "θ̇", "ψ̇"), recovered)
            )
            quantities.append(
                Quantity("rates_from_omega", "φ̇, θ̇, ψ̇ read back from ω (rad/s)", None, "rad/s", text, text_in_unit=True)
            )
        message = physics.singularity_note(theta_now) + f" The motion replays every {CYCLE_S:g} s."
        return Readout(quantities, message=message)
