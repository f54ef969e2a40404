"""``dynlab constrained --quick`` on the Cartesian pendulum: the report's shape, every method, finite errors that fall with effort."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from app.bench.constrained_precision import CASES, SCIPY_SWEEPS, main, our_sweeps
from app.physics.constrained.algorithms import ALGORITHMS


@pytest.fixture(scope="module")
def report(tmp_path_factory: pytest.TempPathFactory) -> dict:
    out = tmp_path_factory.mktemp("constrained")
    assert main(["--quick", "--case", "cartesian-pendulum", "--out", str(out)]) == 0
    data = json.loads((out / "constrained_precision.json").read_text(encoding="utf-8"))
    data["_out"] = out
    return data


def test_report_has_one_case_with_every_method_and_its_plot(report: dict) -> None:
    assert {"created", "machine", "error_measure", "residuals", "cases"} <= set(report)
    (case,) = report["cases"]
    assert case["case_id"] == "cartesian-pendulum" and case["error_unit"] == "m"
    expected = {f"{a}-{i}" for a, i, *_ in our_sweeps(CASES["cartesian-pendulum"]())} | {m for m, *_ in SCIPY_SWEEPS}
    assert {m["method"] for m in case["methods"]} == expected
    assert {m["algorithm"] for m in case["methods"] if m["family"] == "dynlab"} == set(ALGORITHMS)
    assert all(m["projection"] == "none" for m in case["methods"] if m["family"] == "scipy")
    svg = (Path(report["_out"]) / case["plot"]).read_text(encoding="utf-8")
    assert svg.startswith("<svg") and all(f'data-method="{m}"' in svg for m in expected)


def test_every_point_has_a_finite_error_and_residuals(report: dict) -> None:
    for method in report["cases"][0]["methods"]:
        assert len(method["points"]) >= 2, method["method"]
        for point in method["points"]:
            assert point["status"] == "ok", (method["method"], point)
            for key in ("error", "cpu_s", "position_residual", "velocity_residual"):
                assert math.isfinite(point[key]) and point[key] >= 0.0, (method["method"], key, point)


def test_error_falls_with_effort_for_the_convergent_methods(report: dict) -> None:
    """Projection and partitioning with either integrator, and Radau: the most effort gives the smallest error.

    The unit pendulum's exact answer resolves 1e-14 m, so every point of these sweeps lies above the
    reference's floor; a factor 10 between the cheapest and the dearest setting is far below what
    RK4 (order 4 over a factor 8+ in steps) and the tolerance sweeps (3+ decades) give when they work.
    """
    methods = {m["method"]: m for m in report["cases"][0]["methods"]}
    for name in ("projection-rk4", "projection-dopri5", "partitioning-rk4", "partitioning-dopri5", "scipy-Radau"):
        errors = [p["error"] for p in methods[name]["points"]]
        assert errors[-1] < errors[0] / 10.0, (name, errors)
    projected = methods["projection-rk4"]["points"][-1]
    assert projected["position_residual"] < 1e-14  # projected onto g = 0 after every step: round-off of L²/2 = 0.5 m²
