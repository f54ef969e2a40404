"""The sliding-ladder lesson page in a real browser: the viewer connects and the readout shows the physics."""

from __future__ import annotations

import json
import math

import pytest

from app.physics.systems.ch06 import sliding_ladder as sl
from tests.browser.conftest import (
    open_lesson,
    readout_values,
    show_scene_and_keep_screenshot,
)

pytestmark = pytest.mark.browser

LESSON = "6-2-sliding-ladder"


def test_ladder_lesson_connects_and_its_readout_matches_the_physics(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, f"/lessons/{LESSON}")
    page.wait_for_selector('#readout [data-quantity="separation_angle_closed_form_deg"]', timeout=30_000)
    values = readout_values(page)
    # The page shows the readout's numbers as sent (JSON doubles): the closed form to round-off.
    assert values["separation_angle_closed_form_deg"] == pytest.approx(math.degrees(math.asin(2.0 / 3.0 * math.sin(math.radians(60.0)))), rel=1e-12)
    params = sl.PARAMETERS.defaults()
    release = sl.phase_changes(params, t_end_s=2.0)[0]
    assert values["separation_time_s"] == pytest.approx(release.t_s, abs=1e-9)
    assert values["phase"] in set(sl.PHASE_WORDS.values())
    assert 0.0 <= values["angle_deg"] <= 60.0
    energy = params["mass_kg"] * params["g_m_s2"] * 0.5 * params["length_m"] * math.sin(math.radians(60.0))
    assert values["energy_total_J"] == pytest.approx(energy, rel=1e-6)  # the budget: drift ≤ 1e-6 at rtol 1e-8
    show_scene_and_keep_screenshot(page, shots / f"lesson-{LESSON}.png")
    assert not errors, errors
    json.dumps(readout_values(page))  # the readout stays plain JSON while the scene runs
    context.close()
