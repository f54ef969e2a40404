"""Worked example ``path-variables-typed-curve`` (2.1) against an independent computation.

Independent: each curve is written here as a sympy expression, differentiated by sympy in this test and evaluated
with 30 significant digits (mpmath), and the path variables are formed from those high-precision derivatives; the
helix is also checked against its closed forms κ = a/(a² + c²), τ = c/(a² + c²).

Tolerance: the example evaluates the same exact derivative formulas in double precision, a few dozen products,
sums and square roots of O(1) numbers, so each result carries an error of a few ulps (≈ 1e-15) of its scale; the
torsion divides by |r' × r''|², at least 0.01 for these curves, which can amplify that by at most ~1e2. A relative
tolerance of 1e-12 (of each quantity's scale: a vector's length, 1 for unit vectors, |r''| for a_t and a_n) leaves
a margin of ten or more over that, while any wrong formula is off by far more.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
import sympy

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch02.path_variables_example import EXAMPLE

RTOL = 1e-12
t = sympy.Symbol("t", real=True)


def reference(x, y, z, at: float) -> dict[str, object]:
    """Path variables at t = ``at`` from sympy derivatives evaluated with 30 digits."""
    with mpmath.workdps(30):
        return _reference(x, y, z, at)


def _reference(x, y, z, at: float) -> dict[str, object]:
    r = sympy.Matrix([x, y, z])
    d1, d2, d3 = r.diff(t), r.diff(t, 2), r.diff(t, 3)
    value = {
        k: [mpmath.mpf(sympy.N(e.subs(t, sympy.Float(at, 30)), 30)) for e in m]
        for k, m in (("v", d1), ("a", d2), ("j", d3))
    }
    v, a, j = (mpmath.matrix(value[k]) for k in ("v", "a", "j"))

    def cross(p, q):
        return mpmath.matrix([p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]])

    def dot(p, q):
        return sum(p[i] * q[i] for i in range(3))

    speed = mpmath.sqrt(dot(v, v))
    vxa = cross(v, a)
    cross_norm = mpmath.sqrt(dot(vxa, vxa))
    e_t = v / speed
    e_b = vxa / cross_norm
    e_n = cross(e_b, e_t)
    as_array = lambda m: np.array([float(m[i]) for i in range(3)])  # noqa: E731
    return {
        "speed_m_s": float(speed),
        "tangent": as_array(e_t),
        "normal": as_array(e_n),
        "binormal": as_array(e_b),
        "a_tangential_m_s2": float(dot(v, a) / speed),
        "a_normal_m_s2": float(cross_norm / speed),
        "curvature_1_m": float(cross_norm / speed**3),
        "radius_of_curvature_m": float(speed**3 / cross_norm),
        "torsion_1_m": float(dot(vxa, j) / cross_norm**2),
        "|a|": float(mpmath.sqrt(dot(a, a))),
    }


CASES = [
    # (x, y, z as text for the example, the same as sympy here, t)
    ("cos(t)", "sin(t)", "0.2*t", 0.0),
    ("cos(t)", "sin(2*t)/2", "0.3*sin(t)", 0.7),
    ("0.1*t*cos(2*t)", "0.1*t*sin(2*t)", "0.12*t", 3.0),
    ("cos(t)", "sin(t)", "0.2*t^2", 2.0),
    ("0.5*t*cos(2*t)", "0.5*t*sin(2*t)", "0.3*t", 1.0),
    ("2*cos(t)", "2*sin(t)", "-0.5*t", 5.5),
]


def _sympy(text: str) -> sympy.Expr:
    return sympy.sympify(text.replace("^", "**"), locals={"t": t})


def _close(actual, expected, scale):
    assert np.all(np.abs(np.asarray(actual, dtype=float) - np.asarray(expected, dtype=float)) <= RTOL * scale)


@pytest.mark.parametrize(("x", "y", "z", "at"), CASES)
def test_path_variables_match_high_precision_sympy(x, y, z, at):
    inputs = EXAMPLE.inputs.validate({"x_of_t": x, "y_of_t": y, "z_of_t": z, "t_start_s": at})
    out = EXAMPLE.solve(inputs).outputs
    ref = reference(_sympy(x), _sympy(y), _sympy(z), at)
    a_scale = ref["|a|"]
    _close(out["speed_m_s"], ref["speed_m_s"], ref["speed_m_s"])
    for name in ("tangent", "normal", "binormal"):
        _close(out[name], ref[name], 1.0)
    for name in ("a_tangential_m_s2", "a_normal_m_s2"):
        _close(out[name], ref[name], a_scale)
    for name in ("curvature_1_m", "radius_of_curvature_m"):
        _close(out[name], ref[name], ref[name])
    _close(out["torsion_1_m"], ref["torsion_1_m"], ref["curvature_1_m"] + abs(ref["torsion_1_m"]))


def test_defaults_are_the_helix_closed_form_and_the_check_step_closes():
    solution = EXAMPLE.solve(EXAMPLE.inputs.defaults())
    a, c = 1.0, 0.2
    assert solution.outputs["curvature_1_m"] == pytest.approx(a / (a * a + c * c), rel=RTOL)
    assert solution.outputs["torsion_1_m"] == pytest.approx(c / (a * a + c * c), rel=RTOL)
    assert solution.outputs["a_normal_m_s2"] == pytest.approx(a, rel=RTOL)
    assert solution.outputs["a_tangential_m_s2"] == 0.0
    check = solution.steps[-1]
    assert check.title.startswith("Check")
    _close(check.values["a_t e_t + a_n e_n"], check.values["r''"], 1.0)
    assert check.values["sqrt(a_t² + a_n²)"] == pytest.approx(check.values["|r''|"], rel=RTOL)
    assert check.values["a_b"] == 0.0


def test_the_lesson_2_4_conical_spiral_numbers():
    # Lesson 2.4, example 1: R = 0.5t, θ = 2t, z = 0.3t at t = 1 s (numbers rounded as the lesson prints them).
    inputs = EXAMPLE.inputs.validate(
        {"x_of_t": "0.5*t*cos(2*t)", "y_of_t": "0.5*t*sin(2*t)", "z_of_t": "0.3*t", "t_start_s": 1.0}
    )
    out = EXAMPLE.solve(inputs).outputs
    assert out["speed_m_s"] == pytest.approx(1.1576, abs=5e-5)
    assert out["a_tangential_m_s2"] == pytest.approx(0.8639, abs=5e-5)
    assert out["a_normal_m_s2"] == pytest.approx(2.6933, abs=5e-5)
    assert out["curvature_1_m"] == pytest.approx(2.0099, abs=5e-5)
    assert out["torsion_1_m"] == pytest.approx(0.6173, abs=5e-5)


@pytest.mark.parametrize(
    ("changes", "words"),
    [
        ({"x_of_t": "t^3", "y_of_t": "t^2", "z_of_t": "0", "t_start_s": 0.0}, "at rest"),
        ({"x_of_t": "t", "y_of_t": "2*t", "z_of_t": "0.5*t", "t_start_s": 1.0}, "curvature is zero"),
        ({"x_of_t": "sqrt(t-3)", "y_of_t": "t", "z_of_t": "0", "t_start_s": 1.0}, "no finite value"),
    ],
)
def test_an_instant_without_a_frenet_frame_is_refused(changes, words):
    with pytest.raises(ParameterError, match=words) as caught:
        EXAMPLE.inputs.validate(changes)
    assert caught.value.field == "t_start_s"
    with pytest.raises(ValueError, match=words):
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), **changes})
