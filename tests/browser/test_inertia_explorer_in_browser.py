"""Lesson 5.2 in a real browser: the inertia explorer's readout, the body editor, and a refused entry.

The readout's numbers are the scene's own (JSON floats, full precision), so they must agree with
the worked example's solve to rounding: 1e-12 relative (two paths through the same sums).
"""

from __future__ import annotations

import pytest

from app.physics.systems import worked_examples
from tests.browser.conftest import (
    dismiss_webgl_notice,
    let_webgl_draw,
    open_lesson,
    readout_quantity,
    readout_values,
    screenshot,
    wait_for_polls,
)
from tests.conftest import wait_until

pytestmark = pytest.mark.browser

LESSON = "5-2-inertia-properties"
EXAMPLE = worked_examples()["inertia-of-composite-body"]
ADDED_BODY_KG = 1.0  # the editor's new row: a 1 kg sphere


def test_inertia_lesson_readout_body_editor_and_refused_entry(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, f"/lessons/{LESSON}")
    page.wait_for_selector('#readout [data-quantity="I_3"]', timeout=30_000)
    solved = EXAMPLE.solve(EXAMPLE.inputs.defaults()).outputs
    values = readout_values(page)
    for k in range(3):
        assert values[f"I_{k + 1}"] == pytest.approx(float(solved["principal_moments_kg_m2"][k]), rel=1e-12)
    assert values["mass"] == pytest.approx(solved["mass_kg"], rel=1e-12)
    assert page.locator(".katex-error").count() == 0

    # The body editor: one row per body of the default bracket; "add body" adds a 1 kg sphere.
    rows = page.locator(".body-editor .body-row")
    assert rows.count() == 3
    page.click(".body-editor .add-body")
    assert rows.count() == 4
    expected_mass = solved["mass_kg"] + ADDED_BODY_KG
    wait_until(lambda: readout_quantity(page, "mass") == pytest.approx(expected_mass, rel=1e-12), 20, what="the readout's mass to grow by 1 kg")
    assert len(live_server.host.session_params(session_id)["bodies"]) == 4

    # A bad entry (a radius of 200 m) is refused: that row and field are marked, the message names them, nothing changes.
    before = live_server.host.session_params(session_id)
    radius = page.locator('.body-row[data-index="3"] [data-field="radius_m"]')
    radius.fill("200")
    radius.press("Tab")
    page.wait_for_selector('.body-row[data-index="3"].invalid [data-field="radius_m"].invalid', timeout=10_000)
    assert page.locator(".body-row.invalid").count() == 1
    message = page.locator("#control-error").text_content()
    assert message.startswith("bodies, body 4, radius (m):") and "100" in message, message  # the editor's own words
    assert live_server.host.session_params(session_id) == before
    wait_for_polls(page, 2)  # two readout polls later, the scene still shows the 4-body composite
    assert readout_quantity(page, "mass") == pytest.approx(expected_mass, rel=1e-12)

    # Fixing the entry clears the marks and the scene takes it.
    radius.fill("0.06")
    radius.press("Tab")
    page.wait_for_function("document.querySelectorAll('.body-row.invalid').length === 0")
    wait_until(lambda: live_server.host.session_params(session_id)["bodies"][3]["radius_m"] == 0.06, 10, what="the fixed radius to reach the scene")

    # Back to the default bracket for the screenshot.
    page.click("#reset")
    wait_until(lambda: readout_quantity(page, "mass") == pytest.approx(solved["mass_kg"], rel=1e-12), 20, what="the default body")
    page.evaluate("document.getElementById('viewer-wrap').scrollIntoView()")
    dismiss_webgl_notice(page)
    let_webgl_draw(page, 4000)
    screenshot(page, shots / f"lesson-{LESSON}.png")
    assert not errors, errors
    context.close()
