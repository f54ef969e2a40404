"""Heavy-top quadrature solution (app/physics/models/heavy_top_quadrature.py) against a tight integration.

The reference integrates q_world_body and the body angular velocity with Euler's
equations and the gravity torque (written out here, independent of the module and of
the app's integrators) by DOP853 at rtol = atol = 1e-12. Over the 4 nutation periods
used below that integration agrees with the quadrature solution to ≤ 2e-11 rad
(measured; tightening it to rtol 3e-14 brings the two closer, so the residual is the
integrator's); the tests allow 1e-9 rad. A wrong sign or a missing term in φ̇ or ψ̇,
a period off by 1e-6, or a mis-phased start are all ≥ 1e-6 rad away.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from app.physics.math.rotations import (
    body_rates_from_euler_313_rates,
    euler_313_from_quaternion,
    quaternion_conjugate,
    quaternion_from_axis_angle,
    quaternion_from_euler_313,
    quaternion_multiply,
    rotate_vector,
    rotation_matrix,
)
from app.physics.systems.ch10.heavy_top_quadrature import critical_spin_rad_s, heavy_top_quadrature

# The app's heavy-top scene defaults: m = 1 kg, l = 0.05 m, g = 9.807 m/s².
TOP = dict(I_transverse=0.0125, I_axial=0.01, mgl=1.0 * 9.807 * 0.05)
E3 = np.array([0.0, 0.0, 1.0])
TOL_RAD = 1e-9


def reference_rhs(t, y, I_transverse, I_axial, mgl):
    """y = [q_world_body (wxyz), ω_body]; I ω̇ = (I ω) × ω + τ, τ = l e3 × (−m g Z_body)."""
    q, omega = y[:4], y[4:]
    inertia = np.array([I_transverse, I_transverse, I_axial])
    z_body = rotation_matrix(q)[2]  # world Z in body components (row 3 of R)
    torque = -mgl * np.cross(E3, z_body)
    omega_dot = (np.cross(inertia * omega, omega) + torque) / inertia
    q_dot = 0.5 * quaternion_multiply(q, np.concatenate([[0.0], omega]))
    return np.concatenate([q_dot, omega_dot])


def initial_state(top):
    psi_dot0 = top.spin_rad_s - top.phi_dot0 * math.cos(top.theta0_rad)
    omega0 = body_rates_from_euler_313_rates(top.theta0_rad, top.psi0, top.phi_dot0, top.theta_dot0, psi_dot0)
    return np.concatenate([quaternion_from_euler_313(top.phi0, top.theta0_rad, top.psi0), omega0])


def integrate(top, t_end, **kwargs):
    return solve_ivp(
        reference_rhs, (0.0, t_end), initial_state(top), method="DOP853", rtol=1e-12, atol=1e-12,
        args=(top.I_transverse, top.I_axial, top.mgl), **kwargs,
    )


def attitude_error_rad(q, q_ref):
    d = quaternion_multiply(quaternion_conjugate(q), q_ref)
    return 2.0 * np.arcsin(np.minimum(1.0, np.linalg.norm(d[..., 1:], axis=-1)))


def angle_between(a, b):
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=-1), np.sum(a * b, axis=-1))


CASES = {
    # Scene-like fast top, started with nutation and precession rates and nonzero φ0, ψ0.
    "fast-top": dict(spin_rad_s=60.0, theta0_rad=math.radians(30), phi_dot0=0.8, theta_dot0=-1.5, phi0=0.3, psi0=-0.7),
    # Slow top, large nutation (m ≈ 0.18), θ̇0 > 0 and φ̇0 < 0 (looping precession).
    "large-nutation": dict(spin_rad_s=20.0, theta0_rad=math.radians(60), phi_dot0=-2.0, theta_dot0=3.0),
    # Axis below the horizontal, negative spin.
    "below-horizontal": dict(spin_rad_s=-10.0, theta0_rad=math.radians(120), phi_dot0=1.0, theta_dot0=0.5),
}


@pytest.mark.parametrize("name", CASES)
def test_angles_and_axis_match_a_tight_integration_over_four_nutation_periods(name):
    top = heavy_top_quadrature(**TOP, **CASES[name])
    t = np.linspace(0.0, 4.0 * top.nutation_period_s, 801)
    q_ref = integrate(top, t[-1], t_eval=t).y[:4].T
    axis_ref = rotate_vector(q_ref, E3)
    euler_ref = euler_313_from_quaternion(q_ref)
    # Reference φ, ψ unwrapped (θ stays ≥ 0.4 rad here, far from the gimbal lock); same branch at t = 0.
    phi_ref = np.unwrap(euler_ref[:, 0])
    psi_ref = np.unwrap(euler_ref[:, 2])
    phi_ref += 2.0 * math.pi * round((top.phi0 - phi_ref[0]) / (2.0 * math.pi))
    psi_ref += 2.0 * math.pi * round((top.psi0 - psi_ref[0]) / (2.0 * math.pi))

    assert np.abs(top.theta(t) - euler_ref[:, 1]).max() < TOL_RAD
    assert np.abs(top.phi(t) - phi_ref).max() < TOL_RAD
    assert np.abs(top.psi(t) - psi_ref).max() < TOL_RAD
    assert angle_between(top.symmetry_axis(t), axis_ref).max() < TOL_RAD
    assert attitude_error_rad(top.quaternion(t), q_ref).max() < TOL_RAD
    # φ advances by the mean precession rate per period (the module sums whole periods exactly).
    T = top.nutation_period_s
    assert top.phi(np.array(3.0 * T + 0.1)) - top.phi(np.array(0.1)) == pytest.approx(3.0 * T * top.mean_precession_rate_rad_s, abs=1e-11)


def test_tolerance_detects_a_one_ppm_change_of_the_gravity_moment():
    # The same comparison against a top with mgl 1 ppm larger fails by a wide margin (measured:
    # 3.6e-6 rad against 1.6e-11 rad for the right top), so TOL_RAD is a meaningful bar.
    case = CASES["large-nutation"]
    top = heavy_top_quadrature(**TOP, **case)
    wrong = heavy_top_quadrature(**{**TOP, "mgl": TOP["mgl"] * (1.0 + 1e-6)}, **case)
    t = np.linspace(0.0, 4.0 * top.nutation_period_s, 201)
    q_ref = integrate(top, t[-1], t_eval=t).y[:4].T
    assert attitude_error_rad(top.quaternion(t), q_ref).max() < TOL_RAD
    assert attitude_error_rad(wrong.quaternion(t), q_ref).max() > 100 * TOL_RAD


def test_tilt_extremes_and_nutation_period_match_the_integrations_turning_points():
    # Turning points of u = cos θ = Z·(R e3): u̇ = Z_body·(ω × e3) = 0. Rising crossings are
    # minima of u (maxima of θ). Measured: extremes agree to 3e-12 rad, periods to 2e-13 s.
    top = heavy_top_quadrature(**TOP, **CASES["large-nutation"])

    def theta_max(t, y, *args):  # u̇ rising through zero: u minimal, θ maximal
        return float(np.dot(rotation_matrix(y[:4])[2], np.cross(y[4:], E3)))

    def theta_min(t, y, *args):
        return theta_max(t, y)

    theta_max.direction, theta_min.direction = 1.0, -1.0
    sol = integrate(top, 3.2 * top.nutation_period_s, events=[theta_max, theta_min])
    tilts = [np.array([math.acos(rotation_matrix(y[:4])[2, 2]) for y in ys]) for ys in sol.y_events]
    assert len(sol.t_events[0]) == 3 and len(sol.t_events[1]) >= 3
    assert np.abs(tilts[0] - top.theta_max_rad).max() < 1e-9
    assert np.abs(tilts[1] - top.theta_min_rad).max() < 1e-9
    assert np.abs(np.diff(sol.t_events[0]) - top.nutation_period_s).max() < 1e-9
    assert np.abs(np.diff(sol.t_events[1]) - top.nutation_period_s).max() < 1e-9
    # The quadrature solution reaches the same extremes at the same instants.
    for times, tilt in zip(sol.t_events, tilts):
        assert np.abs(top.theta(times) - tilt).max() < 1e-9


def test_roots_conserved_quantities_and_the_cubic():
    case = CASES["fast-top"]
    top = heavy_top_quadrature(**TOP, **case)
    It, Ia, mgl = TOP["I_transverse"], TOP["I_axial"], TOP["mgl"]
    th0, w3 = case["theta0_rad"], case["spin_rad_s"]
    # p_ψ = I_a ω3, p_φ = I_t φ̇ sin²θ + I_a ω3 cos θ, E = ½I_t(θ̇² + φ̇² sin²θ) + ½I_a ω3² + mgl cos θ.
    assert top.p_psi == pytest.approx(Ia * w3, rel=1e-15, abs=0)
    assert top.p_phi == pytest.approx(It * case["phi_dot0"] * math.sin(th0) ** 2 + Ia * w3 * math.cos(th0), rel=1e-14, abs=0)
    kinetic = 0.5 * It * (case["theta_dot0"] ** 2 + case["phi_dot0"] ** 2 * math.sin(th0) ** 2) + 0.5 * Ia * w3**2
    assert top.energy_J == pytest.approx(kinetic + mgl * math.cos(th0), rel=1e-14, abs=0)
    # The roots solve the cubic in its textbook form and bracket cos θ0.
    alpha, beta = 2.0 * (top.energy_J - 0.5 * Ia * w3**2) / It, 2.0 * mgl / It
    b, c = top.p_phi / It, top.p_psi / It

    def f(u):
        return (1.0 - u * u) * (alpha - beta * u) - (b - c * u) ** 2

    def term_sum(u):  # sum of |terms| of β u³ − (α + c²) u² + (2bc − β) u + α − b²: the rounding scale of f
        return beta * abs(u) ** 3 + (abs(alpha) + c * c) * u * u + abs(2 * b * c - beta) * abs(u) + abs(alpha - b * b)

    for u in (top.u1, top.u2, top.u3):
        assert abs(f(u)) < 1e-14 * term_sum(u)
    scale = term_sum(1.0)
    assert -1.0 <= top.u1 <= math.cos(th0) <= top.u2 <= 1.0 <= top.u3
    assert top.theta_max_rad == pytest.approx(math.acos(top.u1), abs=1e-13)
    assert top.theta_min_rad == pytest.approx(math.acos(top.u2), abs=1e-13)

    # Along the solution: E and p_φ from the angle rates (4th-order central differences, h = 1e-4 s,
    # truncation ~1e-10 relative) equal the initial values; u̇² = f(u).
    t = np.linspace(0.0, 3.0 * top.nutation_period_s, 97)
    h = 1e-4

    def rate(fn):
        return (8.0 * (fn(t + h) - fn(t - h)) - (fn(t + 2 * h) - fn(t - 2 * h))) / (12.0 * h)

    theta, phi_dot, theta_dot = top.theta(t), rate(top.phi), rate(top.theta)
    p_phi = It * phi_dot * np.sin(theta) ** 2 + Ia * w3 * np.cos(theta)
    energy = 0.5 * It * (theta_dot**2 + phi_dot**2 * np.sin(theta) ** 2) + 0.5 * Ia * w3**2 + mgl * np.cos(theta)
    assert np.abs(p_phi - top.p_phi).max() < 1e-9 * abs(top.p_psi)
    assert np.abs(energy - top.energy_J).max() < 1e-9 * 0.5 * Ia * w3**2
    u_dot = -np.sin(theta) * theta_dot
    assert np.abs(u_dot**2 - f(np.cos(theta))).max() < 1e-8 * scale
    # ω3 = ψ̇ + φ̇ cos θ stays the given spin.
    assert np.abs(rate(top.psi) + phi_dot * np.cos(theta) - w3).max() < 1e-8 * abs(w3)


def test_sleeping_top_threshold():
    It, Ia, mgl = TOP["I_transverse"], TOP["I_axial"], TOP["mgl"]
    critical = critical_spin_rad_s(It, Ia, mgl)
    assert critical == pytest.approx(math.sqrt(4.0 * mgl * It) / Ia, rel=1e-15, abs=0)
    theta0 = 0.01
    above = heavy_top_quadrature(**TOP, spin_rad_s=1.005 * critical, theta0_rad=theta0, phi_dot0=0.0, theta_dot0=0.0)
    below = heavy_top_quadrature(**TOP, spin_rad_s=0.995 * critical, theta0_rad=theta0, phi_dot0=0.0, theta_dot0=0.0)
    for top in (above, below):
        t = np.linspace(0.0, 1.2 * top.nutation_period_s, 1201)
        sol = integrate(top, t[-1], t_eval=t, dense_output=True)
        tilt = np.arccos(rotate_vector(sol.y[:4].T, E3)[:, 2])
        # Refine the sampled maximum of the tilt on the dense output.
        i = int(np.argmax(tilt))
        fine = np.linspace(t[max(i - 1, 0)], t[min(i + 1, len(t) - 1)], 2001)
        tilt_max = np.arccos(rotate_vector(sol.sol(fine)[:4].T, E3)[:, 2]).max()
        assert tilt_max == pytest.approx(top.theta_max_rad, abs=1e-8)
        assert top.theta_min_rad == pytest.approx(theta0, abs=1e-15)  # released at rest: θ0 is the top turning point
    # Just above the threshold the tilt stays small (here 9·θ0 = 0.09 rad) ...
    assert above.theta_max_rad < 0.1
    # ... just below it the top falls to u1 → c²/β − 1 = 2(ω3/ω_c)² − 1 (0.2 rad whatever the small θ0).
    assert below.theta_max_rad > 0.2
    # Small-tilt limits, independent of the cubic: released at rest, the tilt above the threshold is
    # the sum of two circular modes ω± = (c ± √(c² − 4 mgl/I_t))/2, peaking at θ0·c/√(c² − 4 mgl/I_t)
    # = θ0/√(1 − (ω_c/ω3)²) (≈ 10 θ0 here); below it the top falls to cos θ = 2(ω3/ω_c)² − 1.
    for tiny in (1e-7, 1e-9):
        small_above = heavy_top_quadrature(**TOP, spin_rad_s=1.005 * critical, theta0_rad=tiny, phi_dot0=0.0, theta_dot0=0.0)
        small_below = heavy_top_quadrature(**TOP, spin_rad_s=0.995 * critical, theta0_rad=tiny, phi_dot0=0.0, theta_dot0=0.0)
        assert small_above.theta_max_rad / tiny == pytest.approx(1.0 / math.sqrt(1.0 - 1.0 / 1.005**2), rel=1e-9, abs=0)
        assert small_below.theta_max_rad == pytest.approx(math.acos(2.0 * 0.995**2 - 1.0), rel=1e-9, abs=0)


def test_steady_precession_keeps_theta_and_rates_constant():
    # Slow steady precession: mgl = φ̇ (I_a ω3 − I_t φ̇ cos θ), the smaller root.
    It, Ia, mgl = TOP["I_transverse"], TOP["I_axial"], TOP["mgl"]
    spin, theta0 = 60.0, 0.5
    a, b = It * math.cos(theta0), -Ia * spin
    phi_dot = (-b - math.sqrt(b * b - 4.0 * a * mgl)) / (2.0 * a)
    top = heavy_top_quadrature(**TOP, spin_rad_s=spin, theta0_rad=theta0, phi_dot0=phi_dot, theta_dot0=0.0)
    t = np.linspace(0.0, 2.0, 101)
    assert top.theta_max_rad - top.theta_min_rad < 1e-12
    assert np.abs(top.theta(t) - theta0).max() < 1e-12
    assert np.abs(top.phi(t) - phi_dot * t).max() < 1e-11
    assert np.abs(top.psi(t) - (spin - phi_dot * math.cos(theta0)) * t).max() < 1e-10
    assert top.mean_precession_rate_rad_s == pytest.approx(phi_dot, rel=1e-12, abs=0)


@pytest.mark.parametrize("factor", [1.2, 0.8])
def test_exactly_upright_top_stays_upright(factor):
    # θ0 = 0, θ̇0 = 0: an equilibrium either way (unstable below the threshold); the body turns
    # about Z at ω3, so q(t) is a rotation about Z by ω3 t (φ + ψ; φ̇ = c/2 is the limit value).
    critical = critical_spin_rad_s(**TOP)
    spin = factor * critical
    top = heavy_top_quadrature(**TOP, spin_rad_s=spin, theta0_rad=0.0, phi_dot0=0.0, theta_dot0=0.0)
    t = np.linspace(0.0, 3.0, 31)
    assert np.all(top.theta(t) == 0.0)
    expected = np.array([quaternion_from_axis_angle(E3, spin * ti) for ti in t])
    assert attitude_error_rad(top.quaternion(t), expected).max() < 1e-13
    assert top.mean_precession_rate_rad_s == pytest.approx(0.5 * TOP["I_axial"] * spin / TOP["I_transverse"], rel=1e-15, abs=0)
    if factor > 1.0:  # sleeping top: small-oscillation nutation period 2π/√(c² − 4 mgl/I_t)
        c = TOP["I_axial"] * spin / TOP["I_transverse"]
        expected = 2 * math.pi / math.sqrt(c * c - 4 * TOP["mgl"] / TOP["I_transverse"])
        assert top.nutation_period_s == pytest.approx(expected, rel=1e-14, abs=0)
        assert top.u1 == top.u2 == 1.0
    else:
        assert top.nutation_period_s == math.inf
        assert top.u1 < 1.0 and top.u2 == top.u3 == 1.0


def test_axis_passing_exactly_through_the_vertical():
    # Released from upright with a tilting rate: p_φ = p_ψ, u2 = 1, the axis passes through +Z
    # once per nutation period. No NaN; φ jumps by π at each pass (θ ≥ 0) but the axis and
    # the attitude follow the integration; θ̇0 < 0 at θ0 = 0 is the same motion mirrored.
    top = heavy_top_quadrature(**TOP, spin_rad_s=60.0, theta0_rad=0.0, phi_dot0=0.0, theta_dot0=0.5)
    assert top.u2 == 1.0 and top.theta_min_rad == 0.0
    t = np.linspace(0.0, 4.0 * top.nutation_period_s, 801)
    q_ref = integrate(top, t[-1], t_eval=t).y[:4].T
    for values in (top.theta(t), top.phi(t), top.psi(t), top.quaternion(t)):
        assert np.all(np.isfinite(values))
    assert angle_between(top.symmetry_axis(t), rotate_vector(q_ref, E3)).max() < TOL_RAD
    assert attitude_error_rad(top.quaternion(t), q_ref).max() < TOL_RAD
    # The attitude is continuous through the passes even where φ and ψ jump.
    fine = np.linspace(0.0, 2.0 * top.nutation_period_s, 20001)
    steps = attitude_error_rad(top.quaternion(fine[1:]), top.quaternion(fine[:-1]))
    assert steps.max() < 2.0 * np.abs(top.spin_rad_s) * (fine[1] - fine[0])
    mirrored = heavy_top_quadrature(**TOP, spin_rad_s=60.0, theta0_rad=0.0, phi_dot0=0.0, theta_dot0=-0.5, phi0=math.pi)
    assert angle_between(mirrored.symmetry_axis(t), top.symmetry_axis(t)).max() < 1e-12
    # A top missing the vertical by a hair (p_φ − p_ψ = 1e-9 of the terms that cancel in it)
    # follows the integration as closely.
    theta0, c = 0.3, TOP["I_axial"] * 60.0 / TOP["I_transverse"]
    phi_dot0 = c * (1.0 - math.cos(theta0)) / math.sin(theta0) ** 2 * (1 + 1e-9)  # p_φ = p_ψ when 1e-9 → 0
    near = heavy_top_quadrature(**TOP, spin_rad_s=60.0, theta0_rad=theta0, phi_dot0=phi_dot0, theta_dot0=0.0)
    t_near = np.linspace(0.0, 3.0 * near.nutation_period_s, 601)
    q_near = integrate(near, t_near[-1], t_eval=t_near).y[:4].T
    assert near.theta_min_rad < 1e-8
    assert attitude_error_rad(near.quaternion(t_near), q_near).max() < TOL_RAD


@pytest.mark.parametrize("pole", ["top", "bottom"])
def test_exact_pole_pass_is_the_limit_of_a_near_miss(pole):
    # The exact pass (p_φ = ±p_ψ) has φ, ψ jump by π at the pole; a top starting 1e-9 rad from the
    # pole with p_φ ∓ p_ψ tiny and positive swings φ, ψ through the same π smoothly. Away from the
    # passes the two agree to the size of the perturbation: this pins the sign of each jump
    # (a jump of the other sign differs by 2π — the same attitude, a different angle).
    spin, c = 20.0, TOP["I_axial"] * 20.0 / TOP["I_transverse"]
    if pole == "top":
        exact = heavy_top_quadrature(**TOP, spin_rad_s=spin, theta0_rad=0.0, phi_dot0=0.0, theta_dot0=0.5)
        near = heavy_top_quadrature(**TOP, spin_rad_s=spin, theta0_rad=1e-9, phi_dot0=0.5 * c + 1.0, theta_dot0=0.5)
        assert exact._orbit.jump_top and near._orbit.b_minus_c > 0.0  # (p_φ − p_ψ)/I_t, formed without cancellation
    else:
        exact = heavy_top_quadrature(**TOP, spin_rad_s=spin, theta0_rad=math.pi, phi_dot0=0.0, theta_dot0=-0.5)
        near = heavy_top_quadrature(**TOP, spin_rad_s=spin, theta0_rad=math.pi - 1e-9, phi_dot0=1.0 - 0.5 * c, theta_dot0=-0.5)
        assert exact._orbit.jump_bottom and near._orbit.b_plus_c > 0.0
    T = exact.nutation_period_s  # passes at t = 0, T, 2T, ...
    t = np.concatenate([(np.arange(3) + f) * T for f in (0.25, 0.5, 0.75)])
    assert np.abs(near.phi(t) - exact.phi(t)).max() < 1e-7  # measured 2e-9
    assert np.abs(near.psi(t) - exact.psi(t)).max() < 1e-7
    assert np.abs(near.theta(t) - exact.theta(t)).max() < 1e-7


def test_torque_free_symmetric_top_with_zero_gravity_moment():
    # mgl = 0: the axis cones about the fixed L at |L|/I_t; f(u) is a quadratic (u3 = inf).
    top = heavy_top_quadrature(I_transverse=0.0125, I_axial=0.01, mgl=0.0, spin_rad_s=20.0, theta0_rad=0.7, phi_dot0=1.0, theta_dot0=0.3)
    assert top.u3 == math.inf
    t = np.linspace(0.0, 3.0 * top.nutation_period_s, 301)
    q_ref = integrate(top, t[-1], t_eval=t).y[:4].T
    assert attitude_error_rad(top.quaternion(t), q_ref).max() < TOL_RAD


@pytest.mark.parametrize(
    ("changes", "message"),
    [
        ({"I_transverse": -1.0}, "I_transverse"),
        ({"I_axial": 0.0}, "I_axial"),
        ({"I_axial": 0.03}, "triangle inequality"),
        ({"mgl": -0.1}, "mgl"),
        ({"theta0_rad": 3.5}, r"theta0_rad must lie in \[0, π\]"),
        ({"spin_rad_s": math.nan}, "spin_rad_s must be finite"),
    ],
)
def test_invalid_input_raises(changes, message):
    args = {**TOP, "spin_rad_s": 10.0, "theta0_rad": 0.3, "phi_dot0": 0.0, "theta_dot0": 0.0, **changes}
    with pytest.raises(ValueError, match=message):
        heavy_top_quadrature(**args)
