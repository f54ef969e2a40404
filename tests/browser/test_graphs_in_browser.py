"""The graphs panel in Chromium, on the heavy top (an integrated, conservative scene).

Opened, it shows energy bars whose kinetic and potential parts add up to the total (exactly in the numbers the
page received, and within the rounding of what it shows), a dissipated energy that is only integration drift,
and a total that stays flat over the kept motion while its parts trade energy; a phase plot of one series
against another has more than ten points; the time graph grows while the scene plays and stops growing when
it is paused; the CSV link downloads a CSV whose header names the quantities; axe-core finds nothing serious
in the open panel, and no graph request reaches the console as an error.
"""

from __future__ import annotations

import csv
import io
import math
import re

import pytest

from tests.browser.conftest import (
    dismiss_webgl_notice, keeping_screenshots, let_webgl_draw, open_lesson, screenshot, wait_for_polls,
)
from tests.browser.test_accessibility_in_browser import FAILING_IMPACTS, run_axe
from tests.conftest import wait_until

pytestmark = pytest.mark.browser
LESSON = "/lessons/10-2-spinning-top"
#: The heavy top's default run meets a 1e-6 rad attitude target; its energy drifts far less than 1e-4 of the total
#: in 60 s, so four significant figures (what the page shows) must not move, and the dissipated energy (the drift,
#: for this conservative model) must stay below 1e-4 of the total.
FLAT_TO = 1e-4


#: Scroll the page to the top and the scene's column so that the graphs panel starts right under the (sticky) scene.
SCROLL_PANEL_UNDER_SCENE = """() => {
  window.scrollTo(0, 0);
  const column = document.querySelector('.lesson-live');
  const gap = document.getElementById('graphs').getBoundingClientRect().top - document.getElementById('viewer-wrap').getBoundingClientRect().bottom;
  column.scrollTop += gap - 8;
}"""


def energy_cells(page) -> dict[str, tuple[float | None, str]]:
    """Every energy bar's value as {name: (value received in J, text shown)}, read in one call."""
    return {
        name: (value, text)
        for name, value, text in page.evaluate(
            "() => [...document.querySelectorAll('#graphs [data-energy]')]"
            ".map((cell) => [cell.dataset.energy, JSON.parse(cell.dataset.value), cell.textContent])"
        )
    }


def shown_number(text: str) -> float:
    """The number of a cell such as '12.35 J' or '3.1e-7 J'."""
    assert text.endswith(" J"), text
    return float(text.removesuffix(" J"))


def half_unit_in_fourth_figure(value: float) -> float:
    """The rounding of a value shown to four significant figures."""
    return 0.0 if value == 0 else 0.5 * 10 ** (math.floor(math.log10(abs(value))) - 3)


def points(page) -> int:
    return int(page.get_attribute("#graphs .time-graph", "data-points") or 0)


def pick(page, select_id: str, value: str) -> None:
    page.select_option(f"#{select_id}", value)


def test_energy_bars_phase_plot_live_time_graph_and_csv(browser, live_server, shots):
    context = browser.new_context(viewport={"width": 1400, "height": 1000})
    graph_console_errors: list[str] = []

    def keep_graph_errors(msg) -> None:  # a 404 before the viewer connects would show here as a failed /graph load
        if msg.type == "error" and "/graph" in (msg.location or {}).get("url", "") + msg.text:
            graph_console_errors.append(msg.text)

    context.on("console", keep_graph_errors)
    context, page, session_id, errors = open_lesson(browser, live_server, LESSON, context=context)
    host = live_server.host
    wait_until(lambda: host.motion_state(session_id)["t_s"] > 2.0, timeout_s=20, what="the top to move")
    assert page.is_visible("#graphs > summary")
    page.click("#graphs > summary")
    page.wait_for_function("document.querySelectorAll('#graphs [data-energy]').length >= 4", timeout=15_000)

    # Energy bars: numbers with J; kinetic + potential = total; dissipated only the drift of a conservative run.
    cells = energy_cells(page)
    assert {"energy_total_J", "energy_dissipated_J", "energy_potential_J"} <= set(cells), cells
    assert all(text.endswith(" J") for _, text in cells.values()), cells
    parts = {name: value for name, (value, _) in cells.items() if name not in ("energy_total_J", "energy_dissipated_J")}
    total = cells["energy_total_J"][0]
    assert sum(parts.values()) == pytest.approx(total, rel=1e-9)  # the server's parts add up to 1e-12
    shown_sum = sum(shown_number(cells[name][1]) for name in parts)
    rounding = sum(half_unit_in_fourth_figure(v) for v in parts.values()) + half_unit_in_fourth_figure(total)
    assert abs(shown_sum - shown_number(cells["energy_total_J"][1])) <= rounding * (1 + 1e-9)
    assert abs(cells["energy_dissipated_J"][0]) < FLAT_TO * abs(total), cells
    assert page.locator("#graphs .energy-bars .bar").count() == len(cells)

    # Total energy flat while its parts trade energy: the graph's summary states each curve's range.
    for name in ("energy_total_J", "energy_potential_J"):
        assert page.locator(f"#graph-y1 option[value='{name}']").count() == 1, name
    pick(page, "graph-y1", "energy_total_J")
    pick(page, "graph-y2", "energy_potential_J")
    wait_until(lambda: points(page) > 10, timeout_s=10, what="the energy graph")
    summary = page.text_content("#graphs .graph-summary")
    ranges = dict(re.findall(r"; ([^;]+?) from (\S+ to \S+) J", summary))
    assert len(ranges) == 2, summary
    (total_range, potential_range) = (tuple(map(float, r.split(" to "))) for r in ranges.values())
    assert total_range[1] - total_range[0] <= FLAT_TO * abs(total_range[1]), summary
    assert potential_range[1] - potential_range[0] > 0, summary  # the top nutates: height, so potential, changes

    # A phase plot: one series against another.
    pick(page, "graph-y2", "")
    pick(page, "graph-x", "theta")
    pick(page, "graph-y1", "phi")
    wait_until(lambda: page.get_attribute("#graphs .time-graph", "data-kind") == "phase" and points(page) > 10, timeout_s=10, what="a phase plot")
    polyline = page.get_attribute("#graphs .graph-plot svg polyline", "points")
    assert len(polyline.split()) > 10
    svg_desc = page.text_content("#graphs .graph-plot svg desc")
    assert svg_desc.startswith("Phase plot of") and "(rad)" in svg_desc, svg_desc

    # The time graph grows while the scene plays and stops growing when it is paused (time controls).
    pick(page, "graph-x", "__time__")
    grown_from = points(page)
    wait_until(lambda: points(page) > grown_from + 10, timeout_s=10, what="the time graph to grow while playing")
    page.click(".tc-play")
    page.wait_for_selector('.tc-play[data-playing="false"]')
    held_t = host.motion_state(session_id)["t_s"]
    # A poll in flight when paused lands; a paused scene is asked once a second.
    wait_for_polls(page, 2, path_end="/graph")
    held_points = points(page)
    wait_for_polls(page, 2, path_end="/graph")
    assert points(page) == held_points
    last_t = float(re.search(r"to (\S+) s;", page.text_content("#graphs .graph-summary")).group(1))
    assert last_t == pytest.approx(held_t, abs=0.006)  # shown to 2 decimals: the paused instant is the last point

    # CSV: the kept motion, its header naming every quantity with its unit.
    with page.expect_download() as download_info:
        page.click("#graphs .graph-csv")
    download = download_info.value
    assert download.suggested_filename.endswith(".csv")
    text = open(download.path(), encoding="utf-8").read()
    rows = list(csv.reader(io.StringIO(text)))
    header = rows[0]
    assert header[0].startswith("t_s") and "theta (rad)" in header and any(h.startswith("energy_total_J") for h in header), header
    assert len(rows) > 10 and all(len(row) == len(header) for row in rows[1:])

    # Accessible: axe-core on the open panel, labelled pickers, an SVG that says what it plots.
    violations = [v for v in run_axe(page) if v["impact"] in FAILING_IMPACTS]
    assert not violations, violations
    for select_id in ("graph-x", "graph-y1", "graph-y2", "graph-y3", "graph-window"):
        assert page.locator(f"label[for='{select_id}']").count() == 1

    # The picture for the docs: the scene (sticky at the top of its column) above the open panel, the nutation θ(t)
    # over the last 5 s (over 60 s its few-hertz wobble is a solid band).
    pick(page, "graph-y1", "theta")
    pick(page, "graph-window", "5")
    first_t, last_t = map(float, re.search(r"from t = (\S+) s to (\S+) s;", page.text_content("#graphs .graph-summary")).groups())
    # The last 5 s, or all of the motion when it is shorter (times shown to 2 decimals; points 0.1 s apart at most).
    window_start_s = max(0.0, last_t - 5.0)
    assert window_start_s - 0.01 <= first_t <= window_start_s + 0.1, (first_t, last_t)
    if keeping_screenshots():
        page.set_viewport_size({"width": 1400, "height": 1700})  # tall enough for the scene and the panel together
    page.evaluate(SCROLL_PANEL_UNDER_SCENE)
    dismiss_webgl_notice(page)
    let_webgl_draw(page, 3000)
    screenshot(page, shots / "graphs-panel.png")

    assert errors == [] and graph_console_errors == [], (errors, graph_console_errors)
    context.close()

