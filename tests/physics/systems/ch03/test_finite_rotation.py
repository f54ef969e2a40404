"""Euler's theorem and the order of finite rotations (app/physics/systems/ch03/finite_rotation.py).

The references are independent: scipy's ``Rotation`` for the sequences, their axis and angle and the
two compositions, and closed forms worked by hand (two quarter turns about perpendicular axes give a
120° turn about a cube diagonal). Tolerances are rounding only (a few ulps of entries of size 1).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from app.physics.math.rotations import SEQUENCES
from app.physics.systems.ch03.finite_rotation import finite_rotation

#: Entries of 3×3 rotation matrices are at most 1: 1e-12 leaves room for a few dozen roundings and no more.
MATRIX_TOL = 1e-12


def scipy_rotation(sequence: str, angles_deg) -> Rotation:
    return Rotation.from_euler("".join("XYZ"[int(a) - 1] for a in sequence.split("-")), angles_deg, degrees=True)


@pytest.mark.parametrize("sequence", list(SEQUENCES))
def test_one_turn_about_n_is_the_sequence(sequence):
    rng = np.random.default_rng(int(sequence.replace("-", "")))
    for _ in range(40):
        angles_deg = rng.uniform(-180.0, 180.0, 3)
        r = finite_rotation(np.radians(angles_deg), sequence, second_axis="X", second_angle_rad=0.3)
        a = r.turn_a
        expected = scipy_rotation(sequence, angles_deg)
        # The matrix product of the three elementary turns (scipy's) and Rodrigues' formula from (n, φ) agree.
        assert np.abs(a.R_world_body - expected.as_matrix()).max() < MATRIX_TOL
        assert r.rodrigues_mismatch < MATRIX_TOL
        # n is left in place, and the trace is 1 + 2 cos φ.
        assert np.abs(a.R_world_body @ a.axis_world - a.axis_world).max() < MATRIX_TOL
        assert np.trace(a.R_world_body) == pytest.approx(1.0 + 2.0 * math.cos(a.angle_rad), abs=MATRIX_TOL)
        assert a.angle_rad == pytest.approx(expected.magnitude(), abs=1e-12)
        if a.angle_rad < math.pi - 1e-6:  # at a half turn ±n are the same axis
            assert np.abs(a.axis_world * a.angle_rad - expected.as_rotvec()).max() < 1e-12
        # The two orders are scipy's compositions (B ∘ A is "A, then B about a fixed axis").
        b = Rotation.from_euler("X", 0.3)
        assert np.abs(r.a_then_b.R_world_body - (b * expected).as_matrix()).max() < MATRIX_TOL
        assert np.abs(r.b_then_a.R_world_body - (expected * b).as_matrix()).max() < MATRIX_TOL


def test_two_quarter_turns_are_a_third_of_a_turn_about_a_diagonal():
    # R_Z(90°) R_X(90°) maps x → y → z → x: a 120° turn about (1, 1, 1)/√3; the other order about (1, −1, 1)/√3.
    r = finite_rotation(np.radians([90.0, 0.0, 0.0]), "1-2-3", second_axis="Z", second_angle_rad=math.pi / 2)
    assert math.degrees(r.a_then_b.angle_rad) == pytest.approx(120.0, abs=1e-12)
    assert math.degrees(r.b_then_a.angle_rad) == pytest.approx(120.0, abs=1e-12)
    assert np.abs(r.a_then_b.axis_world - np.array([1.0, 1.0, 1.0]) / math.sqrt(3.0)).max() < 1e-15 * 100
    assert np.abs(r.b_then_a.axis_world - np.array([1.0, -1.0, 1.0]) / math.sqrt(3.0)).max() < 1e-15 * 100
    # The two results differ by a 120° turn too (the angle between the two cube diagonals' rotations).
    expected_gap = Rotation.from_matrix(r.a_then_b.R_world_body @ r.b_then_a.R_world_body.T).magnitude()
    assert r.order_gap_rad == pytest.approx(expected_gap, abs=1e-12)
    assert math.degrees(r.order_gap_rad) == pytest.approx(120.0, abs=1e-9)


def test_turns_about_one_axis_commute_and_small_turns_nearly_do():
    same = finite_rotation(np.radians([50.0, 0.0, 0.0]), "3-2-1", second_axis="Z", second_angle_rad=math.radians(70.0))
    assert same.order_gap_rad < 1e-15 * 100
    assert math.degrees(same.a_then_b.angle_rad) == pytest.approx(120.0, abs=1e-12)
    # Perpendicular turns a and b: the orders differ by a·b to second order (the commutator), error O(a²b).
    a = b = 0.01
    small = finite_rotation(np.array([a, 0.0, 0.0]), "1-2-3", second_axis="Z", second_angle_rad=b)
    assert small.order_gap_rad / (a * b) == pytest.approx(1.0, rel=2 * a)


def test_bad_input_is_refused_with_its_name():
    with pytest.raises(ValueError, match="second turn axis"):
        finite_rotation(np.zeros(3), "3-1-3", second_axis="W", second_angle_rad=0.1)
    with pytest.raises(ValueError, match="angles_rad"):
        finite_rotation(np.array([0.0, math.nan, 0.0]), "3-1-3", second_axis="X", second_angle_rad=0.1)
    with pytest.raises(ValueError, match="unknown rotation sequence"):
        finite_rotation(np.zeros(3), "3-3-1", second_axis="X", second_angle_rad=0.1)
