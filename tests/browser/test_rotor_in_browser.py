"""Lesson 6.1 in a real browser: the unbalanced rotor's viewer connects and the readout's bearing forces match the physics."""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.systems.ch06 import unbalanced_rotor as rotor
from tests.browser.conftest import (
    open_lesson,
    readout_values,
    show_scene_and_keep_screenshot,
)

pytestmark = pytest.mark.browser


def test_rotor_lesson_loads_and_its_readout_bearing_forces_match_the_physics(browser, live_server, shots):
    context, page, _, errors = open_lesson(browser, live_server, "/lessons/6-1-unbalanced-rotor")
    page.wait_for_selector('#readout [data-quantity="bearing_A_force_N"]', timeout=30_000)
    values = readout_values(page)  # one instant: spin angle and forces read in one call
    steady = rotor.UnbalancedRotor.from_params(rotor.PARAMETERS.defaults()).steady_loads()
    loads = steady.at_spin_angle(np.array([math.radians(values["spin_angle_deg"])]))
    # The page carries the server's numbers unrounded (JSON); the degrees round trip costs ~1e-16 relative.
    assert values["bearing_A_force_N"] == pytest.approx(float(loads.bearing_A_force_N[0]), rel=1e-9)
    assert values["bearing_B_force_N"] == pytest.approx(float(loads.bearing_B_force_N[0]), rel=1e-9)
    # Hand check at the defaults: rotating parts √(66.7² + 58.1²) and √(33.3² + 58.1²) N, weight shares 65.4 and 32.7 N.
    assert values["bearing_A_rotating_force_N"] == pytest.approx(88.451, abs=1e-3)
    assert values["bearing_B_rotating_force_N"] == pytest.approx(67.009, abs=1e-3)
    assert 23.05 <= values["bearing_A_force_N"] <= 153.86
    assert values["imbalance_class"] == "both"
    show_scene_and_keep_screenshot(page, shots / "lesson-6-1-unbalanced-rotor.png")
    assert not errors, errors
    context.close()
