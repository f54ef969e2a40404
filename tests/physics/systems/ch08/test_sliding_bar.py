"""The bar on a rough floor (app/physics/systems/ch08/sliding_bar.py): contact force, events and Painlevé.

References: Newton–Euler derived again here with sympy (vectors in 3-D, the moment as a cross
product, the constraint z_B = 0 differentiated symbolically) and solved for θ̈, ẍ_B and N; the
Painlevé condition as the zero set of that solution's denominator; the pivoting bar's motion by
energy (θ̇² = (3g/L)(sin θ0 − sin θ)) with its contact forces in closed form and the time by
quadrature; an independent scipy DOP853 integration of the sliding equations for the time B stops.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

from app.physics.systems.ch08 import sliding_bar as sb


def bar(**values):
    return sb.PARAMETERS.validate(values)


def run(params, *, t_end_s=3.0, frame_rate_hz=200.0):
    return sb.SlidingBar().simulate(params, {"rtol": 1e-10}, t_end_s=t_end_s, frame_rate_hz=frame_rate_hz, request_limits=False)


# -- the contact force against sympy ------------------------------------------------------------------
@functools.cache
def sympy_sliding_solution():
    """(θ̈, ẍ_B, N) of the sliding bar as sympy expressions in θ, θ̇, μ, σ, m, L, g."""
    t = sp.symbols("t")
    m, length, g, mu, sigma = sp.symbols("m L g mu sigma", real=True)
    theta, x_b = sp.Function("theta")(t), sp.Function("x_B")(t)
    alpha, acc_b, normal = sp.symbols("alpha a_B N")
    half = length / 2
    center = sp.Matrix([x_b - half * sp.cos(theta), 0, half * sp.sin(theta)])  # G = B + (L/2)(−cos θ, 0, sin θ)
    bottom = sp.Matrix([x_b, 0, 0])
    acc_center = center.diff(t, 2).subs({theta.diff(t, 2): alpha, x_b.diff(t, 2): acc_b})
    force = sp.Matrix([-mu * sigma * normal, 0, normal])
    moment = (bottom - center).cross(force)
    inertia = m * length**2 / 12
    # ω = θ̇ ŷ (the bar's direction (−cos θ, 0, sin θ) turns about +y as θ grows): Euler's law along ŷ.
    equations = [
        sp.Eq(m * acc_center[0], force[0]),
        sp.Eq(m * acc_center[2], force[2] - m * g),
        sp.Eq(inertia * alpha, moment[1]),
    ]
    rate, th = sp.symbols("omega theta")
    equations = [e.subs(theta.diff(t), rate).subs(theta, th) for e in equations]
    matrix, rhs = sp.linear_eq_to_matrix(equations, [alpha, acc_b, normal])
    solution = matrix.LUsolve(rhs)
    return [sp.cancel(v) for v in solution], (th, rate, mu, sigma, m, length, g)


def test_sliding_contact_force_matches_newton_euler_derived_by_sympy():
    (alpha, acc_b, normal), symbols = sympy_sliding_solution()
    functions = [sp.lambdify(symbols, e, "math") for e in (alpha, acc_b, normal)]
    rng = np.random.default_rng(8)
    for _ in range(40):
        theta, omega = rng.uniform(0.05, 1.5), rng.uniform(-3.0, 3.0)
        mu, sigma = rng.uniform(0.0, 1.2), rng.choice([-1.0, 1.0])
        m, length, g = rng.uniform(0.5, 5.0), rng.uniform(0.3, 3.0), 9.807
        params = bar(mu=mu, mass_kg=m, length_m=length)
        state = np.zeros(len(sb.STATE_NAMES))
        state[sb.THETA], state[sb.OMEGA], state[sb.SLIP], state[sb.U] = theta, omega, sigma, sigma
        forces = sb.contact_forces(params, state)[0]
        expected = [f(theta, omega, mu, sigma, m, length, g) for f in functions]
        # Same equations, two routes: agreement to round-off (relative 1e-10 of the largest term).
        assert forces[sb.C_ANGULAR_ACC] == pytest.approx(expected[0], rel=1e-10, abs=1e-9)
        assert forces[sb.C_CONTACT_ACC] == pytest.approx(expected[1], rel=1e-10, abs=1e-9)
        assert forces[sb.C_NORMAL] == pytest.approx(expected[2], rel=1e-10, abs=1e-9)


def test_painleve_condition_is_the_zero_set_of_the_sympy_denominator():
    (_, _, normal), (th, rate, mu, sigma, m, length, g) = sympy_sliding_solution()
    numerator, denominator = sp.fraction(sp.together(normal))
    # N = m(g − (L/2) θ̇² sin θ)/D: the ratio of sympy's denominator to the model's D is free of θ, θ̇ and μ.
    model_factor = 1 + 3 * sp.cos(th) * (sp.cos(th) - sigma * mu * sp.sin(th))
    ratio = sp.simplify(denominator / model_factor)
    assert not ratio.free_symbols & {th, rate, mu, sigma}
    assert sp.simplify(numerator / ratio - m * (g - length / 2 * rate**2 * sp.sin(th))) == 0
    # D = 0 for σ = 1 ⇔ tan²θ − 3μ tan θ + 4 = 0: the smallest μ with a root is 4/3, at tan θ = 2 (63.43°).
    t, mu_s = sp.symbols("t mu", positive=True)
    mu_of_t = sp.solve(sp.Eq(t**2 - 3 * mu_s * t + 4, 0), mu_s)[0]
    t_critical = sp.solve(sp.diff(mu_of_t, t), t)
    assert t_critical == [2] and mu_of_t.subs(t, 2) == sp.Rational(4, 3)
    assert sb.painleve_band_deg(1.3) is None
    low, high = sb.painleve_band_deg(4.0 / 3.0)
    assert low == pytest.approx(math.degrees(math.atan(2.0)), abs=1e-6) and high == pytest.approx(low, abs=1e-6)


# -- Painlevé detected where the condition says ---------------------------------------------------------
@pytest.mark.parametrize("mu", [1.5, 2.2])
def test_painleve_is_flagged_exactly_inside_the_derived_band_and_never_outside(mu):
    low, high = sb.painleve_band_deg(mu)
    tolerance_deg = 0.01  # the band edges to 0.01° (the check is exact; this is the sampling on each side)
    for angle, inside in ((low - tolerance_deg, False), (low + tolerance_deg, True), (high - tolerance_deg, True), (high + tolerance_deg, False)):
        params = bar(mu=mu, angle0_deg=angle, slide_speed0_m_s=1.0)
        report = run(params, t_end_s=0.5, frame_rate_hz=100.0)
        jammed = report.status == "event" and "Painlevé" in report.message
        assert jammed == inside, (angle, report.status, report.message)
        if inside:
            assert f"θ = {angle:.2f}°" in report.message and f"μ = {mu:.2f}" in report.message
            assert report.t_s[-1] <= 0.01  # stopped, not integrated on
            assert all(np.all(np.isfinite(v)) for v in report.series.values())
        # Sliding the other way (towards the lean) is never inconsistent for θ < 90°.
        reverse = run(bar(mu=mu, angle0_deg=angle, slide_speed0_m_s=-1.0), t_end_s=0.5, frame_rate_hz=100.0)
        assert "Painlevé" not in reverse.message


def test_painleve_preset_values_jam_at_once_and_the_answer_says_so_in_words():
    params = bar(mu=1.5, angle0_deg=63.4, slide_speed0_m_s=1.0)
    events = sb.run_events(params, t_end_s=1.0)
    assert [e.index for e in events] == [sb.JAM_STOP]
    assert events[0].t_s == pytest.approx(sb.JAM_STOP_DELAY_S, abs=1e-12)
    state = events[0].state
    assert state[sb.PHASE] == sb.JAMMED and state[sb.U] == 1.0 and state[sb.OMEGA] == 0.0  # frozen, as started
    message = sb.stop_message(params, events[0])
    assert "no contact force N ≥ 0 fits" in message and "θ = 63.40°" in message


def test_a_bar_sliding_near_the_band_is_braked_short_of_it_and_never_flagged():
    """μ = 1.5 from 45° (D > 0): friction turns the bar up towards the band's lower edge (50.64°); the normal force
    peaks and B stops before D reaches 0 (the jam where u and D vanish together is only approached)."""
    params = bar(mu=1.5, angle0_deg=45.0, slide_speed0_m_s=3.0)
    events = sb.run_events(params, t_end_s=2.0)
    assert events[0].index == sb.SLIP_STOPS
    low, _ = sb.painleve_band_deg(1.5)
    assert math.degrees(events[0].state[sb.THETA]) < low
    assert all(e.index != sb.JAM_STOP for e in events)


# -- the motion's events against independent solutions --------------------------------------------------
def test_pivoting_bar_breaks_loose_at_the_closed_form_angle_and_quadrature_time():
    """From rest with μ = 0.5 at 60°: B sticks and the bar pivots, with (energy) θ̇² = (3g/L)(sin θ0 − sin θ),
    F = (3/4) m g cos θ (2 sin θ0 − 3 sin θ) and N = (m g / 4)(1 − 6 sin θ sin θ0 + 9 sin²θ); it breaks loose
    where |F| = μ N."""
    params = bar(mu=0.5, angle0_deg=60.0, slide_speed0_m_s=0.0)
    length, g, mu = params["length_m"], params["g_m_s2"], params["mu"]
    s0 = math.sin(math.radians(60.0))

    def margin(theta):
        s, c = math.sin(theta), math.cos(theta)
        return mu * 0.25 * (1 - 6 * s * s0 + 9 * s * s) - abs(0.75 * c * (2 * s0 - 3 * s))

    assert margin(math.radians(60.0)) > 0.0
    grid = np.radians(np.linspace(60.0, 0.5, 20000))
    first = int(np.argmax([margin(th) < 0.0 for th in grid]))
    theta_break = brentq(margin, grid[first], grid[first - 1], xtol=1e-15)
    theta0 = math.radians(60.0)
    def smooth_part(theta):  # 1/θ̇ times √(θ0 − θ); sin θ0 − sin θ = 2 cos((θ0 + θ)/2) sin((θ0 − θ)/2)
        gap = theta0 - theta
        if gap <= 0.0:
            return 1.0 / math.sqrt(3 * g / length * math.cos(theta0))
        return math.sqrt(gap / (3 * g / length * 2 * math.cos(0.5 * (theta0 + theta)) * math.sin(0.5 * gap)))

    t_break, error = quad(smooth_part, theta_break, theta0, weight="alg", wvar=(0.0, -0.5), epsabs=1e-14, epsrel=1e-13, limit=400)
    assert error < 1e-11
    events = sb.run_events(params, t_end_s=2.0)
    assert events[0].index == sb.STICK_BREAKS
    # Acceptance figure 1e-6 s; observed |Δt| ≈ 7e-14 s and |Δθ| ≈ 5e-13 rad at rtol 1e-10.
    assert events[0].t_s == pytest.approx(t_break, abs=1e-6)
    assert events[0].state[sb.THETA] == pytest.approx(theta_break, abs=1e-8)


def test_sliding_stops_when_an_independent_integration_says():
    """The sliding equations written out again (numpy linear solve of Newton–Euler) and integrated by scipy
    DOP853 at rtol 1e-12 with an event at u = 0."""
    params = bar(mu=0.8, angle0_deg=40.0, slide_speed0_m_s=1.0)
    m, length, g, mu = params["mass_kg"], params["length_m"], params["g_m_s2"], params["mu"]
    h, inertia = 0.5 * length, m * length**2 / 12.0

    def rhs(t, y):
        theta, omega, u = y[1], y[2], y[3]
        s, c = math.sin(theta), math.cos(theta)
        # Unknowns [θ̈, u̇, N]: m ẍ_G = −μ N, m z̈_G = N − m g, I θ̈ = −h (N cos θ − μ N sin θ)  (σ = +1).
        matrix = np.array([[m * h * s, m, mu], [m * h * c, 0.0, -1.0], [inertia, 0.0, h * (c - mu * s)]])
        rhs_vec = np.array([-m * h * c * omega**2, m * h * s * omega**2 - m * g, 0.0])
        alpha, acc, _ = np.linalg.solve(matrix, rhs_vec)
        return [u, omega, alpha, acc]

    def stops(t, y):
        return y[3]

    stops.terminal, stops.direction = True, -1
    solution = solve_ivp(rhs, (0.0, 2.0), [0.0, math.radians(40.0), 0.0, 1.0], method="DOP853", rtol=1e-12, atol=1e-14, events=stops)
    events = sb.run_events(params, t_end_s=2.0)
    assert events[0].index == sb.SLIP_STOPS
    assert events[0].t_s == pytest.approx(float(solution.t_events[0][0]), abs=1e-6)  # observed 2e-12 s


@pytest.mark.parametrize(
    "values",
    [{}, {"mu": 0.5, "angle0_deg": 60.0, "slide_speed0_m_s": 0.0}, {"mu": 1.5, "angle0_deg": 45.0, "slide_speed0_m_s": 4.0},
     {"mu": 0.8, "angle0_deg": 40.0, "slide_speed0_m_s": -2.0}],
)  # fmt: skip
def test_energy_budget_is_constant_and_sticking_respects_the_friction_limit(values):
    params = bar(**values)
    report = run(params)
    assert report.status in ("ok", "event")
    # Kinetic + potential + friction work; observed ≤ 4e-11 of the initial energy at rtol 1e-10.
    assert report.max_invariant_drift < 1e-9
    series = report.series
    assert np.all(series["friction_work_J" if "friction_work_J" in series else "normal_force_N"] >= -1e-9)
    sticking = series["phase"] == sb.STICKING
    assert np.all(np.abs(series["friction_force_N"][sticking]) <= series["friction_limit_N"][sticking] * (1 + 1e-9) + 1e-9)
    sliding = series["phase"] == sb.SLIDING
    assert np.allclose(np.abs(series["friction_force_N"][sliding]), series["friction_limit_N"][sliding], rtol=1e-12)


def test_lift_off_and_landing_stop_the_run_with_words():
    lifted = run(bar(mu=1.5, angle0_deg=45.0, slide_speed0_m_s=5.0), t_end_s=1.0)
    assert lifted.status == "event" and "leaves the floor" in lifted.message
    assert lifted.series["normal_force_N"][-1] >= -1e-6
    landed = run(bar(), t_end_s=2.0)
    assert landed.status == "event" and "lands flat" in landed.message
