"""Scene: the slider-crank with link masses, its pin forces drawn as arrows and its work–energy balance.

The mechanism's plane (x along the slider's line, y up) is the world xz plane
at y = 0, seen from −y, as in the chapter-4 slider-crank. Crank blue,
connecting rod green, slider grey on its guide. Arrows, each labelled with its
size in N: at O the ground's force on the crank (purple), at A the crank's
force on the rod (orange), at B the rod's force on the slider (red) and the
guide's force on the slider (teal). All four share one scale: the largest
force seen so far is drawn 0.35 of the view wide.

The motion is integrated live (:class:`~app.scenes.kit.IntegratedScene`); the
forces at each frame come from the Newton–Euler solve of the physics module.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.systems.ch06 import mechanism_kinetics as physics
from app.scenes.kit import (
    IntegratedScene,
    Preset,
    Quantity,
    Readout,
    arrow_segments,
    circle_segments,
    move_node,
    update_node,
)
from app.scenes.kit.crank_speed_limit import paused_at_crank_speed_limit
from app.scenes.kit.planar import to_world

LINK_COLORS = np.array([[40, 100, 220], [40, 150, 70]], np.uint8)
FORCE_COLORS = np.array([[130, 60, 180], [230, 130, 20], [210, 40, 40], [20, 150, 150]], np.uint8)
FORCE_NAMES = ("O", "A", "B", "N")
#: The largest force seen so far is drawn this fraction of the view's span long.
FORCE_ARROW_SPAN = 0.35
#: The force labels' numbers are rewritten at 10 Hz (every 3rd frame): still readable, a third of the messages.
LABEL_TEXT_EVERY_FRAMES = 3


class SliderCrankKineticsScene(IntegratedScene):
    id = "slider-crank-kinetics"
    #: Links, joints, slider and the force arrows each frame; four moving labels whose numbers change at 10 Hz.
    frame_message_budget = 10.0
    title = "Kinetics of the slider-crank: pin forces and driving torque"
    chapter = 6
    model = physics.MechanismKinetics
    run_model: physics.MechanismKinetics
    presets = (
        Preset(
            "constant-speed",
            "Motor at constant speed",
            {"drive": "speed", "crank_speed_rad_s": 10.0, "slider_mass_kg": 3.0, "g_m_s2": 9.80665},
            "The motor holds ω = 10 rad/s: watch the torque it must supply, and where it has to brake.",
        ),
        Preset(
            "given-torque",
            "Constant torque",
            {"drive": "torque", "drive_torque_N_m": 2.0, "crank_speed_rad_s": 10.0, "slider_mass_kg": 3.0},
            "A constant 2 N·m: the crank speeds up, unevenly, as M(θ) and gravity change over each turn.",
        ),
        Preset(
            "coasting",
            "Coasting (no torque)",
            {"drive": "torque", "drive_torque_N_m": 0.0, "crank_speed_rad_s": 10.0, "slider_mass_kg": 3.0},
            "No torque: T + V stays constant, so the crank slows going up and speeds up coming down.",
        ),
        Preset(
            "heavy-slider",
            "Heavy slider",
            {"drive": "speed", "crank_speed_rad_s": 10.0, "slider_mass_kg": 50.0},
            "A 50 kg slider: the torque swings hard between driving and braking twice a turn.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self._span = 1.0
        self._center = np.zeros(3)
        self.rail = scene.add_line_segments("/rail", np.zeros((1, 2, 3), np.float32), (110, 110, 110), thickness=0.01)
        self.crank_circle = scene.add_line_segments(
            "/crank_circle", np.zeros((1, 2, 3), np.float32), (150, 170, 210), thickness=1.5, thickness_units="screen"
        )
        self.links = scene.add_line_segments(
            "/links", np.zeros((2, 2, 3), np.float32), np.repeat(LINK_COLORS[:, None, :], 2, axis=1), thickness=0.02
        )
        self.joints = scene.add_point_cloud(
            "/joints", np.zeros((3, 3), np.float32), (30, 30, 30), point_size=0.04, point_shape="circle"
        )
        self.slider = scene.add_box("/slider", color=(150, 150, 160), dimensions=(0.2, 0.1, 0.1))
        self.arrows = scene.add_arrows(
            "/forces",
            np.zeros((4, 2, 3), np.float32),
            FORCE_COLORS,
            shaft_radius=0.01,
            head_radius=0.025,
            head_length=0.05,
        )
        self.force_labels = [scene.add_label(f"/forces/{name}", name, anchor="center-left") for name in FORCE_NAMES]
        self.legend = scene.add_label("/legend", "", anchor="bottom-left")

    def camera_view(self):
        c, span = self._center, self._span
        return (float(c[0] + 0.05 * span), float(-0.8 * span), float(c[2] + 0.1 * span)), (
            float(c[0]),
            0.0,
            float(c[2]),
        )

    def update(self) -> None:
        params = self.physical_params()
        self.restart()
        links = physics.SliderCrankLinks.from_params(params)
        self._links = links
        self._speed_limit = physics.speed_limit_rad_s(params)
        mech = links.mechanism
        r, l, e = mech.crank_m, mech.rod_m, mech.offset_m
        x_min, x_max = mech.stroke_limits_m
        low = np.array([-r - 0.1 * l, min(-r, e) - 0.1 * l])
        high = np.array([x_max + 0.2 * l, max(r, e) + 0.15 * l])
        self._span = span = float(max(high - low))
        self._center = to_world(0.5 * (low + high))
        block = (0.22 * r + 0.05 * l, 0.06 * span, 0.1 * r + 0.03 * l)
        self.slider.dimensions = block
        self.links.thickness = 0.012 * span
        self.rail.thickness = 0.006 * span
        self.joints.point_size = 0.018 * span
        rail_z = e - 0.5 * block[2]
        self.rail.points = np.array([[[x_min - 0.15 * l, 0.0, rail_z], [x_max + 0.15 * l, 0.0, rail_z]]], np.float32)
        self.crank_circle.points = circle_segments(radius=r, normal=(0.0, 1.0, 0.0))
        self.arrows.shaft_radius = 0.004 * span
        self.arrows.head_radius = 0.011 * span
        self.arrows.head_length = 0.025 * span
        self.legend.position = (float(low[0]), 0.0, float(high[1]))
        self.legend.text = "forces: O ground→crank · A crank→rod · B rod→slider · N guide→slider"
        self._largest_force_N = 0.0
        self._draw()

    def _forces_now(self) -> physics.PinForces:
        return self.run_model.forces(self.physical_params(), self.run.y)

    def _draw(self) -> None:
        y = self.run.y
        motion = physics.link_motion(self._links, np.array([y[0]]), np.array([y[1]]), np.zeros(1))
        forces = self._forces_now()
        self._state = (motion, forces)
        a, b = motion.crank_pin[0], motion.slider_pin[0]
        update_node(self.links, points=to_world(np.array([[[0.0, 0.0], a], [a, b]])))
        update_node(self.joints, points=to_world(np.array([[0.0, 0.0], a, b])))
        move_node(self.slider, position=to_world(b))
        vectors = np.array(
            [forces.pivot_O_N[0], forces.crank_pin_A_N[0], forces.wrist_pin_B_N[0], [0.0, forces.guide_force_N[0]]]
        )
        sizes = np.linalg.norm(vectors, axis=-1)
        self._largest_force_N = max(self._largest_force_N, float(np.max(sizes)))
        scale = FORCE_ARROW_SPAN * self._span / max(self._largest_force_N, 1e-12)
        tails = to_world(np.array([[0.0, 0.0], a, b, b]))
        update_node(self.arrows, points=arrow_segments(tails, to_world(vectors), scale))
        rewrite_text = self._frames % LABEL_TEXT_EVERY_FRAMES == 0
        for label, name, tail, vector, size in zip(self.force_labels, FORCE_NAMES, tails, to_world(vectors), sizes):
            move_node(label, position=tail + scale * vector + np.array([0.01 * self._span, 0.0, 0.0]))
            if rewrite_text:
                update_node(label, text=f"{name} {size:.1f} N")

    def step_motion(self, dt_s: float) -> bool:
        if paused_at_crank_speed_limit(self, float(self.run.y[1]), self._speed_limit):
            return False
        return self.step_physics()

    def readout(self) -> Readout:
        params = self.physical_params()
        motion, forces = self._state
        kinetic, potential = self.run_model.energies(params, self.run.y)
        residual = self.current_invariants()["work_energy_residual"]
        guide = float(forces.guide_force_N[0])
        quantities = [
            Quantity("t_s", "time t", self.run.t_s, "s"),
            Quantity("crank_angle", "crank angle θ", math.degrees(float(self.run.y[0])) % 360.0, "deg"),
            Quantity("crank_speed_rad_s", "crank speed ω", float(self.run.y[1]), "rad/s"),
            Quantity("driving_torque_N_m", "driving torque τ", float(forces.driving_torque_N_m[0]), "N·m"),
            Quantity(
                "pin_force_O_N", "pin force at O (ground on crank)", float(np.linalg.norm(forces.pivot_O_N[0])), "N"
            ),
            Quantity(
                "pin_force_A_N", "pin force at A (crank on rod)", float(np.linalg.norm(forces.crank_pin_A_N[0])), "N"
            ),
            Quantity(
                "pin_force_B_N", "pin force at B (rod on slider)", float(np.linalg.norm(forces.wrist_pin_B_N[0])), "N"
            ),
            Quantity("guide_force_N", "guide force N on the slider (+ up)", guide, "N"),
            Quantity("kinetic_energy_J", "kinetic energy T", float(kinetic[0]), "J"),
            Quantity("potential_energy_J", "potential energy V", float(potential[0]), "J"),
            Quantity("torque_work_J", "torque work W", float(self.run.y[2]), "J"),
            Quantity("work_energy_residual_J", "work–energy residual ΔT + ΔV − W", float(residual), "J"),
        ]
        notes = ["The guide is frictionless (guide friction is out of scope)."]
        if guide < 0.0:
            notes.append(
                "The guide force points down: the guide must hold the slider down here; a slider resting on a "
                "one-sided guide would lift off."
            )
        if params["drive"] == "speed" and forces.driving_torque_N_m[0] * self.run.y[1] < 0.0:
            notes.append("The torque opposes the motion: the motor is braking to hold the speed constant.")
        message = self.status or " ".join(notes)
        return Readout(quantities, message=message)
