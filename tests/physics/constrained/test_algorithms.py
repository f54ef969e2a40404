"""The DAE algorithms on the Cartesian pendulum (vs the elliptic-function exact solution) and on a knife edge.

Reference: the unit pendulum (m = L = g = 1) released from (1, 0) m at rest, whose exact
motion is sin(θ/2) = k sn(t + K | k²), k = sin 45° (scipy.special.ellipj, a closed form).
Tolerances are the measured errors with a margin of about 3–5×, and far below what a wrong
equation gives (a sign error in c or γ is off by order 1 within a period).
"""

from __future__ import annotations

import numpy as np
import pytest

from app.physics.constrained.algorithms import ALGORITHMS, algorithm_system, current_partition, repartition_count
from app.physics.constrained.residuals import constraint_residuals, multipliers
from app.physics.solvers.registry import make_integrator
from app.physics.solvers.solve import simulate
from app.physics.systems.ch08.cartesian_pendulum import exact_states, pendulum_system
from tests.physics.constrained.knife_edge import knife_edge, knife_edge_exact

UNIT_START = np.array([1.0, 0.0, 0.0, 0.0])
FRAME_RATE_HZ = 30.0


def run(algorithm: str, *, t_end_s: float, integrator, alpha: float = 5.0, beta: float = 5.0, system=None, start=UNIT_START):
    system = system or pendulum_system(1.0, 1.0, 1.0)
    n = system.n_coordinates
    ode = algorithm_system(system, algorithm, alpha_1_s=alpha, beta_1_s=beta, q=start[:n])
    return ode, simulate(ode, integrator, start, t_end_s=t_end_s, frame_rate_hz=FRAME_RATE_HZ)


# Max |state − exact| over 20 s (about 2.7 periods) with RK4 at 8 steps/frame (h = 4.2 ms), measured:
# uncorrected 8.2e-9, baumgarte 6.9e-9, projection 3.0e-10, partitioning 1.2e-8 (m and m/s).
RK4_TOLERANCE = {"uncorrected": 5e-8, "baumgarte": 5e-8, "projection": 2e-9, "partitioning": 5e-8}


@pytest.mark.parametrize("algorithm", sorted(ALGORITHMS))
def test_every_algorithm_follows_the_exact_pendulum(algorithm):
    _, result = run(algorithm, t_end_s=20.0, integrator=make_integrator("rk4", steps_per_frame=8))
    assert result.ok
    exact = exact_states(1.0, 1.0, UNIT_START, result.t_s)
    error = float(np.max(np.abs(result.states - exact)))
    assert error < RK4_TOLERANCE[algorithm], f"{algorithm}: {error:.2e}"


@pytest.mark.parametrize("algorithm", sorted(ALGORITHMS))
def test_every_algorithm_with_the_adaptive_integrator(algorithm):
    # dopri5 at rtol 1e-10 over 20 s, measured: uncorrected 2.8e-9, baumgarte 1.5e-10, projection 2.2e-9,
    # partitioning 6.5e-9 (m, m/s). 3e-8 leaves room and stays far below any modelling error.
    _, result = run(algorithm, t_end_s=20.0, integrator=make_integrator("dopri5", rtol=1e-10))
    exact = exact_states(1.0, 1.0, UNIT_START, result.t_s)
    assert float(np.max(np.abs(result.states - exact))) < 3e-8


@pytest.mark.parametrize("algorithm", ["projection", "partitioning"])
def test_adaptive_frames_between_steps_lie_on_the_constraints(algorithm):
    """dopri5's frames come from its interpolant, which leaves the manifold by its own error (measured 2.5e-5 m² and 6e-5 m²/s at
    rtol 1e-4 before frames were projected); projected like a step's end, every frame is on it to round-off."""
    _, result = run(algorithm, t_end_s=20.0, integrator=make_integrator("dopri5", rtol=1e-4))
    position, velocity = constraint_residuals(pendulum_system(1.0, 1.0, 1.0), result.states)
    assert float(position.max()) < 1e-13 and float(velocity.max()) < 1e-13


def test_uncorrected_residual_grows_and_the_others_stay_bounded():
    """Uncorrected: max |g| over 100 s is ≥ 10× that over 10 s (measured 100×: quadratic growth); the others do not grow."""
    integrator = lambda: make_integrator("rk4", steps_per_frame=1)  # noqa: E731 - h = 33 ms, the scene's automatic step
    worst = {}
    for algorithm in ALGORITHMS:
        _, result = run(algorithm, t_end_s=100.0, integrator=integrator())
        position, velocity = constraint_residuals(pendulum_system(1.0, 1.0, 1.0), result.states)
        early = result.t_s <= 10.0
        worst[algorithm] = (float(position[early].max()), float(position.max()), float(velocity.max()))
    early, late, _ = worst["uncorrected"]
    assert late >= 10.0 * early and late > 1e-4  # measured 4.7e-6 → 4.7e-4 m²
    for algorithm in ("projection", "partitioning"):
        assert worst[algorithm][1] < 1e-13 and worst[algorithm][2] < 1e-13  # on the manifold to round-off after every step
    b_early, b_late, b_velocity = worst["baumgarte"]
    assert b_late <= 2.0 * b_early and b_late < 1e-5 and b_velocity < 1e-4  # measured 1e-6 m², 7.6e-6 m²/s, flat after 1 s


def test_baumgarte_with_zero_gains_is_the_uncorrected_method():
    _, zero = run("baumgarte", t_end_s=5.0, integrator=make_integrator("rk4", steps_per_frame=1), alpha=0.0, beta=0.0)
    _, plain = run("uncorrected", t_end_s=5.0, integrator=make_integrator("rk4", steps_per_frame=1))
    np.testing.assert_array_equal(zero.states, plain.states)


def test_baumgarte_gains_too_large_for_the_step_blow_up():
    """α = β = 200/s with h = 33 ms: h·α = 6.7, outside RK4's stability region (|hλ| ≲ 2.8): the run stops, non-finite."""
    _, result = run("baumgarte", t_end_s=10.0, integrator=make_integrator("rk4", steps_per_frame=1), alpha=200.0, beta=200.0)
    assert result.status == "non_finite" and "blew up" in result.message
    assert np.all(np.isfinite(result.states))
    # The same gains with a step 20× smaller (h·α = 0.33) are stable and hold the residual tightly.
    _, fine = run("baumgarte", t_end_s=10.0, integrator=make_integrator("rk4", steps_per_frame=20), alpha=200.0, beta=200.0)
    assert fine.ok
    assert float(constraint_residuals(pendulum_system(1.0, 1.0, 1.0), fine.states)[0].max()) < 3e-8  # measured 8.8e-9 m²


def test_undamped_baumgarte_gain_leaves_the_error_oscillating():
    """α = 0, β = 30/s: ë + β² e = 0 has no damping, so the residual is not driven down: worse than α = β = 5/s."""
    integrator = lambda: make_integrator("rk4", steps_per_frame=1)  # noqa: E731
    system = pendulum_system(1.0, 1.0, 9.81)
    _, undamped = run("baumgarte", t_end_s=30.0, integrator=integrator(), alpha=0.0, beta=30.0, system=system)
    _, damped = run("baumgarte", t_end_s=30.0, integrator=integrator(), alpha=5.0, beta=5.0, system=system)
    worst_undamped = float(constraint_residuals(system, undamped.states)[0].max())
    worst_damped = float(constraint_residuals(system, damped.states)[0].max())
    assert worst_undamped > 10.0 * worst_damped  # measured 2.4e-4 vs 1.2e-5 m²


def test_partitioning_re_chooses_its_dependent_coordinate():
    """From (1, 0) m the dependent coordinate must be x (C = (−1, 0)); near the bottom y; four switches a period (7.42 s)."""
    system = pendulum_system(1.0, 1.0, 1.0)
    ode = algorithm_system(system, "partitioning", q=UNIT_START[:2])
    assert current_partition(ode.parameters, 2, 1) == ((0,), (1,))
    result = simulate(ode, make_integrator("rk4", steps_per_frame=4), UNIT_START, t_end_s=7.42, frame_rate_hz=FRAME_RATE_HZ)
    assert result.ok
    assert 3 <= repartition_count(ode.parameters, 2) <= 5


def test_compiled_kernels_match_their_python_twins():
    system = pendulum_system(1.0, 1.0, 1.0)
    for algorithm in ALGORITHMS:
        states = []
        for backend in ("numba", "python"):
            ode = algorithm_system(system, algorithm, alpha_1_s=5.0, beta_1_s=5.0, q=UNIT_START[:2])
            states.append(simulate(ode, make_integrator("rk4", steps_per_frame=2), UNIT_START, t_end_s=1.0, frame_rate_hz=30.0,
                                   backend=backend).states)  # fmt: skip
        np.testing.assert_allclose(states[0], states[1], rtol=0, atol=1e-13, err_msg=algorithm)


def test_multiplier_is_the_rod_tension_per_length():
    """At the bottom of the unit pendulum's swing from 90°: v² = 2 g L, so T = m g + m v²/L = 3 N and λ = T/L = 3 N/m (> 0: pulls)."""
    system = pendulum_system(1.0, 1.0, 1.0)
    bottom = np.array([[0.0, -1.0, -np.sqrt(2.0), 0.0]])
    np.testing.assert_allclose(multipliers(system, np.zeros(1), bottom), [[3.0]], rtol=1e-14)
    released = np.array([[1.0, 0.0, 0.0, 0.0]])  # at rest, level with the pivot: the rod carries nothing
    np.testing.assert_allclose(multipliers(system, np.zeros(1), released), [[0.0]], atol=1e-15)


@pytest.mark.parametrize("algorithm", sorted(ALGORITHMS))
def test_nonholonomic_knife_edge_draws_its_exact_circle(algorithm):
    """Knife edge from the origin heading φ₀ = 0.3 rad, u = 1.5 m/s, ω = 0.8 rad/s: a circle of radius 1.875 m.

    RK4 at 4 steps/frame (h = 8.3 ms) over 10 s: measured ≤ 8.7e-10 (m, rad, m/s); 5e-9 with margin. The residual
    A v stays at round-off with projection/partitioning and measured ≤ 2.8e-10 m/s with the others (2e-9 allowed).
    """
    system = knife_edge()
    speed, rate, phi0 = 1.5, 0.8, 0.3
    start = knife_edge_exact(speed, rate, phi0, np.zeros(1))[0]
    _, result = run(algorithm, t_end_s=10.0, integrator=make_integrator("rk4", steps_per_frame=4), system=system, start=start)
    assert result.ok
    exact = knife_edge_exact(speed, rate, phi0, result.t_s)
    assert float(np.max(np.abs(result.states - exact))) < 5e-9
    position, velocity = constraint_residuals(system, result.states)
    assert np.all(position == 0.0)  # no holonomic rows
    assert float(velocity.max()) < (1e-13 if algorithm in ("projection", "partitioning") else 2e-9)
