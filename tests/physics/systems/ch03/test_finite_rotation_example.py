"""Worked example ``antenna-boom-finite-rotation`` (app/physics/systems/ch03/finite_rotation_example.py).

Independent reference: scipy's ``Rotation``: the sequence from ``from_euler`` (intrinsic, upper-case axes), Euler's
axis and angle from ``as_rotvec``, the second turn from ``from_rotvec``, the two orders as ``rB * rA`` and
``rA * rB`` (scipy's product applies the right-hand turn first, so ``rB * rA`` is A then B about fixed axes) and the
gap as the magnitude of ``(rB rA)(rA rB)⁻¹``. Tolerances: unit vectors and matrices have entries of size ≤ 1 and
tip positions ≤ 10 m, each a few dozen roundings on both sides: 1e-12 (relative to those sizes); angles from
``atan2``/``acos`` of such numbers away from 0 and 180°: 1e-9 degrees.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from app.physics.systems.ch03.finite_rotation_example import EXAMPLE

TOL = 1e-12
ANGLE_TOL_DEG = 1e-9

CASES = [
    EXAMPLE.inputs.defaults(),
    {
        "sequence": "3-2-1",
        "angle1_deg": 20.0,
        "angle2_deg": 40.0,
        "angle3_deg": -30.0,
        "second_axis": "X",
        "second_angle_deg": 45.0,
        "boom_body_m": [0.5, 1.0, -0.3],
    },
    {
        "sequence": "1-2-1",
        "angle1_deg": -100.0,
        "angle2_deg": 120.0,
        "angle3_deg": 170.0,
        "second_axis": "Y",
        "second_angle_deg": -150.0,
        "boom_body_m": [0.0, 0.0, 2.0],
    },
    {
        "sequence": "2-1-3",
        "angle1_deg": 5.0,
        "angle2_deg": -10.0,
        "angle3_deg": 8.0,
        "second_axis": "Z",
        "second_angle_deg": 10.0,
        "boom_body_m": [3.0, -1.0, 0.5],
    },
]


def scipy_rotation(sequence: str, angles_deg) -> Rotation:
    return Rotation.from_euler("".join("XYZ"[int(a) - 1] for a in sequence.split("-")), angles_deg, degrees=True)


@pytest.mark.parametrize("case", range(len(CASES)))
def test_axis_angle_tips_and_order_gap_agree_with_scipy(case):
    inputs = EXAMPLE.inputs.validate(CASES[case])
    out = EXAMPLE.solve(inputs).outputs
    r_a = scipy_rotation(inputs["sequence"], [inputs[f"angle{k}_deg"] for k in (1, 2, 3)])
    rotvec = r_a.as_rotvec()
    angle = float(np.linalg.norm(rotvec))
    assert out["angle_deg"] == pytest.approx(np.degrees(angle), abs=ANGLE_TOL_DEG)
    assert np.abs(out["axis_world"] - rotvec / angle).max() < TOL

    boom = np.asarray(inputs["boom_body_m"], dtype=float)
    axis = np.zeros(3)
    axis["XYZ".index(inputs["second_axis"])] = 1.0
    r_b = Rotation.from_rotvec(np.radians(inputs["second_angle_deg"]) * axis)
    a_then_b, b_then_a = r_b * r_a, r_a * r_b
    assert np.abs(out["tip_after_a_m"] - r_a.apply(boom)).max() < TOL * 10
    assert np.abs(out["tip_a_then_b_m"] - a_then_b.apply(boom)).max() < TOL * 10
    assert np.abs(out["tip_b_then_a_m"] - b_then_a.apply(boom)).max() < TOL * 10
    expected_separation = np.linalg.norm(a_then_b.apply(boom) - b_then_a.apply(boom))
    assert out["tip_separation_m"] == pytest.approx(expected_separation, abs=TOL * 10)
    gap = (a_then_b * b_then_a.inv()).magnitude()
    assert out["order_gap_deg"] == pytest.approx(np.degrees(gap), abs=ANGLE_TOL_DEG)


def test_turns_about_the_same_fixed_axis_commute():
    out = EXAMPLE.solve(
        EXAMPLE.inputs.validate({"sequence": "3-1-3", "angle2_deg": 0.0, "second_axis": "Z", "second_angle_deg": 70.0})
    ).outputs
    assert out["tip_separation_m"] < TOL and out["order_gap_deg"] < ANGLE_TOL_DEG


def test_the_check_step_holds_at_the_defaults():
    check = EXAMPLE.solve(EXAMPLE.inputs.defaults()).steps[-1]
    assert check.title.startswith("Check")
    assert check.values["rodrigues_error"] < TOL and check.values["axis_moved"] < TOL
    assert check.values["chord"] == pytest.approx(check.values["2_rho_sin_half_phi"], abs=TOL)
    assert check.values["r_0_dot_n"] == pytest.approx(check.values["r_A_dot_n"], abs=TOL)


def test_a_boom_of_zero_length_is_refused():
    values = {**EXAMPLE.inputs.defaults(), "boom_body_m": [0.0, 0.0, 0.0]}
    with pytest.raises(ValueError, match="boom"):
        EXAMPLE.solve(values)
    with pytest.raises(ValueError, match="boom"):
        EXAMPLE.inputs.validate({"boom_body_m": [0.0, 0.0, 0.0]})
