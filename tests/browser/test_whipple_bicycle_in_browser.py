"""The bicycle lesson in a real browser: the eigenvalue plot's stable band, the scene's verdict, a design change."""

from __future__ import annotations

import json

import pytest

from tests.browser.conftest import dismiss_webgl_notice, open_lesson, readout_values, screenshot, show_scene_and_keep_screenshot
from tests.physics.mechanics.multibody.test_whipple_bicycle import CAPSIZE_M_S, WEAVE_M_S

pytestmark = pytest.mark.browser

LESSON = "9-3-whipple-bicycle"


def _crossings(page) -> list[float]:
    return json.loads(page.get_attribute(".stability[data-system='whipple-bicycle']", "data-crossings"))


def test_the_plot_marks_the_published_band_the_scene_says_stable_and_a_design_change_moves_the_band(browser, live_server, shots):
    context, page, _, errors = open_lesson(browser, live_server, f"/lessons/{LESSON}")
    dismiss_webgl_notice(page)
    page.wait_for_selector(".stability[data-crossings]", timeout=60_000)
    weave, capsize = _crossings(page)
    assert abs(weave - WEAVE_M_S) < 1e-6 and abs(capsize - CAPSIZE_M_S) < 1e-6
    summary = page.text_content(".stability-summary")
    assert "weave speed 4.292 m/s" in summary and "capsize speed 6.024 m/s" in summary
    assert page.locator(".stability svg .band").count() == 1 and page.locator(".stability svg .marker").count() == 2
    # The default 4.6 m/s lies inside the band: the scene's readout says so, from the same eigenvalues.
    page.wait_for_selector('#readout [data-quantity="upright_stability"]', timeout=40_000)
    assert readout_values(page)["upright_stability"].startswith("stable")
    screenshot(page.locator("#linearised"), shots / "whipple-bicycle-eigenvalues.png")

    page.get_by_role("button", name="Too slow, 3 m/s: the weave grows").click()
    page.wait_for_function(
        "() => (document.querySelector('#readout [data-quantity=\"upright_stability\"]')?.dataset.value || '').includes('unstable')",
        timeout=40_000,
    )
    # A longer trail moves the band: the plot asks again with the scene's new design.
    page.fill("#ctl-trail_m", "0.12")
    page.press("#ctl-trail_m", "Enter")
    page.wait_for_function(
        f"() => {{ const c = document.querySelector('.stability')?.dataset.crossings; return c && JSON.parse(c)[0] !== {weave!r}; }}",
        timeout=60_000,
    )
    assert _crossings(page) != [weave, capsize]
    show_scene_and_keep_screenshot(page, shots / f"lesson-{LESSON}.png")
    assert not errors, errors
    context.close()
