"""Chapter 2's exercises against an independent computation, over several variants each (tolerances stated at each
check): the path-variable exercises by the space-curve scene's own model (a curve typed as formulas, differentiated
symbolically by the app), the helix's curvature also by sympy, the sine slot and the moving point by sympy's
derivatives, and the launched ball by scipy's ODE solver with its landing and top as events."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import sympy
from scipy.integrate import solve_ivp

from app.physics.systems.ch02 import space_curve
from app.practice.exercise import Exercise, parse_exercise
from app.practice.variants import variant

EXERCISE_DIR = Path(__file__).resolve().parents[2] / "lessons" / "ch02" / "exercises"
VARIANTS = range(0, 100, 9)


def _exercise(exercise_id: str) -> Exercise:
    path = EXERCISE_DIR / f"{exercise_id}.md"
    return parse_exercise(path.read_text(encoding="utf-8"), str(path), chapter=2)


def _path_at(x: str, y: str, z: str, t_s: float, t_end_s: float) -> space_curve.PathVariables:
    """The space-curve model's path variables of the typed curve at ``t_s`` (one instant)."""
    curve = space_curve.compile_curve(x, y, z)
    return space_curve.path_variables(curve, t_s, space_curve.reference_scales(curve, t_end_s))


@pytest.mark.parametrize("number", VARIANTS)
def test_braking_on_a_bend_matches_the_space_curve_model(number):
    """The car as the curve ρ cos(s/ρ), ρ sin(s/ρ), 0 with s = v t − ½|v̇| t², its path variables at t = 0 from the
    space-curve model (symbolic derivatives, then floating point): a_n, |a| and the angle between a and v agree to
    1e-9 relative (the model's round-off is ~1e-15 of the numbers typed with 17 digits)."""
    drawn = variant(_exercise("2-1-braking-on-a-bend"), number)
    g = drawn.given
    rho, v, slow = g["radius_m"], g["speed_kmh"] / 3.6, g["slowing_m_s2"]
    s = f"({v!r}*t - {slow / 2!r}*t^2)"
    path = _path_at(f"{rho!r}*cos({s}/{rho!r})", f"{rho!r}*sin({s}/{rho!r})", "0", 0.0, 1.0)
    velocity, acceleration = path.velocity_m_s[0], path.acceleration_m_s2[0]
    assert path.a_tangential_m_s2[0] == pytest.approx(-slow, rel=1e-9)
    assert drawn.answers["normal"].value == pytest.approx(path.a_normal_m_s2[0], rel=1e-9)
    assert drawn.answers["total"].value == pytest.approx(float(np.linalg.norm(acceleration)), rel=1e-9)
    cos_angle = float(velocity @ acceleration) / (np.linalg.norm(velocity) * np.linalg.norm(acceleration))
    assert drawn.answers["angle"].value == pytest.approx(math.degrees(math.acos(cos_angle)), rel=1e-9)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_helix_matches_the_space_curve_model_and_sympys_curvature(number):
    """The helix traced at the given speed (φ = ω t, ω = v/√(a² + c²)) in the space-curve model at t = 0: ρ = 1/κ,
    a_n and the binormal agree to 1e-9 (round-off). The curvature expression equals sympy's |r'×r''|/|r'|³ of the
    helix (the difference simplifies to 0)."""
    drawn = variant(_exercise("2-1-helix-frenet"), number)
    g = drawn.given
    a, c, v = g["radius_m"], g["pitch_m"] / (2 * math.pi), g["speed_m_s"]
    w = v / math.hypot(a, c)
    path = _path_at(f"{a!r}*cos({w!r}*t)", f"{a!r}*sin({w!r}*t)", f"{c * w!r}*t", 0.0, 2 * math.pi / w)
    assert path.speed_m_s[0] == pytest.approx(v, rel=1e-12)
    assert drawn.answers["rho"].value == pytest.approx(1 / path.curvature_1_m[0], rel=1e-9)
    assert drawn.answers["normal"].value == pytest.approx(path.a_normal_m_s2[0], rel=1e-9)
    assert drawn.answers["binormal"].value == pytest.approx(tuple(path.binormal[0]), abs=1e-9)
    sa, sc, phi = sympy.symbols("a c phi", positive=True)
    r = sympy.Matrix([sa * sympy.cos(phi), sa * sympy.sin(phi), sc * phi])
    r1, r2 = r.diff(phi), r.diff(phi, 2)
    kappa = sympy.sqrt(sympy.simplify(r1.cross(r2).dot(r1.cross(r2)))) / sympy.sqrt(sympy.simplify(r1.dot(r1))) ** 3
    answer = drawn.answers["kappa"].value.subs(
        {s: {"a": sa, "c": sc}[s.name] for s in drawn.answers["kappa"].value.free_symbols}
    )
    assert sympy.simplify(kappa - answer) == 0


@pytest.mark.parametrize("number", VARIANTS)
def test_the_balls_path_variables_match_the_space_curve_model(number):
    """The flight v₀ cos α t, 0, v₀ sin α t − ½ g t² in the space-curve model at t₁: a_t, a_n and ρ = 1/κ agree to
    1e-9 relative (round-off of the model's symbolic derivatives evaluated in floating point)."""
    drawn = variant(_exercise("2-1-projectile-path-variables"), number)
    g = drawn.given
    alpha = math.radians(g["angle_deg"])
    vx, vz = g["speed_m_s"] * math.cos(alpha), g["speed_m_s"] * math.sin(alpha)
    path = _path_at(f"{vx!r}*t", "0", f"{vz!r}*t - {g['g_m_s2'] / 2!r}*t^2", g["time_s"], 2 * vz / g["g_m_s2"])
    assert drawn.answers["tangential"].value == pytest.approx(path.a_tangential_m_s2[0], rel=1e-9)
    assert drawn.answers["normal"].value == pytest.approx(path.a_normal_m_s2[0], rel=1e-9)
    assert drawn.answers["rho"].value == pytest.approx(1 / path.curvature_1_m[0], rel=1e-9)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_pin_in_the_slot_matches_sympys_derivatives(number):
    """y(t) = h sin(π u t/L) differentiated by sympy at t = x/u: the velocity and ÿ to 1e-12 (round-off). The peak
    |a| is the largest |ÿ| on 200 001 instants of one run: the grid misses the crest by at most half a step, which
    lowers |ÿ| by at most (π/100 000)²/2 ≈ 5e-10 of it, so 1e-9 relative."""
    drawn = variant(_exercise("2-2-pin-in-sine-slot"), number)
    g = drawn.given
    h, half, u, x = g["amplitude_m"], g["half_wavelength_m"], g["drive_speed_m_s"], g["x_m"]
    t = sympy.Symbol("t", real=True)
    y = h * sympy.sin(sympy.pi * u * t / half)
    ydot, yddot = sympy.diff(y, t), sympy.diff(y, t, 2)
    instant = x / u
    assert drawn.answers["velocity"].value == pytest.approx((u, float(ydot.subs(t, instant)), 0.0), rel=1e-12)
    assert drawn.answers["yddot"].value == pytest.approx(float(yddot.subs(t, instant)), rel=1e-12)
    times = np.linspace(0.0, 2 * half / u, 200_001)
    peak = float(np.max(np.abs(sympy.lambdify(t, yddot, "numpy")(times))))
    assert drawn.answers["peak"].value == pytest.approx(peak, rel=1e-9)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_launched_ball_matches_scipys_integration_with_events(number):
    """ẍ = ÿ = 0, z̈ = −g integrated by scipy (DOP853, rtol 1e-12) with the top (ż = 0) and the landing (z = 0,
    falling) as events: the times, the landing point and velocity agree to 1e-9 relative (the event roots are
    located to ~1e-12 s). The acceleration at the top, a central difference of the integrated velocity across the
    top, is −g K to 1e-6 (the difference's step 1e-4 s, round-off ~1e-12/1e-4)."""
    drawn = variant(_exercise("2-2-projectile-heading"), number)
    g = drawn.given
    v0, gg = g["speed_m_s"], g["g_m_s2"]
    alpha, psi = math.radians(g["elevation_deg"]), math.radians(g["heading_deg"])
    launch = v0 * np.array([math.cos(alpha) * math.cos(psi), math.cos(alpha) * math.sin(psi), math.sin(alpha)])

    def rhs(_t, y):
        return [y[3], y[4], y[5], 0.0, 0.0, -gg]

    def top(_t, y):
        return y[5]

    def landing(t, y):
        return y[2] if t > 0 else 1.0

    top.direction = -1
    landing.terminal, landing.direction = True, -1
    run = solve_ivp(
        rhs, (0.0, 100.0), [0.0, 0.0, 0.0, *launch], method="DOP853", rtol=1e-12, atol=1e-12, events=(top, landing)
    )
    t_top, t_land = run.t_events[0][0], run.t_events[1][0]
    state = run.y_events[1][0]
    assert drawn.answers["top-time"].value == pytest.approx(t_top, rel=1e-9)
    assert drawn.answers["top-time"].mistakes["full-flight"] == pytest.approx(t_land, rel=1e-9)
    reach = float(np.linalg.norm(state[:2]))
    assert np.linalg.norm(np.array(drawn.answers["landing"].value) - state[:3]) <= 1e-9 * reach
    assert np.linalg.norm(np.array(drawn.answers["landing-velocity"].value) - state[3:]) <= 1e-9 * v0
    step = 1e-4
    around = solve_ivp(
        rhs,
        (0.0, t_top + step),
        [0.0, 0.0, 0.0, *launch],
        method="DOP853",
        rtol=1e-12,
        atol=1e-12,
        t_eval=[t_top - step, t_top + step],
    )
    acceleration = (around.y[3:, 1] - around.y[3:, 0]) / (2 * step)
    assert acceleration == pytest.approx([0.0, 0.0, -gg], abs=1e-6 * gg)
    assert drawn.answers["top-acceleration"].value == "down-g"


@pytest.mark.parametrize("number", VARIANTS)
def test_the_elliptic_lift_matches_sympys_derivatives(number):
    """x, y, z differentiated by sympy: the acceleration and speed at t₁ agree to 1e-12 relative (round-off), and
    the ẍ expression equals sympy's second derivative of A cos ωt exactly."""
    drawn = variant(_exercise("2-2-elliptic-lift"), number)
    g = drawn.given
    t = sympy.Symbol("t", real=True)
    w = g["omega_rad_s"]
    position = sympy.Matrix([g["a_m"] * sympy.cos(w * t), g["b_m"] * sympy.sin(w * t), g["lift_m_s2"] * t**2])
    velocity = np.array(position.diff(t).subs(t, g["time_s"]), dtype=float).ravel()
    acceleration = np.array(position.diff(t, 2).subs(t, g["time_s"]), dtype=float).ravel()
    assert drawn.answers["acceleration"].value == pytest.approx(tuple(acceleration), rel=1e-12, abs=1e-12)
    assert drawn.answers["speed"].value == pytest.approx(float(np.linalg.norm(velocity)), rel=1e-12)
    expression = drawn.answers["xddot"].value
    names = {s.name: s for s in expression.free_symbols}
    assert (
        sympy.simplify(sympy.diff(names["A"] * sympy.cos(names["omega"] * names["t"]), names["t"], 2) - expression) == 0
    )


# -- 2.3 and 2.4 -------------------------------------------------------------------------------------------------


def _symbols_of(expression: sympy.Expr) -> dict[str, sympy.Symbol]:
    return {s.name: s for s in expression.free_symbols}


def _cylindrical_axes(theta: float) -> np.ndarray:
    """Rows e_R, e_θ, e_z at the azimuth θ, on XYZ."""
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])


def _sympy_motion(position: sympy.Matrix, t: sympy.Symbol, at: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Position, velocity and acceleration of a sympy position in t, evaluated at ``at``."""
    return tuple(np.array(position.diff(t, k).subs(t, at).evalf(30), dtype=float).ravel() for k in range(3))


@pytest.mark.parametrize("number", VARIANTS)
def test_the_conical_spiral_matches_the_curvilinear_scenes_model(number):
    """The curvilinear-coordinates scene's own model of the conical spiral (a Cartesian position differentiated by
    sympy, then R, θ and their rates found from x, y and their rates) at t: the cylindrical components of v and a
    agree with the answer's closed forms to 1e-9 of their size (floating-point round-off of the model's chain)."""
    from app.physics.systems.ch02.coordinate_paths import CoordinatePath

    drawn = variant(_exercise("2-3-conical-spiral-components"), number)
    g = drawn.given
    path = CoordinatePath("conical-spiral", g["size_m"], g["azimuth_rate_rad_s"], math.radians(g["cone_deg"]))
    _, velocity_xyz, _, kinematics = path.describe("cylindrical", g["time_s"])
    for part, model in (("velocity", kinematics.velocity[0]), ("acceleration", kinematics.acceleration[0])):
        answer = np.array(drawn.answers[part].value)
        assert np.linalg.norm(answer - model) <= 1e-9 * np.linalg.norm(model), (part, answer, model)
    assert drawn.answers["speed"].value == pytest.approx(float(np.linalg.norm(velocity_xyz[0])), rel=1e-9)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_bead_on_the_spinning_hoop_matches_sympys_cartesian_derivatives(number):
    """The bead's Cartesian position R(sin φ cos Ωt, sin φ sin Ωt, cos φ) with φ(t) = φ₀ + φ̇t + ½φ̈t², differentiated
    twice by sympy and projected on (e_r, e_φ, e_θ) at t = 0: the acceleration agrees to 1e-12 of its size
    (round-off), the push is m|a·e_θ| to 1e-12; and the a_θ formula equals sympy's symbolic projection exactly."""
    drawn = variant(_exercise("2-3-bead-on-hoop-spherical"), number)
    g = drawn.given
    t = sympy.Symbol("t", real=True)
    phi0 = sympy.pi * sympy.Rational(str(g["polar_deg"])) / 180
    phi = phi0 + sympy.Rational(str(g["phi_rate_rad_s"])) * t + sympy.Rational(str(g["phi_accel_rad_s2"])) * t**2 / 2
    spin, radius = sympy.Rational(str(g["hoop_rate_rad_s"])), sympy.Rational(str(g["hoop_radius_m"]))
    position = radius * sympy.Matrix(
        [sympy.sin(phi) * sympy.cos(spin * t), sympy.sin(phi) * sympy.sin(spin * t), sympy.cos(phi)]
    )
    _, _, accel = _sympy_motion(position, t, 0.0)
    p = float(phi0)
    axes = np.array([[math.sin(p), 0.0, math.cos(p)], [math.cos(p), 0.0, -math.sin(p)], [0.0, 1.0, 0.0]])
    expected = axes @ accel
    answer = np.array(drawn.answers["acceleration"].value)
    assert np.linalg.norm(answer - expected) <= 1e-12 * np.linalg.norm(expected)
    assert drawn.answers["push"].value == pytest.approx(g["mass_kg"] * abs(expected[2]), rel=1e-12)
    formula = drawn.answers["a-theta"].value
    names = _symbols_of(formula)
    big_r, f, fd, om = names["R"], sympy.Function("f")(t), names["phid"], names["Omega"]
    general = big_r * sympy.Matrix([sympy.sin(f) * sympy.cos(om * t), sympy.sin(f) * sympy.sin(om * t), sympy.cos(f)])
    e_theta = sympy.Matrix([-sympy.sin(om * t), sympy.cos(om * t), 0])
    projected = (general.diff(t, 2).T * e_theta)[0]
    projected = projected.subs(sympy.Derivative(f, (t, 2)), 0).subs(sympy.Derivative(f, t), fd).subs(f, names["phi"])
    assert sympy.simplify(projected - formula) == 0


@pytest.mark.parametrize("number", VARIANTS)
def test_the_straight_road_matches_sympys_polar_derivatives(number):
    """R(t) = |(x + vt, d)| and θ(t) = atan2(d, x + vt) differentiated by sympy at t = 0: Ṙ, θ̇ and R̈ agree to
    1e-12 relative (round-off), and the θ̈ formula evaluated at those R, Ṙ, θ̇ gives sympy's θ̈ to 1e-12."""
    drawn = variant(_exercise("2-3-straight-road-polar"), number)
    g = drawn.given
    t = sympy.Symbol("t", real=True)
    x = sympy.Rational(str(g["x_m"])) + sympy.Rational(str(g["speed_m_s"])) * t
    d = sympy.Rational(str(g["offset_m"]))
    big_r, theta = sympy.sqrt(x**2 + d**2), sympy.atan2(d, x)

    def rate(expr: sympy.Expr, k: int) -> float:
        return float(expr.diff(t, k).subs(t, 0).evalf(30))

    assert drawn.answers["rdot"].value == pytest.approx(rate(big_r, 1), rel=1e-12)
    assert drawn.answers["thetadot"].value == pytest.approx(rate(theta, 1), rel=1e-12)
    assert drawn.answers["rddot"].value == pytest.approx(rate(big_r, 2), rel=1e-12)
    formula = drawn.answers["thetaddot"].value
    names = _symbols_of(formula)
    at = {names["R"]: rate(big_r, 0), names["Rdot"]: rate(big_r, 1), names["thetad"]: rate(theta, 1)}
    assert float(formula.subs(at)) == pytest.approx(rate(theta, 2), rel=1e-12)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_collars_path_variables_match_sympys_cartesian_motion(number):
    """The collar's Cartesian position r(t)(cos θ(t), sin θ(t), 0) from the statement, differentiated by sympy at t:
    a projected on the arm's unit vectors, the speed, a_t = v·a/v and a_n = |v × a|/v agree to 1e-12 of |a| or v
    (round-off)."""
    drawn = variant(_exercise("2-4-collar-path-variables"), number)
    g = drawn.given
    t = sympy.Symbol("t", real=True)

    def q(name: str) -> sympy.Rational:
        return sympy.Rational(str(g[name]))

    theta = q("arm_rate_rad_s") * t + q("arm_accel_rad_s2") * t**2 / 2
    r = q("collar_mean_m") + q("collar_amplitude_m") * sympy.sin(q("collar_frequency_rad_s") * t)
    position = sympy.Matrix([r * sympy.cos(theta), r * sympy.sin(theta), 0])
    _, velocity, accel = _sympy_motion(position, t, g["time_s"])
    angle = float(theta.subs(t, sympy.Rational(str(g["time_s"]))))
    on_arm = _cylindrical_axes(angle) @ accel
    size, speed = float(np.linalg.norm(accel)), float(np.linalg.norm(velocity))
    assert np.linalg.norm(np.array(drawn.answers["acceleration"].value) - on_arm) <= 1e-12 * size
    assert drawn.answers["speed"].value == pytest.approx(speed, rel=1e-12)
    assert drawn.answers["tangential"].value == pytest.approx(float(velocity @ accel) / speed, abs=1e-12 * size)
    assert drawn.answers["normal"].value == pytest.approx(
        float(np.linalg.norm(np.cross(velocity, accel))) / speed, abs=1e-12 * size
    )


@pytest.mark.parametrize("number", VARIANTS)
def test_the_bead_down_the_helix_matches_scipys_integration_of_lagranges_equation(number):
    """The bead's Lagrange equation in θ, (R² + c²)θ̈ = −g c with c = R tan γ, integrated by scipy (DOP853, rtol and
    atol 1e-13) from rest until z = cθ = −h (an event): θ̇ there, the Cartesian acceleration ∂²r/∂θ² θ̇² + ∂r/∂θ θ̈
    projected on the cylindrical unit vectors, and ρ = v³/|v × a|, agree with the answers to 1e-9 relative (the
    event's root and the integration are good to ~1e-12)."""
    drawn = variant(_exercise("2-4-bead-down-helix"), number)
    g = drawn.given
    radius, gg, drop = g["radius_m"], g["g_m_s2"], g["drop_m"]
    c = radius * math.tan(math.radians(g["climb_deg"]))
    theta_ddot = -gg * c / (radius**2 + c**2)

    def landing(_t, y):
        return c * y[0] + drop

    landing.terminal, landing.direction = True, -1
    run = solve_ivp(
        lambda _t, y: [y[1], theta_ddot], (0.0, 100.0), [0.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-13,
        events=landing,
    )  # fmt: skip
    theta, theta_dot = run.y_events[0][0]
    dr = np.array([-radius * math.sin(theta), radius * math.cos(theta), c])
    ddr = np.array([-radius * math.cos(theta), -radius * math.sin(theta), 0.0])
    velocity, accel = dr * theta_dot, ddr * theta_dot**2 + dr * theta_ddot
    on_cylinder = _cylindrical_axes(theta) @ accel
    assert drawn.answers["theta-rate"].value == pytest.approx(theta_dot, rel=1e-9)
    assert np.linalg.norm(np.array(drawn.answers["acceleration"].value) - on_cylinder) <= 1e-9 * np.linalg.norm(accel)
    rho = float(np.linalg.norm(velocity)) ** 3 / float(np.linalg.norm(np.cross(velocity, accel)))
    assert drawn.answers["rho"].value == pytest.approx(rho, rel=1e-9)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_car_seen_from_the_rim_matches_sympys_polar_derivatives(number):
    """The car as C + b(cos ψ, sin ψ) with ψ = 2θ₀ + vt/b (C = (b, 0), the camera at O), its range and bearing
    about O differentiated by sympy at t = 0: Ṙ, θ̇ (the formula at the given v, b) and the acceleration projected
    on (e_R, e_θ) agree to 1e-12 relative (round-off)."""
    drawn = variant(_exercise("2-4-car-seen-from-the-rim"), number)
    g = drawn.given
    t = sympy.Symbol("t", real=True)
    b, v = sympy.Rational(str(g["track_radius_m"])), sympy.Rational(str(g["speed_m_s"]))
    psi = 2 * sympy.pi * sympy.Rational(str(g["bearing_deg"])) / 180 + v * t / b
    position = sympy.Matrix([b + b * sympy.cos(psi), b * sympy.sin(psi), 0])
    big_r, theta = sympy.sqrt(position[0] ** 2 + position[1] ** 2), sympy.atan2(position[1], position[0])
    theta_now = float(theta.subs(t, 0))
    assert theta_now == pytest.approx(math.radians(g["bearing_deg"]), rel=1e-12)
    assert drawn.answers["rdot"].value == pytest.approx(float(big_r.diff(t).subs(t, 0)), rel=1e-12)
    formula = drawn.answers["thetadot"].value
    names = _symbols_of(formula)
    at = {names["v"]: g["speed_m_s"], names["b"]: g["track_radius_m"]}
    assert float(formula.subs(at)) == pytest.approx(float(theta.diff(t).subs(t, 0)), rel=1e-12)
    _, _, accel = _sympy_motion(position, t, 0.0)
    polar = _cylindrical_axes(theta_now) @ accel
    assert drawn.answers["a-radial"].value == pytest.approx(polar[0], rel=1e-12)
    assert drawn.answers["a-transverse"].value == pytest.approx(polar[1], rel=1e-12)
