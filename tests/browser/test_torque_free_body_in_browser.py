"""Real browser: the Poinsot lesson (10.1) — its scene's readout matches the physics, presets and the ghost work.

One test, serial, like the other browser tests: one viser tab costs about a core of software rendering.
"""

from __future__ import annotations

import numpy as np
import pytest

from app.physics.systems.ch10 import torque_free_body as tfb
from tests.browser.conftest import let_webgl_draw, open_lesson, readout_quantity, screenshot
from tests.conftest import wait_until

pytestmark = pytest.mark.browser

LESSON = "/lessons/10-1-poinsot-construction"


def test_poinsot_lesson_readout_presets_and_ghost(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, LESSON, timeout_s=30)
    host = live_server.host
    page.wait_for_selector('#readout [data-quantity="energy"]', timeout=20_000)

    # The readout is the physics of the default book: T = ½ Σ I ω², |L| = |I ω|, axis 2 intermediate.
    defaults = tfb.PARAMETERS.defaults()
    inertia, omega0 = tfb.inertia_of(defaults), np.array(defaults["omega0_rad_s"])
    assert readout_quantity(page, "energy") == pytest.approx(0.5 * np.sum(inertia * omega0**2), rel=1e-12)
    assert readout_quantity(page, "angular_momentum") == pytest.approx(np.linalg.norm(inertia * omega0), rel=1e-12)
    assert readout_quantity(page, "period") == pytest.approx(tfb.motion(defaults).period_s, rel=1e-12)
    assert readout_quantity(page, "intermediate_axis").startswith("2 ")
    assert page.locator(".katex-error").count() == 0
    let_webgl_draw(page, 4000)  # and the trails grow
    page.evaluate("document.getElementById('viewer-wrap').scrollIntoView()")
    let_webgl_draw(page, 1500)
    screenshot(page, shots / "lesson-10-1-poinsot-construction.png")

    # The tennis-racket preset with the numerical ghost on: the scene flips, and RK4 keeps up with the closed form.
    page.click('button[data-preset="tennis-racket"]')
    page.select_option("#ctl-ghost", "on")
    wait_until(
        lambda: host.session_params(session_id)["ghost"] == "on"
        and host.session_params(session_id)["omega0_rad_s"] == [0.1, 4.0, 0.1],
        15, what="the scene to take the preset and the ghost",
    )
    # 5.5 s of the flip in about 1.4 s
    page.evaluate("async () => (await import('/static/js/lesson.js')).lesson.setPlayback({time_scale: 4})")
    page.wait_for_function(
        "() => { const c = document.querySelector('#readout [data-quantity=\"t_s\"]'); return c && JSON.parse(c.dataset.value) > 5.5; }",
        timeout=30_000,
    )
    page.wait_for_selector('#readout [data-quantity="ghost_attitude_difference"]', timeout=10_000)
    difference = readout_quantity(page, "ghost_attitude_difference")
    assert 0.0 <= difference < 1e-6  # measured ~1e-9 rad after a few seconds
    next_flip = readout_quantity(page, "next_flip")
    assert isinstance(next_flip, float) and 0.0 < next_flip <= 0.5 * tfb.motion(host.session_params(session_id)).period_s
    assert "turns over every 4.31 s" in page.text_content("#readout .readout-message")
    page.evaluate("document.getElementById('viewer-wrap').scrollIntoView()")
    let_webgl_draw(page, 1500)
    screenshot(page, shots / "lesson-10-1-poinsot-construction-ghost.png")
    assert not errors, errors
    context.close()
