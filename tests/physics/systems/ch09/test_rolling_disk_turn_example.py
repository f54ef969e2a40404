"""The rolling-disk example (Kane's lean equation by hand) against the project's Newton–Euler equations of the disk.

Independent computation: the derivation engine's ``newton-euler`` formulation (momentum and angular-momentum balance
with the contact force as an unknown, eliminated symbolically; neither Kane's partial velocities nor the Gibbs
function the example's check uses). Its θ̈ at the starting state must equal the example's; at the example's steady
heading rate θ̈ must vanish, and a scipy DOP853 run (rtol 1e-12) of those equations for one second must keep the lean
and trace a circle of the example's radius. Tolerances: θ̈ to 1e-10 relative (both sides are a few dozen floating
operations on the same state; 1e-10 leaves a millionfold margin over rounding and none for a wrong coefficient, which
would be off by tens of percents), θ̈ = 0 to 1e-9 of the gravity term 0.8 g/r · |sin θ| (the steady root is found to
rounding, and θ̈ is its smooth function), the lean over one second to 1e-8 rad and the radius to 1e-8 relative (the
integration's own error after one second is about 1e-11; the steady turns chosen here are not fast-diverging).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch09.rolling_disk_model import LEAN, LEAN_RATE, RollingDiskMotion
from app.physics.systems.ch09.rolling_disk_turn_example import EXAMPLE, disk_state

CASES = [
    {},  # defaults: 1 kg, r = 0.1 m, θ₀ = 10°, φ̇₀ = 12 rad/s, ψ̇₀ = 0
    {"mass_kg": 5.0, "radius_m": 0.3, "lean_0_deg": -20.0, "spin_rate_0_rad_s": -15.0, "heading_rate_0_rad_s": 2.0},
    {"g_m_s2": 1.62, "radius_m": 0.05, "lean_0_deg": 30.0, "spin_rate_0_rad_s": 25.0, "heading_rate_0_rad_s": -1.0},
    {"lean_0_deg": 5.0, "spin_rate_0_rad_s": 40.0, "heading_rate_0_rad_s": 3.0},
]


def _newton_euler(inputs):
    model = RollingDiskMotion()
    params = {**inputs, "formulation": "newton-euler"}
    derivation = model.derived(params)
    p = model.parameter_array(params)
    return lambda t, y: derivation.state_derivative(t, y, p)


@pytest.mark.parametrize("change", CASES)
def test_lean_acceleration_and_steady_turn_match_newton_euler(change):
    inputs = EXAMPLE.inputs.validate(change)
    out = EXAMPLE.solve(inputs).outputs
    rates = _newton_euler(inputs)
    heading = inputs["heading_rate_0_rad_s"]
    expected = rates(0.0, disk_state(inputs, heading))[LEAN_RATE]
    assert out["lean_acceleration_rad_s2"] == pytest.approx(expected, rel=1e-10, abs=1e-12)

    steady = out["steady_heading_rate_rad_s"]
    assert steady is not None
    theta0 = math.radians(inputs["lean_0_deg"])
    gravity_scale = 0.8 * inputs["g_m_s2"] / inputs["radius_m"] * abs(math.sin(theta0))
    start = disk_state(inputs, steady)
    assert abs(rates(0.0, start)[LEAN_RATE]) <= 1e-9 * gravity_scale

    run = solve_ivp(rates, (0.0, 1.0), start, method="DOP853", rtol=1e-12, atol=1e-13, dense_output=True)
    times = np.linspace(0.0, 1.0, 41)
    states = run.sol(times)
    assert np.max(np.abs(states[LEAN] - theta0)) <= 1e-8
    # The contact point (x, y) stays on a circle of radius R = |r φ̇ / ψ̇| (its centre: R to the side of the start).
    radius = out["turn_radius_m"]
    assert radius == pytest.approx(abs(inputs["radius_m"] * inputs["spin_rate_0_rad_s"] / steady), rel=1e-12)
    side = math.copysign(1.0, steady * inputs["spin_rate_0_rad_s"])
    centre = np.array([0.0, side * radius])
    distances = np.hypot(states[0] - centre[0], states[1] - centre[1])
    assert distances == pytest.approx(np.full_like(distances, radius), rel=1e-8)


def test_a_disk_the_floor_would_have_to_pull_down_is_refused():
    change = {"lean_0_deg": 60.0, "spin_rate_0_rad_s": 60.0, "heading_rate_0_rad_s": 20.0}
    with pytest.raises(ParameterError) as refused:
        EXAMPLE.inputs.validate(change)
    assert refused.value.field == "heading_rate_0_rad_s"
    with pytest.raises(ValueError):
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), **change})


def test_too_slow_a_spin_has_no_steady_turn():
    out = EXAMPLE.solve(EXAMPLE.inputs.validate({"spin_rate_0_rad_s": 1.0})).outputs
    assert out["steady_heading_rate_rad_s"] is None and out["turn_radius_m"] is None
