"""Chapter 8's answer functions against independent computations, over several variants each (tolerances stated and
justified at each check): the multiplier equations assembled and solved as one linear system (the double pendulum,
the Cartesian pendulum), a sympy derivation of Lagrange's equations with a multiplier (the rolling cylinder), the
slider-crank's own loop-closure start and mass matrix from the chapter-8 model, scipy's ODE solution of Baumgarte's
error equation with RK4's amplification matrix, the Cartesian pendulum's own Gauss–Newton start, and the stick–slip
belt's event-located integration."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import sympy
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from app.physics.systems.ch08 import stick_slip_belt
from app.physics.systems.ch08.cartesian_pendulum import pendulum_system
from app.physics.systems.ch08.cartesian_pendulum_model import CartesianPendulum
from app.physics.systems.ch08.slider_crank_dae import slider_crank_initial_state, slider_crank_linkage
from app.practice.exercise import parse_exercise
from app.practice.variants import variant
from app.scenes import SCENES

EXERCISE_DIR = Path(__file__).resolve().parents[2] / "lessons" / "ch08" / "exercises"
VARIANTS = range(0, 100, 9)


def _exercise(exercise_id: str):
    path = EXERCISE_DIR / f"{exercise_id}.md"
    return parse_exercise(path.read_text(encoding="utf-8"), str(path), chapter=8)


def _close_vector(answer, expected, rel: float) -> bool:
    expected = np.asarray(expected, dtype=float)
    return float(np.linalg.norm(np.asarray(answer, dtype=float) - expected)) <= rel * float(np.linalg.norm(expected))


def _solve_multipliers(M: np.ndarray, f: np.ndarray, C: np.ndarray, c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """M a = f + Cᵀλ and C a = c as one linear system: the accelerations and the multipliers."""
    n, k = len(f), len(c)
    matrix = np.block([[M, -C.T], [C, np.zeros((k, k))]])
    solution = np.linalg.solve(matrix, np.concatenate([f, c]))
    return solution[:n], solution[n:]


# -- 8.1 --------------------------------------------------------------------------------------------------------


def _double_pendulum_tensions(m1, m2, l1, l2, theta1, theta2, g):
    """Rod tensions (N) at rest from the 6×6 multiplier system in (x₁, y₁, x₂, y₂) with the exercise's g₁, g₂."""
    r1 = l1 * np.array([math.sin(theta1), -math.cos(theta1)])
    r2 = r1 + l2 * np.array([math.sin(theta2), -math.cos(theta2)])
    M = np.diag([m1, m1, m2, m2])
    f = np.array([0.0, -m1 * g, 0.0, -m2 * g])
    d = r2 - r1
    C = np.array([[-r1[0], -r1[1], 0.0, 0.0], [d[0], d[1], -d[0], -d[1]]])
    c = np.zeros(2)  # −Ċ v vanishes at rest
    _, multipliers = _solve_multipliers(M, f, C, c)
    return multipliers[0] * l1, multipliers[1] * l2, multipliers


@pytest.mark.parametrize("number", VARIANTS)
def test_the_double_pendulums_tensions_solve_its_multiplier_system(number):
    """λ from the assembled M q̈ = Q + Cᵀλ, C q̈ = 0 (numpy's solve; round-off only, 1e-10). The expression is
    compared with the same solve at the given numbers and at 20 random states of its symbols' ranges (1e-10)."""
    drawn = variant(_exercise("8-1-double-pendulum-release"), number)
    g = drawn.given
    t1, t2, multipliers = _double_pendulum_tensions(
        g["mass1_kg"],
        g["mass2_kg"],
        g["length1_m"],
        g["length2_m"],
        math.radians(g["theta1_deg"]),
        math.radians(g["theta2_deg"]),
        g["g_m_s2"],
    )
    assert drawn.answers["lambda2"].value == pytest.approx(multipliers[1], rel=1e-10)
    assert drawn.answers["tension1"].value == pytest.approx(t1, rel=1e-10)
    expression = drawn.answers["tension2"].value
    symbols = {str(s): s for s in expression.free_symbols}
    rng = np.random.default_rng(number)
    states = [(g["mass1_kg"], g["mass2_kg"], g["g_m_s2"], math.radians(g["theta1_deg"]), math.radians(g["theta2_deg"]))]
    states += [
        (rng.uniform(0.5, 5), rng.uniform(0.5, 5), rng.uniform(5, 15), rng.uniform(-1, 1), rng.uniform(-1.3, 1.3))
        for _ in range(20)
    ]
    for m1, m2, gravity, a1, a2 in states:
        _, expected, _ = _double_pendulum_tensions(m1, m2, 0.7, 1.1, a1, a2, gravity)
        values = {symbols["m1"]: m1, symbols["m2"]: m2, symbols["g"]: gravity}
        values |= {symbols["theta1"]: a1, symbols["theta2"]: a2}
        assert float(expression.subs(values)) == pytest.approx(expected, rel=1e-10, abs=1e-12)


def test_the_rolling_cylinders_multiplier_comes_from_lagranges_equations():
    """Lagrange's equations with the multiplier derived by sympy from T, V and g = x − rφ, solved with the
    constraint twice differentiated: λ equals the answer's expression exactly; ẍ and μ_s = |λ|/(m g cos β) at the
    given numbers to 1e-12; and λ's power λ (ẋ − r φ̇) is zero on every motion the constraint allows."""
    exercise = _exercise("8-1-rolling-cylinder-multiplier")
    t = sympy.Symbol("t")
    m, g, beta, r, lam = sympy.symbols("m g beta r lambda", real=True)
    x, phi = sympy.Function("x")(t), sympy.Function("phi")(t)
    kinetic = m * x.diff(t) ** 2 / 2 + (m * r**2 / 2) * phi.diff(t) ** 2 / 2
    potential = -m * g * x * sympy.sin(beta)
    constraint = x - r * phi
    lagrangian = kinetic - potential
    equations = [
        sympy.Eq(lagrangian.diff(q.diff(t)).diff(t) - lagrangian.diff(q), lam * constraint.diff(q)) for q in (x, phi)
    ]
    equations.append(sympy.Eq(constraint.diff(t, 2), 0))
    xdd, phidd = x.diff(t, 2), phi.diff(t, 2)
    solution = sympy.solve(equations, [xdd, phidd, lam], dict=True)[0]
    total_power = sum(lam * constraint.diff(q) * q.diff(t) for q in (x, phi))
    assert sympy.simplify(total_power.subs(x.diff(t), r * phi.diff(t))) == 0
    for number in VARIANTS:
        drawn = variant(exercise, number)
        answer = drawn.answers["lambda"].value
        by_name = {str(s): s for s in answer.free_symbols}
        mine = solution[lam].subs({m: by_name["m"], g: by_name["g"], beta: by_name["beta"]})
        assert sympy.simplify(answer - mine) == 0
        angle, gravity = math.radians(drawn.given["incline_deg"]), drawn.given["g_m_s2"]
        values = {m: 2.0, g: gravity, beta: angle, r: 0.3}
        assert drawn.answers["accel"].value == pytest.approx(float(solution[xdd].subs(values)), rel=1e-12)
        friction = abs(float(solution[lam].subs(values)))
        assert drawn.answers["mu"].value == pytest.approx(friction / (2.0 * gravity * math.cos(angle)), rel=1e-12)
        assert drawn.answers["work"].value == "none"


@pytest.mark.parametrize("number", VARIANTS)
def test_the_slider_crank_start_is_the_chapter_8_models_loop_closure(number):
    """The chapter-8 model's consistent start (chapter 4's loop closure through chapter 6's link motion) at the
    exercise's "See it" parameters, and its kinetic energy ½ vᵀ M v from its own mass matrix; the start satisfies the
    model's 8 constraints and their rates (checked to 1e-12). Same geometry by another code path: 1e-10."""
    exercise = _exercise("8-1-slider-crank-start")
    drawn = variant(exercise, number)
    params = SCENES["slider-crank-dae"].parameters.validate(exercise.scene.at(drawn.given)["params"])
    q, v = slider_crank_initial_state(params)
    linkage = slider_crank_linkage(params)
    g, C, _ = linkage.system().constraint_terms(q, v)
    assert np.max(np.abs(g)) <= 1e-12 and np.max(np.abs(C @ v)) <= 1e-12
    assert drawn.answers["phi"].value == pytest.approx(math.degrees(q[5]), rel=1e-10)
    assert drawn.answers["phi-rate"].value == pytest.approx(v[5], rel=1e-10)
    assert _close_vector(drawn.answers["vg2"].value, (v[3], v[4], 0.0), 1e-10)
    assert drawn.answers["energy"].value == pytest.approx(float(linkage.kinetic_energy_J(v)), rel=1e-10)


# -- 8.2 --------------------------------------------------------------------------------------------------------


def _rk4_amplification(alpha: float, h: float) -> np.ndarray:
    """One RK4 step of ė = A e for Baumgarte's error dynamics with α = β, as a matrix."""
    A = np.array([[0.0, 1.0], [-(alpha**2), -2.0 * alpha]])
    hA = h * A
    return np.eye(2) + hA + hA @ hA / 2 + hA @ hA @ hA / 6 + hA @ hA @ hA @ hA / 24


@pytest.mark.parametrize("number", VARIANTS)
def test_baumgartes_residual_and_rk4_step_from_the_error_equation(number):
    """e(t) from scipy's Radau on ë + 2αė + α²e = 0 at rtol 1e-12 (so 1e-8); the step limit where the spectral radius
    of RK4's one-step matrix reaches 1, found by brentq to 1e-14 s. That matrix has a double eigenvalue, which
    numpy's eigvals finds only to about √ε ≈ 1.5e-8; the radius rises at about 1.5 per unit of hα there, so the root
    moves by about 1e-8 relative: 1e-7. And with α = 0 the residual's extremes stay at ±e₀ over ten periods (to 1e-6
    of e₀): it oscillates, neither decaying nor growing."""
    drawn = variant(_exercise("8-2-baumgarte-critical"), number)
    g = drawn.given
    alpha, e0, t_end = g["alpha_1_s"], g["residual0_mm"], g["time_s"]
    solution = solve_ivp(
        lambda t, y: [y[1], -2 * alpha * y[1] - alpha**2 * y[0]],
        (0.0, t_end),
        [e0, 0.0],
        method="Radau",
        rtol=1e-12,
        atol=1e-16,
    )
    assert drawn.answers["residual"].value == pytest.approx(solution.y[0, -1], rel=1e-8)

    def radius(h):
        return float(np.max(np.abs(np.linalg.eigvals(_rk4_amplification(alpha, h))))) - 1.0

    limit = brentq(radius, 2.0 / alpha, 3.0 / alpha, xtol=1e-14)
    assert drawn.answers["step"].value == pytest.approx(limit, rel=1e-7)

    beta = alpha
    undamped = solve_ivp(
        lambda t, y: [y[1], -(beta**2) * y[0]],
        (0.0, 20 * math.pi / beta),
        [e0, 0.0],
        rtol=1e-12,
        atol=1e-16,
        dense_output=True,
    )
    samples = undamped.sol(np.linspace(0.0, 20 * math.pi / beta, 4001))[0]
    assert samples.max() == pytest.approx(e0, rel=1e-6) and samples.min() == pytest.approx(-e0, rel=1e-6)
    assert drawn.answers["undamped"].value == "oscillates"


@pytest.mark.parametrize("number", VARIANTS)
def test_the_pendulums_consistent_start_is_the_models_gauss_newton_start(number):
    """The Cartesian pendulum model's own consistent start (Gauss–Newton to |g| ≤ 1e-10 of the size², then the
    minimum-norm velocity correction) at the exercise's "See it" parameters: 1e-8. The tension λL from the model's
    M, f, C and c solved as one multiplier system: 1e-8."""
    exercise = _exercise("8-2-pendulum-consistent-start")
    drawn = variant(exercise, number)
    params = SCENES["cartesian-pendulum"].parameters.validate(exercise.scene.at(drawn.given)["params"])
    start = CartesianPendulum().consistent_start(params)
    assert _close_vector(drawn.answers["position"].value, (*start.q, 0.0), 1e-8)
    assert _close_vector(drawn.answers["velocity"].value, (*start.v, 0.0), 1e-8)
    system = pendulum_system(params["mass_kg"], params["length_m"], params["g_m_s2"])
    M, f = system.mass_and_forces(0.0, start.q, start.v)
    _, C, c = system.constraint_terms(start.q, start.v)
    _, multipliers = _solve_multipliers(M, f, C, c)
    assert drawn.answers["tension"].value == pytest.approx(multipliers[0] * params["length_m"], rel=1e-8)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_belts_limit_cycle_is_what_the_event_located_integration_finds(number):
    """The belt model integrated by Dormand–Prince at rtol 1e-10 with its located stick/slip events, from the
    exercise's start (x = 0, riding with the belt) for 12 closed-form periods: the last complete cycle's break-loose
    position, stick and slip durations and the heat (the integrated dissipation slot) between its events. Events are
    located to about 1e-9 s and the dissipation integrated to about rtol, so 1e-6."""
    exercise = _exercise("8-2-belt-stick-slip")
    drawn = variant(exercise, number)
    params = SCENES["stick-slip-belt"].parameters.validate(exercise.scene.at(drawn.given)["params"])
    period = drawn.answers["stick"].value + drawn.answers["slip"].value
    events = stick_slip_belt.transitions(params, t_end_s=12 * period, rtol=1e-10)
    breaks = [e for e in events if e.index == stick_slip_belt.STICK_BREAKS]
    sticks = [e for e in events if e.index == stick_slip_belt.SLIP_STOPS]
    last_break = breaks[-2]
    stick_start = max((e for e in sticks if e.t_s < last_break.t_s), key=lambda e: e.t_s)
    next_stick = min((e for e in sticks if e.t_s > last_break.t_s), key=lambda e: e.t_s)
    assert drawn.answers["break"].value == pytest.approx(last_break.state[stick_slip_belt.X], rel=1e-6)
    assert drawn.answers["stick"].value == pytest.approx(last_break.t_s - stick_start.t_s, rel=1e-6)
    assert drawn.answers["slip"].value == pytest.approx(next_stick.t_s - last_break.t_s, rel=1e-6)
    heat = next_stick.state[stick_slip_belt.DISSIPATED] - last_break.state[stick_slip_belt.DISSIPATED]
    assert drawn.answers["heat"].value == pytest.approx(heat, rel=1e-6)
