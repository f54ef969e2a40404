"""The torque-free-body scene on a real (loopback) viser server, without a browser.

A stand-in client carries the server's own scene and GUI APIs, so the scene's build,
per-frame drawing and readout run exactly as for a viewer; what it drew is read back
from its node handles and checked against the physics.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.math.rotations import rotation_matrix
from app.physics.systems.ch10 import torque_free_body as tfb
from app.scenes.ch10.torque_free_body import BOX_FILL, PRESETS, TorqueFreeBodyScene
from app.scenes.kit import FRAME_DT_S

PARAMETERS = TorqueFreeBodyScene.parameters
TENNIS = next(p for p in PRESETS if p.name == "tennis-racket")


def quantities(scene) -> dict:
    return {q.name: q for q in scene.readout().quantities}


def test_tennis_racket_with_ghost_for_20_s(client):
    scene = TorqueFreeBodyScene(client, PARAMETERS.validate({**TENNIS.values, "ghost": "on"}))
    for _ in range(600):
        scene.advance(FRAME_DT_S)
    body = tfb.motion(scene.params)
    t = 600 * FRAME_DT_S
    readout = quantities(scene)
    assert readout["t_s"].value == pytest.approx(20.0, rel=1e-12) and readout["t_s"].unit == "s"
    assert readout["energy"].value == pytest.approx(0.5 * np.sum(body.inertia * body.omega0_body**2), rel=1e-15)
    assert readout["angular_momentum"].value == pytest.approx(np.linalg.norm(body.inertia * body.omega0_body), rel=1e-15)
    assert readout["period"].value == body.period_s and readout["period"].unit == "s"
    assert readout["intermediate_axis"].text.startswith("2 ")
    assert readout["circled_axis"].text == "axis 3 (largest I)"
    flips = tfb.flip_times_s(body, 40.0)
    upcoming = flips[flips > t][0]
    assert readout["next_flip"].value == pytest.approx(upcoming - t, abs=1e-9)
    # The ghost (RK4 on the solver core) stayed within 1e-7 rad of the closed form (measured ~2e-9).
    assert readout["ghost_method"].text.startswith("RK4")
    assert 0.0 < readout["ghost_attitude_difference"].value < 1e-7
    assert "turns over every" in scene.readout().message
    assert [m.as_dict() for m in scene.readout().marks["I3"]] == [{"value": pytest.approx(0.0025 + 0.0049), "label": "I1+I2"}]

    # What was drawn is the physics at t = 20 s.
    q = body.quaternion(np.array([t]))[0]
    assert tfb.attitude_difference_rad(np.asarray(scene.body_frame.wxyz), q) < 1e-12
    assert tfb.attitude_difference_rad(np.asarray(scene.ghost_frame.wxyz), q) < 1e-7
    assert scene.ghost_frame.visible
    contact = np.asarray(scene.contact.position)
    omega_world = rotation_matrix(q) @ body.omega_body(np.array([t]))[0]
    assert contact == pytest.approx(omega_world * scene.scale, abs=1e-12)
    _, distance = tfb.invariable_plane(body)
    assert contact[2] == pytest.approx(-distance * scene.scale, rel=1e-12)  # on the plane …
    shown_axes = np.asarray(scene.ellipsoid.scale)
    assert max(shown_axes) == pytest.approx(1.0)
    body_point = rotation_matrix(q).T @ contact
    assert np.sum((body_point / shown_axes) ** 2) == pytest.approx(1.0, rel=1e-6)  # … and on the drawn ellipsoid (float32 scale)
    # Each trail grows a node per 10 new points (601 points: frames 0 to 600) …
    assert scene.herpolhode_trail.chunk_count == 60
    # … but the polhode stops once ω has gone round once (plus two nodes of overlap).
    polhode_points = sum(1 for k in range(601) if k * FRAME_DT_S <= body.period_s + 20 * FRAME_DT_S)
    assert polhode_points < 601 and scene.polhode_trail.chunk_count == (polhode_points - 1) // 10
    scene.close()


def test_box_fits_its_ellipsoid_and_new_parameters_restart_the_motion(client):
    scene = TorqueFreeBodyScene(client, PARAMETERS.defaults())
    for _ in range(45):
        scene.advance(FRAME_DT_S)
    readout = quantities(scene)
    assert "ghost_attitude_difference" not in readout and not scene.ghost_frame.visible
    assert readout["next_flip"].value is None and readout["next_flip"].text == "no flips in this motion"
    assert scene.readout().message.startswith("The polhode circles axis 3")
    scene.set_params(PARAMETERS.validate({"I1": 0.003}, base=scene.params))
    assert scene.t_s == 0.0 and scene.body.inertia[0] == 0.003
    assert np.asarray(scene.body_frame.wxyz) == pytest.approx(scene.body.q0, abs=1e-15)
    sides = np.asarray(scene.client.scene.handles["/body/box"].dimensions)
    shown_axes = np.asarray(scene.ellipsoid.scale)
    assert math.sqrt(np.sum((0.5 * sides / shown_axes) ** 2)) == pytest.approx(BOX_FILL, rel=1e-6)
    # Box proportions are the uniform box's with these moments.
    expected = tfb.uniform_box_sides(scene.body.inertia)
    assert sides / sides[0] == pytest.approx(expected / expected[0], rel=1e-6)
    scene.close()


def test_steady_rotation_draws_and_says_so(client):
    scene = TorqueFreeBodyScene(client, PARAMETERS.validate({"omega0_rad_s": [0.0, 0.0, 3.0]}))
    for _ in range(40):
        scene.advance(FRAME_DT_S)
    readout = quantities(scene)
    assert readout["period"].value is None and readout["period"].text == "none: ω is constant"
    assert "Steady rotation" in scene.readout().message
    contact = np.asarray(scene.contact.position)
    assert contact == pytest.approx([0.0, 0.0, -scene.plane_distance_rad_s * scene.scale], abs=1e-12)
    scene.close()


@pytest.mark.parametrize("preset", PRESETS, ids=lambda p: p.name)
def test_polhode_and_herpolhode_are_named_on_opposite_sides_at_every_instant(client, preset):
    """The names once overlapped as the body turned (the polhode's rode on the body). Now both are fixed in space:
    the polhode's outside the ellipsoid to the camera's right, running right, the herpolhode's to the left of the
    plane's curve, running left; over a whole period of motion their anchors stay more than 1 display unit apart
    across the view (the ellipsoid being of size 1), whatever the body does."""
    from app.scenes.ch10.torque_free_body import POLHODE_LABEL_SIDE

    scene = TorqueFreeBodyScene(client, PARAMETERS.validate(preset.values))
    forward = np.subtract(scene.camera_look_at, scene.camera_position)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    np.testing.assert_allclose(POLHODE_LABEL_SIDE[:2] / np.linalg.norm(POLHODE_LABEL_SIDE), right[:2], atol=0.01)
    assert scene.polhode_label.anchor == "center-left" and scene.herpolhode_label.anchor == "center-right"
    for _ in range(90):
        scene.advance(FRAME_DT_S)
        polhode = np.asarray(scene.polhode_label.position) @ right
        herpolhode = np.asarray(scene.herpolhode_label.position) @ right
        assert polhode - herpolhode > 1.0
        assert polhode >= np.asarray(scene.contact.position) @ right  # ω's contact point is never right of the name
    scene.close()
