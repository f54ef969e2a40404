"""The torque-free axisymmetric example against Euler's equations integrated with the attitude, from its definition.

Independent computation: the body starts with its symmetry axis tilted θ from world Z (attitude Rx(θ)) and the angular
momentum H K, H = I_a ω₃ / cos θ (which is what ω₃ and θ mean); Euler's equations for I = diag(I_t, I_t, I_a) and
Ṙ = R [ω]× are integrated by scipy's DOP853 at rtol 1e-12 for two precession periods. The rates are read off the run:
φ̇ from the unwrapped azimuth of the symmetry axis about Z, λ from the angle of ω's transverse part in body axes, the
cone half-angles as angles between ω and k and between ω and Z, the energy as ½ ω·[I]ω. Tolerance 1e-9 relative: the
integration's error after two periods is about 1e-11 of the state, and the rates are differences of angles of order
1 rad divided by times of order 10 s, so 1e-9 leaves a hundredfold margin.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch10.free_precession_example import EXAMPLE

RTOL = 1e-9

CASES = [
    {},  # defaults: I_t = 1, I_a = 0.4 kg·m², ω₃ = 3 rad/s, θ = 25°
    {"I_transverse": 2.0, "I_axial": 0.05, "spin_rad_s": 0.5, "nutation_deg": 60.0},  # a needle
    {"I_transverse": 0.6, "I_axial": 1.0, "spin_rad_s": 4.5, "nutation_deg": 10.0},  # a lentil
    {"I_transverse": 0.5, "I_axial": 1.0, "spin_rad_s": 2.0, "nutation_deg": 70.0},  # the flat-disc limit
]


def _hat(w):
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


def _integrate(I_t, I_a, w3, theta, periods=2.0):
    H = I_a * w3 / math.cos(theta)
    inertia = np.array([I_t, I_t, I_a])
    R0 = np.array([[1.0, 0.0, 0.0], [0.0, math.cos(theta), -math.sin(theta)], [0.0, math.sin(theta), math.cos(theta)]])
    w0 = (R0.T @ np.array([0.0, 0.0, H])) / inertia

    def rhs(_t, y):
        w, R = y[:3], y[3:].reshape(3, 3)
        dw = np.cross(inertia * w, w) / inertia
        return np.concatenate([dw, (R @ _hat(w)).ravel()])

    t_end = periods * 2.0 * math.pi * I_t / H
    times = np.linspace(0.0, t_end, 801)
    run = solve_ivp(
        rhs, (0.0, t_end), np.concatenate([w0, R0.ravel()]), method="DOP853", rtol=1e-12, atol=1e-14, t_eval=times
    )
    return times, run.y[:3].T, run.y[3:].T.reshape(-1, 3, 3), inertia


def _slope(times, angles):
    return float(np.polyfit(times, np.unwrap(angles), 1)[0])


@pytest.mark.parametrize("change", CASES)
def test_rates_cones_and_energy_match_an_integration_of_eulers_equations(change):
    inputs = EXAMPLE.inputs.validate(change)
    out = EXAMPLE.solve(inputs).outputs
    theta = math.radians(inputs["nutation_deg"])
    times, w_body, R, inertia = _integrate(inputs["I_transverse"], inputs["I_axial"], inputs["spin_rad_s"], theta)
    axis = R[:, :, 2]  # the symmetry axis in world axes
    assert np.degrees(np.arccos(axis[:, 2])) == pytest.approx(np.full(len(times), inputs["nutation_deg"]), rel=RTOL)
    assert out["precession_rate_rad_s"] == pytest.approx(_slope(times, np.arctan2(axis[:, 1], axis[:, 0])), rel=RTOL)
    if inputs["I_axial"] != inputs["I_transverse"]:
        lam = _slope(times, np.arctan2(w_body[:, 1], w_body[:, 0]))
        assert out["body_frame_rate_rad_s"] == pytest.approx(lam, rel=RTOL)
        assert out["relative_spin_rate_rad_s"] == pytest.approx(-lam, rel=RTOL)
    w_world = np.einsum("nij,nj->ni", R, w_body)
    speed = np.linalg.norm(w_body[0])
    assert out["transverse_rate_rad_s"] == pytest.approx(math.hypot(*w_body[0, :2]), rel=RTOL)
    assert out["body_cone_deg"] == pytest.approx(math.degrees(math.acos(w_body[0, 2] / speed)), rel=RTOL)
    assert out["space_cone_deg"] == pytest.approx(
        math.degrees(math.atan2(math.hypot(*w_world[-1, :2]), w_world[-1, 2])), rel=RTOL, abs=1e-12
    )
    assert out["energy_J"] == pytest.approx(0.5 * float(w_body[-1] @ (inertia * w_body[-1])), rel=RTOL)
    H_world = np.einsum("nij,nj->ni", R, inertia * w_body)
    assert out["angular_momentum_kg_m2_s"] == pytest.approx(float(np.linalg.norm(H_world[-1])), rel=RTOL)
    assert out["sense"] == ("direct" if inputs["I_axial"] < inputs["I_transverse"] else "retrograde")


def test_an_axial_moment_above_twice_the_transverse_one_is_refused():
    """In range I_a ≤ 1 ≤ 2 I_t always holds; beyond it (solve called directly) no real body has such moments."""
    with pytest.raises(ParameterError) as refused:
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), "I_transverse": 0.5, "I_axial": 1.2})
    assert refused.value.field == "I_axial"
