"""The stdlib SVG work-precision diagram (app/bench/plot.py)."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import pytest

from app.bench.plot import (
    PLOT_BOTTOM,
    PLOT_LEFT,
    PLOT_RIGHT,
    PLOT_TOP,
    decade_range,
    tick_label,
    usable_points,
    work_precision_svg,
)
from tests.conftest import HEAVY_TOP_BENCH_SETUP

NS = {"svg": "http://www.w3.org/2000/svg"}


def _pt(setting, cpu_s, error, status="ok"):
    return {"setting": setting, "cpu_s": cpu_s, "error": error, "rhs_evals": 100, "status": status}


def make_scene() -> dict:
    """Errors span 1e-8 .. 1e-2 and CPU times 0.1 .. 100 ms, so the axes are exactly those decades."""
    return {
        **HEAVY_TOP_BENCH_SETUP,
        "title": "Heavy symmetric top, 10 s & <friends>",
        "default": {"method": "splitting4", "setting": 2, "cpu_s": 1e-3, "error": 1e-5},
        "methods": [
            {
                "method": "splitting4",
                "family": "dynlab",
                "label": "Splitting 4 (numba)",
                "setting_name": "steps_per_frame",
                "points": [_pt(1, 1e-4, 1e-2), _pt(2, 1e-3, 1e-5), _pt(4, 2e-3, 1e-8)],
            },
            {
                "method": "scipy-DOP853",
                "family": "scipy",
                "label": "scipy DOP853 (numpy RHS)",
                "setting_name": "rtol",
                "points": [
                    _pt(1e-4, 0.02, 1e-4),
                    _pt(1e-6, 0.05, 3.1622776601683795e-6),
                    _pt(1e-8, 0.1, 0.0),  # exact to round-off: no place on a log axis
                    _pt(1e-10, 0.1, float("nan")),
                    _pt(1e-11, 0.1, None),
                    _pt(1e-12, float("inf"), 1e-7),
                    _pt(1e-13, 0.1, 1e-9, status="failed"),
                ],
            },
            {
                "method": "mujoco-RK4",
                "family": "mujoco",
                "label": "MuJoCo RK4",
                "setting_name": "steps_per_frame",
                "points": [_pt(1, 0.004, 3e-3), _pt(2, 0.008, 2e-4), _pt(4, 0.016, 1.2e-5)],
            },
            {
                "method": "mujoco-Euler",
                "family": "mujoco",
                "label": "MuJoCo Euler",
                "setting_name": "steps_per_frame",
                "points": [_pt(1, 0.001, 0.0), _pt(2, -1.0, 1e-3)],
            },
        ],
        "ratios": [{"baseline": "scipy-DOP853", "at_error": 1e-6, "ratio": 50.0, "text": "..."}],
    }


def expected_x(error: float) -> float:
    return PLOT_LEFT + (math.log10(error) - (-8)) / (-2 - (-8)) * (PLOT_RIGHT - PLOT_LEFT)


def expected_y(cpu_ms: float) -> float:
    return PLOT_BOTTOM - (math.log10(cpu_ms) - (-1)) / (2 - (-1)) * (PLOT_BOTTOM - PLOT_TOP)


def polyline_points(series: ET.Element) -> list[tuple[float, float]]:
    polylines = series.findall("svg:polyline", NS)
    assert len(polylines) == 1
    return [tuple(map(float, pair.split(","))) for pair in polylines[0].get("points").split()]


@pytest.fixture(scope="module")
def svg_text() -> str:
    return work_precision_svg(make_scene())


@pytest.fixture(scope="module")
def root(svg_text) -> ET.Element:
    return ET.fromstring(svg_text)


def series_by_method(root: ET.Element) -> dict[str, ET.Element]:
    return {g.get("data-method"): g for g in root.iter("{http://www.w3.org/2000/svg}g") if g.get("class") == "series"}


def test_is_standalone_svg_that_embeds_in_html(svg_text, root):
    assert root.tag == "{http://www.w3.org/2000/svg}svg"
    assert root.get("viewBox") == f"0 0 {root.get('width')} {root.get('height')}"
    assert 700 <= float(root.get("width")) <= 800 and 440 <= float(root.get("height")) <= 520
    # Nothing that leaks into, or clashes with, a page it is pasted into.
    assert not svg_text.lstrip().startswith("<?xml")
    assert "<style" not in svg_text and ' id="' not in svg_text and "<script" not in svg_text
    # The title is escaped, and is the scene's title.
    assert root.findall(".//svg:text", NS)[0].text == "Heavy symmetric top, 10 s & <friends>"
    assert root.find("svg:title", NS) is not None


def test_text_is_readable(root):
    sizes = [float(t.get("font-size")) for t in root.iter("{http://www.w3.org/2000/svg}text")]
    assert sizes and min(sizes) >= 12


def test_axis_titles_name_quantities_units_and_scale(root):
    texts = [t.text for t in root.iter("{http://www.w3.org/2000/svg}text")]
    assert "Error (rad), log scale" in texts
    assert "CPU time for 10 s of motion (ms), log scale" in texts


def test_one_polyline_per_method_with_two_or_more_usable_points(root):
    series = series_by_method(root)
    assert set(series) == {"splitting4", "scipy-DOP853", "mujoco-RK4", "mujoco-Euler"}
    assert len(polyline_points(series["splitting4"])) == 3
    assert len(polyline_points(series["mujoco-RK4"])) == 3
    # DOP853: only the first two of seven points are usable.
    assert len(polyline_points(series["scipy-DOP853"])) == 2
    # No usable point at all: no line, no markers, but no crash and a legend note.
    assert series["mujoco-Euler"].findall("svg:polyline", NS) == []
    assert len(list(series["mujoco-Euler"])) == 0
    assert any("no valid points" in (t.text or "") for t in root.iter("{http://www.w3.org/2000/svg}text"))
    assert len(root.findall(".//svg:polyline", NS)) == 3


def test_known_points_land_at_their_log_positions(root):
    series = series_by_method(root)
    (x0, y0), (x1, y1), (x2, y2) = polyline_points(series["splitting4"])
    # Corners of the axes: error 1e-2 / 100 µs... and error 1e-8 / 2 ms.
    assert x0 == pytest.approx(PLOT_RIGHT, abs=0.01) and y0 == pytest.approx(PLOT_BOTTOM, abs=0.01)
    assert x2 == pytest.approx(PLOT_LEFT, abs=0.01)
    # error 1e-5 rad, 1 ms: half-way across six decades, one third up three decades.
    assert x1 == pytest.approx(PLOT_LEFT + 0.5 * (PLOT_RIGHT - PLOT_LEFT), abs=0.01)
    assert y1 == pytest.approx(PLOT_BOTTOM - (PLOT_BOTTOM - PLOT_TOP) / 3, abs=0.01)
    assert (x2, y2) == pytest.approx((expected_x(1e-8), expected_y(2.0)), abs=0.01)
    # A point between decades: 10^-5.5 rad at 50 ms.
    (_, _), (xs, ys) = polyline_points(series["scipy-DOP853"])
    assert xs == pytest.approx(expected_x(10**-5.5), abs=0.01)
    assert ys == pytest.approx(expected_y(50.0), abs=0.01)


def test_target_line_and_default_ring(root):
    target = next(g for g in root.iter("{http://www.w3.org/2000/svg}g") if g.get("class") == "target")
    line = target.find("svg:line", NS)
    assert float(line.get("x1")) == pytest.approx(expected_x(1e-6), abs=0.01) == float(line.get("x2"))
    assert line.get("stroke-dasharray")
    assert "target 1e-6 rad" in [t.text for t in target.findall("svg:text", NS)]

    default = next(g for g in root.iter("{http://www.w3.org/2000/svg}g") if g.get("class") == "default")
    ring = default.find("svg:circle", NS)
    assert ring.get("fill") == "none"
    assert (float(ring.get("cx")), float(ring.get("cy"))) == pytest.approx((expected_x(1e-5), expected_y(1.0)), abs=0.01)
    labels = [t.text for t in default.findall("svg:text", NS)]
    assert "default: Splitting 4 (numba)" in labels and "steps per frame = 2" in labels


def test_decade_grid_and_tick_labels(root):
    texts = {t.text for t in root.findall("svg:g[@class='ticks']/svg:text", NS)}
    assert {"1e-8", "1e-6", "1e-4", "0.01"} <= texts  # x decades (every decade labelled: six of them)
    assert {"0.1", "1", "10", "100"} <= texts  # y decades
    assert tick_label(-6) == "1e-6" and tick_label(0) == "1" and tick_label(-2) == "0.01" and tick_label(5) == "1e5"


def test_families_have_their_colours_and_distinct_markers(root):
    series = series_by_method(root)
    colours = {name: g.find("svg:polyline", NS).get("stroke") for name, g in series.items() if name != "mujoco-Euler"}
    assert len(set(colours.values())) == 3
    assert colours["mujoco-RK4"].lower() in {"#e67e00", "#b85c00", "#f2a444", "#cc6d1f"}
    marker_tags = {name: g[1].tag for name, g in series.items() if len(g) > 1}
    assert len(set(marker_tags.values())) == len(marker_tags)


def test_usable_points_and_decade_range():
    scene = make_scene()
    assert [p["setting"] for p in usable_points(scene["methods"][1])] == [1e-4, 1e-6]
    assert usable_points({"points": None}) == []
    assert decade_range([3e-7, 2e-3]) == (-7, -2)
    assert decade_range([1e-6, 1e-3]) == (-6, -3)
    assert decade_range([5e-4]) == (-4, -3)
    assert decade_range([0.0, float("nan")]) == (-1, 0)


@pytest.mark.parametrize(
    "change",
    [
        lambda s: s.update(methods=[]),
        lambda s: s.update(default=None, target_error=None, error_unit="", t_end_s=None),
        lambda s: s.update(target_error=float("nan"), default={"method": "x", "setting": 1, "cpu_s": 0.0, "error": 0.0}),
        lambda s: s["methods"][0].update(points=[_pt(1, 1e-3, 1e-5)]),
    ],
    ids=["no-methods", "bare", "bad-target-and-default", "single-point"],
)
def test_degenerate_scenes_still_give_valid_svg(change):
    scene = make_scene()
    change(scene)
    text = work_precision_svg(scene)
    root = ET.fromstring(text)
    assert root.tag == "{http://www.w3.org/2000/svg}svg"
    assert "nan" not in text.lower().replace("dynamics", "") and "inf" not in text.replace("info", "")


def test_frame_cost_chart_marks_scenes_over_the_budget_red():
    from app.bench.plot import FRAME_BUDGET_US, frame_cost_svg

    live = [
        {"scene_id": "quick", "method": "closed-form", "physics_us_per_frame": 3.0},
        {"scene_id": "slow", "method": "rk4", "physics_us_per_frame": 2 * FRAME_BUDGET_US},
        {"scene_id": "still", "method": "static", "physics_us_per_frame": 0.0},
    ]
    root = ET.fromstring(frame_cost_svg(live))
    bars = [r for r in root.findall("svg:rect", NS) if r.get("height") != root.get("height")]
    assert [b.get("fill") for b in bars] == ["#d0202e", "#1b8a3a", "#1b8a3a"]  # sorted slowest first
    widths = [float(b.get("width")) for b in bars]
    assert widths[0] > widths[1] >= widths[2] > 0.0
    labels = [t.text for t in root.findall("svg:text", NS)]
    assert "slow" in labels and f"budget {FRAME_BUDGET_US:g} µs" in labels
