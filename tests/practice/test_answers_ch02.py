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
