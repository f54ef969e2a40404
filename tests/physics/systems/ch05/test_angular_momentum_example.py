"""Worked example ``skewed-plate-momentum`` against an independent computation.

The test integrates the definitions over the body with sympy, element by element at uniform density (a thin plate, a box
or a thin disk; :mod:`tests.physics.systems.ch05._body_integrals`): p = ∫ v dm, H_G = ∫ (r − r_G) × v dm, H_O = ∫ r × v
dm and T = ∫ ½|v|² dm, with each element's position r(t) = r_G(t) + Rz(Ωt) Rx(tilt) ρ and v = dr/dt differentiated
exactly. No inertia table, tensor, parallel-axis split or stand-in particle enters.

Tolerance: the integrals are exact rationals and π; the example's numbers are a few dozen floating-point operations on
O(1) values, good to ~1e-15 of their scale. 1e-12 of the scale (|H_G| + |r_G||p| for angular momentum, m|v_G| for p, T
itself for energy) leaves a 1000× margin. The angle between ω and H_G goes through acos, which magnifies rounding by
1/sin(angle) (≤ 12 for the angles here): 1e-9° is still ~1e5× the expected error. Every in-range input is a possible
motion, so the refusal tested is an out-of-range value.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch05.angular_momentum_example import EXAMPLE

from ._body_integrals import integrate, motion, t

CASES = [
    {},
    {"view": "particles", "body": "box"},
    {"body": "disk", "tilt_deg": 10.0, "spin_rate_rad_s": 20.0},
    {
        "view": "particles",
        "body": "box",
        "tilt_deg": -60.0,
        "spin_rate_rad_s": -7.0,
        "mass_kg": 12.5,
        "length_m": 0.3,
        "width_m": 0.9,
        "height_m": 0.45,
        "centre_velocity_m_s": [1.0, -2.0, 0.5],
        "centre_position_m": [0.4, 0.1, -1.0],
    },
    {"view": "particles", "body": "plate", "tilt_deg": 75.0, "spin_rate_rad_s": 0.0},
]


def independent(p):
    position, centre = motion(p, p["view"] == "particles")
    velocity = position.diff(t)
    at0 = {t: 0}
    pos0, vel0, g0 = position.subs(at0), velocity.subs(at0), centre.subs(at0)
    num = lambda expr: np.array(sp.N(expr, 30), dtype=float).ravel()  # noqa: E731
    return {
        "linear_momentum_kg_m_s": num(integrate(p, vel0)),
        "angular_momentum_G_kg_m2_s": num(integrate(p, (pos0 - g0).cross(vel0))),
        "angular_momentum_O_kg_m2_s": num(integrate(p, pos0.cross(vel0))),
        "kinetic_energy_J": float(sp.N(integrate(p, vel0.dot(vel0) / 2), 30)),
    }


@pytest.mark.parametrize("changes", CASES)
def test_outputs_match_the_definitions_integrated_over_the_body(changes):
    inputs = EXAMPLE.inputs.validate(changes)
    out = EXAMPLE.solve(inputs).outputs
    ref = independent(inputs)
    mass = inputs["mass_kg"]
    moving = inputs["view"] == "particles"
    v_g = np.asarray(inputs["centre_velocity_m_s"]) if moving else np.zeros(3)
    r_g = np.asarray(inputs["centre_position_m"]) if moving else np.zeros(3)
    h_scale = np.linalg.norm(ref["angular_momentum_G_kg_m2_s"]) + np.linalg.norm(r_g) * mass * np.linalg.norm(v_g)
    assert np.allclose(
        out["linear_momentum_kg_m_s"], ref["linear_momentum_kg_m_s"], rtol=0, atol=1e-12 * mass * np.linalg.norm(v_g)
    )
    for name in ("angular_momentum_G_kg_m2_s", "angular_momentum_O_kg_m2_s"):
        assert np.allclose(out[name], ref[name], rtol=0, atol=1e-12 * h_scale), name
    assert out["kinetic_energy_J"] == pytest.approx(ref["kinetic_energy_J"], rel=1e-12, abs=1e-300)
    h = ref["angular_momentum_G_kg_m2_s"]
    if inputs["spin_rate_rad_s"] == 0.0:
        assert out["angle_omega_H_deg"] is None
    else:
        angle = math.degrees(math.acos(abs(h[2]) / np.linalg.norm(h)))  # ω is along ±Z
        angle = angle if h[2] * inputs["spin_rate_rad_s"] > 0 else 180.0 - angle
        assert out["angle_omega_H_deg"] == pytest.approx(angle, abs=1e-9)


def test_check_step_particle_sums_agree_in_the_particles_view():
    check = EXAMPLE.solve(EXAMPLE.inputs.validate({"view": "particles", "body": "box"})).steps[-1]
    assert check.title.startswith("Check")
    assert np.allclose(check.values["H_O (sum)"], check.values["H_O (formula)"], rtol=0, atol=1e-14)
    assert check.values["T (sum)"] == pytest.approx(check.values["T (formula)"], rel=1e-14)


def test_an_out_of_range_input_is_refused_naming_it():
    with pytest.raises(ParameterError) as refused:
        EXAMPLE.inputs.validate({"tilt_deg": 120.0})
    assert refused.value.field == "tilt_deg"
