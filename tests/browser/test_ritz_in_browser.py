"""The Ritz-series lesson in a real browser: the viewer connects and the readout's frequencies are the physics'."""

from __future__ import annotations

import json

import pytest

from app.physics.systems.ch09 import ritz_beam as physics
from tests.browser.conftest import open_lesson, readout_values, show_scene_and_keep_screenshot

pytestmark = pytest.mark.browser

LESSON = "9-1-ritz-series"


def test_lesson_scene_connects_and_its_first_frequency_is_the_ritz_value(browser, live_server, shots):
    context, page, _, errors = open_lesson(browser, live_server, f"/lessons/{LESSON}")
    page.wait_for_selector('#readout [data-quantity="omega_ritz_1_rad_s"]', timeout=30_000)
    values = readout_values(page)
    ritz = physics.RitzCantilever.from_params(physics.PARAMETERS.defaults())
    # The readout carries the server's float through JSON unchanged: equal to rounding of the repr (1e-12 relative).
    assert values["omega_ritz_1_rad_s"] == pytest.approx(float(ritz.ritz_omega_rad_s[0]), rel=1e-12)
    assert values["omega_exact_1_rad_s"] == pytest.approx(1.875104068711961**2 * 50.0**0.5, rel=1e-14)
    # Six terms at the defaults: every frequency above its exact value, the sixth the worst.
    errors_by_mode = [values[f"relative_error_{n}"] for n in range(1, 7)]
    assert all(error >= -physics.BOUND_SLACK for error in errors_by_mode) and errors_by_mode[-1] == max(errors_by_mode)
    assert values["condition_number_M"] == pytest.approx(8.19e4, rel=1e-2)
    show_scene_and_keep_screenshot(page, shots / f"lesson-{LESSON}.png")
    assert not errors, errors
    json.dumps(readout_values(page))  # the readout stays plain JSON while the scene runs
    context.close()
