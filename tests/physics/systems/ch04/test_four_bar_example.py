"""Worked example ``four-bar-instant`` against an independent computation.

The test closes the loop its own way (the law of cosines in the triangle A B O₄, from the direction of A→O₄) and gets
the rates and accelerations by central finite differences of those positions over the crank angle (θ₂ = θ₂(0) + ω₂ t,
so d/dt = ω₂ d/dθ₂ and d²/dt² = ω₂² d²/dθ₂²), not from the differentiated loop the example solves.

Tolerances: with a step h = 1e-4 rad a central first difference errs by about h²/6·|f‴| ≈ 2e-9·|f‴| and a second
difference by h²/12·|f⁗| + 4 ε|f|/h² ≈ 1e-9·|f⁗| + 1e-7 (ε = 2.2e-16, |f| ≲ 10 rad or m). The cases are far from
toggle positions, where the derivatives are O(1–10), so 1e-6 relative to each quantity's scale (rate: |ω₂|; angular
acceleration: ω₂²; the point's velocity and acceleration: |ω₂| and ω₂² times the largest link) is about 10× the
expected error and still 1e5× below anything the page shows. Positions are exact formulas: 1e-12 of the link lengths.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch04.four_bar_example import EXAMPLE

H = 1e-4
CASES = [
    {},
    {"branch": "crossed", "crank_angle0_deg": -120.0, "crank_speed_rad_s": -2.0},
    {"ground_m": 0.3, "crank_m": 0.7, "coupler_m": 0.9, "rocker_m": 0.8, "crank_angle0_deg": 200.0 - 360.0},
    {"ground_m": 1.2, "crank_m": 0.9, "coupler_m": 0.7, "rocker_m": 0.6, "crank_angle0_deg": 30.0},
    {
        "ground_m": 1.0,
        "crank_m": 0.8,
        "coupler_m": 0.35,
        "rocker_m": 0.9,
        "crank_angle0_deg": 60.0,
        "crank_speed_rad_s": 3.0,
        "coupler_point_m": 0.2,
        "coupler_point_deg": -70.0,
    },
]


def own_positions(theta2, a, b, c, d, branch, ap, angle_p):
    """θ₃, θ₄ (rad) and the coupler point P (complex, m) from the triangle A B O₄ (law of cosines)."""
    pin_a = a * np.exp(1j * theta2)
    to_o4 = d - pin_a
    s = abs(to_o4)
    at_a = math.acos((b * b + s * s - c * c) / (2.0 * b * s))  # angle at A between A→O₄ and A→B
    theta3 = np.angle(to_o4) + (at_a if branch == "open" else -at_a)  # open: B to the left of A→O₄
    pin_b = pin_a + b * np.exp(1j * theta3)
    theta4 = np.angle(pin_b - d)
    return theta3, theta4, pin_a + ap * np.exp(1j * (theta3 + angle_p))


def turn(x, y):
    """x − y as an angle in (−π, π]."""
    return float(np.angle(np.exp(1j * (x - y))))


@pytest.mark.parametrize("changes", CASES)
def test_outputs_match_finite_differences_of_an_independent_loop_closure(changes):
    inputs = EXAMPLE.inputs.validate(changes)
    out = EXAMPLE.solve(inputs).outputs
    a, b, c, d = (inputs[k] for k in ("crank_m", "coupler_m", "rocker_m", "ground_m"))
    w2 = inputs["crank_speed_rad_s"]
    args = (a, b, c, d, inputs["branch"], inputs["coupler_point_m"], math.radians(inputs["coupler_point_deg"]))
    t2 = math.radians(inputs["crank_angle0_deg"])
    (t3m, t4m, pm), (t3, t4, p), (t3p, t4p, pp) = (own_positions(t2 + k * H, *args) for k in (-1, 0, 1))
    length = max(a, b, c, d, inputs["coupler_point_m"])
    assert turn(out["coupler_angle_rad"], t3) == pytest.approx(0.0, abs=1e-12)
    assert turn(out["rocker_angle_rad"], t4) == pytest.approx(0.0, abs=1e-12)
    assert np.allclose(out["coupler_point_m"], [p.real, p.imag], rtol=0, atol=1e-12 * length)
    rate_tol, acc_tol = 1e-6 * max(abs(w2), 1e-3), 1e-6 * max(w2 * w2, 1e-6)
    assert out["coupler_rate_rad_s"] == pytest.approx(w2 * (turn(t3p, t3m)) / (2 * H), abs=rate_tol)
    assert out["rocker_rate_rad_s"] == pytest.approx(w2 * (turn(t4p, t4m)) / (2 * H), abs=rate_tol)
    second3 = (turn(t3p, t3) - turn(t3, t3m)) / H**2
    second4 = (turn(t4p, t4) - turn(t4, t4m)) / H**2
    assert out["coupler_acceleration_rad_s2"] == pytest.approx(w2 * w2 * second3, abs=acc_tol)
    assert out["rocker_acceleration_rad_s2"] == pytest.approx(w2 * w2 * second4, abs=acc_tol)
    v_p = w2 * (pp - pm) / (2 * H)
    a_p = w2 * w2 * (pp - 2 * p + pm) / H**2
    assert np.allclose(out["coupler_point_velocity_m_s"], [v_p.real, v_p.imag], rtol=0, atol=1e-6 * abs(w2) * length)
    assert np.allclose(
        out["coupler_point_acceleration_m_s2"], [a_p.real, a_p.imag], rtol=0, atol=1e-6 * w2 * w2 * length
    )
    # The transmission angle is the angle between the coupler and the rocker lines at B.
    mu = abs(turn(t3, t4))
    assert out["transmission_angle_rad"] == pytest.approx(mu, abs=1e-12)


def test_check_step_agrees_at_the_defaults():
    steps = EXAMPLE.solve(EXAMPLE.inputs.defaults()).steps
    check = steps[-1]
    assert check.title.startswith("Check")
    assert np.allclose(check.values["v_B (coupler)"], check.values["v_B (rocker)"], rtol=0, atol=1e-14)
    assert np.allclose(check.values["a_B (coupler)"], check.values["a_B (rocker)"], rtol=0, atol=1e-14)


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        ({"ground_m": 1.0, "crank_m": 3.0, "coupler_m": 0.5, "rocker_m": 0.5}, "coupler_m"),  # cannot be assembled
        (
            {"ground_m": 1.2, "crank_m": 0.9, "coupler_m": 0.7, "rocker_m": 0.6, "crank_angle0_deg": 120.0},
            "crank_angle0_deg",
        ),
        (  # exactly at the non-Grashof linkage's toggle: the rates are unbounded
            {
                "ground_m": 1.2,
                "crank_m": 0.9,
                "coupler_m": 0.7,
                "rocker_m": 0.6,
                "crank_angle0_deg": math.degrees(math.acos((0.81 + 1.44 - 1.3**2) / (2 * 0.9 * 1.2))),
            },
            "crank_angle0_deg",
        ),
    ],
)
def test_impossible_inputs_are_refused_naming_a_field(changes, field):
    with pytest.raises(ParameterError) as refused:
        EXAMPLE.inputs.validate(changes)
    assert refused.value.field == field
    with pytest.raises(ValueError):
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), **changes})
