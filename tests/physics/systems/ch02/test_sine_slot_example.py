"""Worked example ``pin-in-sine-slot`` (2.2) against an independent computation.

Independent: the pin's x(t) = u t and y(t) = h sin(π u t / L) are written here, differentiated by sympy and evaluated
with 30 significant digits; a_t, a_n come from those derivatives, and the slot's curvature from the arc-length
formula of a plane curve given as x(t), y(t), |ẋÿ − ẏẍ|/(ẋ² + ẏ²)^{3/2}, not from y(x) as the example does.

Tolerance: the example evaluates a handful of sines, products and one square root in double precision, so each
result is within a few ulps (≈ 1e-15) of its scale (|v| for velocities, h k² u² for accelerations, h k² for the
curvature); 1e-12 of that scale leaves a wide margin and still catches any wrong factor.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
import sympy

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch02.sine_slot_example import EXAMPLE

RTOL = 1e-12
t = sympy.Symbol("t", real=True)


def reference(h: float, L: float, u: float, x_pin: float) -> dict[str, float]:
    with mpmath.workdps(30):
        hh, LL, uu = (sympy.Float(v, 30) for v in (h, L, u))
        x = uu * t
        y = hh * sympy.sin(sympy.pi * uu * t / LL)
        at = sympy.Float(x_pin, 30) / uu
        value = lambda e: mpmath.mpf(sympy.N(e.subs(t, at), 30))  # noqa: E731
        xd, yd, xdd, ydd = (value(sympy.diff(e, t, k)) for e, k in ((x, 1), (y, 1), (x, 2), (y, 2)))
        speed = mpmath.sqrt(xd**2 + yd**2)
        return {
            "time_s": float(at),
            "y": float(value(y)),
            "y_dot": float(yd),
            "y_ddot": float(ydd),
            "speed_m_s": float(speed),
            "a_tangential_m_s2": float((xd * xdd + yd * ydd) / speed),
            "a_normal_m_s2": float(abs(xd * ydd - yd * xdd) / speed),
            "slot_curvature_1_m": float(abs(xd * ydd - yd * xdd) / speed**3),
        }


CASES = [
    {},
    {"slot_amplitude_m": 0.6, "slot_length_m": 0.5, "drive_speed_m_s": 0.5, "pin_x_m": 0.1},
    {"slot_amplitude_m": 1.0, "slot_length_m": 3.0, "drive_speed_m_s": 3.0, "pin_x_m": 5.5},
    {"slot_amplitude_m": 0.3, "slot_length_m": 1.0, "drive_speed_m_s": 0.5, "pin_x_m": 0.5},  # the crest
    {"slot_amplitude_m": 0.05, "slot_length_m": 0.2, "drive_speed_m_s": 2.0, "pin_x_m": 0.37},
]


@pytest.mark.parametrize("changes", CASES)
def test_components_and_path_variables_match_sympy(changes):
    inputs = EXAMPLE.inputs.validate(changes)
    h, L, u, x = (inputs[k] for k in ("slot_amplitude_m", "slot_length_m", "drive_speed_m_s", "pin_x_m"))
    out = EXAMPLE.solve(inputs).outputs
    ref = reference(h, L, u, x)
    a_scale = h * (np.pi / L) ** 2 * u**2
    assert out["time_s"] == pytest.approx(ref["time_s"], rel=RTOL)
    assert np.allclose(out["position_m"], [x, ref["y"], 0.0], rtol=0.0, atol=RTOL * (x + h))
    assert np.allclose(out["velocity_m_s"], [u, ref["y_dot"], 0.0], rtol=0.0, atol=RTOL * ref["speed_m_s"])
    assert np.allclose(out["acceleration_m_s2"], [0.0, ref["y_ddot"], 0.0], rtol=0.0, atol=RTOL * a_scale)
    assert out["speed_m_s"] == pytest.approx(ref["speed_m_s"], rel=RTOL)
    for name in ("a_tangential_m_s2", "a_normal_m_s2"):
        assert out[name] == pytest.approx(ref[name], abs=RTOL * a_scale), name
    assert out["slot_curvature_1_m"] == pytest.approx(ref["slot_curvature_1_m"], abs=RTOL * h * (np.pi / L) ** 2)


def test_defaults_reproduce_the_lesson_and_the_check_step_closes():
    solution = EXAMPLE.solve(EXAMPLE.inputs.defaults())
    out = solution.outputs
    # Lesson 2.2 at t = 0.5 s (x = 0.25 m), numbers as it prints them.
    assert out["time_s"] == pytest.approx(0.5, rel=RTOL)
    assert out["position_m"][1] == pytest.approx(0.2121, abs=5e-5)
    assert out["velocity_m_s"][1] == pytest.approx(0.3332, abs=5e-5)
    assert out["speed_m_s"] == pytest.approx(0.6009, abs=5e-5)
    assert out["acceleration_m_s2"][1] == pytest.approx(-0.5234, abs=5e-5)
    check = solution.steps[-1]
    assert check.title.startswith("Check")
    assert check.values["kappa v²"] == pytest.approx(check.values["a_n"], rel=RTOL)


def test_at_the_crest_the_whole_acceleration_is_normal():
    out = EXAMPLE.solve(EXAMPLE.inputs.validate({"pin_x_m": 0.5})).outputs
    assert out["a_tangential_m_s2"] == 0.0  # round-off of its scale is shown as 0
    assert out["a_normal_m_s2"] == pytest.approx(0.3 * np.pi**2 * 0.25, rel=RTOL)


def test_a_pin_beyond_the_slot_is_refused():
    with pytest.raises(ParameterError, match="slot is one wavelength long") as caught:
        EXAMPLE.inputs.validate({"slot_length_m": 1.0, "pin_x_m": 2.5})
    assert caught.value.field == "pin_x_m"
    with pytest.raises(ValueError, match="cannot be at"):
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), "slot_length_m": 0.2, "pin_x_m": 0.41})
