"""Scene for Example 1.1: the robotic arm, its cable, the cable force and its moments.

The readout lists what the example solves: the force's components, its component
along BC, its moment about A and that moment's components about the vertical
axis and about arm AB, with the way the cable turns the arm seen from above.
"""

from __future__ import annotations

import numpy as np

from app.physics.core.solution import zero_round_off
from app.physics.systems.ch01 import robot_arm_cable as physics
from app.scenes.kit import Quantity, Readout, Scene, arrow_segments, quaternion_z_to

LINK_RADIUS_M = 0.05
ARROW_LENGTH_M = 1.6  # the largest force and the largest moment are drawn this long

# Arrow order in the batched arrows node, with colours (RGB).
ARROWS = (
    ("F", (220, 40, 40)),
    ("F_BC e_BC", (240, 150, 20)),
    ("M_A", (130, 60, 200)),
    ("M_z k", (30, 150, 60)),
    ("M_AB e_AB", (30, 110, 220)),
)


class RobotArmCableScene(Scene):
    id = "robot-arm-cable"
    title = "Example 1.1 — robotic arm and cable"
    chapter = 1
    example = physics.EXAMPLE
    camera_position = (3.4, -3.0, 2.6)
    camera_look_at = (1.4, 0.5, 0.6)

    def build(self) -> None:
        scene = self.client.scene
        scene.add_grid("/ground", width=8.0, height=8.0, cell_size=0.5, section_size=1.0, position=(1.0, 0.5, 0.0))
        axes = np.array([[[0, 0, 0], [1, 0, 0]], [[0, 0, 0], [0, 1, 0]], [[0, 0, 0], [0, 0, 1]]], dtype=np.float32)
        scene.add_line_segments(
            "/axes",
            axes * 1.2,
            np.array([[200, 0, 0], [0, 160, 0], [0, 0, 200]], dtype=np.uint8)[:, None, :].repeat(2, 1),
            thickness=0.015,
        )
        for name, tip in (("x", (1.3, 0, 0)), ("y", (0, 1.3, 0)), ("z", (0, 0, 1.3))):
            scene.add_label(f"/axes/{name}", name, position=tip, anchor="center-center")
        self.link_AB = scene.add_cylinder("/arm/AB", radius=LINK_RADIUS_M, height=1.0, color=(90, 110, 140))
        self.link_BC = scene.add_cylinder("/arm/BC", radius=LINK_RADIUS_M * 0.8, height=1.0, color=(200, 140, 60))
        self.pin_B = scene.add_cylinder("/arm/pin", radius=LINK_RADIUS_M * 0.9, height=0.25, color=(60, 60, 60))
        self.points = {name: scene.add_icosphere(f"/points/{name}", radius=0.06, color=(40, 40, 40)) for name in "ABCD"}
        self.point_labels = {
            name: scene.add_label(f"/points/{name}/label", name, position=(0.0, 0.0, 0.12), anchor="bottom-center")
            for name in "ABCD"
        }
        self.cable = scene.add_line_segments("/cable", np.zeros((1, 2, 3), np.float32), (30, 30, 30), thickness=0.012)
        colors = np.array([c for _, c in ARROWS], dtype=np.uint8)
        self.arrows = scene.add_arrows(
            "/vectors",
            np.zeros((len(ARROWS), 2, 3), np.float32),
            colors,
            shaft_radius=0.018,
            head_radius=0.05,
            head_length=0.12,
        )
        self.arrow_labels = [
            scene.add_label(f"/vectors/label{i}", name, anchor="center-left") for i, (name, _) in enumerate(ARROWS)
        ]

    def _place_link(self, handle, start: np.ndarray, end: np.ndarray) -> None:
        handle.position = (start + end) / 2.0
        handle.wxyz = quaternion_z_to(end - start)
        handle.scale = (1.0, 1.0, float(np.linalg.norm(end - start)))

    def update(self) -> None:
        try:
            loads = physics.cable_loads(self.params)
        except ValueError as exc:
            self.status = str(exc)
            return
        self.status = ""
        self.loads = loads
        g = loads.geometry
        self._place_link(self.link_AB, g.A, g.B)
        self._place_link(self.link_BC, g.B, g.C)
        self.pin_B.position = g.B
        self.pin_B.wxyz = quaternion_z_to(np.cross([0.0, 0.0, 1.0], g.e_AB))
        for name, point in zip("ABCD", (g.A, g.B, g.C, g.D)):
            self.points[name].position = point
        self.cable.points = np.array([[g.C, g.D]], dtype=np.float32)

        force_scale = ARROW_LENGTH_M / max(float(np.linalg.norm(loads.F_N)), 1e-9)
        moment_scale = ARROW_LENGTH_M / max(float(np.linalg.norm(loads.M_A_Nm)), 1e-9)
        tails = np.array([g.C, g.C, g.A, g.A, g.A])
        vectors = np.array(
            [
                loads.F_N * force_scale,
                loads.F_BC_N * g.e_BC * force_scale,
                loads.M_A_Nm * moment_scale,
                np.array([0.0, 0.0, loads.M_z_Nm]) * moment_scale,
                loads.M_AB_Nm * g.e_AB * moment_scale,
            ]
        )
        self.arrows.points = arrow_segments(tails, vectors, 1.0)
        texts = (
            f"F = {np.linalg.norm(loads.F_N):,.0f} N",
            f"F_BC = {loads.F_BC_N:,.0f} N",
            f"M_A = {np.linalg.norm(loads.M_A_Nm):,.0f} N·m",
            f"M_z = {loads.M_z_Nm:,.0f} N·m",
            f"M_AB = {loads.M_AB_Nm:,.0f} N·m",
        )
        for label, tail, vector, text in zip(self.arrow_labels, tails, vectors, texts):
            label.position = tail + vector * 1.05
            label.text = text

    def readout(self) -> Readout:
        """The example's answers for the arm drawn (forces in N, moments in N·m, fixed frame xyz)."""
        if self.status:
            return Readout((), message=f"Cannot solve: {self.status}")
        loads = self.loads
        scale = physics.round_off_scales(loads)  # a load within round-off of its scale reads 0, as in the solution
        quantities = [
            Quantity(f"F_{axis}_N", f"cable force on C, {axis} component F_{axis}", float(component), "N")
            for axis, component in zip("xyz", zero_round_off(loads.F_N, scale["F_N"]))
        ]
        along = "toward B: it compresses BC" if loads.F_BC_N < 0.0 else "away from B: it stretches BC"
        quantities += [
            Quantity("F_BC_N", "component along BC (B → C)", zero_round_off(loads.F_BC_N, scale["F_BC_N"]), "N"),
            Quantity("M_A_Nm", "moment about A |M_A|", float(np.linalg.norm(loads.M_A_Nm)), "N·m"),
            Quantity(
                "M_z_Nm", "moment about the vertical axis M_z", zero_round_off(loads.M_z_Nm, scale["M_z_Nm"]), "N·m"
            ),
            Quantity("M_AB_Nm", "moment about arm AB M_AB", zero_round_off(loads.M_AB_Nm, scale["M_AB_Nm"]), "N·m"),
            Quantity.word("turning_about_z", "turns the arm about z, seen from above", physics.turning_about_z(loads)),
        ]
        message = (
            f"The cable pulls C toward D with {np.linalg.norm(loads.F_N):,.0f} N; "
            f"along BC that is {abs(loads.F_BC_N):,.0f} N {along}."
        )
        return Readout(quantities, message=message)
