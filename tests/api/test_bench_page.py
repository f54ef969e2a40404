"""The Solver lab page and the benchmark routes (app/api/bench.py, /solver-lab in app/web/pages.py).

Each test points the running app's settings at its own temporary bench folder,
so nothing here depends on docs/bench having been generated.
"""

from __future__ import annotations

import dataclasses
import json
import xml.etree.ElementTree as ET
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

from app.bench.plot import work_precision_svg
from app.course.bench_reports import diagram_path
from app.settings import Settings
from app.web.pages import fmt_setting, fmt_sig
from tests.conftest import HEAVY_TOP_BENCH_SETUP

RESULTS = {
    "created": "2026-11-22T10:00:00Z",
    "machine": {
        "cpu": "Test CPU 9000",
        "cores": 2,
        "python": "3.11.7",
        "numpy": "2.1.3",
        "scipy": "1.14.1",
        "numba": "0.61.0",
        "mujoco": "3.2.6",
    },
    "scenes": [
        {
            **HEAVY_TOP_BENCH_SETUP,
            "title": "Heavy symmetric top, 10 s",
            "default": {"method": "splitting4", "setting": 3, "cpu_s": 0.0012, "error": 2e-7},
            "methods": [
                {
                    "method": "splitting4",
                    "family": "dynlab",
                    "label": "Splitting 4 (numba)",
                    "setting_name": "steps_per_frame",
                    "points": [
                        {"setting": 1, "cpu_s": 0.0004, "error": 1.6e-5, "rhs_evals": 6000, "status": "ok"},
                        {"setting": 3, "cpu_s": 0.0012, "error": 2e-7, "rhs_evals": 18000, "status": "ok"},
                    ],
                },
                {
                    "method": "scipy-DOP853",
                    "family": "scipy",
                    "label": "scipy DOP853 (numpy RHS)",
                    "setting_name": "rtol",
                    "points": [
                        {"setting": 1e-6, "cpu_s": 0.0912345, "error": 3.3e-6, "rhs_evals": 4000, "status": "ok"},
                        {"setting": 1e-9, "cpu_s": 0.2, "error": 4e-9, "rhs_evals": 9000, "status": "ok"},
                        {"setting": 1e-13, "cpu_s": 3.0, "error": None, "rhs_evals": 0, "status": "failed"},
                    ],
                },
            ],
            "ratios": [
                {
                    "baseline": "scipy-DOP853",
                    "at_error": 1e-6,
                    "ratio": 140.0,
                    "text": "At an error of 1e-6 rad the default needs 140 times less CPU time than scipy DOP853.",
                },
                {"baseline": "mujoco-RK4", "at_error": 1e-6, "ratio": 12.345},
            ],
        },
        {
            "scene_id": "tumbling-t-handle",
            "title": "Tumbling T-handle <Dzhanibekov>, 20 s",
            "t_end_s": 20.0,
            "frame_rate_hz": 60,
            "error_measure": "max invariant drift",
            "error_unit": "relative",
            "default": {"method": "rk4", "setting": 2, "cpu_s": 0.0005, "error": 3e-9},
            "methods": [
                {
                    "method": "rk4",
                    "family": "dynlab",
                    "label": "RK4 (numba)",
                    "setting_name": "steps_per_frame",
                    "points": [{"setting": 2, "cpu_s": 0.0005, "error": 3e-9, "rhs_evals": 9600, "status": "ok"}],
                },
            ],
            "ratios": [],
        },
    ],
}


@pytest.fixture
def client(inprocess_client):
    """These tests point the app's settings at a folder of their own: the app in this process."""
    return inprocess_client


@pytest.fixture
def use_bench_dir(client) -> Iterator[Callable[[Path], None]]:
    """Point the shared app's settings at another bench folder for one test, then put them back."""
    original = client.app.state.settings

    def use(path: Path) -> None:
        client.app.state.settings = dataclasses.replace(original, bench_dir=path)

    yield use
    client.app.state.settings = original


@pytest.fixture
def bench_dir(use_bench_dir, tmp_path) -> Path:
    folder = tmp_path / "bench"
    folder.mkdir()
    (folder / "work_precision.json").write_text(json.dumps(RESULTS), encoding="utf-8")
    (folder / "heavy-top.svg").write_text(work_precision_svg(RESULTS["scenes"][0]), encoding="utf-8")
    # A file next to the bench folder that must never be reachable through the SVG route.
    (tmp_path / "secret.svg").write_text("<svg xmlns='http://www.w3.org/2000/svg'>secret</svg>", encoding="utf-8")
    use_bench_dir(folder)
    return folder


@pytest.fixture
def empty_bench_dir(use_bench_dir, tmp_path) -> Path:
    use_bench_dir(tmp_path)
    return tmp_path


def test_page_shows_each_scene_its_ratios_default_and_points(client, bench_dir):
    response = client.get("/solver-lab")
    assert response.status_code == 200
    assert response.headers["content-type"].startswith("text/html")
    page = response.text
    assert "Heavy symmetric top, 10 s" in page
    assert "Tumbling T-handle &lt;Dzhanibekov&gt;, 20 s" in page  # titles are escaped
    # Ratios: the given sentence verbatim, and one built from the numbers when there is no text.
    assert "At an error of 1e-6 rad the default needs 140 times less CPU time than scipy DOP853." in page
    assert "mujoco-RK4 takes <strong>12.3 times</strong> the CPU time of Splitting 4 (numba)" in page
    # The default: CPU time in ms and error with its unit, to three significant figures.
    assert "<strong>1.20 ms</strong>" in page
    assert "2.00 × 10<sup>−7</sup> rad" in page
    assert "within the target of 10<sup>−6</sup> rad" in page
    # Every point is in the table, including the failed one.
    assert page.count("<tr") - page.count("<thead><tr") == 2 + 3 + 1
    assert "91.2" in page and "failed; not plotted" in page
    # The diagram is embedded where it exists, and its absence is reported where it does not.
    assert '<img src="/bench/heavy-top.svg"' in page
    assert "/bench/tumbling-t-handle.svg" not in page and "diagram for this scene is missing" in page
    # Machine, the explanation and how to regenerate.
    assert "Test CPU 9000" in page and "work-precision diagram" in page
    assert "uv run --group bench dynlab bench" in page


def test_json_route_returns_the_file(client, bench_dir):
    response = client.get("/api/bench/work-precision")
    assert response.status_code == 200
    assert response.headers["content-type"].startswith("application/json")
    assert response.content == (bench_dir / "work_precision.json").read_bytes()
    assert response.json()["scenes"][0]["scene_id"] == "heavy-top"


def test_svg_route_serves_the_diagram(client, bench_dir):
    response = client.get("/bench/heavy-top.svg")
    assert response.status_code == 200
    assert response.headers["content-type"].startswith("image/svg+xml")
    assert response.headers["x-content-type-options"] == "nosniff"
    assert ET.fromstring(response.content).tag == "{http://www.w3.org/2000/svg}svg"


@pytest.mark.parametrize(
    "path",
    [
        "/bench/..%2Fsecret.svg",
        "/bench/%2e%2e%2fsecret.svg",
        "/bench/..%5Csecret.svg",
        "/bench/Heavy-Top.svg",
        "/bench/heavy_top.svg",
        "/bench/heavy-top.svg.svg",
        "/bench/work_precision.svg",
        "/bench/.svg",
        "/bench/tumbling-t-handle.svg",  # a well-formed name whose file does not exist
    ],
)
def test_svg_route_refuses_anything_but_existing_plain_names(client, bench_dir, path):
    response = client.get(path)
    assert response.status_code == 404
    assert "secret" not in response.text


def test_missing_results_give_404_and_the_page_says_how_to_make_them(client, empty_bench_dir):
    response = client.get("/api/bench/work-precision")
    assert response.status_code == 404
    assert "dynlab bench" in response.json()["detail"]
    assert client.get("/bench/heavy-top.svg").status_code == 404
    page = client.get("/solver-lab")
    assert page.status_code == 200
    assert "No measurements yet" in page.text and "<code>uv run --group bench dynlab bench</code>" in page.text
    # The explanation is still there.
    assert "Symplectic does not mean accurate" in page.text


def test_unreadable_results_are_reported_on_the_page(client, empty_bench_dir):
    (empty_bench_dir / "work_precision.json").write_text("{not json", encoding="utf-8")
    page = client.get("/solver-lab")
    assert page.status_code == 200
    assert "cannot be read" in page.text and "dynlab bench" in page.text


def test_course_page_links_to_the_solver_lab(client):
    assert 'href="/solver-lab"' in client.get("/").text


@pytest.mark.parametrize(
    "value, text",
    [
        (0.0012 * 1e3, "1.20"),
        (0.0912345e3, "91.2"),
        (1234.5, "1230"),
        (0.00123456, "0.00123"),
        (2e-7, "2.00 × 10<sup>−7</sup>"),
        (9.996, "10.0"),
        (123456.0, "1.23 × 10<sup>5</sup>"),
        (0, "0"),
        (None, "—"),
        (float("nan"), "—"),
    ],
)
def test_three_significant_figures(value, text):
    assert fmt_sig(value) == text


def test_settings_format():
    assert fmt_setting(3) == "3"
    assert fmt_setting(1e-6) == "10<sup>−6</sup>"
    assert fmt_setting(2.5e-7) == "2.50 × 10<sup>−7</sup>"


@pytest.mark.parametrize(
    "name", ["../secret", "..", "bench/../secret", "heavy-top\n", "heavy-top/", "", "HEAVY", "a.b"]
)
def test_diagram_path_accepts_only_plain_scene_ids(bench_dir, name):
    settings = dataclasses.replace(Settings(), bench_dir=bench_dir)
    assert diagram_path(settings, name) is None
    assert diagram_path(settings, "heavy-top") == bench_dir / "heavy-top.svg"


def test_a_malformed_scene_does_not_break_the_page(client, use_bench_dir, tmp_path):
    results = json.loads(json.dumps(RESULTS))
    results["scenes"].insert(0, {"scene_id": "broken", "title": "Broken scene", "methods": [42], "ratios": "x"})
    results["scenes"].append("not a scene")
    (tmp_path / "work_precision.json").write_text(json.dumps(results), encoding="utf-8")
    use_bench_dir(tmp_path)
    page = client.get("/solver-lab")
    assert page.status_code == 200
    assert "The entry for Broken scene in the benchmark results is malformed" in page.text
    assert "An entry in the benchmark results is malformed" in page.text
    assert "Heavy symmetric top, 10 s" in page.text


def test_the_scaling_report_is_shown_with_its_plot_targets_and_sympy_baseline(client, bench_dir):
    """docs/bench/scaling.json as committed: every chain row, sympy's column beside ours, the bicycle, the targets."""
    shipped = Path(__file__).resolve().parents[2] / "docs" / "bench"
    for name in ("scaling.json", "scaling.svg"):
        (bench_dir / name).write_bytes((shipped / name).read_bytes())
    page = client.get("/solver-lab").text
    section = page[page.index('id="bench-scaling"') :]
    report = json.loads((shipped / "scaling.json").read_text())
    ours = [r for r in report["rows"] if r["engine"] == "ours"]
    assert section.count("<tr><td>") == len(ours) and '<img src="/bench/scaling.svg"' in section
    assert "KanesMethod" in section and "target 15 s" in section and "from the disk cache" in section


def test_a_missing_scaling_report_says_how_to_make_it(client, empty_bench_dir):
    page = client.get("/solver-lab").text
    assert "No scaling measurement yet" in page and "dynlab derivations --scaling" in page
