"""Section 10.3 lesson pages in a real browser: the 3D viewer connects, the readout table shows the
scene's numbers (checked against app.physics), KaTeX renders every formula, and a screenshot of each
page goes to docs/screenshots/ (with DYNLAB_UPDATE_SCREENSHOTS=1) for a person to look at."""

from __future__ import annotations

import math

import pytest

from app.physics.systems.ch10 import free_gyroscope, gyrocompass, rate_gyro
from tests.browser.conftest import let_webgl_draw, open_lesson, readout_values, screenshot, wait_for_math

pytestmark = pytest.mark.browser


def _open_lesson(browser, live_server, lesson_id):
    context, page, session_id, errors = open_lesson(browser, live_server, f"/lessons/{lesson_id}")
    page.wait_for_selector("#readout [data-quantity]", timeout=30_000)
    return context, page, session_id, errors


def _finish(context, page, errors, shots, lesson_id):
    wait_for_math(page)
    assert page.locator(".katex-error").count() == 0
    assert page.locator(".lesson-text .katex").count() > 20  # the formulas were typeset
    page.evaluate("document.getElementById('viewer-wrap').scrollIntoView()")
    let_webgl_draw(page, 3000)
    screenshot(page, shots / f"lesson-{lesson_id}.png")
    assert not errors, errors
    context.close()


def test_free_gyroscope_lesson(browser, live_server, shots):
    """Default yaw turn: the outer ring turns back at the yaw rate, the inner ring stays level."""
    context, page, session_id, errors = _open_lesson(browser, live_server, "10-3-free-gyroscope")
    values = readout_values(page)
    assert values["outer_gimbal_rate_rad_s"] == pytest.approx(-0.3, abs=1e-12)
    assert values["inner_gimbal_deg"] == pytest.approx(0.0, abs=1e-9)
    assert values["angular_momentum_N_m_s"] == pytest.approx(free_gyroscope.angular_momentum_N_m_s(free_gyroscope.PARAMETERS.defaults()))
    t = values["t_s"]
    assert values["outer_gimbal_deg"] == pytest.approx(math.degrees(math.remainder(-0.3 * t, 2 * math.pi)), abs=1e-9)
    _finish(context, page, errors, shots, "10-3-free-gyroscope")


def test_gyrocompass_lesson(browser, live_server, shots):
    """The readout's periods are the physics module's formulas; the integration panel names the time scale."""
    context, page, session_id, errors = _open_lesson(browser, live_server, "10-3-gyrocompass")
    params = gyrocompass.PARAMETERS.defaults()
    values = readout_values(page)
    assert values["small_angle_period_s"] == pytest.approx(97.8286, abs=1e-4)
    assert values["small_angle_period_s"] == pytest.approx(gyrocompass.small_angle_period_s(params), rel=1e-15)
    assert values["swing_period_s"] == pytest.approx(gyrocompass.large_amplitude_period_s(params, math.radians(40.0)), rel=1e-12)
    assert values["time_scale"] == 10.0
    page.wait_for_selector('#live [data-drift="energy_plus_dissipated_J"]', timeout=20_000)
    assert "10× real time" in page.text_content('#live [data-live="description"]')
    assert float(page.text_content('#live [data-drift="energy_plus_dissipated_J"]')) < 1e-8
    _finish(context, page, errors, shots, "10-3-gyrocompass")


def test_rate_gyro_lesson(browser, inprocess_live_server, shots):
    """Gain, natural frequency and damping ratio in the readout; the critical damping marked on its slider."""
    live_server = inprocess_live_server  # the readout's β is compared with the scene instance's own demonstration
    context, page, session_id, errors = _open_lesson(browser, live_server, "10-3-rate-gyro")
    values = readout_values(page)
    assert values["steady_gain_s"] == pytest.approx(0.4, rel=1e-15)
    assert values["natural_frequency_rad_s"] == pytest.approx(10.0, rel=1e-14)
    assert values["damping_ratio"] == pytest.approx(0.2, rel=1e-14)
    scene = live_server.host.instances(session_id)[0]
    assert values["beta_rad"] == pytest.approx(scene.demonstration(values["t_s"])[0], abs=1e-15)
    mark = page.locator('.control[data-name="damping_N_m_s_rad"] .mark')
    assert mark.count() == 1
    assert float(mark.get_attribute("data-value")) == pytest.approx(rate_gyro.critical_damping_N_m_s_rad(rate_gyro.PARAMETERS.defaults()))
    _finish(context, page, errors, shots, "10-3-rate-gyro")
