"""Eulerian angles (app/physics/systems/ch04/eulerian_angles.py): ω and α against the rotation matrix itself.

The reference writes [R(t)] = Rz(φ) Rx(θ) Rz(ψ) out in this file, with the angles quadratic in t, and takes
[ω̃] = Ṙ Rᵀ (world) with Ṙ from an eighth-order central difference; α is the same difference applied to the
module's ω. Random draws keep every rate and acceleration within ±10 (rad/s, rad/s²), so over one 8 s cycle no rate
exceeds 90 rad/s. Step h = 1e-3 s: truncation ≈ h⁸ |R⁽⁹⁾| / 630 ≲ 1e-24 · 90⁹ / 630 ≈ 6e-10 (per unit of R, times
rad/s), round-off ≈ 10 ε / h ≈ 2e-12. Relative to |ω| + 1 rad/s (|α| + 1 rad/s²), 1e-6 is the brief's target and
holds with room.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.systems.ch04 import eulerian_angles as physics

H_S = 1e-3
FIRST = np.array([1 / 280, -4 / 105, 1 / 5, -4 / 5, 0.0, 4 / 5, -1 / 5, 4 / 105, -1 / 280])
RELATIVE_TOL = 1e-6
NAMES = ("precession", "nutation", "spin")


def Rz(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def Rx(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def angles_at(p: dict, t: float) -> tuple[float, float, float]:
    return tuple(math.radians(p[f"{n}_deg"]) + p[f"{n}_rate_rad_s"] * t + 0.5 * p[f"{n}_acceleration_rad_s2"] * t * t for n in NAMES)


def attitude(p: dict, t: float) -> np.ndarray:
    phi, theta, psi = angles_at(p, t)
    return Rz(phi) @ Rx(theta) @ Rz(psi)


def omega_from_matrix(p: dict, t: float) -> np.ndarray:
    R_dot = np.tensordot(FIRST, np.array([attitude(p, t + k * H_S) for k in range(-4, 5)]), axes=1) / H_S
    W = R_dot @ attitude(p, t).T
    assert np.abs(W + W.T).max() < 1e-8  # skew-symmetric, as it must be
    return np.array([W[2, 1], W[0, 2], W[1, 0]])


def random_params(rng) -> dict:
    raw = {}
    for p in physics.PARAMETERS.parameters:
        low, high = (max(p.min, -10.0), min(p.max, 10.0)) if p.unit != "deg" else (p.min, p.max)
        raw[p.name] = float(rng.uniform(low, high))
    return physics.PARAMETERS.validate(raw)


@pytest.mark.parametrize("seed", range(8))
def test_omega_is_the_vee_of_R_dot_R_transpose_and_alpha_its_derivative(seed):
    rng = np.random.default_rng(seed)
    params = random_params(rng) if seed else physics.PARAMETERS.defaults()
    motion = physics.EulerianAngleMotion.from_params(params)
    for t in (0.0, *rng.uniform(0.0, 8.0, 3)):
        k = motion.at(np.array([t])).kinematics
        omega = k.omega_world_rad_s[0]
        assert np.allclose(k.R_world_body[0], attitude(params, t), rtol=0.0, atol=1e-12)
        assert np.linalg.norm(omega - omega_from_matrix(params, t)) <= RELATIVE_TOL * (np.linalg.norm(omega) + 1.0), (seed, t)
        samples = motion.at(t + H_S * np.arange(-4, 5)).kinematics.omega_world_rad_s
        alpha_fd = FIRST @ samples / H_S
        alpha = k.alpha_world_rad_s2[0]
        assert np.linalg.norm(alpha - alpha_fd) <= RELATIVE_TOL * (np.linalg.norm(alpha) + 1.0), (seed, t)


@pytest.mark.parametrize("seed", range(4))
def test_components_on_the_nutation_and_body_frames_are_the_textbook_formulas(seed):
    """ω on x′y′z′ = (θ̇, φ̇ sin θ, φ̇ cos θ + ψ̇); on xyz turned by ψ; α on x′y′z′ = d/dt(components) + Ω′ × ω with
    Ω′ = (θ̇, φ̇ sin θ, φ̇ cos θ) the nutation frame's own angular velocity. Algebraic identities: 1e-12."""
    rng = np.random.default_rng(100 + seed)
    params = random_params(rng)
    t = float(rng.uniform(0.0, 8.0))
    state = physics.EulerianAngleMotion.from_params(params).at(np.array([t]))
    k = state.kinematics
    phi, theta, psi = k.angles_rad[0]
    dphi, dtheta, dpsi = k.rates_rad_s[0]
    ddphi, ddtheta, ddpsi = (params[f"{n}_acceleration_rad_s2"] for n in NAMES)
    st, ct, sp, cp = math.sin(theta), math.cos(theta), math.sin(psi), math.cos(psi)
    w = np.array([dtheta, dphi * st, dphi * ct + dpsi])
    assert state.angular_velocity_nutation[0] == pytest.approx(w, abs=1e-12)
    body = [dphi * st * sp + dtheta * cp, dphi * st * cp - dtheta * sp, dphi * ct + dpsi]
    assert k.omega_body_rad_s[0] == pytest.approx(body, abs=1e-12)
    component_rates = np.array([ddtheta, ddphi * st + dphi * dtheta * ct, ddphi * ct - dphi * dtheta * st + ddpsi])
    frame_rate = np.array([dtheta, dphi * st, dphi * ct])
    assert state.angular_acceleration_nutation[0] == pytest.approx(component_rates + np.cross(frame_rate, w), abs=1e-10)


def test_at_theta_zero_the_rates_cannot_be_read_back_and_the_note_says_why():
    params = physics.PARAMETERS.validate({"nutation_deg": 0.0, "nutation_rate_rad_s": 0.0, "nutation_acceleration_rad_s2": 0.0})
    state = physics.EulerianAngleMotion.from_params(params).at(np.array([0.0, 1.0]))
    assert physics.rates_from_angular_velocity(state, 0) is None
    # ω is still finite and well defined: (φ̇ + ψ̇) K.
    assert state.kinematics.omega_world_rad_s[0] == pytest.approx([0.0, 0.0, 0.8 + 4.0], abs=1e-12)
    note = physics.singularity_note(0.0)
    assert "θ = 0.0°" in note and "φ ± ψ" in note and "line of nodes is undefined" in note
    assert "sin θ" in physics.singularity_note(math.radians(2.0))
    away = physics.EulerianAngleMotion.from_params(physics.PARAMETERS.defaults()).at(np.array([0.0]))
    assert physics.rates_from_angular_velocity(away, 0) == pytest.approx([0.8, 0.15, 4.0], abs=1e-12)


def test_omega_passes_smoothly_through_theta_zero():
    """θ from 20° down through 0 at t = 0.873 s: ω still matches Ṙ Rᵀ there, although the angles are singular."""
    params = physics.PARAMETERS.validate({"nutation_deg": 20.0, "nutation_rate_rad_s": -0.4, "nutation_acceleration_rad_s2": 0.0})
    t0 = math.radians(20.0) / 0.4
    omega = physics.EulerianAngleMotion.from_params(params).at(np.array([t0])).kinematics.omega_world_rad_s[0]
    assert np.linalg.norm(omega - omega_from_matrix(params, t0)) <= RELATIVE_TOL * (np.linalg.norm(omega) + 1.0)


def test_simulate_report_names_every_series_and_is_finite():
    model = physics.EulerianAngleKinematics()
    report = model.simulate(physics.PARAMETERS.defaults(), {}, t_end_s=8.0, frame_rate_hz=30.0).as_dict()
    assert report["stats"]["status"] == "ok"
    assert set(report["series"]) == set(model.series_units)
    assert all(np.all(np.isfinite(v)) for v in report["series"].values())
