"""Chapter 3's answer functions against independent computations, over several variants each.

The answer functions use the lesson's formulas and the app's rotation library; these checks use neither. Attitudes
come from scipy's ``Rotation`` (its own Euler-angle and rotation-vector code); rates and accelerations come from
finite differences of positions and rotation matrices composed directly from the statement, never from a
derivative formula; symbolic answers come from a sympy derivation or are compared at random points with those
finite differences. Tolerances are stated, and justified, in each test's docstring.

Finite differences are the fourth-order central ones: for a first derivative the truncation error is
``h⁴ f⁽⁵⁾/30`` and the rounding error about ``1.5 ε |f| / h``; for a second derivative ``h⁴ f⁽⁶⁾/90`` and
``5 ε |f| / h²`` (ε = 2.2e-16).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest
import sympy
from scipy.integrate import solve_ivp
from scipy.spatial.transform import Rotation

from app.practice.variants import variant
from tests.practice.shipped import EXERCISES

VARIANTS = range(0, 100, 9)


def _drawn(exercise_id: str, number: int):
    return variant(EXERCISES[exercise_id], number)


def _d1(f: Callable[[float], np.ndarray], t: float, h: float) -> np.ndarray:
    return (-f(t + 2 * h) + 8 * f(t + h) - 8 * f(t - h) + f(t - 2 * h)) / (12 * h)


def _d2(f: Callable[[float], np.ndarray], t: float, h: float) -> np.ndarray:
    return (-f(t + 2 * h) + 16 * f(t + h) - 30 * f(t) + 16 * f(t - h) - f(t - 2 * h)) / (12 * h * h)


def _vee(skew: np.ndarray) -> np.ndarray:
    return np.array([skew[2, 1], skew[0, 2], skew[1, 0]])


def _euler(sequence: str, angles_rad) -> np.ndarray:
    """[R] (body components to fixed) of intrinsic turns, by scipy (upper-case axes: intrinsic)."""
    return Rotation.from_euler(sequence, np.asarray(angles_rad, dtype=float)).as_matrix()


def _rz(angle: float) -> np.ndarray:
    return Rotation.from_rotvec([0.0, 0.0, angle]).as_matrix()


def _named(names: str) -> dict[str, sympy.Symbol]:
    """The symbols of an expression part by name (real, as the checker and the answer functions make them)."""
    return {name: sympy.Symbol(name, real=True) for name in names.split()}


def _close(vector, expected, rel: float) -> None:
    vector, expected = np.asarray(vector, dtype=float), np.asarray(expected, dtype=float)
    assert np.linalg.norm(vector - expected) <= rel * np.linalg.norm(expected), (vector, expected)


# -- 3.1 ---------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", VARIANTS)
def test_aircraft_nose_and_wingtip_from_scipys_yaw_pitch_roll(number):
    """scipy's intrinsic Z-Y-X matrix: the nose is its first column, the wingtip b times its (3, 2) entry. Both are
    exact products of sines and cosines, so they agree to rounding (1e-12)."""
    g = _drawn("3-1-aircraft-nose-and-wingtip", number).given
    answers = _drawn("3-1-aircraft-nose-and-wingtip", number).answers
    R = _euler("ZYX", np.radians([g["yaw_deg"], g["pitch_deg"], g["roll_deg"]]))
    _close(answers["nose"].value, R[:, 0], 1e-12)
    # the left wingtip sits at b j from the centre; its height is b (R j)·K
    tip = g["half_span_m"] * (R @ np.array([0.0, 1.0, 0.0]))[2]
    assert answers["tip"].value == pytest.approx(tip, rel=1e-12)
    # and positive pitch is nose down with Z up: a pitched-down nose has a negative Z component
    if g["pitch_deg"] > 0:
        assert answers["nose"].value[2] < 0


@pytest.mark.parametrize("number", VARIANTS)
def test_satellite_single_turn_is_scipys_rotation_vector(number):
    """scipy's rotation vector of the intrinsic Z-X-Z attitude gives the angle and the axis (1e-9: its quaternion
    route loses no digits at these angles, 20° to 170°); rotating by it reproduces [R]'s third column."""
    drawn = _drawn("3-1-satellite-single-turn", number)
    g, answers = drawn.given, drawn.answers
    rotation = Rotation.from_euler("ZXZ", np.radians([g["precession_deg"], g["nutation_deg"], g["spin_deg"]]))
    rotvec = rotation.as_rotvec()
    angle = float(np.linalg.norm(rotvec))
    assert answers["angle"].value == pytest.approx(math.degrees(angle), rel=1e-9)
    _close(answers["axis"].value, rotvec / angle, 1e-9)
    _close(answers["boresight"].value, rotation.apply([0.0, 0.0, 1.0]), 1e-12)
    # the axis is left in place by the turn
    _close(rotation.apply(answers["axis"].value), answers["axis"].value, 1e-9)


@pytest.mark.parametrize("number", VARIANTS)
def test_angles_read_back_are_scipys_3_1_3_angles_of_the_same_attitude(number):
    """scipy converts the intrinsic Z-Y-X attitude to intrinsic Z-X-Z angles (its middle angle in [0°, 180°], the
    others in (−180°, 180°]): agreement to 1e-9 relative. The chosen twin triple rebuilds the same matrix to 1e-12
    and the distractor 'negate' does not."""
    drawn = _drawn("3-1-angles-read-back", number)
    g, answers = drawn.given, drawn.answers
    rotation = Rotation.from_euler("ZYX", np.radians([g["yaw_deg"], g["pitch_deg"], g["roll_deg"]]))
    phi, theta, psi = rotation.as_euler("ZXZ", degrees=True)
    assert answers["nutation"].value == pytest.approx(theta, rel=1e-9)
    assert answers["precession"].value == pytest.approx(phi, rel=1e-9)
    assert answers["spin"].value == pytest.approx(psi, rel=1e-9)
    R = rotation.as_matrix()
    twins = {
        "flip": (phi + 180, -theta, psi + 180),
        "negate": (phi, -theta, psi),
        "swap": (psi, theta, phi),
    }
    same = {key: np.allclose(_euler("ZXZ", np.radians(t)), R, atol=1e-12) for key, t in twins.items()}
    assert same["flip"] and not same["negate"]
    assert answers["twin"].value == "flip"


# -- 3.3 ---------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", VARIANTS)
def test_stretching_vector_rates_are_finite_differences_of_its_composed_position(number):
    """A on XYZ composed from the statement alone: {A}_xyz(t) from its formula, turned by scipy's rotation vector
    Ω t n. Its fourth-order difference (h = 1 ms; rates ≤ 4 rad/s, |A| ≤ 2 m: truncation ~1e-11, rounding ~1e-13)
    is the fixed observer's rate; the difference of {A}_xyz alone is the rider's. Agreement to 1e-8 relative."""
    drawn = _drawn("3-3-stretching-vector-rates", number)
    g, answers = drawn.given, drawn.answers
    tilt = math.radians(g["tilt_deg"])
    omega = g["frame_rate_rad_s"] * np.array([math.sin(tilt), 0.0, math.cos(tilt)])
    e = math.radians(g["elevation_deg"])

    def on_frame(t: float) -> np.ndarray:
        length = g["length_m"] + g["stretch_m"] * math.sin(2 * math.pi * g["stretch_hz"] * t)
        psi = g["turn_rate_rad_s"] * t
        return length * np.array([math.cos(e) * math.cos(psi), math.cos(e) * math.sin(psi), math.sin(e)])

    def frame(t: float) -> np.ndarray:
        return Rotation.from_rotvec(omega * t).as_matrix()

    def on_fixed(t: float) -> np.ndarray:
        return frame(t) @ on_frame(t)

    t = g["time_s"]
    h = 1e-3
    fixed_xyz = frame(t).T @ _d1(on_fixed, t, h)
    relative = _d1(on_frame, t, h)
    _close(answers["relative"].value, relative, 1e-8)
    _close(answers["transport"].value, fixed_xyz - relative, 1e-8)
    assert answers["fixed"].value == pytest.approx(np.linalg.norm(fixed_xyz), rel=1e-8)


def _telescope_rate(spin: float, rise: float, elevation: float) -> np.ndarray:
    """du/dt on XYZ at t = 0 (when the turntable's axes are XYZ), by differencing u(t) = Rz(Ω t)(cos θ, 0, sin θ)."""

    def u(t: float) -> np.ndarray:
        angle = elevation + rise * t
        return _rz(spin * t) @ np.array([math.cos(angle), 0.0, math.sin(angle)])

    return _d1(u, 0.0, 1e-3)


@pytest.mark.parametrize("number", VARIANTS)
def test_telescope_tube_rate_is_the_difference_of_its_turning_unit_vector(number):
    """The tube's unit vector composed as Rz(Ω t) applied to its elevated direction, differenced at t = 0 (h = 1 ms,
    rates ≤ 3 rad/s: error ~1e-12): the vector and the tip speed to 1e-8; the formula at 12 random points of its
    symbols' ranges to 1e-8 as well."""
    drawn = _drawn("3-3-telescope-on-turntable", number)
    g, answers = drawn.given, drawn.answers
    rate = _telescope_rate(g["table_rate_rad_s"], g["rise_rate_rad_s"], math.radians(g["elevation_deg"]))
    _close(answers["rate"].value, rate, 1e-8)
    assert answers["speed"].value == pytest.approx(g["tube_m"] * np.linalg.norm(rate), rel=1e-8)
    formula = answers["magnitude"].value
    symbols = _named("theta thetad Omega")
    rng = np.random.default_rng(33)
    for _ in range(12):
        theta, thetad, spin = rng.uniform(0.1, 1.5), rng.uniform(0.05, 2.0), rng.uniform(0.1, 3.0)
        value = float(formula.subs({symbols["theta"]: theta, symbols["thetad"]: thetad, symbols["Omega"]: spin}))
        assert value == pytest.approx(np.linalg.norm(_telescope_rate(spin, thetad, theta)), rel=1e-8)


@pytest.mark.parametrize("number", VARIANTS)
def test_boom_tip_speed_is_the_difference_of_the_turning_boom(number):
    """The boom composed as Rz(Ω t) applied to its body direction, differenced at t = 0 (h = 1 ms, Ω ≤ 5 rad/s:
    error ~1e-11): the speed to 1e-8; the velocity is perpendicular to the axis and the boom (to 1e-9 of |v||A|),
    which is the choice 'across'; the formula at 12 random (Ω, L, γ) to 1e-8."""
    drawn = _drawn("3-3-vector-fixed-in-frame", number)
    g, answers = drawn.given, drawn.answers

    def boom_velocity(spin: float, length: float, gamma: float) -> tuple[np.ndarray, np.ndarray]:
        body = length * np.array([math.sin(gamma), 0.0, math.cos(gamma)])  # γ from the spin axis Z
        return body, _d1(lambda t: _rz(spin * t) @ body, 0.0, 1e-3)

    boom, velocity = boom_velocity(g["spin_rate_rad_s"], g["boom_m"], math.radians(90 - g["elevation_deg"]))
    assert answers["speed"].value == pytest.approx(np.linalg.norm(velocity), rel=1e-8)
    scale = np.linalg.norm(velocity) * g["boom_m"]
    assert abs(velocity @ boom) < 1e-9 * scale and abs(velocity[2]) * g["boom_m"] < 1e-9 * scale
    assert answers["direction"].value == "across"
    formula = answers["formula"].value
    symbols = _named("Omega L gamma")
    rng = np.random.default_rng(34)
    for _ in range(12):
        spin, length, gamma = rng.uniform(0.1, 5.0), rng.uniform(0.1, 5.0), rng.uniform(0.1, 3.0)
        value = float(formula.subs({symbols["Omega"]: spin, symbols["L"]: length, symbols["gamma"]: gamma}))
        assert value == pytest.approx(np.linalg.norm(boom_velocity(spin, length, gamma)[1]), rel=1e-8)


# -- 3.4 ---------------------------------------------------------------------------------------------------------


def _omega_from_matrices(R_of_t: Callable[[float], np.ndarray], t: float, h: float = 1e-3):
    """(ω on the body axes, ω on the fixed axes) from Ṙ by differences: [R]ᵀṘ and Ṙ[R]ᵀ are their skew matrices."""
    R, R_dot = R_of_t(t), _d1(R_of_t, t, h)
    return _vee(R.T @ R_dot), _vee(R_dot @ R.T)


@pytest.mark.parametrize("number", VARIANTS)
def test_nodding_tops_omega_is_the_skew_part_of_the_differenced_attitude(number):
    """scipy's Z-X-Z matrix at the angles moved on by their rates, differenced (h = 1 ms, |ω| ≤ 5 rad/s: error
    ~1e-10 rad/s): ω on xyz and its Z component on XYZ to 1e-8 relative."""
    drawn = _drawn("3-4-nutating-top-omega", number)
    g, answers = drawn.given, drawn.answers
    angles = np.radians([g["precession_deg"], g["nutation_deg"], g["spin_deg"]])
    rates = np.array([g["precession_rate_rad_s"], g["nutation_rate_rad_s"], g["spin_rate_rad_s"]])
    body, world = _omega_from_matrices(lambda t: _euler("ZXZ", angles + rates * t), 0.0)
    _close(answers["body"].value, body, 1e-8)
    assert answers["size"].value == pytest.approx(np.linalg.norm(world), rel=1e-8)
    assert answers["vertical"].value == pytest.approx(world[2], rel=1e-8)


@pytest.mark.parametrize("number", VARIANTS)
def test_gyro_rates_give_back_the_gyro_readings(number):
    """The map from angle rates to body ω is linear: its matrix is found column by column by differencing scipy's
    Z-Y-X matrix with one unit rate at a time (error ~1e-11), and solved for the gyro readings; yaw and roll rates
    agree to 1e-8. That matrix is singular at a pitch of ±90° (smallest singular value < 1e-8) and not at 0° or
    45°, which is the choice 'p90'."""
    drawn = _drawn("3-4-gyro-rates-to-angle-rates", number)
    g, answers = drawn.given, drawn.answers

    def rate_matrix(pitch: float, roll: float) -> np.ndarray:
        start = np.array([0.3, pitch, roll])
        columns = [
            _omega_from_matrices(lambda t, unit=unit: _euler("ZYX", start + unit * t), 0.0)[0] for unit in np.eye(3)
        ]
        return np.stack(columns, axis=-1)

    pitch, roll = math.radians(g["pitch_deg"]), math.radians(g["roll_deg"])
    rates = np.linalg.solve(rate_matrix(pitch, roll), [g["p_rad_s"], g["q_rad_s"], g["r_rad_s"]])
    assert answers["yaw-rate"].value == pytest.approx(rates[0], rel=1e-8)
    assert answers["roll-rate"].value == pytest.approx(rates[2], rel=1e-8)
    smallest = {deg: np.linalg.svd(rate_matrix(math.radians(deg), roll), compute_uv=False)[-1] for deg in (0, 45, 90)}
    assert smallest[90] < 1e-8 and smallest[0] > 0.1 and smallest[45] > 0.1
    assert answers["lock"].value == "p90"


def test_precessing_disks_angular_acceleration_formula_from_a_sympy_derivation():
    """ω as the skew part of Ṙ[R]ᵀ of the symbolic 3-1-3 product with φ = φ̇t, ψ = ψ̇t and θ fixed, differentiated
    once more by sympy: |α|² simplifies to exactly (φ̇ψ̇ sin θ)², the square of the answer's expression, and |ω|² to
    φ̇² + ψ̇² + 2φ̇ψ̇ cos θ (exact: no tolerance)."""
    t = sympy.Symbol("t", real=True)
    phid, psid, theta = sympy.symbols("phid psid theta", positive=True)

    def r1(a: sympy.Expr) -> sympy.Matrix:
        return sympy.Matrix([[1, 0, 0], [0, sympy.cos(a), -sympy.sin(a)], [0, sympy.sin(a), sympy.cos(a)]])

    def r3(a: sympy.Expr) -> sympy.Matrix:
        return sympy.Matrix([[sympy.cos(a), -sympy.sin(a), 0], [sympy.sin(a), sympy.cos(a), 0], [0, 0, 1]])

    R = r3(phid * t) * r1(theta) * r3(psid * t)
    skew = sympy.simplify(R.diff(t) * R.T)
    omega = sympy.Matrix([skew[2, 1], skew[0, 2], skew[1, 0]])
    alpha = omega.diff(t)
    answer = _drawn("3-4-precessing-disk-alpha", 0).answers["formula"].value
    named = _named("phid psid theta")
    renamed = answer.subs({named["phid"]: phid, named["psid"]: psid, named["theta"]: theta})
    assert sympy.simplify(alpha.dot(alpha) - renamed**2) == 0
    assert sympy.simplify(omega.dot(omega) - (phid**2 + psid**2 + 2 * phid * psid * sympy.cos(theta))) == 0


@pytest.mark.parametrize("number", VARIANTS)
def test_precessing_disks_alpha_is_the_difference_of_its_omega(number):
    """ω on XYZ by differencing scipy's Z-X-Z matrix (h = 1e-4 s), then α by differencing that ω (h = 1e-2 s):
    the outer truncation is ~1e-9 and the inner error (~1e-9 rad/s) divided by the outer step ~1e-7, so 1e-6
    relative on α and 1e-8 on |ω|."""
    drawn = _drawn("3-4-precessing-disk-alpha", number)
    g, answers = drawn.given, drawn.answers
    start = np.radians([g["precession_deg"], g["tilt_deg"], 0.0])
    rates = np.array([g["precession_rate_rad_s"], 0.0, g["spin_rate_rad_s"]])

    def omega_world(t: float) -> np.ndarray:
        return _omega_from_matrices(lambda s: _euler("ZXZ", start + rates * s), t, 1e-4)[1]

    _close(answers["alpha"].value, _d1(omega_world, 0.0, 1e-2), 1e-6)
    assert answers["omega"].value == pytest.approx(np.linalg.norm(omega_world(0.0)), rel=1e-8)


# -- 3.5 ---------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", VARIANTS)
def test_slider_velocity_and_acceleration_are_differences_of_its_world_position(number):
    """P on XYZ composed as Rz(θ(t)) (s(t), d, 0), differenced once and twice (h = 1 ms; ω ≤ 7 rad/s, |r| ≤ 1.5 m:
    second-difference truncation ~1e-9 of the size, rounding ~1e-9 m/s²), then put on the table's axes with the
    same matrix: 1e-7 relative."""
    drawn = _drawn("3-5-slider-in-offset-groove", number)
    g, answers = drawn.given, drawn.answers

    def position(t: float) -> np.ndarray:
        angle = g["spin_rate_rad_s"] * t + 0.5 * g["spin_accel_rad_s2"] * t * t
        s = g["slider_amplitude_m"] * math.sin(2 * math.pi * g["slider_frequency_hz"] * t)
        return _rz(angle) @ np.array([s, g["offset_m"], 0.0])

    t = g["time_s"]
    to_table = _rz(g["spin_rate_rad_s"] * t + 0.5 * g["spin_accel_rad_s2"] * t * t).T
    _close(answers["velocity"].value, to_table @ _d1(position, t, 1e-3), 1e-7)
    _close(answers["acceleration"].value, to_table @ _d2(position, t, 1e-3), 1e-7)


@pytest.mark.parametrize("number", VARIANTS)
def test_tilted_table_point_acceleration_is_the_difference_of_its_world_position(number):
    """The table's attitude Rz(Ω_p t) Rx(β) Rz(θ(t)) by scipy: ω from Ṙ[R]ᵀ (h = 1e-4 s), α by differencing that ω
    (h = 1e-2 s; error ~1e-7 of the size, so 1e-6), and P's acceleration as the second difference of its world
    position (h = 1 ms; ~1e-9, so 1e-7)."""
    drawn = _drawn("3-5-tilted-precessing-table", number)
    g, answers = drawn.given, drawn.answers
    beta = math.radians(g["tilt_deg"])

    def attitude(t: float) -> np.ndarray:
        spin = g["spin_rate_rad_s"] * t + 0.5 * g["spin_accel_rad_s2"] * t * t
        return _euler("ZXZ", [g["precession_rate_rad_s"] * t, beta, spin])

    def omega_world(t: float) -> np.ndarray:
        return _omega_from_matrices(attitude, t, 1e-4)[1]

    _close(answers["omega"].value, omega_world(0.0), 1e-8)
    _close(answers["alpha"].value, _d1(omega_world, 0.0, 1e-2), 1e-6)
    acceleration = _d2(lambda t: attitude(t) @ np.array([0.0, g["offset_m"], 0.0]), 0.0, 1e-3)
    assert answers["accel"].value == pytest.approx(np.linalg.norm(acceleration), rel=1e-7)


@pytest.mark.parametrize("number", VARIANTS)
def test_collars_side_push_is_mass_times_the_differenced_acceleration_across_the_arm(number):
    """The collar on XYZ at (r + u t)(cos θ, sin θ), θ = ω t + ½ α t², differenced twice at t = 0 (h = 1 ms;
    ω ≤ 10 rad/s: truncation ~1e-7 of the size at worst), across the arm (the Y component at t = 0): the force and
    the formula at 12 random points to 1e-6; its sign is forward, the trailing face's push."""
    drawn = _drawn("3-5-collar-on-spinning-arm", number)
    g, answers = drawn.given, drawn.answers

    def across(spin: float, spin_up: float, radius: float, speed: float) -> float:
        def position(t: float) -> np.ndarray:
            angle = spin * t + 0.5 * spin_up * t * t
            return (radius + speed * t) * np.array([math.cos(angle), math.sin(angle), 0.0])

        return float(_d2(position, 0.0, 1e-3)[1])

    value = across(g["arm_rate_rad_s"], g["arm_accel_rad_s2"], g["radius_m"], g["slide_speed_m_s"])
    assert answers["force"].value == pytest.approx(g["mass_kg"] * value, rel=1e-6)
    assert value > 0 and answers["face"].value == "trailing"
    formula = answers["transverse"].value
    symbols = _named("omega alpha r u")
    rng = np.random.default_rng(35)
    for _ in range(12):
        point = {"omega": rng.uniform(0.5, 10.0), "alpha": rng.uniform(0.0, 5.0)}
        point |= {"r": rng.uniform(0.1, 2.0), "u": rng.uniform(0.1, 3.0)}
        expected = across(point["omega"], point["alpha"], point["r"], point["u"])
        assert float(formula.subs({symbols[k]: v for k, v in point.items()})) == pytest.approx(expected, rel=1e-6)


# -- 3.2 ---------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", VARIANTS)
def test_the_lids_point_is_turned_by_scipys_rotation_vector(number):
    """scipy's rotation by the rotation vector φ n applied to P (its own quaternion code, not Rodrigues' matrix):
    the image agrees to 1e-12 of |P| (round-off); the distance moved is |P' − P| to 1e-12; and the chord formula at
    d = |n × P| (the distance from the line, by a cross product) gives that distance to 1e-12."""
    drawn = _drawn("3-2-rodrigues-lid", number)
    g, answers = drawn.given, drawn.answers
    delta, angle = math.radians(g["hinge_tilt_deg"]), math.radians(g["turn_deg"])
    n = np.array([math.sin(delta), 0.0, math.cos(delta)])
    p = np.array([g["x_m"], g["y_m"], 0.0])
    image = Rotation.from_rotvec(angle * n).apply(p)
    _close(answers["image"].value, image, 1e-12)
    moved = float(np.linalg.norm(image - p))
    assert answers["distance"].value == pytest.approx(moved, rel=1e-12)
    names = _named("d phi")
    formula = answers["chord"].value.subs({names["d"]: float(np.linalg.norm(np.cross(n, p))), names["phi"]: angle})
    assert float(formula) == pytest.approx(moved, rel=1e-12)


def test_the_chord_formula_is_sympys_distance_between_the_ends_of_the_arc():
    """A point at distance d from the axis, turned by φ about it: sympy's |r' − r| equals 2 d sin(φ/2) for
    0 < φ < π (exact simplification)."""
    drawn = _drawn("3-2-rodrigues-lid", 0)
    d, phi = sympy.symbols("d phi", positive=True)
    moved = sympy.sqrt((d * sympy.cos(phi) - d) ** 2 + (d * sympy.sin(phi)) ** 2)
    names = _named("d phi")
    formula = drawn.answers["chord"].value.subs({names["d"]: d, names["phi"]: phi})
    assert sympy.simplify(sympy.trigsimp(moved**2 - formula**2)) == 0
    assert float((moved - formula).subs({d: 0.7, phi: 2.9})) == pytest.approx(0.0, abs=1e-15)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_two_orders_are_scipys_compositions_of_fixed_axis_turns(number):
    """scipy's Rotation composition (``B * A``: A first, then B, about fixed axes): the angle and axis of
    "A then B" from its rotation vector, and the gap as the magnitude of ``AB * BA⁻¹``, agree with the answers to
    1e-10 (scipy works through quaternions and atan2: ~1e-15); the cos φ formula at a, b is cos of scipy's angle
    to 1e-12."""
    drawn = _drawn("3-2-two-turns-order", number)
    g, answers = drawn.given, drawn.answers
    a, b = math.radians(g["a_deg"]), math.radians(g["b_deg"])
    turn_a, turn_b = Rotation.from_rotvec([a, 0.0, 0.0]), Rotation.from_rotvec([0.0, b, 0.0])
    ab, ba = turn_b * turn_a, turn_a * turn_b
    rotvec = ab.as_rotvec()
    angle = float(np.linalg.norm(rotvec))
    assert answers["angle"].value == pytest.approx(math.degrees(angle), rel=1e-10)
    _close(answers["axis"].value, rotvec / angle, 1e-10)
    assert answers["gap"].value == pytest.approx(math.degrees((ab * ba.inv()).magnitude()), rel=1e-10)
    assert float(ab.magnitude()) == pytest.approx(float(ba.magnitude()), rel=1e-12)  # same angle, both orders
    names = _named("a b")
    formula = answers["cos-angle"].value.subs({names["a"]: a, names["b"]: b})
    assert float(formula) == pytest.approx(math.cos(angle), abs=1e-12)


@pytest.mark.parametrize("number", VARIANTS)
def test_small_turns_gap_is_scipys_and_its_leading_order_is_the_product(number):
    """scipy's compositions of a about Y and b about Z: the gap magnitude of ``AB * BA⁻¹`` (and with both angles
    doubled) to 1e-9 relative (the gap is ~1e-4 rad, the quaternions' round-off ~1e-16, so ~1e-12 relative); its
    rotation vector points along −X, with off-axis parts of relative size (a/2, b/2) (the next order of the
    product), so within 0.06 for a, b ≤ 6° = 0.105 rad; and the gap divided by the estimate formula at angles
    scaled down by 1e-3 is 1 to 1e-6 (the next term is relative O(a + b) ≈ 1e-4 × 1e-3, and the gap, ~1e-9 rad, is
    computed to ~1e-7 relative)."""
    drawn = _drawn("3-2-small-turns-commute", number)
    g, answers = drawn.given, drawn.answers

    def gap(a: float, b: float) -> Rotation:
        turn_a, turn_b = Rotation.from_rotvec([0.0, a, 0.0]), Rotation.from_rotvec([0.0, 0.0, b])
        return (turn_b * turn_a) * (turn_a * turn_b).inv()

    a, b = math.radians(g["a_deg"]), math.radians(g["b_deg"])
    assert answers["gap"].value == pytest.approx(math.degrees(gap(a, b).magnitude()), rel=1e-9)
    assert answers["doubled"].value == pytest.approx(math.degrees(gap(2 * a, 2 * b).magnitude()), rel=1e-9)
    direction = gap(a, b).as_rotvec() / gap(a, b).magnitude()
    assert direction == pytest.approx([-1.0, 0.0, 0.0], abs=0.06)
    assert answers["gap-axis"].value == "minus-x"
    names = _named("a b")
    small_a, small_b = a * 1e-3, b * 1e-3
    estimate = float(answers["estimate"].value.subs({names["a"]: small_a, names["b"]: small_b}))
    assert gap(small_a, small_b).magnitude() / estimate == pytest.approx(1.0, abs=1e-6)


# -- 3.6 ---------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", VARIANTS)
def test_foucault_plane_turns_as_scipys_integrated_swing_measures(number):
    """The lesson's small-swing equations ẍ − 2Ω_z ẏ + ω₀²x = 0, ÿ + 2Ω_z ẋ + ω₀²y = 0 (Ω_z = k Ω sin λ, the Earth's
    rate exaggerated k = 1000 times, which scales the plane's rate exactly), released from rest at (a, 0), integrated
    by scipy (DOP853, rtol 1e-12) for 40 s with every turning point (|r| largest, an event) recorded. The bearings of
    the turning points, folded to a line and unwrapped, are fitted with a straight line: its slope divided by k is
    the plane's rate, to 1e-6 relative (each event's bearing is good to ~1e-10 rad over a fitted span of radians);
    its sign gives the sense; the period is 2π over it."""
    drawn = _drawn("3-6-foucault-plane-turn", number)
    g, answers = drawn.given, drawn.answers
    k = 1000.0
    earth = 7.292115e-5
    omega_z = k * earth * math.sin(math.radians(g["latitude_deg"]))
    w0 = math.sqrt(9.81 / g["length_m"])

    def rhs(_t, y):
        x, yy, vx, vy = y
        return [vx, vy, 2 * omega_z * vy - w0**2 * x, -2 * omega_z * vx - w0**2 * yy]

    def turning(_t, y):
        return y[0] * y[2] + y[1] * y[3]

    turning.direction = -1  # |r| stops growing: a largest swing
    run = solve_ivp(rhs, (0.0, 40.0), [1.0, 0.0, 0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-12, events=turning)
    times, states = run.t_events[0], run.y_events[0]
    bearings = np.unwrap(2 * np.arctan2(states[:, 1], states[:, 0])) / 2  # a swing's line: bearing modulo π
    slope = float(np.polyfit(times, bearings, 1)[0]) / k  # rad/s, counterclockwise positive
    rate_deg_h = math.degrees(abs(slope)) * 3600
    assert answers["rate"].value == pytest.approx(rate_deg_h, rel=1e-6)
    assert answers["period"].value == pytest.approx(2 * math.pi / abs(slope), rel=1e-6)
    assert answers["sense"].value == ("clockwise" if slope < 0 else "counterclockwise")


@pytest.mark.parametrize("number", VARIANTS)
def test_the_dropped_stone_lands_where_scipys_rotating_frame_integration_says(number):
    """r̈ = −g k − 2Ω × ṙ in the ground's frame (Ω = Ω(0, cos λ, sin λ)), integrated by scipy (DOP853, rtol 1e-13,
    atol 1e-13 m) from rest at height h to the ground (an event). The landing time and the eastward landing point
    agree with the first-order answers to 1e-6 relative: the terms the first-order answers leave out are relative
    O((Ω t)²) ≤ (7.3e-5 × 9 s)² ≈ 4e-7, and the integration's error in x is below 1e-10 m against x ≥ 1e-3 m. The
    formula, evaluated at the given numbers and the integrated fall time, gives the same deflection to 1e-6."""
    drawn = _drawn("3-6-stone-dropped-east", number)
    g, answers = drawn.given, drawn.answers
    lam, gg, earth = math.radians(g["latitude_deg"]), g["g_m_s2"], 7.292115e-5
    omega = earth * np.array([0.0, math.cos(lam), math.sin(lam)])

    def rhs(_t, y):
        return [*y[3:], *(np.array([0.0, 0.0, -gg]) - 2 * np.cross(omega, y[3:]))]

    def ground(_t, y):
        return y[2]

    ground.terminal, ground.direction = True, -1
    run = solve_ivp(
        rhs, (0.0, 100.0), [0.0, 0.0, g["height_m"], 0.0, 0.0, 0.0], method="DOP853", rtol=1e-13, atol=1e-13,
        events=ground,
    )  # fmt: skip
    t_land, east = float(run.t_events[0][0]), float(run.y_events[0][0][0])
    assert answers["fall-time"].value == pytest.approx(t_land, rel=1e-6)
    assert answers["deflection"].value == pytest.approx(east, rel=1e-6)
    assert answers["direction"].value == ("east" if east > 0 else "west")
    names = _named("Omega g t lam")
    formula = answers["formula"].value.subs(
        {names["Omega"]: earth, names["g"]: gg, names["t"]: t_land, names["lam"]: lam}
    )
    assert float(formula) == pytest.approx(east, rel=1e-6)


@pytest.mark.parametrize("number", VARIANTS)
def test_the_riders_view_of_the_puck_is_the_difference_of_its_position_on_the_table(number):
    """The puck's straight path over the ground, r(t) = r₀ + v t, written on the table's axes, Rz(−Ωt) r(t) (scipy),
    and differenced at t = 0 (h = 1e-3 s, fourth order: truncation ~1e-12, rounding ~5ε/h² ~ 1e-9 of |r|): v_rel
    to 1e-9 and a_rel to 1e-7 relative; the bend is the sign of their cross product."""
    drawn = _drawn("3-6-puck-on-turntable", number)
    g, answers = drawn.given, drawn.answers
    spin = g["table_rate_rad_s"]
    start, velocity = np.array([g["distance_m"], 0.0, 0.0]), np.array([g["u_x_m_s"], g["u_y_m_s"], 0.0])

    def on_table(t: float) -> np.ndarray:
        return _rz(-spin * t) @ (start + velocity * t)

    v_rel, a_rel = _d1(on_table, 0.0, 1e-3), _d2(on_table, 0.0, 1e-3)
    _close(answers["v-rel"].value, v_rel, 1e-9)
    _close(answers["a-rel"].value, a_rel, 1e-7)
    assert answers["bend"].value == ("left" if np.cross(v_rel, a_rel)[2] > 0 else "right")


@pytest.mark.parametrize("number", VARIANTS)
def test_the_trains_coriolis_term_is_the_difference_of_its_position_seen_from_the_stars(number):
    """The ground's frame turns about the Earth's axis, (0, cos λ, sin λ) on its own axes at t = 0; the train goes
    straight over the ground, r_rel = v t from the frame's origin. Its position against the stars, R(Ω t) r_rel(t)
    with R by scipy, differenced twice at t = 0 (h = 1 s, fourth order: truncation ~(Ω h)⁴ ≈ 3e-17 relative and
    rounding ~5ε · 180 m / 1 s² ≈ 2e-13 m/s², against at least 2Ωv sin 10° ≈ 5e-4 m/s²) is the absolute acceleration,
    2Ω × v here (a_rel = 0, r = 0); the Coriolis term is minus it, to 1e-8 relative. The side force, the rail and the
    load change follow from it (1e-8)."""
    drawn = _drawn("3-6-train-coriolis-rails", number)
    g, answers = drawn.given, drawn.answers
    lam, psi = math.radians(g["latitude_deg"]), math.radians(g["heading_deg"])
    axis = np.array([0.0, math.cos(lam), math.sin(lam)])
    velocity = g["speed_m_s"] * np.array([math.sin(psi), math.cos(psi), 0.0])
    earth = 7.292115e-5

    def against_stars(t: float) -> np.ndarray:
        return Rotation.from_rotvec(earth * t * axis).apply(velocity * t)

    coriolis = -_d2(against_stars, 0.0, 1.0)
    _close(answers["coriolis"].value, coriolis, 1e-8)
    mass = g["mass_kg"]
    assert answers["side-force"].value == pytest.approx(mass * math.hypot(coriolis[0], coriolis[1]), rel=1e-8)
    across = float(np.cross(velocity, coriolis)[2])  # > 0: the push is to the left of the motion
    assert answers["rail"].value == ("left" if across > 0 else "right")
    assert answers["load"].value == pytest.approx(-mass * coriolis[2], rel=1e-8)
