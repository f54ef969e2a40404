"""``dynlab derivations --scaling``: one measurement of each kind runs and the report draws (the full run is a
benchmark, committed as docs/bench/scaling.json and .svg, not a test)."""

from __future__ import annotations

from app.bench.scaling import measure_ours, measure_sympy, scaling_svg


def test_one_measurement_of_each_engine_and_the_plot():
    ours, spatial, theirs = measure_ours(2, True), measure_ours(2, False), measure_sympy(2)
    assert ours["coordinates"] == 2 and spatial["coordinates"] == 4 and theirs["coordinates"] == 2
    assert ours["operations_written_out"] > ours["operations_in_code"] > 0
    assert all(row["rhs_us"] > 0 for row in (ours, spatial, theirs))
    assert ours["frame_us"] > 0 and ours["frame_integration"]
    bicycle = {"cold": {"total_s": 4.0}, "cached": {"equations_s": 0.02}}
    svg = scaling_svg({"rows": [ours, spatial, theirs], "bicycle": bicycle})
    assert svg.startswith("<svg") and "sympy KanesMethod" in svg and svg.count("<polyline") == 4
