"""Chapter 6's answer functions against independent computations, over several variants each (tolerances stated and
justified at each check): the project's own models where the answer function used a closed form (the unbalanced
rotor, the sliding ladder, the slider-crank's 8×8 Newton–Euler solve, the disks' impulse law), brute-force particle
sums for inertia (plates and bars cut into many small masses), linear solves of the free-body equations written
afresh, sympy derivations by Lagrange's equations from position vectors, and scipy ODE solutions with tight
tolerances."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import sympy
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from app.physics.systems.ch06 import mechanism_kinetics, planar_collision, sliding_ladder
from app.physics.systems.ch06.unbalanced_rotor import UnbalancedRotor
from app.practice.exercise import parse_exercise
from app.practice.variants import variant
from app.scenes import SCENES

EXERCISE_DIR = Path(__file__).resolve().parents[2] / "lessons" / "ch06" / "exercises"
VARIANTS = range(0, 100, 9)


def _exercise(exercise_id: str):
    path = EXERCISE_DIR / f"{exercise_id}.md"
    return parse_exercise(path.read_text(encoding="utf-8"), str(path), chapter=6)


def _drawn(exercise_id: str, number: int):
    return variant(_exercise(exercise_id), number)


def _bar_particles(length: float, n: int = 4000) -> np.ndarray:
    """Midpoints of n equal pieces of [0, length]. The midpoint rule is exact for first moments; for a second
    moment about a point at the bar's end or inside it, its relative error is at most 1/n² (6.3e-8 for n = 4000)."""
    return (np.arange(n) + 0.5) * length / n


# -- 6.1 --------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", VARIANTS)
def test_the_rotor_loads_are_the_unbalanced_rotor_models(number):
    """The scene's own model (the disk's tensor turned onto the skewed axes, moments about bearing A, then the
    force balance) at the exercise's "See it" parameters. Same physics by another route, so round-off only: 1e-10."""
    exercise = _exercise("6-1-rotor-bearing-loads")
    drawn = variant(exercise, number)
    params = SCENES["unbalanced-rotor"].parameters.validate(exercise.scene.at(drawn.given)["params"])
    rotor = UnbalancedRotor.from_params(params)
    force, moment_about_a = rotor.inertial_loads_rotor()
    part = rotor.disk.part()
    couple = moment_about_a - np.cross(part.centre_m, force)  # ω × H_G: the moment about G alone
    assert drawn.answers["static"].value == pytest.approx(np.linalg.norm(force), rel=1e-10)
    assert drawn.answers["couple"].value == pytest.approx(np.linalg.norm(couple), rel=1e-10)
    bearing_a = np.linalg.norm(rotor.steady_loads().bearing_A_rotating_rotor_N)
    assert drawn.answers["bearing-a"].value == pytest.approx(bearing_a, rel=1e-10)


def test_the_hinged_bars_equation_is_lagranges_from_its_particles_and_the_steady_state_balances():
    """θ̈ from Lagrange's equations for the bar as a continuum, its points' positions written in the fixed frame
    (sympy, exact: the difference simplifies to 0). The steady angle is the root of that θ̈ found by brentq
    (xtol 1e-14 rad, so 1e-9 relative in degrees). The hinge force is m a_G − m g with a_G summed over 4000
    particles each on its own circle: first moments, so the midpoint sums are exact to round-off (1e-10)."""
    exercise = _exercise("6-1-hinged-bar-on-shaft")
    theta, Omega, L, g, m, s, t = sympy.symbols("theta Omega L g m s t", real=True)
    q = sympy.Function("q")(t)
    point = sympy.Matrix(
        [s * sympy.sin(q) * sympy.cos(Omega * t), s * sympy.sin(q) * sympy.sin(Omega * t), -s * sympy.cos(q)]
    )
    speed2 = sympy.simplify(point.diff(t).dot(point.diff(t)))
    kinetic = sympy.integrate(m / L * speed2 / 2, (s, 0, L))
    potential = sympy.integrate(m / L * g * point[2], (s, 0, L))
    lagrangian = kinetic - potential
    qd = sympy.Symbol("qd")
    equation = sympy.diff(lagrangian, q.diff(t)).diff(t) - sympy.diff(lagrangian, q)
    acceleration = sympy.solve(equation, q.diff(t, 2))[0]
    acceleration = acceleration.subs(q.diff(t), qd).subs(q, theta)
    for number in VARIANTS:
        drawn = variant(exercise, number)
        assert sympy.simplify(acceleration - drawn.answers["equation"].value) == 0
        given = drawn.given
        numeric = sympy.lambdify(
            theta, acceleration.subs({Omega: given["spin_rad_s"], L: given["length_m"], g: given["g_m_s2"]})
        )
        steady = brentq(numeric, 1e-3, math.pi / 2 - 1e-9, xtol=1e-14)
        assert drawn.answers["steady"].value == pytest.approx(math.degrees(steady), rel=1e-9)
        radii = _bar_particles(given["length_m"]) * math.sin(steady)
        dm = given["mass_kg"] / radii.size
        horizontal = float(np.sum(dm * radii * given["spin_rad_s"] ** 2))
        assert drawn.answers["hinge"].value == pytest.approx(
            math.hypot(horizontal, given["mass_kg"] * given["g_m_s2"]), rel=1e-10
        )


@pytest.mark.parametrize("number", VARIANTS)
def test_the_plate_on_its_diagonal_matches_its_particles(number):
    """H_G = Σ mᵢ ρᵢ × (ω × ρᵢ) over a 600 × 600 grid of cell centres. On a uniform grid the midpoint rule gives
    every second moment (1 − 1/n²) times its exact value and the products exactly 0, so H, ω × H and the force are
    all low by the same factor 1/n² = 2.8e-6: tolerance 3e-6."""
    drawn = _drawn("6-1-plate-about-diagonal", number)
    given = drawn.given
    a, b, mass, w = given["side_a_m"], given["side_b_m"], given["mass_kg"], given["speed_rad_s"]
    n = 600
    x = (np.arange(n) + 0.5) * a / n - a / 2
    y = (np.arange(n) + 0.5) * b / n - b / 2
    X, Y = np.meshgrid(x, y)
    points = np.stack([X.ravel(), Y.ravel(), np.zeros(X.size)], axis=1)
    omega = w * np.array([a, b, 0.0]) / math.hypot(a, b)
    h = (mass / X.size) * np.sum(np.cross(points, np.cross(omega, points)), axis=0)
    moment = np.linalg.norm(np.cross(omega, h))
    assert np.allclose(drawn.answers["h"].value, h, rtol=3e-6, atol=1e-12)
    assert drawn.answers["moment"].value == pytest.approx(moment, rel=3e-6)
    assert drawn.answers["force"].value == pytest.approx(moment / given["span_m"], rel=3e-6)


# -- 6.2 --------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", range(0, 100, 20))
def test_the_ladder_at_release_is_the_sliding_ladder_models(number):
    """The model's contact dynamics (its own 3×3 solve for θ̈, N_A, N_B, written with the friction terms) at the
    initial state: round-off only, 1e-10. The angle where the top leaves the wall is the model's event, located on
    a Dormand–Prince solution at rtol 1e-10: agreement to 1e-7."""
    exercise = _exercise("6-2-ladder-at-release")
    drawn = variant(exercise, number)
    params = SCENES["sliding-ladder"].parameters.validate(exercise.scene.at(drawn.given)["params"])
    contact = sliding_ladder.contact_forces(params, sliding_ladder.initial_state(params))[0]
    assert drawn.answers["alpha"].value == pytest.approx(contact[sliding_ladder.C_ANGULAR_ACC], rel=1e-10)
    assert drawn.answers["wall"].value == pytest.approx(contact[sliding_ladder.C_WALL_N], rel=1e-10)
    assert drawn.answers["floor"].value == pytest.approx(contact[sliding_ladder.C_FLOOR_N], rel=1e-10)
    changes = sliding_ladder.phase_changes(params, t_end_s=30.0)
    release = next(c for c in changes if c.index == sliding_ladder.WALL_RELEASE)
    assert drawn.answers["leave"].value == pytest.approx(math.degrees(release.state[sliding_ladder.THETA]), rel=1e-7)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_spool_solves_its_free_body_equations_and_balances_power(number):
    """The four equations written afresh about G (force along and across the floor, moment about G, rolling) and
    solved with numpy for (a, α, F, N): round-off, 1e-10. Independently, the power balance: the cord's power
    P·v_hub-point equals dT/dt (friction and the normal force do no work on a rolling body), 1e-10."""
    drawn = _drawn("6-2-spool-pulled", number)
    given = drawn.given
    m, R, r, k = given["mass_kg"], given["rim_m"], given["hub_m"], given["gyration_m"]
    pull, phi, g = given["pull_n"], math.radians(given["angle_deg"]), given["g_m_s2"]
    # Unknowns u = (a, α, F, N); α counterclockwise, x along the pull, the cord leaves the hub at r(sin φ, −cos φ).
    K = np.array(
        [
            [m, 0.0, -1.0, 0.0],  # m a = P cos φ + F
            [0.0, 0.0, 0.0, 1.0],  # N = m g − P sin φ
            [0.0, m * k**2, -R, 0.0],  # m k² α = r P + R F  (moments about G of the cord and of friction at (0, −R))
            [1.0, R, 0.0, 0.0],  # rolling: a = −R α
        ]
    )
    f = np.array([pull * math.cos(phi), m * g - pull * math.sin(phi), r * pull, 0.0])
    a, alpha, friction, normal = np.linalg.solve(K, f)
    assert drawn.answers["accel"].value == pytest.approx(a, rel=1e-10)
    assert drawn.answers["friction"].value == pytest.approx(friction, rel=1e-10)
    assert drawn.answers["mu"].value == pytest.approx(abs(friction) / normal, rel=1e-10)
    assert drawn.answers["direction"].value == ("toward" if a > 0 else "away")
    # Power, at a speed v: the hub point moves at v_G + ω k × r_p with ω = −v/R.
    v = 1.7
    spin = -v / R
    hub_point = r * np.array([math.sin(phi), -math.cos(phi)])
    point_velocity = np.array([v, 0.0]) + spin * np.array([-hub_point[1], hub_point[0]])
    power = pull * np.dot([math.cos(phi), math.sin(phi)], point_velocity)
    kinetic_rate = m * v * drawn.answers["accel"].value + m * k**2 * spin * (-drawn.answers["accel"].value / R)
    assert kinetic_rate == pytest.approx(power, rel=1e-10)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_cut_bar_matches_its_particles(number):
    """The bar as 4000 particles: I_O = Σ mᵢ (xᵢ − s)² (relative error ≤ 1/n² = 6.3e-8), gravity's moment about
    the pin Σ mᵢ g (xᵢ − s) (exact), the pin force from Newton's law over the particles' accelerations
    α (xᵢ − s). Tolerance 1e-6."""
    drawn = _drawn("6-2-bar-support-cut", number)
    given = drawn.given
    mass, length, s, g = given["mass_kg"], given["length_m"], given["pin_m"], given["g_m_s2"]
    x = _bar_particles(length)
    dm = mass / x.size
    arm = x - s
    alpha = np.sum(dm * g * arm) / np.sum(dm * arm**2)
    pin = mass * g - np.sum(dm * alpha * arm)
    assert drawn.answers["alpha"].value == pytest.approx(alpha, rel=1e-6)
    assert drawn.answers["pin"].value == pytest.approx(pin, rel=1e-6)
    assert drawn.answers["end"].value == pytest.approx(alpha * (length - s), rel=1e-6)


# -- 6.3 --------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", VARIANTS)
def test_the_dead_centre_forces_are_the_mechanism_models(number):
    """The scene's model: chapter 4's loop-closure kinematics and its 8×8 Newton–Euler solve for every pin force
    and the torque, at θ = 0 with the crank's speed held. Round-off only: 1e-9 (absolute 1e-9 N for zero parts)."""
    exercise = _exercise("6-3-slider-crank-dead-centre")
    drawn = variant(exercise, number)
    params = SCENES["slider-crank-kinetics"].parameters.validate(exercise.scene.at(drawn.given)["params"])
    links = mechanism_kinetics.SliderCrankLinks.from_params(params)
    w = params["crank_speed_rad_s"]
    motion = mechanism_kinetics.link_motion(links, 0.0, w, 0.0)
    forces = mechanism_kinetics.newton_euler(links, np.array([0.0]), np.array([w]), crank_acceleration_rad_s2=0.0)
    assert drawn.answers["slider-acc"].value == pytest.approx(motion.slider_acceleration[0, 0], rel=1e-9)
    pin = np.array([*forces.crank_pin_A_N[0], 0.0])
    assert np.allclose(drawn.answers["pin-a"].value, pin, rtol=1e-9, atol=1e-9)
    assert drawn.answers["torque"].value == pytest.approx(forces.driving_torque_N_m[0], rel=1e-9)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_pulley_system_obeys_work_energy_and_its_free_body_equations(number):
    """The acceleration from work–energy over a distance D (½(m₁ + m₂)v² + ½ I (v/R)² = (m₂ g − μ m₁ g) D, so
    a = v²/2D), with the pulley's I = ½ M R² summed over 300 × 720 polar cells (ring centroid radii: error below
    1e-9); the tensions from the four free-body equations solved with numpy. Tolerance 1e-8."""
    drawn = _drawn("6-3-block-pulley-hanging", number)
    given = drawn.given
    m1, m2, M, R, mu, g = (
        given["table_kg"],
        given["hanging_kg"],
        given["pulley_kg"],
        given["pulley_radius_m"],
        given["mu"],
        given["g_m_s2"],
    )
    edges = np.linspace(0.0, R, 301)
    ring_mass = M * (edges[1:] ** 2 - edges[:-1] ** 2) / R**2
    ring_r2 = (edges[1:] ** 2 + edges[:-1] ** 2) / 2  # exact mean of r² over each annulus
    inertia = float(np.sum(ring_mass * ring_r2))
    distance = 0.8
    v2 = 2 * (m2 * g - mu * m1 * g) * distance / (m1 + m2 + inertia / R**2)
    assert drawn.answers["accel"].value == pytest.approx(v2 / (2 * distance), rel=1e-8)
    # u = (a, α, T1, T2)
    K = np.array([[m1, 0, -1, 0], [m2, 0, 0, 1], [0, inertia, R, -R], [1, -R, 0, 0]], dtype=float)
    f = np.array([-mu * m1 * g, m2 * g, 0.0, 0.0])
    a, _, t1, t2 = np.linalg.solve(K, f)
    assert drawn.answers["accel"].value == pytest.approx(a, rel=1e-8)
    assert drawn.answers["table"].value == pytest.approx(t1, rel=1e-8)
    assert drawn.answers["hanging"].value == pytest.approx(t2, rel=1e-8)


def _cart_bar_rhs():
    """Cart (x) and bar (θ from the downward vertical, its lower end trailing behind for θ > 0) by Lagrange's
    equations from the bar's particles' positions, with a viscous damper c at the pin: the state derivative and
    the bar's centre-of-mass acceleration, as numeric functions."""
    x, th, xd, thd = sympy.symbols("x th xd thd", real=True)
    M, m, L, g, F, c, s, t = sympy.symbols("M m L g F c s t", positive=True)
    X, TH = sympy.Function("X")(t), sympy.Function("TH")(t)
    point = sympy.Matrix([X - s * sympy.sin(TH), -s * sympy.cos(TH)])
    speed2 = point.diff(t).dot(point.diff(t))
    kinetic = M * X.diff(t) ** 2 / 2 + sympy.integrate(m / L * speed2 / 2, (s, 0, L))
    potential = sympy.integrate(m / L * g * point[1], (s, 0, L))
    lagrangian = kinetic - potential
    forces = {X: F, TH: -c * TH.diff(t)}
    equations = [sympy.diff(lagrangian, q.diff(t)).diff(t) - sympy.diff(lagrangian, q) - forces[q] for q in (X, TH)]
    plain = {X.diff(t, 2): sympy.Symbol("xdd"), TH.diff(t, 2): sympy.Symbol("thdd")}
    plain_rates = {X.diff(t): xd, TH.diff(t): thd}
    equations = [e.subs(plain).subs(plain_rates).subs({X: x, TH: th}) for e in equations]
    solved = sympy.solve(equations, [sympy.Symbol("xdd"), sympy.Symbol("thdd")], dict=True)[0]
    xdd, thdd = solved[sympy.Symbol("xdd")], solved[sympy.Symbol("thdd")]
    centre = sympy.Matrix([x - L / 2 * sympy.sin(th), -L / 2 * sympy.cos(th)])
    # a_G = ∂²/∂t² of the centre, with ẍ, θ̈ from the solution.
    jac = centre.jacobian([x, th])
    centre_acc = jac * sympy.Matrix([xdd, thdd]) + sympy.Matrix(
        [L / 2 * sympy.sin(th) * thd**2, L / 2 * sympy.cos(th) * thd**2]
    )
    args = (x, th, xd, thd, M, m, L, g, F, c)
    return sympy.lambdify(args, [xdd, thdd]), sympy.lambdify(args, list(centre_acc))


def test_the_cart_and_bar_settle_to_the_steady_answer():
    """The full two-degree-of-freedom motion from rest (bar hanging straight down), with a damper at the pin
    (damping ratio about 0.3 of the bar's swing), integrated by scipy's DOP853 at rtol 1e-11 for 60 s, by which
    time the swing has decayed by e⁻³⁰ or more. Then: the cart's acceleration, the bar's angle and the pin force
    m a_G − m g agree with the steady answers to 1e-7."""
    exercise = _exercise("6-3-cart-pendulum")
    accelerations, centre_acceleration = _cart_bar_rhs()
    for number in range(0, 100, 20):
        drawn = variant(exercise, number)
        given = drawn.given
        M, m, L, F, g = given["cart_kg"], given["bar_kg"], given["length_m"], given["force_n"], given["g_m_s2"]
        swing = math.sqrt(3 * g / (2 * L))
        damping = 2 * 0.3 * swing * (m * L**2 / 3)

        def rhs(_t, y, M=M, m=m, L=L, F=F, g=g, damping=damping):
            xdd, thdd = accelerations(y[0], y[1], y[2], y[3], M, m, L, g, F, damping)
            return [y[2], y[3], xdd, thdd]

        solution = solve_ivp(rhs, (0.0, 60.0), [0.0, 0.0, 0.0, 0.0], method="DOP853", rtol=1e-11, atol=1e-12)
        x, th, xd, thd = solution.y[:, -1]
        xdd, _ = accelerations(x, th, xd, thd, M, m, L, g, F, damping)
        a_g = np.array(centre_acceleration(x, th, xd, thd, M, m, L, g, F, damping), dtype=float)
        pin = m * (a_g - np.array([0.0, -g]))
        assert drawn.answers["accel"].value == pytest.approx(xdd, rel=1e-7)
        assert drawn.answers["angle"].value == pytest.approx(math.degrees(th), rel=1e-7)
        assert drawn.answers["pin"].value == pytest.approx(np.linalg.norm(pin), rel=1e-7)


# -- 6.4 --------------------------------------------------------------------------------------------------------


def test_the_struck_bar_matches_its_particles_and_a_symbolic_derivation():
    """Impulse–momentum over 4000 particles with rigid velocities vᵢ = v_G + ω xᵢ: Σ mᵢ vᵢ = P and Σ mᵢ xᵢ vᵢ = P d
    solved for (v_G, ω) (second moment: relative error ≤ 1/n² = 6.3e-8; tolerance 1e-6). The far end's velocity
    by sympy from the continuum (exact), and the centre of percussion as the root, by brentq, of the particle
    model's far-end velocity in d (xtol 1e-13 m; tolerance 1e-6)."""
    exercise = _exercise("6-4-struck-bar")
    P, m, L, d, x, vG, w = sympy.symbols("P m L d x v_G omega", real=True)
    equations = [
        sympy.integrate(m / L * (vG + w * x), (x, -L / 2, L / 2)) - P,
        sympy.integrate(m / L * x * (vG + w * x), (x, -L / 2, L / 2)) - P * d,
    ]
    solved = sympy.solve(equations, [vG, w], dict=True)[0]
    far_end = solved[vG] + solved[w] * (-L / 2)  # the struck side is x > 0
    for number in VARIANTS:
        drawn = variant(exercise, number)
        given = drawn.given
        mass, length, impulse, offset = given["mass_kg"], given["length_m"], given["impulse_ns"], given["offset_m"]
        xs = _bar_particles(length) - length / 2
        dm = mass / xs.size

        def model(d_value, xs=xs, dm=dm, impulse=impulse):
            K = np.array([[dm * xs.size, np.sum(dm * xs)], [np.sum(dm * xs), np.sum(dm * xs**2)]])
            return np.linalg.solve(K, [impulse, impulse * d_value])

        v_centre, spin = model(offset)
        assert drawn.answers["vg"].value == pytest.approx(v_centre, rel=1e-6)
        assert drawn.answers["omega"].value == pytest.approx(spin, rel=1e-6)
        assert sympy.simplify(far_end - drawn.answers["far-end"].value) == 0
        still = brentq(
            lambda d_value, half=length / 2: model(d_value)[0] - model(d_value)[1] * half, 0.0, length / 2, xtol=1e-13
        )
        assert drawn.answers["percussion"].value == pytest.approx(still, rel=1e-6)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_disk_collision_is_the_impulse_laws(number):
    """The project's impulse law (Stronge's energetic restitution with Coulomb friction followed along the normal
    impulse, :func:`planar_collision.collide`) on the same two disks; the energy lost from the disks' kinetic
    energies before and after. Closed-form phases, so round-off only: 1e-9."""
    drawn = _drawn("6-4-disk-collision", number)
    given = drawn.given
    inputs = {
        "m1_kg": given["m1_kg"],
        "m2_kg": given["m2_kg"],
        "r1_m": given["r1_m"],
        "r2_m": given["r2_m"],
        "v1_m_s": [given["speed_m_s"], 0.0, 0.0],
        "v2_m_s": [0.0, 0.0, 0.0],
        "omega1_rad_s": 0.0,
        "omega2_rad_s": 0.0,
        "line_of_centres_deg": given["beta_deg"],
        "restitution": given["restitution"],
        "friction_coefficient": given["mu"],
    }
    collision = planar_collision.collide(inputs)
    assert drawn.answers["pn"].value == pytest.approx(collision.impact.impulse_N_s[0], rel=1e-9)
    state = {"slid throughout": "slid", "stuck": "stuck", "reversed": "reversed"}[collision.impact.slip_state]
    assert drawn.answers["slip"].value == state
    assert drawn.answers["spin2"].value == pytest.approx(collision.after[1].spin_rad_s, rel=1e-9)
    lost = collision.energy_before_J - sum(disk.kinetic_energy_J for disk in collision.after)
    assert drawn.answers["loss"].value == pytest.approx(lost, rel=1e-9)


def test_the_swinging_bar_matches_an_ode_solution():
    """The bar's swing integrated by scipy's DOP853 (rtol 1e-12) from rest at θ₀, with I_O and gravity's moment
    summed over 4000 particles (I_O to 1/n² = 6.3e-8): ω at the bottom (found as an event) and ω² at θ₀/2, θ₀/4
    agree with the answers to 1e-6; the pivot force there, m g plus the particles' centripetal forces, to 1e-6."""
    exercise = _exercise("6-4-pendulum-energy")
    theta, theta0, g_symbol, L_symbol = sympy.symbols("theta theta0 g L", real=True)
    for number in VARIANTS:
        drawn = variant(exercise, number)
        given = drawn.given
        mass, length, angle0, g = (
            given["mass_kg"],
            given["length_m"],
            math.radians(given["angle0_deg"]),
            given["g_m_s2"],
        )
        s = _bar_particles(length)
        dm = mass / s.size
        inertia, first = np.sum(dm * s**2), np.sum(dm * s)

        def rhs(_t, y, inertia=inertia, first=first, g=g):
            return [y[1], -first * g * math.sin(y[0]) / inertia]

        def bottom(_t, y):
            return y[0]

        bottom.terminal = True
        solution = solve_ivp(
            rhs, (0.0, 60.0), [angle0, 0.0], method="DOP853", rtol=1e-12, atol=1e-14, events=bottom, dense_output=True
        )
        spin = abs(solution.y_events[0][0][1])
        assert drawn.answers["omega"].value == pytest.approx(spin, rel=1e-6)
        expression = drawn.answers["omega-squared"].value
        for fraction in (0.5, 0.25):
            when = brentq(
                lambda t, f=fraction, sol=solution.sol, start=angle0: sol(t)[0] - f * start,
                0.0,
                solution.t_events[0][0],
                xtol=1e-14,
            )
            expected = solution.sol(when)[1] ** 2
            value = float(expression.subs({theta: fraction * angle0, theta0: angle0, g_symbol: g, L_symbol: length}))
            assert value == pytest.approx(expected, rel=1e-6)
        pivot = mass * g + np.sum(dm * s * spin**2)
        assert drawn.answers["pivot"].value == pytest.approx(pivot, rel=1e-6)
