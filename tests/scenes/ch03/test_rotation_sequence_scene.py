"""The rotation-sequence scene on a real (loopback) viser server, without a browser.

What it draws and reads out is checked against scipy's ``Rotation`` (an
independent implementation of intrinsic sequences), not against our own code.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from app.physics.core.parameters import ParameterError
from app.physics.math.rotations import rotation_matrix
from app.physics.math.rotations import rotate_vector
from app.scenes.ch03.rotation_sequence import (
    CYCLE_S,
    FRAME_AXIS_LENGTH,
    LOCK_COLOR,
    TIMELINE,
    TURN_COLORS,
    RotationSequenceScene,
    boxes_overlap,
    label_box_px,
    text_box,
    view_px,
)
from app.scenes.kit import FRAME_DT_S

PARAMETERS = RotationSequenceScene.parameters
PRESETS = {p.name: p for p in RotationSequenceScene.presets}


def quantities(scene) -> dict:
    """What the student reads in each row: the number, or the text where there is none."""
    return {q.name: q.value if q.value is not None else q.text for q in scene.readout().quantities}


def reference(params) -> Rotation:
    letters = "".join("XYZ"[int(a) - 1] for a in params["sequence"].split("-"))
    return Rotation.from_euler(letters, [params["angle1_deg"], params["angle2_deg"], params["angle3_deg"]], degrees=True)


@pytest.mark.parametrize("preset", list(PRESETS))
def test_readout_is_the_attitude_scipy_computes(client, preset):
    params = PARAMETERS.validate(PRESETS[preset].values)
    scene = RotationSequenceScene(client, params)
    values = quantities(scene)
    expected = reference(params)
    # Angle and quaternion: the readout carries full precision; 1e-9 allows rounding only.
    assert values["rotation_angle_deg"] == pytest.approx(math.degrees(expected.magnitude()), abs=1e-9)
    x, y, z, w = expected.as_quat()
    q = np.array([values[f"q_{c}"] for c in "wxyz"])
    assert min(np.abs(q - [w, x, y, z]).max(), np.abs(q + [w, x, y, z]).max()) < 1e-12
    # Rows are shown to 4 decimals.
    rows = np.array([[float(v) for v in values[f"R_row{i}"].split()] for i in (1, 2, 3)])
    assert np.abs(rows - expected.as_matrix()).max() <= 5e-5
    axis = np.array([float(v) for v in values["axis"].split()])
    assert np.abs(axis - expected.as_rotvec() / expected.magnitude()).max() <= 5e-5
    scene.close()


def test_gimbal_lock_is_highlighted_and_explained(client):
    params = PARAMETERS.validate(PRESETS["gimbal-lock"].values)  # 3-2-1, θ = (30°, 90°, 10°)
    scene = RotationSequenceScene(client, params)
    readout = scene.readout()
    values = quantities(scene)
    assert values["gimbal_lock_distance_deg"] < 1e-12 and values["rate_gain"] == "unbounded"
    assert "Only θ1 − θ3 = 20° is determined" in readout.message
    assert [m.as_dict() for m in readout.marks["angle2_deg"]] == [{"value": -90.0, "label": "gimbal lock"}, {"value": 90.0, "label": "gimbal lock"}]
    assert scene.turn_labels[2].text == "turn 3: θ3 = 10° about x″ (on the line of Z: gimbal lock)"
    assert [tuple(np.asarray(a.colors)) for a in scene.turn_axes] == [LOCK_COLOR, TURN_COLORS[1], LOCK_COLOR]
    # The angles read back differ from the ones typed but have the same θ1 − θ3 and the same [R].
    recovered = [float(v) for v in values["recovered_angles_deg"].split(",")]
    assert recovered[0] - recovered[2] == pytest.approx(20.0, abs=0.01) and recovered[1] == pytest.approx(90.0, abs=0.01)
    assert np.abs(Rotation.from_euler("ZYX", recovered, degrees=True).as_matrix() - reference(params).as_matrix()).max() < 1e-3
    # Turn 1's axis (Z) and turn 3's axis (x″) are drawn on one line.
    n1, n3 = (np.asarray(scene.turn_axes[k].points, float)[0, 1] for k in (0, 2))
    assert abs(abs(n1 @ n3) / (np.linalg.norm(n1) * np.linalg.norm(n3)) - 1.0) < 1e-6

    # One step away from lock, the message warns instead, and the highlight goes.
    scene.set_params(PARAMETERS.validate({"angle2_deg": 85.0}, base=params))
    assert "Near gimbal lock (5° away)" in scene.readout().message
    # 3-2-1 body rates written out: ωx = θ̇3 − θ̇1 s2, ωy = θ̇2 c3 + θ̇1 c2 s3, ωz = −θ̇2 s3 + θ̇1 c2 c3.
    t2, t3 = math.radians(85.0), math.radians(10.0)
    J = np.array([
        [-math.sin(t2), 0.0, 1.0],
        [math.cos(t2) * math.sin(t3), math.cos(t3), 0.0],
        [math.cos(t2) * math.cos(t3), -math.sin(t3), 0.0],
    ])
    assert quantities(scene)["rate_gain"] == pytest.approx(1.0 / np.linalg.svd(J, compute_uv=False)[-1], rel=1e-12)
    assert "gimbal lock" not in scene.turn_labels[0].text + scene.turn_labels[2].text
    scene.close()


def test_animation_applies_the_turns_in_order(client):
    params = PARAMETERS.validate({"sequence": "2-3-1", "angle1_deg": 50.0, "angle2_deg": -40.0, "angle3_deg": 120.0})
    scene = RotationSequenceScene(client, params)
    final = reference(params).as_matrix()
    dt = 1.0 / 30.0
    # Halfway through the sweep of turn 2: x′y′z′ is complete, x″y″z″ is moving, xyz not yet shown.
    t_mid_turn2 = sum(d for *_, d in TIMELINE[:3]) + 0.5 * TIMELINE[3][2]
    for _ in range(round(t_mid_turn2 / dt)):
        scene.advance(dt)
    assert scene.frames[1].visible and scene.frames[2].visible and not scene.frames[3].visible
    assert np.abs(rotation_matrix(np.asarray(scene.frames[1].wxyz)) - Rotation.from_euler("Y", 50, degrees=True).as_matrix()).max() < 1e-12
    R2 = rotation_matrix(np.asarray(scene.frames[2].wxyz))
    swept_deg = math.degrees(math.acos(np.clip((np.trace(Rotation.from_euler("Y", 50, degrees=True).as_matrix().T @ R2) - 1) / 2, -1, 1)))
    assert 0.0 < swept_deg < 40.0  # partway through θ2 = −40°
    # The arc ends at the tip of the turning frame's axis (turn 2 is about z′, the arc follows x″).
    arc_end = np.asarray(scene.arcs[1].points, float)[-1, 1]
    assert np.abs(arc_end - R2[:, 0] * FRAME_AXIS_LENGTH[2]).max() < 1e-6  # float32 points
    # In the final hold the body frame is the full sequence.
    t_hold = sum(d for *_, d in TIMELINE[:6]) + 1.0
    for _ in range(round((t_hold - t_mid_turn2) / dt)):
        scene.advance(dt)
    assert all(frame.visible for frame in scene.frames)
    assert np.abs(rotation_matrix(np.asarray(scene.frames[3].wxyz)) - final).max() < 1e-12
    # The loop starts again with only the fixed frame.
    for _ in range(round((CYCLE_S - t_hold + 0.3) / dt)):
        scene.advance(dt)
    assert not any(frame.visible for frame in scene.frames[1:])
    scene.close()


def test_static_stage_holds_the_chosen_frame(client):
    params = PARAMETERS.validate({"sequence": "1-2-1", "angle1_deg": 20.0, "angle2_deg": 70.0, "angle3_deg": -35.0, "stage": "after turn 2"})
    scene = RotationSequenceScene(client, params)
    for _ in range(100):
        scene.advance(1.0 / 30.0)
    assert scene.frames[2].visible and not scene.frames[3].visible
    expected = Rotation.from_euler("XY", [20.0, 70.0], degrees=True).as_matrix()
    assert np.abs(rotation_matrix(np.asarray(scene.frames[2].wxyz)) - expected).max() < 1e-12
    scene.close()


@pytest.mark.parametrize(
    "raw, field",
    [({"sequence": "3-3-1"}, "sequence"), ({"angle2_deg": 200.0}, "angle2_deg"), ({"stage": "after turn 4"}, "stage"), ({"angle1_deg": float("nan")}, "angle1_deg")],
)
def test_bad_input_names_the_field(raw, field):
    with pytest.raises(ParameterError) as info:
        PARAMETERS.validate(raw)
    assert info.value.field == field


def drawn_label_boxes(scene) -> dict[str, np.ndarray]:
    """Text boxes (px, default view) of every shown name: the frames' axis names at their tips and the turns' labels."""
    camera = scene.camera_view()
    boxes = {}
    for n, frame in enumerate(scene.frames):
        if not frame.visible:
            continue
        R_tip = np.asarray(frame.wxyz, float)
        for handle in (scene.client.scene.handles[f"/frame{n}/label_{axis}"] for axis in range(3)):
            tip = np.asarray(frame.position, float) + rotate_vector(R_tip, np.asarray(handle.position, float))
            boxes[handle.text] = text_box(view_px(*camera, tip[None, :])[0], label_box_px(handle.text, handle.font_screen_scale), handle.anchor)
    for k, label in enumerate(scene.turn_labels):
        if label.visible:
            boxes[f"turn {k + 1}"] = text_box(view_px(*camera, np.asarray(label.position, float)[None, :])[0], label_box_px(label.text, 1.0), label.anchor)
    return boxes


@pytest.mark.parametrize("preset", list(PRESETS))
def test_axis_names_never_cover_each_other_during_the_motion(client, preset):
    """Frames share the axis of the turn between them and axes swing through the line of sight, so tips meet on the
    screen (y′ and y″ were 5 px apart in the aircraft sequence, x and z of the body 4 px in the classic one). At every
    frame of a whole loop, in the default view of the lesson's 520 px tall viewer, no name's text box (7 px a
    character, 15 px tall at font scale 1: the 5.3 × 12 px drawn, padded) shares a pixel with another's or with a
    turn's label, and the names do stay at their own axis tips (the side of the text is what moves)."""
    params = PARAMETERS.validate({**PRESETS[preset].values, "stage": "animate"})
    scene = RotationSequenceScene(client, params)
    tips = {h.text: np.asarray(h.position, float) for name, h in client.scene.handles.items() if "/label_" in name}
    shown_together = 0
    for _ in range(round(CYCLE_S / FRAME_DT_S)):
        boxes = drawn_label_boxes(scene)
        names = list(boxes)
        for i, a in enumerate(names):
            for b in names[i + 1 :]:
                assert boxes_overlap(boxes[a], boxes[b]) == 0.0, (a, b, scene.t_s)
        shown_together = max(shown_together, len(names))
        scene.advance(FRAME_DT_S)
    assert shown_together == 15  # all four frames' names and the three turns' labels were checked together
    assert {h.text: np.asarray(h.position, float) for name, h in client.scene.handles.items() if "/label_" in name}.keys() == tips.keys()
    for name, h in client.scene.handles.items():
        if "/label_" in name:
            np.testing.assert_array_equal(h.position, tips[h.text])
    scene.close()
