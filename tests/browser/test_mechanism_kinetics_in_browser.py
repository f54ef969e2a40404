"""The mechanism-kinetics lesson in a real browser: the viewer connects and the readout shows Newton–Euler's numbers."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from app.physics.systems.ch06 import mechanism_kinetics as physics
from tests.browser.conftest import (
    open_lesson,
    readout_values,
    show_scene_and_keep_screenshot,
)

pytestmark = pytest.mark.browser

LESSON = "6-3-mechanism-kinetics"


def test_lesson_scene_connects_and_its_torque_and_energy_match_the_physics(browser, live_server, shots):
    context, page, _, errors = open_lesson(browser, live_server, f"/lessons/{LESSON}")
    page.wait_for_selector('#readout [data-quantity="driving_torque_N_m"]', timeout=30_000)
    values = readout_values(page)
    links = physics.SliderCrankLinks.from_params(physics.PARAMETERS.defaults())
    theta = np.array([math.radians(values["crank_angle"])])
    assert values["crank_speed_rad_s"] == pytest.approx(10.0, abs=1e-9)
    forces = physics.newton_euler(links, theta, 10.0, crank_acceleration_rad_s2=0.0)
    # The crank angle is shown to 0.005° (9e-5 rad) and |dτ/dθ| < 150 N·m/rad here: 0.02 N·m covers it.
    assert values["driving_torque_N_m"] == pytest.approx(float(forces.driving_torque_N_m[0]), abs=0.02)
    # T = ½ M(θ) ω² with |dM/dθ| < 0.5 kg·m²: 0.005° moves T by < 3e-3 J.
    assert values["kinetic_energy_J"] == pytest.approx(0.5 * float(physics.generalized_inertia_kg_m2(links, theta)[0]) * 100.0, abs=5e-3)
    assert abs(values["work_energy_residual_J"]) < 1e-4
    show_scene_and_keep_screenshot(page, shots / f"lesson-{LESSON}.png")
    assert not errors, errors
    json.dumps(readout_values(page))  # the readout stays plain JSON while the scene runs
    context.close()
