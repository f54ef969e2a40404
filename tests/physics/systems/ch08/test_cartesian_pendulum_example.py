"""The Cartesian-pendulum worked example against polar coordinates and the scene's own integrated model.

Independent computations:

* the consistent start, the multiplier and the acceleration in polar coordinates: θ = atan2(x₀, −y₀) puts the bob at
  L (sin θ, −cos θ); only the velocity's component along the tangent (cos θ, sin θ) survives; the bob's acceleration
  is −(v²/L) ê_r − g sin θ ê_θ and the tension m v²/L + m g cos θ. A few operations on O(1) numbers: 1e-12 of the
  scales L, √(gL) + |v|, g + v²/L and m (g + v²/L);
* the drift: the scene's model (:class:`~app.physics.systems.ch08.cartesian_pendulum_model.CartesianPendulum`)
  integrated with its own RK4 and its own index-1 right-hand side (it solves the 3 × 3 system numerically where the
  example uses λ in closed form) and its own projection, one step per frame at 1/h frames per second. Both are the
  same method, so they differ by round-off alone, grown over the run: measured ~2e-14 m² in 300 steps; 1e-11 of
  L² (and of the energy scale m (g L + v²)) allows for runs of thousands of steps;
* RK4 is fourth order: halving h divides the drift by 16 (12–20 allowed, for h small enough that the
  next order is a few per cent).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch08.cartesian_pendulum_example import EXAMPLE
from app.physics.systems.ch08.cartesian_pendulum_model import CartesianPendulum

CASES = [
    {},
    {"y0_m": -0.3},
    {"y0_m": -0.3, "vx0_m_s": 1.0},
    {"mass_kg": 2.5, "length_m": 2.0, "g_m_s2": 3.7, "x0_m": -1.0, "y0_m": 1.5, "vx0_m_s": -2.0, "vy0_m_s": 0.5},
    {"x0_m": 0.0, "y0_m": -3.0, "vx0_m_s": 4.0, "step_s": 0.01, "duration_s": 5.0},
]


@pytest.mark.parametrize("changes", CASES)
def test_start_multiplier_and_acceleration_match_polar_coordinates(changes):
    p = EXAMPLE.inputs.validate(changes)
    solution = EXAMPLE.solve(p)
    out = solution.outputs
    m, length, g = p["mass_kg"], p["length_m"], p["g_m_s2"]
    theta = math.atan2(p["x0_m"], -p["y0_m"])
    e_r, e_t = np.array([math.sin(theta), -math.cos(theta)]), np.array([math.cos(theta), math.sin(theta)])
    v_t = p["vx0_m_s"] * e_t[0] + p["vy0_m_s"] * e_t[1]
    speed = math.sqrt(g * length) + abs(v_t)
    np.testing.assert_allclose(out["consistent_position_m"], length * e_r, rtol=0, atol=1e-12 * length)
    np.testing.assert_allclose(out["consistent_velocity_m_s"], v_t * e_t, rtol=0, atol=1e-12 * speed)
    tension = m * v_t**2 / length + m * g * math.cos(theta)
    force_scale = m * (g + v_t**2 / length)
    assert out["tension_N"] == pytest.approx(tension, abs=1e-12 * force_scale)
    assert out["multiplier_N_m"] == pytest.approx(tension / length, abs=1e-12 * force_scale / length)
    acceleration = -(v_t**2 / length) * e_r - g * math.sin(theta) * e_t
    np.testing.assert_allclose(solution.steps[3].values["a"], acceleration, rtol=0, atol=1e-12 * force_scale / m)
    check = solution.steps[-1]
    assert check.title.startswith("Check")
    np.testing.assert_allclose(check.values["q_general"], length * e_r, rtol=0, atol=1e-12 * length)
    np.testing.assert_allclose(check.values["v_general"], v_t * e_t, rtol=0, atol=1e-12 * speed)


@pytest.mark.parametrize("changes", CASES)
def test_drift_matches_the_scene_model_with_its_own_rk4(changes):
    p = EXAMPLE.inputs.validate(changes)
    out = EXAMPLE.solve(p).outputs
    params = {name: p[name] for name in CartesianPendulum.parameters.by_name}
    m, length, g = p["mass_kg"], p["length_m"], p["g_m_s2"]
    speed2 = float(np.sum(np.asarray(out["consistent_velocity_m_s"]) ** 2))
    energy_scale = m * (g * length + speed2)
    for method, drift, energy in (
        ("uncorrected", "drift_uncorrected_m2", "energy_change_uncorrected_J"),
        ("projection", "drift_projected_m2", "energy_change_projected_J"),
    ):
        report = CartesianPendulum().simulate(
            params,
            {"method": method, "integrator": "rk4", "steps_per_frame": 1},
            t_end_s=p["duration_s"],
            frame_rate_hz=1.0 / p["step_s"],
            request_limits=False,
        )
        assert report.t_s[-1] == pytest.approx(p["duration_s"], rel=1e-12)
        residual = report.invariants["constraint_position"][-1]  # |g| at the end
        assert abs(abs(out[drift]) - residual) <= 1e-11 * length**2, method
        energy_change = report.invariants["energy"][-1] - report.invariants["energy"][0]
        assert out[energy] == pytest.approx(energy_change, abs=1e-11 * energy_scale), method
    assert abs(out["drift_projected_m2"]) <= 1e-12 * length**2


def test_the_drift_falls_as_the_fourth_power_of_the_step():
    drifts = [
        EXAMPLE.solve(EXAMPLE.inputs.validate({"step_s": h})).outputs["drift_uncorrected_m2"] for h in (0.02, 0.01)
    ]
    assert 12.0 < drifts[0] / drifts[1] < 20.0


def test_impossible_inputs_are_refused():
    with pytest.raises(ParameterError, match="pivot"):  # a 422 from the API, naming y0_m
        EXAMPLE.inputs.validate({"x0_m": 0.0, "y0_m": 0.0})  # at the pivot: no nearest point on the circle
    with pytest.raises(ParameterError, match="steps"):
        EXAMPLE.inputs.validate({"step_s": 0.002, "duration_s": 60.0})  # 30 000 steps: over the budget
    with pytest.raises(ParameterError, match="diverges"):  # h ω ≈ (50 m/s / 0.05 m) / 30 = 33: RK4 is unstable
        EXAMPLE.solve(EXAMPLE.inputs.validate({"length_m": 0.05, "x0_m": 0.05, "y0_m": 0.0, "vy0_m_s": 50.0}))
    with pytest.raises(ValueError, match="pivot"):
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), "x0_m": 0.0, "y0_m": 0.0})
