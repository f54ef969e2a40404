"""The spherical-pendulum Routh example against a Cartesian integration of the bob that knows nothing of θ, φ or H.

Independent computation: the bob's position r (m) obeys r̈ = −g ẑ − μ r with the rod's pull per unit mass
μ = (|ṙ|² − g z)/l², integrated by scipy's DOP853 at rtol 1e-12 over about three periods. The turning angles are θ at
the events ż = 0, the period of θ the time between two like events, H = ½ m |ṙ|² + m g z and p_φ = m (x ẏ − y ẋ) at
the start, and the cone angle solves the conical-pendulum condition sin⁴θ / cos θ = p_φ² / (m² g l³) (not the
example's V_eff′ = 0). Tolerance 1e-8 relative (1e-8 J or kg·m²/s absolute near zero): the integration's state error
is about 1e-11 after three periods, events are located on its dense output to about the same, and the arccos that
turns z into θ amplifies by less than 10 for turning angles between 10° and 170°; 1e-8 keeps a hundredfold margin.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch09.spherical_pendulum_routh_example import EXAMPLE

RTOL = 1e-8

CASES = [
    {},  # defaults: 1 kg, 1 m, θ₀ = 60°, φ̇₀ = 120°/s
    {"mass_kg": 2.5, "length_m": 0.4, "theta_0_deg": 100.0, "theta_rate_0_deg_s": -150.0, "phi_rate_0_deg_s": 300.0},
    {"g_m_s2": 0.0, "theta_0_deg": 45.0, "theta_rate_0_deg_s": 30.0, "phi_rate_0_deg_s": -90.0},
    {
        "mass_kg": 0.2,
        "length_m": 3.0,
        "g_m_s2": 1.62,
        "theta_0_deg": 20.0,
        "theta_rate_0_deg_s": 40.0,
        "phi_rate_0_deg_s": 50.0,
    },
]


def _cartesian_start(inputs):
    l = inputs["length_m"]
    th, thd = math.radians(inputs["theta_0_deg"]), math.radians(inputs["theta_rate_0_deg_s"])
    phd = math.radians(inputs["phi_rate_0_deg_s"])
    r = l * np.array([math.sin(th), 0.0, -math.cos(th)])
    v = l * np.array([math.cos(th) * thd, math.sin(th) * phd, math.sin(th) * thd])
    return r, v


def _run(inputs, t_end):
    l, g = inputs["length_m"], inputs["g_m_s2"]

    def rhs(_t, y):
        r, v = y[:3], y[3:]
        mu = (v @ v - g * r[2]) / l**2
        return np.concatenate([v, -mu * r - np.array([0.0, 0.0, g])])

    def vertical_rate(_t, y):
        return y[5]

    r, v = _cartesian_start(inputs)
    return solve_ivp(
        rhs, (0.0, t_end), np.concatenate([r, v]), method="DOP853", rtol=1e-12, atol=1e-14, events=vertical_rate
    )


@pytest.mark.parametrize("change", CASES)
def test_turning_angles_period_and_invariants_match_a_cartesian_integration(change):
    inputs = EXAMPLE.inputs.validate(change)
    out = EXAMPLE.solve(inputs).outputs
    m, l, g = inputs["mass_kg"], inputs["length_m"], inputs["g_m_s2"]
    r, v = _cartesian_start(inputs)
    energy = 0.5 * m * v @ v + m * g * r[2]
    p_phi = m * (r[0] * v[1] - r[1] * v[0])
    assert out["hamiltonian_J"] == pytest.approx(energy, rel=RTOL, abs=RTOL)
    assert out["p_phi_kg_m2_s"] == pytest.approx(p_phi, rel=RTOL)

    run = _run(inputs, 3.2 * out["theta_period_s"])
    events = run.t_events[0]
    states = run.y_events[0]
    # ż from + to −: z highest, θ lowest; − to +: θ highest. Classify by the sign of z̈ there.
    accel = np.array([-((s[3:] @ s[3:] - g * s[2]) / l**2) * s[2] - g for s in states])
    highs = events[accel < 0.0]  # z maxima
    lows = events[accel > 0.0]
    theta = np.degrees(np.arccos(-states[:, 2] / l))
    assert np.max(theta) == pytest.approx(out["theta_max_deg"], rel=RTOL)
    assert np.min(theta) == pytest.approx(out["theta_min_deg"], rel=RTOL)
    periods = np.concatenate([np.diff(highs), np.diff(lows)])
    assert len(periods) >= 2
    assert periods == pytest.approx(np.full(len(periods), out["theta_period_s"]), rel=RTOL)

    # Steady cone for this p_φ from the conical-pendulum condition (g > 0), or the equator (g = 0).
    if g > 0.0:
        target = p_phi**2 / (m * m * g * l**3)
        cone = brentq(lambda t: math.sin(t) ** 4 / math.cos(t) - target, 1e-9, math.pi / 2 - 1e-12, xtol=1e-15)
        assert out["cone_angle_deg"] == pytest.approx(math.degrees(cone), rel=RTOL)
    else:
        assert out["cone_angle_deg"] == 90.0


def test_no_azimuthal_rate_is_refused():
    with pytest.raises(ParameterError) as refused:
        EXAMPLE.inputs.validate({"phi_rate_0_deg_s": 0.0})
    assert refused.value.field == "phi_rate_0_deg_s"
    with pytest.raises(ValueError):
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), "phi_rate_0_deg_s": 0.0})
