"""Worked example ``heavy-top-euler-rates`` against an independent computation.

The test writes the top's attitude as a function of time, R(t) = Rz(φ(t)) Rx(θ(t)) Rz(ψ(t)) with each angle
quadratic in t (its value, rate and constant acceleration at t = 0), and lets sympy differentiate it exactly: ω from
[ω̃] = Ṙ Rᵀ, α = dω/dt, and G's velocity and acceleration as derivatives of its position l R ẑ. The results are put
on the nutation frame with the exact Rz(φ) Rx(θ) and on the body axes with R. No Eulerian-angle rate formula enters.
The project's own model (:class:`EulerianAngleMotion`, integrating nothing but composing rotation matrices) is compared
as well.

Tolerance: exact expressions evaluated once in floating point (~1e-15 of their scale); 1e-12 of the scale (|rates|,
|rates|² + |accelerations|, times l for G) leaves a 1000× margin. Every in-range input is a possible motion (θ = 0 is a
singularity of the angles only, and the forward formulas stay finite there), so the refusal tested is an out-of-range
value.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch04.eulerian_angles import EulerianAngleMotion
from app.physics.systems.ch04.eulerian_angles_example import EXAMPLE

CASES = [
    {},
    {"nutation_rate_rad_s": 0.0, "spin_rate_rad_s": 30.0, "cg_distance_m": 0.2},
    {"nutation_deg": 0.0, "precession_deg": -150.0, "spin_deg": 77.0},
    {
        "precession_deg": 100.0,
        "nutation_deg": 160.0,
        "spin_deg": -40.0,
        "precession_rate_rad_s": -6.0,
        "nutation_rate_rad_s": 2.5,
        "spin_rate_rad_s": -12.0,
        "precession_acceleration_rad_s2": 1.5,
        "nutation_acceleration_rad_s2": -2.0,
        "spin_acceleration_rad_s2": 7.0,
        "cg_distance_m": 1.3,
    },
]

t = sp.Symbol("t", real=True)


def rot(axis, angle):
    c, s = sp.cos(angle), sp.sin(angle)
    if axis == "x":
        return sp.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])
    return sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def independent(p):
    names = ("precession", "nutation", "spin")
    phi, theta, psi = (
        sp.Rational(str(p[f"{n}_deg"])) * sp.pi / 180
        + p[f"{n}_rate_rad_s"] * t
        + p[f"{n}_acceleration_rad_s2"] * t**2 / 2
        for n in names
    )
    nutation = rot("z", phi) * rot("x", theta)
    R = nutation * rot("z", psi)
    skew = R.diff(t) * R.T
    omega = sp.Matrix([skew[2, 1], skew[0, 2], skew[1, 0]])
    centre = p["cg_distance_m"] * R[:, 2]

    def num(expr):
        return np.array(sp.N(expr.subs(t, 0), 30), dtype=float).ravel()

    to_nutation = nutation.T
    return {
        "angular_velocity_nutation_rad_s": num(to_nutation * omega),
        "angular_velocity_body_rad_s": num(R.T * omega),
        "angular_acceleration_nutation_rad_s2": num(to_nutation * omega.diff(t)),
        "centre_velocity_nutation_m_s": num(to_nutation * centre.diff(t)),
        "centre_acceleration_nutation_m_s2": num(to_nutation * centre.diff(t, 2)),
    }


@pytest.mark.parametrize("changes", CASES)
def test_outputs_match_exact_derivatives_of_the_attitude(changes):
    inputs = EXAMPLE.inputs.validate(changes)
    out = EXAMPLE.solve(inputs).outputs
    ref = independent(inputs)
    names = ("precession", "nutation", "spin")
    w = sum(abs(inputs[f"{n}_rate_rad_s"]) for n in names)
    acc = w * w + sum(abs(inputs[f"{n}_acceleration_rad_s2"]) for n in names)
    length = inputs["cg_distance_m"]
    scales = {
        "angular_velocity_nutation_rad_s": w,
        "angular_velocity_body_rad_s": w,
        "angular_acceleration_nutation_rad_s2": acc,
        "centre_velocity_nutation_m_s": w * length,
        "centre_acceleration_nutation_m_s2": acc * length,
    }
    for name, scale in scales.items():
        assert np.allclose(out[name], ref[name], rtol=0, atol=1e-12 * scale), name
    # The project's model gives the same ω and α (on the nutation frame) at t = 0.
    state = EulerianAngleMotion.from_params(inputs).at(np.zeros(1))
    assert np.allclose(out["angular_velocity_nutation_rad_s"], state.angular_velocity_nutation[0], atol=1e-12 * w)
    assert np.allclose(
        out["angular_acceleration_nutation_rad_s2"], state.angular_acceleration_nutation[0], atol=1e-12 * acc
    )


def test_check_step_second_method_agrees_at_the_defaults():
    check = EXAMPLE.solve(EXAMPLE.inputs.defaults()).steps[-1]
    assert check.title.startswith("Check")
    assert np.allclose(check.values["alpha (term by term)"], check.values["alpha (frame rates)"], rtol=0, atol=1e-14)
    assert check.values["r_G·v_G"] == 0.0


def test_an_out_of_range_input_is_refused_naming_it():
    with pytest.raises(ParameterError) as refused:
        EXAMPLE.inputs.validate({"cg_distance_m": 0.0})
    assert refused.value.field == "cg_distance_m"
