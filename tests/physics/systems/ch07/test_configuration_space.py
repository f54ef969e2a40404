"""Constraints in configuration space: virtual against actual displacements, and the knife edge's non-integrability."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch07 import configuration_space as cs

times = st.floats(0.0, 20.0)
phases = st.floats(-math.pi, math.pi)


@settings(max_examples=60, deadline=None)
@given(t=times, phase=phases, a=st.floats(0.3, 3.0), b=st.floats(0.3, 3.0), rate=st.floats(-3.0, 3.0))
def test_fixed_ellipse_virtual_and_actual_displacements_are_both_tangent(t, phase, a, b, rate):
    snap = cs.FixedEllipse(a, b, rate).snapshot(t, phase_rad=phase)
    # Every term is O(1/m · m) with a, b ≥ 0.3 m: round-off is ~1e-15, so 1e-12 is a wide margin.
    assert abs(snap.constraint_value) < 1e-12
    assert abs(snap.virtual_variation) < 1e-12
    assert snap.time_rate == 0.0
    assert abs(snap.gradient_along_velocity) < 1e-12 and abs(snap.actual_variation) < 1e-12
    if abs(rate) > 1e-6:
        # Scleronomic: the actual velocity lies along the virtual displacement (angle 0° or 180°).
        assert min(snap.angle_between_deg, 180.0 - snap.angle_between_deg) < 1e-5


@settings(max_examples=60, deadline=None)
@given(t=times, phase=phases, radius=st.floats(0.3, 2.0), amplitude=st.floats(-1.5, 1.5), centre_rate=st.floats(-3.0, 3.0), rate=st.floats(-3.0, 3.0))
def test_sliding_hoop_virtual_displacement_is_tangent_at_frozen_time_and_actual_one_obeys_the_full_variation(
    t, phase, radius, amplitude, centre_rate, rate
):
    hoop = cs.SlidingHoop(radius, amplitude, centre_rate, rate)
    snap = hoop.snapshot(t, phase_rad=phase)
    # Terms are at most |∇g||ṙ| ≤ (2/R)(|A Ω| + R|ω|) ≈ 40 1/s here; round-off ~1e-14, so 1e-12.
    assert abs(snap.constraint_value) < 1e-12
    assert abs(snap.virtual_variation) < 1e-12  # ∇g·δr = 0 at frozen t
    assert abs(snap.actual_variation) < 1e-12  # ∇g·dr + ∂g/∂t dt = 0
    # ∇g·ṙ alone is −∂g/∂t = 2 cos φ · A Ω cos Ωt / R: not zero while the hoop moves.
    phi = phase + rate * t
    assert snap.gradient_along_velocity == pytest.approx(2.0 * math.cos(phi) * amplitude * centre_rate * math.cos(centre_rate * t) / radius, abs=1e-12)


def test_sliding_hoop_velocity_and_time_rate_agree_with_finite_differences():
    """Independent of the closed-form derivatives: central differences of the position and of g at a fixed point.

    Step 1e-5 s: truncation ~h²|r'''| ≈ 1e-10 and round-off ~1e-16/1e-5 = 1e-11, so 1e-8 is safe.
    """
    hoop, t, h = cs.SlidingHoop(1.0, 0.8, 1.5, 0.5), 0.9, 1e-5
    snap = hoop.snapshot(t, phase_rad=0.4)
    rate = (hoop.snapshot(t + h, phase_rad=0.4).position - hoop.snapshot(t - h, phase_rad=0.4).position) / (2 * h)
    assert np.allclose(snap.velocity, rate, atol=1e-8)
    g_rate = (hoop.constraint(snap.position, t + h) - hoop.constraint(snap.position, t - h)) / (2 * h)
    assert snap.time_rate == pytest.approx(g_rate, abs=1e-8)
    assert abs(snap.time_rate) > 0.1  # the case is a real test: the hoop's motion changes g at this point
    assert 20.0 < snap.angle_between_deg < 160.0  # dr is visibly not along δr


def test_a_resting_hoop_is_scleronomic_again():
    snap = cs.SlidingHoop(1.0, 0.0, 1.5, 0.7).snapshot(2.0)
    assert snap.time_rate == 0.0 and abs(snap.gradient_along_velocity) < 1e-15
    assert snap.angle_between_deg == pytest.approx(0.0, abs=1e-6)


@pytest.mark.parametrize("q", [np.array([0.0, 0.0, 0.0]), np.array([1.3, -0.4, 2.1]), np.array([-2.0, 0.5, -0.8])])
def test_knife_edge_fields_are_admissible_and_their_bracket_leaves_the_plane(q):
    a = cs.knife_edge_covector(q)
    assert abs(a @ cs.drive_field(q)) < 1e-15 and abs(a @ cs.turn_field(q)) < 1e-15
    numeric = cs.lie_bracket(cs.drive_field, cs.turn_field, q)
    # Central differences with step 1e-6 rad: truncation step²/6 ≈ 2e-13, round-off 1e-16/1e-6 = 1e-10.
    assert np.allclose(numeric, cs.drive_turn_bracket(q), atol=1e-9)
    assert cs.bracket_leaves_the_plane(q) == pytest.approx(1.0, abs=1e-15)
    assert abs(a @ numeric) == pytest.approx(1.0, abs=1e-9)  # Frobenius fails: not integrable


def test_frobenius_test_tells_an_integrable_constraint_apart():
    """The same bracket routine on a holonomic case (ẏ = 0: fields x̂ and ψ̂) gives zero: the plane is involutive."""
    along_x = lambda q: np.array([1.0, 0.0, 0.0])  # noqa: E731
    turning = lambda q: np.array([0.0, 0.0, 1.0])  # noqa: E731
    assert np.allclose(cs.lie_bracket(along_x, turning, np.array([0.3, 0.2, 1.0])), 0.0, atol=1e-12)


@pytest.mark.parametrize("heading", [0.0, 0.7, -2.5])
def test_parallel_parking_path_obeys_the_constraint_and_ends_where_the_closed_form_says(heading):
    park = cs.ParallelParking(0.6, math.radians(25.0))
    start = np.array([0.2, -0.1, heading])
    for progress in np.linspace(0.0, 4.0, 81):
        q, velocity = park.configuration(start, progress)
        assert abs(cs.knife_edge_covector(q) @ velocity) < 1e-15  # no sideways slip on any leg
    end, _ = park.configuration(start, 4.0)
    # Four exact legs against the trigonometric net motion: round-off only (~1e-16 m), so 1e-13 m.
    assert np.allclose(end - start, park.net_displacement(heading), atol=1e-13)
    right = np.array([math.sin(heading), -math.cos(heading)])
    assert (end - start)[:2] @ right == pytest.approx(park.sideways_drift_m, abs=1e-13)
    assert (end - start)[:2] @ cs.drive_field(start)[:2] == pytest.approx(park.forward_drift_m, abs=1e-13)


def test_parallel_parking_matches_an_independent_integration_of_the_constrained_motion():
    """solve_ivp on q̇ = u₁ drive(q) + u₂ turn(q), leg by leg, at rtol 1e-12: agrees to 1e-9 m with the closed form."""
    park, start = cs.ParallelParking(0.8, 0.5), np.array([0.0, 0.0, 0.3])
    q = start.copy()
    for leg in range(4):
        drive, turn = cs.MANOEUVRE_LEGS[leg]

        def rhs(_t, y, drive=drive, turn=turn):
            return drive * park.drive_distance_m * cs.drive_field(y) + turn * park.turn_angle_rad * cs.turn_field(y)

        q = solve_ivp(rhs, (0.0, 1.0), q, method="DOP853", rtol=1e-12, atol=1e-14).y[:, -1]
    assert np.allclose(q - start, park.net_displacement(0.3), atol=1e-9)


def test_net_sideways_motion_is_epsilon_squared_times_the_bracket():
    """With s = L ε and α = ε the net motion is ε² L [drive, turn] + O(ε³): the remainder s(1 − cos α, sin α − α)
    is at most L ε³/2 + L ε⁴/6, and halving ε divides it by 8 (third order), within 2 %."""
    length, heading = 1.5, 0.4
    remainders = []
    for eps in (0.1, 0.05, 0.025):
        park = cs.ParallelParking(length * eps, eps)
        net = park.net_displacement(heading)
        leading = park.leading_order_displacement(heading)
        assert np.allclose(leading, eps**2 * length * cs.drive_turn_bracket(np.array([0.0, 0.0, heading])), atol=1e-15)
        remainder = float(np.linalg.norm(net - leading))
        assert remainder <= length * eps**3 / 2 + length * eps**4 / 6
        assert park.sideways_drift_m == pytest.approx(length * eps**2, rel=eps**2 / 6 + 1e-12)  # sin ε = ε(1 − ε²/6 + …)
        remainders.append(remainder)
    assert remainders[0] / remainders[1] == pytest.approx(8.0, rel=0.02)
    assert remainders[1] / remainders[2] == pytest.approx(8.0, rel=0.02)


def test_bad_inputs_name_their_field():
    with pytest.raises(ParameterError, match="semi_axis_b_m"):
        cs.FixedEllipse(1.0, 0.0, 1.0)
    with pytest.raises(ParameterError, match="hoop_radius_m"):
        cs.SlidingHoop(-1.0, 0.5, 1.0, 1.0)
    with pytest.raises(ParameterError, match="drive_distance_m"):
        cs.ParallelParking(0.0, 0.3)
    with pytest.raises(ParameterError, match="turn_angle_deg"):
        cs.ParallelParking(0.5, math.nan)
    with pytest.raises(ValueError, match="progress"):
        cs.ParallelParking(0.5, 0.3).configuration(np.zeros(3), 4.5)
