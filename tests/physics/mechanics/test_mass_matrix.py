"""The mass matrix ∂²T/∂q̇² found numerically from T, and where a motion meets a singular one (issue 24, Found 12).

References are closed forms: the double pendulum's and the polar particle's mass matrices, and where a straight
segment of (r, θ) crosses r = 0.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.mechanics.mass_matrix import (
    SINGULAR_FALL,
    first_singular_crossing,
    mass_matrices,
    not_positive_definite,
    relative_inertia,
)

RNG = np.random.default_rng(24)


def double_pendulum_kinetic(t, q, qd, p):
    """T of two equal bobs m on equal rods l (q1, q2 from the downward vertical), J."""
    m, l = p
    return m * l**2 * (2 * qd[0] ** 2 + qd[1] ** 2 + 2 * np.cos(q[0] - q[1]) * qd[0] * qd[1]) / 2


def polar_kinetic(t, q, qd, p):
    """T = m (ṙ² + r² θ̇²) / 2 with q = (r, θ), J."""
    (m,) = p
    return m * (qd[0] ** 2 + q[0] ** 2 * qd[1] ** 2) / 2


def test_a_quadratic_kinetic_energy_gives_its_mass_matrix_to_rounding():
    """M = m l² [[2, cos(q1 − q2)], [cos(q1 − q2), 1]], exact in closed form; the differences are exact for a quadratic T,
    so only rounding remains: 1e-12 relative is ~1e4 ulps, the complex step and one subtraction of O(1) numbers."""
    p = np.array([1.3, 0.7])
    q, qd = RNG.uniform(-3, 3, (2, 50)), RNG.uniform(-5, 5, (2, 50))
    matrices = mass_matrices(double_pendulum_kinetic, np.zeros(50), q, qd, p)
    c = np.cos(q[0] - q[1])
    expected = p[0] * p[1] ** 2 * np.stack([np.stack([2 + 0 * c, c], -1), np.stack([c, 1 + 0 * c], -1)], -2)
    np.testing.assert_allclose(matrices, expected, rtol=0, atol=1e-12 * p[0] * p[1] ** 2)


def test_a_kinetic_energy_not_quadratic_in_the_rates_is_second_order_in_the_step():
    """T = cosh(q̇): ∂T/∂q̇ = sinh(q̇) exactly (complex step), and its central difference with h = 1e-3·max(1, |q̇|) is
    cosh(q̇) sinh(h)/h exactly, a relative error of sinh(h)/h − 1 ≈ h²/6 (1.7e-7 to 1.04e-6 here). The computed entries
    equal that to 1e-12 (rounding of the difference of two O(1) numbers over 2h ~ 1e-3: ~1e-13)."""
    kinetic = lambda t, q, qd, p: np.cosh(qd[0])  # noqa: E731
    qd = np.array([[0.3, 1.0, 2.5]])
    h = 1e-3 * np.maximum(1.0, np.abs(qd[0]))
    matrices = mass_matrices(kinetic, np.zeros(3), np.zeros((1, 3)), qd, np.array([]))
    np.testing.assert_allclose(matrices[:, 0, 0], np.cosh(qd[0]) * np.sinh(h) / h, rtol=1e-12)
    assert np.all(np.abs(matrices[:, 0, 0] / np.cosh(qd[0]) - 1.0) <= 1.001 * h**2 / 6)


def test_definiteness_is_named_with_its_rate():
    assert not_positive_definite(np.diag([2.0, 1.0]), ["q1d", "q2d"]) == ("", "")
    kind, why = not_positive_definite(np.diag([2.0, -1.0]), ["q1d", "q2d"])
    assert kind == "negative" and "-1" in why and "q2d" in why
    kind, why = not_positive_definite(np.diag([0.0, 3.0]), ["q1d", "q2d"])
    assert kind == "singular" and "q1d" in why
    assert not_positive_definite(np.array([[np.inf, 0], [0, 1]]), ["q1d", "q2d"])[0] == "not_finite"


def test_relative_inertia_is_the_weakest_direction_against_the_start_whatever_the_units():
    """diag(m, m r²) against r₀ = 1: the weakest direction keeps min(1, r²) of its inertia, however large r is (M's own
    condition number, r² or 1/r², would call r = 10⁵ singular)."""
    start = np.diag([1.0, 1.0])
    r = np.array([1.0, 0.5, 1e-3, 1e5])
    matrices = np.stack([np.diag([1.0, rr**2]) for rr in r])
    np.testing.assert_allclose(relative_inertia(matrices, start), np.minimum(1.0, r**2), rtol=1e-12)


def test_a_straight_path_through_r_zero_is_found_between_two_frames_and_placed_at_r_zero():
    """Frames at r = +0.079 and −0.19 (as the typed Kepler run left them): the conditioning r² is quadratic along the
    segment, so the parabola through the samples finds its zero at r = 0 exactly (to rounding)."""
    start = np.array([1.0, 0.0, 0.0, 0.0])
    frames = np.array([[0.5, 0.0, -1.0, 0.0], [0.079, 0.0, -3.0, 0.0], [-0.19, 0.0, -4.0, 0.0], [-0.8, 0.0, -4.5, 0.0]])
    reference = mass_matrices(polar_kinetic, np.zeros(1), start[:2, None], start[2:, None], np.array([1.0]))[0]
    crossing = first_singular_crossing(polar_kinetic, np.arange(4) / 60, frames, np.array([1.0]), reference=reference)
    assert crossing is not None and crossing.frame == 1
    assert abs(crossing.q[0]) < 1e-12 and crossing.rate_index == 1 and not crossing.indefinite
    assert crossing.inertia <= SINGULAR_FALL


def test_a_frame_that_jumps_far_across_r_zero_is_caught_too():
    """A live RK4 run's frames went from r = 0.079 straight to r = −142.6 (the acceleration −k/r² blew the step up): the
    smallest eigenvalue min(1, r²) is flat at 1 at every sample but the first, while the determinant r² stays quadratic
    in s along the whole segment, so its parabola still finds the zero, at r = 0 (to 1e-9 of the 143 m jump)."""
    frames = np.array([[0.197, 0.0, -2.85, 0.0], [0.079, 0.0, -4.83, 0.0], [-142.6, 0.0, -6417.0, 0.0]])
    crossing = first_singular_crossing(polar_kinetic, np.arange(3) / 30, frames, np.array([1.0]), reference=np.eye(2))
    assert crossing is not None and crossing.frame == 1 and crossing.rate_index == 1
    assert abs(crossing.q[0]) < 1e-9 * 143


def test_a_path_that_passes_the_centre_at_a_distance_is_not_singular():
    """The same frames with θ turning: the straight segment in (r, θ) keeps r ≥ 0.07, so r² ≥ 5e-3 ≫ SINGULAR_FALL."""
    frames = np.array([[0.5, 0.0, -1.0, 1.0], [0.079, 0.5, -3.0, 9.0], [0.07, 1.0, 1.0, 9.0], [0.3, 1.4, 3.0, 2.0]])
    reference = np.diag([1.0, 1.0])
    assert first_singular_crossing(polar_kinetic, np.arange(4) / 60, frames, np.array([1.0]), reference=reference) is None


def test_a_mass_matrix_that_turns_indefinite_is_found():
    """T = (q̇1² + q1 q̇2²)/2: M = diag(1, q1) is indefinite for q1 < 0; a frame at q1 = −0.2 is outside the model."""
    kinetic = lambda t, q, qd, p: (qd[0] ** 2 + q[0] * qd[1] ** 2) / 2  # noqa: E731
    frames = np.array([[1.0, 0.0, -1.0, 0.5], [0.4, 0.1, -1.0, 0.5], [-0.2, 0.2, -1.0, 0.5]])
    crossing = first_singular_crossing(kinetic, np.arange(3) / 60, frames, np.array([]), reference=np.eye(2))
    assert crossing is not None and crossing.frame == 1 and crossing.indefinite and crossing.rate_index == 1
    # The inertia along q2, q1, is linear along the segment: interpolated to its zero between two samples, exactly.
    assert math.isclose(crossing.q[0], 0.0, abs_tol=1e-12)
