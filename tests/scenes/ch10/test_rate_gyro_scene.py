"""The rate gyro's scale: the numbers a student reads are where the pointer stops for that input rate.

In the steady state β = G Ω (G = I_a ω_s / k); a numbered tick for Ω must sit where the indicator needle's tip is
at that β, to round-off (1e-12 m: a few float64 operations on numbers of order 1). Only the ends and zero are
numbered, in full-size type, so the numbers cannot run into each other on the short arc. The scale once stood on a
case wall that turned with the table and was seen edge-on; now it is on an indicator fixed in space, facing the
default camera, whose needle the pickoff turns by the gimbal's own β.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from app.physics.math.rotations import rotate_vector, rotation_matrix
from app.physics.systems.ch10 import rate_gyro as physics
from app.scenes.ch10.rate_gyro import (
    DIAL_FACE_X,
    MAX_SCALE_RAD,
    MIN_SCALE_RAD,
    NEEDLE_LENGTH,
    SCALE_LABEL_GAP,
    SCALE_LABEL_SIZE,
    RateGyroScene,
    indicator_pose,
)
from app.scenes.kit import FRAME_DT_S

#: Least horizontal distance, in the default view, between the "0" and an end number's anchor, as the tangent of the
#: angle seen from the camera. The end numbers run outwards from their anchors and the "0" is centred on its own, so
#: this gap is what keeps them apart: 0.04 is 19 px in a 520 px tall viewer (vertical field of view 1 rad, so
#: 260 px / tan 0.5 = 476 px per unit), more than twice the half-width of a "0" and its label padding (~8 px).
MIN_NUMBER_GAP = 0.04


def scale_labels(client) -> dict[str, object]:
    return {name: handle for name, handle in client.scene.handles.items() if re.fullmatch(r"/indicator/scale/t\d+", name) and not handle._impl.removed}


def label_rate(text: str) -> float:
    return 0.0 if text == "0" else float(re.match(r"([+−][\d.e+]+)", text).group(1).replace("−", "-"))


def view_coordinates(scene, points_world: np.ndarray) -> np.ndarray:
    """(n, 2) screen coordinates (right, up) of ``points_world`` (n, 3) as tangents of the angles off the default
    camera's line of sight (a pinhole projection: divide by the depth along it)."""
    camera, look_at = (np.asarray(v, float) for v in scene.camera_view())
    forward = (look_at - camera) / np.linalg.norm(look_at - camera)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    offsets = np.asarray(points_world, float) - camera
    return np.column_stack([offsets @ right, offsets @ up]) / (offsets @ forward)[:, None]


@pytest.mark.parametrize("rate", [0.5, -0.3, 2.0])
def test_numbered_ticks_sit_where_the_pointer_reads_their_rate(client, rate):
    scene = RateGyroScene(client, RateGyroScene.parameters.validate({"input_rate_rad_s": rate}))
    gain = physics.steady_gain_s(scene.params)
    labels = scale_labels(client)
    texts = sorted(handle.text for handle in labels.values())
    assert len(labels) == 3 and "0" in texts and all(t == "0" or t.endswith(" rad/s") for t in texts)
    for handle in labels.values():
        beta = gain * label_rate(handle.text)
        expected = np.array([DIAL_FACE_X, -math.sin(beta), math.cos(beta)]) * np.array([1.0, NEEDLE_LENGTH + SCALE_LABEL_GAP, NEEDLE_LENGTH + SCALE_LABEL_GAP])
        np.testing.assert_allclose(handle.position, expected, rtol=0, atol=1e-12)
        assert handle.font_screen_scale == SCALE_LABEL_SIZE >= 1.0
    ends = [label_rate(t) for t in texts if t != "0"]
    assert sorted(ends) == pytest.approx([-max(ends), max(ends)]) and max(ends) >= abs(rate) - 1e-12  # the scale reaches Ω₀
    scene.close()


@pytest.mark.parametrize("preset", RateGyroScene.presets, ids=lambda p: p.name)
def test_indicator_stays_put_faces_the_camera_and_its_needle_reads_beta(client, preset):
    """Over a whole on/off cycle of the table (or 6 s of the sine): the indicator never moves, its face is square to
    the default line of sight, the needle is turned by exactly the gimbal's β (the same quaternion) and reads the β
    of the readout, and in the default view the end numbers stay MIN_NUMBER_GAP to either side of the "0".
    The needle's tip is checked to 3e-5: viser's setter keeps the old orientation when the new one is np.allclose
    to it (rtol 1e-5 on components of size ≤ 1, atol 1e-8), so the drawn quaternion may lag by up to ~1e-5 per
    component, i.e. ≤ 2e-5 in β; a needle read against the wrong tick would be off by ≥ G × a tick step ≈ 0.1."""
    scene = RateGyroScene(client, RateGyroScene.parameters.validate(preset.values))
    indicator = client.scene.handles["/indicator"]
    centre, wxyz = indicator_pose(*scene.camera_view())
    np.testing.assert_allclose(indicator.position, centre, rtol=0, atol=1e-12)
    sight = centre - np.asarray(scene.camera_view()[0])
    face_normal = rotation_matrix(np.asarray(indicator.wxyz, float))[:, 0]
    assert np.linalg.norm(np.cross(face_normal, sight / np.linalg.norm(sight))) < 1e-12 and face_normal @ sight > 0.0
    labels = scale_labels(client)
    world = {handle.text: centre + rotate_vector(wxyz, np.asarray(handle.position, float)) for handle in labels.values()}
    start = {name: (tuple(h.position), h.text) for name, h in labels.items()}
    frames = round(2.0 * scene._hold_s / FRAME_DT_S) if preset.values["input_kind"] == "step" else round(6.0 / FRAME_DT_S)
    turned = 0.0
    for frame in range(frames):
        scene.advance(FRAME_DT_S)
        if frame % 15:
            continue
        table_angle = 2.0 * math.atan2(client.scene.handles["/table"].wxyz[3], client.scene.handles["/table"].wxyz[0])
        turned = max(turned, abs(table_angle))
        np.testing.assert_allclose(indicator.position, centre, rtol=0, atol=1e-12)
        np.testing.assert_allclose(indicator.wxyz, wxyz, rtol=0, atol=1e-12)
        assert {name: (tuple(h.position), h.text) for name, h in scale_labels(client).items()} == start
        beta = next(q.value for q in scene.readout().quantities if q.name == "beta_rad")
        np.testing.assert_array_equal(scene.needle.wxyz, scene.gimbal.wxyz)
        needle_tip = rotate_vector(np.asarray(scene.needle.wxyz, float), np.array([0.0, 0.0, 1.0]))
        np.testing.assert_allclose(needle_tip, [0.0, -math.sin(beta), math.cos(beta)], rtol=0, atol=3e-5)
    assert turned > 0.05  # the table did turn while the indicator held still
    screen = {text: view_coordinates(scene, point[None, :])[0] for text, point in world.items()}
    zero = screen.pop("0")
    for text, point in screen.items():
        assert abs(point[0] - zero[0]) > MIN_NUMBER_GAP, (text, point, zero)
        assert (point[0] > zero[0]) == (label_rate(text) * physics.steady_gain_s(scene.params) > 0.0)  # +β swings right
    scene.close()


@pytest.mark.parametrize("stiffness", [50.0, 1000.0])
def test_a_small_gain_widens_the_scale_instead_of_crowding_it(client, stiffness):
    """With a stiff spring the steady β for ±2Ω₀ is under a degree: the scale is widened to four round steps whose
    ends are MIN_SCALE_RAD to 2 MIN_SCALE_RAD (a nice step at most doubles) from zero."""
    scene = RateGyroScene(client, RateGyroScene.parameters.validate({"stiffness_N_m_rad": stiffness}))
    gain = physics.steady_gain_s(scene.params)
    ends = [abs(label_rate(h.text)) for h in scale_labels(client).values() if h.text != "0"]
    assert len(ends) == 2 and MIN_SCALE_RAD * (1 - 1e-12) <= gain * ends[0] <= min(2.0 * MIN_SCALE_RAD, MAX_SCALE_RAD) + 1e-12
    scene.close()
