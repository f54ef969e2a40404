"""Lessons 9.2 and 9.3 in a real browser: the scenes connect and their readouts agree with the physics.

The readout cells carry full-precision values (``data-value``) read at one
instant, so the checks below recompute each number from others in the same
row set: only rounding separates them, and the integration's drift from the
initial values at the default fixed RK4 step was measured at up to 3e-6 relative (β) in the first seconds.
"""

from __future__ import annotations

import math

import pytest

from tests.browser.conftest import open_lesson, readout_values, show_scene_and_keep_screenshot

pytestmark = pytest.mark.browser

#: Conserved quantities against their initial values: RK4's drift at the default step is a few 1e-6 of the scales
#: (~2 to 10 J, kg·m²/s) in the first seconds; 1e-4 bounds it while a wrong β or H (off by ≥ 1e-2) fails.
CONSERVED_ABS = 1e-4


def test_hamilton_and_routh_lesson_shows_h_conserved_and_the_turning_angles(browser, live_server, shots):
    lesson = "9-2-hamilton-and-routh"
    context, page, _, errors = open_lesson(browser, live_server, f"/lessons/{lesson}")
    page.wait_for_selector('#readout [data-quantity="hamiltonian_J"]', timeout=60_000)
    values = readout_values(page)
    m, l, g = 1.0, 1.0, 9.81  # the defaults
    theta = math.radians(values["theta_deg"])
    hamiltonian = values["p_theta_kg_m2_s"] ** 2 / (2 * m * l * l) - m * g * l * math.cos(theta)
    assert values["hamiltonian_J"] == pytest.approx(hamiltonian, abs=1e-9)
    assert values["hamiltonian_J"] == pytest.approx(-m * g * l * math.cos(math.radians(60.0)), abs=CONSERVED_ABS)
    assert values["separatrix_J"] == pytest.approx(9.81, rel=1e-12)
    assert values["formulation_agreement"] < 1e-12
    show_scene_and_keep_screenshot(page, shots / f"lesson-{lesson}-phase-portrait.png")
    assert not errors, errors
    context.close()


def test_spherical_pendulum_scene_shows_beta_and_the_turning_angles(browser, live_server, shots):
    lesson = "9-2-hamilton-and-routh"
    context, page, _, errors = open_lesson(browser, live_server, f"/lessons/{lesson}?scene=spherical-pendulum")
    page.wait_for_selector('#readout [data-quantity="beta_kg_m2_s"]', timeout=60_000)
    values = readout_values(page)
    beta = math.sin(math.radians(60.0)) ** 2 * math.radians(120.0)  # m l² sin²θ0 φ̇0 at the defaults
    assert values["beta_kg_m2_s"] == pytest.approx(beta, abs=CONSERVED_ABS)
    # The cubic's roots at the defaults (θ̇0 = 0, so θ_max is the release angle exactly).
    assert values["theta_max_deg"] == pytest.approx(60.0, abs=1e-9)
    assert values["theta_min_deg"] == pytest.approx(28.71888696, abs=1e-7)
    assert values["theta_min_deg"] - 1e-6 <= values["theta_deg"] <= values["theta_max_deg"] + 1e-6
    show_scene_and_keep_screenshot(page, shots / f"lesson-{lesson}-spherical-pendulum.png")
    assert not errors, errors
    context.close()


def test_gibbs_appell_and_kane_lesson_shows_the_rolling_disk(browser, live_server, shots):
    lesson = "9-3-gibbs-appell-and-kane"
    context, page, _, errors = open_lesson(browser, live_server, f"/lessons/{lesson}")
    page.wait_for_selector('#readout [data-quantity="critical_spin_rad_s"]', timeout=60_000)
    values = readout_values(page)
    assert values["critical_spin_rad_s"] == pytest.approx(math.sqrt(9.81 / 0.3), rel=1e-6)
    # ẋ, ẏ are integrated states: they keep to the rolling constraint to the integration's accuracy.
    assert values["contact_speed_m_s"] == pytest.approx(values["rolling_speed_m_s"], rel=1e-6)
    assert values["energy_J"] == pytest.approx(2.04609641, abs=1e-6)
    assert values["formulation_agreement"] < 1e-12
    show_scene_and_keep_screenshot(page, shots / f"lesson-{lesson}.png")
    assert not errors, errors
    context.close()
