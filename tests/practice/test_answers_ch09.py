"""Chapter 9's exercises against independent computations: the Ritz frequencies against the scene's own Ritz model
(an orthogonal basis spanning the same polynomials) and the exact frequency equations, the Ritz integrals and the
Legendre transformations and Routhians by sympy from position vectors, the actions by numerical quadrature, every
motion (spherical pendulum, bead, puck) by scipy's DOP853 on Lagrange's equations derived by sympy, the wheel by
Newton–Euler with the friction force as an unknown, the Gibbs function summed over particles, and the rolling disk's
partial velocities by finite differences of the project's own pose of the disk. Each test states its tolerance and
why."""

from __future__ import annotations

import math
from functools import cache

import numpy as np
import pytest
import sympy
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq, minimize_scalar

from app.physics.math.rotations import elementary_rotation_matrix
from app.physics.systems.ch09.ritz_beam import RitzCantilever
from app.physics.systems.ch09.rolling_disk_model import disk_pose
from app.practice.variants import variant
from app.scenes import SCENES
from tests.practice.shipped import EXERCISES

VARIANTS = range(0, 100, 9)
#: The integrators' tolerances: far below every check's tolerance.
TIGHT = {"method": "DOP853", "rtol": 1e-12, "atol": 1e-12}

t = sympy.Symbol("t", real=True)


def _lagrange_rates(lagrangian: sympy.Expr, coordinates: list[sympy.Function]):
    """Lagrange's equations of ``lagrangian`` (in the functions of t ``coordinates``) solved for the accelerations,
    as a numerical right-hand side f(t, (q, q̇)) for solve_ivp."""
    n = len(coordinates)
    q = sympy.symbols(f"q0:{n}", real=True)
    qd = sympy.symbols(f"qd0:{n}", real=True)
    qdd = sympy.symbols(f"qdd0:{n}", real=True)
    replace = {}
    for i, c in enumerate(coordinates):
        replace[sympy.diff(c, t, 2)] = qdd[i]
        replace[sympy.diff(c, t)] = qd[i]
    equations = []
    for c in coordinates:
        expr = sympy.diff(sympy.diff(lagrangian, sympy.diff(c, t)), t) - sympy.diff(lagrangian, c)
        expr = expr.subs(replace)
        expr = expr.subs({c: q[i] for i, c in enumerate(coordinates)})
        equations.append(expr)
    solved = sympy.solve(equations, qdd, dict=True)[0]
    accelerations = sympy.lambdify([q, qd], [solved[s] for s in qdd], "numpy")

    def rates(_t, y):
        return np.concatenate([y[n:], np.asarray(accelerations(y[:n], y[n:]), dtype=float)])

    return rates


# ---- 9.1 ----------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", VARIANTS)
def test_the_two_term_ritz_frequencies_match_the_scenes_orthogonal_basis_and_lie_above_the_exact(number):
    """The scene's Ritz model at the exercise's "See it" numbers but with the orthogonal basis (Legendre curvatures,
    Gauss quadrature) spans the same polynomials, so its frequencies must agree to rounding: 1e-10 relative (a 2 × 2
    eigenproblem with cond ≈ 150). The integrals of the monomials are checked by sympy exactly, and every Ritz
    frequency is above the exact one (the beam's frequency equation), as the choice says."""
    exercise = EXERCISES["9-1-two-term-ritz-cantilever"]
    drawn = variant(exercise, number)
    params = dict(SCENES["ritz-cantilever"].parameters.validate(exercise.scene.at(drawn.given)["params"]))
    two = RitzCantilever.from_params({**params, "basis": "orthogonal", "terms": 2})
    one = RitzCantilever.from_params({**params, "basis": "orthogonal", "terms": 1})
    assert drawn.answers["one-term"].value == pytest.approx(float(one.ritz_omega_rad_s[0]), rel=1e-10)
    assert drawn.answers["omega1"].value == pytest.approx(float(two.ritz_omega_rad_s[0]), rel=1e-10)
    assert drawn.answers["omega2"].value == pytest.approx(float(two.ritz_omega_rad_s[1]), rel=1e-10)
    xi = sympy.Symbol("xi")
    shapes = [xi**2, xi**3]
    mass = sympy.Matrix(2, 2, lambda i, j: sympy.integrate(shapes[i] * shapes[j], (xi, 0, 1)))
    stiffness = sympy.Matrix(
        2, 2, lambda i, j: sympy.integrate(sympy.diff(shapes[i], xi, 2) * sympy.diff(shapes[j], xi, 2), (xi, 0, 1))
    )
    assert mass == sympy.Matrix(
        [[sympy.Rational(1, 5), sympy.Rational(1, 6)], [sympy.Rational(1, 6), sympy.Rational(1, 7)]]
    )
    assert stiffness == sympy.Matrix([[4, 6], [6, 12]])
    exact = two.beam.exact_omega_rad_s(2)
    assert drawn.answers["omega1"].value > exact[0] and drawn.answers["omega2"].value > exact[1]
    assert drawn.answers["one-term"].value > drawn.answers["omega1"].value  # adding a term never raises ω₁
    assert drawn.answers["bound"].value == "above"


def _tip_mass_exact_omega(length: float, rigidity: float, density: float, tip: float) -> float:
    """The exact first frequency of a uniform cantilever with a point mass at its tip: the first root λ of
    1 + cos λ cosh λ + μ λ (cos λ sinh λ − sin λ cosh λ) = 0, μ = M/(ρA L), written divided by cosh λ so that it
    stays finite; ω = λ² √(EI/(ρA L⁴))."""
    mu = tip / (density * length)

    def equation(lam: float) -> float:
        return 1.0 / math.cosh(lam) + math.cos(lam) + mu * lam * (math.cos(lam) * math.tanh(lam) - math.sin(lam))

    lam = brentq(equation, 1e-3, 1.8752, xtol=1e-15)  # the bare beam's 1.875104 bounds the first root from above
    return lam**2 * math.sqrt(rigidity / (density * length**4))


def test_the_tip_mass_frequency_equation_has_the_known_limits():
    """No tip mass: 1.875104² (the bare cantilever); a heavy tip mass: √(3EI/(M L³)) (a massless spring) to 1e-3."""
    assert _tip_mass_exact_omega(1.0, 1.0, 1.0, 0.0) == pytest.approx(1.8751040687**2, rel=1e-9)
    assert _tip_mass_exact_omega(1.0, 1.0, 1.0, 1e4) == pytest.approx(math.sqrt(3.0 / 1e4), rel=1e-3)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_static_shape_ritz_values_come_from_their_integrals_and_bound_the_exact_frequency(number):
    """k and m_eq from T and V integrated by sympy along the beam with the shape in x (exact: 1e-12 relative). The
    Ritz frequency lies above the exact one of the beam with its tip mass (the frequency equation, solved to 1e-15)
    and within 1.5 % of it: the static shape's error for a bare beam is 1.47 % and a tip mass, which makes that shape
    the exact mode as M/(ρA L) grows, only shrinks it."""
    drawn = variant(EXERCISES["9-1-tip-mass-static-shape"], number)
    g = drawn.given
    length, rigidity, density, tip = g["length_m"], g["rigidity_n_m2"], g["mass_per_length_kg_m"], g["tip_mass_kg"]
    x = sympy.Symbol("x")
    shape = (x / length) ** 2 * (3 - x / length) / 2
    stiffness = float(sympy.integrate(rigidity * sympy.diff(shape, x, 2) ** 2, (x, 0, length)))
    mass = float(sympy.integrate(density * shape**2, (x, 0, length))) + tip * float(shape.subs(x, length)) ** 2
    assert drawn.answers["stiffness"].value == pytest.approx(stiffness, rel=1e-12)
    assert drawn.answers["mass"].value == pytest.approx(mass, rel=1e-12)
    exact = _tip_mass_exact_omega(length, rigidity, density, tip)
    omega = drawn.answers["omega"].value
    assert omega == pytest.approx(math.sqrt(stiffness / mass), rel=1e-12)
    assert exact < omega < 1.015 * exact


@pytest.mark.parametrize("number", VARIANTS)
def test_the_toss_actions_are_the_integrals_of_the_lagrangian_along_the_paths(number):
    """The action by adaptive quadrature (scipy quad, 1e-12 relative) along the trial path at three amplitudes and
    along the true path; the stationary amplitude as the root (brentq, 1e-14) of dS/da, itself a quadrature of
    ∂L/∂a along the path: all to 1e-10 relative, which the quadrature's 1e-12 leaves room for. (A minimiser of S
    itself could only place a* to about √ε ≈ 1e-8, the flatness of a minimum: it is used only to confirm that the
    stationary point is the lowest.)"""
    drawn = variant(EXERCISES["9-1-action-of-a-toss"], number)
    m, tau, g = drawn.given["mass_kg"], drawn.given["flight_time_s"], drawn.given["g_m_s2"]

    def action(path, rate) -> float:
        return quad(lambda s: 0.5 * m * rate(s) ** 2 - m * g * path(s), 0.0, tau, epsabs=0.0, epsrel=1e-12)[0]

    def trial(amplitude: float) -> float:
        return action(
            lambda s: amplitude * math.sin(math.pi * s / tau),
            lambda s: amplitude * math.pi / tau * math.cos(math.pi * s / tau),
        )

    expression = drawn.answers["action"].value
    names = {s.name: s for s in expression.free_symbols}
    for amplitude in (0.3, 1.0, 2.5):
        ours = float(expression.subs({names["a"]: amplitude, names["m"]: m, names["g"]: g, names["tau"]: tau}))
        assert ours == pytest.approx(trial(amplitude), rel=1e-10)

    def slope(amplitude: float) -> float:  # dS/da = ∫ (m ẋ ∂ẋ/∂a − m g ∂x/∂a) dt along the trial path
        def integrand(s: float) -> float:
            shape, shape_rate = math.sin(math.pi * s / tau), math.pi / tau * math.cos(math.pi * s / tau)
            return m * amplitude * shape_rate**2 - m * g * shape

        return quad(integrand, 0.0, tau, epsabs=1e-14 * m * g * tau, epsrel=1e-12)[0]  # each term is ~ m g τ

    best = brentq(slope, 0.0, g * tau**2, xtol=1e-15, rtol=1e-14)
    assert drawn.answers["amplitude"].value == pytest.approx(best, rel=1e-10)
    assert drawn.answers["trial-action"].value == pytest.approx(trial(best), rel=1e-10)
    lowest = minimize_scalar(trial, bounds=(0.0, g * tau**2), method="bounded", options={"xatol": 1e-12})
    assert lowest.fun == pytest.approx(trial(best), rel=1e-12)  # the stationary amplitude is the minimum
    true = action(lambda s: 0.5 * g * s * (tau - s), lambda s: g * (tau / 2 - s))
    assert drawn.answers["true-action"].value == pytest.approx(true, rel=1e-10)
    assert true < trial(best)  # the true path's action is the smaller: a minimum, as the statement invites to see


# ---- 9.2 ----------------------------------------------------------------------------------------------------------


@cache
def _spherical_pendulum_lagrangian():
    m, l, g = sympy.symbols("m l g", positive=True)
    theta, phi = sympy.Function("theta")(t), sympy.Function("phi")(t)
    position = sympy.Matrix(
        [l * sympy.sin(theta) * sympy.cos(phi), l * sympy.sin(theta) * sympy.sin(phi), -l * sympy.cos(theta)]
    )
    velocity = position.diff(t)
    lagrangian = m * velocity.dot(velocity) / 2 - m * g * position[2]
    return lagrangian, (m, l, g), (theta, phi)


def test_the_spherical_pendulums_effective_potential_is_rouths():
    """Routh's function from the Lagrangian of the bob's position vector (sympy, exactly): β = ∂L/∂φ̇ solved for
    φ̇, R = L − βφ̇, and −R + ½ m l² θ̇² must be the answer's V_eff (a difference that simplifies to 0)."""
    drawn = variant(EXERCISES["9-2-spherical-pendulum-routh"], 0)
    lagrangian, (m, l, g), (theta, phi) = _spherical_pendulum_lagrangian()
    th, thd, phd, beta = sympy.symbols("th thd phd beta", real=True)
    plain = lagrangian.subs({sympy.diff(theta, t): thd, sympy.diff(phi, t): phd}).subs({theta: th})
    rate = sympy.solve(sympy.Eq(sympy.diff(plain, phd), beta), phd)[0]
    routhian = (plain - beta * phd).subs(phd, rate)
    veff = sympy.expand(-(routhian - m * l**2 * thd**2 / 2))
    answer = drawn.answers["veff"].value
    names = {s.name: s for s in answer.free_symbols}
    ours = answer.subs({names["theta"]: th, names["beta"]: beta, names["m"]: m, names["l"]: l, names["g"]: g})
    assert sympy.simplify(ours - veff) == 0


@pytest.mark.parametrize("number", VARIANTS)
def test_the_spherical_pendulum_turns_where_the_integrated_motion_does(number):
    """Lagrange's equations in (θ, φ) derived by sympy from the bob's position and integrated by DOP853 at 1e-12
    from the release: θ first moves the way the choice says, β stays m l² sin²θ φ̇ (1e-9 relative), and the next
    turning angle (where θ̇ = 0 again, located by the integrator's event to 1e-12) equals the answer to 1e-7
    relative."""
    exercise = EXERCISES["9-2-spherical-pendulum-routh"]
    drawn = variant(exercise, number)
    g = drawn.given
    lagrangian, (m, l, gs), coordinates = _spherical_pendulum_lagrangian()
    rates = _lagrange_rates(lagrangian.subs({m: g["mass_kg"], l: g["length_m"], gs: g["g_m_s2"]}), list(coordinates))
    y0 = np.array([math.radians(g["theta_0_deg"]), 0.0, 0.0, math.radians(g["phi_rate_0_deg_s"])])
    beta = g["mass_kg"] * g["length_m"] ** 2 * math.sin(y0[0]) ** 2 * y0[3]
    assert drawn.answers["beta"].value == pytest.approx(beta, rel=1e-12)
    start = solve_ivp(rates, (0.0, 1e-3), y0, **TIGHT)
    outward = start.y[2, -1] > 0.0
    assert drawn.answers["direction"].value == ("outward" if outward else "inward")

    def turning(_t, y):
        return y[2]

    turning.terminal = True
    turning.direction = -1.0 if outward else 1.0
    run = solve_ivp(rates, (1e-3, 60.0), start.y[:, -1], events=turning, **TIGHT)
    assert run.status == 1
    end = run.y_events[0][0]
    assert g["mass_kg"] * g["length_m"] ** 2 * math.sin(end[0]) ** 2 * end[3] == pytest.approx(beta, rel=1e-9)
    assert drawn.answers["other-angle"].value == pytest.approx(math.degrees(end[0]), rel=1e-7)


@cache
def _bead_lagrangian():
    m, radius, spin, g = sympy.symbols("m R Omega g", positive=True)
    theta = sympy.Function("theta")(t)
    position = sympy.Matrix(
        [
            radius * sympy.sin(theta) * sympy.cos(spin * t),
            radius * sympy.sin(theta) * sympy.sin(spin * t),
            -radius * sympy.cos(theta),
        ]
    )
    velocity = position.diff(t)
    lagrangian = sympy.simplify(m * velocity.dot(velocity) / 2 - m * g * position[2])
    return lagrangian, (m, radius, spin, g), theta


@cache
def _bead_hamiltonian():
    """(θ, p, H(θ, p)) by the Legendre transformation of the bead's Lagrangian."""
    lagrangian, _, theta = _bead_lagrangian()
    th, thd, p = sympy.symbols("th thd p", real=True)
    plain = lagrangian.subs(sympy.diff(theta, t), thd).subs(theta, th)
    rate = sympy.solve(sympy.Eq(sympy.diff(plain, thd), p), thd)[0]
    return th, p, sympy.simplify((p * thd - plain).subs(thd, rate))


@pytest.mark.parametrize("number", VARIANTS)
def test_the_beads_hamiltonian_is_the_legendre_transform_and_the_bottom_rate_is_integrated(number):
    """H = p θ̇ − L from the bead's position on the turning hoop (sympy, exactly: the difference simplifies to 0);
    h is that H at the release (1e-12); the motion integrated by DOP853 at 1e-12 from the release to the bottom (an
    event at θ = 0) crosses it at the answer's |θ̇| to 1e-8 relative, with T + V changed by more than 1 % on the way
    (so it is not conserved, as the choice says)."""
    drawn = variant(EXERCISES["9-2-bead-jacobi-integral"], number)
    g = drawn.given
    lagrangian, (m, radius, spin, gs), theta = _bead_lagrangian()
    th, p, hamiltonian = _bead_hamiltonian()
    answer = drawn.answers["hamiltonian"].value
    names = {s.name: s for s in answer.free_symbols}
    ours = answer.subs(
        {names["theta"]: th, names["p"]: p, names["m"]: m, names["R"]: radius, names["Omega"]: spin, names["g"]: gs}
    )
    assert sympy.simplify(ours - hamiltonian) == 0
    numbers = {m: g["bead_mass_kg"], radius: g["hoop_radius_m"], spin: g["hoop_speed_rad_s"], gs: g["g_m_s2"]}
    theta0 = math.radians(g["theta_0_deg"])
    assert drawn.answers["jacobi"].value == pytest.approx(
        float(hamiltonian.subs(numbers).subs({th: theta0, p: 0})), rel=1e-12
    )
    rates = _lagrange_rates(lagrangian.subs(numbers), [theta])

    def bottom(_t, y):
        return y[0]

    bottom.terminal = True
    run = solve_ivp(rates, (0.0, 30.0), np.array([theta0, 0.0]), events=bottom, **TIGHT)
    assert run.status == 1
    crossing = run.y_events[0][0]
    assert drawn.answers["bottom-rate"].value == pytest.approx(abs(crossing[1]), rel=1e-8)
    mass, r_, w_, gg = g["bead_mass_kg"], g["hoop_radius_m"], g["hoop_speed_rad_s"], g["g_m_s2"]

    def energy(angle: float, angle_rate: float) -> float:
        return 0.5 * mass * r_**2 * (angle_rate**2 + w_**2 * math.sin(angle) ** 2) - mass * gg * r_ * math.cos(angle)

    before, after = energy(theta0, 0.0), energy(0.0, crossing[1])
    assert abs(after - before) > 0.01 * abs(before)
    assert drawn.answers["conserved"].value == "h-only"


@cache
def _puck_lagrangian():
    m1, m2, g = sympy.symbols("m1 m2 g", positive=True)
    r, phi = sympy.Function("r")(t), sympy.Function("phi")(t)
    puck = sympy.Matrix([r * sympy.cos(phi), r * sympy.sin(phi), 0])
    weight_height = r - sympy.Symbol("ell")  # the string's length ℓ: the weight hangs ℓ − r below the table
    kinetic = m1 * puck.diff(t).dot(puck.diff(t)) / 2 + m2 * sympy.diff(weight_height, t) ** 2 / 2
    return kinetic - m2 * g * weight_height, (m1, m2, g), (r, phi)


def test_the_pucks_routhian_is_l_minus_beta_phi_dot():
    """Routh's function from the Lagrangian of the puck's and the weight's positions (sympy, exactly); the answer
    may differ from it by a constant (the string's length), so their difference must not depend on r or ṙ."""
    drawn = variant(EXERCISES["9-2-puck-and-hanging-weight"], 0)
    lagrangian, (m1, m2, g), (r, phi) = _puck_lagrangian()
    rr, rd, phd, beta = sympy.symbols("rr rd phd beta", real=True)
    plain = lagrangian.subs({sympy.diff(r, t): rd, sympy.diff(phi, t): phd}).subs(r, rr)
    rate = sympy.solve(sympy.Eq(sympy.diff(plain, phd), beta), phd)[0]
    routhian = (plain - beta * phd).subs(phd, rate)
    answer = drawn.answers["routhian"].value
    names = {s.name: s for s in answer.free_symbols}
    ours = answer.subs(
        {names["r"]: rr, names["rd"]: rd, names["beta"]: beta, names["m1"]: m1, names["m2"]: m2, names["g"]: g}
    )
    difference = sympy.simplify(ours - routhian)
    assert not difference.has(rr) and not difference.has(rd)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_pucks_steady_circle_and_radial_frequency_come_from_the_integrated_motion(number):
    """Lagrange's equations in (r, φ) from sympy, integrated by DOP853 at 1e-12. Started on the answer's circle with
    the answer's β, r stays within 1e-9 of r_s for 5 s; started 1e-4 off it with the same β, two consecutive
    turning points of r (events on ṙ = 0) are half a period apart, π/ω to 1e-6 relative (the amplitude's effect on
    the period is of order (1e-4)² = 1e-8)."""
    drawn = variant(EXERCISES["9-2-puck-and-hanging-weight"], number)
    g = drawn.given
    m1v, m2v = g["puck_mass_kg"], g["hanging_mass_kg"]
    lagrangian, (m1, m2, gs), coordinates = _puck_lagrangian()
    rates = _lagrange_rates(lagrangian.subs({m1: m1v, m2: m2v, gs: g["g_m_s2"]}), list(coordinates))
    beta = m1v * g["radius_0_m"] ** 2 * g["phi_rate_0_rad_s"]
    assert drawn.answers["beta"].value == pytest.approx(beta, rel=1e-12)
    steady = drawn.answers["radius"].value
    run = solve_ivp(rates, (0.0, 5.0), [steady, 0.0, 0.0, beta / (m1v * steady**2)], dense_output=True, **TIGHT)
    assert np.max(np.abs(run.sol(np.linspace(0.0, 5.0, 400))[0] - steady)) < 1e-9 * steady
    start = steady * (1.0 + 1e-4)

    def turning(_t, y):
        return y[2]

    run = solve_ivp(rates, (0.0, 100.0), [start, 0.0, 0.0, beta / (m1v * start**2)], events=turning, **TIGHT)
    times = run.t_events[0]
    times = times[times > 1e-9]
    period = times[1] - times[0] if len(times) >= 2 else math.nan
    assert drawn.answers["frequency"].value == pytest.approx(math.pi / period, rel=1e-6)


# ---- 9.3 ----------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", VARIANTS)
def test_the_wheel_by_kane_agrees_with_newton_euler_and_its_rolling_constraint(number):
    """Newton–Euler with the friction force as an unknown (m a = m g sin β − f, I_G α_z = f r, a = −r α_z, solved
    by numpy): the acceleration to 1e-12, and F₁/u̇ = m_eff. The partial angular velocity from the no-slip condition
    v_G + ω × (−r j) = 0 solved for ω at two speeds (it is linear in u, so the difference quotient is exact:
    1e-12)."""
    drawn = variant(EXERCISES["9-3-kane-wheel-on-incline"], number)
    g = drawn.given
    m, r, k, beta = g["mass_kg"], g["radius_m"], g["gyration_m"], math.radians(g["slope_deg"])
    # unknowns (a, alpha_z, f): m a + f = m g sin β;  m k² α_z − (moment of f about G)_z = 0;  a + r α_z = 0
    # friction −f i at P = −r j: moment (−r j) × (−f i) = −r f k
    system = np.array([[m, 0.0, 1.0], [0.0, m * k**2, r], [1.0, r, 0.0]])
    a, alpha_z, f = np.linalg.solve(system, [m * g["g_m_s2"] * math.sin(beta), 0.0, 0.0])
    assert drawn.answers["acceleration"].value == pytest.approx(a, rel=1e-12)
    assert drawn.answers["active"].value / drawn.answers["inertia"].value == pytest.approx(a, rel=1e-12)
    assert drawn.answers["active"].value == pytest.approx(m * g["g_m_s2"] * math.sin(beta), rel=1e-12)

    def omega_z(u: float) -> float:  # v_P = u i + ω_z k × (−r j) = (u + r ω_z) i = 0
        contact = lambda w: np.array([u, 0.0, 0.0]) + np.cross([0.0, 0.0, w], [0.0, -r, 0.0])  # noqa: E731
        return -contact(0.0)[0] / (contact(1.0)[0] - contact(0.0)[0])

    partial = (omega_z(2.0) - omega_z(1.0)) / 1.0
    assert np.allclose(drawn.answers["partial-omega"].value, (0.0, 0.0, partial), rtol=1e-12, atol=1e-12)
    assert alpha_z == pytest.approx(partial * a, rel=1e-12)


def _particle_body(moments: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Six particles at ±e_k (1 m from G) whose masses give principal moments ``moments`` about G:
    I₁ = 2(μ₂ + μ₃) and so on round, so μ_k = (I_i + I_j − I_k)/4 ≥ 0 by the triangle inequality."""
    total = moments.sum()
    mu = (total - 2.0 * moments) / 4.0
    points, masses = [], []
    for axis in range(3):
        for sign in (1.0, -1.0):
            e = np.zeros(3)
            e[axis] = sign
            points.append(e)
            masses.append(mu[axis])
    return np.array(points), np.array(masses)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_gibbs_function_summed_over_particles_gives_the_answers(number):
    """The Gibbs function S = Σ ½ m a·a of six particles with the body's principal moments, each a = u̇ × ρ +
    ω × (ω × ρ), built by sympy with u̇ as symbols: ∂S/∂u̇ at u̇ = 0 is ω × Iω, and ∂S/∂u̇ = (M₁, 0, 0) solved for
    u̇ gives the angular acceleration (exact arithmetic up to float evaluation: 1e-12). The expression part is
    compared with ∂S/∂u̇₁ of particles of symbolic masses, written in their moments (sympy, exactly)."""
    drawn = variant(EXERCISES["9-3-gibbs-appell-body"], number)
    g = drawn.given
    moments = np.array([g["i1_kg_m2"], g["i2_kg_m2"], g["i3_kg_m2"]])
    omega = np.array([g["u1_rad_s"], g["u2_rad_s"], g["u3_rad_s"]])
    points, masses = _particle_body(moments)
    ud = sympy.Matrix(sympy.symbols("ud1:4", real=True))
    w = sympy.Matrix([sympy.nsimplify(c) for c in omega])
    gibbs = 0
    for rho, mass in zip(points, masses, strict=True):
        rho_s = sympy.Matrix([sympy.nsimplify(c) for c in rho])
        acceleration = ud.cross(rho_s) + w.cross(w.cross(rho_s))
        gibbs += sympy.nsimplify(mass) * acceleration.dot(acceleration) / 2
    gradient = [sympy.diff(gibbs, s) for s in ud]
    at_rest = [float(gi.subs({s: 0 for s in ud})) for gi in gradient]
    assert np.allclose(drawn.answers["gyroscopic"].value, at_rest, rtol=1e-12, atol=1e-12)
    solved = sympy.solve(
        [gradient[0] - sympy.nsimplify(g["torque_n_m"]), gradient[1], gradient[2]], list(ud), dict=True
    )[0]
    alpha = [float(solved[s]) for s in ud]
    assert np.allclose(drawn.answers["alpha"].value, alpha, rtol=1e-12, atol=1e-12)
    # the expression, for any body: particles of masses μ₁, μ₂, μ₃ on the axes at unit distance
    mu = sympy.symbols("mu1:4", positive=True)
    u = sympy.Matrix(sympy.symbols("u1:4", real=True))
    general = 0
    for axis in range(3):
        for sign in (1, -1):
            rho_s = sympy.Matrix([sign if i == axis else 0 for i in range(3)])
            acceleration = ud.cross(rho_s) + u.cross(u.cross(rho_s))
            general += mu[axis] * acceleration.dot(acceleration) / 2
    derivative = sympy.diff(general, ud[0])
    answer = drawn.answers["derivative"].value
    names = {s.name: s for s in answer.free_symbols}
    in_mu = answer.subs(
        {
            names["I1"]: 2 * (mu[1] + mu[2]),
            names["I2"]: 2 * (mu[0] + mu[2]),
            names["I3"]: 2 * (mu[0] + mu[1]),
            names["u1d"]: ud[0],
            names["u2"]: u[1],
            names["u3"]: u[2],
        }
    )
    assert sympy.expand(in_mu - derivative) == 0


@pytest.mark.parametrize("number", VARIANTS)
def test_the_rolling_disks_partial_velocities_are_the_projects_pose_differentiated(number):
    """The project's pose of the disk (centre and R_NB = Rz(ψ) Rx(θ) Ry(φ)) at the exercise's lean and a heading drawn
    at random: central differences (step 1e-6 rad, truncation ~1e-12 r, rounding ~1e-10 r) of the centre in ψ and
    θ, written in the heading frame, are the partial velocities to 1e-8 r; −∂(m g z_G)/∂θ is F_θ to 1e-8 relative.
    The statement's picture is checked too: the disk's axis (R_NB's second column) is e2 cos θ + e3 sin θ, so a
    positive lean tips the top toward −e2, and the contact point lies r below G along the disk's plane."""
    drawn = variant(EXERCISES["9-3-rolling-disk-partials"], number)
    g = drawn.given
    r, m = g["radius_m"], g["mass_kg"]
    lean = math.radians(g["lean_0_deg"])
    heading = np.random.default_rng(number).uniform(-math.pi, math.pi)
    e1 = np.array([math.cos(heading), math.sin(heading), 0.0])
    e2 = np.array([-math.sin(heading), math.cos(heading), 0.0])
    e3 = np.array([0.0, 0.0, 1.0])
    frame = np.array([e1, e2, e3])

    def centre(psi: float, theta: float) -> np.ndarray:
        state = np.zeros(10)
        state[2], state[3] = psi, theta
        return disk_pose(r, state)[0]

    h = 1e-6
    v_psi = frame @ (centre(heading + h, lean) - centre(heading - h, lean)) / (2 * h)
    v_theta = frame @ (centre(heading, lean + h) - centre(heading, lean - h)) / (2 * h)
    assert np.allclose(drawn.answers["v-psi"].value, v_psi, rtol=0.0, atol=1e-8 * r)
    assert np.allclose(drawn.answers["v-theta"].value, v_theta, rtol=0.0, atol=1e-8 * r)
    height = lambda theta: m * g["g_m_s2"] * centre(heading, theta)[2]  # noqa: E731
    force = -(height(lean + h) - height(lean - h)) / (2 * h)
    assert drawn.answers["active"].value == pytest.approx(force, rel=1e-8)
    state = np.zeros(10)
    state[2], state[3] = heading, lean
    _, rotation = disk_pose(r, state)
    assert np.allclose(rotation[:, 1], math.cos(lean) * e2 + math.sin(lean) * e3, atol=1e-14)
    expected = elementary_rotation_matrix(2, heading) @ elementary_rotation_matrix(0, lean)
    assert np.allclose(rotation, expected, atol=1e-14)
    assert np.allclose(centre(heading, lean) - r * (-math.sin(lean) * e2 + math.cos(lean) * e3), 0.0, atol=1e-14)
    assert drawn.answers["forces"].value == "gravity"
