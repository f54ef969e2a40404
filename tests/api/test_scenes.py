"""Scenes API, per-session parameters, the viewer page and the websocket relay."""

from __future__ import annotations

import itertools

import msgspec
import pytest
import viser
from websockets.exceptions import InvalidStatus
from websockets.sync.client import connect

from app.physics.systems.ch01 import projectile, radar_tracking, robot_arm_cable
from app.scenes.viser_boundary import viewer_camera_message
from app.web.relay import is_blocked_message

_ids = itertools.count()


def new_session() -> str:
    """A fresh valid session id (8-64 of [A-Za-z0-9_-]) so tests never share state."""
    return f"test-session-{next(_ids):04d}"


def put(client, scene_id, session_id, params):
    return client.put(f"/api/scenes/{scene_id}/sessions/{session_id}", json={"params": params})


def test_list_scenes(client):
    response = client.get("/api/scenes")
    assert response.status_code == 200
    scenes = {s["id"]: s for s in response.json()}
    expected = {
        "robot-arm-cable": robot_arm_cable.INPUTS,
        "radar-tracking": radar_tracking.INPUTS,
        "projectile-drag": projectile.INPUTS,
    }
    assert set(expected) <= set(scenes)
    for scene_id, inputs in expected.items():
        scene = scenes[scene_id]
        assert scene["title"] and scene["chapter"] == 1
        assert [p["name"] for p in scene["parameters"]] == [p.name for p in inputs.parameters]
        for p in scene["parameters"]:
            assert {"name", "unit", "default", "min", "max", "description"} <= set(p)
            assert p["min"] <= p["default"] <= p["max"]
            assert p["description"]


def test_put_merges_into_the_session(client):
    sid = new_session()
    response = put(client, "robot-arm-cable", sid, {"theta_deg": 10})
    assert response.status_code == 200
    body = response.json()
    assert body["scene_id"] == "robot-arm-cable" and body["session_id"] == sid
    assert body["params"] == {**robot_arm_cable.INPUTS.defaults(), "theta_deg": 10.0}
    body = put(client, "robot-arm-cable", sid, {"tension_N": 800}).json()
    assert body["params"] == {**robot_arm_cable.INPUTS.defaults(), "theta_deg": 10.0, "tension_N": 800.0}


@pytest.mark.parametrize(
    ("params", "field"),
    [
        ({"theta_deg": 400}, "theta_deg"),
        ({"tension_N": -1}, "tension_N"),
        ({"theta_deg": "ten"}, "theta_deg"),
        ({"no_such": 1}, "no_such"),
        ({"theta_deg": 0, "gamma_deg": 0, "AB_m": 2.0, "BC_m": 1.5, "D_x_m": 3.5}, "D_x_m"),
    ],
)
def test_invalid_put_is_422_and_changes_nothing(client, params, field):
    sid = new_session()
    before = put(client, "robot-arm-cable", sid, {"theta_deg": 10, "gamma_deg": 0}).json()["params"]
    response = put(client, "robot-arm-cable", sid, params)
    assert response.status_code == 422
    assert field in response.json()["detail"][0]["loc"]
    assert put(client, "robot-arm-cable", sid, {}).json()["params"] == before


def test_invalid_put_with_nan_is_422_and_changes_nothing(client):
    sid = new_session()
    before = put(client, "radar-tracking", sid, {"t_s": 3.0}).json()["params"]
    response = client.put(
        f"/api/scenes/radar-tracking/sessions/{sid}",
        content='{"params": {"dt_s": NaN}}',
        headers={"content-type": "application/json"},
    )
    assert response.status_code == 422
    assert "dt_s" in response.json()["detail"][0]["loc"]
    assert put(client, "radar-tracking", sid, {}).json()["params"] == before


def test_invalid_put_for_another_scene_leaves_the_session_alone(client):
    sid = new_session()
    before = put(client, "robot-arm-cable", sid, {"theta_deg": 10}).json()["params"]
    assert put(client, "radar-tracking", sid, {"t_s": 999}).status_code == 422
    assert put(client, "robot-arm-cable", sid, {}).json()["params"] == before


def test_sessions_are_independent(client):
    a, b = new_session(), new_session()
    assert put(client, "robot-arm-cable", a, {"theta_deg": 10}).status_code == 200
    assert put(client, "robot-arm-cable", b, {"theta_deg": -70}).status_code == 200
    assert put(client, "robot-arm-cable", a, {}).json()["params"]["theta_deg"] == 10.0
    assert put(client, "robot-arm-cable", b, {}).json()["params"]["theta_deg"] == -70.0


@pytest.mark.parametrize("session_id", ["x", "short", "a" * 65, "../etc", "..%2Fetc", "bad%20id%20here", "bad.id.here"])
def test_malformed_session_id_is_refused(client, session_id):
    response = client.put(f"/api/scenes/robot-arm-cable/sessions/{session_id}", json={"params": {}})
    assert response.status_code in (404, 422), (session_id, response.status_code)


def test_unknown_scene_is_404(client):
    assert put(client, "no-such-scene", new_session(), {}).status_code == 404


def test_extra_body_key_is_422(client):
    response = client.put(
        f"/api/scenes/robot-arm-cable/sessions/{new_session()}", json={"params": {}, "foo": 1}
    )
    assert response.status_code == 422
    assert "foo" in response.json()["detail"][0]["loc"]


def test_viewer_page_is_the_viser_client(client):
    response = client.get(f"/viewer/robot-arm-cable/{new_session()}/")
    assert response.status_code == 200
    assert response.headers["content-type"].startswith("text/html")
    assert response.text.lstrip().lower().startswith("<!doctype html>")
    assert "<script" in response.text


@pytest.mark.parametrize("path", ["/viewer/no-such-scene/abcdefgh12/", "/viewer/robot-arm-cable/x/"])
def test_viewer_page_for_unknown_scene_or_bad_session_is_404(client, path):
    assert client.get(path).status_code == 404


def test_relay_accepts_viser_subprotocol_and_forwards_binary_frames(client):
    protocol = "viser-v" + viser.__version__
    session_id = new_session()
    assert client.put(f"/api/scenes/robot-arm-cable/sessions/{session_id}", json={"params": {}}).status_code == 200
    with connect(client.websocket_url(f"/viewer/robot-arm-cable/{session_id}"), subprotocols=[protocol], open_timeout=20) as ws:  # type: ignore[list-item]
        assert ws.subprotocol == protocol
        ws.send(viewer_camera_message())
        message = ws.recv(timeout=20)
        assert isinstance(message, bytes) and message


def refused_status(client, path: str, subprotocols: list[str] | None) -> int:
    """The HTTP status of a websocket handshake the server refuses before accepting it."""
    with pytest.raises(InvalidStatus) as refused:
        with connect(client.websocket_url(path), subprotocols=subprotocols, open_timeout=20):  # type: ignore[arg-type]
            pass
    return refused.value.response.status_code


def test_relay_refuses_a_connection_without_the_subprotocol(client):
    session_id = new_session()
    assert client.put(f"/api/scenes/robot-arm-cable/sessions/{session_id}", json={"params": {}}).status_code == 200
    assert refused_status(client, f"/viewer/robot-arm-cable/{session_id}", None) == 403


@pytest.mark.parametrize("path", ["/viewer/no-such-scene/abcdefgh12", "/viewer/robot-arm-cable/x", "/viewer/robot-arm-cable/never-opened-1234"])
def test_relay_refuses_unknown_scene_bad_or_unopened_session(client, path):
    assert refused_status(client, path, ["viser-v" + viser.__version__]) == 403


def test_share_url_requests_are_blocked_and_others_pass():
    encode = msgspec.msgpack.encode
    assert is_blocked_message(encode({"type": "ShareUrlRequest"}))
    assert is_blocked_message(encode({"type": "ShareUrlDisconnect"}))
    camera = {"type": "ViewerCameraMessage", "wxyz": [1.0, 0.0, 0.0, 0.0], "position": [0.0, 0.0, 1.0], "fov": 1.0}
    assert not is_blocked_message(encode(camera))
    # A message that merely mentions ShareUrl in a value is not a share request.
    assert not is_blocked_message(encode({"type": "GuiUpdateMessage", "value": "ShareUrlRequest"}))
    assert not is_blocked_message(b"\xc1ShareUrlRequest garbage \xff")
    assert not is_blocked_message(b"")
    assert not is_blocked_message(encode(["ShareUrlRequest"]))
