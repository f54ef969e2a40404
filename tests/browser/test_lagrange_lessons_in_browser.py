"""The chapter-7 Lagrange lessons in a real browser: the live scenes' readouts against the physics."""

from __future__ import annotations

import json
import math

import pytest

from app.physics.systems.ch07.bead_on_hoop_model import critical_spin_rad_s
from app.physics.systems.ch07.double_pendulum_model import normal_mode_frequencies_rad_s
from tests.browser.conftest import open_lesson, readout_values, show_scene_and_keep_screenshot

pytestmark = pytest.mark.browser


def open_running_lesson(browser, live_server, lesson: str, quantity: str):
    """Open ``lesson``, wait for the readout row ``quantity`` and for 1 s of simulated time; (context, page, errors)."""
    context, page, _, errors = open_lesson(browser, live_server, f"/lessons/{lesson}")
    page.wait_for_selector(f'#readout [data-quantity="{quantity}"]', timeout=30_000)
    page.wait_for_function("() => Number(document.querySelector('#readout [data-quantity=\"t_s\"]').dataset.value) > 1.0", timeout=30_000)
    return context, page, errors


def test_double_pendulum_lesson_shows_its_modes_and_a_conserved_energy(browser, live_server, shots):
    lesson = "7-5-lagranges-equations"
    context, page, errors = open_running_lesson(browser, live_server, lesson, "energy_J")
    values = readout_values(page)
    defaults = {"m1_kg": 1.0, "m2_kg": 1.0, "l1_m": 1.0, "l2_m": 1.0, "g_m_s2": 9.81}
    slow, fast = normal_mode_frequencies_rad_s(defaults)
    # Shown numbers are rounded for display; 1e-3 relative is far inside the gap to any other formula.
    assert values["slow_mode_rad_s"] == pytest.approx(math.sqrt(9.81 * (2 - math.sqrt(2))), rel=1e-3) == pytest.approx(slow, rel=1e-3)
    assert values["fast_mode_rad_s"] == pytest.approx(fast, rel=1e-3)
    # Released at rest from θ₁ = 60°, θ₂ = 0: E = −19.62 J; RK4 at the automatic step keeps it within 0.1% of the 58.9 J scale.
    assert values["energy_J"] == pytest.approx(-19.62, abs=0.06)
    assert values["energy_drift"] < 1e-3
    assert values["formulation_agreement"] < 1e-12
    show_scene_and_keep_screenshot(page, shots / f"lesson-{lesson}.png")
    assert not errors, errors
    json.dumps(readout_values(page))
    context.close()


def test_bead_on_hoop_lesson_shows_the_bifurcation_and_the_jacobi_integral(browser, live_server, shots):
    lesson = "7-6-bead-on-hoop"
    context, page, errors = open_running_lesson(browser, live_server, lesson, "jacobi_integral_J")
    values = readout_values(page)
    defaults = {"g_m_s2": 9.81, "hoop_radius_m": 0.5}
    assert values["critical_spin_rad_s"] == pytest.approx(critical_spin_rad_s(defaults), rel=1e-3)
    assert math.cos(math.radians(values["off_bottom_equilibrium_deg"])) == pytest.approx(9.81 / (0.5 * 6.0**2), rel=1e-3)
    # h at the start (θ₀ = 20°, at rest): −½ m R² Ω² sin²θ₀ − m g R cos θ₀ = −0.5136 J; it must not move (drift below 1e-3 of
    # its 1.88 J scale); E is not conserved but E − h = 2 T₀ = m R² Ω² sin²θ at the shown θ (to its display rounding).
    start_h = -0.5 * 0.1 * 0.25 * 36.0 * math.sin(math.radians(20.0)) ** 2 - 0.1 * 9.81 * 0.5 * math.cos(math.radians(20.0))
    assert values["jacobi_integral_J"] == pytest.approx(start_h, abs=2e-3)
    assert values["jacobi_integral_drift"] < 1e-3
    theta = math.radians(values["theta_deg"])
    assert values["energy_J"] - values["jacobi_integral_J"] == pytest.approx(0.1 * 0.25 * 36.0 * math.sin(theta) ** 2, abs=2e-3)
    show_scene_and_keep_screenshot(page, shots / f"lesson-{lesson}.png")
    assert not errors, errors
    context.close()
