"""The 10.1 lesson in a real browser: the scene connects, animates, and its readout matches the closed form."""

from __future__ import annotations

import math

import pytest

from app.physics.systems.ch10 import torque_free_axisymmetric as physics
from tests.browser.conftest import let_webgl_draw, open_lesson, readout_values, screenshot
from tests.conftest import wait_until

pytestmark = pytest.mark.browser

LESSON = "/lessons/10-1-axisymmetric-free-motion"


def test_lesson_scene_readout_matches_the_closed_form_and_presets_switch_the_sense(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, LESSON, timeout_s=30)
    host = live_server.host
    page.wait_for_selector('#readout [data-quantity="precession_rate"]', timeout=45_000)
    assert page.locator(".katex-error").count() == 0

    # Default (prolate) body: the page shows the model's own numbers.
    motion = physics.motion_from_params(physics.PARAMETERS.defaults())
    shown = readout_values(page)
    assert shown["precession_rate"] == pytest.approx(motion.precession_rate_rad_s, rel=1e-15)
    assert shown["spin_rate"] == pytest.approx(motion.spin_rate_rad_s, rel=1e-15)
    assert shown["body_cone_half_angle"] + shown["space_cone_half_angle"] == pytest.approx(25.0, rel=1e-13)
    assert shown["sense"] == "direct"
    wait_until(lambda: (host.playback(session_id) or {}).get("t_s", 0.0) > 1.0, 20, what="the scene to animate")
    page.evaluate("document.getElementById('viewer-wrap').scrollIntoView()")
    let_webgl_draw(page, 3000)
    screenshot(page, shots / "lesson-10-1-axisymmetric-free-motion.png")

    # The coin preset: oblate, retrograde, the space cone inside the body cone.
    page.click('button[data-preset="coin"]')
    wait_until(lambda: host.session_params(session_id)["I_axial"] == 0.99, 15, what="the scene to take the coin preset")
    page.wait_for_function(
        "() => { const c = document.querySelector('#readout [data-quantity=\"sense\"]'); return c && JSON.parse(c.dataset.value) === 'retrograde'; }",
        timeout=45_000,
    )
    coin = readout_values(page)
    beta, gamma = coin["body_cone_half_angle"], coin["space_cone_half_angle"]
    assert beta - gamma == pytest.approx(15.0, rel=1e-13) and math.isclose(coin["spin_rate"], -0.98, rel_tol=1e-13)
    page.evaluate("document.getElementById('viewer-wrap').scrollIntoView()")
    let_webgl_draw(page, 2500)
    screenshot(page, shots / "lesson-10-1-axisymmetric-free-motion-coin.png")
    assert not errors, errors
    context.close()
