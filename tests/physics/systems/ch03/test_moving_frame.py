"""The five-term moving-frame acceleration (app/physics/moving_frame.py), checked by differentiating the motion.

The reference here never uses the formula being tested: the slider's world
position is composed from the body's attitude (built from elementary quaternions,
not from the module's rotation matrices), the cart's position and the slider's
position in the groove, and is then differentiated numerically.
"""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

from app.physics.core.parameters import ParameterError
from app.physics.math.rotations import quaternion_from_axis_angle, quaternion_multiply, rotation_matrix
from app.physics.systems.ch03 import moving_frame as physics

H_S = 1e-3  # finite-difference step (s)
DRAWS = 150


def composed_position(params, t: float) -> np.ndarray:
    """World position of P from first principles: r_O + R_z(Ω_p t) R_x(β) R_z(θ) r_rel (built from quaternions)."""
    theta = params["spin_rate_rad_s"] * t + 0.5 * params["spin_acceleration_rad_s2"] * t * t
    q = quaternion_multiply(
        quaternion_multiply(
            quaternion_from_axis_angle(np.array([0.0, 0.0, 1.0]), params["precession_rate_rad_s"] * t),
            quaternion_from_axis_angle(np.array([1.0, 0.0, 0.0]), math.radians(params["tilt_deg"])),
        ),
        quaternion_from_axis_angle(np.array([0.0, 0.0, 1.0]), theta),
    )
    s = params["slider_amplitude_m"] * math.sin(2 * math.pi * params["slider_frequency_hz"] * t)
    r_rel_body = np.array([s, params["groove_offset_m"], 0.0])
    x_cart = params["cart_amplitude_m"] * math.sin(2 * math.pi * params["cart_frequency_hz"] * t)
    return np.array([x_cart, 0.0, physics.TABLE_HEIGHT_M]) + rotation_matrix(q) @ r_rel_body


def second_derivative(f, t: float, h: float = H_S) -> np.ndarray:
    """Fourth-order central difference: error h⁴ f⁽⁶⁾ / 90 plus round-off ≈ 5.3 ε |f| / h²."""
    return (-f(t + 2 * h) + 16 * f(t + h) - 30 * f(t) + 16 * f(t - h) - f(t - 2 * h)) / (12 * h * h)


def first_derivative(f, t: float, h: float = H_S) -> np.ndarray:
    """Fourth-order central difference: error h⁴ f⁽⁵⁾ / 30 plus round-off ≈ 1.5 ε |f| / h."""
    return (-f(t + 2 * h) + 8 * f(t + h) - 8 * f(t - h) + f(t - 2 * h)) / (12 * h)


def random_params(rng: np.random.Generator) -> dict:
    """Parameters drawn uniformly over each control's whole range, redrawn until the slider stays on the table."""
    while True:
        raw = {}
        for p in physics.PARAMETERS.parameters:
            raw[p.name] = float(rng.uniform(p.min, p.max))
        raw["slider_amplitude_m"] = float(rng.uniform(0.0, raw["table_radius_m"]))
        raw["groove_offset_m"] = float(rng.uniform(-1.0, 1.0) * math.sqrt(raw["table_radius_m"] ** 2 - raw["slider_amplitude_m"] ** 2))
        try:
            return physics.PARAMETERS.validate(raw)
        except ParameterError:
            continue


@functools.cache
def draws():
    rng = np.random.default_rng(20240603)
    return [(random_params(rng), float(rng.uniform(0.0, 5.0))) for _ in range(DRAWS)]


def tolerance_m_s2(terms: dict) -> float:
    """Allowed |Σ terms − d²r/dt²|.

    With h = 1 ms the stencil's truncation error relative to an acceleration of
    the motion is about (h W)⁴/90, W the sum of all rates in the draw
    (≤ 3 + 16 + 4π + 4π ≈ 44 rad/s for t ≤ 5 s): ≤ 4e-8. Round-off is
    5.3 ε |r| / h² ≈ 5e-9 m/s² for |r| ≤ 4 m. Allowing 1e-6 of the sum of the
    terms' magnitudes (plus 1e-6 m/s²) leaves a margin of 25 over both, while any
    term with the wrong factor or sign would be off by that term's own size.
    """
    scale = sum(float(np.linalg.norm(terms[name])) for name in physics.TERM_NAMES)
    return 1e-6 * (scale + 1.0)


def test_sum_of_the_five_terms_is_the_second_derivative_of_the_composed_position():
    worst = (0.0, None)
    for params, t in draws():
        motion = physics.MovingFrameMotion.from_params(params)
        terms = {k: v[0] for k, v in motion.acceleration_terms(np.array([t])).items()}
        reference = second_derivative(lambda s: composed_position(params, s), t)
        ratio = float(np.linalg.norm(terms["total"] - reference)) / tolerance_m_s2(terms)
        worst = max(worst, (ratio, (params, t)), key=lambda w: w[0])
    assert worst[0] <= 1.0, worst


def test_the_check_above_would_catch_any_single_wrong_term():
    """Over the draws, every term is much larger than the tolerance somewhere: dropping it would fail the test."""
    largest_ratio = {name: 0.0 for name in physics.TERM_NAMES}
    for params, t in draws():
        terms = {k: v[0] for k, v in physics.MovingFrameMotion.from_params(params).acceleration_terms(np.array([t])).items()}
        tol = tolerance_m_s2(terms)
        for name in physics.TERM_NAMES:
            largest_ratio[name] = max(largest_ratio[name], float(np.linalg.norm(terms[name])) / tol)
    assert min(largest_ratio.values()) > 1e4, largest_ratio


def test_velocity_is_the_first_derivative_of_the_composed_position():
    for params, t in draws()[:40]:
        motion = physics.MovingFrameMotion.from_params(params)
        velocity = motion.velocity_world(np.array([t]))[0]
        reference = first_derivative(lambda s: composed_position(params, s), t)
        # (h W)⁴/30 ≤ 1.3e-7 relative to W·|r|, round-off 1.5 ε |r| / h ≈ 1.3e-12 m/s: 1e-6 of the speed scale.
        scale = float(np.linalg.norm(velocity)) + 1.0
        assert np.linalg.norm(velocity - reference) <= 1e-6 * scale


def test_angular_velocity_and_acceleration_come_from_the_attitude():
    """ω from Ṙ Rᵀ (finite differences of the module's own R) and α from finite differences of ω."""
    for params, t in draws()[:40]:
        motion = physics.MovingFrameMotion.from_params(params)
        R = lambda s: motion.attitude(np.array([s]))[0]  # noqa: E731
        spin = first_derivative(R, t) @ R(t).T  # skew-symmetric [ω]×
        omega_fd = np.array([spin[2, 1], spin[0, 2], spin[1, 0]])
        omega = motion.angular_velocity_world(np.array([t]))[0]
        assert np.linalg.norm(spin + spin.T) < 1e-7 * (1 + np.linalg.norm(omega))  # a rotation's Ṙ Rᵀ is skew
        assert np.linalg.norm(omega - omega_fd) < 1e-7 * (1 + np.linalg.norm(omega))
        alpha_fd = first_derivative(lambda s: motion.angular_velocity_world(np.array([s]))[0], t)
        alpha = motion.angular_acceleration_world(np.array([t]))[0]
        assert np.linalg.norm(alpha - alpha_fd) < 1e-7 * (1 + np.linalg.norm(alpha))


def test_steady_spin_and_precession_still_have_an_angular_acceleration():
    """Constant spin θ̇ about an axis tilted by β that precesses at Ω_p: |α| = θ̇ Ω_p sin β, perpendicular to k and Z."""
    params = physics.PARAMETERS.validate({"spin_rate_rad_s": 2.0, "tilt_deg": 30.0, "precession_rate_rad_s": 0.8})
    motion = physics.MovingFrameMotion.from_params(params)
    t = np.linspace(0.0, 10.0, 7)
    alpha = motion.angular_acceleration_world(t)
    np.testing.assert_allclose(np.linalg.norm(alpha, axis=-1), 2.0 * 0.8 * math.sin(math.radians(30.0)), rtol=1e-14)
    np.testing.assert_allclose(np.einsum("ni,ni->n", alpha, motion.spin_axis_world(t)), 0.0, atol=1e-14)
    np.testing.assert_allclose(alpha[:, 2], 0.0, atol=1e-14)


def test_slider_leaving_the_centre_of_a_steady_turntable_feels_only_coriolis():
    """Radial groove, steady spin ω Z, slider at the centre at t = 0 moving along body x at u = 2π f A:
    r = 0 and a_rel = 0 there, so a_P = 2 ω Z × u X = 2 ω u Y exactly."""
    params = physics.PARAMETERS.validate(
        {"spin_rate_rad_s": 1.5, "groove_offset_m": 0.0, "slider_amplitude_m": 0.7, "slider_frequency_hz": 0.2}
    )
    terms = {k: v[0] for k, v in physics.MovingFrameMotion.from_params(params).acceleration_terms(np.array([0.0])).items()}
    u = 2 * math.pi * 0.2 * 0.7
    np.testing.assert_allclose(terms["coriolis"], [0.0, 2 * 1.5 * u, 0.0], atol=1e-15)
    np.testing.assert_allclose(terms["total"], terms["coriolis"], atol=1e-15)
    for name in ("reference", "angular", "centripetal", "relative"):
        np.testing.assert_allclose(terms[name], 0.0, atol=1e-15)


def test_a_slider_that_would_leave_the_table_is_refused_by_name():
    with pytest.raises(ParameterError) as info:
        physics.PARAMETERS.validate({"table_radius_m": 1.0, "slider_amplitude_m": 0.9, "groove_offset_m": 0.5})
    assert info.value.field == "slider_amplitude_m" and "leave the table" in str(info.value)


def test_closed_form_model_reports_every_series_it_declares():
    model = physics.MovingFrameAcceleration()
    t = np.linspace(0.0, 3.0, 31)
    solution = model.evaluate(physics.PARAMETERS.defaults(), t)
    assert set(solution.series) == set(model.series_units)
    total = np.stack([solution.series[f"a_total_{c}"] for c in "xyz"], axis=-1)
    parts = sum(np.stack([solution.series[f"a_{n}_{c}"] for c in "xyz"], axis=-1) for n in physics.TERM_NAMES)
    np.testing.assert_allclose(total, parts, rtol=0, atol=1e-14)
