"""The disk on the turntable (app/physics/systems/ch04/rigid_body_points.py): v_B and a_B against finite differences.

The reference builds B's position from scratch in this file, r_B(t) = L n̂ + Rz(φ) Ry(−β) Rx(ψ) r_B/A (body), with
φ and ψ quadratic in t, and differentiates it with eighth-order central differences; it uses none of the code under
test. Step h = 1e-3 s: truncation ≈ h⁸ |r⁽⁹⁾| / 630 ≲ 1e-24 · (55 rad/s)⁹ · 1 m / 630 ≈ 7e-10 m/s² even at the
fastest rates reachable in a cycle (ω₂ = 20 + 5 × 6 rad/s plus ω₁), round-off ≈ 10 ε · 1 m / h² ≈ 2e-9 m/s².
Errors are taken relative to the sum of the terms' magnitudes (|v_A| + |ω × r_B/A|, or the three acceleration
terms), since v_B itself may be nearly zero by cancellation: 1e-6 is the brief's target and holds with room.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch04 import rigid_body_points as physics

H_S = 1e-3
FIRST = np.array([1 / 280, -4 / 105, 1 / 5, -4 / 5, 0.0, 4 / 5, -1 / 5, 4 / 105, -1 / 280])
SECOND = np.array([-1 / 560, 8 / 315, -1 / 5, 8 / 5, -205 / 72, 8 / 5, -1 / 5, 8 / 315, -1 / 560])
RELATIVE_TOL = 1e-6


def Rz(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def Ry(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def Rx(a: float) -> np.ndarray:
    c, s = math.cos(a), math.sin(a)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def position_of_B(p: dict, t: float) -> np.ndarray:
    """B's world position (m) written out from the description, independent of the module."""
    phi = p["turntable_rate_rad_s"] * t + 0.5 * p["turntable_acceleration_rad_s2"] * t * t
    psi = p["spin_rate_rad_s"] * t + 0.5 * p["spin_acceleration_rad_s2"] * t * t
    beta, gamma = math.radians(p["shaft_elevation_deg"]), math.radians(p["point_angle_deg"])
    rho = p["point_radius_fraction"] * p["disk_radius_m"]
    R = Rz(phi) @ Ry(-beta) @ Rx(psi)
    return p["shaft_length_m"] * R[:, 0] + R @ np.array([0.0, rho * math.cos(gamma), rho * math.sin(gamma)])


def differences(p: dict, t: float) -> tuple[np.ndarray, np.ndarray]:
    samples = np.array([position_of_B(p, t + k * H_S) for k in range(-4, 5)])
    return FIRST @ samples / H_S, SECOND @ samples / H_S**2


def random_params(rng) -> dict:
    raw = {p.name: float(rng.uniform(p.min, p.max)) for p in physics.PARAMETERS.parameters}
    return physics.PARAMETERS.validate(raw)


@pytest.mark.parametrize("seed", range(8))
def test_v_B_and_a_B_match_finite_differences_of_the_position(seed):
    rng = np.random.default_rng(seed)
    params = random_params(rng) if seed else physics.PARAMETERS.defaults()
    system = physics.DiskOnTurntable.from_params(params)
    times = np.array([0.0, *rng.uniform(0.0, 6.0, 3)])
    state = system.at(times)
    for i, t in enumerate(times):
        v_fd, a_fd = differences(params, float(t))
        assert np.allclose(state.point[i], position_of_B(params, float(t)), rtol=0.0, atol=1e-12)
        v_scale = np.linalg.norm(state.center_velocity[i]) + np.linalg.norm(state.relative_velocity[i]) + 1e-3
        a_scale = sum(np.linalg.norm(getattr(state, name)[i]) for name in ("center_acceleration", "tangential_acceleration", "centripetal_acceleration")) + 1e-3
        assert np.linalg.norm(state.point_velocity[i] - v_fd) <= RELATIVE_TOL * v_scale, (seed, t)
        assert np.linalg.norm(state.point_acceleration[i] - a_fd) <= RELATIVE_TOL * a_scale, (seed, t)
        # The terms add up to the resultants drawn at B.
        assert np.allclose(state.center_velocity[i] + state.relative_velocity[i], state.point_velocity[i], rtol=0.0, atol=1e-12)
        terms = state.center_acceleration[i] + state.tangential_acceleration[i] + state.centripetal_acceleration[i]
        assert np.allclose(terms, state.point_acceleration[i], rtol=0.0, atol=1e-12)


def test_the_defaults_at_t_0_are_the_lessons_numbers():
    """The worked numbers of lesson 4.1, written out by hand: ω = ω₁K + ω₂n̂, α = ω̇₁K + ω̇₂n̂ + ω₁ω₂ K × n̂."""
    state = physics.DiskOnTurntable.from_params(physics.PARAMETERS.defaults()).at(np.array([0.0]))
    c, s = math.cos(math.radians(30.0)), 0.5
    n = np.array([c, 0.0, s])
    assert state.angular_velocity[0] == pytest.approx(1.2 * np.array([0, 0, 1.0]) + 4.0 * n, abs=1e-12)
    assert state.angular_acceleration[0] == pytest.approx([-0.5 * c, 1.2 * 4.0 * c, 0.3 - 0.5 * s], abs=1e-12)
    assert state.center_velocity[0] == pytest.approx([0.0, 1.2 * 0.8 * c, 0.0], abs=1e-12)
    assert state.center_acceleration[0] == pytest.approx([-1.2**2 * 0.8 * c, 0.3 * 0.8 * c, 0.0], abs=1e-12)
    assert np.round(state.point_velocity[0], 3) + 0.0 == pytest.approx([0.0, -0.549, 0.0])
    assert np.round(state.point_acceleration[0], 3) == pytest.approx([4.498, 0.313, -4.157])


def test_two_points_of_the_body_never_approach_along_their_join():
    """(v_B − v_A) · r_B/A = 0 for a rigid body: to round-off, at every point and instant."""
    rng = np.random.default_rng(11)
    for _ in range(5):
        state = physics.DiskOnTurntable.from_params(random_params(rng)).at(np.linspace(0.0, 6.0, 7))
        along = np.einsum("ni,ni->n", state.point_velocity - state.center_velocity, state.point_from_center)
        assert np.abs(along).max() <= 1e-12


def test_bad_inputs_name_the_field():
    with pytest.raises(ParameterError, match="^ρ/R: ") as refused:  # named as its control shows it
        physics.PARAMETERS.validate({"point_radius_fraction": 1.5})
    assert refused.value.field == "point_radius_fraction"
    with pytest.raises(ValueError, match="β"):
        physics.DiskOnTurntable(1.0, 0.0, 1.0, 0.0, math.radians(90.0), 0.8, 0.3, 0.0, 1.0)


def test_simulate_report_names_every_series_and_is_finite():
    report = physics.DiskOnTurntableMotion().simulate(physics.PARAMETERS.defaults(), {}, t_end_s=6.0, frame_rate_hz=30.0).as_dict()
    assert report["stats"]["status"] == "ok"
    assert set(report["series"]) == set(physics.DiskOnTurntableMotion.series_units)
    assert all(np.all(np.isfinite(v)) for v in report["series"].values())
