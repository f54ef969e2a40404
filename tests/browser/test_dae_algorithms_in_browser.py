"""The DAE-algorithms lesson in a real browser: the Cartesian pendulum connects, stays on its circle, and its multiplier is the tension."""

from __future__ import annotations

import json

import pytest

from tests.browser.conftest import open_lesson, readout_values, show_scene_and_keep_screenshot

pytestmark = pytest.mark.browser

LESSON = "8-2-dae-algorithms"


def test_cartesian_pendulum_keeps_its_rod_and_reports_the_tension(browser, live_server, shots):
    context, page, _, errors = open_lesson(browser, live_server, f"/lessons/{LESSON}")
    page.wait_for_selector('#readout [data-quantity="constraint_position_m2"]', timeout=30_000)
    page.wait_for_function(
        "() => { const c = document.querySelector('#readout [data-quantity=\"t_s\"]'); return c && JSON.parse(c.dataset.value) > 1.0; }",
        timeout=30_000,
    )
    values = readout_values(page)
    m, length, g, y0 = 1.0, 1.0, 9.81, -0.6  # the defaults: released at rest from (0.8, −0.6) m
    # Default method: projection after every step, so the rod keeps its length to round-off.
    assert values["distance_m"] == pytest.approx(length, abs=1e-12)
    assert values["constraint_position_m2"] < 1e-12 and values["constraint_velocity_m2_s"] < 1e-12
    # Energy: RK4 at the automatic 2 steps/frame drifts by 1.4e-5 J over 60 s (measured off-screen); 1e-3 J is generous.
    assert values["energy_J"] == pytest.approx(m * g * y0, abs=1e-3)
    # λ = T/L with T = m g (−y/L) + m v²/L and v² from the readout's own energy: the same instant, so round-off only.
    y = values["y_m"]
    speed_squared = 2.0 * (values["energy_J"] - m * g * y) / m
    assert values["multiplier_N_m"] == pytest.approx((-m * g * y + m * speed_squared) / length**2, abs=1e-9)
    assert values["multiplier_N_m"] > 0.0  # the rod pulls: tension
    show_scene_and_keep_screenshot(page, shots / f"lesson-{LESSON}.png")
    assert not errors, errors
    json.dumps(readout_values(page))
    context.close()
