"""Chapter 4's answer functions against independent computations, over several variants each.

The answer functions use the lessons' formulas or the project's chapter-4 models (the disk on the turntable, the
Eulerian-angle kinematics, the four-bar, the slider-crank, the cardan joint). These checks use neither: attitudes are
composed with scipy's ``Rotation`` straight from the statement, positions are written down from the geometry (the
four-bar's loop and the cardan joint's pin constraint are solved by a bracketing root finder, not by their closed
forms), and every rate and acceleration is a finite difference of those positions or attitudes, or a sympy derivative
of a position. Where the answer function
used a closed form for a system the project models (the rolling disk and cone), the check takes the model's positions
and differences them. Tolerances are stated, and justified, in each test's docstring.

Finite differences are the fourth-order central ones: for a first derivative the truncation error is
``h⁴ f⁽⁵⁾/30`` and the rounding error about ``1.5 ε |f| / h``; for a second derivative ``h⁴ f⁽⁶⁾/90`` and
``5 ε |f| / h²`` (ε = 2.2e-16). With h = 1 ms and a rate ω the truncation is about ``(ω h)⁴/30`` of the derivative:
below 1e-9 for the 12 rad/s that most exercises stay under, and 3e-8 for the fastest, the cone at up to 30 rad/s.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import pytest
import sympy
from scipy.optimize import brentq
from scipy.spatial.transform import Rotation

from app.physics.systems.ch04.rolling import SteadyRolling
from app.practice.variants import variant
from tests.practice.shipped import EXERCISES

VARIANTS = range(0, 100, 9)
H = 1e-3


def _drawn(exercise_id: str, number: int):
    return variant(EXERCISES[exercise_id], number)


def _d1(f: Callable[[float], np.ndarray], t: float = 0.0, h: float = H) -> np.ndarray:
    return (-f(t + 2 * h) + 8 * f(t + h) - 8 * f(t - h) + f(t - 2 * h)) / (12 * h)


def _d2(f: Callable[[float], np.ndarray], t: float = 0.0, h: float = H) -> np.ndarray:
    return (-f(t + 2 * h) + 16 * f(t + h) - 30 * f(t) + 16 * f(t - h) - f(t - 2 * h)) / (12 * h * h)


def _vee(skew: np.ndarray) -> np.ndarray:
    """The vector of a (nearly) skew matrix, from its skew part."""
    s = 0.5 * (skew - skew.T)
    return np.array([s[2, 1], s[0, 2], s[1, 0]])


def _omega_alpha(attitude: Callable[[float], np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """ω and α on the fixed frame at t = 0 from an attitude [R](t) alone: [ω̃] = Ṙ Rᵀ and, differentiating that,
    [α̃] = R̈ Rᵀ + Ṙ Ṙᵀ."""
    R, Rd, Rdd = attitude(0.0), _d1(attitude), _d2(attitude)
    return _vee(Rd @ R.T), _vee(Rdd @ R.T + Rd @ Rd.T)


def _close(vector, expected, rel: float) -> None:
    vector, expected = np.asarray(vector, dtype=float), np.asarray(expected, dtype=float)
    assert np.linalg.norm(vector - expected) <= rel * np.linalg.norm(expected), (vector, expected)


def _named(names: str) -> dict[str, sympy.Symbol]:
    """The symbols of an expression part by name (real, as the checker and the answer functions make them)."""
    return {name: sympy.Symbol(name, real=True) for name in names.split()}


def _at(expression: sympy.Expr, values: dict[str, float]) -> float:
    return float(expression.subs({sympy.Symbol(k, real=True): v for k, v in values.items()}))


# -- 4.1 ---------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", VARIANTS)
def test_disk_on_turntable_point_is_the_difference_of_its_composed_position(number):
    """The disk's attitude composed by scipy as intrinsic Z-Y-X turns (φ(t), −β, ψ(t)) with φ and ψ moving at constant
    accelerations; B = L n̂(t) + [R(t)] r_B/A (body). ω, α from the attitude, v_B and a_B from differencing B.
    h = 1 ms and |ω| ≤ 10 rad/s: truncation below 1e-8, rounding below 1e-9, so agreement to 1e-6."""
    drawn = _drawn("4-1-disk-on-turntable-point", number)
    g, answers = drawn.given, drawn.answers
    beta, gamma = math.radians(g["elevation_deg"]), math.radians(g["point_deg"])
    radius, length = g["radius_m"], g["shaft_m"]

    def attitude(t: float) -> np.ndarray:
        phi = g["turntable_rate_rad_s"] * t + 0.5 * g["turntable_accel_rad_s2"] * t * t
        psi = g["spin_rate_rad_s"] * t + 0.5 * g["spin_accel_rad_s2"] * t * t
        return Rotation.from_euler("ZYX", [phi, -beta, psi]).as_matrix()

    body_point = radius * np.array([0.0, math.cos(gamma), math.sin(gamma)])

    def point(t: float) -> np.ndarray:
        R = attitude(t)
        return length * R[:, 0] + R @ body_point

    omega, alpha = _omega_alpha(attitude)
    _close(answers["omega"].value, omega, 1e-6)
    _close(answers["alpha"].value, alpha, 1e-6)
    _close(answers["velocity"].value, _d1(point), 1e-6)
    _close(answers["accel"].value, _d2(point), 1e-6)
    # the statement's r_B/A is the composed one at t = 0
    _close(point(0.0) - length * attitude(0.0)[:, 0], radius * np.array([
        -math.sin(gamma) * math.sin(beta), math.cos(gamma), math.sin(gamma) * math.cos(beta)]), 1e-12)  # fmt: skip


@pytest.mark.parametrize("number", VARIANTS)
def test_ladder_answers_are_sympy_derivatives_of_the_top_height(number):
    """The foot at x_A(t) = L cos θ + v t + a t²/2 and the top at y_B = √(L² − x_A²) (the ladder's length): the
    bar's angle is atan2(y_B, −x_A). sympy differentiates exactly, so the numbers agree to rounding (1e-10); the
    formula for ω agrees with the derivative at 12 random (v, L, θ) to 1e-10 as well."""
    drawn = _drawn("4-1-ladder-sliding-ends", number)
    g, answers = drawn.given, drawn.answers
    t = sympy.Symbol("t", real=True)
    x_a = g["length_m"] * sympy.cos(sympy.rad(g["angle_deg"])) + g["foot_speed_m_s"] * t
    x_a += sympy.Rational(1, 2) * g["foot_accel_m_s2"] * t**2
    y_b = sympy.sqrt(g["length_m"] ** 2 - x_a**2)
    angle = sympy.atan2(y_b, -x_a)
    at0 = {t: 0}
    assert answers["vb"].value == pytest.approx(float(sympy.diff(y_b, t).subs(at0)), rel=1e-10)
    assert answers["ab"].value == pytest.approx(float(sympy.diff(y_b, t, 2).subs(at0)), rel=1e-10)
    assert answers["alpha"].value == pytest.approx(float(sympy.diff(angle, t, 2).subs(at0)), rel=1e-10)
    rng = np.random.default_rng(41)
    for _ in range(12):
        speed, length, theta = rng.uniform(0.1, 3.0), rng.uniform(1.0, 8.0), rng.uniform(0.3, 1.3)
        foot = length * math.cos(theta) + speed * t
        derived = sympy.diff(sympy.atan2(sympy.sqrt(length**2 - foot**2), -foot), t).subs(at0)
        value = _at(answers["omega"].value, {"v": speed, "L": length, "theta": theta})
        assert value == pytest.approx(float(derived), rel=1e-10)


@pytest.mark.parametrize("number", VARIANTS)
def test_drone_hub_is_the_difference_of_a_body_turned_by_a_rotation_vector(number):
    """The body turned by exp([ω t + α t²/2]×) (scipy's rotation vector): its angular velocity at t = 0 is ω and its
    angular acceleration α (the correction ½ θ × θ̇ is O(t²)). The hub B(t) = G(t) + that turn applied to r_B/G,
    differenced at t = 0 (|ω| ≤ 4.2 rad/s: error below 1e-9): agreement to 1e-7. With −ω the velocity changes and
    the acceleration does not, which is the choice 'velocity-only'."""
    drawn = _drawn("4-1-drone-rotor-hub", number)
    g, answers = drawn.given, drawn.answers
    omega = np.array([g["p_rad_s"], g["q_rad_s"], g["r_rad_s"]])
    alpha = np.array([g["alpha_x_rad_s2"], g["alpha_y_rad_s2"], g["alpha_z_rad_s2"]])
    chi = math.radians(g["arm_deg"])
    arm = g["arm_m"] * np.array([math.cos(chi), math.sin(chi), 0.0])

    def hub(w: np.ndarray) -> Callable[[float], np.ndarray]:
        def position(t: float) -> np.ndarray:
            centre = np.array([g["speed_m_s"] * t, 0.0, 0.5 * g["climb_accel_m_s2"] * t * t])
            return centre + Rotation.from_rotvec(w * t + 0.5 * alpha * t * t).apply(arm)

        return position

    _close(answers["velocity"].value, _d1(hub(omega)), 1e-7)
    _close(answers["accel"].value, _d2(hub(omega)), 1e-7)
    reversed_v, reversed_a = _d1(hub(-omega)), _d2(hub(-omega))
    assert not np.allclose(reversed_v, _d1(hub(omega)), rtol=1e-3, atol=1e-6)
    _close(reversed_a, _d2(hub(omega)), 1e-7)
    assert answers["reverse"].value == "velocity-only"


# -- 4.2 ---------------------------------------------------------------------------------------------------------


def _zxz(phi: float, theta: float, psi: float) -> np.ndarray:
    """[R] of the 3-1-3 Eulerian angles, by scipy (upper-case axes: intrinsic)."""
    return Rotation.from_euler("ZXZ", [phi, theta, psi]).as_matrix()


def _nutation_frame_rates(phid: float, thetad: float, psid: float, theta: float, phidd: float = 0.0):
    """ω and α on the nutation frame at t = 0 for φ(t) = φ̇t + φ̈t²/2, θ(t) = θ + θ̇t, ψ(t) = ψ̇t, from the attitude
    alone; and that attitude."""

    def attitude(t: float) -> np.ndarray:
        return _zxz(phid * t + 0.5 * phidd * t * t, theta + thetad * t, psid * t)

    omega, alpha = _omega_alpha(attitude)
    frame = Rotation.from_euler("ZX", [0.0, theta]).as_matrix()  # x′y′z′ on XYZ at t = 0 (φ = 0)
    return frame.T @ omega, frame.T @ alpha, attitude


@pytest.mark.parametrize("number", VARIANTS)
def test_top_nutation_frame_rates_are_differences_of_scipys_attitude(number):
    """scipy's Z-X-Z attitude with the three angles moving at the given rates; ω and α from Ṙ Rᵀ and R̈ Rᵀ + Ṙ Ṙᵀ
    (h = 1 ms, |ω| ≤ 11 rad/s: error below 1e-8), turned onto x′y′z′: agreement to 1e-6. The formula for α_y′ is
    compared with the same differences at 12 random points of its symbols' ranges, to 1e-6 of |α|."""
    drawn = _drawn("4-2-top-nutation-frame", number)
    g, answers = drawn.given, drawn.answers
    omega, alpha, _ = _nutation_frame_rates(
        g["precession_rate_rad_s"], g["nutation_rate_rad_s"], g["spin_rate_rad_s"], math.radians(g["nutation_deg"])
    )
    _close(answers["omega"].value, omega, 1e-6)
    _close(answers["alpha"].value, alpha, 1e-6)
    rng = np.random.default_rng(42)
    for _ in range(12):
        values = {
            "phid": rng.uniform(0.2, 3.0),
            "thetad": rng.uniform(0.2, 2.0),
            "psid": rng.uniform(2.0, 20.0),
            "theta": rng.uniform(0.2, 1.4),
        }
        _, expected, _ = _nutation_frame_rates(values["phid"], values["thetad"], values["psid"], values["theta"])
        assert abs(_at(answers["alpha-y"].value, values) - expected[1]) <= 1e-6 * np.linalg.norm(expected)


@pytest.mark.parametrize("number", VARIANTS)
def test_gyro_rotor_rim_point_is_the_difference_of_the_turned_point(number):
    """The rim point is the body point (0, R, L) (body axes = nutation frame at t = 0, since ψ = 0 then), carried by
    scipy's Z-X-Z attitude with φ speeding up; its position differenced at t = 0 (error below 1e-8) gives v_P and
    a_P, and the attitude gives α, all turned onto x′y′z′: agreement to 1e-6."""
    drawn = _drawn("4-2-gyro-rotor-rim-point", number)
    g, answers = drawn.given, drawn.answers
    theta = math.radians(g["nutation_deg"])
    _, alpha, attitude = _nutation_frame_rates(
        g["precession_rate_rad_s"], 0.0, g["spin_rate_rad_s"], theta, g["precession_accel_rad_s2"]
    )
    frame = Rotation.from_euler("ZX", [0.0, theta]).as_matrix()
    body_point = np.array([0.0, g["radius_m"], g["arm_m"]])

    def point(t: float) -> np.ndarray:
        return attitude(t) @ body_point

    _close(answers["alpha"].value, alpha, 1e-6)
    assert answers["speed"].value == pytest.approx(np.linalg.norm(_d1(point)), rel=1e-6)
    _close(answers["accel"].value, frame.T @ _d2(point), 1e-6)
    # P is the highest point of the rim: no other rim point of the disk is higher
    rim = [attitude(0.0) @ np.array([g["radius_m"] * math.cos(a), g["radius_m"] * math.sin(a), g["arm_m"]])
           for a in np.linspace(0.0, 2 * math.pi, 721)]  # fmt: skip
    assert max(p[2] for p in rim) <= point(0.0)[2] + 1e-12


@pytest.mark.parametrize("number", VARIANTS)
def test_rates_near_upright_reproduce_the_gyro_readings(number):
    """The body components of ω for unit rates of each angle, by differencing scipy's Z-X-Z attitude ({ω}_body =
    vee(Rᵀ Ṙ)), make the 3×3 matrix that maps (φ̇, θ̇, ψ̇) to the gyros; solving it with numpy gives the rates, and
    again with ω_x + δ the bias's effect (error below 1e-9 each; agreement to 1e-6). The matrix's determinant
    vanishes at θ = 0 (the choice 'upright') and not at θ = 90°."""
    drawn = _drawn("4-2-rates-near-upright", number)
    g, answers = drawn.given, drawn.answers
    psi = math.radians(g["spin_deg"])

    def columns(theta: float) -> np.ndarray:
        out = []
        for k in range(3):
            rates = np.eye(3)[k]

            def attitude(t: float, rates: np.ndarray = rates) -> np.ndarray:
                return _zxz(rates[0] * t, theta + rates[1] * t, psi + rates[2] * t)

            out.append(_vee(attitude(0.0).T @ _d1(attitude)))
        return np.array(out).T

    J = columns(math.radians(g["nutation_deg"]))
    gyros = np.array([g["wx_rad_s"], g["wy_rad_s"], g["wz_rad_s"]])
    rates = np.linalg.solve(J, gyros)
    shifted = np.linalg.solve(J, gyros + np.array([g["bias_rad_s"], 0.0, 0.0]))
    assert answers["precession"].value == pytest.approx(rates[0], rel=1e-6)
    assert answers["spin"].value == pytest.approx(rates[2], rel=1e-6)
    assert answers["bias"].value == pytest.approx(abs(shifted[0] - rates[0]), rel=1e-6)
    assert abs(np.linalg.det(columns(0.0))) < 1e-9 and abs(np.linalg.det(columns(math.pi / 2))) > 0.99
    assert answers["fails"].value == "upright"


# -- 4.3 ---------------------------------------------------------------------------------------------------------


def _four_bar_pins(g: dict, crank: float) -> tuple[np.ndarray, np.ndarray]:
    """A and B of the open assembly at crank angle ``crank``, by brentq on the rocker angle: B = O₄ + c e^{iθ₄} must
    be b from A. The two roots are bracketed on a 720-step grid; the open one has B left of A → O₄. Each root is
    found to 1e-15 + 8.9e-16 |θ₄| rad (about 4e-15 rad), brentq's tightest."""
    a, b, c, d = g["crank_m"], g["coupler_m"], g["rocker_m"], g["ground_m"]
    pin_a = a * np.array([math.cos(crank), math.sin(crank)])

    def miss(angle: float) -> float:
        pin_b = np.array([d + c * math.cos(angle), c * math.sin(angle)])
        return float(np.dot(pin_b - pin_a, pin_b - pin_a) - b * b)

    grid = np.linspace(-math.pi, math.pi, 721)
    values = [miss(x) for x in grid]
    for lo, hi, f_lo, f_hi in zip(grid[:-1], grid[1:], values[:-1], values[1:]):
        if f_lo * f_hi < 0:
            angle = brentq(miss, lo, hi, xtol=1e-15, rtol=8.9e-16)
            pin_b = np.array([d + c * math.cos(angle), c * math.sin(angle)])
            to_o4, to_b = np.array([d, 0.0]) - pin_a, pin_b - pin_a
            if to_o4[0] * to_b[1] - to_o4[1] * to_b[0] > 0:
                return pin_a, pin_b
    raise AssertionError("no open assembly found")


def _angle_near(vector: np.ndarray, reference: float) -> float:
    """The direction of a plane vector, within π of ``reference`` (so differences do not jump by 2π)."""
    angle = math.atan2(vector[1], vector[0])
    return reference + (angle - reference + math.pi) % (2 * math.pi) - math.pi


def _four_bar_motion(g: dict, crank_accel: float = 0.0):
    theta2 = math.radians(g["crank_deg"])
    w2 = g["crank_speed_rad_s"]
    d = g["ground_m"]
    pin_a0, pin_b0 = _four_bar_pins(g, theta2)
    ref3, ref4 = math.atan2(*(pin_b0 - pin_a0)[::-1]), math.atan2(pin_b0[1], pin_b0[0] - d)

    def pins(t: float) -> tuple[np.ndarray, np.ndarray]:
        return _four_bar_pins(g, theta2 + w2 * t + 0.5 * crank_accel * t * t)

    def angles(t: float) -> np.ndarray:
        pin_a, pin_b = pins(t)
        return np.array([_angle_near(pin_b - pin_a, ref3), _angle_near(pin_b - np.array([d, 0.0]), ref4)])

    def pin_b(t: float) -> np.ndarray:
        return np.append(pins(t)[1], 0.0)

    return angles, pin_b


@pytest.mark.parametrize("number", VARIANTS)
def test_four_bar_rates_are_differences_of_a_loop_closed_by_root_finding(number):
    """The loop closed by brentq on the rocker angle (roots to about 4e-15 rad), at crank angles θ₂ + ω₂t; the coupler
    and rocker angles and B differenced at t = 0 with h = 1 ms (rounding ~1.5 × 4e-15/h = 6e-12 rad/s, truncation
    ~1e-10): θ₄ to 1e-9, the rates and v_B to 1e-6."""
    drawn = _drawn("4-3-four-bar-rates", number)
    g, answers = drawn.given, drawn.answers
    angles, pin_b = _four_bar_motion(g)
    theta4 = math.degrees(angles(0.0)[1])
    assert answers["rocker-angle"].value == pytest.approx(theta4, rel=1e-9, abs=1e-9)
    rates = _d1(angles)
    assert answers["omega3"].value == pytest.approx(rates[0], rel=1e-6)
    assert answers["omega4"].value == pytest.approx(rates[1], rel=1e-6)
    _close(answers["velocity-b"].value, _d1(pin_b), 1e-6)


@pytest.mark.parametrize("number", VARIANTS)
def test_four_bar_accelerations_are_second_differences_of_the_closed_loop(number):
    """As above with the crank at θ₂ + ω₂t + α₂t²/2, differenced twice (h = 1 ms: rounding ~5 × 4e-15/h² = 2e-8
    rad/s², truncation ~1e-9): α₃, α₄ and a_B to 1e-5 (the answers are at least 0.05 rad/s² by the exercise's own
    check, so 2e-8 is below 1e-6 of them)."""
    drawn = _drawn("4-3-four-bar-accelerations", number)
    g, answers = drawn.given, drawn.answers
    angles, pin_b = _four_bar_motion(g, g["crank_accel_rad_s2"])
    second = _d2(angles)
    assert answers["alpha3"].value == pytest.approx(second[0], rel=1e-5)
    assert answers["alpha4"].value == pytest.approx(second[1], rel=1e-5)
    _close(answers["accel-b"].value, _d2(pin_b), 1e-5)


@pytest.mark.parametrize("number", VARIANTS)
def test_offset_slider_crank_answers_are_sympy_derivatives_of_the_slider_position(number):
    """sin φ = (e − r sin θ)/l and x = r cos θ + l cos φ with θ = θ₀ + ω t, differentiated by sympy: exact, so the
    numbers agree to rounding (1e-10). The formula for φ̇ is compared with the sympy derivative at 12 random points
    of its symbols' ranges (1e-10)."""
    drawn = _drawn("4-3-offset-slider-crank", number)
    g, answers = drawn.given, drawn.answers
    t = sympy.Symbol("t", real=True)

    def slider(crank, rod, offset, angle0, speed):
        angle = angle0 + speed * t
        phi = sympy.asin((offset - crank * sympy.sin(angle)) / rod)
        return phi, crank * sympy.cos(angle) + rod * sympy.cos(phi)

    phi, x = slider(g["crank_m"], g["rod_m"], g["offset_m"], sympy.rad(g["crank_deg"]), g["crank_speed_rad_s"])
    at0 = {t: 0}
    assert answers["rod-angle"].value == pytest.approx(math.degrees(float(phi.subs(at0))), rel=1e-10)
    assert answers["slider-vel"].value == pytest.approx(float(sympy.diff(x, t).subs(at0)), rel=1e-10)
    assert answers["slider-acc"].value == pytest.approx(float(sympy.diff(x, t, 2).subs(at0)), rel=1e-10)
    rng = np.random.default_rng(43)
    for _ in range(12):
        values = {
            "r": rng.uniform(0.05, 0.3),
            "l": rng.uniform(0.8, 1.5),
            "e": rng.uniform(0.1, 0.4),
            "theta": rng.uniform(-3.0, 3.0),
            "omega": rng.uniform(1.0, 10.0),
        }
        rate, _ = slider(values["r"], values["l"], values["e"], values["theta"], values["omega"])
        expected = float(sympy.diff(rate, t).subs(at0))
        assert _at(answers["rod-rate"].value, values) == pytest.approx(expected, rel=1e-10, abs=1e-12)


def _cardan_output_angle(beta: float, phi1: float) -> float:
    """φ₂ from the statement's pins alone: the root of u·v = 0 within a quarter turn of φ₁, by brentq (u·v is a
    sinusoid in φ₂ with roots π apart, so that interval holds exactly one; xtol 1e-15, rtol 8.9e-16)."""
    u = np.array([0.0, math.cos(phi1), math.sin(phi1)])

    def dot(phi2: float) -> float:
        v = math.cos(phi2) * np.array([0.0, 0.0, 1.0]) + math.sin(phi2) * np.array([math.sin(beta), -math.cos(beta), 0])
        return float(u @ v)

    return brentq(dot, phi1 - math.pi / 2 + 1e-9, phi1 + math.pi / 2 - 1e-9, xtol=1e-15, rtol=8.9e-16)


@pytest.mark.parametrize("number", VARIANTS)
def test_cardan_output_is_the_root_of_the_pin_constraint_and_its_differences(number):
    """The output angle as the root of u·v = 0 (to about 4e-15 rad) at input angles φ₁ + ω₁t, differenced at t = 0
    with h = 1 ms (ω ≤ 20 rad/s: truncation below 6e-9, rounding below 2e-8 rad/s²): φ₂ to 1e-9, ω₂ to 1e-7, α₂ to
    1e-5 of ω₁² (its natural size). The formula for ω₂/ω₁ agrees with dφ₂/dφ₁ differenced (h = 1e-3 rad) at 12 random
    (β, φ₁) to 1e-8."""
    drawn = _drawn("4-3-cardan-output", number)
    g, answers = drawn.given, drawn.answers
    beta, phi1, w1 = math.radians(g["shaft_angle_deg"]), math.radians(g["input_deg"]), g["input_speed_rad_s"]

    def output(t: float) -> np.ndarray:
        return np.array([_cardan_output_angle(beta, phi1 + w1 * t)])

    assert answers["out-angle"].value == pytest.approx(math.degrees(output(0.0)[0]), rel=1e-9)
    assert answers["out-speed"].value == pytest.approx(_d1(output)[0], rel=1e-7)
    assert abs(answers["out-accel"].value - _d2(output)[0]) <= 1e-5 * w1**2
    rng = np.random.default_rng(45)
    for _ in range(12):
        b, p = rng.uniform(0.1, 1.2), rng.uniform(-3.0, 3.0)
        slope = _d1(lambda x, b=b, p=p: np.array([_cardan_output_angle(b, p + x)]))[0]
        assert _at(answers["ratio"].value, {"beta": b, "phi": p}) == pytest.approx(slope, rel=1e-8)


# -- 4.4 ---------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("number", VARIANTS)
def test_wheel_rim_point_is_the_difference_of_its_rolled_position(number):
    """The wheel's centre at s(t) = v t + a t²/2 and its turn −s(t)/R (rolling without slip, written as a position):
    P(t) = G(t) + turn applied to R(sin β, −cos β), differenced at t = 0 (rates ≤ 12 rad/s: error below 1e-8):
    agreement to 1e-6. At β = 0 the same differences give an acceleration straight up, of size v²/R."""
    drawn = _drawn("4-4-wheel-rim-points", number)
    g, answers = drawn.given, drawn.answers
    radius = g["radius_m"]

    def rim_point(beta: float) -> Callable[[float], np.ndarray]:
        def position(t: float) -> np.ndarray:
            travel = g["speed_m_s"] * t + 0.5 * g["accel_m_s2"] * t * t
            turn = Rotation.from_rotvec([0.0, 0.0, -travel / radius])
            return np.array([travel, radius, 0.0]) + turn.apply(radius * np.array([math.sin(beta), -math.cos(beta), 0]))

        return position

    point = rim_point(math.radians(g["point_deg"]))
    _close(answers["velocity"].value, _d1(point), 1e-6)
    _close(answers["accel"].value, _d2(point), 1e-6)
    assert np.linalg.norm(_d1(rim_point(0.0))) <= 1e-9 * g["speed_m_s"]  # no slip, as written into the position
    contact = _d2(rim_point(0.0))
    _close(contact, [0.0, g["speed_m_s"] ** 2 / radius, 0.0], 1e-6)
    assert answers["contact"].value == "up"


def _rolling(body: str, radius: float, tilt_deg: float, path: float, speed: float) -> SteadyRolling:
    return SteadyRolling.from_params(
        {"body": body, "rim_radius_m": radius, "tilt_deg": tilt_deg, "path_radius_m": path, "speed_m_s": speed}
    )


def _rolling_attitude(model: SteadyRolling) -> Callable[[float], np.ndarray]:
    """[R](t) of the rolling body from the model's attitude quaternion (composed from the heading and spin angles;
    no angular-velocity formula in it). scipy reads quaternions as (x, y, z, w)."""

    def attitude(t: float) -> np.ndarray:
        w, x, y, z = model.at(np.array([t])).wxyz[0]
        return Rotation.from_quat([x, y, z, w]).as_matrix()

    return attitude


@pytest.mark.parametrize("number", VARIANTS)
def test_leaning_disk_answers_match_the_rolling_models_positions(number):
    """The rolling scene's model, by its positions: ω from the difference of its attitude (at t = 0, ê_r = X and
    ê_ψ = Y, so the world components are the answer's), and the spin as the component of that ω along the axis less
    the turn's share, ω·n̂ − (v/ρ) sin θ. The centre's speed is the difference of the model's centre position, the
    contact's material point (the model's rim point at the bottom) differences to zero velocity, and the point
    (0, 0, z_O′) of the answer moves at v_G + ω × (r − r_G) = 0 and lies on the disk's axis. Differences: error
    below 1e-9; agreement to 1e-7."""
    drawn = _drawn("4-4-leaning-disk-circle", number)
    g, answers = drawn.given, drawn.answers
    model = _rolling("disk", g["radius_m"], g["tilt_deg"], g["path_m"], g["speed_m_s"])
    state = model.at(np.array([0.0]))
    omega, _ = _omega_alpha(_rolling_attitude(model))
    _close(answers["omega"].value, omega, 1e-7)
    turn_share = g["speed_m_s"] / g["path_m"] * math.sin(math.radians(g["tilt_deg"]))
    assert answers["spin"].value == pytest.approx(float(omega @ state.axis[0]) - turn_share, rel=1e-7)

    def centre(t: float) -> np.ndarray:
        return model.at(np.array([t])).center[0]

    def contact(t: float) -> np.ndarray:
        return model.rim_points(model.at(np.array([t])), 0, 2)[0]

    v_g = _d1(centre)
    assert answers["centre-speed"].value == pytest.approx(np.linalg.norm(v_g), rel=1e-7)
    assert np.linalg.norm(_d1(contact)) <= 1e-7 * g["speed_m_s"]
    axis_point = np.array([0.0, 0.0, answers["axis-height"].value])
    from_centre = axis_point - state.center[0]
    assert np.linalg.norm(v_g + np.cross(omega, from_centre)) <= 1e-7 * g["speed_m_s"]
    assert np.linalg.norm(np.cross(from_centre, state.axis[0])) <= 1e-9 * np.linalg.norm(from_centre)


@pytest.mark.parametrize("number", VARIANTS)
def test_cone_answers_match_the_rolling_models_motion(number):
    """The rolling scene's cone (path radius R / sin θ), by its positions: ω and α from differences of the model's
    attitude, the top of the base rim as the difference of the model's rim point that is highest at t = 0 (|ω| up to
    30 rad/s: errors below 3e-8; agreement to 1e-7). The formula for |ω| is compared at 12 random points with |ω|
    from the attitude of a cone of those dimensions (1e-7; R from 0.15 m, so that |ω| stays under 30 rad/s)."""
    drawn = _drawn("4-4-cone-rolling-apex", number)
    g, answers = drawn.given, drawn.answers
    model = _rolling("cone", g["radius_m"], g["half_angle_deg"], 1.0, g["speed_m_s"])
    state = model.at(np.array([0.0]))
    omega, alpha = _omega_alpha(_rolling_attitude(model))
    _close(answers["omega"].value, omega, 1e-7)

    def top(t: float) -> np.ndarray:
        return model.rim_points(model.at(np.array([t])), 0, 2)[1]

    assert top(0.0)[2] == pytest.approx(max(p[2] for p in model.rim_points(state, 0, 720)), rel=1e-12)
    assert answers["top-speed"].value == pytest.approx(np.linalg.norm(_d1(top)), rel=1e-7)
    assert answers["alpha"].value == pytest.approx(np.linalg.norm(alpha), rel=1e-7)
    rng = np.random.default_rng(44)
    for _ in range(12):
        speed, radius, theta = rng.uniform(0.2, 4.0), rng.uniform(0.15, 0.6), rng.uniform(0.1, 1.0)
        cone = _rolling("cone", radius, math.degrees(theta), 1.0, speed)
        expected = np.linalg.norm(_omega_alpha(_rolling_attitude(cone))[0])
        assert _at(answers["omega-size"].value, {"v": speed, "R": radius, "theta": theta}) == pytest.approx(
            expected, rel=1e-7
        )
