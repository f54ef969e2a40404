"""A worked solution shows a number that is zero up to round-off as 0 (app/physics/core/solution.py).

Round-off: within ROUND_OFF_RTOL (1e-12) of the number's scale, a vector's own length unless the solution states a
scale. The robotic arm (worked example 1.1) at θ = 25°, γ = 45° computed M_A = [4.5e-13, 10178.8, −12413.2] N·m: the
x component is 3e-17 of |M_A|, an ulp or two of the cross product, and the page showed it.
"""

from __future__ import annotations

import numpy as np
import pytest

from app.physics.core.solution import ROUND_OFF_RTOL, Solution, Step, zero_round_off
from app.physics.systems.ch01 import robot_arm_cable as arm


def test_round_off_of_a_vectors_length_is_zero_and_the_rest_is_kept():
    assert zero_round_off(np.array([4.5e-13, 10178.8, -12413.2])).tolist() == [0.0, 10178.8, -12413.2]
    assert zero_round_off([4.5e-13, 10178.8, -12413.2]) == [0.0, 10178.8, -12413.2]  # lists stay lists
    assert zero_round_off(np.array([1e-6, 1.0, 0.0])).tolist() == [1e-6, 1.0, 0.0]  # small but real
    assert zero_round_off([[1.0, 3e-17], [3e-17, 2.0]]) == [[1.0, 0.0], [0.0, 2.0]]  # a matrix: its Frobenius length
    # A lone number has no length to compare with, unless a scale is given.
    assert zero_round_off(-1.07e-12) == -1.07e-12 and zero_round_off(-1.07e-12, 17_500.0) == 0.0
    assert zero_round_off(2e-8, 17_500.0) == 2e-8  # 1.1e-12 of the scale: above round-off
    # A sweep spans decades: its smallest numbers are not round-off of its length (radar tracking's dt from 1e-12 s).
    sweep = list(np.logspace(-12, 0.3, 50))
    assert zero_round_off(sweep) == sweep and zero_round_off(np.array(sweep)).tolist() == sweep
    assert not np.signbit(zero_round_off(np.array([-1e-20, 1.0]))[0])  # 0, never −0
    # Words, booleans, integers and non-finite numbers pass unchanged.
    assert zero_round_off("clockwise") == "clockwise" and zero_round_off(True) is True and zero_round_off(3) == 3
    assert zero_round_off([float("nan"), 1.0]) == pytest.approx([float("nan"), 1.0], nan_ok=True)
    assert ROUND_OFF_RTOL == 1e-12


def test_steps_and_outputs_store_zero_for_round_off():
    step = Step("moment", "M", {"M": np.array([4.5e-13, 1.0e4, -1.2e4]), "M_z": -1e-12}, {"M": "N·m"}, scales={"M_z": 1.75e4})
    assert step.values["M"].tolist() == [0.0, 1.0e4, -1.2e4] and step.values["M_z"] == 0.0
    solution = Solution({"M_A_Nm": [4.5e-13, 1.0e4, -1.2e4], "M_z_Nm": -1e-12, "sweep": list(np.linspace(0, 1, 5))}, (step,),
                        output_scales={"M_z_Nm": 1.75e4})
    assert solution.outputs["M_A_Nm"] == [0.0, 1.0e4, -1.2e4] and solution.outputs["M_z_Nm"] == 0.0
    assert solution.outputs["sweep"] == list(np.linspace(0, 1, 5))
    assert solution.as_dict()["steps"][0]["values"]["M"] == [0.0, 1.0e4, -1.2e4]


@pytest.mark.parametrize(
    ("inputs", "zero"),
    [
        ({"theta_deg": 25.0, "gamma_deg": 45.0}, {"M_A_Nm": [0]}),  # the 4.5e-13 N·m
        ({"theta_deg": 180.0, "gamma_deg": 0.0}, {"F_N": [1], "M_A_Nm": [0, 1, 2], "M_z_Nm": None, "M_AB_Nm": None}),
        ({"theta_deg": 180.0, "gamma_deg": 40.0}, {"F_N": [1], "M_A_Nm": [0, 2], "M_z_Nm": None, "M_AB_Nm": None}),
    ],
)
def test_example_1_1_shows_round_off_as_zero_and_keeps_every_other_number(inputs, zero):
    """Where the loads are zero by geometry (θ = 180°: the arm and the cable in the xz plane), they are exactly 0; every
    other number is the computation's own, to the bit."""
    values = arm.INPUTS.validate(inputs)
    loads = arm.cable_loads(values)
    scale = arm.round_off_scales(loads)
    raw = {"F_N": loads.F_N, "F_BC_N": loads.F_BC_N, "M_A_Nm": loads.M_A_Nm, "M_z_Nm": loads.M_z_Nm, "M_AB_Nm": loads.M_AB_Nm}
    solution = arm.solve(values)
    for name, value in raw.items():
        shown = np.asarray(solution.outputs[name], dtype=float)
        expected = np.array(value, dtype=float)
        if name in zero:
            at = slice(None) if zero[name] is None else zero[name]
            assert np.all(np.abs(np.atleast_1d(expected)[at]) <= 1e-12 * scale[name]), (name, expected)  # round-off indeed
            assert np.all(np.atleast_1d(shown)[at] == 0.0), (name, shown)
            np.atleast_1d(expected)[at] = 0.0
        np.testing.assert_array_equal(shown, expected, err_msg=name)
    steps = {key: value for step in solution.steps for key, value in step.values.items()}
    np.testing.assert_array_equal(steps["M_A"], solution.outputs["M_A_Nm"])
    assert steps["M_z"] == solution.outputs["M_z_Nm"] and steps["M_AB"] == solution.outputs["M_AB_Nm"]


def test_a_turn_of_a_millionth_of_a_degree_is_not_round_off():
    """θ = 180° + 1e-6°: M_z ≈ 1.8e-8 of its scale, a real moment, and the arm is told it turns."""
    values = arm.INPUTS.validate({"theta_deg": 179.999999, "gamma_deg": 0.0})
    solution = arm.solve(values)
    assert solution.outputs["M_z_Nm"] != 0.0
    assert arm.turning_about_z(arm.cable_loads(values)) != "none"
