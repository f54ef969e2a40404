"""Section 6.4, the bouncing bar, in a real browser: the viewer connects and the readout follows the impacts to rest."""

from __future__ import annotations

import httpx
import pytest

from app.physics.systems.ch06 import bouncing_bar
from tests.browser.conftest import (
    dismiss_webgl_notice,
    let_webgl_draw,
    open_lesson,
    readout_quantity,
    readout_values,
    screenshot,
)
from tests.conftest import wait_until

pytestmark = pytest.mark.browser

LESSON = "6-4-bouncing-bar"


def test_bouncing_bar_lesson_counts_impacts_keeps_the_energy_ledger_and_comes_to_rest(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, f"/lessons/{LESSON}")
    page.wait_for_selector('#readout [data-quantity="impact_count"]', timeout=30_000)
    wait_until(lambda: (readout_quantity(page, "impact_count") or 0) >= 1, 30, what="the first impact in the readout")
    values = readout_values(page)
    # Kinetic + potential + lost is m g h₀ = 9.807 J at the defaults (the physics keeps it to 1e-9 relative).
    assert values["energy_J"] + values["energy_lost_J"] == pytest.approx(9.807, rel=1e-8)
    assert values["slip_state"] in bouncing_bar.SLIP_NAMES[1:]
    assert values["last_energy_loss_J"] > 0.0
    assert page.locator(".katex-error").count() == 0
    # At the defaults the bar rests after 17 impacts, 1.3 s of simulated time (real time here).
    wait_until(lambda: readout_quantity(page, "mode") == "resting", 40, what="the bar to come to rest")
    values = readout_values(page)
    assert values["impact_count"] == 17
    assert values["energy_lost_J"] == pytest.approx(9.807, rel=1e-8)
    assert "Resting" in page.locator("#readout .readout-message").inner_text()
    # Try-this 5 (e = 1, μ = 0, here from 45°): it bounces for ever, losing nothing; the screenshot shows it in flight.
    host = live_server.host
    elastic = {"restitution": 1.0, "friction_coefficient": 0.0, "angle0_deg": 45.0}
    # The page claimed its session with its key: a change from outside the page must carry it (without it: 403).
    url = f"{live_server.url}/api/scenes/bouncing-bar/sessions/{session_id}"
    assert httpx.put(url, json={"params": elastic}).status_code == 403
    key = page.evaluate("async () => (await import('/static/js/lesson.js')).lesson.session.key")
    assert httpx.put(url, json={"params": elastic}, headers={"X-Session-Key": key}).status_code == 200
    wait_until(lambda: host.session_params(session_id)["restitution"] == 1.0, 15, what="the scene to take the new parameters")
    def bouncing_elastically() -> bool:
        now = readout_values(page)
        return now.get("mode") == "flight" and now.get("impact_count", 0) >= 3

    wait_until(bouncing_elastically, 30, what="the restarted bar's elastic impacts in the readout")
    values = readout_values(page)
    assert values["energy_lost_J"] == 0.0 and values["mode"] == "flight"
    assert values["energy_J"] == pytest.approx(9.807, rel=1e-12)
    page.evaluate("document.getElementById('viewer-wrap').scrollIntoView()")
    dismiss_webgl_notice(page)
    let_webgl_draw(page, 1500)
    screenshot(page, shots / f"lesson-{LESSON}.png")
    assert not errors, errors
    context.close()
