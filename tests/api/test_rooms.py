"""The classroom API: roles enforced by the server, room state, joining, polls, the room socket and the fan-out viewer.

One app (scenes in-process) for the module, its instructor key fixed. The role
test enumerates every route that requires the instructor from the app itself,
so a new instructor-only route cannot escape it, and tries each from a
student's request and every instructor action from a student's socket:
each is refused with 403 and the room is as it was.
"""

from __future__ import annotations

import json
import math
import secrets
import time
from collections.abc import Iterator

import pytest
import viser
from fastapi.routing import APIRoute
from fastapi.testclient import TestClient
from starlette.websockets import WebSocketDisconnect

from app.classroom import routes as rooms_api
from app.classroom.relay import ends_replay
from app.classroom.routes import require_instructor
from app.main import create_app
from app.physics.systems.ch10 import heavy_top as heavy_top_physics
from app.scenes.viser_boundary import viewer_camera_message
from app.settings import Settings
from tests.conftest import wait_until

KEY = "test-instructor-key-0123"
INSTRUCTOR = {"X-Instructor-Key": KEY}
VISER = [f"viser-v{viser.__version__}"]


@pytest.fixture(scope="module")
def client() -> Iterator[TestClient]:
    with TestClient(create_app(Settings(instructor_key=KEY))) as client:
        yield client


def heavy_top_lesson(client: TestClient) -> str:
    return next(lesson.id for lesson in client.app.state.catalogue.lessons.values() if "heavy-top" in lesson.scenes)


@pytest.fixture
def room(client) -> dict:
    answer = client.post("/api/rooms", json={"lesson_id": heavy_top_lesson(client), "scene_id": "heavy-top"}, headers=INSTRUCTOR)
    assert answer.status_code == 200, answer.text
    yield answer.json()
    client.delete(f"/api/rooms/{answer.json()['room_id']}", headers=INSTRUCTOR)


def state_of(client: TestClient, room_id: str) -> dict:
    return client.get(f"/api/rooms/{room_id}/state").json()


def join(client: TestClient, code: str, name: str = "") -> str:
    """Join from a new device (no device cookie: the one shared client would otherwise be one student)."""
    client.cookies.clear()
    answer = client.post("/api/rooms/join", json={"code": code.lower(), "name": name})  # codes are case-blind
    client.cookies.clear()
    assert answer.status_code == 200, answer.text
    return answer.json()["student_token"]


def instructor_routes() -> set[tuple[str, str]]:
    """(method, path) of every API route that depends on require_instructor (all are in the rooms router)."""
    out = set()
    for route in rooms_api.router.routes:
        if isinstance(route, APIRoute) and any(d.dependency is require_instructor for d in route.dependencies):
            out |= {(method, route.path) for method in route.methods}
    return out


def test_the_instructor_link_and_me(client):
    assert client.get("/api/me").json() == {"role": "student"}
    assert client.get("/api/me", headers=INSTRUCTOR).json() == {"role": "instructor"}
    wrong = client.get("/instructor", params={"key": "not-the-key-at-all"}, follow_redirects=False)
    assert wrong.status_code == 403 and "set-cookie" not in wrong.headers
    browser = TestClient(client.app)  # its own cookie jar; not entered: the app's lifespan (scene host) is the module's
    link = browser.get("/instructor", params={"key": KEY}, follow_redirects=False)
    assert link.status_code == 303 and "httponly" in link.headers["set-cookie"].lower()
    assert browser.get("/api/me").json() == {"role": "instructor"}  # the cookie, no header


def test_every_instructor_action_from_a_student_is_refused_and_changes_nothing(client, room):
    room_id = room["room_id"]
    poll = client.post(f"/api/rooms/{room_id}/polls", json={"question": "Which way?", "kind": "choice", "choices": ["left", "right"]}, headers=INSTRUCTOR).json()
    token = join(client, room["code"])
    before = state_of(client, room_id)
    tried = {
        ("POST", "/api/rooms"): ("/api/rooms", {"lesson_id": before["lesson_id"]}),
        ("DELETE", "/api/rooms/{room_id}"): (f"/api/rooms/{room_id}", None),
        ("POST", "/api/rooms/{room_id}/state"): (f"/api/rooms/{room_id}/state", {"playing": False, "params": {"spin_rad_s": 1.0}}),
        ("GET", "/api/rooms/{room_id}/polls/ready"): (f"/api/rooms/{room_id}/polls/ready", None),
        ("POST", "/api/rooms/{room_id}/polls"): (f"/api/rooms/{room_id}/polls", {"question": "Mine?", "kind": "number", "unit": "m"}),
        ("POST", "/api/rooms/{room_id}/polls/{poll_id}"): (f"/api/rooms/{room_id}/polls/{poll['poll_id']}", {"open": False}),
        ("GET", "/api/rooms/{room_id}/polls/{poll_id}/results"): (f"/api/rooms/{room_id}/polls/{poll['poll_id']}/results", None),
        ("GET", "/api/rooms/{room_id}/polls/{poll_id}/results.csv"): (f"/api/rooms/{room_id}/polls/{poll['poll_id']}/results.csv", None),
        ("GET", "/api/rooms/{room_id}/students"): (f"/api/rooms/{room_id}/students", None),
        ("DELETE", "/api/rooms/{room_id}/students/{student_id}"): (f"/api/rooms/{room_id}/students/s1", None),
    }
    assert set(tried) == instructor_routes()  # every instructor-only route of the app is tried below
    disguises = [{}, {"X-Student-Token": token}, {"X-Instructor-Key": KEY[:-1] + "x"}, {"Cookie": "dynlab_instructor=" + "0" * 64}]
    for (method, _), (url, body) in tried.items():
        for headers in disguises:
            answer = client.request(method, url, json=body, headers=headers)
            assert answer.status_code == 403, (method, url, headers, answer.text)
    with client.websocket_connect(f"/api/rooms/{room_id}/socket") as socket:
        assert json.loads(socket.receive_text())["type"] == "state"
        socket.send_text(json.dumps({"type": "hello", "student_token": token, "following": True}))
        for action in (
            {"type": "set_state", "playing": False, "time_scale": 2.0, "mode": "explore"},
            {"type": "open_poll", "question": "Mine?", "kind": "number", "unit": "m"},
            {"type": "update_poll", "poll_id": poll["poll_id"], "reveal": True},
        ):
            socket.send_text(json.dumps(action))
            reply = next(m for m in (json.loads(socket.receive_text()) for _ in range(20)) if m["type"] == "error")
            assert reply["status"] == 403 and reply["action"] == action["type"]
    after = state_of(client, room_id)
    for name in ("lesson_id", "scene_id", "params", "playing", "time_scale", "mode", "revision", "poll"):
        assert after[name] == before[name], name
    assert client.get(f"/api/rooms/{room_id}/polls/{poll['poll_id']}/results", headers=INSTRUCTOR).json()["open"] is True


def test_state_changes_are_checked_whole_and_drive_the_stage(client, room):
    room_id, host = room["room_id"], client.app.state.scene_host
    stage = f"room-{room_id}"
    state = state_of(client, room_id)
    assert (state["scene_id"], state["mode"], state["playing"], state["time_scale"]) == ("heavy-top", "follow", True, 1.0)
    changed = client.post(f"/api/rooms/{room_id}/state", json={"params": {"spin_rad_s": 42.0}, "playing": False}, headers=INSTRUCTOR).json()
    assert changed["params"]["spin_rad_s"] == 42.0 and changed["playing"] is False and changed["revision"] == state["revision"] + 1
    assert host.session_params(stage)["spin_rad_s"] == 42.0 and host.playback(stage)["playing"] is False
    for bad, field in (
        ({"params": {"spin_rad_s": math.inf}}, "params"),
        ({"params": {"mass_kg": -1.0}, "playing": True}, "params"),
        ({"time_scale": 9.0}, "time_scale"),
        ({"mode": "lecture"}, "mode"),
        ({"scene_id": "four-bar"}, "scene_id"),
        ({"lesson_id": "no-such-lesson"}, "lesson_id"),
        ({"preset": "no-such-preset"}, "preset"),
        ({"colour": "red"}, "colour"),
    ):
        # json.dumps writes Infinity (not strict JSON, but what a careless client sends): the server must refuse it.
        answer = client.post(f"/api/rooms/{room_id}/state", content=json.dumps(bad), headers={**INSTRUCTOR, "Content-Type": "application/json"})
        assert answer.status_code == 422, bad
        assert field in json.dumps(answer.json()["detail"]), (bad, answer.json())
        now = state_of(client, room_id)
        assert (now["revision"], now["params"], now["playing"]) == (changed["revision"], changed["params"], False), bad
    reset = client.post(f"/api/rooms/{room_id}/state", json={"reset": True, "playing": True}, headers=INSTRUCTOR).json()
    assert reset["reset_count"] == state["reset_count"] + 1 and host.live_readout("heavy-top", stage)["t_s"] < 0.5
    other = next(l for l in client.app.state.catalogue.lessons.values() if l.scene and l.scene != "heavy-top" and host.scenes[l.scene].presets)
    moved = client.post(f"/api/rooms/{room_id}/state", json={"lesson_id": other.id}, headers=INSTRUCTOR).json()
    assert moved["scene_id"] == other.scene and moved["params"] == host.scenes[other.scene].parameters.defaults()
    preset = host.scenes[other.scene].presets[-1]
    with_preset = client.post(f"/api/rooms/{room_id}/state", json={"preset": preset.name}, headers=INSTRUCTOR).json()
    assert all(with_preset["params"][k] == v for k, v in preset.values.items())
    moved = with_preset
    assert host.session_params(stage) == moved["params"]


def test_explore_starts_each_student_from_the_rooms_motion(client, room):
    room_id, host = room["room_id"], client.app.state.scene_host
    wait_until(lambda: host.live_readout("heavy-top", f"room-{room_id}")["t_s"] > 1.0, timeout_s=10, what="the room's top moving")
    state = client.post(f"/api/rooms/{room_id}/state", json={"mode": "explore"}, headers=INSTRUCTOR).json()
    start = state["explore_start"]
    assert start["scene_id"] == "heavy-top" and start["motion"]["t_s"] > 1.0 and start["params"] == state["params"]
    sessions = [f"explore-{secrets.token_hex(6)}" for _ in range(2)]
    for session_id in sessions:
        answer = client.put(f"/api/scenes/heavy-top/sessions/{session_id}", json={"params": {}, "from_room": room_id})
        assert answer.status_code == 200 and answer.json()["params"] == start["params"]
    with client.websocket_connect(f"/viewer/heavy-top/{sessions[0]}", subprotocols=VISER) as viewer:
        viewer.send_bytes(viewer_camera_message())
        wait_until(lambda: host.live_readout("heavy-top", sessions[0]) is not None, timeout_s=10, what="the explorer's scene")
        assert host.live_readout("heavy-top", sessions[0])["t_s"] >= start["motion"]["t_s"]  # continues, not from t = 0
    wrong = client.put(f"/api/scenes/four-bar/sessions/{sessions[1]}", json={"params": {}, "from_room": room_id})
    assert wrong.status_code == 422 and "explores 'heavy-top'" in wrong.text
    back = client.post(f"/api/rooms/{room_id}/state", json={"mode": "follow"}, headers=INSTRUCTOR).json()
    assert back["explore_start"] is None
    refused = client.put(f"/api/scenes/heavy-top/sessions/{sessions[1]}", json={"params": {}, "from_room": room_id})
    assert refused.status_code == 422 and "not exploring" in refused.text


def test_joining_answering_and_results(client, room):
    room_id = room["room_id"]
    assert client.post("/api/rooms/join", json={"code": "ZZZZZZ"}).status_code == 404
    tokens = [join(client, room["code"], name=f"Student {n}") for n in range(3)]
    ready = client.get(f"/api/rooms/{room_id}/polls/ready", headers=INSTRUCTOR).json()
    sleeping = next(q for q in ready if q["scene_id"] == "heavy-top" and q["kind"] == "number")
    poll = client.post(f"/api/rooms/{room_id}/polls", json={"ready_id": sleeping["id"]}, headers=INSTRUCTOR).json()
    answers = f"/api/rooms/{room_id}/polls/{poll['poll_id']}/answers"
    assert client.post(answers, json={"value": 10.0}).status_code == 403  # no token: not a student of this room
    assert client.post(answers, json={"value": 10.0}, headers={"X-Student-Token": "x" * 24}).status_code == 403
    for token, value in zip(tokens, (10.0, 20.0, 30.0), strict=True):
        assert client.post(answers, json={"value": value}, headers={"X-Student-Token": token}).status_code == 200
    assert client.post(answers, json={"value": 12.0}, headers={"X-Student-Token": tokens[0]}).status_code == 200  # changed, not added
    not_a_number = client.post(answers, content='{"value": NaN}', headers={"X-Student-Token": tokens[0], "Content-Type": "application/json"})
    assert not_a_number.status_code == 422
    results = client.get(f"/api/rooms/{room_id}/polls/{poll['poll_id']}/results", headers=INSTRUCTOR).json()
    assert results["answers"] == 3 and sum(b["count"] for b in results["histogram"]) == 3 and "names" not in results
    revealed = client.post(f"/api/rooms/{room_id}/polls/{poll['poll_id']}", json={"reveal": True}, headers=INSTRUCTOR).json()
    params = client.app.state.scene_host.session_params(f"room-{room_id}")
    expected = heavy_top_physics.critical_spin_rad_s(params)
    assert revealed["revealed"]["value"] == pytest.approx(expected, rel=1e-12) and "scene" in revealed["revealed"]["source"]
    assert client.post(answers, json={"value": 5.0}, headers={"X-Student-Token": tokens[1]}).status_code == 409
    csv_text = client.get(f"/api/rooms/{room_id}/polls/{poll['poll_id']}/results.csv", headers=INSTRUCTOR).text
    assert "Student 1" not in csv_text and csv_text.count("\n") == 4  # header + 3 anonymous rows
    client.post(f"/api/rooms/{room_id}/polls/{poll['poll_id']}", json={"show_names": True}, headers=INSTRUCTOR)
    assert "Student 1" in client.get(f"/api/rooms/{room_id}/polls/{poll['poll_id']}/results.csv", headers=INSTRUCTOR).text


def test_the_socket_pushes_each_change_and_the_readout(client, room):
    room_id = room["room_id"]
    token = join(client, room["code"])
    with client.websocket_connect(f"/api/rooms/{room_id}/socket") as socket:
        first = json.loads(socket.receive_text())
        assert first["type"] == "state" and first["state"]["scene_id"] == "heavy-top"
        socket.send_text(json.dumps({"type": "hello", "student_token": token, "following": True}))
        sent = time.monotonic()
        client.post(f"/api/rooms/{room_id}/state", json={"params": {"spin_rad_s": 77.0}}, headers=INSTRUCTOR)
        seen: set[str] = set()
        for _ in range(40):
            message = json.loads(socket.receive_text())
            seen.add(message["type"])
            if message["type"] == "state" and message["state"]["params"]["spin_rad_s"] == 77.0:
                pushed_after_s = time.monotonic() - sent
                break
        assert pushed_after_s < 5.0  # pushed, not polled (the browser test holds the 200 ms a student sees)
        while "readout" not in seen:
            message = json.loads(socket.receive_text())
            seen.add(message["type"])
            if message["type"] == "readout":
                assert message["scene_id"] == "heavy-top" and "t_s" in message["data"]
        socket.send_text("not json")
        assert next(json.loads(socket.receive_text()) for _ in range(1))["type"] in ("error", "readout", "state")
    assert state_of(client, room_id)["students"]["connected"] == 0


def test_followers_share_one_stream_of_the_rooms_scene(client, room):
    room_id, host = room["room_id"], client.app.state.scene_host
    followers = [client.websocket_connect(f"/room-viewer/{room_id}", subprotocols=VISER) for _ in range(3)]
    opened = [f.__enter__() for f in followers]
    try:
        for viewer in opened:
            viewer.send_bytes(viewer_camera_message())
            snapshot = []
            while not snapshot or not ends_replay(snapshot[-1]):
                snapshot.append(viewer.receive_bytes())
            assert sum(map(len, snapshot)) > 5000  # the whole scene as it is now
            frames = [viewer.receive_bytes() for _ in range(5)]  # then the shared stream
            assert all(frames)
        # Three followers, one viewer of the stage: the front's stream (no snapshot viewer left open).
        wait_until(lambda: host.stage_viewers(f"room-{room_id}") == 1, timeout_s=5, what="one stage viewer for three followers")
    finally:
        for f in followers:
            f.__exit__(None, None, None)
    refused = client.get(f"/room-viewer/{'0' * 16}/")
    assert refused.status_code == 404


def test_a_page_can_neither_drive_nor_join_a_rooms_stage_by_its_session_id(client, room):
    """The stage's id (room-<room_id>) is derivable from the public room id: the page routes refuse it."""
    room_id, host = room["room_id"], client.app.state.scene_host
    stage = f"room-{room_id}"
    before = host.session_params(stage)
    answer = client.put(f"/api/scenes/heavy-top/sessions/{stage}", json={"params": {"spin_rad_s": 3.0}})
    assert answer.status_code == 403 and "room's shared scene" in answer.text
    with pytest.raises(WebSocketDisconnect):  # refused before it is accepted (tests/api/test_access.py: on the served app)
        with client.websocket_connect(f"/viewer/heavy-top/{stage}", subprotocols=VISER) as viewer:
            viewer.receive_bytes()
    with host.inspect(stage) as scenes:
        assert len(scenes) == 1  # the stage's own scene only: the page's viewer built nothing in it
    assert host.session_params(stage) == before


def test_a_follower_that_falls_behind_is_dropped_whole_not_left_with_a_gap():
    from app.classroom.relay import FOLLOWER_QUEUE, Follower

    follower = Follower(websocket=None)  # type: ignore[arg-type]  # queueing needs no socket, nor a running loop
    follower.go_live()
    for n in range(FOLLOWER_QUEUE + 5):
        follower.offer(bytes([n % 256]))
    follower.offer(b"later")
    left = [follower.queue.get_nowait() for _ in range(follower.queue.qsize())]
    assert follower.dropped and left == [None]  # nothing after the gap is sent: the viewer reconnects from a snapshot
