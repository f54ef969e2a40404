"""The slider-crank worked example against Lagrange's equation and a hand elimination, both from sympy.

Independent computation: the positions of the pins and centres of mass are written afresh in sympy as functions of
the crank angle θ, and differentiated exactly. Lagrange's equation for the one coordinate θ,
``M(θ) α + ½ M′(θ) ω² + V′(θ) = τ``, gives τ (speed drive, α = 0) or α (torque drive). The forces then follow by
eliminating in another order than the example's 8×8 solve: the slider's x equation gives B_x, the rod's moments
about the crank pin A give B_y, the rod's force sum gives A, the crank's gives O, the slider's y equation gives N.
Both sides are exact formulas evaluated in floating point, so they agree to round-off: 1e-10 of the force scale
m_total (g + r ω² (1 + r/l)) + |τ|/r (and that times r for τ) leaves ample room for the ~100 operations and the
8×8 solve's conditioning (its entries span lengths of 0.1–1 m and unit coefficients).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch06.mechanism_kinetics_example import EXAMPLE

RTOL = 1e-10

_th = sp.symbols("theta")
_r, _l, _e = sp.symbols("r l e", positive=True)
_phi = sp.asin((_e - _r * sp.sin(_th)) / _l)
_A = sp.Matrix([_r * sp.cos(_th), _r * sp.sin(_th)])
_B = sp.Matrix([_r * sp.cos(_th) + _l * sp.cos(_phi), _e])
_G1 = _A / 2
_G2 = _A + _l / 2 * sp.Matrix([sp.cos(_phi), sp.sin(_phi)])
_NAMES = {"phi": sp.Matrix([_phi]), "A": _A, "B": _B, "G1": _G1, "G2": _G2}
#: name -> (value, first derivative, second derivative) in θ, as numeric functions of (θ, r, l, e)
GEOMETRY = {
    name: tuple(sp.lambdify((_th, _r, _l, _e), sp.diff(expr, _th, k) if k else expr, "numpy") for k in range(3))
    for name, expr in _NAMES.items()
}


def kinematics(name, theta, omega, alpha, r, l, e):
    f, f1, f2 = (np.array(g(theta, r, l, e), dtype=float).ravel() for g in GEOMETRY[name])
    return f, f1 * omega, f2 * omega**2 + f1 * alpha, f1, f2


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def by_lagrange_and_elimination(p):
    r, l, e = p["crank_m"], p["rod_m"], p["offset_m"]
    m1, m2, m3, g = p["crank_mass_kg"], p["rod_mass_kg"], p["slider_mass_kg"], p["g_m_s2"]
    theta, omega = math.radians(p["crank_angle0_deg"]), p["crank_speed_rad_s"]
    i_o, i_g2 = m1 * r * r / 3.0, m2 * l * l / 12.0
    _, _, _, phi1, phi2 = kinematics("phi", theta, 1.0, 0.0, r, l, e)
    _, _, _, g2_1, g2_2 = kinematics("G2", theta, 1.0, 0.0, r, l, e)
    _, _, _, g1_1, _ = kinematics("G1", theta, 1.0, 0.0, r, l, e)
    _, _, _, b1, b2 = kinematics("B", theta, 1.0, 0.0, r, l, e)
    inertia = i_o + m2 * g2_1 @ g2_1 + i_g2 * phi1[0] ** 2 + m3 * b1[0] ** 2
    half_slope = m2 * g2_1 @ g2_2 + i_g2 * phi1[0] * phi2[0] + m3 * b1[0] * b2[0]
    potential_slope = g * (m1 * g1_1[1] + m2 * g2_1[1])
    if p["drive"] == "torque":
        tau = p["drive_torque_N_m"]
        alpha = (tau - half_slope * omega**2 - potential_slope) / inertia
    else:
        alpha = 0.0
        tau = half_slope * omega**2 + potential_slope
    weight = np.array([0.0, -g])
    _, _, phi_dd, _, _ = kinematics("phi", theta, omega, alpha, r, l, e)
    r_a, _, _, _, _ = kinematics("A", theta, omega, alpha, r, l, e)
    r_b, _, a_b, _, _ = kinematics("B", theta, omega, alpha, r, l, e)
    _, _, a_g1, _, _ = kinematics("G1", theta, omega, alpha, r, l, e)
    r_g2, _, a_g2, _, _ = kinematics("G2", theta, omega, alpha, r, l, e)
    b_x = m3 * a_b[0]
    # Rod about A: (r_B − r_A) × (−B) + (r_G2 − r_A) × m2 g = I_G2 φ̈ + (r_G2 − r_A) × m2 a_G2, linear in B_y.
    d, c = r_b - r_a, r_g2 - r_a
    b_y = (cross(c, m2 * weight) - i_g2 * phi_dd[0] - cross(c, m2 * a_g2) + d[1] * b_x) / d[0]
    b = np.array([b_x, b_y])
    a = b + m2 * (a_g2 - weight)
    o = a + m1 * (a_g1 - weight)
    n = m3 * g - b_y
    return {
        "driving_torque_N_m": tau,
        "crank_acceleration_rad_s2": alpha,
        "pivot_O_N": o,
        "crank_pin_A_N": a,
        "wrist_pin_B_N": b,
        "guide_force_N": n,
    }, inertia


CASES = [
    {},
    {"crank_angle0_deg": 60.0},
    {"drive": "torque", "crank_angle0_deg": 100.0},
    {"offset_m": 0.2, "rod_m": 0.8, "crank_angle0_deg": -135.0, "crank_speed_rad_s": -15.0},
    {"slider_mass_kg": 50.0, "g_m_s2": 0.0, "crank_angle0_deg": 170.0},
    {
        "drive": "torque",
        "drive_torque_N_m": -40.0,
        "crank_m": 0.5,
        "rod_m": 1.4,
        "offset_m": -0.3,
        "crank_speed_rad_s": 3.0,
    },
]


@pytest.mark.parametrize("changes", CASES)
def test_the_example_matches_lagrange_and_a_hand_elimination(changes):
    p = EXAMPLE.inputs.validate(changes)
    solution = EXAMPLE.solve(p)
    expected, inertia = by_lagrange_and_elimination(p)
    masses = p["crank_mass_kg"] + p["rod_mass_kg"] + p["slider_mass_kg"]
    r, l, omega = p["crank_m"], p["rod_m"], p["crank_speed_rad_s"]
    force_scale = masses * (p["g_m_s2"] + r * omega**2 * (1 + r / l)) + abs(expected["driving_torque_N_m"]) / r
    for name, value in expected.items():
        tolerance = RTOL * {
            "driving_torque_N_m": force_scale * r,
            "crank_acceleration_rad_s2": force_scale * r / inertia,
        }.get(name, force_scale)
        np.testing.assert_allclose(solution.outputs[name], value, rtol=0, atol=tolerance, err_msg=name)
    check = solution.steps[-1]
    assert check.title.startswith("Check")
    # The check's torque comes from fourth-order differences (step 1e-3 rad): about 1e-12 of the scale, 1e-9 allowed.
    assert check.values["tau_energy"] == pytest.approx(check.values["tau_Newton_Euler"], abs=1e-9 * force_scale * r)


def test_a_rod_too_short_to_follow_the_crank_is_refused():
    with pytest.raises(ParameterError, match="connecting rod"):  # a 422 from the API, naming rod_m
        EXAMPLE.inputs.validate({"crank_m": 0.3, "rod_m": 0.35, "offset_m": 0.1})
    with pytest.raises(ValueError, match="connecting rod"):
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), "crank_m": 0.5, "rod_m": 0.5})
