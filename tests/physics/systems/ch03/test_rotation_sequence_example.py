"""Worked example ``camera-gimbal-sequence`` (app/physics/systems/ch03/rotation_sequence_example.py).

Independent reference: scipy's ``Rotation`` (``from_euler`` with intrinsic, upper-case axes builds the sequence;
``apply`` turns the line of sight; ``as_euler`` reads the second sequence's angles back), and plain trigonometry for
the azimuth and elevation. Tolerances: matrix entries and unit-vector components are at most 1 and both sides are a
few dozen roundings, so 1e-12 absolute; angles come from ``atan2`` of such numbers, so 1e-9 degrees (1.7e-11 rad)
leaves room for the conditioning of ``atan2`` away from gimbal lock and no more.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from app.physics.systems.ch03.rotation_sequence_example import AT_GIMBAL_LOCK, CLEAR_OF_GIMBAL_LOCK, EXAMPLE

MATRIX_TOL = 1e-12
ANGLE_TOL_DEG = 1e-9

CASES = [
    EXAMPLE.inputs.defaults(),
    {
        "sequence": "3-2-1",
        "angle1_deg": 30.0,
        "angle2_deg": -20.0,
        "angle3_deg": 10.0,
        "sight_body": [0.0, 0.0, 1.0],
        "readback_sequence": "3-1-3",
    },
    {
        "sequence": "1-2-3",
        "angle1_deg": -120.0,
        "angle2_deg": 70.0,
        "angle3_deg": 45.0,
        "sight_body": [0.3, -0.4, 0.5],
        "readback_sequence": "2-3-1",
    },
    {
        "sequence": "2-3-2",
        "angle1_deg": 15.0,
        "angle2_deg": 150.0,
        "angle3_deg": -95.0,
        "sight_body": [-1.0, 0.2, 0.0],
        "readback_sequence": "3-2-1",
    },
]


def scipy_rotation(sequence: str, angles_deg) -> Rotation:
    return Rotation.from_euler("".join("XYZ"[int(a) - 1] for a in sequence.split("-")), angles_deg, degrees=True)


def wrapped_difference_deg(a, b):
    return (np.asarray(a) - np.asarray(b) + 180.0) % 360.0 - 180.0


@pytest.mark.parametrize("case", range(len(CASES)))
def test_matrix_sight_and_readback_agree_with_scipy(case):
    inputs = EXAMPLE.inputs.validate(CASES[case])
    out = EXAMPLE.solve(inputs).outputs
    rotation = scipy_rotation(inputs["sequence"], [inputs[f"angle{k}_deg"] for k in (1, 2, 3)])
    assert np.abs(out["R_world_body"] - rotation.as_matrix()).max() < MATRIX_TOL

    sight = np.asarray(inputs["sight_body"], dtype=float)
    expected_sight = rotation.apply(sight / np.linalg.norm(sight))
    assert np.abs(out["sight_world"] - expected_sight).max() < MATRIX_TOL
    east, north, up = expected_sight
    assert out["azimuth_deg"] == pytest.approx(math.degrees(math.atan2(north, east)), abs=ANGLE_TOL_DEG)
    assert out["elevation_deg"] == pytest.approx(math.degrees(math.asin(up)), abs=ANGLE_TOL_DEG)

    other = inputs["readback_sequence"]
    expected_angles = rotation.as_euler("".join("XYZ"[int(a) - 1] for a in other.split("-")), degrees=True)
    assert out["readback_at_gimbal_lock"] == CLEAR_OF_GIMBAL_LOCK
    assert np.abs(wrapped_difference_deg(out["readback_angles_deg"], expected_angles)).max() < ANGLE_TOL_DEG
    # and the read-back angles put the body in the same attitude
    again = scipy_rotation(other, out["readback_angles_deg"]).as_matrix()
    assert np.abs(again - rotation.as_matrix()).max() < MATRIX_TOL


def test_the_check_step_shows_round_off_only():
    check = EXAMPLE.solve(EXAMPLE.inputs.defaults()).steps[-1]
    assert check.title.startswith("Check")
    for name in ("orthogonality_error", "rebuilt_error_other", "rebuilt_error_own"):
        assert check.values[name] < MATRIX_TOL
    assert check.values["det_R"] == pytest.approx(1.0, abs=MATRIX_TOL)


def test_a_readback_at_gimbal_lock_is_flagged_and_still_rebuilds_the_attitude():
    inputs = EXAMPLE.inputs.validate({"sequence": "3-2-1", "angle2_deg": 90.0, "readback_sequence": "3-2-1"})
    out = EXAMPLE.solve(inputs).outputs
    assert out["readback_at_gimbal_lock"] == AT_GIMBAL_LOCK
    rebuilt = scipy_rotation("3-2-1", out["readback_angles_deg"]).as_matrix()
    assert np.abs(rebuilt - out["R_world_body"]).max() < MATRIX_TOL


def test_a_line_of_sight_of_zero_length_is_refused():
    values = {**EXAMPLE.inputs.defaults(), "sight_body": [0.0, 0.0, 0.0]}
    with pytest.raises(ValueError, match="line of sight"):
        EXAMPLE.solve(values)
    with pytest.raises(ValueError, match="line of sight"):
        EXAMPLE.inputs.validate({"sight_body": [0.0, 0.0, 0.0]})
