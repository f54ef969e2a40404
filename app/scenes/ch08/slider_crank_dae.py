"""Scene: the slider-crank in absolute coordinates (9 coordinates, 8 constraints), every DAE algorithm live.

Crank blue, connecting rod green, slider block grey on its guide; the arrows are
the multipliers of the pins O, A and B (ground on crank, crank on rod, rod on
slider), as in chapter 6's free-body diagrams.
"""

from __future__ import annotations

import numpy as np

from app.physics.systems.ch08.slider_crank_dae import SliderCrankDae
from app.scenes.ch08.planar_linkage_scene import PlanarLinkageScene
from app.scenes.kit import Preset
from app.scenes.kit.planar import to_world


class SliderCrankDaeScene(PlanarLinkageScene):
    id = "slider-crank-dae"
    title = "The slider-crank in absolute coordinates: multipliers as pin forces"
    chapter = 8
    model = SliderCrankDae
    has_slider = True
    presets = (
        Preset(
            "driven",
            "Driven by 2 N·m",
            {"drive_torque_N_m": 2.0, "crank_speed_rad_s": 10.0, "method": "projection"},
            "Chapter 6's defaults: compare the pin forces with lesson 6.3.",
        ),
        Preset(
            "coasting-uncorrected",
            "Coasting, uncorrected",
            {"drive_torque_N_m": 0.0, "method": "uncorrected", "steps_per_frame": 4},
            "No torque and no correction: watch the residuals grow while the energy should stay put.",
        ),
        Preset(
            "baumgarte",
            "Baumgarte, α = β = 20/s",
            {"method": "baumgarte", "baumgarte_alpha_1_s": 20.0, "baumgarte_beta_1_s": 20.0, "steps_per_frame": 4},
            "The residuals are pulled back like a damped oscillator.",
        ),
    )

    def ground_segments(self, params) -> np.ndarray:
        links = self.model().linkage(params)
        r, l, e = links.links[0].length_m, links.links[1].length_m, float(params["offset_m"])
        z = e - 0.5 * links.links[2].length_m
        return to_world(np.array([[[-0.1 * l, z], [r + 1.2 * l, z]]]))

    def _pin_points(self, ends: np.ndarray) -> np.ndarray:
        crank, rod, _ = ends
        return np.array([crank[0], crank[1], rod[1], rod[1]])
