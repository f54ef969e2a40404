"""Sections 2.2–2.4: the Cartesian particle, the paths in cylindrical/spherical coordinates, the collar on a rotating arm.

Every velocity and acceleration is checked against an independent computation:

- finite differences of the position alone (a five-point stencil, h = 1e-3 s: truncation
  error ≈ h⁴·|r⁽⁵⁾|/30 ≲ 1e-11 of the scale for these smooth motions, round-off ≈ 1e-16/h² ≈ 1e-10
  for the second derivative), so 1e-6 of the run's largest |v| or |a| is a tolerance with
  four orders of margin that still fails for any wrong term;
- the curvilinear components against the same formulas applied to coordinates written
  here in sympy from each path's definition (another form of the Gudermannian for the
  loxodrome), and against projections of the Cartesian v and a on the unit vectors; these
  agree to rounding, 1e-9 of the scale;
- closed forms a student can check by hand (helix, circle of latitude, conical spiral).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch02 import cartesian_components, coordinate_paths, rotating_arm
from app.physics.systems.ch02.coordinate_paths import CoordinatePath

STEP_S = 1e-3
FD_TOLERANCE = 1e-6  # of the run's largest |v| or |a| (see the module docstring)
ROUNDING = 1e-9  # of the scale: two exact routes to the same number


def five_point(position, t_s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """First and second derivatives (N, 3) of ``position(t) -> (N, 3)`` by five-point central differences."""
    h = STEP_S
    p = [position(t_s + k * h) for k in (-2, -1, 0, 1, 2)]
    first = (p[0] - 8 * p[1] + 8 * p[3] - p[4]) / (12 * h)
    second = (-p[0] + 16 * p[1] - 30 * p[2] + 16 * p[3] - p[4]) / (12 * h**2)
    return first, second


def assert_close_to_scale(actual: np.ndarray, expected: np.ndarray, tolerance: float) -> None:
    scale = max(float(np.max(np.abs(expected))), 1e-12)
    assert np.max(np.abs(actual - expected)) <= tolerance * scale, (np.max(np.abs(actual - expected)), scale)


# -- 2.2 rectangular Cartesian coordinates ----------------------------------------------------------

CARTESIAN_CASES = [
    {"motion": "sine-slot"},
    {"motion": "sine-slot", "slot_amplitude_m": 0.6, "slot_length_m": 0.5, "drive_speed_m_s": 2.0},
    {"motion": "projectile"},
    {"motion": "projectile", "launch_speed_m_s": 20.0, "launch_angle_deg": 90.0, "launch_heading_deg": -120.0, "gravity_m_s2": 1.62},
]


@pytest.mark.parametrize("values", CARTESIAN_CASES)
def test_cartesian_components_are_the_derivatives_of_the_position(values):
    params = cartesian_components.PARAMETERS.validate(values)
    motion = cartesian_components.cartesian_motion(params)
    t = np.linspace(0.0, motion.run_s, 41)
    state = motion.at(t)
    first, second = five_point(lambda s: motion.at(s).position_m, t)
    assert_close_to_scale(state.velocity_m_s, first, FD_TOLERANCE)
    assert_close_to_scale(state.acceleration_m_s2, second, FD_TOLERANCE)


def test_the_pin_stays_in_its_slot_and_the_projectile_lands_at_the_end_of_its_run():
    slot = cartesian_components.SineSlot(0.3, 1.0, 0.5)
    p = slot.at(np.linspace(0.0, slot.run_s, 101)).position_m
    assert p[:, 1] == pytest.approx(0.3 * np.sin(np.pi * p[:, 0] / 1.0), abs=1e-15)
    assert p[-1, 0] == pytest.approx(2.0, rel=1e-15)  # one wavelength, 2L
    projectile = cartesian_components.Projectile(8.0, math.radians(50.0), math.radians(30.0), 9.81)
    end = projectile.at(projectile.run_s)
    assert end.position_m[0, 2] == pytest.approx(0.0, abs=1e-14)
    # Range on level ground: v₀² sin 2α / g, along the heading ψ.
    assert np.hypot(*end.position_m[0, :2]) == pytest.approx(64.0 * math.sin(math.radians(100.0)) / 9.81, rel=1e-14)
    assert end.velocity_m_s[0, 2] == pytest.approx(-8.0 * math.sin(math.radians(50.0)), rel=1e-14)  # lands as fast as it left


def test_the_report_says_when_the_projectile_would_be_below_the_ground():
    model = cartesian_components.CartesianParticle()
    params = model.parameters.validate({"motion": "projectile"})
    flight = cartesian_components.cartesian_motion(params).run_s
    inside = model.simulate(params, {}, t_end_s=0.9 * flight, frame_rate_hz=30.0).as_dict()
    assert inside["stats"]["status"] == "ok"
    beyond = model.simulate(params, {}, t_end_s=2.0 * flight, frame_rate_hz=30.0).as_dict()
    assert beyond["stats"]["status"] == "outside_model" and "below the ground" in beyond["stats"]["message"]
    assert beyond["series"]["z_ddot"] == pytest.approx([-9.81] * len(beyond["t"]))


# -- 2.3 cylindrical and spherical coordinates on a chosen path -----------------------------------

PATH_CASES = [
    {"path": "helix", "size_m": 1.0, "azimuth_rate_rad_s": 1.0, "path_angle_deg": 15.0},
    {"path": "helix", "size_m": 0.4, "azimuth_rate_rad_s": 2.5, "path_angle_deg": 0.0},
    {"path": "conical-spiral", "size_m": 0.1 * math.pi, "azimuth_rate_rad_s": 2.0, "path_angle_deg": 40.0},
    {"path": "conical-spiral", "size_m": 1.0, "azimuth_rate_rad_s": 0.7, "path_angle_deg": 90.0},
    {"path": "latitude-circle", "size_m": 1.0, "azimuth_rate_rad_s": 1.0, "path_angle_deg": 50.0},
    {"path": "loxodrome", "size_m": 1.0, "azimuth_rate_rad_s": 1.0, "path_angle_deg": 75.0},
    {"path": "loxodrome", "size_m": 2.0, "azimuth_rate_rad_s": 0.5, "path_angle_deg": 30.0},
]


def path_of(values) -> CoordinatePath:
    return CoordinatePath.from_params(coordinate_paths.PARAMETERS.validate(values))


def coordinates_from_definition(path: CoordinatePath):
    """(R, θ, z) and (r, φ, θ) as sympy functions of t, written from the path's definition (not from its x, y, z)."""
    t = sympy.Symbol("t", real=True)
    a, w, beta = (sympy.Float(v, 30) for v in (path.size_m, path.azimuth_rate_rad_s, path.path_angle_rad))
    theta = sympy.Float(path.start_azimuth_rad, 30) + w * t
    if path.path == "helix":
        R, z = a + 0 * t, a * theta * sympy.tan(beta)
    elif path.path == "conical-spiral":
        R = a * (1 + theta / (2 * sympy.pi))
        z = R / sympy.tan(beta)
    elif path.path == "latitude-circle":
        R, z = a * sympy.sin(beta) + 0 * t, a * sympy.cos(beta) + 0 * t
    else:  # loxodrome: latitude λ = 2 atan(exp(θ cot β)) − π/2, the Gudermannian in another form
        latitude = 2 * sympy.atan(sympy.exp(theta / sympy.tan(beta))) - sympy.pi / 2
        R, z = a * sympy.cos(latitude), a * sympy.sin(latitude)
    r, phi = sympy.sqrt(R**2 + z**2), sympy.atan2(R, z)
    return t, (R, theta, z), (r, phi, theta)


def expected_components(path: CoordinatePath, t_s: np.ndarray):
    """Cylindrical and spherical (v, a) components (N, 3) from the textbook formulas on the coordinates above."""
    t, (R, theta, z), (r, phi, _) = coordinates_from_definition(path)
    d = lambda f, n=1: sympy.diff(f, t, n)  # noqa: E731
    cyl_v = [d(R), R * d(theta), d(z)]
    cyl_a = [d(R, 2) - R * d(theta) ** 2, R * d(theta, 2) + 2 * d(R) * d(theta), d(z, 2)]
    s, c = sympy.sin(phi), sympy.cos(phi)
    sph_v = [d(r), r * d(phi), r * s * d(theta)]
    sph_a = [
        d(r, 2) - r * d(phi) ** 2 - r * s**2 * d(theta) ** 2,
        r * d(phi, 2) + 2 * d(r) * d(phi) - r * s * c * d(theta) ** 2,
        r * s * d(theta, 2) + 2 * d(r) * d(theta) * s + 2 * r * d(phi) * d(theta) * c,
    ]
    f = sympy.lambdify(t, [*cyl_v, *cyl_a, *sph_v, *sph_a], modules="numpy")
    values = np.stack([np.broadcast_to(np.asarray(v, dtype=float), t_s.shape) for v in f(t_s)], axis=1)
    return values[:, 0:3], values[:, 3:6], values[:, 6:9], values[:, 9:12]


@pytest.mark.parametrize("values", PATH_CASES, ids=lambda v: f"{v['path']}-{v['path_angle_deg']:g}")
def test_path_velocity_and_acceleration_are_the_derivatives_of_its_position(values):
    path = path_of(values)
    t = np.linspace(0.0, path.run_s, 37)
    _, velocity, acceleration = path.at(t)
    first, second = five_point(lambda s: path.at(s)[0], t)
    assert_close_to_scale(velocity, first, FD_TOLERANCE)
    assert_close_to_scale(acceleration, second, FD_TOLERANCE)


@pytest.mark.parametrize("values", PATH_CASES, ids=lambda v: f"{v['path']}-{v['path_angle_deg']:g}")
def test_cylindrical_and_spherical_components_match_the_formulas_on_the_path_coordinates(values):
    path = path_of(values)
    t = np.linspace(0.0, path.run_s, 29)
    cyl_v, cyl_a, sph_v, sph_a = expected_components(path, t)
    for frame, exp_v, exp_a in (("cylindrical", cyl_v, cyl_a), ("spherical", sph_v, sph_a)):
        _, v, a, described = path.describe(frame, t)
        assert_close_to_scale(described.velocity, exp_v, ROUNDING)
        assert_close_to_scale(described.acceleration, exp_a, ROUNDING)
        # The components are the projections of the Cartesian v and a on the unit vectors …
        assert_close_to_scale(described.velocity, np.einsum("nkj,nj->nk", described.unit_vectors, v), ROUNDING)
        assert_close_to_scale(described.acceleration, np.einsum("nkj,nj->nk", described.unit_vectors, a), ROUNDING)
        # … so |v| and |a| from them are the Cartesian magnitudes.
        assert_close_to_scale(np.linalg.norm(described.velocity, axis=1), np.linalg.norm(v, axis=1), ROUNDING)
        assert_close_to_scale(np.linalg.norm(described.acceleration, axis=1), np.linalg.norm(a, axis=1), ROUNDING)
        # The unit vectors are orthonormal and right-handed.
        gram = np.einsum("nij,nkj->nik", described.unit_vectors, described.unit_vectors)
        assert np.max(np.abs(gram - np.eye(3))) < 1e-14
        assert np.linalg.det(described.unit_vectors) == pytest.approx(np.ones(len(t)), abs=1e-14)


def test_closed_forms_a_student_can_check_by_hand():
    a, w = 1.0, 1.0
    helix = path_of({"path": "helix", "size_m": a, "azimuth_rate_rad_s": w, "path_angle_deg": 15.0})
    *_, cyl = helix.describe("cylindrical", np.linspace(0.0, helix.run_s, 9))
    assert cyl.velocity == pytest.approx(np.tile([0.0, a * w, a * w * math.tan(math.radians(15.0))], (9, 1)), abs=1e-12)
    assert cyl.acceleration == pytest.approx(np.tile([-a * w**2, 0.0, 0.0], (9, 1)), abs=1e-12)
    spiral = path_of({"path": "conical-spiral", "size_m": 0.1 * math.pi, "azimuth_rate_rad_s": 2.0, "path_angle_deg": 40.0})
    *_, cyl = spiral.describe("cylindrical", np.linspace(0.0, spiral.run_s, 9))
    assert cyl.velocity[:, 0] == pytest.approx(np.full(9, 0.1), rel=1e-12)  # Ṙ = a θ̇ / 2π
    assert cyl.acceleration[:, 1] == pytest.approx(np.full(9, 0.4), rel=1e-12)  # 2 Ṙ θ̇, with θ̈ = 0
    beta = math.radians(50.0)
    circle = path_of({"path": "latitude-circle", "size_m": a, "azimuth_rate_rad_s": w, "path_angle_deg": 50.0})
    *_, sph = circle.describe("spherical", np.linspace(0.0, circle.run_s, 9))
    assert sph.acceleration[:, 0] == pytest.approx(np.full(9, -a * math.sin(beta) ** 2 * w**2), rel=1e-12)
    assert sph.acceleration[:, 1] == pytest.approx(np.full(9, -a * math.sin(beta) * math.cos(beta) * w**2), rel=1e-12)
    loxodrome = path_of({"path": "loxodrome", "size_m": a, "azimuth_rate_rad_s": w, "path_angle_deg": 75.0})
    *_, sph = loxodrome.describe("spherical", np.linspace(0.0, loxodrome.run_s, 9))
    # The bearing: every meridian is crossed at 75° from north, v_φ (south) / v_θ (east) = −cot β.
    assert sph.velocity[:, 1] / sph.velocity[:, 2] == pytest.approx(np.full(9, -1.0 / math.tan(math.radians(75.0))), rel=1e-12)
    assert sph.coordinates[[0, -1], 1] == pytest.approx([math.radians(170.0), math.radians(10.0)], rel=1e-12)  # latitude −80° to 80°


def test_on_the_polar_axis_the_description_is_undefined_not_garbage():
    pole = path_of({"path": "latitude-circle", "size_m": 1.0, "path_angle_deg": 0.0})
    *_, cyl = pole.describe("cylindrical", 0.0)
    assert np.all(np.isnan(cyl.unit_vectors[0, :2])) and cyl.unit_vectors[0, 2] == pytest.approx([0.0, 0.0, 1.0])
    assert np.isnan(cyl.velocity[0, 0]) and cyl.velocity[0, 2] == 0.0
    *_, sph = pole.describe("spherical", 0.0)
    assert sph.unit_vectors[0, 0] == pytest.approx([0.0, 0.0, 1.0]) and np.all(np.isnan(sph.unit_vectors[0, 1:]))


@pytest.mark.parametrize(("path", "beta"), [("loxodrome", 5.0), ("conical-spiral", 0.0), ("helix", 70.0)])
def test_a_path_angle_a_path_cannot_take_is_refused_naming_beta(path, beta):
    with pytest.raises(ParameterError) as caught:
        coordinate_paths.PARAMETERS.validate({"path": path, "path_angle_deg": beta})
    assert caught.value.field == "path_angle_deg" and "β" in str(caught.value)


def test_the_path_report_has_both_descriptions_and_finite_series():
    model = coordinate_paths.ParticleOnCoordinatePath()
    params = model.parameters.validate({"path": "loxodrome", "path_angle_deg": 75.0})
    report = model.simulate(params, {}, t_end_s=10.0, frame_rate_hz=20.0).as_dict()
    assert report["stats"]["status"] == "ok"
    assert report["series"]["r"] == pytest.approx([1.0] * len(report["t"]), rel=1e-12)
    assert report["series"]["v_r"] == pytest.approx([0.0] * len(report["t"]), abs=1e-12)


# -- 2.4 a collar on a rotating arm ---------------------------------------------------------------

ARM_CASES = [
    {},
    {"arm_rate_rad_s": -2.0, "arm_acceleration_rad_s2": 0.3, "collar_mean_m": -0.5, "collar_amplitude_m": 1.2, "collar_frequency_rad_s": 3.0},
    {"arm_rate_rad_s": 0.6, "collar_mean_m": 0.0, "collar_amplitude_m": 1.2, "collar_frequency_rad_s": 1.0},
]


def arm_position(params, t_s: np.ndarray) -> np.ndarray:
    """The collar's position written here from the two given motions: r(t) along the arm at angle θ(t)."""
    theta = params["arm_rate_rad_s"] * t_s + 0.5 * params["arm_acceleration_rad_s2"] * t_s**2
    r = params["collar_mean_m"] + params["collar_amplitude_m"] * np.sin(params["collar_frequency_rad_s"] * t_s)
    return np.stack([r * np.cos(theta), r * np.sin(theta), np.zeros_like(t_s)], axis=1)


@pytest.mark.parametrize("values", ARM_CASES)
def test_the_four_terms_add_up_to_the_acceleration_of_the_position(values):
    params = rotating_arm.PARAMETERS.validate(values)
    t = np.linspace(0.0, rotating_arm.RUN_S, 61)
    state = rotating_arm.RotatingArm.from_params(params).at(t)
    assert_close_to_scale(state.position_m, arm_position(params, t), 1e-15)
    first, second = five_point(lambda s: arm_position(params, s), t)
    assert_close_to_scale(state.velocity_m_s, first, FD_TOLERANCE)
    assert_close_to_scale(state.acceleration_m_s2, second, FD_TOLERANCE)
    terms = state.sliding_m_s2 + state.centripetal_m_s2, state.angular_m_s2 + state.coriolis_m_s2
    assert_close_to_scale(np.stack(terms, axis=1), np.stack([state.a_radial_m_s2, state.a_transverse_m_s2], axis=1), 1e-15)
    # Path variables from the same v and a: a_t² + a_n² = |a|².
    speed, a_t, a_n = state.path_variables()
    assert_close_to_scale(a_t**2 + a_n**2, np.sum(state.acceleration_m_s2**2, axis=1), 1e-12)


def test_the_coriolis_term_is_twice_the_sliding_speed_times_the_arm_rate():
    state = rotating_arm.RotatingArm(1.0, 0.0, 0.8, 0.6, 1.5).at(0.0)  # passing r₀ with ṙ = b ω_c = 0.9 m/s
    assert state.coriolis_m_s2[0] == pytest.approx(2 * 0.9 * 1.0, rel=1e-15)
    assert state.centripetal_m_s2[0] == pytest.approx(-0.8, rel=1e-15)
    assert state.sliding_m_s2[0] == 0.0 and state.angular_m_s2[0] == 0.0


def test_a_collar_that_would_leave_the_arm_is_refused():
    with pytest.raises(ParameterError) as caught:
        rotating_arm.PARAMETERS.validate({"collar_mean_m": 1.5, "collar_amplitude_m": 1.0})
    assert caught.value.field == "collar_amplitude_m" and "slide off the arm" in str(caught.value)
