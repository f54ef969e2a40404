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
