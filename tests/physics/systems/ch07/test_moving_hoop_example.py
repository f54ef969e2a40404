"""The bead on the moving hoop (worked example ``moving-hoop-virtual-displacement``, section 7.3) against sympy: the
position ``r(φ, t) = (A sin Ωt + R cos φ, R sin φ)`` differentiated symbolically (∂r/∂φ at frozen t; ṙ and r̈ along
φ = ωt), the pushes from Newton's law, and the kinetic energy's rate as d/dt of ½ m |ṙ|², then evaluated at the
inputs with 30 digits.

Tolerance 1e-12 relative to each quantity's scale (R for displacements per radian, |A Ω| + |R ω| for speeds, m times
the largest acceleration term for forces, force × speed for powers): the example's arithmetic is a few products and
sums of O(1) numbers, exact to a few ulps of those scales. The angle between ṙ and δr comes from an arccosine,
which loses half the digits where the two are nearly parallel (acos(1 − ε) ≈ √(2ε)): 1e-7 rad.

No input in range is physically impossible here (any hoop, any drive, any instant), so nothing is refused.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy

from app.physics.systems.ch07.moving_hoop_example import EXAMPLE

CASES = [
    {},
    {"time_s": 0.0},
    {"hoop_radius_m": 2.0, "hoop_amplitude_m": 1.5, "hoop_rate_rad_s": 4.0, "bead_rate_rad_s": -2.5, "time_s": 3.7},
    {"hoop_amplitude_m": 0.0, "time_s": 1.3},  # the hoop at rest: a scleronomic constraint
    {"hoop_radius_m": 0.3, "hoop_rate_rad_s": 0.2, "bead_rate_rad_s": 3.0, "time_s": 17.0, "bead_mass_kg": 5.0},
]

_phi, _t, _R, _A, _W, _w, _m = sympy.symbols("phi t R A Omega omega m", real=True)
_r = sympy.Matrix([_A * sympy.sin(_W * _t) + _R * sympy.cos(_phi), _R * sympy.sin(_phi)])
_on_path = {_phi: _w * _t}
_virtual = _r.diff(_phi)
_velocity = (_r.diff(_phi) * _w + _r.diff(_t)).subs(_on_path)
_r_path = _r.subs(_on_path)
_acceleration = _r_path.diff(_t, 2)
_radial = sympy.Matrix([sympy.cos(_w * _t), sympy.sin(_w * _t)])
_tangent = sympy.Matrix([-sympy.sin(_w * _t), sympy.cos(_w * _t)])
_normal = _m * (_acceleration.T * _radial)[0]
_along = _m * (_acceleration.T * _tangent)[0]
_kinetic_rate = sympy.diff(sympy.Rational(1, 2) * _m * (_r_path.diff(_t).T * _r_path.diff(_t))[0], _t)


def _reference(values):
    subs = {
        _R: values["hoop_radius_m"],
        _A: values["hoop_amplitude_m"],
        _W: values["hoop_rate_rad_s"],
        _w: values["bead_rate_rad_s"],
        _m: values["bead_mass_kg"],
        _t: values["time_s"],
    }

    def number(expr):
        return float(sympy.N(expr.subs(subs), 30))

    return {
        "virtual": np.array([number(e) for e in _virtual.subs(_on_path)]),
        "velocity": np.array([number(e) for e in _velocity]),
        "normal": number(_normal),
        "along": number(_along),
        "normal_power": number(_normal * (_velocity.T * _radial)[0]),
        "kinetic_rate": number(_kinetic_rate),
    }


@pytest.mark.parametrize("changes", CASES)
def test_displacements_pushes_and_powers_match_sympy(changes):
    values = EXAMPLE.inputs.validate(changes)
    R, A, W, w, m = (
        values[n] for n in ("hoop_radius_m", "hoop_amplitude_m", "hoop_rate_rad_s", "bead_rate_rad_s", "bead_mass_kg")
    )
    speed = abs(A * W) + abs(R * w)
    force = m * (A * W * W + R * w * w)
    ref = _reference(values)
    out = EXAMPLE.solve(values).outputs
    assert np.allclose(out["virtual_displacement_m_per_rad"], ref["virtual"], rtol=0, atol=1e-12 * R)
    assert np.allclose(out["velocity_m_s"], ref["velocity"], rtol=0, atol=1e-12 * speed)
    assert out["normal_force_N"] == pytest.approx(ref["normal"], abs=1e-12 * force)
    assert out["tangential_force_N"] == pytest.approx(ref["along"], abs=1e-12 * force)
    assert out["normal_power_W"] == pytest.approx(ref["normal_power"], abs=1e-12 * force * speed)
    assert out["kinetic_energy_rate_W"] == pytest.approx(ref["kinetic_rate"], abs=1e-12 * force * speed)
    speed_now = np.linalg.norm(ref["velocity"])
    if speed_now > 0:
        cosine = float(ref["velocity"] @ ref["virtual"]) / (speed_now * R)
        assert out["angle_rad"] == pytest.approx(math.acos(max(-1.0, min(1.0, cosine))), abs=1e-7)


def test_the_check_step_holds_and_a_hoop_at_rest_does_no_work():
    check = EXAMPLE.solve(EXAMPLE.inputs.defaults()).steps[-1]
    assert check.title.startswith("Check")
    v = check.values
    assert v["grad_g_dot_dr"] == 0.0 and v["dg/dt_total"] == 0.0
    assert v["grad_g_dot_rdot"] == pytest.approx(-v["dg/dt_partial"], rel=1e-12)
    assert v["power"] == pytest.approx(v["dT/dt"], rel=1e-12)
    at_rest = EXAMPLE.solve(EXAMPLE.inputs.validate({"hoop_amplitude_m": 0.0})).outputs
    assert at_rest["normal_power_W"] == 0.0 and at_rest["angle_rad"] == pytest.approx(0.0, abs=1e-7)
