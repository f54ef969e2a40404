"""Worked Example 1.1 (app/physics/robot_arm_cable.py) against an independent construction.

The reference here builds the arm in its own vertical plane (the xz plane before
rotation) and turns that plane about z with a rotation matrix, takes moments with
the force placed at D instead of C, uses a scalar triple product (determinant)
for the moment about AB, and gets F_BC from the law of cosines in triangle BCD
(distances only, no dot product).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch01 import robot_arm_cable as arm


def Rz(angle_rad: float) -> np.ndarray:
    c, s = math.cos(angle_rad), math.sin(angle_rad)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def reference(theta_deg, gamma_deg, tension_N, AB_m, BC_m, D_x_m):
    """Independent solution of Example 1.1 (positions in m, forces in N, moments in N·m)."""
    R = Rz(math.radians(theta_deg))
    g = math.radians(gamma_deg)
    # In the arm's own vertical plane (x' along AB, z up) B and C are plain 2D points.
    B_plane = np.array([AB_m, 0.0, 0.0])
    C_plane = np.array([AB_m + BC_m * math.cos(g), 0.0, BC_m * math.sin(g)])
    A = np.zeros(3)
    B, C = R @ B_plane, R @ C_plane
    D = np.array([D_x_m, 0.0, 0.0])
    CD = math.dist(C, D)
    F = tension_N * (D - C) / CD
    # Moment about A with F placed at D (same line of action as at C).
    M_A = np.cross(D - A, F)
    # Moment about line AB: triple product det[e_AB, r_{D/B}, F] with B as the point on the axis.
    e_AB = R @ np.array([1.0, 0.0, 0.0])
    with np.errstate(divide="ignore", invalid="ignore"):  # LU of a singular (e.g. T = 0) matrix warns
        M_AB = float(np.linalg.det(np.array([e_AB, D - B, F])))
    # F_BC = T cos(angle between B->C and C->D) = -T cos(interior angle BCD); law of cosines.
    BD, BC = math.dist(B, D), math.dist(B, C)
    F_BC = tension_N * (BD**2 - BC**2 - CD**2) / (2.0 * BC * CD)
    return {"A": A, "B": B, "C": C, "D": D, "F": F, "M_A": M_A, "M_AB": M_AB, "F_BC": F_BC, "e_AB": e_AB}


DEFAULTS = arm.INPUTS.defaults()


def args(inputs):
    return (inputs[k] for k in ("theta_deg", "gamma_deg", "tension_N", "AB_m", "BC_m", "D_x_m"))


def test_defaults_match_the_colleagues_hand_solution():
    # Independently worked numbers, quoted to 4 significant figures: compare at 5e-4 relative
    # (half a unit in the 4th figure, with margin for the quoted rounding).
    loads = arm.cable_loads(DEFAULTS)
    np.testing.assert_allclose(loads.F_N, [1829, -3768, -2730], rtol=5e-4)
    assert loads.F_BC_N == pytest.approx(-1705, rel=5e-4)
    assert loads.M_A_Nm[0] == pytest.approx(0.0, abs=1e-9)  # exactly zero in exact arithmetic (see below)
    np.testing.assert_allclose(loads.M_A_Nm[1:], [9555, -13190], rtol=5e-4)
    assert loads.M_z_Nm == pytest.approx(-1.319e4, rel=5e-4)
    assert loads.M_AB_Nm == pytest.approx(4038, rel=5e-4)


def test_defaults_match_the_independent_construction():
    loads = arm.cable_loads(DEFAULTS)
    ref = reference(*args(DEFAULTS))
    g = loads.geometry
    # 1e-12 relative: the same closed-form quantities computed two ways in double precision
    # (rotation matrix vs trig products, cross product at D vs at C); errors are a few ulps
    # of magnitudes ~1e4, amplified at most by |r| ~ 4 m.
    for name in "ABCD":
        np.testing.assert_allclose(getattr(g, name), ref[name], rtol=0, atol=1e-12)
    np.testing.assert_allclose(loads.F_N, ref["F"], rtol=1e-12)
    np.testing.assert_allclose(loads.M_A_Nm, ref["M_A"], rtol=0, atol=1e-12 * np.linalg.norm(ref["M_A"]))
    assert loads.F_BC_N == pytest.approx(ref["F_BC"], rel=1e-12)
    assert loads.M_AB_Nm == pytest.approx(ref["M_AB"], rel=1e-12)


def test_moment_components_agree_with_each_other():
    loads = arm.cable_loads(DEFAULTS)
    g = loads.geometry
    F = loads.F_N
    tol = 1e-12 * np.linalg.norm(loads.M_A_Nm)  # a few ulps of |M_A| ~ 1.6e4 N·m
    # M_A from C and from D must be the same: D lies on the line of action.
    np.testing.assert_allclose(np.cross(g.C, F), np.cross(g.D, F), rtol=0, atol=tol)
    # M_z: the z component of M_A and the planar formula x F_y - y F_x at C (and at D).
    assert loads.M_z_Nm == pytest.approx(loads.M_A_Nm[2], abs=tol)
    assert loads.M_z_Nm == pytest.approx(g.C[0] * F[1] - g.C[1] * F[0], abs=tol)
    assert loads.M_z_Nm == pytest.approx(g.D[0] * F[1] - g.D[1] * F[0], abs=tol)
    # M_AB with A or with B as the point on the axis, and C or D on the line of action.
    e = g.e_AB
    for P in (g.A, g.B):
        for Q in (g.C, g.D):
            assert loads.M_AB_Nm == pytest.approx(np.dot(e, np.cross(Q - P, F)), abs=tol)


def test_cable_force_along_bc_is_tension_times_cosine():
    loads = arm.cable_loads(DEFAULTS)
    g = loads.geometry
    BC, CD = g.C - g.B, g.D - g.C
    cos_angle = np.dot(BC, CD) / (np.linalg.norm(BC) * np.linalg.norm(CD))
    # 1e-12 relative: one closed form, two orders of operations.
    assert loads.F_BC_N == pytest.approx(DEFAULTS["tension_N"] * cos_angle, rel=1e-12)


angles = st.floats(-180.0, 180.0)
inputs_strategy = st.fixed_dictionaries(
    {
        "theta_deg": angles,
        "gamma_deg": st.floats(-90.0, 90.0),
        "tension_N": st.floats(0.0, 100_000.0),
        "AB_m": st.floats(0.05, 10.0),
        "BC_m": st.floats(0.05, 10.0),
        "D_x_m": st.floats(-10.0, 10.0),
    }
)


def validated(raw):
    try:
        return arm.INPUTS.validate(raw)
    except ParameterError as exc:  # only the C-coincides-with-D case may be refused
        assert exc.field == "D_x_m"
        assume(False)


@settings(max_examples=150, deadline=None)
@given(inputs_strategy)
def test_properties_over_random_valid_inputs(raw):
    inputs = validated(raw)
    loads = arm.cable_loads(inputs)
    T = inputs["tension_N"]
    F, M_A, C = loads.F_N, loads.M_A_Nm, loads.geometry.C
    r = np.linalg.norm(C)
    # |F| = T: F is T times a unit vector; 1e-13 relative is a few ulps. (math.hypot scales,
    # so a tiny tension such as 1e-287 N does not underflow when squared, as np.linalg.norm does.)
    assert math.hypot(*F) == pytest.approx(T, rel=1e-13, abs=1e-300)
    # The moment of a force is perpendicular to it: (r x F).F = 0. Rounding of r x F is
    # ~eps |r||F|, so the dot product is at most ~1e-15 |r||F|^2; allow 1e-12.
    assert abs(np.dot(M_A, F)) <= 1e-12 * r * T**2 + 1e-300
    # A at the origin and D = (x_D, 0, 0): taking the moment at D gives M_A = x_D i x F, which
    # has no i component; at C the two products C_y F_z and C_z F_y cancel to rounding, ~eps|r||F|.
    assert abs(M_A[0]) <= 1e-12 * r * T + 1e-300
    # M_z is the k component of M_A; M_AB is M_A along e_AB (moment about an axis through A).
    assert loads.M_z_Nm == M_A[2]
    assert loads.M_AB_Nm == pytest.approx(np.dot(M_A, loads.geometry.e_AB), abs=1e-12 * r * T + 1e-300)


@settings(max_examples=150, deadline=None)
@given(inputs_strategy)
def test_matches_independent_construction_over_random_inputs(raw):
    inputs = validated(raw)
    ref = reference(*args(inputs))
    CD = math.dist(ref["C"], ref["D"])
    # Keep C at least 1 mm from D: closer, the cable direction itself is ill-conditioned
    # (rounding in D - C of ~eps*10 m is amplified by 1/|CD|) and the two constructions may
    # legitimately differ by more than the tolerance below.
    assume(CD > 1e-3)
    loads = arm.cable_loads(inputs)
    T = inputs["tension_N"]
    # Error model: positions agree to ~eps*20 m (|r| <= 20 m), so F agrees to ~eps*T*20/|CD| and
    # moments to ~eps*T*400/|CD|. Measured over 2e5 random inputs: at most 1.4 eps and 0.93 eps of
    # those scales. Tolerance 1e-13 (~450 eps) of the scales: >= 300x margin.
    f_tol = 1e-13 * T * 20.0 / CD + 1e-300
    m_tol = 1e-13 * T * 400.0 / CD + 1e-300
    np.testing.assert_allclose(loads.F_N, ref["F"], rtol=0, atol=f_tol)
    np.testing.assert_allclose(loads.M_A_Nm, ref["M_A"], rtol=0, atol=m_tol)
    assert abs(loads.M_AB_Nm - ref["M_AB"]) <= m_tol
    # The law of cosines cancels squares of lengths: its rounding is ~eps*T*(BD^2+BC^2+CD^2)/(BC*CD)
    # (measured at most 18 eps of that); 1e-12 (~4500 eps) leaves 250x margin.
    BD, BC = math.dist(ref["B"], ref["D"]), math.dist(ref["B"], ref["C"])
    assert abs(loads.F_BC_N - ref["F_BC"]) <= 1e-12 * T * (BD**2 + BC**2 + CD**2) / (BC * CD) + 1e-300


def test_c_coinciding_with_d_is_refused_naming_d_x():
    # theta = gamma = 0 puts B and C on the x axis at AB and AB + BC; D_x = AB + BC puts C on D.
    raw = {"theta_deg": 0.0, "gamma_deg": 0.0, "AB_m": 2.0, "BC_m": 1.5, "D_x_m": 3.5}
    with pytest.raises(ValueError) as info:
        arm.INPUTS.validate(raw)
    assert isinstance(info.value, ParameterError)
    assert info.value.field == "D_x_m"
    assert str(info.value).startswith("x_D (m): ")  # named as its control shows it; the field keeps the API name
    with pytest.raises(ValueError, match="D_x_m"):
        arm.cable_loads({**DEFAULTS, **raw})
    # A millimetre away the cable has a direction again, along -i (C is past D on x).
    loads = arm.cable_loads({**DEFAULTS, **raw, "D_x_m": 3.499})
    np.testing.assert_allclose(loads.F_N, [-5000.0, 0.0, 0.0], rtol=0, atol=1e-9)


@pytest.mark.parametrize(
    ("theta_deg", "expected"),
    [(25.0, "clockwise"), (-30.0, "counter-clockwise"), (150.0, "clockwise"), (0.0, "none"), (180.0, "none")],
)
def test_turning_seen_from_above_follows_the_sign_of_the_independent_moment(theta_deg, expected):
    # The reference moment about A (force placed at D) gives M_z; its sign is the turning sense by the right-hand
    # rule about +z. In the vertical plane through the x axis (θ = 0° or 180°) the cable and the z axis are
    # coplanar: no turning (M_z is 0 or a few ulps of T·|r_C|, under NO_TURNING_RTOL).
    inputs = {**DEFAULTS, "theta_deg": theta_deg}
    M_z = reference(*args(inputs))["M_A"][2]
    assert arm.turning_about_z(arm.cable_loads(inputs)) == expected
    if expected != "none":
        assert (M_z > 0) == (expected == "counter-clockwise") and abs(M_z) > 1e3  # N·m: well clear of zero
    assert arm.turning_about_z(arm.cable_loads({**inputs, "tension_N": 0.0})) == "none"  # no pull, no turning
