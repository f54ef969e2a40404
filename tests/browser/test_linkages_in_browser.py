"""Chapter 4 lesson pages in a real browser: the viewer connects, the readout shows the physics.

One test per lesson page; each waits for the scene's readout on the page and
checks a number in it against app.physics, then saves the page's screenshot.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from app.physics.systems.ch04 import cardan_joint, four_bar, slider_crank
from tests.browser.conftest import (
    open_lesson,
    readout_values,
    show_scene_and_keep_screenshot,
)

pytestmark = pytest.mark.browser


def _check_four_bar(values: dict) -> None:
    motion = four_bar.FourBarMotion.from_params(four_bar.PARAMETERS.defaults())
    assert values["grashof_class"] == "crank-rocker"
    state = motion.at(np.array([values["t_s"]]))
    # t is shown to 1 ms and μ to 0.01°: |dμ/dt| ≤ 32°/s here, so the two agree to 0.016° + 0.005°.
    assert values["transmission_angle"] == pytest.approx(math.degrees(state.transmission_angle[0]), abs=0.03)


def _check_slider_crank(values: dict) -> None:
    mech = slider_crank.SliderCrank(0.3, 1.0, 0.0)
    x_min, x_max = mech.stroke_limits_m
    assert values["stroke"] == pytest.approx(x_max - x_min, abs=1e-6)
    x, _ = mech.positions(np.array([math.radians(values["crank_angle"])]))
    # Crank angle rounded to 0.005°: x moves by at most r · 0.005° ≈ 3e-5 m.
    assert values["slider_position"] == pytest.approx(float(x[0]), abs=5e-5)


def _check_cardan(values: dict) -> None:
    joint = cardan_joint.CardanJoint(math.radians(30.0))
    assert values["speed_ratio_min"] == pytest.approx(math.cos(math.radians(30.0)), abs=1e-6)
    assert values["speed_ratio_max"] == pytest.approx(1 / math.cos(math.radians(30.0)), abs=1e-6)
    ratio = joint.speed_ratio(np.array([math.radians(values["input_angle"])]))[0]
    assert values["speed_ratio"] == pytest.approx(float(ratio), abs=2e-4)  # φ₁ rounded to 0.005°


def _check_rolling(values: dict) -> None:
    assert values["contact_point_velocity"] == "0.000"
    assert 0.0 <= values["contact_point_speed"] < 1e-14
    assert values["center_speed"] == pytest.approx(0.8 - 0.4 * (0.8 / 1.5) * math.sin(math.radians(20.0)), abs=1e-6)


LESSONS = [
    ("4-3-four-bar-linkage", "grashof_class", _check_four_bar),
    ("4-3-slider-crank", "stroke", _check_slider_crank),
    ("4-3-cardan-joint", "speed_ratio", _check_cardan),
    ("4-4-rolling", "contact_point_velocity", _check_rolling),
]


@pytest.mark.parametrize("lesson_id, quantity, check", LESSONS, ids=[lesson for lesson, _, _ in LESSONS])
def test_lesson_scene_connects_and_its_readout_matches_the_physics(browser, live_server, shots, lesson_id, quantity, check):
    context, page, session_id, errors = open_lesson(browser, live_server, f"/lessons/{lesson_id}")
    page.wait_for_selector(f'#readout [data-quantity="{quantity}"]', timeout=30_000)
    check(readout_values(page))
    show_scene_and_keep_screenshot(page, shots / f"lesson-{lesson_id}.png")
    assert not errors, errors
    json.dumps(readout_values(page))  # the readout stays plain JSON while the scene runs
    context.close()
