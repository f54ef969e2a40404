"""Worked example ``rolling-disk-instant`` against an independent computation.

The test describes the rim by where its material points are, with no angular velocity in it: the point at body angle
a is at ``ρ ê_r(ψ) + R d̂(ψ) + R (cos(a + σ) d̂(ψ) − sin(a + σ) ê_ψ(ψ))`` with heading ψ = v t / ρ and spin angle
σ = s t about the axle. sympy differentiates these positions exactly; the spin rate s is *solved* from the condition
that the material point touching the ground at t = 0 (a = π) has zero velocity; ω(t) is recovered from three
body-fixed unit vectors as ω = ½ Σ eᵢ × ėᵢ and α as its exact time derivative.

Tolerance: every quantity is an exact expression evaluated once in floating point, a few dozen operations on O(1)
numbers, so it is good to about 1e-15 of its scale; 1e-12 of the scale (|v|, |v|/R, |v|²/R) leaves 1000× margin.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch04.rolling_example import EXAMPLE

CASES = [
    {},
    {"tilt_deg": 0.0, "path_radius_m": 20.0},
    {"body": "cone", "tilt_deg": 35.0, "rim_radius_m": 0.3, "speed_m_s": -1.7},
    {"tilt_deg": 55.0, "path_radius_m": 0.3, "rim_radius_m": 1.2, "speed_m_s": 4.0},
    {"tilt_deg": 12.0, "path_radius_m": 5.0, "rim_radius_m": 0.05, "speed_m_s": 0.25},
]

t, a = sp.symbols("t a", real=True)


def independent(inputs):
    R, v, theta = inputs["rim_radius_m"], inputs["speed_m_s"], math.radians(inputs["tilt_deg"])
    rho = R / math.sin(theta) if inputs["body"] == "cone" else inputs["path_radius_m"]
    s = sp.Symbol("s", real=True)
    psi, sigma = v * t / rho, s * t
    e_r = sp.Matrix([sp.cos(psi), sp.sin(psi), 0])
    e_psi = sp.Matrix([-sp.sin(psi), sp.cos(psi), 0])
    up = sp.Matrix([0, 0, 1])
    d_hat = math.cos(theta) * up - math.sin(theta) * e_r
    centre = rho * e_r + R * d_hat
    rim_dir = sp.cos(a + sigma) * d_hat - sp.sin(a + sigma) * e_psi
    point = centre + R * rim_dir
    velocity = point.diff(t)
    spin = sp.solve(velocity.subs({a: sp.pi, t: 0})[1], s)[0]  # the contact point's velocity is along ê_ψ = Y
    at0 = {t: 0, s: spin}
    e1 = rim_dir.subs({a: 0, s: spin})
    e2 = rim_dir.subs({a: sp.pi / 2, s: spin})
    e3 = e1.cross(e2)
    omega = sum((e.cross(e.diff(t)) for e in (e1, e2, e3)), sp.zeros(3, 1)) / 2

    def num(expr):
        return np.array(sp.N(expr.subs(at0), 30), dtype=float).ravel()

    return {
        "spin": float(spin),
        "v_G": num(centre.diff(t).subs(s, spin)),
        "v_C": num(velocity.subs({a: sp.pi, s: spin})),
        "v_T": num(velocity.subs({a: 0, s: spin})),
        "a_C": num(point.diff(t, 2).subs({a: sp.pi, s: spin})),
        "omega": num(omega),
        "alpha": num(omega.diff(t)),
        "r_G": num(centre),
    }


@pytest.mark.parametrize("changes", CASES)
def test_outputs_match_exact_derivatives_of_the_material_points(changes):
    inputs = EXAMPLE.inputs.validate(changes)
    out = EXAMPLE.solve(inputs).outputs
    ref = independent(inputs)
    v, R = abs(inputs["speed_m_s"]), inputs["rim_radius_m"]
    tol_v, tol_w, tol_a = 1e-12 * v, 1e-12 * v / R, 1e-12 * v * v / R
    assert np.linalg.norm(ref["v_C"]) <= tol_v  # the solved spin makes the contact point rest
    assert out["spin_rate_rad_s"] == pytest.approx(ref["spin"], abs=tol_w)
    assert np.allclose(out["center_velocity_m_s"], ref["v_G"], rtol=0, atol=tol_v)
    assert np.allclose(out["top_point_velocity_m_s"], ref["v_T"], rtol=0, atol=tol_v)
    assert np.allclose(out["angular_velocity_rad_s"], ref["omega"], rtol=0, atol=tol_w)
    assert np.allclose(out["angular_acceleration_rad_s2"], ref["alpha"], rtol=0, atol=tol_w * v / R + tol_a)
    assert np.allclose(out["contact_point_acceleration_m_s2"], ref["a_C"], rtol=0, atol=tol_a)
    # O′ (from the example) is at rest in the independent velocity field v_G + ω × (r − r_G).
    o_prime = np.array([0.0, 0.0, out["axis_point_height_m"]])
    v_o = ref["v_G"] + np.cross(ref["omega"], o_prime - ref["r_G"])
    scale = v + v / R * (np.linalg.norm(o_prime) + np.linalg.norm(ref["r_G"]))
    assert np.linalg.norm(v_o) <= 1e-12 * scale


def test_a_cone_too_slender_to_have_an_apex_is_refused():
    with pytest.raises(ParameterError) as refused:
        EXAMPLE.inputs.validate({"body": "cone", "tilt_deg": 3.0})
    assert refused.value.field == "tilt_deg"
    with pytest.raises(ValueError):
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), "body": "cone", "tilt_deg": 0.0})
