"""The heavy-top lesson in a real browser: the live panel states the accuracy target, the estimate and the phase error."""

from __future__ import annotations

import re

import pytest

from tests.browser.conftest import open_lesson, screenshot, show_scene_and_keep_screenshot

pytestmark = pytest.mark.browser

LESSON = "10-2-spinning-top"


def test_live_panel_shows_target_estimate_and_error_against_the_quadrature(browser, live_server, shots):
    context, page, _, errors = open_lesson(browser, live_server, f"/lessons/{LESSON}")
    page.wait_for_selector('#live [data-live="reference_error"]:not([hidden])', timeout=40_000)
    # The restart starts at once with the fixed step rule ("estimating…") and its pilot runs off the frame loop:
    # wait for the measured choice to be in before reading it.
    page.wait_for_selector('#live [data-live="accuracy"][data-status="ok"]', timeout=40_000)
    accuracy = page.inner_text('#live [data-live="accuracy"]')
    assert re.search(r"target 1e-06 rad over 60 s · estimated \de-0[6-9] rad · \d+ steps?/frame", accuracy), accuracy
    estimated = float(page.get_attribute('#live [data-live="accuracy"]', "data-estimated"))
    assert estimated <= 1e-6
    # The error against the quadrature stays below the target the panel states (measured, not assumed).
    error = float(page.get_attribute('#live [data-live="reference_error"]', "data-value"))
    assert 0.0 <= error <= 1e-6
    assert "quadrature" in page.inner_text('#live [data-live="reference_error"]')
    show_scene_and_keep_screenshot(page, shots / f"lesson-{LESSON}-accuracy.png")
    page.locator("#live").scroll_into_view_if_needed()
    screenshot(page.locator("#live"), shots / f"lesson-{LESSON}-accuracy-panel.png")
    assert not errors, errors
    context.close()
