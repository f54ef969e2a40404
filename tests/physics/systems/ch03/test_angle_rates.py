"""ω and α from angle rates (app/physics/systems/ch03/angle_rates.py), checked against the rotation matrix itself.

The reference differentiates [R(t)] built from the moving angles: ω̃ = Ṙ Rᵀ (world) and Rᵀ Ṙ (body),
with Ṙ from a fourth-order central difference; α is the central difference of that ω, where Ṙ comes
from a complex step (exact to rounding, so the outer difference alone sets the error). Neither uses
the turn-axis formulas being tested. All twelve sequences, random angles, rates and accelerations.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.math.rotations import SEQUENCES, matrix_from_angles
from app.physics.systems.ch03 import angle_rates as physics

H_S = 1e-3
COMPLEX_STEP_S = 1e-20
#: Fourth-order differences with h = 1e-3 s: truncation h⁴|R⁽⁵⁾|/30 ≲ 1e-12·(23 rad/s)⁵/30 ≈ 2e-7 at the very
#: fastest rates reached (3 rad/s + 2 rad/s² × 10 s), far less at typical ones; round-off ≈ 1.5 ε / h ≈ 3e-13.
#: Relative to |ω| (or |α|) plus 1 rad/s (rad/s²), 1e-6 is the brief's target and holds with room.
RELATIVE_TOL = 1e-6


def vee(W: np.ndarray) -> np.ndarray:
    return np.array([W[2, 1], W[0, 2], W[1, 0]])


def attitude(motion: physics.AngleMotion, t) -> np.ndarray:
    return matrix_from_angles(motion.angles(np.array([t]))[0], motion.sequence)


def matrix_rate(motion, t: float, h: float = H_S) -> np.ndarray:
    R = lambda s: attitude(motion, s)  # noqa: E731
    return (-R(t + 2 * h) + 8 * R(t + h) - 8 * R(t - h) + R(t - 2 * h)) / (12 * h)


def omega_complex_step(motion, t: float) -> np.ndarray:
    R_dot = attitude(motion, t + 1j * COMPLEX_STEP_S).imag / COMPLEX_STEP_S
    return vee(R_dot @ attitude(motion, t).T)


def random_motion(rng, sequence: str) -> tuple[dict, physics.AngleMotion]:
    raw = {p.name: float(rng.uniform(p.min, p.max)) for p in physics.PARAMETERS.parameters if p.kind == "float"}
    params = physics.PARAMETERS.validate({**raw, "sequence": sequence})
    return params, physics.AngleMotion.from_params(params)


@pytest.mark.parametrize("sequence", list(SEQUENCES))
def test_omega_and_alpha_match_the_rotation_matrix(sequence):
    rng = np.random.default_rng(int(sequence.replace("-", "")))
    for _ in range(25):
        _, motion = random_motion(rng, sequence)
        t = float(rng.uniform(0.0, 10.0))
        k = motion.kinematics(np.array([t]))
        R, R_dot = attitude(motion, t), matrix_rate(motion, t)
        omega_world, omega_body = vee(R_dot @ R.T), vee(R.T @ R_dot)
        scale = np.linalg.norm(omega_world) + 1.0
        assert np.abs(k.omega_world_rad_s[0] - omega_world).max() <= RELATIVE_TOL * scale
        assert np.abs(k.omega_body_rad_s[0] - omega_body).max() <= RELATIVE_TOL * scale
        h = H_S
        alpha = (-omega_complex_step(motion, t + 2 * h) + 8 * omega_complex_step(motion, t + h)
                 - 8 * omega_complex_step(motion, t - h) + omega_complex_step(motion, t - 2 * h)) / (12 * h)  # fmt: skip
        assert np.abs(k.alpha_world_rad_s2[0] - alpha).max() <= RELATIVE_TOL * (np.linalg.norm(alpha) + 1.0)
        assert np.abs(k.alpha_body_rad_s2[0] - R.T @ alpha).max() <= RELATIVE_TOL * (np.linalg.norm(alpha) + 1.0)
        # The two parts of α add up to it.
        assert np.abs(k.alpha_along_axes_world_rad_s2[0] + k.alpha_turning_axes_world_rad_s2[0] - k.alpha_world_rad_s2[0]).max() < 1e-12
        # Away from lock the rates come back from ω exactly (to rounding amplified by 1/σ_min of J).
        if k.lock_distance_rad[0] > 0.05:
            recovered, why = k.recovered_rates(0)
            assert why == "" and np.abs(recovered - k.rates_rad_s[0]).max() < 1e-12 * k.rate_gain(0) * scale


def test_steady_precession_and_spin_still_have_an_angular_acceleration():
    # 3-1-3 with φ̇ = 0.8, ψ̇ = 2 rad/s at θ = 30°: α = φ̇ψ̇ Z × k, horizontal, |α| = φ̇ψ̇ sin θ = 0.8 rad/s².
    params = physics.PARAMETERS.validate({"sequence": "3-1-3", "angle2_deg": 30.0, "rate1_rad_s": 0.8, "rate2_rad_s": 0.0, "rate3_rad_s": 2.0})
    k = physics.AngleMotion.from_params(params).kinematics(np.linspace(0.0, 8.0, 9))
    assert np.abs(np.linalg.norm(k.alpha_world_rad_s2, axis=-1) - 0.8 * 2.0 * math.sin(math.radians(30.0))).max() < 1e-15 * 10
    assert np.abs(k.alpha_world_rad_s2[:, 2]).max() < 1e-15 * 10
    assert np.all(k.alpha_along_axes_world_rad_s2 == 0.0)
    # |ω|² = φ̇² + ψ̇² + 2 φ̇ψ̇ cos θ (the two rates along axes 30° apart).
    expected = math.sqrt(0.8**2 + 2.0**2 + 2 * 0.8 * 2.0 * math.cos(math.radians(30.0)))
    assert np.abs(np.linalg.norm(k.omega_world_rad_s, axis=-1) - expected).max() < 1e-14


@pytest.mark.parametrize("sequence, theta2_deg, combination", [("3-1-3", 0.0, "θ̇1 + θ̇3"), ("3-1-3", 180.0, "θ̇1 − θ̇3"), ("3-2-1", 90.0, "θ̇1 − θ̇3")])
def test_at_gimbal_lock_the_rates_cannot_be_recovered(sequence, theta2_deg, combination):
    params = physics.PARAMETERS.validate({"sequence": sequence, "angle2_deg": theta2_deg, "rate2_rad_s": 0.0, "accel2_rad_s2": 0.0, "rate1_rad_s": 0.5, "rate3_rad_s": 1.0})
    k = physics.AngleMotion.from_params(params).kinematics(np.array([0.0, 3.0]))
    for i in (0, 1):
        assert k.locked(i) and math.isinf(k.rate_gain(i))
        recovered, why = k.recovered_rates(i)
        assert recovered is None and "the rates cannot be recovered here" in why and combination in why
    # ω itself is still right there: compare with the matrix.
    motion = physics.AngleMotion.from_params(params)
    R = attitude(motion, 3.0)
    assert np.abs(k.omega_world_rad_s[1] - vee(matrix_rate(motion, 3.0) @ R.T)).max() < RELATIVE_TOL * 2.0
    report = physics.AngleRates().simulate(params, {}, t_end_s=1.0, frame_rate_hz=10.0).as_dict()
    assert report["stats"]["status"] == "ok"
    assert [(e["t_s"], e["kind"]) for e in report["events"]] == [(0.0, "gimbal_lock")]


def test_simulate_report_names_every_series():
    report = physics.AngleRates().simulate(physics.PARAMETERS.defaults(), {}, t_end_s=2.0, frame_rate_hz=30.0).as_dict()
    assert set(report["series"]) == set(physics.AngleRates.series_units) and report["events"] == []
    assert all(np.all(np.isfinite(v)) for v in report["series"].values())
