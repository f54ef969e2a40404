"""Worked example ``disk-on-turntable-point`` against an independent computation.

The test writes the disk's attitude as a function of time, R(t) = Rz(φ(t)) Ry(−β) Rx(ψ(t)) with φ = ω₁t + ½ω̇₁t² and ψ =
ω₂t + ½ω̇₂t² (body x along the shaft), and B's position r_B = L R x̂ + R (0, ρ cos γ, ρ sin γ). sympy differentiates it
exactly: v_B, a_B and v_A, a_A are time derivatives of positions, ω comes from [ω̃] = Ṙ Rᵀ and α is dω/dt. No rigid-body
formula enters. The module's own tests differentiate the same positions numerically; this one is exact.

Tolerance: each output is an exact expression evaluated once in floating point (a few dozen operations on O(1) numbers),
so it is good to ~1e-15 of its scale; 1e-12 of the scale (|ω|, |α| + |ω|², and those times L + R) leaves a 1000× margin.
Every in-range input is a possible motion (β stays within ±75°), so the refusal tested is an out-of-range value.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch04.rigid_body_points_example import EXAMPLE

CASES = [
    {},
    {"turntable_rate_rad_s": 0.0, "turntable_acceleration_rad_s2": 0.0, "spin_acceleration_rad_s2": 0.0},
    {"shaft_elevation_deg": -60.0, "point_angle_deg": -135.0, "point_radius_fraction": 0.4, "spin_rate_rad_s": -15.0},
    {"turntable_rate_rad_s": -4.0, "turntable_acceleration_rad_s2": 1.7, "shaft_length_m": 2.0, "disk_radius_m": 1.0},
    {"shaft_elevation_deg": 0.0, "point_radius_fraction": 0.0, "spin_acceleration_rad_s2": 4.0},
]

t = sp.Symbol("t", real=True)


def rot(axis, angle):
    c, s = sp.cos(angle), sp.sin(angle)
    if axis == "x":
        return sp.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])
    if axis == "y":
        return sp.Matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    return sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def independent(p):
    phi = p["turntable_rate_rad_s"] * t + p["turntable_acceleration_rad_s2"] * t**2 / 2
    psi = p["spin_rate_rad_s"] * t + p["spin_acceleration_rad_s2"] * t**2 / 2
    R = rot("z", phi) * rot("y", -math.radians(p["shaft_elevation_deg"])) * rot("x", psi)
    rho, gamma = p["point_radius_fraction"] * p["disk_radius_m"], math.radians(p["point_angle_deg"])
    centre = p["shaft_length_m"] * R[:, 0]
    point = centre + R * sp.Matrix([0, rho * math.cos(gamma), rho * math.sin(gamma)])
    skew = R.diff(t) * R.T
    omega = sp.Matrix([skew[2, 1], skew[0, 2], skew[1, 0]])

    def num(expr):
        return np.array(sp.N(expr.subs(t, 0), 30), dtype=float).ravel()

    return {
        "angular_velocity_rad_s": num(omega),
        "angular_acceleration_rad_s2": num(omega.diff(t)),
        "center_velocity_m_s": num(centre.diff(t)),
        "center_acceleration_m_s2": num(centre.diff(t, 2)),
        "point_velocity_m_s": num(point.diff(t)),
        "point_acceleration_m_s2": num(point.diff(t, 2)),
    }


@pytest.mark.parametrize("changes", CASES)
def test_outputs_match_exact_derivatives_of_the_attitude(changes):
    inputs = EXAMPLE.inputs.validate(changes)
    out = EXAMPLE.solve(inputs).outputs
    ref = independent(inputs)
    w = abs(inputs["turntable_rate_rad_s"]) + abs(inputs["spin_rate_rad_s"])
    acc = abs(inputs["turntable_acceleration_rad_s2"]) + abs(inputs["spin_acceleration_rad_s2"]) + w * w
    size = inputs["shaft_length_m"] + inputs["disk_radius_m"]
    scales = {
        "angular_velocity_rad_s": w,
        "angular_acceleration_rad_s2": acc,
        "center_velocity_m_s": w * size,
        "center_acceleration_m_s2": acc * size,
        "point_velocity_m_s": w * size,
        "point_acceleration_m_s2": acc * size,
    }
    for name, scale in scales.items():
        assert np.allclose(out[name], ref[name], rtol=0, atol=1e-12 * scale), name


def test_check_step_second_method_agrees_at_the_defaults():
    check = EXAMPLE.solve(EXAMPLE.inputs.defaults()).steps[-1]
    assert check.title.startswith("Check")
    assert np.allclose(check.values["v_B (moving frame)"], check.values["v_B (general equation)"], rtol=0, atol=1e-14)
    assert np.allclose(check.values["a_B (moving frame)"], check.values["a_B (general equation)"], rtol=0, atol=1e-13)
    assert check.values["(v_B - v_A)·r_B/A"] == 0.0


def test_an_out_of_range_input_is_refused_naming_it():
    with pytest.raises(ParameterError) as refused:
        EXAMPLE.inputs.validate({"shaft_elevation_deg": 80.0})
    assert refused.value.field == "shaft_elevation_deg"
