"""The rate gyro at undamped resonance, and the warning when β leaves the small-angle model.

The resonant closed form β = (G Ω₀/2)(sin ω_n t − ω_n t cos ω_n t) is checked against a
tight numerical integration of the output equation I_g β̈ + k β = I_a ω_s Ω₀ sin(ω_n t)
from rest, and against the general (detuned) formula just off resonance.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from app.physics.core.closed_form import OUTSIDE_MODEL
from app.physics.systems.ch10 import rate_gyro as rg

RESONANT = rg.PARAMETERS.validate(
    {"input_kind": "sine", "damping_N_m_s_rad": 0.0, "stiffness_N_m_rad": 0.5, "gimbal_inertia_kg_m2": 5e-3, "input_frequency_rad_s": 10.0}
)


def integrated_beta(params, t_s: np.ndarray) -> np.ndarray:
    """β(t) of I_g β̈ + c β̇ + k β = H Ω(t) from rest, by DOP853 at rtol 1e-12."""
    I_g, c, k = params["gimbal_inertia_kg_m2"], params["damping_N_m_s_rad"], params["stiffness_N_m_rad"]
    H = rg.angular_momentum_N_m_s(params)

    def rhs(t, y):
        return [y[1], (H * float(rg.input_rate(params, np.array([t]))[0]) - c * y[1] - k * y[0]) / I_g]

    solution = solve_ivp(rhs, (0.0, float(t_s[-1])), [0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-14, t_eval=t_s)
    return solution.y[0]


def test_exact_resonance_is_answered_by_the_secular_closed_form():
    assert rg.resonant(RESONANT)
    t = np.linspace(0.0, 30.0, 601)
    beta = rg.gimbal_response(RESONANT, t).beta_rad
    reference = integrated_beta(RESONANT, t)
    amplitude = 0.5 * rg.steady_gain_s(RESONANT) * RESONANT["input_rate_rad_s"] * 10.0 * 30.0  # envelope G Ω₀ ω_n t / 2 at 30 s
    # DOP853 at rtol 1e-12 over 48 periods keeps ~1e-10 of the amplitude; 1e-8 leaves a wide margin and is far
    # below the growth being checked (β reaches `amplitude`; a wrong secular term would be off by O(1)).
    assert np.max(np.abs(beta - reference)) < 1e-8 * amplitude
    assert np.max(np.abs(beta)) == pytest.approx(amplitude, rel=0.02)  # grows linearly in t
    # β̇ is the derivative of β: central differences at h = 1e-5 s agree to O(h²) ~ 1e-8 of the amplitude rate.
    h = 1e-5
    rate = rg.gimbal_response(RESONANT, t[1:-1]).beta_rate_rad_s
    difference = (rg.gimbal_response(RESONANT, t[1:-1] + h).beta_rad - rg.gimbal_response(RESONANT, t[1:-1] - h).beta_rad) / (2 * h)
    assert np.max(np.abs(rate - difference)) < 1e-6 * amplitude * 10.0


def test_just_off_resonance_the_general_formula_approaches_the_secular_one():
    t = np.linspace(0.0, 10.0, 201)
    detuned = {**RESONANT, "input_frequency_rad_s": 10.0 * (1.0 + 1e-6)}
    assert not rg.resonant(detuned)
    # The detuned response differs from the resonant one by O(δ ω t) relative, δ = 1e-6: ~1e-4 at t = 10 s.
    exact = rg.gimbal_response(RESONANT, t).beta_rad
    near = rg.gimbal_response(detuned, t).beta_rad
    assert np.max(np.abs(near - exact)) < 1e-3 * np.max(np.abs(exact))


def test_frequency_response_at_resonance_is_unbounded_not_a_division_by_zero():
    ratio, lag = rg.frequency_response(RESONANT, rg.natural_frequency_rad_s(RESONANT))
    assert ratio == math.inf and lag == pytest.approx(math.pi / 2)


def test_report_warns_where_beta_leaves_the_small_angle_model():
    report = rg.RateGyro().simulate(RESONANT, {}, t_end_s=20.0, frame_rate_hz=60.0).as_dict()
    beta = np.array(report["series"]["beta_rad"])
    first = float(np.array(report["t"])[np.argmax(np.abs(beta) > rg.SMALL_ANGLE_LIMIT_RAD)])
    assert report["stats"]["status"] == OUTSIDE_MODEL
    assert f"t = {first:.4g} s" in report["stats"]["message"]
    assert report["events"] == [{"t_s": first, "kind": "outside-model", "message": report["stats"]["message"]}]
    calm = rg.RateGyro().simulate(rg.PARAMETERS.validate({}), {}, t_end_s=20.0, frame_rate_hz=60.0).as_dict()
    assert calm["stats"]["status"] == "ok" and calm["events"] == []
