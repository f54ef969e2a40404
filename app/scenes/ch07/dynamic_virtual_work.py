"""Scene: the slider-crank at constant crank speed, its drive torque by dynamic virtual work.

The mechanism's plane (x along the slider's line, y up) is the world xz plane
at y = 0, seen from −y, as in the chapter-4 and chapter-6 slider-cranks. Crank
blue, connecting rod green, slider grey on its guide. Green arrows: the
admissible virtual displacements δr = r′(θ) δθ of G₁, G₂ and B for the drawn δθ,
to scale (m); the faint grey linkage is the mechanism with its crank turned
through that δθ. Red arrows: the inertia forces −m a at G₁, G₂ and B, on one
scale (the largest over a turn is drawn 0.3 of the view wide).

The motion is periodic in θ, so every quantity drawn is tabulated once per
change of the controls, over a turn at :data:`SAMPLES_PER_TURN` crank angles;
a frame shows the sample nearest θ(t) = θ(0) + ω t (within 0.05°) and costs no
physics. The readout recomputes τ at the sample shown, by virtual work and by
the Newton–Euler solve of chapter 6.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.core.parameters import Parameter
from app.physics.systems.ch06 import mechanism_kinetics as kinetics
from app.physics.systems.ch07 import virtual_work as physics
from app.scenes.kit import Preset, Quantity, Readout, Scene, arrow_segments, circle_segments, move_node, update_node
from app.scenes.kit.planar import to_world

LINK_COLORS = np.array([[40, 100, 220], [40, 150, 70]], np.uint8)
GHOST_COLOR = (185, 185, 195)
DISPLACEMENT_COLOR = (30, 160, 60)
INERTIA_COLOR = (210, 40, 40)
ARROW_COLORS = np.array([DISPLACEMENT_COLOR] * 3 + [INERTIA_COLOR] * 3, np.uint8)
#: Crank angles tabulated over a turn: 0.1° apart.
SAMPLES_PER_TURN = 3600
#: The largest inertia force over a turn is drawn this fraction of the view's span long.
INERTIA_ARROW_SPAN = 0.3


class DynamicVirtualWorkScene(Scene):
    id = "dynamic-virtual-work"
    #: Links, joints, slider, the turned ghost and one batch of six arrows: five messages a frame.
    frame_message_budget = 6.0
    title = "Dynamic virtual work: the slider-crank's drive torque"
    chapter = 7
    model = physics.SliderCrankVirtualWork
    animated = True
    controls = (
        Parameter(
            "virtual_rotation_deg",
            "deg",
            15.0,
            1.0,
            45.0,
            "Size of the virtual rotation δθ of the crank drawn (display only)",
            "δθ drawn",
            step=1,
        ),
    )
    presets = (
        Preset(
            "constant-speed",
            "Motor at 10 rad/s",
            {"crank_speed_rad_s": 10.0, "slider_mass_kg": 3.0, "g_m_s2": 9.80665, "offset_m": 0.0},
            "The defaults of lesson 6.3: τ by virtual work and by Newton–Euler agree to round-off.",
        ),
        Preset(
            "flat",
            "Lying flat (g = 0)",
            {"g_m_s2": 0.0, "crank_speed_rad_s": 10.0},
            "Only the inertia forces do virtual work: τ vanishes at both dead centres, where δr_B = 0.",
        ),
        Preset(
            "heavy-slider",
            "Heavy slider",
            {"slider_mass_kg": 50.0, "crank_speed_rad_s": 10.0},
            "The slider's −m a dominates; its virtual work −m ẍ x′ sets the torque.",
        ),
        Preset(
            "offset",
            "Offset guide",
            {"offset_m": 0.25, "rod_m": 0.8, "crank_speed_rad_s": 10.0},
            "An offset guide: the dead centres move, and so do the zeros of δr_B.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.t_s = 0.0
        self._sample = -1
        self._span = 1.0
        self._center = np.zeros(3)
        self.rail = scene.add_line_segments("/rail", np.zeros((1, 2, 3), np.float32), (110, 110, 110), thickness=0.01)
        self.crank_circle = scene.add_line_segments(
            "/crank_circle", np.zeros((1, 2, 3), np.float32), (150, 170, 210), thickness=1.5, thickness_units="screen"
        )
        self.ghost = scene.add_line_segments("/ghost", np.zeros((2, 2, 3), np.float32), GHOST_COLOR, thickness=0.01)
        self.links = scene.add_line_segments(
            "/links", np.zeros((2, 2, 3), np.float32), np.repeat(LINK_COLORS[:, None, :], 2, axis=1), thickness=0.02
        )
        self.joints = scene.add_point_cloud(
            "/joints", np.zeros((3, 3), np.float32), (30, 30, 30), point_size=0.04, point_shape="circle"
        )
        self.slider = scene.add_box("/slider", color=(150, 150, 160), dimensions=(0.2, 0.1, 0.1))
        self.arrows = scene.add_arrows(
            "/arrows",
            np.zeros((6, 2, 3), np.float32),
            ARROW_COLORS,
            shaft_radius=0.01,
            head_radius=0.025,
            head_length=0.05,
        )
        self.legend = scene.add_label("/legend", "", anchor="bottom-left")

    def camera_view(self):
        c, span = self._center, self._span
        return (float(c[0] + 0.05 * span), float(-0.62 * span), float(c[2] + 0.05 * span)), (
            float(c[0]),
            0.0,
            float(c[2]),
        )

    def _physical_params(self) -> dict:
        return {name: self.params[name] for name in physics.PARAMETERS.by_name}

    def update(self) -> None:
        params = self._physical_params()
        self.t_s = 0.0
        self._sample = -1
        self._links = links = kinetics.SliderCrankLinks.from_params(params)
        self._drive = physics.crank_drive(params)
        self._grid = np.linspace(0.0, 2.0 * math.pi, SAMPLES_PER_TURN, endpoint=False)
        self._table = table = physics.dynamic_virtual_work(links, self._grid, params["crank_speed_rad_s"], 0.0)
        self._ghost_shift = int(
            round(math.radians(self.params["virtual_rotation_deg"]) / (2.0 * math.pi) * SAMPLES_PER_TURN)
        )
        # The view holds every pin over the tabulated turn, with a margin of a fifth of the rod.
        swept = np.concatenate([table.motion.crank_pin, table.motion.slider_pin, np.zeros((1, 2))])
        margin = 0.2 * links.mechanism.rod_m
        low, high = swept.min(axis=0) - margin, swept.max(axis=0) + margin
        self._span = span = float(max(high - low))
        self._center = to_world(0.5 * (low + high))
        crank = links.mechanism.crank_m
        block = (0.08 * span, 0.05 * span, 0.04 * span)
        self.slider.dimensions = block
        for handle, share in ((self.links, 0.012), (self.ghost, 0.006), (self.rail, 0.006)):
            handle.thickness = share * span
        self.joints.point_size = 0.018 * span
        stroke = table.motion.slider_pin[:, 0]
        rail = np.array(
            [
                [stroke.min() - 0.5 * block[0], links.mechanism.offset_m],
                [stroke.max() + 0.5 * block[0], links.mechanism.offset_m],
            ]
        )
        self.rail.points = (to_world(rail) - np.array([0.0, 0.0, 0.5 * block[2]]))[None].astype(np.float32)
        self.crank_circle.points = circle_segments(radius=crank, normal=(0.0, 1.0, 0.0))
        self.arrows.shaft_radius, self.arrows.head_radius, self.arrows.head_length = (
            0.004 * span,
            0.011 * span,
            0.025 * span,
        )
        largest = max(
            float(np.max(np.linalg.norm(f, axis=-1)))
            for f in (table.inertia_force_G1_N, table.inertia_force_G2_N, table.inertia_force_B_N)
        )
        self._inertia_scale = INERTIA_ARROW_SPAN * span / max(largest, 1e-12)
        self._virtual_rotation_rad = math.radians(self.params["virtual_rotation_deg"])
        self.legend.position = (float(low[0]), 0.0, float(high[1]))
        self.legend.text = (
            "green: δr of G₁, G₂, B for the drawn δθ · red: inertia forces −m a · grey: crank turned by δθ"
        )
        self._draw()

    def _sample_now(self) -> int:
        theta = float(self._drive.angle(np.array([self.t_s]))[0])
        return int(round(theta / (2.0 * math.pi) * SAMPLES_PER_TURN)) % SAMPLES_PER_TURN

    def _draw(self) -> None:
        k = self._sample_now()
        if k == self._sample:
            return
        self._sample = k
        table, motion = self._table, self._table.motion
        a, b = motion.crank_pin[k], motion.slider_pin[k]
        update_node(self.links, points=to_world(np.array([[[0.0, 0.0], a], [a, b]])))
        update_node(self.joints, points=to_world(np.array([[0.0, 0.0], a, b])))
        move_node(self.slider, position=to_world(b))
        turned = (k + self._ghost_shift) % SAMPLES_PER_TURN
        a2, b2 = motion.crank_pin[turned], motion.slider_pin[turned]
        update_node(self.ghost, points=to_world(np.array([[[0.0, 0.0], a2], [a2, b2]])))
        tails = to_world(
            np.array([motion.crank_centre[k], motion.rod_centre[k], b, motion.crank_centre[k], motion.rod_centre[k], b])
        )
        shifts = self._virtual_rotation_rad * np.array(
            [table.virtual_displacement_G1[k], table.virtual_displacement_G2[k], table.virtual_displacement_B[k]]
        )
        inertia = self._inertia_scale * np.array(
            [table.inertia_force_G1_N[k], table.inertia_force_G2_N[k], table.inertia_force_B_N[k]]
        )
        update_node(self.arrows, points=arrow_segments(tails, to_world(np.concatenate([shifts, inertia])), 1.0))

    def readout(self) -> Readout:
        k = self._sample
        links, table = self._links, self._table
        theta = self._grid[k : k + 1]
        omega = self.params["crank_speed_rad_s"]
        by_virtual_work = float(physics.driving_torque_by_virtual_work(links, theta, omega)[0])
        forces = kinetics.newton_euler(links, theta, omega, crank_acceleration_rad_s2=0.0)
        by_newton_euler = float(forces.driving_torque_N_m[0])
        constraints = physics.constraint_virtual_work(links, theta, forces)
        quantities = [
            Quantity("t_s", "time t", self.t_s, "s"),
            Quantity("crank_angle", "crank angle θ (sample shown)", math.degrees(float(theta[0])), "deg"),
            Quantity("crank_speed_rad_s", "crank speed ω", omega, "rad/s"),
            Quantity("driving_torque_virtual_work_N_m", "τ by dynamic virtual work", by_virtual_work, "N·m"),
            Quantity("driving_torque_newton_euler_N_m", "τ by Newton–Euler (8×8 solve)", by_newton_euler, "N·m"),
            Quantity(
                "driving_torque_difference_N_m", "difference of the two τ", by_virtual_work - by_newton_euler, "N·m"
            ),
            Quantity(
                "gravity_virtual_work_N_m",
                "virtual work of the weights per δθ",
                float(table.gravity_work_N_m[k]),
                "N·m",
            ),
            Quantity(
                "inertia_virtual_work_N_m",
                "virtual work of −m a and −I α per δθ",
                float(table.inertia_work_N_m[k]),
                "N·m",
            ),
            Quantity(
                "crank_pin_on_rod_virtual_work_N_m",
                "virtual work of pin force A on the rod per δθ",
                float(constraints.crank_pin_on_rod[0]),
                "N·m",
            ),
            Quantity(
                "constraint_virtual_work_N_m",
                "virtual work of all pin and guide forces per δθ",
                float(constraints.total[0]),
                "N·m",
            ),
            Quantity("slider_virtual_displacement_m", "δx_B per δθ", float(table.virtual_displacement_B[k, 0]), "m"),
            Quantity(
                "generalized_inertia_kg_m2",
                "generalized inertia M(θ)",
                float(kinetics.generalized_inertia_kg_m2(links, theta)[0]),
                "kg·m²",
            ),
        ]
        message = (
            "Each pin force does virtual work on one link and the opposite amount on the other (both ends move "
            "together), "
            "and the guide force is normal to δr_B: all of it cancels, so τ follows from the weights and the "
            "inertia forces alone."
        )
        return Readout(quantities, message=message)
