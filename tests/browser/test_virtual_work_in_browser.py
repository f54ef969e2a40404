"""The virtual-work lesson in a real browser: the toggle press's holding force and the slider-crank's drive torque
in the readout match the physics, by virtual work and by Newton alike."""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.systems.ch06 import mechanism_kinetics as mk
from app.physics.systems.ch07 import virtual_work as vw
from tests.browser.conftest import open_lesson, readout_values, show_scene_and_keep_screenshot

pytestmark = pytest.mark.browser

LESSON = "7-1-virtual-work"


def test_lesson_shows_the_press_holding_force_and_the_slider_crank_torque_both_ways(browser, live_server, shots):
    context, page, _, errors = open_lesson(browser, live_server, f"/lessons/{LESSON}")
    page.wait_for_selector('#readout [data-quantity="holding_force_N"]', timeout=30_000)
    values = readout_values(page)
    expected = vw.holding_force_by_virtual_work(vw.TogglePress.from_params(vw.TOGGLE_PARAMETERS.defaults()))
    # The readout carries the float itself (JSON round-trips it exactly); 1e-12 only allows for a different summation order.
    assert values["holding_force_N"] == pytest.approx(expected, rel=1e-12)
    assert values["holding_force_N"] == pytest.approx(755.556, abs=1e-3)  # the lesson's worked number
    assert values["relative_difference"] < 1e-10
    show_scene_and_keep_screenshot(page, shots / f"lesson-{LESSON}.png")
    assert not errors, errors
    context.close()

    context, page, _, errors = open_lesson(browser, live_server, f"/lessons/{LESSON}?scene=dynamic-virtual-work")
    page.wait_for_selector('#readout [data-quantity="driving_torque_newton_euler_N_m"]', timeout=30_000)
    values = readout_values(page)
    links = mk.SliderCrankLinks.from_params(vw.PARAMETERS.defaults())
    theta = np.array([math.radians(values["crank_angle"])])  # the tabulated sample shown: degrees and back lose ~1e-16 rad
    torque = float(mk.newton_euler(links, theta, 10.0, crank_acceleration_rad_s2=0.0).driving_torque_N_m[0])
    # |dτ/dθ| < 150 N·m/rad, so a 1e-15 rad round trip moves τ by < 1e-12 N·m: 1e-9 N·m is generous.
    assert values["driving_torque_newton_euler_N_m"] == pytest.approx(torque, abs=1e-9)
    assert values["driving_torque_virtual_work_N_m"] == pytest.approx(torque, abs=1e-9)
    assert abs(values["driving_torque_difference_N_m"]) < 1e-10 and abs(values["constraint_virtual_work_N_m"]) < 1e-10
    show_scene_and_keep_screenshot(page, shots / f"lesson-{LESSON}-dynamic.png")
    assert not errors, errors
    context.close()
