"""Chapter 1's exercises against an independent computation, over several variants each (tolerances stated at each
check): the arm's cable by the lesson's closed forms and a second point on the line of action, the pole's hinge by a
determinant about another point of the axis and by a virtual rotation, the radar by sympy's derivative of the position,
the drag by pint's units and an integrated fall, the linear-drag fall by scipy's ODE solver, the bat by a force pulse
integrated in time."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pint
import pytest
import sympy
from scipy.integrate import quad, solve_ivp
from scipy.spatial.transform import Rotation

from app.practice.exercise import Exercise, parse_exercise
from app.practice.variants import variant

EXERCISE_DIR = Path(__file__).resolve().parents[2] / "lessons" / "ch01" / "exercises"
VARIANTS = range(0, 100, 9)


def _exercise(exercise_id: str) -> Exercise:
    path = EXERCISE_DIR / f"{exercise_id}.md"
    return parse_exercise(path.read_text(encoding="utf-8"), str(path), chapter=1)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_arm_cable_answers_match_the_lessons_closed_forms(number):
    """The lesson's closed forms M_A = (T x_D/|CD|)(z_C j − y_C k), M_z = −T x_D y_C/|CD|, M_AB = T x_D z_C sin θ/|CD|
    (moments taken at D, the cable's other end), and F_BC from the angle between the cable and BC. Both sides are a few
    dozen double-precision operations, so they agree to ~1e-15; 1e-10 relative leaves room without hiding a wrong
    formula (a wrong term changes the answer by percent)."""
    drawn = variant(_exercise("1-1-arm-cable-moments"), number)
    g = drawn.given
    th, ga, tension, x_d = math.radians(g["theta_deg"]), math.radians(g["gamma_deg"]), g["tension_n"], g["anchor_x_m"]
    reach = 2.0 + 1.5 * math.cos(ga)  # horizontal distance of C from A
    x_c, y_c, z_c = reach * math.cos(th), reach * math.sin(th), 1.5 * math.sin(ga)
    cd = math.sqrt((x_d - x_c) ** 2 + y_c**2 + z_c**2)
    force = tension / cd * np.array([x_d - x_c, -y_c, -z_c])
    e_bc = np.array([math.cos(ga) * math.cos(th), math.cos(ga) * math.sin(th), math.sin(ga)])
    cos_angle = float(force @ e_bc) / tension
    assert drawn.answers["force"].value == pytest.approx(tuple(force), rel=1e-10)
    assert drawn.answers["f-bc"].value == pytest.approx(tension * cos_angle, rel=1e-10)
    assert drawn.answers["m-z"].value == pytest.approx(-tension * x_d * y_c / cd, rel=1e-10)
    assert drawn.answers["m-ab"].value == pytest.approx(tension * x_d * z_c * math.sin(th) / cd, rel=1e-10)
    moment_at_d = np.cross([x_d, 0.0, 0.0], force)
    assert np.linalg.norm(moment_at_d) == pytest.approx(drawn.answers["m-ab"].mistakes["magnitude"], rel=1e-10)
    r_b = 2.0 * np.array([math.cos(th), math.sin(th), 0.0])
    assert np.cross(r_b, force)[2] == pytest.approx(drawn.answers["m-z"].mistakes["point-b"], rel=1e-10)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_poles_hinge_moment_is_the_triple_product_about_another_point_and_the_work_of_a_virtual_rotation(number):
    """M_e as the determinant [e; r_D − r_E; F] (the anchor D on the line of action, the point E on the axis) agrees
    to 1e-10 relative (round-off only); and the work F·δr of a small rotation δ of the pole about the axis, by a
    central difference of scipy's rotation with δ = 1e-5 rad (error ~δ² ≈ 1e-10 of the moment), agrees to 1e-8."""
    drawn = variant(_exercise("1-1-guyed-pole-hinge"), number)
    g = drawn.given
    b = np.array([0.0, 0.0, g["height_m"]])
    d = np.array([g["anchor_x_m"], g["anchor_y_m"], 0.0])
    e_point = np.array([g["hinge_x_m"], g["hinge_y_m"], 0.0])
    force = g["tension_n"] * (d - b) / np.linalg.norm(d - b)
    e = e_point / np.linalg.norm(e_point)
    assert drawn.answers["force"].value == pytest.approx(tuple(force), rel=1e-12)
    assert drawn.answers["moment-o"].value == pytest.approx(tuple(np.cross(d, force)), rel=1e-10)
    determinant = float(np.linalg.det(np.array([e, d - e_point, force])))
    assert drawn.answers["hinge"].value == pytest.approx(determinant, rel=1e-10)
    delta = 1e-5
    moved = [Rotation.from_rotvec(s * delta * e).apply(b) for s in (1.0, -1.0)]
    virtual_work = float(force @ (moved[0] - moved[1])) / (2 * delta)
    assert drawn.answers["hinge"].value == pytest.approx(virtual_work, rel=1e-8)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_radar_velocity_is_sympys_derivative_of_the_position(number):
    """The position r cos β cos θ, … with r, θ, β linear in t through the given values and rates, differentiated by
    sympy and evaluated at t = 0: the velocity and speed agree to 1e-12 relative (round-off only). The expression part
    is sympy's derivative of r(t) cos β(t) cos θ(t), exactly (the difference simplifies to 0)."""
    exercise = _exercise("1-1-radar-velocity")
    drawn = variant(exercise, number)
    g = drawn.given
    t = sympy.Symbol("t", real=True)
    r = g["range_m"] + g["range_rate_m_s"] * t
    th = sympy.rad(sympy.Float(g["azimuth_deg"])) + g["azimuth_rate_rad_s"] * t
    be = sympy.rad(sympy.Float(g["elevation_deg"])) + g["elevation_rate_rad_s"] * t
    position = [r * sympy.cos(be) * sympy.cos(th), r * sympy.cos(be) * sympy.sin(th), r * sympy.sin(be)]
    velocity = np.array([float(sympy.diff(c, t).subs(t, 0)) for c in position])
    assert drawn.answers["velocity"].value == pytest.approx(tuple(velocity), rel=1e-12)
    assert drawn.answers["speed"].value == pytest.approx(float(np.linalg.norm(velocity)), rel=1e-12)
    rf, thf, bef = (sympy.Function(n)(t) for n in ("r", "theta", "beta"))
    derivative = sympy.diff(rf * sympy.cos(bef) * sympy.cos(thf), t)
    names = {n: sympy.Symbol(n, real=True) for n in ("r", "rd", "theta", "thetad", "beta", "betad")}
    derivative = derivative.subs(
        {
            sympy.Derivative(rf, t): names["rd"],
            sympy.Derivative(thf, t): names["thetad"],
            sympy.Derivative(bef, t): names["betad"],
        }
    ).subs({rf: names["r"], thf: names["theta"], bef: names["beta"]})
    assert sympy.simplify(derivative - drawn.answers["xdot"].value) == 0


@pytest.mark.parametrize("number", VARIANTS)
def test_the_drag_numbers_follow_from_pints_units_and_an_integrated_fall(number):
    """c and the drag computed with pint quantities (kg/m³ × m² …, converted to N): 1e-12 relative, round-off only.
    The terminal speed is where a fall from rest, m v̇ = m g − c v² integrated by scipy (DOP853, rtol 1e-12) for
    30 v_t/g, levels off; the approach is as tanh, within 1e-25 by then, so the integrator's 1e-10 sets the
    tolerance. The unit choice is kg/m because c's dimension is a mass per length (pint)."""
    exercise = _exercise("1-2-drag-terminal-speed")
    drawn = variant(exercise, number)
    g = drawn.given
    ureg = pint.UnitRegistry()
    rho = g["air_density_kg_m3"] * ureg.kilogram / ureg.meter**3
    area = math.pi * (g["diameter_m"] * ureg.meter / 2) ** 2
    c = 0.5 * rho * g["drag_coefficient"] * area
    assert c.dimensionality == (ureg.kilogram / ureg.meter).dimensionality
    assert drawn.answers["unit"].value == "kg-per-m"
    drag = (c * (g["speed_m_s"] * ureg.meter / ureg.second) ** 2).to(ureg.newton)
    weight = (g["mass_kg"] * ureg.kilogram * g["g_m_s2"] * ureg.meter / ureg.second**2).to(ureg.newton)
    assert drawn.answers["drag"].value == pytest.approx(drag.magnitude, rel=1e-12)
    assert drawn.answers["ratio"].value == pytest.approx((drag / weight).to("").magnitude, rel=1e-12)
    m, cc, gg = g["mass_kg"], c.to("kg/m").magnitude, g["g_m_s2"]
    v_scale = math.sqrt(m * gg / cc)
    fall = solve_ivp(
        lambda _t, v: [gg - cc * v[0] ** 2 / m],
        (0.0, 30 * v_scale / gg),
        [0.0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-12 * v_scale,
    )
    assert drawn.answers["terminal"].value == pytest.approx(float(fall.y[0, -1]), rel=1e-10)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_linear_drag_fall_matches_scipys_integration(number):
    """m v̇ = m g − b v, ż = v and Ẇ_drag = −b v² integrated by scipy (DOP853, rtol 1e-12, atol 1e-12 of the scale)
    to t₁: the speed expression (at t₁ and at 5 other instants) and the drag work agree to 1e-9 relative, the
    integrator's error; the terminal speed is where the integrated speed levels off after 40 time constants
    (e^-40 ≈ 4e-18 short of it)."""
    exercise = _exercise("1-2-falling-linear-drag")
    drawn = variant(exercise, number)
    g = drawn.given
    m, b, t1, gg = g["mass_kg"], g["drag_kg_s"], g["time_s"], g["g_m_s2"]

    def rhs(_t, y):
        v = y[0]
        return [gg - b * v / m, v, -b * v**2]

    scale = m * gg / b
    times = np.linspace(0.0, t1, 6)[1:]
    run = solve_ivp(rhs, (0.0, t1), [0.0, 0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-12 * scale, t_eval=times)
    expression = drawn.answers["speed"].value
    symbols = {s.name: s for s in expression.free_symbols}
    for t, v in zip(times, run.y[0]):
        ours = float(expression.subs({symbols["m"]: m, symbols["b"]: b, symbols["g"]: gg, symbols["t"]: t}))
        assert ours == pytest.approx(v, rel=1e-9)
    assert drawn.answers["work"].value == pytest.approx(run.y[2, -1], rel=1e-9)
    long_run = solve_ivp(rhs, (0.0, 40 * m / b), [0.0, 0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-12 * scale)
    assert drawn.answers["terminal"].value == pytest.approx(long_run.y[0, -1], rel=1e-9)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_bats_impulse_turns_v1_into_v2_when_applied_as_a_force_pulse(number):
    """The answer's impulse applied as a half-sine force pulse over the contact time and integrated by scipy (DOP853,
    rtol 1e-12): the ball's velocity goes from v₁ to v₂ (built from the speeds and angles), and the pulse's work
    ∫F·v dt equals the answer's work, both to 1e-9 relative; the pulse's mean force |∫F dt|/Δt by quadrature equals
    the average force to 1e-10."""
    exercise = _exercise("1-2-bat-impulse")
    drawn = variant(exercise, number)
    g = drawn.given
    m, contact = g["mass_kg"], g["contact_ms"] / 1000.0
    d, a = math.radians(g["in_angle_deg"]), math.radians(g["out_angle_deg"])
    v1 = g["in_speed_m_s"] * np.array([-math.cos(d), 0.0, -math.sin(d)])
    v2 = g["out_speed_m_s"] * np.array([math.cos(a), 0.0, math.sin(a)])
    impulse = np.array(drawn.answers["impulse"].value)

    def force(t: float) -> np.ndarray:
        return impulse * (math.pi / (2 * contact)) * math.sin(math.pi * t / contact)

    def rhs(t, y):
        f = force(t)
        return [*(f / m), float(f @ y[:3])]

    run = solve_ivp(rhs, (0.0, contact), [*v1, 0.0], method="DOP853", rtol=1e-12, atol=1e-12)
    scale = float(np.linalg.norm(v2))
    assert np.linalg.norm(run.y[:3, -1] - v2) <= 1e-9 * scale
    assert drawn.answers["work"].value == pytest.approx(run.y[3, -1], rel=1e-9)
    mean = np.array([quad(lambda t, i=i: force(t)[i], 0.0, contact, epsabs=0.0, epsrel=1e-13)[0] for i in range(3)])
    assert drawn.answers["force"].value == pytest.approx(float(np.linalg.norm(mean)) / contact, rel=1e-10)
