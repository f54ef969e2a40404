"""Worked example ``tilted-ride-angular-velocity`` (app/physics/systems/ch03/angle_rates_example.py).

Independent reference: sympy. The attitude [R(t)] is the product of the three elementary matrices with the angles'
quadratic time laws, built symbolically; ω is read from the exact skew-symmetric matrix Ṙ Rᵀ and α is its exact
time derivative. No turn axis and no rate-matrix J is used. Tolerance: both sides are double-precision evaluations
of a few dozen operations on numbers of size ≤ 10 rad/s: 1e-12 of |ω| and |α| (with a floor of 1e-3).

There is no impossible combination of inputs to refuse here: gimbal lock is a failure of the angles as a
description, not of the motion. The example solves there and says the rates cannot be recovered (tested below).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp

from app.physics.systems.ch03.angle_rates_example import AT_GIMBAL_LOCK, CLEAR_OF_GIMBAL_LOCK, EXAMPLE

RELATIVE_TOL = 1e-12

CASES = [
    EXAMPLE.inputs.defaults(),
    {
        "sequence": "3-2-1",
        "angle1_deg": 30.0,
        "angle2_deg": -10.0,
        "angle3_deg": 5.0,
        "rate1_rad_s": 0.2,
        "rate2_rad_s": -0.3,
        "rate3_rad_s": 0.4,
        "accel1_rad_s2": 0.1,
        "accel2_rad_s2": -0.05,
        "accel3_rad_s2": 0.3,
        "time_s": 2.5,
    },
    {
        "sequence": "1-3-1",
        "angle1_deg": -150.0,
        "angle2_deg": 100.0,
        "angle3_deg": 170.0,
        "rate1_rad_s": -3.0,
        "rate2_rad_s": 2.5,
        "rate3_rad_s": 1.5,
        "accel1_rad_s2": 2.0,
        "accel2_rad_s2": -2.0,
        "accel3_rad_s2": 1.0,
        "time_s": 0.7,
    },
    {
        "sequence": "2-1-3",
        "angle1_deg": 10.0,
        "angle2_deg": 20.0,
        "angle3_deg": 30.0,
        "rate1_rad_s": 1.0,
        "rate2_rad_s": 0.5,
        "rate3_rad_s": -1.0,
        "accel1_rad_s2": 0.0,
        "accel2_rad_s2": 0.2,
        "accel3_rad_s2": 0.0,
        "time_s": 47.0,
        "replay_s": 20.0,
    },
]


def elementary(axis: int, angle):
    c, s = sp.cos(angle), sp.sin(angle)
    j, k = (axis + 1) % 3, (axis + 2) % 3
    R = sp.eye(3)
    R[j, j], R[k, k], R[k, j], R[j, k] = c, c, s, -s
    return R


def reference(inputs) -> tuple[np.ndarray, np.ndarray]:
    """ω and α (XYZ components) from sympy's exact Ṙ Rᵀ and its derivative."""
    t = sp.symbols("t", real=True)
    axes = [int(a) - 1 for a in inputs["sequence"].split("-")]
    R = sp.eye(3)
    for k, axis in enumerate(axes, start=1):
        angle = (
            sp.rad(sp.Float(inputs[f"angle{k}_deg"], 30))
            + sp.Float(inputs[f"rate{k}_rad_s"], 30) * t
            + sp.Float(inputs[f"accel{k}_rad_s2"], 30) * t**2 / 2
        )
        R = R * elementary(axis, angle)
    W = R.diff(t) * R.T
    omega = sp.Matrix([W[2, 1], W[0, 2], W[1, 0]])
    alpha = omega.diff(t)
    instant = math.fmod(inputs["time_s"], inputs["replay_s"])
    evaluate = lambda m: np.array([float(c.subs(t, instant).evalf(30)) for c in m])  # noqa: E731
    return evaluate(omega), evaluate(alpha)


@pytest.mark.parametrize("case", range(len(CASES)))
def test_omega_and_alpha_are_sympys_rates_of_the_attitude(case):
    inputs = EXAMPLE.inputs.validate(CASES[case])
    solution = EXAMPLE.solve(inputs)
    out = solution.outputs
    omega, alpha = reference(inputs)
    omega_scale = max(float(np.linalg.norm(omega)), 1e-3)
    alpha_scale = max(float(np.linalg.norm(alpha)), 1e-3)
    assert np.abs(out["omega_world_rad_s"] - omega).max() < RELATIVE_TOL * omega_scale
    assert np.abs(out["alpha_world_rad_s2"] - alpha).max() < RELATIVE_TOL * alpha_scale
    assert np.abs(out["alpha_along_axes_rad_s2"] + out["alpha_turning_axes_rad_s2"] - alpha).max() < (
        RELATIVE_TOL * alpha_scale
    )
    assert float(np.linalg.norm(out["omega_body_rad_s"])) == pytest.approx(np.linalg.norm(omega), rel=RELATIVE_TOL)
    # the rates come back from ω (none of these cases is at gimbal lock)
    assert out["gimbal_lock"] == CLEAR_OF_GIMBAL_LOCK
    back = solution.steps[4].values["theta_dot_back"]
    instant = math.fmod(inputs["time_s"], inputs["replay_s"])
    expected = [inputs[f"rate{k}_rad_s"] + inputs[f"accel{k}_rad_s2"] * instant for k in (1, 2, 3)]
    assert np.abs(back - expected).max() < 1e-11


def test_the_check_step_agrees_at_the_defaults():
    check = EXAMPLE.solve(EXAMPLE.inputs.defaults()).steps[-1]
    assert check.title.startswith("Check")
    # fourth-order differences with h = 1e-3 s: truncation ≈ 1e-13, round-off ≈ 2e-13 rad/s (see the module)
    assert np.abs(check.values["omega_from_R_dot"] - check.values["omega"]).max() < 1e-9
    assert np.abs(check.values["alpha_differenced"] - check.values["alpha"]).max() < 1e-9


def test_at_gimbal_lock_omega_stands_and_only_the_sum_of_rates_is_recovered():
    inputs = EXAMPLE.inputs.validate({"sequence": "3-1-3", "angle2_deg": 0.0, "rate2_rad_s": 0.0})
    solution = EXAMPLE.solve(inputs)
    omega, _ = reference(inputs)
    assert np.abs(solution.outputs["omega_world_rad_s"] - omega).max() < RELATIVE_TOL * np.linalg.norm(omega)
    assert solution.outputs["gimbal_lock"] == AT_GIMBAL_LOCK
    step = solution.steps[4]
    assert "gimbal lock" in step.title
    assert step.values["theta1_dot_pm_theta3_dot"] == pytest.approx(omega[2], rel=1e-12)
