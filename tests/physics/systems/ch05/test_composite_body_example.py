"""Worked example ``inertia-of-composite-body`` (section 5.2) against an independent computation, and its Check step.

The test integrates the bracket element by element with sympy: the plate over its rectangle at its areal density,
the hole over its circle with the negative of its own areal density (its mass over its area), and the rod along its
line at its line density, each placed and turned in the reference frame by the part's own 3-2-1 turn
Rz(angle 1) Ry(angle 2) Rx(angle 3). From those integrals come m, r_G and the tensor ∫ (|d|² 1 − d dᵀ) dm about G and
about P. No inertia table, rotation of a tabulated tensor or parallel-axis shift enters.

Tolerance: exact integrals against sums of a few dozen floating-point products of O(0.1–1) numbers (~1e-16 of the
scale); 1e-12 of the scale (m for the mass, the largest part's offset for r_G, tr I_P for the tensors) leaves a 1000×
margin. A hole that removes more than the body has where it is cut is refused (ParameterError naming ``bodies``).
"""

from __future__ import annotations

import copy

import numpy as np
import pytest
import sympy as sp

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch05.composite_body import DEFAULT_BODIES, EXAMPLE

u, w, r, q = sp.symbols("u w r q", real=True)
ORIGINAL_STEPS = [
    "Each body about its own centre of mass, in reference axes",
    "Mass and centre of mass",
    "Parallel-axis theorem to the common centre of mass",
    "Inertia about the point P",
    "Principal moments and axes at G",
]


def exact(value):
    return sp.Rational(str(value))


def turn(angles_deg):
    a1, a2, a3 = (exact(a) * sp.pi / 180 for a in angles_deg)
    c1, s1, c2, s2, c3, s3 = sp.cos(a1), sp.sin(a1), sp.cos(a2), sp.sin(a2), sp.cos(a3), sp.sin(a3)
    rz = sp.Matrix([[c1, -s1, 0], [s1, c1, 0], [0, 0, 1]])
    ry = sp.Matrix([[c2, 0, s2], [0, 1, 0], [-s2, 0, c2]])
    rx = sp.Matrix([[1, 0, 0], [0, c3, -s3], [0, s3, c3]])
    return rz * ry * rx


def parts(bodies):
    """(position of an element in reference axes, signed density × measure, limits) for each part."""
    out = []
    for body in bodies:
        assert body["sequence"] == "3-2-1"
        mass = -exact(body["mass_kg"]) if body["hole"] else exact(body["mass_kg"])
        R, centre = turn(body["angles_deg"]), sp.Matrix([exact(c) for c in body["position_m"]])
        if body["shape"] == "plate":
            a, b = exact(body["length_m"]), exact(body["width_m"])
            out.append((centre + R * sp.Matrix([u, w, 0]), mass / (a * b), [(u, -a / 2, a / 2), (w, -b / 2, b / 2)]))
        elif body["shape"] == "disk":
            rad = exact(body["radius_m"])
            local = sp.Matrix([r * sp.cos(q), r * sp.sin(q), 0])
            out.append((centre + R * local, mass * r / (sp.pi * rad**2), [(r, 0, rad), (q, 0, 2 * sp.pi)]))
        else:
            assert body["shape"] == "rod"
            length = exact(body["length_m"])
            out.append((centre + R * sp.Matrix([0, 0, u]), mass / length, [(u, -length / 2, length / 2)]))
    return out


def integral(pieces, integrand):
    total = None
    for position, density, limits in pieces:
        value = integrand(position).applyfunc(lambda e, d=density, lim=limits: sp.integrate(sp.expand(e * d), *lim))
        total = value if total is None else total + value
    return total


def tensor_about(pieces, point):
    def integrand(position):
        d = position - point
        return d.dot(d) * sp.eye(3) - d * d.T

    return np.array(sp.N(integral(pieces, integrand), 30), dtype=float)


def variant():
    bodies = copy.deepcopy(DEFAULT_BODIES)
    bodies[1]["position_m"] = [-0.05, -0.06, 0.0]
    bodies[2]["angles_deg"] = [20.0, 30.0, 0.0]
    bodies[2]["position_m"] = [-0.2, 0.0, 0.25]
    return bodies


CASES = [
    (DEFAULT_BODIES, [0.0, 0.0, 0.0]),
    (DEFAULT_BODIES, [-0.2, 0.0, 0.5]),
    (variant(), [0.3, -0.2, 0.1]),
    (variant(), [0.0, 0.0, 0.0]),
]


@pytest.mark.parametrize(("bodies", "point"), CASES)
def test_outputs_match_the_body_integrated_element_by_element(bodies, point):
    inputs = EXAMPLE.inputs.validate({"bodies": bodies, "about_point_m": point})
    solution = EXAMPLE.solve(inputs)
    out = solution.outputs
    pieces = parts(bodies)
    mass = float(sp.N(integral(pieces, lambda p: sp.Matrix([1]))[0], 30))
    moment = np.array(sp.N(integral(pieces, lambda p: p), 30), dtype=float).ravel()
    centre = moment / mass
    assert out["mass_kg"] == pytest.approx(mass, rel=1e-12)
    assert np.allclose(out["centre_of_mass_m"], centre, rtol=0, atol=1e-12)
    at_g = tensor_about(pieces, sp.Matrix([sp.Rational(c) for c in centre]))
    at_p = tensor_about(pieces, sp.Matrix([exact(c) for c in point]))
    assert np.allclose(out["inertia_cm_kg_m2"], at_g, rtol=0, atol=1e-12 * np.trace(at_g))
    assert np.allclose(out["inertia_point_kg_m2"], at_p, rtol=0, atol=1e-12 * np.trace(at_p))
    assert np.allclose(out["principal_moments_kg_m2"], np.linalg.eigvalsh(at_g), rtol=0, atol=1e-12 * np.trace(at_g))
    # The steps the outside checks rely on are unchanged, and the added Check step's two routes agree.
    titles = [step.title for step in solution.steps]
    assert titles[:5] == ORIGINAL_STEPS and titles[5].startswith("Check")
    check = solution.steps[5].values
    assert np.allclose(check["I_P (part by part)"], check["I_P (through G)"], rtol=0, atol=1e-12 * np.trace(at_p))
    assert check["tr I_G"] == pytest.approx(check["I_1 + I_2 + I_3"], rel=1e-12)


def test_a_hole_removing_more_than_its_body_has_there_is_refused():
    bodies = copy.deepcopy(DEFAULT_BODIES)
    bodies[1]["mass_kg"] = 20.0
    with pytest.raises(ParameterError) as refused:
        EXAMPLE.inputs.validate({"bodies": bodies})
    assert refused.value.field == "bodies"
