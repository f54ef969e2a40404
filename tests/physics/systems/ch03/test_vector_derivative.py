"""(dA/dt)_fixed = (dA/dt)_rel + ω × A (app/physics/systems/ch03/vector_derivative.py), checked by differentiating A.

The reference never uses the formula: A's world components are composed from the frame's attitude
(built here from a quaternion, not the module's matrices) and A's components on the frame, and then
differentiated numerically with a fourth-order central difference.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.core.parameters import ParameterError
from app.physics.math.rotations import quaternion_from_axis_angle, rotation_matrix
from app.physics.systems.ch03 import vector_derivative as physics

H_S = 1e-3
#: Fourth-order central difference with h = 1e-3 s: truncation h⁴|A⁽⁵⁾|/30 ≤ 1e-12·(13 rad/s)⁵·3 m/30 ≈ 4e-8 m/s
#: at the fastest controls, round-off ≈ 1.5 ε |A| / h ≈ 1e-12 m/s; 1e-6 of the rates' size leaves ample room.
RELATIVE_TOL = 1e-6


def composed_vector(params, t: float) -> np.ndarray:
    """A in XYZ from first principles: the frame turned by Ω t about n (a quaternion), times A's frame components."""
    tilt = math.radians(params["frame_axis_tilt_deg"])
    q = quaternion_from_axis_angle(np.array([math.sin(tilt), 0.0, math.cos(tilt)]), params["frame_rate_rad_s"] * t)
    length = params["length_m"] + params["stretch_amplitude_m"] * math.sin(2 * math.pi * params["stretch_frequency_hz"] * t)
    e, psi = math.radians(params["elevation_deg"]), params["relative_turn_rate_rad_s"] * t
    return rotation_matrix(q) @ (length * np.array([math.cos(e) * math.cos(psi), math.cos(e) * math.sin(psi), math.sin(e)]))


def derivative(f, t: float, h: float = H_S) -> np.ndarray:
    return (-f(t + 2 * h) + 8 * f(t + h) - 8 * f(t - h) + f(t - 2 * h)) / (12 * h)


def random_params(rng) -> dict:
    raw = {p.name: float(rng.uniform(p.min, p.max)) for p in physics.PARAMETERS.parameters}
    raw["stretch_amplitude_m"] = float(rng.uniform(0.0, 0.95 * raw["length_m"]))
    return physics.PARAMETERS.validate(raw)


def test_fixed_frame_rate_is_relative_rate_plus_omega_cross_a():
    rng = np.random.default_rng(33)
    for _ in range(200):
        params = random_params(rng)
        t = float(rng.uniform(0.0, 20.0))
        rates = physics.VectorMotion.from_params(params).rates(np.array([t]))
        numeric = derivative(lambda s: composed_vector(params, s), t)
        terms = {name: value[0] for name, value in rates.terms_m_s.items()}
        size = np.linalg.norm(terms["relative"]) + np.linalg.norm(terms["transport"])
        assert np.abs(rates.vector_world_m[0] - composed_vector(params, t)).max() < 1e-12
        assert np.abs(terms["fixed"] - numeric).max() <= RELATIVE_TOL * max(size, 1e-3), params
        assert np.array_equal(terms["fixed"], terms["relative"] + terms["transport"])


def test_a_vector_fixed_in_the_frame_changes_only_by_omega_cross_a():
    params = physics.PARAMETERS.validate({"stretch_amplitude_m": 0.0, "relative_turn_rate_rad_s": 0.0, "frame_axis_tilt_deg": 20.0, "elevation_deg": 30.0})
    motion = physics.VectorMotion.from_params(params)
    t = np.linspace(0.0, 10.0, 7)
    rates = motion.rates(t)
    assert np.all(rates.terms_m_s["relative"] == 0.0)
    assert np.array_equal(rates.terms_m_s["fixed"], np.cross(motion.omega_world_rad_s, rates.vector_world_m))
    # |ω × A| = Ω L sin(angle between n and A), and that angle does not change: A rides a cone about n.
    n = motion.frame_axis_world
    sin_angle = np.linalg.norm(np.cross(n, rates.vector_world_m), axis=-1) / params["length_m"]
    expected = abs(params["frame_rate_rad_s"]) * params["length_m"] * sin_angle
    assert np.abs(np.linalg.norm(rates.terms_m_s["fixed"], axis=-1) - expected).max() < 1e-15 * 100
    assert np.ptp(sin_angle) < 1e-14
    for i in range(len(t)):  # and it agrees with differentiating A
        assert np.abs(rates.terms_m_s["fixed"][i] - derivative(lambda s: composed_vector(params, s), float(t[i]))).max() < RELATIVE_TOL


def test_turning_back_as_fast_as_the_frame_holds_a_still():
    params = physics.PARAMETERS.validate({"frame_axis_tilt_deg": 0.0, "frame_rate_rad_s": 0.8, "relative_turn_rate_rad_s": -0.8, "stretch_amplitude_m": 0.0})
    rates = physics.VectorMotion.from_params(params).rates(np.linspace(0.0, 10.0, 11))
    assert np.abs(rates.terms_m_s["fixed"]).max() < 1e-15 * 10
    assert np.abs(rates.vector_world_m - rates.vector_world_m[0]).max() < 1e-14


def test_simulate_report_and_bad_input():
    report = physics.VectorDerivative().simulate(physics.PARAMETERS.defaults(), {}, t_end_s=2.0, frame_rate_hz=30.0).as_dict()
    assert report["stats"]["method"] == "closed-form" and report["stats"]["status"] == "ok"
    assert set(report["series"]) == set(physics.VectorDerivative.series_units)
    with pytest.raises(ParameterError) as info:
        physics.PARAMETERS.validate({"length_m": 0.5, "stretch_amplitude_m": 0.5})
    assert info.value.field == "stretch_amplitude_m" and "shrink through zero" in str(info.value)
