"""Worked example ``sorting-table-carriage`` (app/physics/systems/ch03/moving_frame_example.py).

Independent reference: sympy. The carriage's floor position r_O(t) + Rz(Ω_p t) Rx(β) Rz(θ(t)) {s(t), d, 0} is
built symbolically and differentiated exactly twice; ω and α come from the exact Ṙ Rᵀ, and the Coriolis and
relative terms from the exact derivatives of the guide coordinate. The moving-frame formula is never used.
Tolerance: double-precision evaluations of a few dozen operations on accelerations up to about 100 m/s²: 1e-12 of
the chain's size (with a floor of 1e-3 m/s²).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from app.physics.systems.ch03.moving_frame import TABLE_HEIGHT_M
from app.physics.systems.ch03.moving_frame_example import EXAMPLE

RELATIVE_TOL = 1e-12

CASES = [
    EXAMPLE.inputs.defaults(),
    {
        "spin_rate_rad_s": 1.2,
        "spin_acceleration_rad_s2": 0.2,
        "tilt_deg": 25.0,
        "precession_rate_rad_s": 0.6,
        "groove_offset_m": 0.3,
        "slider_amplitude_m": 0.6,
        "slider_frequency_hz": 0.3,
        "cart_amplitude_m": 0.2,
        "cart_frequency_hz": 0.5,
        "time_s": 3.7,
    },
    {
        "spin_rate_rad_s": -6.0,
        "spin_acceleration_rad_s2": 2.0,
        "tilt_deg": 60.0,
        "precession_rate_rad_s": -3.0,
        "table_radius_m": 3.0,
        "groove_offset_m": -2.0,
        "slider_amplitude_m": 2.2,
        "slider_frequency_hz": 2.0,
        "cart_amplitude_m": 2.0,
        "cart_frequency_hz": 2.0,
        "time_s": 0.4,
    },
    {
        "spin_rate_rad_s": 0.5,
        "spin_acceleration_rad_s2": 0.3,
        "slider_amplitude_m": 0.0,
        "groove_offset_m": 0.6,
        "time_s": 44.0,
        "replay_s": 30.0,
    },
]


def Rz(a):
    return sp.Matrix([[sp.cos(a), -sp.sin(a), 0], [sp.sin(a), sp.cos(a), 0], [0, 0, 1]])


def Rx(a):
    return sp.Matrix([[1, 0, 0], [0, sp.cos(a), -sp.sin(a)], [0, sp.sin(a), sp.cos(a)]])


def reference(inputs) -> dict[str, np.ndarray]:
    t = sp.symbols("t", real=True)
    F = lambda x: sp.Float(x, 30)  # noqa: E731
    theta = F(inputs["spin_rate_rad_s"]) * t + F(inputs["spin_acceleration_rad_s2"]) * t**2 / 2
    R = Rz(F(inputs["precession_rate_rad_s"]) * t) * Rx(sp.rad(F(inputs["tilt_deg"]))) * Rz(theta)
    s = F(inputs["slider_amplitude_m"]) * sp.sin(2 * sp.pi * F(inputs["slider_frequency_hz"]) * t)
    r_body = sp.Matrix([s, F(inputs["groove_offset_m"]), 0])
    r_origin = sp.Matrix(
        [F(inputs["cart_amplitude_m"]) * sp.sin(2 * sp.pi * F(inputs["cart_frequency_hz"]) * t), 0, TABLE_HEIGHT_M]
    )
    position = r_origin + R * r_body
    W = R.diff(t) * R.T
    omega = sp.Matrix([W[2, 1], W[0, 2], W[1, 0]])
    instant = math.fmod(inputs["time_s"], inputs["replay_s"])
    value = lambda m: np.array([float(c.subs(t, instant).evalf(30)) for c in m])  # noqa: E731
    return {
        "position": value(position),
        "total": value(position.diff(t, 2)),
        "omega": value(omega),
        "alpha": value(omega.diff(t)),
        "coriolis": value(2 * omega.cross(R * r_body.diff(t))),
        "relative": value(R * r_body.diff(t, 2)),
        "reference": value(r_origin.diff(t, 2)),
    }


@pytest.mark.parametrize("case", range(len(CASES)))
def test_acceleration_and_its_terms_agree_with_sympys_derivatives(case):
    inputs = EXAMPLE.inputs.validate(CASES[case])
    out = EXAMPLE.solve(inputs).outputs
    ref = reference(inputs)
    chain = max(
        sum(
            float(np.linalg.norm(out[f"a_{n}_m_s2"]))
            for n in ("reference", "angular", "centripetal", "coriolis", "relative")
        ),
        1e-3,
    )
    assert np.abs(out["position_m"] - ref["position"]).max() < 1e-12 * np.linalg.norm(ref["position"])
    assert np.abs(out["omega_rad_s"] - ref["omega"]).max() < RELATIVE_TOL * max(np.linalg.norm(ref["omega"]), 1e-3)
    assert np.abs(out["alpha_rad_s2"] - ref["alpha"]).max() < RELATIVE_TOL * max(np.linalg.norm(ref["alpha"]), 1e-3)
    for name in ("total", "coriolis", "relative", "reference"):
        assert np.abs(out[f"a_{name}_m_s2"] - ref[name]).max() < RELATIVE_TOL * chain, name


def test_the_check_step_agrees_at_the_defaults():
    check = EXAMPLE.solve(EXAMPLE.inputs.defaults()).steps[-1]
    assert check.title.startswith("Check")
    # fourth-order second difference with h = 1e-3 s: truncation ≈ 1e-13, round-off ≈ 5 ε |r| / h² ≈ 1e-9 m/s²
    assert np.abs(check.values["a_P_differenced"] - check.values["a_P"]).max() < 1e-8


def test_a_carriage_that_would_leave_the_table_is_refused():
    values = {**EXAMPLE.inputs.defaults(), "table_radius_m": 0.5, "slider_amplitude_m": 0.6}
    with pytest.raises(ValueError, match="leave the table"):
        EXAMPLE.solve(values)
    with pytest.raises(ValueError, match="leave the table"):
        EXAMPLE.inputs.validate({"table_radius_m": 0.5})
