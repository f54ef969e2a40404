"""Worked example ``skewed-rotor-bearings`` against an independent computation.

The test integrates H_G(t) = ∫ (r − r_G) × v dm over the body with sympy, element by element at uniform density
(:mod:`tests.physics.systems.ch05._body_integrals`), with each element at r(t) = r_G(t) + Rz(Ωt) Rx(tilt) ρ, and
differentiates it exactly in time: dH_G/dt at t = 0 with no ω × H, no inertia tensor and no Euler equation. The bearing
forces are then solved from the two moment equations about G, (s/2) Z × F_B + (−s/2) Z × F_A = dH_G/dt, with F_A = −F_B
across the shaft (the force sum is zero: G does not accelerate).

Tolerance: exact integrals against a few dozen floating-point operations on O(1) numbers (~1e-15 of the scale); 1e-12 of
the scale Ω² m (a² + b² + c² + r²) (a bound on the size of every moment in play, Ω² tr(I), which stays finite even where
the moment itself is zero at a principal tilt) leaves a 1000× margin. Every in-range input is a possible motion, so the
refusal tested is an out-of-range value.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch05.bearing_moment_example import EXAMPLE

from ._body_integrals import integrate, motion, t

CASES = [
    {},
    {"body": "disk", "tilt_deg": 10.0, "spin_rate_rad_s": 20.0},
    {"body": "box", "tilt_deg": -60.0, "view": "particles", "bearing_span_m": 0.3},
    {"body": "plate", "tilt_deg": 90.0, "spin_rate_rad_s": -12.0},
    {"body": "box", "tilt_deg": 45.0, "spin_rate_rad_s": 25.0, "length_m": 1.1, "width_m": 0.2, "height_m": 0.7},
]


def independent(p):
    position, centre = motion(p, p["view"] == "particles")
    velocity = position.diff(t)
    rate_integrand = ((position - centre).cross(velocity)).diff(t).subs(t, 0)
    rate = np.array(sp.N(integrate(p, rate_integrand), 30), dtype=float).ravel()
    span = p["bearing_span_m"]
    # (s/2) Z × F_B + (−s/2) Z × (−F_B) = s Z × F_B = s (−F_By, F_Bx, 0) = dH/dt
    force_b = np.array([rate[1] / span, -rate[0] / span, 0.0])
    return rate, force_b


@pytest.mark.parametrize("changes", CASES)
def test_outputs_match_the_time_derivative_of_the_integrated_angular_momentum(changes):
    inputs = EXAMPLE.inputs.validate(changes)
    out = EXAMPLE.solve(inputs).outputs
    rate, force_b = independent(inputs)
    scale = (
        inputs["spin_rate_rad_s"] ** 2
        * inputs["mass_kg"]
        * (inputs["length_m"] ** 2 + inputs["width_m"] ** 2 + inputs["height_m"] ** 2 + inputs["radius_m"] ** 2)
    )
    assert abs(rate[2]) <= 1e-12 * scale  # no moment along the shaft: no motor torque
    assert np.allclose(out["angular_momentum_rate_N_m"], rate, rtol=0, atol=1e-12 * scale)
    assert out["bearing_moment_N_m"] == pytest.approx(np.linalg.norm(rate), abs=1e-12 * scale)
    assert np.allclose(out["bearing_force_B_N"], force_b, rtol=0, atol=1e-12 * scale / inputs["bearing_span_m"])
    assert out["bearing_force_magnitude_N"] == pytest.approx(
        np.linalg.norm(force_b), abs=1e-12 * scale / inputs["bearing_span_m"]
    )


def test_check_step_second_method_agrees_at_the_defaults():
    check = EXAMPLE.solve(EXAMPLE.inputs.defaults()).steps[-1]
    assert check.title.startswith("Check")
    for name in ("M (Euler, world)", "couple"):
        assert np.allclose(check.values[name], check.values["dH_G/dt"], rtol=0, atol=1e-15), name
    assert check.values["M_x (closed form)"] == pytest.approx(check.values["dH_G/dt"][0], rel=1e-14)


def test_an_out_of_range_input_is_refused_naming_it():
    with pytest.raises(ParameterError) as refused:
        EXAMPLE.inputs.validate({"bearing_span_m": 0.0})
    assert refused.value.field == "bearing_span_m"
