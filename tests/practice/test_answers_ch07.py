"""Chapter 7's new exercises against independent computations, over several variants each (tolerances stated and
justified at each check): the project's own models where the answer function used a closed form (the toggle press's
six-equation Newton solve, the slider-crank's 8×8 Newton–Euler solve, the sliding hoop's snapshot, the derivation
engine's Lagrange equations of the pendulum on a cart and of the bead on a hoop), central finite differences of
positions for virtual displacements and generalized forces, sympy derivations of Lagrange's equations from position
vectors, numerical Jacobians of the engine's equations for equilibria and natural frequencies, and scipy ODE solutions
with tight tolerances for finite motions."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import sympy
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from app.physics.mechanics.engine import derived
from app.physics.systems.ch06 import mechanism_kinetics
from app.physics.systems.ch07 import bead_on_hoop, configuration_space, pendulum_on_cart, virtual_work
from app.practice.exercise import parse_exercise
from app.practice.variants import variant

EXERCISE_DIR = Path(__file__).resolve().parents[2] / "lessons" / "ch07" / "exercises"
VARIANTS = range(0, 100, 9)
#: Step of the central differences: their truncation error is about h²/6 of the third derivative (≈ 2e-13 of the
#: value for these trigonometric geometries) and their round-off about 1e-16/h ≈ 1e-10 of the value, so 1e-7 relative
#: leaves a margin of a thousand.
H = 1e-6
FD_REL = 1e-7


def _drawn(exercise_id: str, number: int):
    path = EXERCISE_DIR / f"{exercise_id}.md"
    return variant(parse_exercise(path.read_text(encoding="utf-8"), str(path), chapter=7), number)


def _derivative(function, at: float, h: float = H) -> np.ndarray:
    """d function/dq at q = at by a central difference (arrays in, arrays out)."""
    return (np.asarray(function(at + h), dtype=float) - np.asarray(function(at - h), dtype=float)) / (2 * h)


def _jacobian(function, state: np.ndarray, h: float = H) -> np.ndarray:
    columns = []
    for i in range(len(state)):
        step = np.zeros_like(state)
        step[i] = h
        columns.append((function(state + step) - function(state - step)) / (2 * h))
    return np.array(columns).T


# -- 7.1 --------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", VARIANTS)
def test_the_toggle_hold_is_the_six_equation_newton_solve_and_its_displacements_are_position_differences(number):
    """Q against the project's Newton statics of both bars (six equations, pin forces included): the same statics by
    another route, round-off only, 1e-9. δr_B and x_C′ against central differences of the press's points at θ ± h
    (FD_REL)."""
    drawn = _drawn("7-1-toggle-press-hold", number)
    given = drawn.given

    def press(angle_rad: float) -> virtual_work.TogglePress:
        return virtual_work.TogglePress(
            given["bar_ab_m"],
            given["bar_bc_m"],
            angle_rad,
            given["load_n"],
            given["weight_ab_n"],
            given["weight_bc_n"],
        )

    angle = math.radians(given["angle_deg"])
    newton = virtual_work.toggle_equilibrium(press(angle))
    assert drawn.answers["hold"].value == pytest.approx(newton.holding_force_N, rel=1e-9)
    knee = _derivative(lambda q: press(q).points()["B"], angle)
    slider = _derivative(lambda q: press(q).points()["C"][0], angle)
    assert np.allclose(drawn.answers["knee"].value[:2], knee, rtol=FD_REL, atol=FD_REL * given["bar_ab_m"])
    assert drawn.answers["knee"].value[2] == 0.0
    assert drawn.answers["slider"].value == pytest.approx(float(slider), rel=FD_REL)


def _scissor_pins(stages: int, length: float, angle: float) -> tuple[np.ndarray, list[tuple[np.ndarray, np.ndarray]]]:
    """The lift built bar by bar from its ground pins up: each X is two bars that cross at their midpoints; the ends
    of one X are the pins of the next. Returns the bottom slider's position and every bar's two ends."""
    left, right = np.array([0.0, 0.0]), np.array([length * math.cos(angle), 0.0])
    slider = right.copy()
    bars = []
    for _ in range(stages):
        rise = np.array([0.0, length * math.sin(angle)])
        top_left, top_right = left + rise, right + rise
        bars += [(left, top_right), (right, top_left)]
        assert math.isclose(np.linalg.norm(top_right - left), length) and math.isclose(
            np.linalg.norm(top_left - right), length
        )
        left, right = top_left, top_right
    return slider, bars


@pytest.mark.parametrize("number", VARIANTS)
def test_the_scissor_lifts_force_is_the_energy_balance_of_the_lift_built_bar_by_bar(number):
    """The lift built pin by pin; its total potential V(θ) (platform at the top pins, each bar's weight at the mean
    of its ends) and the slider's x(θ) differenced centrally: F = −V′/x′ (virtual work of a push along −x). The
    rise is the top pins' height differenced. FD_REL."""
    drawn = _drawn("7-1-scissor-lift-force", number)
    given = drawn.given
    stages, length = round(given["stages"]), given["bar_m"]

    def potential(angle: float) -> float:
        _, bars = _scissor_pins(stages, length, angle)
        top = max(end[1] for bar in bars for end in bar)
        return given["platform_n"] * top + sum(given["bar_n"] * 0.5 * (a[1] + b[1]) for a, b in bars)

    def height(angle: float) -> float:
        return max(end[1] for bar in _scissor_pins(stages, length, angle)[1] for end in bar)

    angle = math.radians(given["angle_deg"])
    slider = _derivative(lambda q: _scissor_pins(stages, length, q)[0][0], angle)
    force = -float(_derivative(potential, angle)) / float(slider)
    assert drawn.answers["force"].value == pytest.approx(force, rel=FD_REL)
    assert drawn.answers["rise"].value == pytest.approx(float(_derivative(height, angle)), rel=FD_REL)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_crank_torque_is_the_newton_euler_solve_of_lesson_six_three(number):
    """τ against the project's 8×8 Newton–Euler solve (pin forces and the guide force as unknowns) at the same
    instant, and x_B′, ẍ_B against its link kinematics: two routes to the same equations, round-off only, 1e-9."""
    drawn = _drawn("7-1-crank-drive-torque", number)
    given = drawn.given
    links = mechanism_kinetics.SliderCrankLinks.from_params(
        {
            "crank_m": given["crank_m"],
            "rod_m": given["rod_m"],
            "offset_m": 0.0,
            "crank_mass_kg": given["crank_kg"],
            "rod_mass_kg": given["rod_kg"],
            "slider_mass_kg": given["slider_kg"],
            "g_m_s2": given["g_m_s2"],
        }
    )
    theta = np.array([math.radians(given["angle_deg"])])
    omega = np.array([given["speed_rad_s"]])
    forces = mechanism_kinetics.newton_euler(links, theta, omega, crank_acceleration_rad_s2=0.0)
    assert drawn.answers["torque"].value == pytest.approx(float(forces.driving_torque_N_m[0]), rel=1e-9)
    motion = mechanism_kinetics.link_motion(links, theta, omega, np.zeros(1))
    assert drawn.answers["slider-accel"].value == pytest.approx(float(motion.slider_acceleration[0, 0]), rel=1e-9)
    rate = float(motion.slider_velocity[0, 0]) / given["speed_rad_s"]
    assert drawn.answers["slider-rate"].value == pytest.approx(rate, rel=1e-9)


# -- 7.2 --------------------------------------------------------------------------------------------------------


def _degrees_of_freedom(constraints, q: np.ndarray) -> int:
    """Coordinates less the rank of the constraints' Jacobian (by central differences) at q."""
    return len(q) - int(np.linalg.matrix_rank(_jacobian(constraints, q), tol=1e-6))


_WORDS = {1: "one", 2: "two", 3: "three", 4: "four"}


@pytest.mark.parametrize("number", VARIANTS)
def test_the_double_pendulums_coordinates_count_position_and_speed(number):
    """DOF: four Cartesian coordinates less the rank of the rods' two length constraints (exact integer). The bob
    by complex numbers, z₂ = −i(l₁e^{iθ₁} + l₂e^{iθ₂}) (round-off, 1e-12); its speed from a central difference of z₂
    along θ(t) = θ + θ̇ t (FD_REL)."""
    drawn = _drawn("7-2-double-pendulum-coords", number)
    given = drawn.given
    l1, l2 = given["upper_m"], given["lower_m"]
    t1, t2 = math.radians(given["theta1_deg"]), math.radians(given["theta2_deg"])

    def rod(length: float, angle: float, rate: float, time: float) -> complex:
        """A rod hanging at ``angle`` from the downward vertical, as a complex number x + iy (y up)."""
        return -1j * length * np.exp(1j * (angle + rate * time))

    def bob(time: float) -> complex:
        return rod(l1, t1, given["rate1_rad_s"], time) + rod(l2, t2, given["rate2_rad_s"], time)

    upper, z = rod(l1, t1, 0.0, 0.0), bob(0.0)
    cartesian = np.array([upper.real, upper.imag, z.real, z.imag])

    def constraints(q: np.ndarray) -> np.ndarray:
        return np.array([q[0] ** 2 + q[1] ** 2 - l1**2, (q[2] - q[0]) ** 2 + (q[3] - q[1]) ** 2 - l2**2])

    assert drawn.answers["dof"].value == _WORDS[_degrees_of_freedom(constraints, cartesian)]
    assert np.allclose(drawn.answers["bob"].value, (z.real, z.imag, 0.0), rtol=1e-12, atol=1e-12)
    speed = abs((bob(H) - bob(-H)) / (2 * H))
    assert drawn.answers["speed"].value == pytest.approx(speed, rel=FD_REL)


def _circle_meet(a: np.ndarray, b_len: float, o4: np.ndarray, c_len: float) -> list[np.ndarray]:
    """The two points at distance b_len from a and c_len from o4 (the radical-line construction)."""
    span = o4 - a
    e = float(np.linalg.norm(span))
    along = (b_len**2 - c_len**2 + e**2) / (2 * e)
    across = math.sqrt(b_len**2 - along**2)
    unit = span / e
    normal = np.array([-unit[1], unit[0]])
    return [a + along * unit + across * normal, a + along * unit - across * normal]


@pytest.mark.parametrize("number", VARIANTS)
def test_the_four_bars_rocker_from_meeting_circles_and_its_rate_by_differences(number):
    """B where the circles about A (radius b) and O₄ (radius c) meet, the one above the line A→O₄ chosen by the
    sign of a cross product; θ₄ from B (round-off, 1e-9). ω₄ = ω₂ dθ₄/dθ₂ by a central difference of that
    construction (FD_REL, with an absolute floor of 1e-7·ω₂ for a rocker that is nearly at rest). DOF from the rank
    of the loop equations' Jacobian in (θ₂, θ₃, θ₄)."""
    drawn = _drawn("7-2-four-bar-constraints", number)
    given = drawn.given
    a, b, c, d = given["crank_m"], given["coupler_m"], given["rocker_m"], given["ground_m"]
    o4 = np.array([d, 0.0])

    def rocker(crank: float) -> float:
        pin_a = a * np.array([math.cos(crank), math.sin(crank)])
        span = o4 - pin_a
        upper = [p for p in _circle_meet(pin_a, b, o4, c) if span[0] * (p - pin_a)[1] - span[1] * (p - pin_a)[0] > 0]
        (pin_b,) = upper
        return math.atan2(pin_b[1], pin_b[0] - d)

    crank = math.radians(given["crank_deg"])
    assert drawn.answers["rocker"].value == pytest.approx(math.degrees(rocker(crank)), rel=1e-9)
    rate = given["crank_rate_rad_s"] * float(_derivative(rocker, crank))
    assert drawn.answers["rocker-rate"].value == pytest.approx(rate, rel=FD_REL, abs=1e-7 * given["crank_rate_rad_s"])
    t4 = rocker(crank)
    pin_b = o4 + c * np.array([math.cos(t4), math.sin(t4)])
    pin_a = a * np.array([math.cos(crank), math.sin(crank)])
    t3 = math.atan2(*(pin_b - pin_a)[::-1])

    def loop(q: np.ndarray) -> np.ndarray:
        return (
            a * np.array([math.cos(q[0]), math.sin(q[0])])
            + b * np.array([math.cos(q[1]), math.sin(q[1])])
            - c * np.array([math.cos(q[2]), math.sin(q[2])])
            - o4
        )

    assert np.allclose(loop(np.array([crank, t3, t4])), 0.0, atol=1e-12)
    assert drawn.answers["dof"].value == _WORDS[_degrees_of_freedom(loop, np.array([crank, t3, t4]))]


@pytest.mark.parametrize("number", VARIANTS)
def test_the_spool_by_its_instant_centre_and_the_rank_of_its_constraints(number):
    """The spool turns about its contact point at v/R; the hub's lowest point is R − r above it, so the cord's end
    moves at (R − r) v/R: integrated over the travel by solve_ivp (rtol 1e-12) it must match Δs to 1e-9. The turn:
    the rim's contact arc equals the travel (the ODE for φ, the same tolerance). DOF: three coordinates less the rank
    of the two constraints; "holonomic": the rolling one-form dx − R dφ is exact (its coefficients' cross
    derivatives agree, sympy)."""
    drawn = _drawn("7-2-spool-rolling-cord", number)
    given = drawn.given
    outer, hub, travel = given["outer_m"], given["hub_m"], given["travel_m"]

    def rates(_t: float, y: np.ndarray) -> list[float]:
        spin = 1.0 / outer  # the centre moves at 1 m/s: rotation about the contact point at v/R
        return [1.0, spin, spin * (outer - hub)]

    end = solve_ivp(rates, (0.0, travel), [0.0, 0.0, 0.0], rtol=1e-12, atol=1e-14).y[:, -1]
    assert drawn.answers["cord"].value == pytest.approx(end[2], rel=1e-9)
    assert drawn.answers["turn"].value == pytest.approx(math.degrees(end[1]), rel=1e-9)

    def constraints(q: np.ndarray) -> np.ndarray:
        return np.array([q[0] - outer * q[1], q[2] - q[0] + hub * q[1]])

    assert drawn.answers["dof"].value == _WORDS[_degrees_of_freedom(constraints, np.array([0.3, 0.2, 0.1]))]
    x, phi, big_r = sympy.symbols("x phi R")
    form = (sympy.Integer(1), -big_r)  # coefficients of dx and dφ
    exact = sympy.diff(form[0], phi) == sympy.diff(form[1], x)
    assert drawn.answers["kind"].value == ("holonomic" if exact else "nonholonomic")


# -- 7.3 --------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", VARIANTS)
def test_the_sliding_hoop_is_the_scenes_snapshot(number):
    """The scene's own model of the rheonomic hoop (SlidingHoop.snapshot at the given t): velocity, ∇g·ṙ and the
    angle between ṙ and δr. Same formulas by another hand, round-off only, 1e-10; and ∇g·ṙ + ∂g/∂t = 0."""
    drawn = _drawn("7-3-sliding-hoop-bead", number)
    given = drawn.given
    hoop = configuration_space.SlidingHoop(
        given["hoop_radius_m"], given["amplitude_m"], given["hoop_rate_rad_s"], given["bead_rate_rad_s"]
    )
    snap = hoop.snapshot(given["time_s"])
    assert np.allclose(drawn.answers["velocity"].value[:2], snap.velocity, rtol=1e-10, atol=1e-12)
    assert drawn.answers["grad-dot"].value == pytest.approx(snap.gradient_along_velocity, rel=1e-10)
    assert drawn.answers["angle"].value == pytest.approx(snap.angle_between_deg, rel=1e-10)
    assert abs(snap.actual_variation) < 1e-12


@pytest.mark.parametrize("number", VARIANTS)
def test_the_ladders_turning_point_and_displacements_from_position_differences(number):
    """δy_B and δr_P by central differences of the positions (FD_REL); the turning point from A's differenced
    virtual displacement and the ladder's differenced rotation, p = r_A + (k × δr_A)/δφ, and the same from B
    (FD_REL)."""
    drawn = _drawn("7-3-ladder-instant-centre", number)
    given = drawn.given
    length, d = given["length_m"], given["point_m"]

    def ends(angle: float) -> np.ndarray:
        return np.array([length * math.cos(angle), 0.0, 0.0, length * math.sin(angle)])

    def point(angle: float) -> np.ndarray:
        foot, top = ends(angle)[:2], ends(angle)[2:]
        return foot + d * (top - foot) / length

    def direction(angle: float) -> float:
        foot, top = ends(angle)[:2], ends(angle)[2:]
        return math.atan2(top[1] - foot[1], top[0] - foot[0])

    angle = math.radians(given["angle_deg"])
    rates = _derivative(ends, angle)
    spin = float(_derivative(direction, angle))
    assert drawn.answers["top"].value == pytest.approx(rates[3], rel=FD_REL)
    for position, velocity in ((ends(angle)[:2], rates[:2]), (ends(angle)[2:], rates[2:])):
        centre = position + np.array([-velocity[1], velocity[0]]) / spin
        assert np.allclose(drawn.answers["centre"].value[:2], centre, rtol=FD_REL, atol=FD_REL * length)
    assert np.allclose(drawn.answers["point"].value[:2], _derivative(point, angle), rtol=FD_REL, atol=FD_REL * length)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_knife_edge_manoeuvre_integrated_leg_by_leg(number):
    """The four legs integrated by solve_ivp (rtol 1e-12) with q̇ = s·drive or α·turn, the constraint's own fields;
    the net step matches to 1e-9 of s, and its part to the right of the heading too. Admissible δq: the project's
    covector annihilates drive and turn and not a sideways step."""
    drawn = _drawn("7-3-knife-edge-parking", number)
    given = drawn.given
    s, alpha = given["drive_m"], math.radians(given["turn_deg"])
    q = np.array([0.0, 0.0, math.radians(given["heading_deg"])])
    for drive, turn in ((s, 0.0), (0.0, alpha), (-s, 0.0), (0.0, -alpha)):

        def field(_t: float, y: np.ndarray, drive=drive, turn=turn) -> np.ndarray:
            return drive * configuration_space.drive_field(y) + turn * configuration_space.turn_field(y)

        q = solve_ivp(field, (0.0, 1.0), q, rtol=1e-12, atol=1e-14).y[:, -1]
    assert abs(q[2] - math.radians(given["heading_deg"])) < 1e-10
    assert np.allclose(drawn.answers["step"].value[:2], q[:2], rtol=1e-9, atol=1e-9 * s)
    heading = math.radians(given["heading_deg"])
    right = np.array([math.sin(heading), -math.cos(heading)])
    assert drawn.answers["sideways"].value == pytest.approx(float(q[:2] @ right), rel=1e-9)
    at = np.array([0.3, -0.2, heading])
    covector = configuration_space.knife_edge_covector(at)
    assert abs(covector @ configuration_space.drive_field(at)) < 1e-15
    assert abs(covector @ configuration_space.turn_field(at)) < 1e-15
    assert abs(covector @ np.array([right[0], right[1], 0.0])) > 0.5
    assert drawn.answers["admissible"].value == "roll-and-turn"


# -- 7.4 --------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", VARIANTS)
def test_the_cart_pendulums_generalized_forces_are_differenced_virtual_work(number):
    """Q_j = Σ F·∂r/∂q_j with ∂r/∂q_j by central differences of the cart's and bob's positions (FD_REL of the
    largest term); the rod's equal and opposite pulls (any tension) sum to zero virtual work in δx."""
    drawn = _drawn("7-4-cart-pendulum-forces", number)
    given = drawn.given
    length, angle, x = given["length_m"], math.radians(given["theta_deg"]), given["x_m"]

    def positions(q: np.ndarray) -> np.ndarray:
        return np.array([q[0], 0.0, q[0] + length * math.sin(q[1]), -length * math.cos(q[1])])

    forces = np.array(
        [given["push_n"] - given["stiffness_n_m"] * x, 0.0, given["pull_n"], -given["bob_kg"] * given["g_m_s2"]]
    )
    jac = _jacobian(positions, np.array([x, angle]))
    q = forces @ jac
    scale = float(np.abs(forces).max()) * max(1.0, length)
    assert drawn.answers["qx"].value == pytest.approx(q[0], abs=FD_REL * scale)
    assert drawn.answers["qtheta"].value == pytest.approx(q[1], abs=FD_REL * scale)
    along = np.array([math.sin(angle), -math.cos(angle)])  # cart → bob
    tension = 37.0
    rod = np.concatenate([tension * along, -tension * along])  # on the cart towards the bob; on the bob back
    assert abs(rod @ jac[:, 0]) < 1e-9 * tension
    assert drawn.answers["rod"].value == "zero"


@pytest.mark.parametrize("number", VARIANTS)
def test_the_elbow_motors_generalized_forces_in_both_coordinate_sets(number):
    """Virtual work of F on the lower bob and of the motor, τ times the change of the angle between the rods
    (read back from the rods' directions with atan2), differenced centrally in each coordinate of each set
    (FD_REL of the largest term)."""
    drawn = _drawn("7-4-double-pendulum-motor", number)
    given = drawn.given
    l1, l2, force, torque = given["upper_m"], given["lower_m"], given["force_n"], given["torque_n_m"]

    def work(absolute: np.ndarray) -> float:
        """F x₂ + τ (angle of the lower rod − angle of the upper rod), as a potential-like work function."""
        elbow = l1 * np.array([math.sin(absolute[0]), -math.cos(absolute[0])])
        bob = elbow + l2 * np.array([math.sin(absolute[1]), -math.cos(absolute[1])])
        upper_dir = math.atan2(elbow[1], elbow[0])
        lower_dir = math.atan2(bob[1] - elbow[1], bob[0] - elbow[0])
        return force * bob[0] + torque * (lower_dir - upper_dir)

    t1, t2 = math.radians(given["theta1_deg"]), math.radians(given["theta2_deg"])
    scale = force * (l1 + l2) + torque
    absolute = _jacobian(lambda q: np.array([work(q)]), np.array([t1, t2]))[0]
    assert drawn.answers["q1"].value == pytest.approx(absolute[0], abs=FD_REL * scale)
    assert drawn.answers["q2"].value == pytest.approx(absolute[1], abs=FD_REL * scale)
    relative = _jacobian(lambda q: np.array([work(np.array([q[0], q[0] + q[1]]))]), np.array([t1, t2 - t1]))[0]
    assert drawn.answers["q1-relative"].value == pytest.approx(relative[0], abs=FD_REL * scale)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_sprung_bars_potential_and_generalized_force(number):
    """Q_θ as forces dotted with differenced virtual displacements: the weight at the centre, the spring's force
    k(d − ℓ₀) at the tip towards the anchor (FD_REL). V: sympy builds it afresh from the tip's position vector and
    the centre's height; it must differ from the answer by a constant (exactly), and −dV/dθ of the answer at the
    variant's numbers must equal that Q_θ (FD_REL)."""
    drawn = _drawn("7-4-spring-bar-potential", number)
    given = drawn.given
    mass, length, k = given["mass_kg"], given["length_m"], given["stiffness_n_m"]
    h, natural, gravity = given["anchor_m"], given["natural_m"], given["g_m_s2"]
    anchor = np.array([0.0, h])

    def tip(angle: float) -> np.ndarray:
        return length * np.array([math.sin(angle), -math.cos(angle)])

    angle = math.radians(given["theta_deg"])
    stretch = tip(angle) - anchor
    d = float(np.linalg.norm(stretch))
    spring_force = -k * (d - natural) * stretch / d
    weight = np.array([0.0, -mass * gravity])
    q = spring_force @ _derivative(tip, angle) + weight @ (0.5 * _derivative(tip, angle))
    scale = (k * d + mass * gravity) * length
    assert drawn.answers["q"].value == pytest.approx(float(q), abs=FD_REL * scale)
    theta, m, g, big_l, kk, hh, l0 = sympy.symbols("theta m g L k h l0", real=True)
    tip_s = sympy.Matrix([big_l * sympy.sin(theta), -big_l * sympy.cos(theta)])
    spring_length = sympy.sqrt(
        sympy.expand(sympy.trigsimp((tip_s - sympy.Matrix([0, hh])).dot(tip_s - sympy.Matrix([0, hh]))))
    )
    fresh = m * g * (-big_l * sympy.cos(theta) / 2) + kk * (spring_length - l0) ** 2 / 2
    answer = drawn.answers["potential"].value
    difference = sympy.simplify(sympy.expand(fresh - answer))
    assert difference.free_symbols == set()
    numbers = {theta: angle, m: mass, g: gravity, big_l: length, kk: k, hh: h, l0: natural}
    assert float(-sympy.diff(answer, theta).subs(numbers)) == pytest.approx(float(q), abs=FD_REL * scale)


# -- 7.5 --------------------------------------------------------------------------------------------------------


def _cart_parameters(given) -> np.ndarray:
    return np.array(
        pendulum_on_cart.SYSTEM.parameter_array(
            {
                "cart_mass_kg": given["cart_kg"],
                "bob_mass_kg": given["bob_kg"],
                "length_m": given["length_m"],
                "stiffness_N_m": given["stiffness_n_m"],
                "force_amplitude_N": 0.0,
                "force_frequency_rad_s": 1.0,
                "g_m_s2": given["g_m_s2"],
            }
        )
    )


@pytest.mark.parametrize("number", VARIANTS)
def test_the_cart_pendulum_release_against_the_derivation_engine(number):
    """ẍ at release against the engine's Lagrange equations at (x₀, θ₀, 0, 0) (round-off, 1e-10). θ̈(ẍ, θ) against the
    engine's θ̈ and ẍ at 20 random states (1e-10 of g/l). T from the bob's and cart's velocities in sympy (exact)."""
    drawn = _drawn("7-5-cart-pendulum-release", number)
    given = drawn.given
    engine = derived(pendulum_on_cart.SYSTEM, "lagrange")
    p = _cart_parameters(given)
    start = np.array([given["x0_m"], math.radians(given["theta0_deg"]), 0.0, 0.0])
    assert drawn.answers["cart-accel"].value == pytest.approx(engine.state_derivative(0.0, start, p)[2], rel=1e-10)
    swing = drawn.answers["swing"].value
    xdd, theta, g, l = sympy.symbols("xdd theta g l", real=True)
    rng = np.random.default_rng(number)
    for _ in range(20):
        state = np.array([rng.uniform(-0.3, 0.3), rng.uniform(-1.2, 1.2), rng.uniform(-2, 2), rng.uniform(-3, 3)])
        rates = engine.state_derivative(0.0, state, p)
        ours = float(swing.subs({xdd: rates[2], theta: state[1], g: given["g_m_s2"], l: given["length_m"]}))
        assert ours == pytest.approx(rates[3], abs=1e-10 * given["g_m_s2"] / given["length_m"])
    t = sympy.Symbol("t")
    x, th = sympy.Function("x")(t), sympy.Function("th")(t)
    big_m, m, xd, thetad = sympy.symbols("M m xd thetad", real=True)
    bob = sympy.Matrix([x + l * sympy.sin(th), -l * sympy.cos(th)])
    kinetic = big_m * sympy.diff(x, t) ** 2 / 2 + m * bob.diff(t).dot(bob.diff(t)) / 2
    kinetic = kinetic.subs({sympy.Derivative(x, t): xd, sympy.Derivative(th, t): thetad}).subs(th, theta)
    assert sympy.simplify(kinetic - drawn.answers["kinetic"].value) == 0


def test_the_spring_pendulums_equations_by_a_sympy_lagrange_derivation():
    """T from the bob's Cartesian position r(sin θ, −cos θ); Lagrange's equations d/dt ∂L/∂q̇ − ∂L/∂q = 0 derived
    afresh and solved for r̈ and θ̈: the answers must equal them exactly (sympy simplify), and the number part must
    equal the derived θ̈ at the variant's numbers (1e-12) for several variants."""
    t = sympy.Symbol("t")
    rf, thf = sympy.Function("r")(t), sympy.Function("th")(t)
    m, k, l0, g = sympy.symbols("m k l0 g", real=True)
    r, rd, theta, thetad = sympy.symbols("r rd theta thetad", real=True)
    position = sympy.Matrix([rf * sympy.sin(thf), -rf * sympy.cos(thf)])
    kinetic = m * position.diff(t).dot(position.diff(t)) / 2
    potential = k * (rf - l0) ** 2 / 2 + m * g * position[1]
    lagrangian = kinetic - potential
    rdd, thdd = sympy.symbols("rdd thdd")
    equations = [sympy.diff(sympy.diff(lagrangian, sympy.diff(q, t)), t) - sympy.diff(lagrangian, q) for q in (rf, thf)]
    plain = {
        sympy.Derivative(rf, (t, 2)): rdd,
        sympy.Derivative(thf, (t, 2)): thdd,
    }
    firsts = {sympy.Derivative(rf, t): rd, sympy.Derivative(thf, t): thetad}
    equations = [e.subs(plain).subs(firsts).subs({rf: r, thf: theta}) for e in equations]
    solved = sympy.solve(equations, [rdd, thdd], dict=True)[0]
    drawn = _drawn("7-5-spring-pendulum", 0)
    flat_kinetic = kinetic.subs(firsts).subs({rf: r, thf: theta})
    assert sympy.simplify(flat_kinetic - drawn.answers["kinetic"].value) == 0
    assert sympy.simplify(solved[rdd] - drawn.answers["radial"].value) == 0
    assert sympy.simplify(solved[thdd] - drawn.answers["swing"].value) == 0
    for number in VARIANTS:
        drawn = _drawn("7-5-spring-pendulum", number)
        given = drawn.given
        value = solved[thdd].subs(
            {
                r: given["r_m"],
                rd: given["r_rate_m_s"],
                theta: math.radians(given["theta_deg"]),
                thetad: given["theta_rate_rad_s"],
                g: given["g_m_s2"],
            }
        )
        assert drawn.answers["swing-now"].value == pytest.approx(float(value), rel=1e-12)


# -- 7.6 --------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", VARIANTS)
def test_the_hoops_stability_from_the_engines_numerical_jacobian(number):
    """The engine's (θ̇, θ̈) linearised by central differences at the stable equilibrium and at the bottom; the
    eigenvalues of that 2×2 Jacobian are ±iω (stable) or ±λ (unstable). ω against the answer to 1e-6 (the
    difference's error is about 1e-10 of Ω², and the root halves it relatively); the bottom's stability by the sign of
    the eigenvalues' real parts; Ω_c is the spin at which the bottom's Jacobian becomes singular (1e-9)."""
    drawn = _drawn("7-6-hoop-stability", number)
    given = drawn.given
    engine = derived(bead_on_hoop.SYSTEM, "lagrange")

    def params(spin: float) -> np.ndarray:
        return np.array(
            bead_on_hoop.SYSTEM.parameter_array(
                {
                    "hoop_radius_m": given["hoop_radius_m"],
                    "hoop_speed_rad_s": spin,
                    "g_m_s2": given["g_m_s2"],
                    "bead_mass_kg": 0.1,
                }
            )
        )

    p = params(given["hoop_speed_rad_s"])

    def eigen(at: float, parameters: np.ndarray) -> np.ndarray:
        jac = _jacobian(lambda s: engine.state_derivative(0.0, s, parameters), np.array([at, 0.0]))
        return np.linalg.eigvals(jac)

    bottom = eigen(0.0, p)
    unstable = bool(np.max(bottom.real) > 1e-6)
    assert drawn.answers["bottom"].value == ("unstable" if unstable else "stable")
    if unstable:
        ratio = given["g_m_s2"] / (given["hoop_radius_m"] * given["hoop_speed_rad_s"] ** 2)
        star = math.acos(ratio)
        assert abs(engine.state_derivative(0.0, np.array([star, 0.0]), p)[1]) < 1e-9
        at = eigen(star, p)
    else:
        at = bottom
    assert drawn.answers["frequency"].value == pytest.approx(float(np.max(np.abs(at.imag))), rel=1e-6)
    critical = brentq(
        lambda spin: float(
            np.linalg.det(_jacobian(lambda s: engine.state_derivative(0.0, s, params(spin)), np.array([0.0, 0.0])))
        ),
        0.01,
        50.0,
        xtol=1e-13,
    )
    assert drawn.answers["critical"].value == pytest.approx(critical, rel=1e-6)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_cart_pendulums_modes_from_the_engines_numerical_jacobian(number):
    """The engine's 4×4 state Jacobian at rest by central differences; its eigenvalues ±iω₁, ±iω₂ and the slow
    eigenvector's θ/x. The equations are linear to first order, so the difference's error is round-off, about 1e-10
    of ω²: 1e-6 relative."""
    drawn = _drawn("7-6-cart-pendulum-modes", number)
    given = drawn.given
    engine = derived(pendulum_on_cart.SYSTEM, "lagrange")
    p = _cart_parameters(given)
    jac = _jacobian(lambda s: engine.state_derivative(0.0, s, p), np.zeros(4))
    values, vectors = np.linalg.eig(jac)
    positive = [i for i in range(4) if values[i].imag > 0]
    slow, fast = sorted(positive, key=lambda i: values[i].imag)
    assert drawn.answers["slow"].value == pytest.approx(values[slow].imag, rel=1e-6)
    assert drawn.answers["fast"].value == pytest.approx(values[fast].imag, rel=1e-6)
    shape = vectors[1, slow] / vectors[0, slow]
    assert abs(shape.imag) < 1e-6 * abs(shape)
    assert drawn.answers["shape"].value == pytest.approx(shape.real, rel=1e-6)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_bars_swing_integrated_numerically(number):
    """θ̈ = −(3g/2L) sin θ integrated by solve_ivp (DOP853, rtol 1e-12, atol 1e-14) from rest at θ₀ until θ first
    crosses 0: four times that time is the period and |θ̇| there the speed (both to 1e-9). The small-swing period
    from the same integration at θ₀ = 1e-4 rad, whose amplitude correction is θ₀²/16 ≈ 6e-10 relative (1e-8)."""
    drawn = _drawn("7-6-bar-large-swing", number)
    given = drawn.given
    rate = 3 * given["g_m_s2"] / (2 * given["length_m"])

    def quarter(amplitude: float) -> tuple[float, float]:
        def crossing(_t, y):
            return y[0]

        crossing.terminal = True
        crossing.direction = -1
        solution = solve_ivp(
            lambda _t, y: [y[1], -rate * math.sin(y[0])],
            (0.0, 100.0),
            [amplitude, 0.0],
            method="DOP853",
            rtol=1e-12,
            atol=1e-14,
            events=crossing,
        )
        return float(solution.t_events[0][0]), float(abs(solution.y_events[0][0][1]))

    time, speed = quarter(math.radians(given["theta0_deg"]))
    assert drawn.answers["period"].value == pytest.approx(4 * time, rel=1e-9)
    assert drawn.answers["speed"].value == pytest.approx(speed, rel=1e-9)
    assert drawn.answers["small"].value == pytest.approx(4 * quarter(1e-4)[0], rel=1e-8)
