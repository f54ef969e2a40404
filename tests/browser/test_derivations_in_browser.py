"""The formulations side by side on a lesson page (7.4): every column derived by the server and rendered by KaTeX."""

from __future__ import annotations

import pytest

from tests.browser.conftest import open_lesson, screenshot

pytestmark = pytest.mark.browser

LESSON = "7-4-generalized-forces"


def test_the_cart_pendulum_is_shown_by_five_formulations_and_routh_says_why_not(browser, live_server, shots):
    context, page, _, errors = open_lesson(browser, live_server, f"/lessons/{LESSON}", viewer=False)
    section = page.locator("#derivations")
    section.wait_for(state="visible", timeout=20_000)
    page.wait_for_function("document.querySelectorAll('#derivations .formulation[data-ready=\"true\"]').length === 5", timeout=60_000)
    columns = {c.get_attribute("data-formulation"): c for c in section.locator(".formulation").all()}
    assert set(columns) == {"newton-euler", "lagrange", "hamilton", "routh", "gibbs-appell", "kane"}
    assert "ignorable" in columns["routh"].inner_text()
    # Lagrange: two equations (x and θ); Newton–Euler: six (three per particle, reactions as unknowns).
    assert columns["lagrange"].locator(".equations > div").count() == 2
    assert columns["newton-euler"].locator(".equations > div").count() == 6
    assert columns["lagrange"].locator(".equations .katex").count() == 2
    assert page.locator("#derivations .katex-error").count() == 0
    # The generalized force of x is the push F₀ cos(Ωt): the last step for x says so.
    columns["lagrange"].locator("summary").click()
    assert "F_{0}" in columns["lagrange"].locator(".step").nth(5).locator("annotation").first.text_content()
    section.scroll_into_view_if_needed()
    screenshot(section, shots / f"lesson-{LESSON}-formulations.png")
    assert not errors, errors
    context.close()
