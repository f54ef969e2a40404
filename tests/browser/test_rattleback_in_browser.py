"""The rattleback lesson in a real browser: the scene spins, rattles and reverses; the eigenvalue plot against the
spin says it is unstable both ways; a preset and a design change move both."""

from __future__ import annotations

import pytest

from tests.browser.conftest import (
    dismiss_webgl_notice,
    open_lesson,
    readout_values,
    screenshot,
    show_scene_and_keep_screenshot,
)

pytestmark = pytest.mark.browser

LESSON = "8-2-rattleback"


def test_spun_anticlockwise_it_reverses_and_the_plot_says_unstable_both_ways(browser, live_server, shots):
    context, page, _, errors = open_lesson(browser, live_server, f"/lessons/{LESSON}")
    dismiss_webgl_notice(page)
    page.wait_for_selector(".stability[data-crossings]", timeout=60_000)
    summary = page.text_content(".stability-summary")
    assert "Unstable at every" in summary and "rad/s" in summary
    assert page.locator(".stability svg .band").count() == 0
    screenshot(page.locator("#linearised"), shots / "rattleback-eigenvalues.png")
    # Kane and Levinson's start, 5 rad/s anticlockwise: the readout's verdict comes from the same eigenvalues.
    page.wait_for_selector('#readout [data-quantity="spin_stability"]', timeout=40_000)
    assert readout_values(page)["spin_stability"].startswith("unstable")
    # The spin passes through zero at 2.35 s of model time and settles near −5.2 rad/s.
    page.wait_for_function(
        "() => { const q = document.querySelector('#readout [data-quantity=\"spin_rad_s\"]');"
        " return q && JSON.parse(q.dataset.value) < -1; }",
        timeout=90_000,
    )
    assert readout_values(page)["spin_rad_s"] < -1.0
    show_scene_and_keep_screenshot(page, shots / f"lesson-{LESSON}.png")

    page.get_by_role("button", name="Tapped at one end: it starts to spin clockwise").click()
    page.wait_for_function(
        "() => (document.querySelector('#readout [data-quantity=\"spin_stability\"]')?.dataset.value || '')"
        ".includes('at rest')",
        timeout=40_000,
    )
    assert not errors, errors
    context.close()
