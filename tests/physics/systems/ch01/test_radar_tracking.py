"""Worked Example 1.2 (app/physics/radar_tracking.py) against sympy's exact derivatives."""

from __future__ import annotations

import functools

import numpy as np
import pytest
import sympy as sp

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch01 import radar_tracking as radar

EPS = float(np.finfo(float).eps)


@functools.cache
def symbolic_position():
    """x(t), y(t), z(t) written from the problem statement, and the symbol t."""
    t = sp.symbols("t", positive=True)
    r = 2000 + 100 * t
    theta = sp.pi / 2 * (1 - sp.exp(-sp.Rational(15, 100) * t))
    beta = sp.pi / 3 - sp.Rational(1, 10) * sp.sqrt(t)
    return t, sp.Matrix([r * sp.cos(beta) * sp.cos(theta), r * sp.cos(beta) * sp.sin(theta), r * sp.sin(beta)])


def exact_derivative(order: int, t_s: float) -> np.ndarray:
    """d^order p / dt^order at t_s, evaluated by sympy at 30 digits."""
    t, p = symbolic_position()
    d = p.diff(t, order) if order else p
    t_exact = sp.Rational(repr(t_s))  # the double t_s written exactly as a decimal
    return np.array([float(c.subs(t, t_exact).evalf(30)) for c in d])


@pytest.mark.parametrize("t_s", [1.0, 2.0, 7.5, 30.0, 60.0])
def test_position_and_exact_velocity_match_sympy(t_s):
    # 1e-12 relative: closed forms in double precision (errors ~1e-15 relative) against
    # a 30-digit evaluation rounded to double.
    np.testing.assert_allclose(radar.position(t_s), exact_derivative(0, t_s), rtol=1e-12)
    np.testing.assert_allclose(radar.velocity_exact(t_s), exact_derivative(1, t_s), rtol=1e-12)


def test_range_is_the_length_of_the_position_vector():
    # r = 2000 + 100 t is the distance from the radar: 2200 m at 2 s. 1e-14 relative: a norm of
    # three products of numbers of size ~2e3, a few ulps.
    assert np.linalg.norm(radar.position(2.0)) == pytest.approx(2200.0, rel=1e-14)


def test_default_numbers_match_the_colleagues_hand_solution():
    out = radar.solve(radar.INPUTS.defaults()).outputs
    # Quoted to 6 significant figures: 1e-5 relative is one unit in the 6th figure.
    np.testing.assert_allclose(out["position_m"], [1246.60, 537.552, 1731.19], rtol=1e-5)
    np.testing.assert_allclose(out["velocity_exact_m_s"], [19.0374, 266.266, 30.6933], rtol=1e-5)
    # Quoted to 3 figures: 2e-3 relative.
    assert out["fd_error_m_s"] == pytest.approx(4.27e-6, rel=2e-3)
    # The error is |fd - exact| of the two reported vectors (1e-9 relative: the reported
    # error is that same norm; the vectors themselves are rounded only in the last ulp).
    diff = np.linalg.norm(np.asarray(out["velocity_fd_m_s"]) - np.asarray(out["velocity_exact_m_s"]))
    assert out["fd_error_m_s"] == pytest.approx(diff, rel=1e-9)


@pytest.mark.parametrize(("t_s", "h"), [(2.0, 1e-3), (20.0, 1e-2)])
def test_fd_error_equals_the_leading_truncation_term(t_s, h):
    # Central difference: v_fd - v = (h^2/6) p''' + O(h^4). h is chosen so that the truncation
    # term (4.3e-6 m/s at t = 2 s, h = 1 ms; 5.7e-6 m/s at t = 20 s, h = 10 ms) exceeds the
    # round-off eps|p|/h (5e-10 and 9e-11 m/s) by >= 1e4, and the h^4 term is ~h^2 ~ 1e-4 of it
    # or less; compare at 1e-3 of |error|, component by component.
    err = radar.velocity_central_difference(t_s, h) - radar.velocity_exact(t_s)
    np.testing.assert_allclose(err, h**2 / 6.0 * exact_derivative(3, t_s), rtol=0, atol=1e-3 * np.linalg.norm(err))


def test_fd_error_falls_as_dt_squared_in_the_truncation_range():
    t = 2.0
    v = radar.velocity_exact(t)
    hs = np.logspace(-2, -3, 5)  # 1e-2 ... 1e-3 s: truncation dominates round-off by >= 1e4
    for h in hs:
        e_h = np.linalg.norm(radar.velocity_central_difference(t, h) - v)
        e_half = np.linalg.norm(radar.velocity_central_difference(t, h / 2) - v)
        # Ratio 4 (1 + O(h^2)) plus round-off of <= ~1e-3 relative at h/2 = 5e-4 s
        # (eps*2200/5e-4 ~ 1e-9 m/s against an error ~1e-6 m/s); 5e-3 tolerance on the ratio.
        assert e_h / e_half == pytest.approx(4.0, rel=5e-3)


def test_error_sweep_has_the_truncation_round_off_shape():
    out = radar.solve({"t_s": 2.0, "dt_s": 1e-3}).outputs
    dt = np.asarray(out["error_sweep_dt_s"])
    err = np.asarray(out["error_sweep_m_s"])
    assert dt.min() == pytest.approx(1e-12) and dt.max() <= 2.0
    best = dt[np.argmin(err)]
    assert 1e-6 < best < 1e-4
    at = {d: err[np.argmin(abs(np.log(dt / d)))] for d in (1e-12, 1e-5)}
    assert at[1e-12] > at[1e-5]  # round-off grows as dt shrinks
    # The sweep is recomputed independently here at its own dt values (same t): equal to rounding.
    v = radar.velocity_exact(2.0)
    mine = [np.linalg.norm(radar.velocity_central_difference(2.0, d) - v) for d in dt[::12]]
    np.testing.assert_allclose(err[::12], mine, rtol=1e-12)


def test_optimal_dt_matches_the_error_model_with_the_exact_third_derivative():
    # Model: minimise (h^2/6)|p'''| + eps|p|/h  ->  h* = (3 eps |p| / |p'''|)^(1/3).
    t = 2.0
    out = radar.solve({"t_s": t, "dt_s": 1e-3}).outputs
    p3 = np.linalg.norm(exact_derivative(3, t))
    expected = (3.0 * EPS * 2200.0 / p3) ** (1.0 / 3.0)
    assert expected == pytest.approx(3.85e-5, rel=2e-3)  # the colleague's figure, 3 s.f.
    # The module estimates p''' by a 10 ms central difference of the exact velocity: relative
    # error O(h^2) ~ 1e-4 in p''', a third of that in h*; 1e-3 relative leaves margin.
    assert out["optimal_dt_s"] == pytest.approx(expected, rel=1e-3)


def test_dt_longer_than_t_is_refused_naming_dt():
    with pytest.raises(ValueError, match="dt_s"):
        radar.velocity_central_difference(1.0, 1.5)
    # Through the parameter set the same rule is a ParameterError on dt_s. With the current
    # ranges (t_s >= 1, dt_s <= 1) it can only be reached by the check, so call the check.
    with pytest.raises(ParameterError) as info:
        radar.INPUTS.check({"t_s": 1.0, "dt_s": 1.5})
    assert info.value.field == "dt_s"
    # dt_s = t_s is the allowed edge (t - dt = 0 is still inside the elevation formula's domain).
    assert radar.INPUTS.validate({"t_s": 1.0, "dt_s": 1.0}) == {"t_s": 1.0, "dt_s": 1.0}
    assert np.all(np.isfinite(radar.velocity_central_difference(1.0, 1.0)))


@pytest.mark.parametrize("bad", [0.0, 2.0, -1e-3])
def test_dt_outside_its_range_is_refused(bad):
    with pytest.raises(ParameterError) as info:
        radar.INPUTS.validate({"dt_s": bad})
    assert info.value.field == "dt_s"
    assert "between 1e-12 and 1 s" in info.value.message


def radar_axes(t_s: float) -> np.ndarray:
    """Rows e_r (line of sight), e_theta (azimuth growing), e_beta (elevation growing), written from θ and β."""
    _, theta, beta = (float(v) for v in radar.radar_measurements(t_s))
    ct, st, cb, sb = np.cos(theta), np.sin(theta), np.cos(beta), np.sin(beta)
    return np.array([[cb * ct, cb * st, sb], [-st, ct, 0.0], [-sb * ct, -sb * st, cb]])


@pytest.mark.parametrize("t_s", [0.25, 2.0, 7.5, 30.0, 60.0])
def test_radar_frame_velocity_and_acceleration_are_sympys_derivatives_on_the_radar_axes(t_s):
    # The textbook formulas in r, θ, β and their rates against sympy's 30-digit first and second derivatives of
    # the xyz position, projected on the radar's axes. 1e-12 of the vector's length: double-precision closed forms
    # (a few ulps, ~1e-15 relative) with margin; a wrong sign or a missing Coriolis term 2ṙθ̇ is off by percent.
    axes = radar_axes(t_s)
    velocity, acceleration = exact_derivative(1, t_s), exact_derivative(2, t_s)
    np.testing.assert_allclose(radar.velocity_radar_components(t_s), axes @ velocity, rtol=0, atol=1e-12 * np.linalg.norm(velocity))
    np.testing.assert_allclose(
        radar.acceleration_radar_components(t_s), axes @ acceleration, rtol=0, atol=1e-12 * np.linalg.norm(acceleration)
    )
    # The radar sees r̈ = 0, yet the line-of-sight acceleration is not zero: −r β̇² − r cos²β θ̇² < 0.
    assert radar.radar_second_rates(t_s)[0] == 0.0 and radar.acceleration_radar_components(t_s)[0] < 0.0


def test_rates_at_the_first_instant_say_the_elevation_rate_is_infinite():
    assert radar.radar_rates(0.0)[2] == -np.inf and np.isfinite(radar.radar_rates(0.0)[:2]).all()
    for components in (radar.velocity_radar_components, radar.acceleration_radar_components):
        with pytest.raises(ValueError, match="infinite at t = 0"):
            components(0.0)
