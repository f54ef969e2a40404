"""Constraints (app/physics/solvers/constraints.py): a planar pendulum in Cartesian coordinates.

State (x, y, vx, vy) of a point mass m on a massless rod of length L from the
origin, +y up; constraint g = x² + y² − L², G = [2x, 2y]. The right-hand side
solves [M Gᵀ; G 0][a; λ] = [f; −Ġv − 2α ġ − β² g] (shared helper). The
reference is the angle-coordinate pendulum θ'' = −(g/L) sin θ by scipy's DOP853
at rtol = atol = 1e-12.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from app.physics.solvers import Constraints, OdeSystem, make_integrator, simulate
from app.physics.solvers.constraints import baumgarte_target, constrained_acceleration
from app.physics.solvers.kernels import CONSTRAINT_SIGNATURE, RHS_SIGNATURE, kernel

MASS_KG, G_M_S2, LENGTH_M, THETA0_RAD = 1.0, 9.81, 1.0, 1.0
T_END_S, RATE_HZ = 10.0, 60.0


@kernel(RHS_SIGNATURE)
def cartesian_pendulum_rhs(t, y, p, dydt):
    """p = [m (kg), g (m/s²), L (m), α (1/s), β (1/s)]; Lagrange multiplier keeps G a = γ."""
    m, g, L = p[0], p[1], p[2]
    M = np.zeros((2, 2))
    M[0, 0] = m
    M[1, 1] = m
    G = np.empty((1, 2))
    G[0, 0] = 2.0 * y[0]
    G[0, 1] = 2.0 * y[1]
    force = np.array([0.0, -m * g])
    residual = np.array([y[0] * y[0] + y[1] * y[1] - L * L])
    rate = np.array([2.0 * (y[0] * y[2] + y[1] * y[3])])
    gdot_v = np.array([2.0 * (y[2] * y[2] + y[3] * y[3])])
    gamma = np.empty(1)
    baumgarte_target(gdot_v, residual, rate, p[3], p[4], gamma)
    acceleration = np.empty(2)
    constrained_acceleration(M, G, force, gamma, acceleration)
    dydt[0] = y[2]
    dydt[1] = y[3]
    dydt[2] = acceleration[0]
    dydt[3] = acceleration[1]


@kernel(CONSTRAINT_SIGNATURE)
def rod_length(y, p, g_out, G_out):
    """x² + y² − L² (m²) and its gradient [2x, 2y] (m)."""
    g_out[0] = y[0] * y[0] + y[1] * y[1] - p[2] * p[2]
    G_out[0, 0] = 2.0 * y[0]
    G_out[0, 1] = 2.0 * y[1]


def pendulum(*, project: bool, alpha: float = 0.0, beta: float = 0.0) -> OdeSystem:
    return OdeSystem(
        rhs=cartesian_pendulum_rhs, parameters=np.array([MASS_KG, G_M_S2, LENGTH_M, alpha, beta]),
        state_names=("x_m", "y_m", "vx_m_s", "vy_m_s"),
        constraints=Constraints(rod_length, n_constraints=1, n_positions=2, project=project),
    )


Y0 = np.array([LENGTH_M * math.sin(THETA0_RAD), -LENGTH_M * math.cos(THETA0_RAD), 0.0, 0.0])


@pytest.fixture(scope="module")
def reference_angle():
    t = np.arange(int(T_END_S * RATE_HZ) + 1) / RATE_HZ
    sol = solve_ivp(lambda _t, s: [s[1], -G_M_S2 / LENGTH_M * math.sin(s[0])], (0.0, T_END_S), [THETA0_RAD, 0.0],
                    method="DOP853", rtol=1e-12, atol=1e-12, t_eval=t)
    assert sol.success
    return sol.y[0]


def residual(system: OdeSystem, states: np.ndarray) -> float:
    return float(np.max(np.abs(system.constraints.residuals(states, system.parameters))))


def run(system: OdeSystem, method: str = "rk4", steps_per_frame: int = 4):
    kwargs = {"rtol": 1e-9} if method == "dopri5" else {"steps_per_frame": steps_per_frame}
    result = simulate(system, make_integrator(method, **kwargs), Y0, t_end_s=T_END_S, frame_rate_hz=RATE_HZ)
    assert result.status == "ok"
    return result


@pytest.mark.parametrize("method", ["rk4", "dopri5"])
def test_projection_holds_the_constraint_at_round_off_and_the_motion_is_the_pendulum(method, reference_angle):
    system = pendulum(project=True)
    result = run(system, method)
    if method == "rk4":
        # Every frame is a projected step end. |g| in m² on an L² = 1 m² constraint: a few ulp
        # (observed ≤ 2.3e-16); bound 1e-14. The normal velocity G v is projected to zero too.
        assert residual(system, result.states) <= 1e-14
        normal_speed = np.abs(np.sum(result.states[:, :2] * result.states[:, 2:], axis=1)) / LENGTH_M
        assert normal_speed.max() <= 1e-13
    else:
        # Step ends are projected, but frames inside a step come from the dense-output polynomial,
        # which is accurate to ~rtol: observed 5.2e-10 m² at rtol 1e-9; bound 1e-8 (10 × rtol).
        assert residual(system, result.states) <= 1e-8
    theta = np.arctan2(result.states[:, 0], -result.states[:, 1])
    # h·ω = 3.1/240 ≈ 0.013 for rk4 (observed error 1.1e-8 rad), rtol 1e-9 for dopri5 (observed 1.4e-8 rad) over
    # 10 s (~6 periods); 1e-6 rad still catches a wrong multiplier (which changes the period at once).
    assert np.max(np.abs(theta - reference_angle)) <= 1e-6


def test_without_projection_the_residual_drifts():
    # Index reduction alone (α = β = 0) only holds g̈ = 0: integration errors in g and ġ grow.
    projected, free = pendulum(project=True), pendulum(project=False)
    drift = residual(free, run(free, steps_per_frame=2).states)
    held = residual(projected, run(projected, steps_per_frame=2).states)
    # Observed drift 8.8e-6 m² (growing from 8e-8 in the first second) against 2.2e-16 projected:
    # demanding > 1e-8 (10⁶ × the projected bound) shows that the projection holds the constraint.
    assert held <= 1e-14
    assert drift > 1e-8, drift


def test_baumgarte_keeps_the_residual_bounded():
    free = pendulum(project=False)
    stabilised = pendulum(project=False, alpha=5.0, beta=5.0)
    drift = residual(free, run(free, steps_per_frame=2).states)
    states = run(stabilised, steps_per_frame=2).states
    bounded = residual(stabilised, states)
    # Critically damped constraint dynamics (α = β = 5 1/s): the residual is pulled back each step
    # instead of accumulating; observed 4.5e-8 m² (first second) and 4.3e-8 m² (last) vs 8.8e-6 m² free.
    # Demand 20× smaller than the drift and no growth: the last second is no worse than twice the first.
    assert bounded < drift / 20.0, (bounded, drift)
    per_frame = np.abs(stabilised.constraints.residuals(states, stabilised.parameters))[:, 0]
    assert per_frame[-60:].max() <= 2.0 * per_frame[:60].max() + 1e-15


def test_splitting_refuses_a_constrained_system():
    with pytest.raises(ValueError, match="splitting4 needs a rigid body"):
        run(pendulum(project=True), "splitting4")


def test_constraint_declaration_is_checked():
    with pytest.raises(ValueError, match="over-determine"):
        Constraints(rod_length, n_constraints=3, n_positions=2)
    with pytest.raises(ValueError, match="state slots"):
        dataclasses.replace(pendulum(project=True), state_names=("x_m", "y_m", "vx_m_s"))
