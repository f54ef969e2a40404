"""Observations from the rotating Earth: the Foucault pendulum and the eastward deflection of a falling body.

References are independent of the code under test: the measured swing plane
comes from the bob's turning points (geometry only), the falling body is
integrated with scipy's DOP853 at rtol = atol = 1e-12 and checked against a
matrix exponential, and the textbook first- and second-order formulas are
written out here.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.linalg import expm

from app.physics.core.parameters import ParameterError
from app.physics.systems import earth
from app.physics.systems.ch03 import eastward_deflection as deflection
from app.physics.systems.ch03 import foucault_pendulum as foucault

MODEL = foucault.FoucaultPendulum()


def run_pendulum(overrides: dict, *, t_end_s: float, frame_rate_hz: float = 240.0, method: str = "rk4", **controls):
    params = foucault.PARAMETERS.validate(overrides)
    report = MODEL.simulate(params, {"method": method, **controls}, t_end_s=t_end_s, frame_rate_hz=frame_rate_hz, request_limits=False)
    assert report.status == "ok", report.message
    return params, report


def measured_clockwise_rate(report) -> float:
    tracker = foucault.apex_bearings(report.t_s, report.series["bob_east"], report.series["bob_north"])
    assert tracker.count >= 30
    return tracker.clockwise_rate_rad_s()


# -- the Earth's frame -------------------------------------------------------------------------
def test_earth_rate_in_the_local_frame_points_north_and_up():
    omega = earth.earth_rate_local(30.0)
    assert np.linalg.norm(omega) == pytest.approx(earth.EARTH_RATE_RAD_S, rel=1e-15)
    np.testing.assert_allclose(omega, earth.EARTH_RATE_RAD_S * np.array([0.0, math.cos(math.pi / 6), 0.5]), rtol=1e-15)
    assert earth.vertical_earth_rate_rad_s(-30.0) == pytest.approx(-0.5 * earth.EARTH_RATE_RAD_S, rel=1e-15)


def test_coriolis_pushes_a_moving_body_to_the_right_in_the_north_and_left_in_the_south():
    north = np.array([0.0, 10.0, 0.0])  # moving north at 10 m/s
    assert earth.coriolis_acceleration(earth.earth_rate_local(45.0), north)[0] > 0.0  # pushed east: to its right
    assert earth.coriolis_acceleration(earth.earth_rate_local(-45.0), north)[0] < 0.0  # pushed west: to its left


# -- Foucault pendulum -------------------------------------------------------------------------
@pytest.mark.parametrize("latitude_deg", [90.0, 75.0, 48.85, 20.0, -45.0])
def test_swing_plane_turns_at_omega_sin_latitude(latitude_deg):
    """Small swing (a/L = 0.01), Earth rate ×1000, 120 s (37 turning points) at 240 frames/s.

    Tolerance 2e-4 relative: the finite swing's own turning (Airy) makes the
    plane lag Ω sin λ by ⅜ (a/L)² = 3.75e-5, and the turning-point bearings, read
    at the sampled frame nearest each apex, scatter by less than 1e-5 of the rate.
    """
    params, report = run_pendulum({"amplitude_m": 0.1, "latitude_deg": latitude_deg}, t_end_s=120.0)
    expected = foucault.clockwise_precession_rate_rad_s(params)
    assert expected == pytest.approx(earth.EARTH_RATE_RAD_S * 1000.0 * math.sin(math.radians(latitude_deg)), rel=1e-15)
    assert measured_clockwise_rate(report) == pytest.approx(expected, rel=2e-4)


def test_hemisphere_decides_the_sense_and_the_equator_has_none():
    rates = {}
    for latitude in (45.0, 0.0, -45.0):
        _, report = run_pendulum({"amplitude_m": 0.1, "latitude_deg": latitude}, t_end_s=120.0)
        rates[latitude] = measured_clockwise_rate(report)
    scale = earth.EARTH_RATE_RAD_S * 1000.0 * math.sin(math.radians(45.0))
    assert rates[45.0] > 0.99 * scale  # clockwise seen from above in the north
    assert rates[-45.0] < -0.99 * scale  # counterclockwise in the south
    assert abs(rates[0.0]) < 1e-6 * scale  # Ω is horizontal at the equator: the plane does not turn


def test_finite_swing_lag_follows_airys_correction():
    """a/L = 0.2 released from rest: the plane lags Ω sin λ by ⅜ (a/L)² = 1.5 %.

    Airy's ⅜ h_z/L² is the leading term of an expansion in (a/L)²; at a/L = 0.2
    the measured lag differs from it by 0.28 % of the lag (a higher-order term),
    so the tolerance is 0.5 % of the lag, and a check that the lag is really
    there. Pushed through the centre the bob has no angular momentum about the
    vertical and there is no lag at that order (measured 1.3e-4 of Ω sin λ;
    tolerance 5e-4)."""
    params, report = run_pendulum({"amplitude_m": 2.0}, t_end_s=120.0)
    omega_z = foucault.clockwise_precession_rate_rad_s(params)
    expected = foucault.expected_clockwise_rate_rad_s(params)
    assert 1.0 - expected / omega_z == pytest.approx(0.375 * 0.2**2, rel=1e-12)
    measured = measured_clockwise_rate(report)
    assert abs(measured - expected) < 5e-3 * (omega_z - expected)
    assert abs(measured - omega_z) > 0.9 * (omega_z - expected)  # the lag is really there
    params, report = run_pendulum({"amplitude_m": 2.0, "release": "from the centre"}, t_end_s=120.0)
    assert foucault.expected_clockwise_rate_rad_s(params) == omega_z
    assert measured_clockwise_rate(report) == pytest.approx(omega_z, rel=5e-4)


def test_real_earth_rate_in_paris_is_about_eleven_degrees_an_hour():
    """No exaggeration, a 67 m pendulum, one hour: Ω sin λ = 11.33°/h; Airy lag ⅜(1/67)² = 8e-5; tolerance 3e-4."""
    params, report = run_pendulum(
        {"latitude_deg": 48.85, "earth_rate_factor": 1.0, "length_m": 67.0, "amplitude_m": 1.0}, t_end_s=3600.0, frame_rate_hz=30.0
    )
    deg_per_hour = math.degrees(measured_clockwise_rate(report)) * 3600.0
    assert math.degrees(earth.vertical_earth_rate_rad_s(48.85)) * 3600.0 == pytest.approx(11.3258, abs=1e-4)
    assert deg_per_hour == pytest.approx(11.3258, rel=3e-4)


def test_swing_plane_series_agrees_with_the_turning_points():
    """The per-frame swing-plane bearing (principal axis of ω'² r rᵀ + w wᵀ) equals the apex bearings to 0.05°."""
    params, report = run_pendulum({"amplitude_m": 0.5}, t_end_s=60.0)
    tracker = foucault.apex_bearings(report.t_s, report.series["bob_east"], report.series["bob_north"])
    series = np.interp(tracker.times_s, report.t_s, report.series["swing_plane_bearing"])
    apex = np.degrees(tracker.bearings_rad)
    offset = 180.0 * np.round((series - apex) / 180.0)
    assert np.max(np.abs(series - offset - apex)) < 0.05


def test_jacobi_integral_is_conserved_in_the_rotating_frame():
    """½|v|² + g z has no source: the Coriolis force is perpendicular to v and the string to the path.

    Over 600 s at the live scene's 30 frames/s: RK4 with the automatic step
    (h·ω ≤ 0.1) keeps it to 1e-6 of the swing energy (measured 3.4e-7), the
    adaptive method at rtol 1e-10 to 1e-7 (measured 5e-9); the string length stays
    exact to round-off through the projection.
    """
    params, report = run_pendulum({}, t_end_s=600.0, frame_rate_hz=30.0)
    assert report.max_invariant_drift < 1e-6
    assert np.max(np.abs(report.invariants["string_length_error"])) < 1e-12 * params["length_m"]
    _, adaptive = run_pendulum({}, t_end_s=600.0, frame_rate_hz=30.0, method="dopri5", rtol=1e-10)
    assert adaptive.max_invariant_drift < 1e-7


def reference_pendulum(params, t_s: np.ndarray) -> np.ndarray:
    """The same physics written independently (vector form) and integrated by scipy DOP853 at 1e-12."""
    g, L = params["g_m_s2"], params["length_m"]
    omega = foucault.earth_rate_vector(params)
    pivot = np.array([0.0, 0.0, L])

    def rhs(_t, y):
        r, v = y[:3], y[3:]
        u = r - pivot
        free = np.array([0.0, 0.0, -g]) - 2.0 * np.cross(omega, v)
        tension = -(u @ free + v @ v) / (u @ u)  # keeps d²|u|²/dt² = 0
        return np.concatenate([v, free + tension * u])

    solution = solve_ivp(rhs, (0.0, t_s[-1]), foucault.initial_state(params), method="DOP853", rtol=1e-12, atol=1e-12, t_eval=t_s)
    return solution.y.T


def test_integrated_pendulum_matches_a_tight_scipy_reference():
    """30 s, a/L = 0.1: RK4 (automatic step, 1 step per 1/30 s frame) to 1e-5 of the amplitude — its phase
    error (hω)⁴ ω t / 120 ≈ 3e-7 rad per second of swing times 30 s — and dopri5 at rtol 1e-10 to 1e-7."""
    params, report = run_pendulum({"amplitude_m": 1.0}, t_end_s=30.0, frame_rate_hz=30.0)
    reference = reference_pendulum(params, report.t_s)
    ours = np.column_stack([report.series["bob_east"], report.series["bob_north"], report.series["bob_up"]])
    assert np.max(np.linalg.norm(ours - reference[:, :3], axis=1)) < 1e-5 * params["amplitude_m"]
    _, adaptive = run_pendulum({"amplitude_m": 1.0}, t_end_s=30.0, frame_rate_hz=30.0, method="dopri5", rtol=1e-10)
    ours = np.column_stack([adaptive.series["bob_east"], adaptive.series["bob_north"], adaptive.series["bob_up"]])
    assert np.max(np.linalg.norm(ours - reference[:, :3], axis=1)) < 1e-7 * params["amplitude_m"]


def test_small_swing_follows_the_linearised_closed_form():
    """a/L = 1e-3, Earth rate ×1000, 60 s, dopri5 at rtol 1e-12 (so integration error is below 1e-9 of a).

    The closed form e^{−iΩ_z t}(A e^{iω't} + B e^{−iω't}) drops effects of relative
    size a/L: the period's growth with amplitude (a phase error ω₀ t (a/L)²/16 ≈
    4e-6) and the coupling of the horizontal part of Ω with the swing's small
    vertical motion, which grows in proportion to a (2e-5 measured here, 1e-5 at
    half the amplitude). Tolerance 1e-4 of the amplitude = 0.1 a/L.
    """
    params, report = run_pendulum({"amplitude_m": 0.01}, t_end_s=60.0, frame_rate_hz=30.0, method="dopri5", rtol=1e-12)
    closed = foucault.small_amplitude_solution(params, report.t_s)
    error = np.hypot(report.series["bob_east"] - closed[:, 0], report.series["bob_north"] - closed[:, 1])
    assert np.max(error) < 1e-4 * params["amplitude_m"]
    # The comparison is not vacuous: without the Earth's rotation the closed form is off by the whole turning.
    still = foucault.small_amplitude_solution({**params, "earth_rate_factor": 1e-12}, report.t_s)
    assert np.max(np.hypot(report.series["bob_east"] - still[:, 0], report.series["bob_north"] - still[:, 1])) > 0.5 * params["amplitude_m"]


def test_amplitude_longer_than_the_string_allows_is_refused():
    with pytest.raises(ParameterError) as info:
        foucault.PARAMETERS.validate({"length_m": 2.0, "amplitude_m": 1.9})
    assert info.value.field == "amplitude_m"


def test_apex_tracker_reads_a_known_turning_ellipse():
    """A synthetic path turning clockwise at exactly 0.05 rad/s: the tracker reports 0.05 rad/s (to 1e-9)."""
    t = np.arange(0.0, 100.0, 1.0 / 240.0)
    bearing = math.radians(30.0) + 0.05 * t  # clockwise from north
    swing = 2.0 * np.cos(1.3 * t)
    east, north = swing * np.sin(bearing), swing * np.cos(bearing)
    tracker = foucault.apex_bearings(t, east, north)
    assert tracker.clockwise_rate_rad_s() == pytest.approx(0.05, rel=1e-4)


# -- eastward deflection ------------------------------------------------------------------------
def reference_flight(params, t_end_s: float, *, omega=None) -> np.ndarray:
    """``r̈ = −g Z − 2 Ω × ṙ`` integrated by scipy DOP853 at rtol = atol = 1e-12; state at t_end."""
    omega = earth.earth_rate_local(params["latitude_deg"]) if omega is None else omega
    gravity = np.array([0.0, 0.0, -params["g_m_s2"]])

    def rhs(_t, y):
        return np.concatenate([y[3:], gravity - 2.0 * np.cross(omega, y[3:])])

    y0 = np.concatenate([[0.0, 0.0, params["height_m"]], params["launch_velocity_m_s"]])
    return solve_ivp(rhs, (0.0, t_end_s), y0, method="DOP853", rtol=1e-12, atol=1e-12).y[:, -1]


def random_flights(count: int):
    rng = np.random.default_rng(7)
    for _ in range(count):
        yield deflection.PARAMETERS.validate(
            {
                "height_m": float(10 ** rng.uniform(0.0, math.log10(2000.0))),
                "latitude_deg": float(rng.uniform(-90.0, 90.0)),
                "launch_velocity_m_s": [float(v) for v in rng.uniform(-30.0, 30.0, 3)],
                "g_m_s2": float(rng.uniform(1.0, 30.0)),
            }
        )


def test_exact_flight_matches_tight_numerical_integration():
    """Random heights, latitudes, throws and g: positions agree with DOP853 (1e-12) to 1e-11 of the flight's size.

    DOP853 at rtol = atol = 1e-12 is accurate to about 1e-12 relative on these
    smooth flights (the difference measured was 1.5e-15); the exact form is good
    to round-off, so 1e-11 leaves a margin without hiding the southward
    second-order part, which is ~1e-7 of the height.
    """
    for params in random_flights(25):
        flight = deflection.Flight.from_params(params)
        t_end = flight.landing_time_s()
        reference = reference_flight(params, t_end)
        position, velocity = flight.state(np.array([t_end]))
        size = params["height_m"] + np.linalg.norm(params["launch_velocity_m_s"]) * t_end
        assert np.linalg.norm(position[0] - reference[:3]) < 1e-11 * size, params
        assert np.linalg.norm(velocity[0] - reference[3:]) < 1e-11 * (size / t_end), params
        assert abs(position[0, 2]) < 1e-9 * size  # the landing time puts it on the ground


def test_exact_flight_matches_the_matrix_exponential():
    """The linear system d/dt [r, v, 1] = M [r, v, 1] solved by scipy.linalg.expm (independent of the Rodrigues form),
    with the Earth rate ×1000 so the rotation terms are large: agreement to 1e-12 of the height."""
    params = deflection.PARAMETERS.validate({"height_m": 500.0, "latitude_deg": 35.0, "launch_velocity_m_s": [5.0, -3.0, 12.0]})
    omega = earth.earth_rate_local(35.0, 1000.0 * earth.EARTH_RATE_RAD_S)
    skew = np.array([[0.0, -omega[2], omega[1]], [omega[2], 0.0, -omega[0]], [-omega[1], omega[0], 0.0]])
    M = np.zeros((7, 7))
    M[0:3, 3:6] = np.eye(3)
    M[3:6, 3:6] = -2.0 * skew
    M[3:6, 6] = [0.0, 0.0, -params["g_m_s2"]]
    y0 = np.array([0.0, 0.0, 500.0, 5.0, -3.0, 12.0, 1.0])
    flight = deflection.Flight.from_params(params, earth_rate_rad_s=1000.0 * earth.EARTH_RATE_RAD_S)
    for t in (0.3, 2.0, 7.5):
        exact = expm(M * t) @ y0
        position, velocity = flight.state(np.array([t]))
        assert np.linalg.norm(position[0] - exact[:3]) < 1e-12 * 500.0
        assert np.linalg.norm(velocity[0] - exact[3:6]) < 1e-12 * 500.0


@pytest.mark.parametrize("height_m, latitude_deg", [(100.0, 45.0), (158.0, 50.9), (1000.0, 10.0), (30.0, -60.0)])
def test_drop_lands_east_by_a_third_omega_g_t_cubed_cos_latitude(height_m, latitude_deg):
    """East = ⅓ Ω g t³ cos λ and south = ⅙ Ω² g t⁴ sin λ cos λ (t = √(2h/g)) to relative 1e-6: the east part has
    only odd powers of Ω and the south part only even ones (Ω → −Ω mirrors the fall), so the first neglected terms are
    (Ω t)² ≤ 2e-7 relative, and the landing time's shift is itself second order."""
    g = earth.STANDARD_GRAVITY_M_S2
    params = deflection.PARAMETERS.validate({"height_m": height_m, "latitude_deg": latitude_deg})
    flight = deflection.Flight.from_params(params)
    t = math.sqrt(2.0 * height_m / g)
    lam = math.radians(latitude_deg)
    east = earth.EARTH_RATE_RAD_S * g * t**3 * math.cos(lam) / 3.0
    south = earth.EARTH_RATE_RAD_S**2 * g * t**4 * math.sin(lam) * math.cos(lam) / 6.0
    exact = flight.deflection()
    assert exact[0] == pytest.approx(east, rel=1e-6)
    assert -exact[1] == pytest.approx(south, rel=1e-6)
    assert deflection.drop_east_deflection_first_order_m(height_m=height_m, latitude_deg=latitude_deg, g_m_s2=g) == pytest.approx(east, rel=1e-14)
    assert deflection.drop_south_deflection_second_order_m(height_m=height_m, latitude_deg=latitude_deg, g_m_s2=g) == pytest.approx(south, rel=1e-14)
    if height_m == 100.0:
        assert 1000.0 * exact[0] == pytest.approx(15.52, abs=0.01)  # the number quoted in the lesson


def test_series_error_shrinks_with_the_next_power_of_omega():
    """At a fixed time, exact − series(order n) is O(Ω^{n+1}): doubling Ω multiplies it by 2^{n+1} (±5 %)."""
    params = deflection.PARAMETERS.validate({"height_m": 300.0, "latitude_deg": 40.0, "launch_velocity_m_s": [3.0, 4.0, 5.0]})
    t = np.array([6.0])
    errors = {}
    for factor in (100.0, 200.0):
        flight = deflection.Flight.from_params(params, earth_rate_rad_s=factor * earth.EARTH_RATE_RAD_S)
        exact = flight.state(t)[0][0]
        errors[factor] = [float(np.linalg.norm(exact - flight.series(t, order=n)[0])) for n in (0, 1, 2)]
    for n in (0, 1, 2):
        assert errors[200.0][n] / errors[100.0][n] == pytest.approx(2.0 ** (n + 1), rel=0.05)


def test_thrown_straight_up_lands_west():
    """From (nearly) the ground at speed u: lands (4/3) Ω cos λ u³/g² west (to first order in Ω).

    Released 1 m up, the flight lasts 0.3 % longer than 2u/g, but the first-order
    deflection Ω cos λ (g t³/3 − u t²) is stationary at t = 2u/g, so it changes
    only by ~(0.003)² ≈ 1e-5; the second-order terms are ~Ω t ≈ 6e-4 of it and act
    north–south. Tolerance 1e-4 (measured 2.8e-5).
    """
    u, lam = 40.0, math.radians(45.0)
    params = deflection.PARAMETERS.validate({"height_m": 1.0, "latitude_deg": 45.0, "launch_velocity_m_s": [0.0, 0.0, u]})
    west = 4.0 / 3.0 * earth.EARTH_RATE_RAD_S * math.cos(lam) * u**3 / earth.STANDARD_GRAVITY_M_S2**2
    exact = deflection.Flight.from_params(params).deflection()
    assert -exact[0] == pytest.approx(west, rel=1e-4)


def test_jacobi_integral_of_the_exact_flight_is_constant():
    params = deflection.PARAMETERS.validate({"height_m": 800.0, "launch_velocity_m_s": [20.0, -10.0, 30.0]})
    solution = deflection.EastwardDeflection().evaluate(params, np.linspace(0.0, 10.0, 101))
    jacobi = solution.invariants["jacobi_integral"]
    assert np.max(np.abs(jacobi - jacobi[0])) < 1e-12 * abs(jacobi[0])
