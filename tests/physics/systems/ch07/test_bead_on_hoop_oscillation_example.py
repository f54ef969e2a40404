"""The bead on the spinning hoop's small oscillations (worked example ``bead-on-hoop-small-oscillations``, section 7.6)
against an independent computation: the full nonlinear equation ``θ̈ = sin θ (Ω² cos θ − g/R)`` written here,
its equilibrium found by scipy's ``brentq`` (a root of θ̈(θ) at rest), and its natural frequency measured by
integrating it with ``solve_ivp`` (DOP853, rtol 1e-12) from θₑ + ε at rest, timing ten periods by the zero crossings
of the rate.

Tolerances: the equilibrium 1e-12 rad (brentq's xtol). The measured frequency of an oscillation of amplitude ε
differs from the linear ω_n by a relative amount of order ε² (the amplitude dependence of a nonlinear oscillator's
period): with ε = 1e-4 rad that is ≈ 1e-8, the integrator adds ≈ 1e-11 and the crossing interpolation less;
so 1e-6 relative. A missing factor (sin²θ* dropped, or 2θ for θ in cos 2θ) changes ω_n by tens of percent.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch07.bead_on_hoop_oscillation_example import EXAMPLE

CASES = [
    {},
    {"hoop_speed_rad_s": 2.0},
    {"theta_0_deg": -20.0, "hoop_radius_m": 1.2, "hoop_speed_rad_s": 9.0},
    {"g_m_s2": 0.0, "hoop_speed_rad_s": 3.0},
    {"g_m_s2": 1.62, "hoop_radius_m": 0.1, "hoop_speed_rad_s": 0.0, "theta_0_deg": 150.0},
]
EPSILON = 1e-4


def _rhs(g_over_R, spin):
    return lambda theta: math.sin(theta) * (spin * spin * math.cos(theta) - g_over_R)


def _measured_frequency(g_over_R, spin, theta_e):
    accel = _rhs(g_over_R, spin)
    guess = math.sqrt(abs(g_over_R * math.cos(theta_e) - spin * spin * math.cos(2 * theta_e)))

    def crossing(t, y):
        return y[1]

    crossing.direction = 1.0
    run = solve_ivp(
        lambda t, y: [y[1], accel(y[0])],
        (0.0, 12.0 * 2 * math.pi / guess),
        [theta_e + EPSILON, 0.0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-16,
        events=crossing,
    )
    times = run.t_events[0]
    assert len(times) >= 11
    return 2 * math.pi * 10 / (times[10] - times[0])


@pytest.mark.parametrize("changes", CASES)
def test_equilibrium_and_frequency_match_the_integrated_nonlinear_equation(changes):
    values = EXAMPLE.inputs.validate(changes)
    g_over_R, spin = values["g_m_s2"] / values["hoop_radius_m"], values["hoop_speed_rad_s"]
    out = EXAMPLE.solve(values).outputs
    theta_e = out["equilibrium_rad"]
    if theta_e != 0.0:  # off the bottom: the root of θ̈ at rest strictly between the bottom and the top, on θ₀'s side
        side = math.copysign(1.0, theta_e)
        root = brentq(lambda th: _rhs(g_over_R, spin)(side * th), 1e-9, math.pi - 1e-9, xtol=1e-14)
        assert theta_e == pytest.approx(side * root, abs=1e-12)
    measured = _measured_frequency(g_over_R, spin, theta_e)
    assert out["natural_frequency_rad_s"] == pytest.approx(measured, rel=1e-6)
    assert out["period_s"] == pytest.approx(2 * math.pi / measured, rel=1e-6)
    assert out["critical_spin_rad_s"] == pytest.approx(math.sqrt(g_over_R), rel=1e-15)


def test_the_check_step_rests_at_the_equilibrium_with_the_slope_minus_k():
    check = EXAMPLE.solve(EXAMPLE.inputs.defaults()).steps[-1]
    assert check.title.startswith("Check")
    assert check.values["thetaddot_at_theta_e"] == 0.0
    assert check.values["k_engine"] == pytest.approx(check.values["k"], rel=1e-8)  # the central difference's error


@pytest.mark.parametrize(
    "changes",
    [{"hoop_speed_rad_s": math.sqrt(9.81 / 0.5)}, {"g_m_s2": 0.0, "hoop_speed_rad_s": 0.0}],
)
def test_the_critical_spin_and_a_hoop_without_gravity_or_spin_are_refused(changes):
    with pytest.raises(ParameterError, match="no small oscillation") as refused:
        EXAMPLE.inputs.validate(changes)
    assert refused.value.field == "hoop_speed_rad_s"
    with pytest.raises(ValueError, match="no small oscillation"):  # solve refuses too, called without the check
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), **changes})


def test_the_unstable_equilibria_have_negative_stiffness():
    values = EXAMPLE.inputs.defaults()
    steps = EXAMPLE.solve(values).steps
    stiffness = next(s for s in steps if s.title.startswith("Linearise")).values
    assert stiffness["k_bottom"] < 0 and stiffness["k_top"] < 0 and stiffness["k_star"] > 0
    assert np.isclose(
        stiffness["k_bottom"], values["g_m_s2"] / values["hoop_radius_m"] - values["hoop_speed_rad_s"] ** 2
    )
