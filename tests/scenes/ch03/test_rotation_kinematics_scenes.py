"""The chapter-3 kinematics scenes (finite-rotation, vector-derivative, angle-rates) on a real loopback viser client.

What they draw and read out is checked against scipy's ``Rotation`` and against numbers worked here
independently (cross products, hand-written closed forms), not against the scene's own code paths.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from app.physics.math.rotations import rotation_matrix
from app.scenes.ch03.angle_rates import AngleRatesScene
from app.scenes.ch03.finite_rotation import CYCLE_S, FiniteRotationScene
from app.scenes.ch03.vector_derivative import VectorDerivativeScene
from app.scenes.kit import FRAME_DT_S


def quantities(scene) -> dict:
    return {q.name: q.value if q.value is not None else q.text for q in scene.readout().quantities}


def components(text: str) -> np.ndarray:
    return np.array([float(v) for v in text.strip("()").split(",")])


def preset(cls, name):
    return cls.parameters.validate(next(p for p in cls.presets if p.name == name).values)


def arrow_segments(client, prefix: str) -> np.ndarray:
    """The points of the newest arrow batch under ``prefix`` (LabelledArrows renames a batch when it rebuilds)."""
    names = [n for n in client.scene.handles if n.startswith(prefix + "/") and n.rsplit("/", 1)[-1].isdigit()]
    return np.asarray(client.scene.handles[max(names, key=lambda n: int(n.rsplit("/", 1)[-1]))].points, float)


def test_finite_rotation_reads_out_eulers_axis_and_angle(client):
    scene = FiniteRotationScene(client, preset(FiniteRotationScene, "classic-euler"))
    values = quantities(scene)
    expected = Rotation.from_euler("ZXZ", [80.0, 35.0, 60.0], degrees=True)
    assert values["rotation_angle_deg"] == pytest.approx(math.degrees(expected.magnitude()), abs=1e-9)  # 141.92°
    axis = np.array([values[f"axis_{c}"] for c in "xyz"])
    assert np.abs(axis - expected.as_rotvec() / expected.magnitude()).max() < 1e-12
    x, y, z, w = expected.as_quat()
    assert np.abs(np.array([values[f"q_{c}"] for c in "wxyz"]) - [w, x, y, z]).max() < 1e-12
    assert values["rodrigues_mismatch"] < 1e-12
    assert "order_gap_deg" not in values and "141.92°" in scene.readout().message
    # In the hold the body is at the sequence's attitude.
    for _ in range(round((CYCLE_S - 1.0) / FRAME_DT_S)):
        scene.advance(FRAME_DT_S)
    assert np.abs(rotation_matrix(np.asarray(scene.bodies[0].wxyz)) - expected.as_matrix()).max() < 1e-12
    assert not scene.bodies[1].visible
    scene.close()


def test_quarter_turns_end_in_two_attitudes(client):
    scene = FiniteRotationScene(client, preset(FiniteRotationScene, "quarter-turns"))
    values = quantities(scene)
    a, b = Rotation.from_euler("X", 90, degrees=True), Rotation.from_euler("Z", 90, degrees=True)
    assert values["a_then_b_angle_deg"] == pytest.approx(120.0, abs=1e-9) and values["b_then_a_angle_deg"] == pytest.approx(120.0, abs=1e-9)
    assert np.abs(components(values["a_then_b_axis"]) - np.array([1, 1, 1]) / math.sqrt(3)).max() < 5e-5  # shown to 4 decimals
    assert np.abs(components(values["b_then_a_axis"]) - np.array([1, -1, 1]) / math.sqrt(3)).max() < 5e-5
    assert values["order_gap_deg"] == pytest.approx(120.0, abs=1e-9)
    assert "do not commute" in scene.readout().message
    for _ in range(round((CYCLE_S - 1.0) / FRAME_DT_S)):
        scene.advance(FRAME_DT_S)
    left, right = (rotation_matrix(np.asarray(body.wxyz)) for body in scene.bodies)
    assert np.abs(left - (b * a).as_matrix()).max() < 1e-12 and np.abs(right - (a * b).as_matrix()).max() < 1e-12
    scene.set_params(FiniteRotationScene.parameters.validate({"second_angle_deg": 0.0}, base=scene.params))
    assert "order_gap_deg" not in quantities(scene) and not scene.bodies[1].visible
    scene.close()


def test_vector_derivative_draws_the_three_rates_at_the_tip(client):
    scene = VectorDerivativeScene(client, VectorDerivativeScene.parameters.defaults())
    for _ in range(17):
        scene.advance(FRAME_DT_S)
    values = quantities(scene)
    A = components(values["A_world"])
    omega = components(values["omega"])
    tilt = math.radians(scene.params["frame_axis_tilt_deg"])
    assert np.abs(omega - scene.params["frame_rate_rad_s"] * np.array([math.sin(tilt), 0, math.cos(tilt)])).max() < 5e-4
    assert np.abs(components(values["dA_transport"]) - np.cross(omega, A)).max() < 2e-3  # from 3-decimal text
    assert values["dA_fixed_magnitude"] == pytest.approx(np.linalg.norm(scene.now.terms_m_s["relative"][0] + np.cross(scene.motion.omega_world_rad_s, scene.now.vector_world_m[0])), rel=1e-12)
    # Drawn: A from the origin, the relative rate from A's tip, ω × A from its head, the fixed-frame rate from the tip to the same end.
    segments = arrow_segments(client, "/vectors")
    tip = scene.now.vector_world_m[0]
    s = values["arrow_scale"]
    vector, relative, transport, fixed = segments[:4]
    assert np.abs(vector[1] - tip).max() < 1e-6 and np.abs(relative[0] - tip).max() < 1e-6 and np.abs(fixed[0] - tip).max() < 1e-6
    assert np.abs(transport[0] - relative[1]).max() < 1e-6 and np.abs(transport[1] - fixed[1]).max() < 1e-6
    assert np.abs((fixed[1] - fixed[0]) / s - scene.now.terms_m_s["fixed"][0]).max() < 1e-5  # float32 points
    scene.set_params(VectorDerivativeScene.parameters.validate(preset(VectorDerivativeScene, "fixed-in-frame"), base=scene.params))
    values = quantities(scene)
    assert values["dA_relative_magnitude"] == 0.0 and "ω × A alone" in scene.readout().message
    scene.close()


def test_angle_rates_readout_and_arrows(client):
    scene = AngleRatesScene(client, preset(AngleRatesScene, "steady-top"))
    for _ in range(40):
        scene.advance(FRAME_DT_S)
    values = quantities(scene)
    assert values["alpha_magnitude"] == pytest.approx(0.8, abs=1e-12)  # φ̇ψ̇ sin θ = 0.8 × 2 × sin 30°
    assert components(values["alpha_along_axes"]) == pytest.approx([0, 0, 0], abs=1e-12)
    assert values["omega_magnitude"] == pytest.approx(math.sqrt(0.64 + 4 + 3.2 * math.cos(math.radians(30))), abs=1e-12)
    # Body components of ω for 3-1-3 written out: (φ̇ sθ sψ + θ̇ cψ, φ̇ sθ cψ − θ̇ sψ, φ̇ cθ + ψ̇).
    t = values["t_s"]
    psi, theta = 2.0 * t, math.radians(30.0)
    assert np.abs(components(values["omega_body"]) - [0.8 * math.sin(theta) * math.sin(psi), 0.8 * math.sin(theta) * math.cos(psi), 0.8 * math.cos(theta) + 2.0]).max() < 2e-3
    assert components(values["recovered_rates"]) == pytest.approx([0.8, 0.0, 2.0], abs=1e-3)
    # The three parts chain head to tail from the origin and end where ω ends.
    segments = arrow_segments(client, "/rates")
    chain_end = segments[2][1] if len(segments) == 4 else segments[1][1]  # θ̇2 = 0: its arrow is not drawn
    omega_arrow = segments[-2]
    assert np.abs(chain_end - omega_arrow[1]).max() < 1e-6
    assert [m.value for m in scene.readout().marks["angle2_deg"]] == [-180.0, 0.0, 180.0]
    # Scrubbing: the motion is the time; a state from elsewhere resumes exactly there.
    scene.resume_from({"t_s": 2.5})
    assert scene.motion_state() == {"t_s": 2.5} and quantities(scene)["t_s"] == 2.5
    with pytest.raises(ValueError, match="finite"):
        scene.resume_from({"t_s": math.inf})
    scene.close()


def test_angle_rates_at_lock_says_the_rates_are_lost(client):
    scene = AngleRatesScene(client, preset(AngleRatesScene, "euler-lock"))
    values = quantities(scene)
    assert values["rate_gain"].startswith("unbounded") and values["recovered_rates"].startswith("the rates cannot be recovered here")
    assert "only θ̇1 + θ̇3" in scene.readout().message
    assert components(values["omega_world"]) == pytest.approx([0.0, 0.0, 1.5], abs=1e-12)  # (φ̇ + ψ̇) Z
    scene.close()
