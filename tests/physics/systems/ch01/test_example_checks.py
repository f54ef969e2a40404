"""The Check steps added to chapter 1's worked examples (1.1, 1.2, particle-work-energy), against independent
computations, and their stories' places.

Tolerances:

* 1.1 (moments) and 1.2 (velocity on the radar's axes) are a few dozen products of numbers of order the answer, exact
  to a few ulps (≈ 1e-16) of the scale |r_C|·|F| or |v|; 1e-12 of that scale leaves a margin of ~1e3 or more.
* particle-work-energy integrates at rtol 1e-11; its balances then close to 1e-9 of the launch energy and momentum
  (the bound tests/physics/systems/ch01/test_projectile.py already justifies), which the Check step must meet too.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import sympy

from app.physics.systems.ch01 import projectile, radar_tracking, robot_arm_cable

RTOL = 1e-12


def _check_step(solution):
    step = solution.steps[-1]
    assert step.title.startswith("Check")
    return step.values


@pytest.mark.parametrize(
    "changes",
    [
        {},
        {"theta_deg": 0.0},
        {"theta_deg": -130.0, "gamma_deg": -20.0, "tension_N": 80_000.0, "AB_m": 0.3, "BC_m": 7.0, "D_x_m": -4.0},
        {"theta_deg": 170.0, "gamma_deg": 85.0, "tension_N": 10.0, "AB_m": 9.0, "BC_m": 0.05, "D_x_m": 10.0},
    ],
)
def test_robot_arm_moments_do_not_depend_on_the_point_used(changes):
    example = robot_arm_cable.EXAMPLE
    inputs = example.inputs.validate(changes)
    solution = example.solve(inputs)
    values = _check_step(solution)
    loads = robot_arm_cable.cable_loads(inputs)
    g = loads.geometry
    scale = float(np.linalg.norm(g.C)) * float(np.linalg.norm(loads.F_N))
    # Independent: a third point of the line of action (the cable's midpoint) and of the axis (AB's midpoint).
    mid_cable, mid_arm = 0.5 * (g.C + g.D), 0.5 * (g.A + g.B)
    M_A_mid = np.cross(mid_cable, loads.F_N)
    M_AB_mid = float(np.cross(g.C - mid_arm, loads.F_N) @ g.e_AB)
    for key in ("M_A (via C)", "M_A (via D)"):
        assert np.all(np.abs(values[key] - M_A_mid) <= RTOL * scale), key
    for key in ("M_AB (about A)", "M_AB (about B)"):
        assert abs(values[key] - M_AB_mid) <= RTOL * scale, key
    assert np.array_equal(values["M_A (via C)"], solution.outputs["M_A_Nm"])


def _radar_velocity_sympy(at: float) -> np.ndarray:
    """The aircraft's velocity on xyz from sympy's derivative of its position, with 30 digits."""
    t = sympy.Symbol("t", positive=True)
    r = 2000 + 100 * t
    theta = sympy.pi / 2 * (1 - sympy.exp(-sympy.Rational(15, 100) * t))
    beta = sympy.pi / 3 - sympy.Rational(1, 10) * sympy.sqrt(t)
    position = (r * sympy.cos(beta) * sympy.cos(theta), r * sympy.cos(beta) * sympy.sin(theta), r * sympy.sin(beta))
    with mpmath.workdps(30):
        return np.array([float(sympy.N(sympy.diff(p, t).subs(t, sympy.Float(at, 30)), 30)) for p in position])


@pytest.mark.parametrize("t_s", [2.0, 1.0, 7.3, 60.0])
def test_radar_axes_rebuild_the_chain_rule_velocity(t_s):
    example = radar_tracking.EXAMPLE
    values = _check_step(example.solve(example.inputs.validate({"t_s": t_s})))
    reference = _radar_velocity_sympy(t_s)
    speed = float(np.linalg.norm(reference))
    for key in ("v (radar axes)", "v (chain rule)"):
        assert np.all(np.abs(values[key] - reference) <= RTOL * speed), key
    assert values["speed (radar axes)"] == pytest.approx(speed, rel=RTOL)
    assert values["speed (chain rule)"] == pytest.approx(speed, rel=RTOL)
    axes = radar_tracking.radar_axes(t_s)
    assert np.allclose(axes @ axes.T, np.eye(3), rtol=0.0, atol=1e-15)  # orthonormal
    assert np.allclose(np.cross(axes[0], axes[1]), axes[2], rtol=0.0, atol=1e-15)  # right-handed (r, θ, β)


@pytest.mark.parametrize(
    "changes",
    [
        {},
        {"quadratic_drag_kg_m": 0.0},
        {"quadratic_drag_kg_m": 0.0, "linear_drag_kg_s": 0.05, "height0_m": 20.0},
        {"mass_kg": 2.0, "speed0_m_s": 120.0, "elevation_deg": 70.0, "quadratic_drag_kg_m": 0.01, "g_m_s2": 3.7},
    ],
)
def test_projectile_check_step_balances_and_drag_only_slows(changes):
    example = projectile.EXAMPLE
    inputs = example.inputs.validate(changes)
    values = _check_step(example.solve(inputs))
    m, v0 = inputs["mass_kg"], inputs["speed0_m_s"]
    T0, p0 = 0.5 * m * v0**2, m * v0
    assert abs(values["T2 - T1"] - values["W_g + W_d"]) <= 1e-9 * T0
    assert np.linalg.norm(values["m_dv"] - values["I_g + I_d"]) <= 1e-9 * p0
    no_drag = math.sqrt(v0**2 + 2.0 * inputs["g_m_s2"] * inputs["height0_m"])
    assert values["v2 (no drag)"] == pytest.approx(no_drag, rel=RTOL)
    if inputs["linear_drag_kg_s"] == 0.0 and inputs["quadratic_drag_kg_m"] == 0.0:
        assert values["v2"] == pytest.approx(no_drag, rel=1e-9)  # energy conserved: the integrator's accuracy
    else:
        assert values["v2"] < no_drag


@pytest.mark.parametrize(
    ("example", "section"),
    [(robot_arm_cable.EXAMPLE, "1.1"), (radar_tracking.EXAMPLE, "1.1"), (projectile.EXAMPLE, "1.2")],
)
def test_chapter_1_examples_have_their_section_and_story(example, section):
    assert example.section == section
    assert example.story is not None
