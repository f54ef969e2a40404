"""Consistent initial conditions: least change onto the constraints, what changed, and refusals with reasons."""

from __future__ import annotations

import numpy as np
import pytest

from app.physics.constrained.initial_conditions import consistent_initial_conditions
from app.physics.systems.ch08.cartesian_pendulum import pendulum_system
from tests.physics.constrained.knife_edge import knife_edge

PENDULUM = pendulum_system(1.0, 1.0, 9.81)


def test_off_circle_start_moves_radially_and_keeps_the_tangential_velocity():
    """Closest point of the circle to (1.2, 0.4) is along the ray; the velocity loses only its radial part (closed forms)."""
    q0, v0 = np.array([1.2, 0.4]), np.array([1.0, 1.0])
    start = consistent_initial_conditions(PENDULUM, q0, v0, names=("x0_m", "y0_m", "vx0_m_s", "vy0_m_s"), units=("m", "m", "m/s", "m/s"))
    radial = q0 / np.linalg.norm(q0)
    np.testing.assert_allclose(start.q, radial, atol=1e-14)
    np.testing.assert_allclose(start.v, v0 - (v0 @ radial) * radial, atol=1e-14)
    assert start.position_residual < 1e-15 and start.velocity_residual < 1e-15
    assert [c.name for c in start.changes] == ["x0_m", "y0_m", "vx0_m_s", "vy0_m_s"]
    assert start.changes[0].unit == "m" and start.changes[0].change == pytest.approx(radial[0] - 1.2, abs=1e-14)
    assert "x0_m 1.2 → 0.948683 m" in start.summary()


def test_fixed_coordinate_is_kept_and_only_the_free_one_moves():
    """x fixed at 0.6 m: y goes from −0.5 to the nearer root −0.8 m of x² + y² = 1."""
    start = consistent_initial_conditions(PENDULUM, [0.6, -0.5], [0.0, 0.0], fixed_positions=(0,))
    np.testing.assert_allclose(start.q, [0.6, -0.8], atol=1e-14)
    assert [c.name for c in start.changes] == ["y"]


def test_consistent_request_changes_nothing():
    start = consistent_initial_conditions(PENDULUM, [0.8, -0.6], [0.6, 0.8])
    assert not start.changed and start.summary() == "the start satisfies the constraints as requested"


@pytest.mark.parametrize(
    ("q0", "fixed", "reason"),
    [
        ([0.0, 0.0], (), "rows are dependent"),  # the bob at the pivot: every direction is tangent
        ([0.5, 0.5], (0, 1), "only 0 free coordinates"),  # both fixed: over-determined
        ([1.5, 0.3], (0,), "cannot reach"),  # x fixed beyond the rod's reach: unreachable
    ],
)
def test_impossible_requests_are_refused_with_the_reason(q0, fixed, reason):
    with pytest.raises(ValueError, match=reason):
        consistent_initial_conditions(PENDULUM, q0, [0.0, 0.0], fixed_positions=fixed)


def test_nonholonomic_row_removes_the_sideways_velocity():
    """Knife edge heading φ = 0: a sideways ẏ = 0.5 m/s is removed, ẋ and φ̇ kept (minimum change)."""
    start = consistent_initial_conditions(knife_edge(), [0.0, 0.0, 0.0], [1.0, 0.5, 0.2])
    np.testing.assert_allclose(start.v, [1.0, 0.0, 0.2], atol=1e-15)
    assert [c.name for c in start.changes] == ["y_rate"]


def test_fixed_velocity_that_breaks_the_constraint_is_refused():
    with pytest.raises(ValueError, match="velocities"):
        consistent_initial_conditions(knife_edge(), [0.0, 0.0, 0.0], [1.0, 0.5, 0.2], fixed_velocities=(1,))


@pytest.mark.parametrize("radius_in_lengths", [0.01, 0.5, 1.9, 2.1, 5.0, 40.0, 280.0])
@pytest.mark.parametrize("angle_deg", [-143.0, -36.87, 0.0, 17.0, 90.0, 171.0])
def test_a_start_far_from_the_rod_moves_radially_at_any_distance(radius_in_lengths, angle_deg):
    """Helper session's report, fixed: a bob asked for more than two rod lengths from the pivot was refused (the
    Gauss–Newton iteration without the constraint's curvature grows its own round-off by λκ = r/L − 1 a step along
    the circle). The scene allows 10 m with a 0.05 m rod (280 lengths). The nearest point is on the ray (closed form),
    to 1e-13 of the rod's length."""
    angle = np.radians(angle_deg)
    q0 = radius_in_lengths * np.array([np.cos(angle), np.sin(angle)])
    start = consistent_initial_conditions(PENDULUM, q0, [0.0, 0.0])
    np.testing.assert_allclose(start.q, [np.cos(angle), np.sin(angle)], atol=1e-13)
    assert start.position_residual < 1e-13


class _Ellipse:
    """A bead on the ellipse (x/a)² + y² = 1, as far as the initial-conditions solver reads a system."""

    semi_x = 2.0
    coordinate_names = ("x", "y")
    n_coordinates, n_holonomic, n_constraints = 2, 1, 1

    def constraint_terms(self, q, v):
        x, y = q
        g = np.array([0.5 * ((x / self.semi_x) ** 2 + y**2 - 1.0)])
        return g, np.array([[x / self.semi_x**2, y]]), np.array([v[0] ** 2 / self.semi_x**2 + v[1] ** 2])


def test_the_nearest_point_of_a_curved_constraint_is_found_where_it_is_not_on_a_ray():
    """A bead on the ellipse (x/2)² + y² = 1 asked to start at (3, 2.5), far outside: the nearest point, from a
    brute-force search over the ellipse's parameter (scipy's bounded scalar minimiser to 1e-12 in the parameter, so
    about 2e-12 m), is not where the ray from the centre crosses the ellipse."""
    from scipy.optimize import minimize_scalar

    ellipse, q0 = _Ellipse(), np.array([3.0, 2.5])
    best = minimize_scalar(
        lambda t: (ellipse.semi_x * np.cos(t) - q0[0]) ** 2 + (np.sin(t) - q0[1]) ** 2,
        bounds=(0.0, np.pi / 2),
        method="bounded",
        options={"xatol": 1e-12},
    )
    nearest = np.array([ellipse.semi_x * np.cos(best.x), np.sin(best.x)])
    start = consistent_initial_conditions(ellipse, q0, [0.0, 0.0])
    np.testing.assert_allclose(start.q, nearest, atol=1e-9)
    on_ray = q0 / np.hypot(q0[0] / ellipse.semi_x, q0[1])
    assert np.max(np.abs(start.q - on_ray)) > 0.05  # not the naive answer
