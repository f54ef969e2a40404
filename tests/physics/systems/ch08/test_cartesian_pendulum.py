"""The Cartesian pendulum: its exact solution, the model's series and invariants, the minimal-coordinate reference."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from app.physics.systems.ch08.cartesian_pendulum import angle_and_rate, exact_states
from app.physics.systems.ch08.cartesian_pendulum_model import CartesianPendulum

UNIT = {"mass_kg": 1.0, "length_m": 1.0, "g_m_s2": 1.0, "x0_m": 1.0, "y0_m": 0.0, "vx0_m_s": 0.0, "vy0_m_s": 0.0}


@pytest.mark.parametrize("start", [np.array([1.0, 0.0, 0.0, 0.0]), np.array([0.6, -0.8, -1.2, -0.9])])
def test_elliptic_solution_matches_a_tight_independent_integration(start):
    """θ̈ = −(g/L) sin θ by DOP853 at rtol 1e-12 over 15 s agrees with the closed form to 1e-9 rad (measured ~1e-11).

    The second start moves toward negative θ̇ (cn(u₀) < 0 branch), g = 9.81, L = 1.
    """
    g = 1.0 if start[0] == 1.0 else 9.81
    theta0, rate0 = (float(a[0]) for a in angle_and_rate(1.0, start[None, :]))
    t = np.linspace(0.0, 15.0, 301)
    tight = solve_ivp(lambda _, y: [y[1], -g * np.sin(y[0])], (0.0, 15.0), [theta0, rate0], method="DOP853", rtol=1e-12, atol=1e-12, t_eval=t)
    theta, rate = angle_and_rate(1.0, exact_states(1.0, g, start, t))
    np.testing.assert_allclose(theta, tight.y[0], atol=1e-9)
    np.testing.assert_allclose(rate, tight.y[1], atol=1e-9)


def test_over_the_top_has_no_libration_closed_form():
    with pytest.raises(ValueError, match="over the top"):
        exact_states(1.0, 9.81, np.array([0.0, -1.0, 7.0, 0.0]), np.zeros(1))


@pytest.mark.parametrize("method", ["uncorrected", "baumgarte", "projection", "partitioning", "minimal"])
def test_model_reports_residuals_energy_and_tension_for_every_method(method):
    """dopri5 at rtol 1e-10 over 10 s: energy constant to 1e-8 J (measured ≤ 1e-9), and at the lowest point the
    multiplier is the closed form λ = T/L = 3 m g / L = 3 N/m (swing from 90°), within 1e-5 N/m (frames sample near it)."""
    model = CartesianPendulum()
    params = CartesianPendulum.parameters.validate(UNIT)
    report = model.simulate(params, {"method": method, "integrator": "dopri5", "rtol": 1e-10}, t_end_s=10.0, frame_rate_hz=240.0)
    assert report.status == "ok" and report.method == method and report.integrator == "dopri5"
    assert report.initial_conditions == []
    energy = report.invariants["energy"]
    assert float(np.max(np.abs(energy - energy[0]))) < 1e-8
    assert float(report.invariants["constraint_position"].max()) < 1e-8
    lowest = int(np.argmin(report.series["y_m"]))
    assert report.series["multiplier"][lowest] == pytest.approx(3.0, abs=1e-3)  # 240 Hz frames: within ±2 ms of the bottom
    assert np.all(report.series["tension_N"] == report.series["multiplier"])  # L = 1 m


def test_minimal_method_is_the_chapter_7_engine_and_matches_the_closed_form():
    """The engine's θ equation, RK4 at 8 steps/frame over 20 s: within 1e-8 m of the exact bob (measured below 1e-9)."""
    params = CartesianPendulum.parameters.validate(UNIT)
    report = CartesianPendulum().simulate(params, {"method": "minimal", "steps_per_frame": 8}, t_end_s=20.0, frame_rate_hz=30.0)
    states = np.stack([report.series[k] for k in ("x_m", "y_m", "vx_m_s", "vy_m_s")], axis=1)
    exact = exact_states(1.0, 1.0, np.array([1.0, 0.0, 0.0, 0.0]), report.t_s)
    assert float(np.max(np.abs(states - exact))) < 1e-8


def test_inconsistent_start_is_made_consistent_and_reported():
    params = CartesianPendulum.parameters.validate({"x0_m": 1.2, "y0_m": 0.4, "vx0_m_s": 1.0, "vy0_m_s": 1.0})
    report = CartesianPendulum().simulate(params, {}, t_end_s=1.0, frame_rate_hz=30.0)
    changed = {c["name"]: c for c in report.initial_conditions}
    assert set(changed) == {"x0_m", "y0_m", "vx0_m_s", "vy0_m_s"}
    assert changed["x0_m"]["consistent"] == pytest.approx(1.2 / np.hypot(1.2, 0.4), abs=1e-14) and changed["x0_m"]["unit"] == "m"
    assert report.method == "projection"  # auto


def test_start_at_the_pivot_is_refused_by_the_parameters():
    with pytest.raises(ValueError, match="pivot"):
        CartesianPendulum.parameters.validate({"x0_m": 0.0, "y0_m": 0.0})
