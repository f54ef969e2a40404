"""Numbers a student should not see, in Chromium against the served app (issue 29, item 9).

- the heavy top's energy bars: its splitting keeps the energy to round-off (a few 1e-12 of its 18 J), which showed as
  "dissipated −1.1e-11 J", a loss that never happened; now "0 J";
- worked example 1.1 at γ = 45°: M_A's x component was 4.5e-13 N·m (round-off of a 1.6e4 N·m cross product) in the
  solution's outputs table and its step (b); now 0;
- the torque-free body near its major axis: "time to next flip" has no number, only the words "no flips in this
  motion", and its unit cell said "s" beside them; now empty (the row of a number keeps its unit).
"""

from __future__ import annotations

import json

import pytest

from tests.browser.conftest import open_lesson, wait_for_polls
from tests.conftest import wait_until

pytestmark = pytest.mark.browser


def test_the_heavy_tops_energy_bars_show_no_dissipation(browser, live_server):
    context, page, session_id, errors = open_lesson(browser, live_server, "/lessons/10-2-spinning-top")
    wait_until(lambda: live_server.host.motion_state(session_id)["t_s"] > 3.0, timeout_s=30, what="the top to run 3 s")
    page.click("#graphs > summary")
    cell = '#graphs [data-energy="energy_dissipated_J"]'
    page.wait_for_selector(cell, timeout=15_000)
    # The bars show the latest kept frame; read them once the panel has an instant past 3 s.
    page.wait_for_function("() => /t = ([3-9]|\\d\\d+)\\.\\d\\d s/.test(document.getElementById('energy-bars-title').textContent)", timeout=15_000)
    value, text = page.evaluate(f"() => {{ const c = document.querySelector('{cell}'); return [JSON.parse(c.dataset.value), c.textContent]; }}")
    assert value == 0.0 and text == "0 J", (value, text)
    total = page.evaluate("() => JSON.parse(document.querySelector('#graphs [data-energy=\"energy_total_J\"]').dataset.value)")
    assert total > 1.0  # the scale against which the round-off was judged: 18 J
    assert not errors, errors
    context.close()


def test_example_1_1_shows_a_zero_component_as_zero(browser, live_server):
    context, page, session_id, errors = open_lesson(browser, live_server, "/lessons/1-1-vector-operations", viewer=False)
    page.wait_for_selector('#solution [data-output="M_A_Nm"]', timeout=20_000)
    page.fill("#ctl-gamma_deg", "45")
    page.press("#ctl-gamma_deg", "Enter")
    page.wait_for_function(
        "() => { const box = document.querySelector('#solution [data-example=\"1.1\"]');"
        " return box && JSON.parse(box.dataset.inputs).gamma_deg === 45; }",
        timeout=15_000,
    )
    cell = page.locator('#solution [data-output="M_A_Nm"]')
    moment = json.loads(cell.get_attribute("data-value"))
    assert moment[0] == 0.0 and abs(moment[1]) > 1e4 and abs(moment[2]) > 1e4, moment
    shown = cell.text_content()
    assert "e-" not in shown and shown.startswith("[0,"), shown
    step = page.locator("#solution .step", has_text="(b) Moment of F about A").locator("table.values td").nth(1).text_content()
    assert "e-" not in step and step.startswith("[0,"), step
    assert not errors, errors
    context.close()


def test_a_readout_word_has_no_unit_beside_it(browser, live_server):
    context, page, session_id, errors = open_lesson(browser, live_server, "/lessons/10-1-poinsot-construction")
    page.click('button[data-preset="major-axis"]')
    row = '#readout tr:has([data-quantity="next_flip"])'
    page.wait_for_function(
        f"() => {{ const c = document.querySelector('{row} [data-quantity]');"
        " return c && JSON.parse(c.dataset.value) === 'no flips in this motion'; }",
        timeout=20_000,
    )
    assert page.locator(f"{row} td.unit").text_content() == ""
    # A row whose value is a number keeps its unit.
    wait_for_polls(page, 1)
    units = page.evaluate(
        "() => [...document.querySelectorAll('#readout tbody tr')].map((tr) => [tr.children[1].dataset.quantity,"
        " JSON.parse(tr.children[1].dataset.value), tr.children[2].textContent])"
    )
    assert any(isinstance(value, (int, float)) and unit for _, value, unit in units), units
    assert all(unit == "" for _, value, unit in units if isinstance(value, str)), units
    assert not errors, errors
    context.close()
