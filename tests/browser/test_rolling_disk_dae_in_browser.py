"""The unsteady-rolling-disk lesson in a real browser: the scene runs and the readout shows the threshold and the slip residual."""

from __future__ import annotations

import json
import math

import pytest

from tests.browser.conftest import open_lesson, readout_values, show_scene_and_keep_screenshot
from tests.conftest import wait_until

pytestmark = pytest.mark.browser

LESSON = "8-2-unsteady-rolling-disk"


def test_lesson_scene_rolls_and_the_readout_shows_the_critical_spin_and_a_zero_slip_speed(browser, live_server, shots):
    context, page, _, errors = open_lesson(browser, live_server, f"/lessons/{LESSON}")
    page.wait_for_selector('#readout [data-quantity="critical_spin_rad_s"]', timeout=30_000)
    first = readout_values(page)
    # Defaults r = 0.1 m, g = 9.81 m/s²: Ω_c = √(g/(3r)) (the app's root finder is good to 1e-11 relative).
    assert first["critical_spin_rad_s"] == pytest.approx(math.sqrt(9.81 / 0.3), rel=1e-6)
    assert first["upright_stability"] == "upright rolling at 12.0 rad/s is stable (critical 5.7 rad/s)"
    wait_until(lambda: readout_values(page)["t_s"] > first["t_s"] + 0.5, 20.0, what="the disk to roll on")
    values = readout_values(page)
    # Projection (method auto) keeps the contact point's slip speed at round-off (2e-16 m/s measured); the energy
    # drifts ~2e-9 of its scale in 30 s with RK4 at 12 steps per frame.
    assert values["constraint_velocity_m_s"] < 1e-12
    assert values["energy_drift"] < 1e-7
    assert values["energy_J"] == pytest.approx(2.046, abs=1e-3)  # ½ v·M v + m g r cos 10° at the default start
    assert 5.0 < abs(values["lean_deg"]) < 20.0  # the default start wobbles between 10° and 15.7°
    show_scene_and_keep_screenshot(page, shots / f"lesson-{LESSON}.png")
    assert not errors, errors
    json.dumps(readout_values(page))  # the readout stays plain JSON while the scene runs
    context.close()
