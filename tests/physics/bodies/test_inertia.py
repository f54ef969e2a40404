"""The inertia home: primitives against quadrature of the definitions, transformations, principal axes, refusals."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.physics.bodies import inertia
from app.physics.bodies.composite import SHAPES
from app.physics.math.rotations import matrix_from_angles
from tests.physics.bodies.quadrature import mass_properties, sample

DIMENSIONS = {
    "sphere": {"radius_m": 0.3},
    "spherical-shell": {"radius_m": 0.3},
    "cylinder": {"radius_m": 0.2, "length_m": 0.7},
    "tube": {"radius_m": 0.2, "inner_radius_m": 0.15, "length_m": 0.7},
    "box": {"length_m": 0.5, "width_m": 0.3, "height_m": 0.2},
    "rod": {"length_m": 1.2},
    "plate": {"length_m": 0.6, "width_m": 0.25},
    "disk": {"radius_m": 0.4},
    "cone": {"radius_m": 0.25, "height_m": 0.8},
}


@pytest.mark.parametrize("shape", list(SHAPES))
def test_primitive_tensor_matches_quadrature_of_the_definition(shape):
    """Closed form vs ∫(|r|²1 − r rᵀ) dm by 24-point Gauss–Legendre per coordinate: agree to 1e-12 relative.

    The quadrature also confirms each shape's measure (so a hole's density is
    computed right) and that its own origin is its centre of mass (the cone's
    lies a quarter of the height above the base).
    """
    spec = SHAPES[shape]
    dims = DIMENSIONS[shape]
    mass = 2.5
    points, weights = sample(shape, **dims)
    measure = float(np.sum(weights))
    assert measure == pytest.approx(spec.measure(*(dims[n] for n in spec.dimensions)), rel=1e-12)
    m, centre, tensor_quadrature = mass_properties(points, weights * mass / measure)
    assert m == pytest.approx(mass, rel=1e-13)
    assert np.max(np.abs(centre)) < 1e-13 * max(dims.values())
    tensor = spec.tensor(mass, *(dims[n] for n in spec.dimensions))
    scale = np.max(np.abs(tensor_quadrature))
    assert np.max(np.abs(tensor - tensor_quadrature)) < 1e-12 * scale


def test_cone_tensor_also_agrees_with_monte_carlo_over_its_volume():
    """Rejection sampling in the bounding box with the shape's own ``contains``: 2¹⁸ quasi-random points.

    A second, cruder witness (and a check of the cone's containment test). The
    sample error of a Sobol' estimate here is below 1e-3 relative; 3e-3 is allowed.
    """
    from scipy.stats import qmc

    spec = SHAPES["cone"]
    r, h = 0.25, 0.8
    u = qmc.Sobol(3, seed=7).random_base2(18)
    points = np.column_stack([(2 * u[:, 0] - 1) * r, (2 * u[:, 1] - 1) * r, -h / 4 + u[:, 2] * h])
    inside = points[spec.contains(points, r, h, 0.0)]
    assert len(inside) / len(points) == pytest.approx(math.pi / 12, rel=3e-3)  # volume fraction π r² h/3 ÷ (2r)² h
    _, centre, tensor = mass_properties(inside, np.full(len(inside), 1.0 / len(inside)))
    assert np.max(np.abs(centre)) < 3e-3 * h
    closed = inertia.solid_cone(1.0, r, h)
    assert np.max(np.abs(tensor - closed)) < 3e-3 * np.max(closed)


def test_products_of_inertia_carry_the_stated_sign():
    """A point mass at (x, y) = (1, 2) m: I_xy = ∫ x y dm = 2 kg·m², so the tensor entry is −2."""
    tensor = inertia.parallel_axis(np.zeros((3, 3)), 1.0, np.array([1.0, 2.0, 0.0]))
    assert tensor[0, 1] == tensor[1, 0] == -2.0
    assert tensor[0, 0] == 4.0 and tensor[1, 1] == 1.0 and tensor[2, 2] == 5.0


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.floats(-math.pi, math.pi), min_size=3, max_size=3),
    st.lists(st.floats(-2.0, 2.0), min_size=3, max_size=3),
)
def test_rotation_and_translation_agree_with_quadrature_of_the_moved_body(angles, offset):
    """A box turned by a 3-1-3 sequence and moved: R I Rᵀ and the parallel-axis theorem vs quadrature of the moved points (1e-12)."""
    dims = DIMENSIONS["box"]
    R = matrix_from_angles(np.array(angles), "3-1-3")
    points, weights = sample("box", **dims)
    moved = points @ R.T + np.array(offset)
    _, _, expected = mass_properties(moved, weights * 3.0 / np.sum(weights))
    tensor = inertia.parallel_axis(inertia.rotate_tensor(inertia.box(3.0, *dims.values()), R), 3.0, np.array(offset))
    assert np.max(np.abs(tensor - expected)) < 1e-12 * np.max(np.abs(expected))
    back = inertia.centroidal_from_point(tensor, 3.0, np.array(offset))
    assert np.max(np.abs(back - inertia.rotate_tensor(inertia.box(3.0, *dims.values()), R))) < 1e-12 * np.max(np.abs(expected))


@settings(max_examples=80, deadline=None)
@given(
    st.lists(st.floats(0.05, 5.0), min_size=3, max_size=3),
    st.lists(st.floats(-math.pi, math.pi), min_size=3, max_size=3),
)
def test_principal_axes_diagonalise_and_are_right_handed(sides, angles):
    """For any box turned any way: axes orthonormal (1e-12), det +1, Eᵀ diag(I) E rebuilds the tensor (1e-12), moments ascending."""
    tensor = inertia.rotate_tensor(inertia.box(2.0, *sides), matrix_from_angles(np.array(angles), "3-2-1"))
    principal = inertia.principal_axes(tensor)
    E = principal.axes
    assert np.max(np.abs(E @ E.T - np.eye(3))) < 1e-12
    assert np.linalg.det(E) == pytest.approx(1.0, abs=1e-12)
    assert np.all(np.diff(principal.moments_kg_m2) >= 0.0)
    rebuilt = E.T @ np.diag(principal.moments_kg_m2) @ E
    assert np.max(np.abs(rebuilt - tensor)) < 1e-12 * np.max(np.abs(tensor))


@pytest.mark.parametrize(
    "tensor, degeneracy",
    [
        (inertia.solid_sphere(3.0, 0.2), "spherical"),
        (inertia.box(3.0, 0.4, 0.4, 0.4), "spherical"),  # a cube: every axis through its centre is principal
        (inertia.rotate_tensor(inertia.box(3.0, 0.4, 0.4, 0.4), matrix_from_angles(np.radians([30.0, 40.0, 50.0]), "3-2-1")), "spherical"),
        (inertia.solid_cylinder(3.0, 0.2, 0.9), "axisymmetric"),
        (inertia.thin_disk(3.0, 0.2), "axisymmetric"),
        (inertia.box(3.0, 0.2, 0.3, 0.4), "distinct"),
    ],
)
def test_repeated_moments_are_reported_and_the_axes_stay_the_frames_own(tensor, degeneracy):
    principal = inertia.principal_axes(tensor)
    assert principal.degeneracy == degeneracy
    assert np.linalg.det(principal.axes) == pytest.approx(1.0, abs=1e-12)
    if degeneracy == "spherical":
        assert np.array_equal(principal.axes, np.eye(3))
        assert "every axis" in principal.describe()
    if degeneracy == "axisymmetric":
        # The symmetric pair is chosen nearest the frame's own x and y; the symmetry axis is z.
        assert principal.repeated == (0, 1) or principal.repeated == (1, 2)
        assert np.allclose(np.abs(principal.axes), np.eye(3)[[0, 1, 2]], atol=1e-12) or np.allclose(np.abs(principal.axes), np.eye(3)[[2, 0, 1]], atol=1e-12)


def test_nearly_repeated_moments_still_give_orthonormal_axes():
    """Two moments 1e-7 apart (relative): reported distinct, axes orthonormal to 1e-12 and the tensor rebuilt to 1e-12."""
    base = np.diag([1.0, 1.0 + 1e-7, 2.0])
    R = matrix_from_angles(np.radians([10.0, 20.0, 30.0]), "1-2-3")
    tensor = inertia.rotate_tensor(base, R)
    principal = inertia.principal_axes(tensor)
    assert principal.degeneracy == "distinct"
    E = principal.axes
    assert np.max(np.abs(E @ E.T - np.eye(3))) < 1e-12
    assert np.max(np.abs(E.T @ np.diag(principal.moments_kg_m2) @ E - tensor)) < 1e-12


def test_inertia_ellipsoid_is_longest_along_the_axis_of_least_inertia():
    semi = inertia.inertia_ellipsoid_semi_axes_m(np.array([1.0, 4.0, 9.0]), size_m=0.6)
    assert semi == pytest.approx([0.6, 0.3, 0.2], rel=1e-15)


@pytest.mark.parametrize(
    "tensor, reason",
    [
        (np.diag([1.0, 1.0, 3.0]), "triangle inequality"),
        (np.diag([1.0, -1.0, 1.0]), "not positive definite"),
        (np.diag([1.0, 0.0, 1.0]), "not positive definite"),
        (np.array([[1.0, 0.5, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]), "not symmetric"),
        (np.diag([1.0, math.nan, 1.0]), "finite"),
    ],
)
def test_tensors_no_body_can_have_are_refused_with_the_reason(tensor, reason):
    with pytest.raises(ValueError, match=reason):
        inertia.check_inertia_tensor(tensor)


def test_a_flat_plate_is_the_triangle_inequalitys_limit_and_is_accepted():
    principal = inertia.check_inertia_tensor(inertia.thin_plate(1.0, 0.5, 0.3))
    I1, I2, I3 = principal.moments_kg_m2
    assert I3 == pytest.approx(I1 + I2, rel=1e-15)
