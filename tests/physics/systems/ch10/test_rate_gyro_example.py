"""The rate-gyro example's closed forms against a time integration with event detection and the complex gain.

Independent computation: the output equation I_g β̈ + c β̇ + k β = I_a ω_s Ω₀ integrated from rest by scipy's DOP853
(rtol 1e-12) with an event at β̇ = 0 (falling): its first event is the peak (time and deflection), and β after forty of
its slowest time constants is the steady deflection. The sine response comes from the complex gain β/Ω = I_a ω_s /
(k − I_g w² + i c w), its modulus and argument. Tolerances: 1e-9 relative for the peak and its time (the event is
located on the dense output to about 1e-12 of the time scale, and the peak is flat in time, so its value is better
still), 1e-9 for the steady deflection (the transient e^{−40} ≈ 4e-18 is gone), and 1e-12 for the complex gain
(a handful of floating-point operations).
"""

from __future__ import annotations

import cmath
import math

import pytest
from scipy.integrate import solve_ivp

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch10.rate_gyro_example import EXAMPLE

CASES = [
    {},  # defaults: ζ = 0.2, ω_n = 10 rad/s
    {"damping_N_m_s_rad": 0.003, "input_rate_rad_s": -0.2, "input_frequency_rad_s": 9.0},  # ζ = 0.03, near resonance
    {"spin_rad_s": -24000.0, "rotor_axial_inertia_kg_m2": 1e-5, "stiffness_N_m_rad": 2.0, "damping_N_m_s_rad": 0.15},
    {"damping_N_m_s_rad": 0.3, "input_frequency_rad_s": 40.0},  # ζ = 3: overdamped
]


def _integrate(inputs, t_end, events=None):
    J, c, k = inputs["gimbal_inertia_kg_m2"], inputs["damping_N_m_s_rad"], inputs["stiffness_N_m_rad"]
    moment = inputs["rotor_axial_inertia_kg_m2"] * inputs["spin_rad_s"] * inputs["input_rate_rad_s"]
    return solve_ivp(
        lambda _t, y: (y[1], (moment - c * y[1] - k * y[0]) / J),
        (0.0, t_end),
        (0.0, 0.0),
        method="DOP853",
        rtol=1e-12,
        atol=1e-16,
        events=events,
    )


@pytest.mark.parametrize("change", CASES)
def test_step_and_sine_responses_match_integration_and_the_complex_gain(change):
    inputs = EXAMPLE.inputs.validate(change)
    out = EXAMPLE.solve(inputs).outputs
    J, c, k = inputs["gimbal_inertia_kg_m2"], inputs["damping_N_m_s_rad"], inputs["stiffness_N_m_rad"]
    H = inputs["rotor_axial_inertia_kg_m2"] * inputs["spin_rad_s"]
    wn = math.sqrt(k / J)
    zeta = c / (2.0 * math.sqrt(k * J))
    assert out["angular_momentum_N_m_s"] == pytest.approx(H, rel=1e-15)
    assert out["natural_frequency_rad_s"] == pytest.approx(wn, rel=1e-15)
    assert out["damping_ratio"] == pytest.approx(zeta, rel=1e-15)

    slowest = zeta * wn if zeta < 1.0 else wn * (zeta - math.sqrt(zeta * zeta - 1.0))  # slowest free decay rate
    steady = _integrate(inputs, 40.0 / slowest).y[0, -1]
    assert out["steady_deflection_rad"] == pytest.approx(steady, rel=1e-9)
    if zeta < 1.0:

        def turn(_t, y):
            return y[1]

        turn.direction = -1.0 if steady > 0 else 1.0
        run = _integrate(inputs, 2.0 * math.pi / wn, turn)
        t_peak, beta_peak = run.t_events[0][0], run.y_events[0][0][0]
        assert out["peak_time_s"] == pytest.approx(t_peak, rel=1e-9)
        assert out["peak_deflection_rad"] == pytest.approx(beta_peak, rel=1e-9)
        assert out["overshoot"] == pytest.approx(beta_peak / steady - 1.0, rel=1e-8)
    else:
        assert out["overshoot"] == 0.0 and "peak_time_s" not in out

    w = inputs["input_frequency_rad_s"]
    gain = H / complex(k - J * w * w, c * w)
    assert out["sine_amplitude_ratio_s"] == pytest.approx(abs(gain), rel=1e-12)
    lag = -cmath.phase(gain) if H > 0 else -cmath.phase(-gain)  # β behind Ω (H < 0 flips β's sign, not its lag)
    assert out["sine_phase_lag_deg"] == pytest.approx(math.degrees(lag % (2 * math.pi)), rel=1e-12)


def test_a_rotor_without_spin_is_refused():
    with pytest.raises(ParameterError) as refused:
        EXAMPLE.inputs.validate({"spin_rad_s": 0.0})
    assert refused.value.field == "spin_rad_s"
    with pytest.raises(ValueError):
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), "spin_rad_s": 0.0})
