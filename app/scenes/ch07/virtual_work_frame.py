"""Scene: the toggle press held by virtual work — loads, the released hold at C and the virtual displacements.

The press's plane (x along AC, y up) is the world xz plane at y = 0, seen from
−y. Bars AB blue and BC green; the fixed pin A, the slider C on its guide
(grey). Red arrows: the loads P at B and the weights W₁, W₂ at the bars'
midpoints. Orange: the released constraint, the workpiece's force Q on C (drawn
from beyond C, where the workpiece is).
Green arrows: the admissible virtual displacements δr = r′(θ) δθ of B, G₁, G₂
and C for the drawn δθ, to scale (m); the faint grey frame is the press turned
through the same finite δθ, which the arrows match to first order.
Nothing moves, so the scene has no model to simulate: the picture and the readout are redrawn when a
control changes.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from app.physics.core.parameters import Parameter
from app.physics.systems.ch07 import virtual_work as physics
from app.scenes.kit import Preset, Quantity, Readout, Scene, arrow_segments
from app.scenes.kit.planar import to_world

BAR_COLORS = np.array([[40, 100, 220], [40, 150, 70]], np.uint8)
GHOST_COLOR = (185, 185, 195)
LOAD_COLOR = (210, 40, 40)
HOLD_COLOR = (235, 140, 20)
DISPLACEMENT_COLOR = (30, 160, 60)
#: Arrow order: loads P, W₁, W₂, the hold Q, then the virtual displacements of B, G₁, G₂, C.
ARROW_NAMES = ("P", "W₁", "W₂", "Q", "δr_B", "δr_G₁", "δr_G₂", "δr_C")
ARROW_COLORS = np.array([LOAD_COLOR] * 3 + [HOLD_COLOR] + [DISPLACEMENT_COLOR] * 4, np.uint8)
#: The largest force is drawn this fraction of the view's span long.
FORCE_ARROW_SPAN = 0.3


class VirtualWorkFrameScene(Scene):
    id = "virtual-work-frame"
    title = "Virtual work: the toggle press and its holding force"
    chapter = 7
    controls = (
        *physics.TOGGLE_PARAMETERS.parameters,
        Parameter(
            "virtual_angle_deg",
            "deg",
            12.0,
            1.0,
            20.0,
            "Size of the virtual rotation δθ drawn (display only; δW = 0 holds for every δθ)",
            "δθ drawn",
            step=0.5,
        ),
    )
    #: The press's own check (BC must reach the line AC), run on every change.
    check_controls = physics.TOGGLE_PARAMETERS.check
    presets = (
        Preset(
            "press",
            "Toggle press (θ = 20°)",
            {"angle_deg": 20.0, "load_B_N": 500.0},
            "Q = 755.6 N, 1.51 times the knee load P: the toggle already multiplies the force.",
        ),
        Preset(
            "near-toggle",
            "Near the toggle (θ = 3°)",
            {"angle_deg": 3.0, "load_B_N": 500.0},
            "Close to the line of the bars δx_C is tiny: the same 500 N at B holds Q = 5247 N.",
        ),
        Preset(
            "toggle",
            "At the toggle (θ = 0°)",
            {"angle_deg": 0.0, "load_B_N": 500.0},
            "Bars in line: δx_C = 0 for every δθ. Q does no virtual work, and no finite Q holds P.",
        ),
        Preset(
            "steep",
            "Steep, unequal bars",
            {"angle_deg": 60.0, "bar_AB_m": 0.6, "bar_BC_m": 1.2, "load_B_N": 500.0},
            "A steep AB: C moves a lot for each δθ, and Q = 248.6 N is about half of P.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self._span = 1.0
        self._center = np.zeros(3)
        self.guide = scene.add_line_segments("/guide", np.zeros((1, 2, 3), np.float32), (110, 110, 110), thickness=0.01)
        self.ghost = scene.add_line_segments("/ghost", np.zeros((2, 2, 3), np.float32), GHOST_COLOR, thickness=0.01)
        self.bars = scene.add_line_segments(
            "/bars", np.zeros((2, 2, 3), np.float32), np.repeat(BAR_COLORS[:, None, :], 2, axis=1), thickness=0.02
        )
        self.joints = scene.add_point_cloud(
            "/joints", np.zeros((3, 3), np.float32), (30, 30, 30), point_size=0.04, point_shape="circle"
        )
        self.slider = scene.add_box("/slider", color=(150, 150, 160), dimensions=(0.2, 0.1, 0.1))
        self.arrows = scene.add_arrows(
            "/arrows",
            np.zeros((len(ARROW_NAMES), 2, 3), np.float32),
            ARROW_COLORS,
            shaft_radius=0.01,
            head_radius=0.025,
            head_length=0.05,
        )
        self.arrow_labels = [
            scene.add_label(f"/arrows/{index}", name, anchor="center-left") for index, name in enumerate(ARROW_NAMES)
        ]
        self.point_labels = [scene.add_label(f"/points/{name}", name, anchor="top-center") for name in "ABC"]
        self.legend = scene.add_label("/legend", "", anchor="top-left")

    def camera_view(self):
        c, span = self._center, self._span
        return (float(c[0]), float(-0.75 * span), float(c[2] + 0.05 * span)), (float(c[0]), 0.0, float(c[2]))

    def update(self) -> None:
        press = physics.TogglePress.from_params(self.params)
        self._press = press
        try:
            self._holding_force_N: float | None = physics.holding_force_by_virtual_work(press)
            self._check: physics.ToggleForces | None = physics.toggle_equilibrium(press)
            self._refusal = ""
        except physics.TogglePositionError as exc:
            self._holding_force_N, self._check, self._refusal = None, None, str(exc)
        points = press.points()
        pin, knee, slider = points["A"], points["B"], points["C"]
        size = press.bar_AB_m + press.bar_BC_m
        low = np.array([-0.1 * size, -0.1 * size])
        high = np.array([slider[0] + 0.05 * size, knee[1] + 0.05 * size])
        # Room for the longest force arrow (FORCE_ARROW_SPAN of the span) to the right of C and above B.
        self._span = span = float(max(high - low)) / (1.0 - FORCE_ARROW_SPAN)
        high = high + FORCE_ARROW_SPAN * span
        self._center = to_world(0.5 * (low + high))
        self.bars.thickness = 0.012 * span
        self.ghost.thickness = 0.006 * span
        self.guide.thickness = 0.006 * span
        self.joints.point_size = 0.02 * span
        self.arrows.shaft_radius = 0.004 * span
        self.arrows.head_radius = 0.011 * span
        self.arrows.head_length = 0.025 * span
        block = (0.08 * span, 0.04 * span, 0.04 * span)
        self.slider.dimensions = block
        self.slider.position = tuple(to_world(slider))
        self.guide.points = np.array(
            [[[slider[0] - 0.15 * span, 0.0, -0.5 * block[2]], [slider[0] + 0.15 * span, 0.0, -0.5 * block[2]]]],
            np.float32,
        )
        self.bars.points = to_world(np.array([[pin, knee], [knee, slider]])).astype(np.float32)
        self.joints.points = to_world(np.array([pin, knee, slider])).astype(np.float32)
        for label, point in zip(self.point_labels, (pin, knee, slider)):
            label.position = tuple(to_world(point) + np.array([0.0, 0.0, -0.03 * span]))
        delta = math.radians(self.params["virtual_angle_deg"])
        self._draw_ghost(press, delta)
        self._draw_arrows(press, points, delta)
        self.legend.position = (float(low[0]), 0.0, float(low[1]))
        self.legend.text = "red: loads · orange: Q, the released hold · green: δr for δθ · grey: turned by δθ"

    def _draw_ghost(self, press: physics.TogglePress, delta_rad: float) -> None:
        try:
            turned = replace(press, angle_rad=press.angle_rad + delta_rad).points()
        except ValueError:  # turned past what the bars can reach: no ghost
            self.ghost.points = np.zeros((2, 2, 3), np.float32)
            return
        self.ghost.points = to_world(np.array([[turned["A"], turned["B"]], [turned["B"], turned["C"]]])).astype(
            np.float32
        )

    def _draw_arrows(self, press: physics.TogglePress, points: dict[str, np.ndarray], delta_rad: float) -> None:
        loads = press.loads()
        hold = np.array([-(self._holding_force_N or 0.0), 0.0])
        forces = np.array([loads["B"], loads["G1"], loads["G2"], hold])
        largest = float(np.max(np.linalg.norm(forces, axis=-1)))
        scale = FORCE_ARROW_SPAN * self._span / max(largest, 1e-12)
        displacements = press.virtual_displacements()
        # Loads end at their points (they push on them), Q too (the workpiece beyond C pushes back); δr start at their
        # points.
        tails = np.array([points[name] for name in ("B", "G1", "G2", "C")]) - scale * forces
        shift_tails = np.array([points[name] for name in ("B", "G1", "G2", "C")])
        shifts = delta_rad * np.array([displacements[name] for name in ("B", "G1", "G2", "C")])
        segments = np.concatenate(
            [
                arrow_segments(to_world(tails), to_world(forces), scale),
                arrow_segments(to_world(shift_tails), to_world(shifts), 1.0),
            ]
        )
        self.arrows.points = segments
        sizes = (press.load_B_N, press.weight_AB_N, press.weight_BC_N)
        texts = [f"{name} = {size:.0f} N" for name, size in zip(ARROW_NAMES[:3], sizes)]
        texts.append("Q → ∞ (toggle)" if self._holding_force_N is None else f"Q = {self._holding_force_N:.1f} N")
        texts += list(ARROW_NAMES[4:])
        offset = np.array([0.012 * self._span, 0.0, 0.0])
        for index, (label, text) in enumerate(zip(self.arrow_labels, texts)):
            label.position = tuple(
                segments[index, 0 if index < 4 else 1]
                + offset
                + (np.array([0.0, 0.0, 0.03 * self._span]) if index < 3 else 0.0)
            )
            label.text = text

    def readout(self) -> Readout:
        press = self._press
        d = press.virtual_displacements()
        q, check = self._holding_force_N, self._check
        infinite = "infinite: the bars are in line (toggle position)"
        quantities = [
            Quantity.or_text("holding_force_N", "holding force Q by virtual work", q, "N", infinite),
            Quantity.or_text(
                "holding_force_newtonian_N",
                "Q from both bars' equilibrium (6 equations)",
                None if check is None else check.holding_force_N,
                "N",
                "singular at the toggle position",
            ),
            Quantity.or_text(
                "relative_difference",
                "relative difference of the two Q",
                None
                if q is None or check is None
                else abs(q - check.holding_force_N) / max(abs(check.holding_force_N), 1e-300),
                "",
                "—",
            ),
            Quantity.or_text(
                "force_ratio",
                "force ratio Q / P",
                None if q is None or press.load_B_N == 0.0 else q / press.load_B_N,
                "",
                "—",
            ),
            Quantity("load_virtual_work_N_m", "virtual work of the loads per δθ", press.load_virtual_work_N_m(), "N·m"),
            Quantity("slider_virtual_displacement_m", "δx_C per δθ", float(d["C"][0]), "m"),
            Quantity("knee_virtual_displacement_y_m", "δy_B per δθ", float(d["B"][1]), "m"),
            Quantity.or_text(
                "guide_force_C_N",
                "guide force C_y on the slider (+ up)",
                None if check is None else check.guide_C_N,
                "N",
                "singular at the toggle position",
            ),
        ]
        message = self._refusal or (
            "The pins at A and B and the guide at C do no virtual work (A does not move, the two sides of B move "
            "together, "
            "and C moves along its guide), so only the loads and Q enter δW = 0."
        )
        return Readout(quantities, message=message)
