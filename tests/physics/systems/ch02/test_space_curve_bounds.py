"""A typed curve is refused where it overflows the span it is drawn on, and evaluating it has bounded memory."""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch02 import space_curve as sc
from app.scenes.ch02.space_curve import SpaceCurveScene, table_times

#: Near the derivative-size limits: sympy's common subexpressions make hundreds of temporaries per evaluation.
HEAVY = (
    "sin(t)*cos(2*t)*exp(sin(3*t))*log(2+cos(t))",
    "cos(t)*sin(7*t)*exp(cos(2*t))*sqrt(4+cos(t))",
    "sin(t)^3*cos(t)^5*exp(sin(t)*cos(t))",
)


@pytest.mark.parametrize(("text", "component"), [("exp(50*t)", "x_of_t"), ("t^100", "x_of_t")])
def test_span_check_names_the_component_and_the_first_time(text, component):
    curve = sc.compile_curve(text, "sin(t)", "0.2*t")
    t = np.linspace(0.0, 600.0, 72_001)
    with pytest.raises(sc.CurveError) as refused:
        sc.check_curve_span(curve, t)
    assert refused.value.component == component
    jets = curve.jets(t)
    first = int(np.argmax(np.any(np.abs(jets) > sc.MAX_CURVE_MAGNITUDE, axis=(0, 2))))
    assert f"at t = {t[first]:.4g} s" in str(refused.value)
    assert np.all(np.abs(curve.jets(t[:first])) <= sc.MAX_CURVE_MAGNITUDE)  # nothing earlier was over


def test_poles_and_roots_of_negatives_are_not_overflow():
    # 1/t at t = 0 and sqrt(t − 1) before t = 1 are undefined instants, drawn as gaps, not refused.
    sc.check_curve_span(sc.compile_curve("1/t", "sqrt(t-1)", "t"), np.linspace(0.0, 10.0, 1201))


def test_scene_parameters_refuse_a_curve_that_overflows_its_loop():
    base = SpaceCurveScene.parameters.validate({})
    with pytest.raises(ParameterError) as refused:
        SpaceCurveScene.parameters.validate({"x_of_t": "exp(t)", "t_end_s": 600.0}, base=base)
    assert refused.value.path == ("x_of_t",)
    SpaceCurveScene.parameters.validate({"x_of_t": "exp(t)", "t_end_s": 60.0}, base=base)  # e^60 ≈ 1e26: drawn
    # The check covers exactly the instants the scene's frame table draws.
    assert table_times(600.0)[-1] == 600.0 and len(table_times(600.0)) == 12_001


def test_chunked_evaluation_equals_one_pass():
    curve = sc.compile_curve(*HEAVY)
    t = np.linspace(0.0, 50.0, 3 * sc.EVALUATION_CHUNK + 17)
    chunked = curve.jets(t)
    whole = np.stack([np.stack(np.broadcast_arrays(*curve._evaluate(t)[3 * k : 3 * k + 3]), axis=-1) for k in range(4)])
    np.testing.assert_array_equal(chunked, whole)  # the same arithmetic, element by element


#: Peak Python-heap memory of a worst-case simulate's evaluation (MB). Before chunking it measured 223 MB (one
#: temporary of 36 000 or 288 000 floats per subexpression); chunked it measured ~38 MB, mostly the 23 output
#: series and the JSON lists. 80 MB is 2× that and fails for the unchunked evaluation.
PEAK_EVALUATION_MB = 80


def test_worst_case_simulate_evaluation_memory_is_bounded():
    sc.compile_curve(*HEAVY)  # compiled (and cached) outside the measurement
    tracemalloc.start()
    try:
        report = sc.ParticleOnCurve().simulate(dict(zip(sc.COMPONENTS, HEAVY)), {}, t_end_s=600.0, frame_rate_hz=60.0).as_dict()
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert len(report["t"]) == 36_001
    print(f"peak {peak / 2**20:.1f} MB")
    assert peak / 2**20 < PEAK_EVALUATION_MB
