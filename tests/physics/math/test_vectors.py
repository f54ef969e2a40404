"""Vector helpers (app/physics/vectors.py) against hand-worked and algebraic identities."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.physics.math.vectors import force_moment_about_axis, moment_about_point, unit_vector

finite = st.floats(-100.0, 100.0, allow_nan=False, allow_infinity=False)
vec3 = st.tuples(finite, finite, finite).map(np.array)


def test_unit_vector_of_3_4_12():
    # |(3, 4, 12)| = 13 exactly, so the unit vector is (3, 4, 12)/13; 1e-15 absolute: one rounding.
    np.testing.assert_allclose(unit_vector([3.0, 4.0, 12.0]), np.array([3.0, 4.0, 12.0]) / 13.0, rtol=0, atol=1e-15)


def test_unit_vector_of_zero_raises():
    with pytest.raises(ValueError, match="zero-length"):
        unit_vector(np.zeros(3))


def test_moment_of_a_hand_worked_case():
    # F = 10 j at (2, 0, 0), taken about (0, 0, 0): M = 2 i x 10 j = 20 k (exact in binary).
    M = moment_about_point(np.array([2.0, 0.0, 0.0]), np.array([0.0, 10.0, 0.0]), np.zeros(3))
    assert M.tolist() == [0.0, 0.0, 20.0]
    # About the z axis it is +20 N·m, about -z it is -20 N·m (right-hand rule).
    assert force_moment_about_axis([2.0, 0, 0], [0, 10.0, 0], np.zeros(3), [0, 0, 5.0]) == 20.0
    assert force_moment_about_axis([2.0, 0, 0], [0, 10.0, 0], np.zeros(3), [0, 0, -1.0]) == -20.0


@settings(max_examples=60, deadline=None)
@given(vec3, vec3, vec3, st.floats(-50.0, 50.0))
def test_moment_does_not_depend_on_where_on_the_line_of_action(point, force, about, slide):
    # Sliding the point of application along F adds slide*F x F = 0 to the moment.
    # Tolerance: 1e-12 of the scale |r||F| (products of numbers up to ~1e4 in double precision).
    M1 = moment_about_point(point, force, about)
    M2 = moment_about_point(point + slide * force, force, about)
    scale = (np.linalg.norm(point - about) + abs(slide) * np.linalg.norm(force) + 1.0) * (np.linalg.norm(force) + 1.0)
    np.testing.assert_allclose(M1, M2, rtol=0, atol=1e-12 * scale)


@settings(max_examples=60, deadline=None)
@given(vec3, vec3, vec3, vec3)
def test_force_moment_about_axis_is_a_scalar_triple_product(point, force, axis_point, axis_direction):
    # Independent formula: det[e, r, F] with e = direction/|direction|, r = point - axis_point.
    norm = np.linalg.norm(axis_direction)
    if norm < 1e-6:
        return
    e = axis_direction / norm
    with np.errstate(divide="ignore", invalid="ignore"):  # LU of a singular matrix warns
        expected = np.linalg.det(np.array([e, point - axis_point, force]))
    got = force_moment_about_axis(point, force, axis_point, axis_direction)
    # 1e-11 of |r||F|: det by LU and cross-then-dot differ by a few roundings of that size.
    scale = (np.linalg.norm(point - axis_point) + 1.0) * (np.linalg.norm(force) + 1.0)
    assert abs(got - expected) <= 1e-11 * scale
