"""Worked example ``tower-drop-deflection`` (app/physics/systems/ch03/eastward_deflection_example.py).

Independent reference: scipy's DOP853 integrating r̈ = −g Z − 2 Ω × ṙ from release to the ground (an event at
z = 0) at rtol 1e-13, never using the closed form. Tolerances:

* exact landing point: 1e-13 of the flight's size (h + |u| t₀), the integrator's relative accuracy on positions of
  that size (two tolerances, 1e-12 and 1e-13, agree to 1e-15 of it); landing time 1e-12 s, landing speed 1e-12 of it;
* first-order deflection: against the odd part (D(Ω) − D(−Ω))/2 of the integrated deflection, which is the first
  order plus the third; the third is ε² of the first, ε = Ω (t₀ + |u|/g), times coefficients of order one (the
  cases below give 0.05 to 0.6 of ε²), so 2 ε² of the first order;
* the drop from rest against the textbook ⅓ Ω g t³ cos λ: the same closed form, 1e-13 relative.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from app.physics.systems.ch03.eastward_deflection import drop_east_deflection_first_order_m
from app.physics.systems.ch03.eastward_deflection_example import EXAMPLE
from app.physics.systems.earth import EARTH_RATE_RAD_S

CASES = [
    EXAMPLE.inputs.defaults(),
    {"height_m": 1.0, "latitude_deg": 45.0, "launch_velocity_m_s": [0.0, 0.0, 40.0]},
    {"height_m": 2000.0, "latitude_deg": 10.0, "launch_velocity_m_s": [100.0, 100.0, 100.0]},
    {"height_m": 1.0, "latitude_deg": -60.0, "launch_velocity_m_s": [100.0, 0.0, 0.0], "g_m_s2": 3.71},
    {"height_m": 158.0, "latitude_deg": 50.9, "launch_velocity_m_s": [0.0, 0.0, 0.0]},
]


def integrated_landing(inputs, rate_rad_s: float) -> tuple[float, np.ndarray]:
    """(landing time s, state [r, v] at landing) of r̈ = −g Z − 2 Ω × ṙ by DOP853."""
    lam = math.radians(inputs["latitude_deg"])
    omega = rate_rad_s * np.array([0.0, math.cos(lam), math.sin(lam)])
    g = inputs["g_m_s2"]

    def rhs(t, y):
        return np.concatenate([y[3:], np.array([0.0, 0.0, -g]) - 2.0 * np.cross(omega, y[3:])])

    def ground(t, y):
        return y[2]

    ground.terminal, ground.direction = True, -1
    y0 = np.array([0.0, 0.0, inputs["height_m"], *inputs["launch_velocity_m_s"]], dtype=float)
    sol = solve_ivp(
        rhs, (0.0, 1e4), y0, method="DOP853", rtol=1e-13, atol=1e-12 * max(1.0, inputs["height_m"]), events=ground
    )
    return float(sol.t_events[0][0]), sol.y_events[0][0]


@pytest.mark.parametrize("case", range(len(CASES)))
def test_landing_point_and_first_order_agree_with_an_integration(case):
    inputs = EXAMPLE.inputs.validate(CASES[case])
    out = EXAMPLE.solve(inputs).outputs
    u, g = np.asarray(inputs["launch_velocity_m_s"], dtype=float), inputs["g_m_s2"]
    t0 = (u[2] + math.sqrt(u[2] ** 2 + 2.0 * g * inputs["height_m"])) / g
    assert out["fall_time_s"] == pytest.approx(t0, rel=1e-14)
    plain = np.array([u[0] * t0, u[1] * t0, 0.0])
    size = inputs["height_m"] + float(np.linalg.norm(u)) * t0

    t_land, state = integrated_landing(inputs, EARTH_RATE_RAD_S)
    deflection = state[:3] - plain
    deflection[2] = 0.0
    assert out["landing_time_s"] == pytest.approx(t_land, abs=1e-12)
    assert np.abs(out["deflection_m"] - deflection).max() < 1e-13 * size
    assert out["landing_speed_m_s"] == pytest.approx(np.linalg.norm(state[3:]), rel=1e-12)

    _, mirrored = integrated_landing(inputs, -EARTH_RATE_RAD_S)
    odd = 0.5 * (state[:3] - mirrored[:3])
    odd[2] = 0.0
    first = out["first_order_deflection_m"]
    epsilon = EARTH_RATE_RAD_S * (t0 + float(np.linalg.norm(u)) / g)
    assert np.linalg.norm(first - odd) <= 2.0 * epsilon**2 * np.linalg.norm(first) + 1e-13 * size


@pytest.mark.parametrize("latitude_deg", [0.0, 45.0, 50.9, -33.9])
def test_a_drop_from_rest_gives_the_textbook_first_order_deflection(latitude_deg):
    inputs = EXAMPLE.inputs.validate({"height_m": 158.0, "latitude_deg": latitude_deg})
    first = EXAMPLE.solve(inputs).outputs["first_order_deflection_m"]
    expected = drop_east_deflection_first_order_m(height_m=158.0, latitude_deg=latitude_deg, g_m_s2=inputs["g_m_s2"])
    assert first[0] == pytest.approx(expected, rel=1e-13)
    assert first[1] == 0.0 and first[2] == 0.0


def test_the_check_step_conserves_the_jacobi_integral_and_the_error_is_of_order_epsilon():
    check = EXAMPLE.solve(EXAMPLE.inputs.defaults()).steps[-1]
    assert check.title.startswith("Check")
    assert check.values["half_v2_plus_gz_landing"] == pytest.approx(check.values["half_v2_plus_gz_release"], rel=1e-13)
    assert check.values["relative_difference"] < check.values["epsilon"]


def test_at_the_pole_a_drop_is_not_deflected():
    out = EXAMPLE.solve(EXAMPLE.inputs.validate({"latitude_deg": 90.0})).outputs
    assert np.all(out["deflection_m"] == 0.0) and np.all(out["first_order_deflection_m"] == 0.0)
