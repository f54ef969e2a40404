"""Scene: the four-bar with link masses in absolute coordinates (9 coordinates, 8 constraints), every DAE algorithm
live.

Crank blue, coupler green, rocker grey; the arrows are the multipliers of the
pins O₂, A, B and O₄ (ground on crank, crank on coupler, coupler on rocker,
ground on rocker).
"""

from __future__ import annotations

import numpy as np

from app.physics.systems.ch08.massive_four_bar import MassiveFourBar
from app.scenes.ch08.planar_linkage_scene import PlanarLinkageScene
from app.scenes.kit import Preset
from app.scenes.kit.planar import to_world


class FourBarDaeScene(PlanarLinkageScene):
    id = "four-bar-dae"
    title = "The massive four-bar in absolute coordinates: nine coordinates, eight constraints"
    chapter = 8
    model = MassiveFourBar
    presets = (
        Preset(
            "crank-rocker",
            "Crank-rocker, 1 N·m",
            {"crank_m": 0.3, "drive_torque_N_m": 1.0, "method": "projection"},
            "The crank turns fully; the rocker swings.",
        ),
        Preset(
            "uncorrected",
            "Uncorrected, few steps",
            {"method": "uncorrected", "steps_per_frame": 4, "drive_torque_N_m": 0.0},
            "No correction: the residuals drift.",
        ),
        Preset(
            "non-grashof",
            "Non-Grashof (toggles)",
            {"crank_m": 1.5, "crank_angle0_deg": 0.0, "drive_torque_N_m": 0.0, "method": "projection"},
            "The crank cannot turn fully: it swings through toggle positions, where the one-coordinate equation fails.",
        ),
    )

    def ground_segments(self, params) -> np.ndarray:
        d = float(params["ground_m"])
        return to_world(np.array([[[0.0, 0.0], [d, 0.0]]]))

    def _pin_points(self, ends: np.ndarray) -> np.ndarray:
        crank, coupler, rocker = ends
        return np.array([crank[0], crank[1], coupler[1], rocker[0]])

    def notes(self, params) -> list[str]:
        if self.model().crank_turns_fully(params):
            return []
        return [
            "The crank cannot turn fully here (non-Grashof): at a toggle position the crank angle is not a usable "
            "coordinate, so a one-coordinate equation in θ₂ would fail; the nine absolute coordinates carry on."
        ]
