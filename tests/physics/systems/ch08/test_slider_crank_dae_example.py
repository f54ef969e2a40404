"""The slider-crank-multipliers worked example against Lagrange's equation in θ and a hand elimination (sympy).

The independent computation is the one the chapter-6 example is tested with
(:func:`tests.physics.systems.ch06.test_mechanism_kinetics_example.by_lagrange_and_elimination`): positions written
afresh in sympy as functions of θ and differentiated exactly, Lagrange's equation in the one coordinate θ for α under
the given torque, and the forces by eliminating link by link. It shares no code with the example's 17 × 17 solve
in nine absolute coordinates. Both are exact formulas in floating point: 1e-10 of the force scale
m_total (g + r ω² (1 + r/l)) + |τ|/r leaves ample room for the solve's round-off (its matrix mixes kg, kg·m² and
lengths of 0.1–1 m, a condition number of about 10³ at the defaults).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch08.slider_crank_dae import (
    slider_crank_absolute_motion,
    slider_crank_initial_state,
    slider_crank_system,
)
from app.physics.systems.ch08.slider_crank_dae_example import EXAMPLE
from tests.physics.systems.ch06.test_mechanism_kinetics_example import by_lagrange_and_elimination

RTOL = 1e-10

CASES = [
    {},
    {"crank_angle0_deg": 100.0, "drive_torque_N_m": 0.0},
    {"offset_m": 0.2, "rod_m": 0.8, "crank_angle0_deg": -135.0, "crank_speed_rad_s": -15.0},
    {"slider_mass_kg": 50.0, "g_m_s2": 0.0, "crank_angle0_deg": 170.0, "drive_torque_N_m": 30.0},
    {"drive_torque_N_m": -40.0, "crank_m": 0.5, "rod_m": 1.4, "offset_m": -0.3, "crank_speed_rad_s": 3.0},
]


@pytest.mark.parametrize("changes", CASES)
def test_the_multipliers_are_the_pin_forces_of_an_independent_computation(changes):
    p = EXAMPLE.inputs.validate(changes)
    outputs = EXAMPLE.solve(p).outputs
    expected, inertia = by_lagrange_and_elimination({**p, "drive": "torque"})
    masses = p["crank_mass_kg"] + p["rod_mass_kg"] + p["slider_mass_kg"]
    r, l, omega = p["crank_m"], p["rod_m"], p["crank_speed_rad_s"]
    force_scale = masses * (p["g_m_s2"] + r * omega**2 * (1 + r / l)) + abs(p["drive_torque_N_m"]) / r
    assert outputs["crank_acceleration_rad_s2"] == pytest.approx(
        expected["crank_acceleration_rad_s2"], abs=RTOL * force_scale * r / inertia
    )
    for ours, theirs in (
        ("pin_O_N", "pivot_O_N"),
        ("pin_A_N", "crank_pin_A_N"),
        ("pin_B_N", "wrist_pin_B_N"),
        ("guide_force_N", "guide_force_N"),
    ):
        np.testing.assert_allclose(outputs[ours], expected[theirs], rtol=0, atol=RTOL * force_scale, err_msg=ours)
    assert abs(outputs["slider_moment_N_m"]) <= RTOL * force_scale * r  # every force on the slider acts at its centre


@pytest.mark.parametrize("changes", CASES)
def test_the_solution_satisfies_the_equations_it_came_from(changes):
    # With the accelerations of chapter 4's loop closure at the example's θ̈: M a − Cᵀλ = f and C a = c, and the
    # start lies on the constraints; the check step repeats the multipliers.
    p = EXAMPLE.inputs.validate(changes)
    solution = EXAMPLE.solve(p)
    out = solution.outputs
    system = slider_crank_system(p)
    q, v = slider_crank_initial_state(p)
    _, _, a = slider_crank_absolute_motion(
        p, math.radians(p["crank_angle0_deg"]), p["crank_speed_rad_s"], out["crank_acceleration_rad_s2"]
    )
    mass, f = system.mass_and_forces(0.0, q, v)
    g, C, c = system.constraint_terms(q, v)
    lam = np.concatenate(
        [out["pin_O_N"], out["pin_A_N"], out["pin_B_N"], [out["guide_force_N"]], [out["slider_moment_N_m"]]]
    )
    masses = p["crank_mass_kg"] + p["rod_mass_kg"] + p["slider_mass_kg"]
    r, l, omega = p["crank_m"], p["rod_m"], p["crank_speed_rad_s"]
    force_scale = masses * (p["g_m_s2"] + r * omega**2 * (1 + r / l)) + abs(p["drive_torque_N_m"]) / r
    assert np.max(np.abs(g)) <= 1e-14 * (r + l)
    assert np.max(np.abs(mass @ a[0] - C.T @ lam - f)) <= RTOL * force_scale
    assert np.max(np.abs(C @ a[0] - c)) <= RTOL * (r + l) * (omega**2 + abs(out["crank_acceleration_rad_s2"]) + 1.0)
    check = solution.steps[-1]
    assert check.title.startswith("Check")
    np.testing.assert_allclose(check.values["O_ch6"], out["pin_O_N"], rtol=0, atol=RTOL * force_scale)
    assert check.values["N_ch6"] == pytest.approx(out["guide_force_N"], abs=RTOL * force_scale)


def test_a_rod_too_short_to_follow_the_crank_is_refused():
    with pytest.raises(ParameterError, match="connecting rod"):  # a 422 from the API, naming rod_m
        EXAMPLE.inputs.validate({"crank_m": 0.3, "rod_m": 0.35, "offset_m": 0.1})
    with pytest.raises(ValueError, match="connecting rod"):
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), "crank_m": 0.5, "rod_m": 0.5})
