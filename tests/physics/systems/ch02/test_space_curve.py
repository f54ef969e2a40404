"""Path variables (Frenet frame, curvature, torsion, a_t/a_n, arc length) and curvilinear components.

Independent checks: the helix's closed forms; the Frenet–Serret formulas by
central differences of the computed frame; the symbolic derivatives against
finite differences of the position alone; the arc length against scipy's
adaptive quadrature; the cylindrical and spherical component formulas by
rebuilding the Cartesian velocity and acceleration, and their coordinate rates
against finite differences of the coordinates.
"""

from __future__ import annotations

import time

import numpy as np
import pytest
from scipy.integrate import quad

from app.physics.core.parameters import ParameterError
from app.physics.math.curvilinear import cylindrical, spherical
from app.physics.systems.ch02 import space_curve as sc

CURVES = {
    "helix": ("cos(t)", "sin(t)", "0.2*t"),
    "conical-spiral": ("0.1*t*cos(2*t)", "0.1*t*sin(2*t)", "0.12*t"),
    "figure-eight": ("cos(t)", "sin(2*t)/2", "0.3*sin(t)"),
    "viviani": ("0.5*(1+cos(t))", "0.5*sin(t)", "sin(t/2)"),
    "decaying-twist": ("exp(-t/4)*cos(3*t)", "t^2/5 - t", "log(2+sin(t))"),
}
TIMES = np.array([0.31, 1.2, 2.7, 4.05, 5.5])


def path(name: str, t_s=TIMES, t_end_s: float = 6.5) -> sc.PathVariables:
    curve = sc.compile_curve(*CURVES[name])
    return sc.path_variables(curve, t_s, sc.reference_scales(curve, t_end_s))


# -- the helix: exact values ------------------------------------------------------------

@pytest.mark.parametrize("a, c, omega", [(2.0, 0.5, 1.0), (1.0, 0.2, 1.0), (0.3, -1.5, 2.5), (5.0, 0.0, 0.7)])
def test_helix_curvature_and_torsion_are_exact(a, c, omega):
    """x = a cos ωt, y = a sin ωt, z = c ωt: κ = a/(a²+c²), τ = c/(a²+c²) for any ω."""
    curve = sc.compile_curve(f"{a}*cos({omega}*t)", f"{a}*sin({omega}*t)", f"{c}*{omega}*t")
    t = np.linspace(0.0, 10.0, 41)
    p = sc.path_variables(curve, t, sc.reference_scales(curve, 10.0))
    denominator = a * a + c * c
    # Every formula is a handful of float operations on exact symbolic derivatives: 1e-12 is
    # ~1e4 rounding units, and any wrong power of |r'| would be off by order one.
    np.testing.assert_allclose(p.curvature_1_m, a / denominator, rtol=1e-12)
    speed = omega * np.sqrt(denominator)
    np.testing.assert_allclose(p.speed_m_s, speed, rtol=1e-12)
    np.testing.assert_allclose(p.a_tangential_m_s2, 0.0, atol=1e-12 * a * omega**2)
    np.testing.assert_allclose(p.a_normal_m_s2, a * omega**2, rtol=1e-12)
    np.testing.assert_allclose(sc.arc_length(curve, t), speed * t, rtol=1e-12, atol=1e-14)
    if c == 0.0:
        assert np.all(p.torsion_1_m == 0.0)  # a circle is planar
    else:
        np.testing.assert_allclose(p.torsion_1_m, c / denominator, rtol=1e-12)
    # The normal points at the helix's axis, horizontally.
    np.testing.assert_allclose(p.normal, -np.stack([np.cos(omega * t), np.sin(omega * t), 0 * t], axis=1), atol=1e-12)


# -- general curves: identities and independent derivatives -----------------------------------

@pytest.mark.parametrize("name", sorted(CURVES))
def test_frame_is_right_handed_orthonormal_and_splits_the_acceleration(name):
    p = path(name)
    assert p.curving.all()
    frame = np.stack([p.tangent, p.normal, p.binormal], axis=1)
    np.testing.assert_allclose(frame @ frame.transpose(0, 2, 1), np.broadcast_to(np.eye(3), frame.shape), atol=1e-13)
    np.testing.assert_allclose(np.linalg.det(frame), 1.0, atol=1e-13)
    a = p.acceleration_m_s2
    # a_t² + a_n² = |a|² and a = a_t T + a_n N, to rounding (1e-12 relative to |a|²).
    np.testing.assert_allclose(p.a_tangential_m_s2**2 + p.a_normal_m_s2**2, np.sum(a * a, axis=1), rtol=1e-12)
    rebuilt = p.a_tangential_m_s2[:, None] * p.tangent + p.a_normal_m_s2[:, None] * p.normal
    np.testing.assert_allclose(rebuilt, a, atol=1e-12 * np.abs(a).max())
    np.testing.assert_allclose(p.a_normal_m_s2, p.curvature_1_m * p.speed_m_s**2, rtol=1e-12)


@pytest.mark.parametrize("name", sorted(CURVES))
def test_frenet_serret_formulas_by_central_differences(name):
    """dT/ds = κN, dN/ds = −κT + τB, dB/ds = −τN, with d/ds = (1/v) d/dt taken by central differences.

    h = 1e-4 s: truncation error ~ h² |d³(frame)/dt³| ≈ 1e-8 for these curves, rounding ~ 1e-16/h
    = 1e-12; the tolerance 1e-6 sits well above both and far below κ, τ ~ 0.1-10 1/m.
    """
    h = 1e-4
    centre, ahead, behind = path(name), path(name, TIMES + h), path(name, TIMES - h)
    v, kappa, tau = centre.speed_m_s[:, None], centre.curvature_1_m[:, None], centre.torsion_1_m[:, None]

    def d_ds(field):
        return (getattr(ahead, field) - getattr(behind, field)) / (2 * h) / v

    np.testing.assert_allclose(d_ds("tangent"), kappa * centre.normal, atol=1e-6)
    np.testing.assert_allclose(d_ds("normal"), -kappa * centre.tangent + tau * centre.binormal, atol=1e-6)
    np.testing.assert_allclose(d_ds("binormal"), -tau * centre.normal, atol=1e-6)
    # And a_t = d|v|/dt.
    np.testing.assert_allclose((ahead.speed_m_s - behind.speed_m_s) / (2 * h), centre.a_tangential_m_s2, atol=1e-6)


@pytest.mark.parametrize("name", sorted(CURVES))
def test_symbolic_derivatives_match_finite_differences_of_the_position(name):
    """r', r'', r''' from sympy against 5-point central differences of r(t) alone.

    The stencils are fourth order: truncation ≈ 0.06 h⁴ |r⁽ⁿ⁺⁴⁾| ≤ 2e-6 with h = 1e-2 s for the
    fastest component here (cos 3t: |r⁽⁷⁾| ≤ 3⁷), rounding ≈ 1e-16 |r| / hⁿ ≤ 1e-10; tolerance 1e-5.
    """
    curve = sc.compile_curve(*CURVES[name])
    r = curve.position
    _, v, a, j = curve.jets(TIMES)
    h = 1e-2
    v_fd = (-r(TIMES + 2 * h) + 8 * r(TIMES + h) - 8 * r(TIMES - h) + r(TIMES - 2 * h)) / (12 * h)
    a_fd = (-r(TIMES + 2 * h) + 16 * r(TIMES + h) - 30 * r(TIMES) + 16 * r(TIMES - h) - r(TIMES - 2 * h)) / (12 * h * h)
    j_fd = (-r(TIMES + 3 * h) + 8 * r(TIMES + 2 * h) - 13 * r(TIMES + h) + 13 * r(TIMES - h) - 8 * r(TIMES - 2 * h) + r(TIMES - 3 * h)) / (8 * h**3)
    np.testing.assert_allclose(v, v_fd, atol=1e-5)
    np.testing.assert_allclose(a, a_fd, atol=1e-5)
    np.testing.assert_allclose(j, j_fd, atol=1e-5)


@pytest.mark.parametrize("name", ["figure-eight", "decaying-twist"])
def test_arc_length_matches_adaptive_quadrature(name):
    curve = sc.compile_curve(*CURVES[name])
    t = np.array([0.4, 1.0, 3.3, 6.0])
    expected = [quad(lambda s: float(np.linalg.norm(curve.jets(s)[1][0])), 0.0, end, epsabs=1e-13, epsrel=1e-13)[0] for end in t]
    # 8-point Gauss–Legendre on 0.05 s panels: error ~ (0.05)^16 × |d^16 speed| ≪ 1e-12 here.
    np.testing.assert_allclose(sc.arc_length(curve, t), expected, rtol=1e-11)


# -- degenerate instants are reported, not drawn -------------------------------------------------

def test_zero_speed_leaves_the_frame_undefined():
    curve = sc.compile_curve("t^3", "t^2", "0")  # a cusp at t = 0
    p = sc.path_variables(curve, np.array([0.0, 0.5]), sc.reference_scales(curve, 1.0))
    assert list(p.moving) == [False, True]
    assert np.isnan(p.tangent[0]).all() and np.isnan(p.normal[0]).all() and np.isnan(p.curvature_1_m[0])
    assert np.isnan(p.a_tangential_m_s2[0]) and np.isnan(p.a_normal_m_s2[0])
    assert p.speed_m_s[0] == 0.0
    assert "momentarily at rest" in sc.undefined_reason(p, 0)
    assert sc.undefined_reason(p, 1) == ""


def test_zero_curvature_leaves_normal_binormal_and_torsion_undefined():
    curve = sc.compile_curve("1 + 2*t", "t^3", "t^4")  # r'' = 0 at t = 0: locally straight there only
    p = sc.path_variables(curve, np.array([0.0, 1.0]), sc.reference_scales(curve, 2.0))
    assert list(p.curving) == [False, True]
    assert p.curvature_1_m[0] == 0.0 and p.a_normal_m_s2[0] == 0.0
    assert np.isnan(p.normal[0]).all() and np.isnan(p.binormal[0]).all() and np.isnan(p.torsion_1_m[0])
    np.testing.assert_allclose(p.tangent[0], [1.0, 0.0, 0.0])
    assert "curvature is zero" in sc.undefined_reason(p, 0)


def test_undefined_formula_values_are_nan_with_a_reason():
    curve = sc.compile_curve("sqrt(t - 1)", "t", "log(t)")
    p = sc.path_variables(curve, np.array([0.5, 2.0]), sc.reference_scales(curve, 3.0))
    assert list(p.defined) == [False, True]
    assert np.isnan(p.position_m[0, 0]) and np.isnan(p.speed_m_s[0])
    assert "no finite value" in sc.undefined_reason(p, 0)


def test_rounding_noise_is_not_mistaken_for_curvature():
    """cos(t)^2 + sin(t)^2 is 1 but evaluates with ~1e-16 noise: the path is still straight."""
    curve = sc.compile_curve("t", "cos(t)^2 + sin(t)^2", "2*t")
    p = sc.path_variables(curve, TIMES, sc.reference_scales(curve, 6.0))
    assert p.moving.all() and not p.curving.any()
    assert np.isnan(p.torsion_1_m).all()


def test_a_formula_too_complicated_to_differentiate_is_refused_quickly():
    start = time.perf_counter()
    with pytest.raises(sc.CurveError, match="too long .* to evaluate quickly") as info:
        sc.compile_curve("t", "sin(" * 26 + "t" + ")" * 26, "0")
    assert info.value.component == "y_of_t"
    assert time.perf_counter() - start < 10.0  # measured ~0.1 s; differentiating it fully would take seconds per order


def test_bad_text_is_refused_naming_the_component():
    with pytest.raises(ParameterError) as info:
        sc.INPUTS.validate({"z_of_t": "t.__class__"})
    assert info.value.field == "z_of_t" and "attribute access" in str(info.value)


# -- cylindrical and spherical components ------------------------------------------------------

@pytest.mark.parametrize("name", sorted(CURVES))
@pytest.mark.parametrize("describe", [cylindrical, spherical])
def test_curvilinear_components_rebuild_cartesian_velocity_and_acceleration(name, describe):
    p = path(name)
    coords = describe(p.position_m, p.velocity_m_s, p.acceleration_m_s2, length_scale_m=1.0)
    e = coords.unit_vectors  # (N, 3, 3): rows are unit vectors
    np.testing.assert_allclose(e @ e.transpose(0, 2, 1), np.broadcast_to(np.eye(3), e.shape), atol=1e-13)
    np.testing.assert_allclose(np.linalg.det(e), 1.0, atol=1e-13)  # right-handed in the stated order
    # The textbook component formulas, summed on the unit vectors, give back v and a (rounding only).
    v_rebuilt = np.einsum("nk,nki->ni", coords.velocity, e)
    a_rebuilt = np.einsum("nk,nki->ni", coords.acceleration, e)
    np.testing.assert_allclose(v_rebuilt, p.velocity_m_s, atol=1e-12 * np.abs(p.velocity_m_s).max())
    np.testing.assert_allclose(a_rebuilt, p.acceleration_m_s2, atol=1e-11 * np.abs(p.acceleration_m_s2).max())


@pytest.mark.parametrize("name", ["conical-spiral", "figure-eight", "decaying-twist"])
@pytest.mark.parametrize("describe", [cylindrical, spherical])
def test_coordinate_rates_match_finite_differences_of_the_coordinates(name, describe):
    """(R, θ, z) or (r, φ, θ) at t ± h; first and second central differences (h = 1e-4 s):
    truncation ~ h² ≈ 1e-8, rounding ~ 1e-16/h² = 1e-8 for the second; tolerance 1e-5."""
    h = 1e-4
    states = [path(name, TIMES + dt) for dt in (-h, 0.0, h)]
    behind, centre, ahead = (describe(s.position_m, s.velocity_m_s, s.acceleration_m_s2, length_scale_m=1.0) for s in states)
    np.testing.assert_allclose((ahead.coordinates - behind.coordinates) / (2 * h), centre.rates, atol=1e-5)
    second = (ahead.coordinates - 2 * centre.coordinates + behind.coordinates) / h**2
    np.testing.assert_allclose(second, centre.second_rates, atol=1e-5)


def test_spherical_components_on_vivianis_curve():
    """Viviani's curve lies on the sphere r = 1 m: v_r = 0 and a_r = −v²/r (the sphere's centripetal term)."""
    p = path("viviani")
    coords = spherical(p.position_m, p.velocity_m_s, p.acceleration_m_s2, length_scale_m=1.0)
    np.testing.assert_allclose(coords.coordinates[:, 0], 1.0, rtol=1e-14)
    np.testing.assert_allclose(coords.velocity[:, 0], 0.0, atol=1e-14)
    np.testing.assert_allclose(coords.acceleration[:, 0], -p.speed_m_s**2, rtol=1e-12)


def test_axis_and_origin_leave_the_singular_directions_undefined():
    position = np.array([[0.0, 0.0, 2.0], [0.0, 0.0, 0.0]])
    velocity = np.array([[1.0, 0.0, 0.5], [1.0, 1.0, 0.0]])
    acceleration = np.zeros((2, 3))
    cyl = cylindrical(position, velocity, acceleration, length_scale_m=1.0)
    assert np.isnan(cyl.unit_vectors[0, :2]).all() and not np.isnan(cyl.unit_vectors[0, 2]).any()
    assert cyl.velocity[0, 2] == 0.5 and np.isnan(cyl.velocity[0, 0])
    sph = spherical(position, velocity, acceleration, length_scale_m=1.0)
    np.testing.assert_allclose(sph.unit_vectors[0, 0], [0.0, 0.0, 1.0])  # e_r is +Z on the axis
    assert np.isnan(sph.unit_vectors[0, 1:]).all()
    assert np.isnan(sph.unit_vectors[1]).all()  # nothing is defined at the origin


# -- the model behind POST /api/scenes/space-curve/simulate ---------------------------------------

def test_model_series_for_the_helix():
    params = sc.INPUTS.validate({"x_of_t": "2*cos(t)", "y_of_t": "2*sin(t)", "z_of_t": "0.5*t"})
    report = sc.ParticleOnCurve().simulate(params, {}, t_end_s=6.0, frame_rate_hz=10.0).as_dict()
    series = {k: np.array(v, dtype=float) for k, v in report["series"].items()}
    t = np.array(report["t"])
    assert set(series) == set(sc.ParticleOnCurve.series_units)
    np.testing.assert_allclose(series["curvature"], 2 / 4.25, rtol=1e-12)
    np.testing.assert_allclose(series["torsion"], 0.5 / 4.25, rtol=1e-12)
    np.testing.assert_allclose(series["speed"], np.sqrt(4.25), rtol=1e-12)
    np.testing.assert_allclose(series["arc_length"], np.sqrt(4.25) * t, rtol=1e-12, atol=1e-14)
    np.testing.assert_allclose(series["theta"], t, atol=1e-12)  # unwrapped azimuth
    np.testing.assert_allclose(series["v_theta"], 2.0, rtol=1e-12)
    np.testing.assert_allclose(series["a_R"], -2.0, rtol=1e-12)
    assert report["events"] == [] and report["stats"]["status"] == "ok"


def test_model_reports_degenerate_instants_as_events():
    params = sc.INPUTS.validate({"x_of_t": "t^3", "y_of_t": "t^2", "z_of_t": "0"})
    report = sc.ParticleOnCurve().simulate(params, {}, t_end_s=1.0, frame_rate_hz=10.0).as_dict()
    assert [(e["t_s"], e["kind"]) for e in report["events"]] == [(0.0, "at-rest")]
    assert report["series"]["curvature"][0] is None and report["series"]["speed"][0] == 0.0


# -- the numbers printed in the Chapter 2 lessons ----------------------------------------------

def test_lesson_2_4_example_1_conical_spiral_at_one_second():
    curve = sc.compile_curve("0.5*t*cos(2*t)", "0.5*t*sin(2*t)", "0.3*t")
    p = sc.path_variables(curve, np.array([1.0]), sc.reference_scales(curve, 5.0))
    cyl = cylindrical(p.position_m, p.velocity_m_s, p.acceleration_m_s2, length_scale_m=1.0)
    np.testing.assert_allclose(cyl.velocity[0], [0.5, 1.0, 0.3], atol=1e-14)
    np.testing.assert_allclose(cyl.acceleration[0], [-2.0, 2.0, 0.0], atol=1e-13)
    # Exact forms of the printed 4-5 figure values (the lesson rounds them).
    assert p.speed_m_s[0] == pytest.approx(np.sqrt(1.34), rel=1e-14)
    assert p.a_tangential_m_s2[0] == pytest.approx(1 / np.sqrt(1.34), rel=1e-13)
    assert p.a_normal_m_s2[0] == pytest.approx(np.sqrt(8 - 1 / 1.34), rel=1e-13)
    assert p.curvature_1_m[0] == pytest.approx(np.sqrt(9.72) / 1.34**1.5, rel=1e-13)
    assert p.torsion_1_m[0] == pytest.approx(50 / 81, rel=1e-13)
    on_cylindrical = cyl.unit_vectors[0]  # rows e_R, e_θ, e_z on XYZ
    np.testing.assert_allclose(on_cylindrical @ p.tangent[0], [0.4319, 0.8639, 0.2592], atol=5e-5)
    np.testing.assert_allclose(on_cylindrical @ p.normal[0], [-0.8811, 0.4655, -0.0831], atol=5e-5)
    np.testing.assert_allclose(on_cylindrical @ p.binormal[0], np.array([-1.0, -1.0, 5.0]) / np.sqrt(27), atol=1e-13)
    assert np.degrees(np.arccos(p.binormal[0, 2])) == pytest.approx(15.8, abs=0.05)


def test_lesson_2_4_example_2_bead_on_a_helix_at_two_seconds():
    curve = sc.compile_curve("cos(0.25*t^2/sqrt(1.04))", "sin(0.25*t^2/sqrt(1.04))", "0.05*t^2/sqrt(1.04)")
    p = sc.path_variables(curve, np.array([2.0]), sc.reference_scales(curve, 4.0))
    cyl = cylindrical(p.position_m, p.velocity_m_s, p.acceleration_m_s2, length_scale_m=1.0)
    root = np.sqrt(1.04)
    np.testing.assert_allclose(cyl.velocity[0], [0.0, 1 / root, 0.2 / root], atol=1e-13)
    np.testing.assert_allclose(cyl.acceleration[0], [-1 / 1.04, 0.5 / root, 0.1 / root], atol=1e-13)
    assert p.a_tangential_m_s2[0] == pytest.approx(0.5, rel=1e-13)
    assert p.a_normal_m_s2[0] == pytest.approx(1 / 1.04, rel=1e-13)
    assert sc.arc_length(curve, np.array([2.0]))[0] == pytest.approx(1.0, rel=1e-12)


def test_lesson_2_1_figure_eight_torsion():
    """By hand: at t = 0, τ = 0.9/1.09; at the crossing t = π/2, κ = 0.15 1/m and τ = −5 1/m."""
    p = path("figure-eight", np.array([0.0, np.pi / 2]))
    np.testing.assert_allclose(p.torsion_1_m, [0.9 / 1.09, -5.0], rtol=1e-12)
    assert p.curvature_1_m[1] == pytest.approx(0.15, rel=1e-12)
    assert p.speed_m_s[1] == pytest.approx(np.sqrt(2.0), rel=1e-14)  # fastest at the crossing
