"""Worked example ``turret-boom-tip-velocity`` (app/physics/systems/ch03/vector_derivative_example.py).

Independent reference: sympy. The boom vector is written symbolically in ground components (the turret's turn as
Rodrigues' formula in sympy, times the boom's turret components) and differentiated exactly in t, so no part of the
formula (dA/dt)_fixed = (dA/dt)_rel + ω × A is used. Tolerance: both sides are evaluated in double precision from
a few dozen operations on numbers of size ≤ 3 m and ≤ 10 m/s: 1e-12 of the rate's size.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from app.physics.systems.ch03.vector_derivative_example import EXAMPLE

RELATIVE_TOL = 1e-12

CASES = [
    EXAMPLE.inputs.defaults(),
    {
        "frame_rate_rad_s": -2.0,
        "frame_axis_tilt_deg": 75.0,
        "length_m": 1.6,
        "stretch_amplitude_m": 1.2,
        "stretch_frequency_hz": 1.3,
        "relative_turn_rate_rad_s": 2.5,
        "elevation_deg": -40.0,
        "time_s": 4.2,
    },
    {
        "frame_rate_rad_s": 0.0,
        "frame_axis_tilt_deg": 0.0,
        "length_m": 0.5,
        "stretch_amplitude_m": 0.1,
        "stretch_frequency_hz": 0.5,
        "relative_turn_rate_rad_s": -1.0,
        "elevation_deg": 10.0,
        "time_s": 0.3,
    },
    {
        "frame_rate_rad_s": 3.0,
        "frame_axis_tilt_deg": 90.0,
        "length_m": 2.0,
        "stretch_amplitude_m": 0.0,
        "stretch_frequency_hz": 0.0,
        "relative_turn_rate_rad_s": 0.0,
        "elevation_deg": 80.0,
        "time_s": 37.0,
        "replay_s": 15.0,
    },
]


def reference(inputs) -> tuple[float, np.ndarray, np.ndarray]:
    """(t, A, dA/dt) in ground components, from sympy's exact derivative of the composed vector."""
    t = sp.symbols("t", real=True)
    beta = sp.rad(sp.Float(inputs["frame_axis_tilt_deg"], 30))
    n = sp.Matrix([sp.sin(beta), 0, sp.cos(beta)])
    K = sp.Matrix([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])
    angle = sp.Float(inputs["frame_rate_rad_s"], 30) * t
    R = sp.eye(3) + sp.sin(angle) * K + (1 - sp.cos(angle)) * K * K
    L = inputs["length_m"] + inputs["stretch_amplitude_m"] * sp.sin(2 * sp.pi * inputs["stretch_frequency_hz"] * t)
    e = sp.rad(sp.Float(inputs["elevation_deg"], 30))
    psi = inputs["relative_turn_rate_rad_s"] * t
    A = R * (L * sp.Matrix([sp.cos(e) * sp.cos(psi), sp.cos(e) * sp.sin(psi), sp.sin(e)]))
    instant = math.fmod(inputs["time_s"], inputs["replay_s"])
    value = np.array([float(c.subs(t, instant).evalf(30)) for c in A])
    rate = np.array([float(sp.diff(c, t).subs(t, instant).evalf(30)) for c in A])
    return instant, value, rate


@pytest.mark.parametrize("case", range(len(CASES)))
def test_tip_velocity_is_sympys_derivative_of_the_composed_vector(case):
    inputs = EXAMPLE.inputs.validate(CASES[case])
    out = EXAMPLE.solve(inputs).outputs
    instant, A, rate = reference(inputs)
    size = max(float(np.linalg.norm(rate)), 1e-3)
    assert out["t_s"] == pytest.approx(instant, abs=1e-15 * inputs["replay_s"])
    assert np.abs(out["A_m"] - A).max() < RELATIVE_TOL * np.linalg.norm(A)
    assert np.abs(out["dA_fixed_m_s"] - rate).max() < RELATIVE_TOL * size
    assert out["tip_speed_m_s"] == pytest.approx(np.linalg.norm(rate), abs=RELATIVE_TOL * size)
    # the two parts add to the whole, and the turret's part is ω × A with ω = Ω n
    assert np.abs(out["dA_relative_m_s"] + out["omega_cross_A_m_s"] - rate).max() < RELATIVE_TOL * size


def test_the_check_step_agrees_at_the_defaults():
    check = EXAMPLE.solve(EXAMPLE.inputs.defaults()).steps[-1]
    assert check.title.startswith("Check")
    assert check.values["A_dot_dA_over_A"] == pytest.approx(check.values["L_dot"], abs=1e-14)
    # fourth-order difference with h = 1e-3 s: truncation h⁴|A⁽⁵⁾|/30 ≈ 1e-13 m/s here, round-off ≈ 2e-13 m/s
    assert np.abs(check.values["dA_differenced"] - check.values["dA_fixed"]).max() < 1e-9


def test_a_stretch_as_long_as_the_boom_is_refused():
    values = {**EXAMPLE.inputs.defaults(), "length_m": 0.5, "stretch_amplitude_m": 0.5}
    with pytest.raises(ValueError, match="stretch amplitude"):
        EXAMPLE.solve(values)
    with pytest.raises(ValueError, match="stretch amplitude"):
        EXAMPLE.inputs.validate({"length_m": 0.5, "stretch_amplitude_m": 0.6})
