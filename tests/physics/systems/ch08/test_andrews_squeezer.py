"""Andrews' squeezing mechanism against finite differences, the test set's initial values and its published reference."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from app.physics.solvers.constraints import constrained_acceleration
from app.physics.systems.ch08.andrews_squeezer import (
    INITIAL_ACCELERATIONS_RAD_S2,
    PUBLISHED_INITIAL_MULTIPLIERS_N,
    REFERENCE_POSITIONS_RAD,
    REFERENCE_RATES_RAD_S,
    REFERENCE_TIME_S,
    AndrewsParameters,
    andrews_initial_state,
    andrews_system,
)

SYSTEM = andrews_system()
RNG = np.random.default_rng(8)
STATES = [(RNG.uniform(-np.pi, np.pi, 7), RNG.uniform(-300.0, 300.0, 7)) for _ in range(5)]


def _g(q: np.ndarray) -> np.ndarray:
    return SYSTEM.constraint_terms(q, np.zeros(7))[0]


def _acceleration_and_multipliers(q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """q̈ (7,) and λ (6,) in the contract's sign (M q̈ = f + Gᵀλ) from the index-1 equations."""
    mass, forces = SYSTEM.mass_and_forces(0.0, q, v)
    _, jacobian, convective = SYSTEM.constraint_terms(q, v)
    acceleration = np.empty(7)
    kkt_multiplier = constrained_acceleration(mass, jacobian, forces, convective, acceleration)  # solves M a + Gᵀμ = f
    return acceleration, -kkt_multiplier


def test_shape_of_the_system() -> None:
    assert SYSTEM.n_coordinates == 7 and SYSTEM.n_holonomic == 6 and SYSTEM.degrees_of_freedom == 1
    assert SYSTEM.parameters.shape == (42,)


@pytest.mark.parametrize("q, v", STATES)
def test_jacobian_is_the_derivative_of_the_loop_closures(q: np.ndarray, v: np.ndarray) -> None:
    # Central differences with h = 1e-6 rad: truncation ~ h²·|g'''| ≤ 1e-12 · 0.04 m and round-off ~ 1e-17 m / 1e-6;
    # 1e-9 m/rad is far above both and far below a wrong entry (the smallest term is ra-sized, ~1e-3 m/rad).
    h = 1e-6
    _, jacobian, _ = SYSTEM.constraint_terms(q, v)
    numeric = np.column_stack([(_g(q + h * e) - _g(q - h * e)) / (2 * h) for e in np.eye(7)])
    np.testing.assert_allclose(jacobian, numeric, atol=1e-9, rtol=0)


@pytest.mark.parametrize("q, v", STATES)
def test_convective_term_is_minus_the_jacobian_rate_times_v(q: np.ndarray, v: np.ndarray) -> None:
    # Ġ v = d/ds [G(q + s v)] v at s = 0, by central differences in s (h = 1e-7 s with |v| ≤ 300 rad/s):
    # truncation ~ (h|v|)²·|v|²·0.04 m ≈ 4e-5 m/s² out of |c| up to ~1e4 m/s², so a relative 1e-7 of the largest entry.
    h = 1e-7
    _, _, convective = SYSTEM.constraint_terms(q, v)
    plus = SYSTEM.constraint_terms(q + h * v, v)[1]
    minus = SYSTEM.constraint_terms(q - h * v, v)[1]
    numeric = -((plus - minus) / (2 * h)) @ v
    np.testing.assert_allclose(convective, numeric, atol=1e-7 * np.abs(numeric).max(), rtol=0)


def test_published_initial_values_are_consistent_to_round_off() -> None:
    q0, v0 = andrews_initial_state()
    g0, jacobian, _ = SYSTEM.constraint_terms(q0, v0)
    # The residuals are differences of terms up to 0.07 m, whose spacing of doubles is 1.4e-17 m: allow a few of those.
    assert np.abs(g0).max() <= 1e-16
    assert np.abs(jacobian @ v0).max() == 0.0
    acceleration, multipliers = _acceleration_and_multipliers(q0, v0)
    # The test set gives q̈(0) and λ(0) to 30 digits; a 13×13 solve with condition ~1e5 keeps about 10 of them.
    np.testing.assert_allclose(acceleration, INITIAL_ACCELERATIONS_RAD_S2, rtol=1e-9, atol=1e-9 * 14222.0)
    np.testing.assert_allclose(multipliers, -PUBLISHED_INITIAL_MULTIPLIERS_N, rtol=1e-9, atol=1e-9 * 98.6)


def test_tight_integration_reproduces_the_published_reference_at_30_ms() -> None:
    """Index-1 equations with DOP853 at rtol 1e-10: β turns 2.5 revolutions, the spring and motor do work."""
    params = AndrewsParameters()
    q0, v0 = andrews_initial_state()

    def rhs(_t: float, y: np.ndarray) -> np.ndarray:
        acceleration, _ = _acceleration_and_multipliers(y[:7], y[7:])
        return np.concatenate([y[7:], acceleration])

    solution = solve_ivp(rhs, (0.0, REFERENCE_TIME_S), np.concatenate([q0, v0]), method="DOP853", rtol=1e-10, atol=1e-12)
    assert solution.success
    q, v = solution.y[:7, -1], solution.y[7:, -1]
    # Measured: 1.6e-9 rad and 6e-7 rad/s from the reference, unchanged at rtol 1e-12 and 1e-13 (so that is the published
    # values' own accuracy, ~1e-10 of |β| = 15.8 rad). 1e-8 rad / 5e-6 rad/s leave a factor 6–8 and would catch any
    # wrong term: a 1 % change in one mass moves β(0.03 s) by ~1e-2 rad.
    np.testing.assert_allclose(q, REFERENCE_POSITIONS_RAD, rtol=0, atol=1e-8)
    np.testing.assert_allclose(v, REFERENCE_RATES_RAD_S, rtol=0, atol=5e-6)
    # Work–energy: T + V_spring − mom·β is constant (the constraint forces do no work on a consistent motion).
    assert np.abs(SYSTEM.constraint_terms(q, v)[0]).max() < 1e-11

    def energy_minus_work(q: np.ndarray, v: np.ndarray) -> float:
        mass, _ = SYSTEM.mass_and_forces(0.0, q, v)
        x_d = params.sd_m * np.cos(q[2]) + params.sc_m * np.sin(q[2]) + params.xb_m
        y_d = params.sd_m * np.sin(q[2]) - params.sc_m * np.cos(q[2]) + params.yb_m
        stretch = np.hypot(x_d - params.xc_m, y_d - params.yc_m) - params.l0_m
        return 0.5 * v @ mass @ v + 0.5 * params.c0_N_m * stretch**2 - params.mom_N_m * q[0]

    work_done_J = params.mom_N_m * (q[0] - q0[0])  # 0.52 J; the integration error is ~1e-10 of it
    assert abs(energy_minus_work(q, v) - energy_minus_work(q0, v0)) < 1e-8 * work_done_J


def test_parameters_are_checked_by_name() -> None:
    with pytest.raises(ValueError, match="m3_kg"):
        AndrewsParameters(m3_kg=0.0)
    with pytest.raises(ValueError, match="c0_N_m"):
        AndrewsParameters(c0_N_m=-1.0)
    with pytest.raises(ValueError, match="mom_N_m"):
        AndrewsParameters(mom_N_m=float("nan"))
