"""The sliding-ladder lesson page in a real browser: the viewer connects and the readout shows the physics."""

from __future__ import annotations

import json
import math

import pytest

from app.physics.systems.ch06 import sliding_ladder as sl
from tests.browser.conftest import (
    open_lesson,
    readout_values,
    show_scene_and_keep_screenshot,
)
from tests.browser.test_graphs_in_browser import pick, points
from tests.conftest import wait_until

pytestmark = pytest.mark.browser

LESSON = "6-2-sliding-ladder"


#: In the page: from now on, note every moment the graph is hidden, drawn empty or plots something other than the
#: student's choice, and count the replays (the plotted span's end going back in time).
WATCH_THE_GRAPH = """([y, x]) => {
  const box = document.querySelector('#graphs .time-graph');
  const watch = window.__graphWatch = { replays: 0, faults: [], lastEnd: null };
  const look = () => {
    const y1 = document.getElementById('graph-y1').value, xPick = document.getElementById('graph-x').value;
    if (box.hidden) watch.faults.push('graph hidden');
    if (y1 !== y || xPick !== x) watch.faults.push(`plots ${y1} against ${xPick}`);
    if (!box.querySelector('.graph-plot svg polyline')) watch.faults.push('no line drawn');
    const end = /to (-?[0-9.]+) s;/.exec(box.querySelector('.graph-summary').textContent);
    if (end) {
      const t = Number(end[1]);
      if (watch.lastEnd !== null && t < watch.lastEnd) watch.replays += 1;
      watch.lastEnd = t;
    }
  };
  new MutationObserver(look).observe(box, { subtree: true, childList: true, attributes: true, characterData: true });
}"""


def test_ladder_lesson_connects_its_readout_matches_the_physics_and_a_replay_keeps_the_graph(
    browser, live_server, shots
):
    context, page, _, errors = open_lesson(browser, live_server, f"/lessons/{LESSON}")
    page.wait_for_selector('#readout [data-quantity="separation_angle_closed_form_deg"]', timeout=30_000)
    values = readout_values(page)
    # The page shows the readout's numbers as sent (JSON doubles): the closed form to round-off.
    assert values["separation_angle_closed_form_deg"] == pytest.approx(math.degrees(math.asin(2.0 / 3.0 * math.sin(math.radians(60.0)))), rel=1e-12)
    params = sl.PARAMETERS.defaults()
    release = sl.phase_changes(params, t_end_s=2.0)[0]
    assert values["separation_time_s"] == pytest.approx(release.t_s, abs=1e-9)
    assert values["phase"] in set(sl.PHASE_WORDS.values())
    assert 0.0 <= values["angle_deg"] <= 60.0
    energy = params["mass_kg"] * params["g_m_s2"] * 0.5 * params["length_m"] * math.sin(math.radians(60.0))
    assert values["energy_total_J"] == pytest.approx(energy, rel=1e-6)  # the budget: drift ≤ 1e-6 at rtol 1e-8
    show_scene_and_keep_screenshot(page, shots / f"lesson-{LESSON}.png")
    assert not errors, errors
    json.dumps(readout_values(page))  # the readout stays plain JSON while the scene runs

    # Issue 29, item 4: the ladder replays every ~3.5 s; at each replay the graph hid for about a second and the chosen
    # plot (wall force against angle) went back to the first series against time.
    page.click("#graphs > summary")
    page.wait_for_selector("#graph-y1 option[value='wall_force_N']", state="attached", timeout=15_000)
    pick(page, "graph-y1", "wall_force_N")
    pick(page, "graph-x", "angle_from_floor")
    wait_until(lambda: points(page) > 10, timeout_s=15, what="the phase plot of the wall force")
    page.evaluate(WATCH_THE_GRAPH, ["wall_force_N", "angle_from_floor"])
    page.wait_for_function("window.__graphWatch.replays >= 2", timeout=30_000)
    assert page.evaluate("window.__graphWatch.faults") == []
    assert page.get_attribute("#graphs .time-graph", "data-kind") == "phase"
    assert not errors, errors
    context.close()
