"""Who may change what (app/api/access.py), checked on ``dynlab serve`` as a class would meet it.

Each test plays issue 24's hostile student from an address of their own, beside a victim student; after the attack
the victim's scene must be exactly as it was (its scene, parameters, claim, worker and viewer). The door test
enumerates every state-changing route and socket of the app itself, so a new one cannot be added without saying who
may use it.
"""

from __future__ import annotations

import contextlib
import json
import secrets
import time
from collections.abc import Iterator

import msgspec.msgpack as msgpack
import pytest
import viser
from fastapi.routing import APIRoute, APIWebSocketRoute
from websockets.sync.client import connect

from app.api.access import (
    CREATE_BURST,
    CREATE_RATE_PER_S,
    MAX_FOLLOWERS_PER_CLIENT,
    MAX_SESSIONS_PER_CLIENT,
    MAX_VIEWERS_PER_CLIENT,
    MAX_VIEWERS_PER_SESSION,
    Refused,
    SessionDirectory,
)
from app.main import create_app
from app.practice.variants import learner_variant
from app.scenes.viser_boundary import viewer_camera_message
from tests.api.conftest import live_viewer
from tests.conftest import wait_until

VISER = [f"viser-v{viser.__version__}"]
HEAVY_TOP_LESSON = "10-2-spinning-top"


def new_session() -> str:
    return "access-" + secrets.token_hex(8)


def put(client, session_id: str, params: dict, key: str | None = None, scene: str = "heavy-top"):
    headers = {"X-Session-Key": key} if key is not None else {}
    return client.put(f"/api/scenes/{scene}/sessions/{session_id}", json={"params": params}, headers=headers)


# -- a page's key ------------------------------------------------------------------------------------------------
def test_a_claimed_session_refuses_changes_without_its_key_and_keeps_its_values(client):
    sid, owner_key = new_session(), secrets.token_hex(16)
    assert put(client, sid, {"spin_rad_s": 80.0}, owner_key).status_code == 200
    for intruder_key in (None, secrets.token_hex(16)):
        refused = put(client, sid, {"spin_rad_s": 5.0}, intruder_key)
        assert refused.status_code == 403 and "belongs to another page" in refused.json()["detail"]
        pause = client.put(f"/api/scenes/heavy-top/sessions/{sid}/playback", json={"playing": False},
                           headers={"X-Session-Key": intruder_key} if intruder_key else {})  # fmt: skip
        assert pause.status_code == 403
    kept = put(client, sid, {}, owner_key)
    assert kept.status_code == 200 and kept.json()["params"]["spin_rad_s"] == 80.0
    assert client.get(f"/api/scenes/heavy-top/sessions/{sid}/playback").json()["playing"] is True


def test_an_unclaimed_session_stays_open_to_keyless_changes(client):
    sid = new_session()
    assert put(client, sid, {"spin_rad_s": 70.0}).status_code == 200
    assert put(client, sid, {"spin_rad_s": 71.0}).json()["params"]["spin_rad_s"] == 71.0


def test_a_refused_change_does_not_claim_or_create_the_session(client):
    sid = new_session()
    assert put(client, sid, {"mass_kg": -1.0}, secrets.token_hex(16)).status_code == 422
    assert client.get(f"/api/scenes/heavy-top/sessions/{sid}").status_code == 404
    assert put(client, sid, {"spin_rad_s": 70.0}).status_code == 200  # still unclaimed


@pytest.mark.parametrize("bad_key", ["short", "x" * 129, "has space in it 0123", "bad!key-0123456789abcdef"])
def test_a_malformed_key_is_a_422_naming_the_header(client, bad_key):
    response = put(client, new_session(), {}, bad_key)
    assert response.status_code == 422
    assert response.json()["detail"][0]["loc"] == ["header", "X-Session-Key"]


# -- a class room's shared scene (Found 2) ------------------------------------------------------------------------
@pytest.fixture
def room(served) -> Iterator[dict]:
    instructor = served.instructor_headers
    answer = served.client.post("/api/rooms", json={"lesson_id": HEAVY_TOP_LESSON, "scene_id": "heavy-top"}, headers=instructor)
    assert answer.status_code == 200, answer.text
    yield answer.json()
    served.client.delete(f"/api/rooms/{answer.json()['room_id']}", headers=instructor)


@pytest.mark.parametrize("change", [
    {"playing": False}, {"time_scale": 0.1}, {"seek_s": 0.0}, {"go_to_s": 5.0}, {"reset": True},
    {"camera": {"position": [9.0, 9.0, 9.0], "look_at": [0.0, 0.0, 0.0]}}, {"reset_camera": True}, {"step": 3},
])  # fmt: skip
def test_nobody_drives_a_rooms_shared_scene_through_a_page_route(served, client, room, change):
    """Found 2: every student learns the room id; the page routes refused none of these changes to the room's stage."""
    stage = f"room-{room['room_id']}"
    before = served.client.get(f"/api/scenes/heavy-top/sessions/{stage}/playback").json()
    refused = client.put(f"/api/scenes/heavy-top/sessions/{stage}/playback", json=change)
    assert refused.status_code == 403 and "instructor" in refused.json()["detail"]
    assert put(client, stage, {"spin_rad_s": 1.0}).status_code == 403
    after = served.client.get(f"/api/scenes/heavy-top/sessions/{stage}/playback").json()
    assert (after["playing"], after["time_scale"]) == (before["playing"], before["time_scale"]) == (True, 1.0)
    assert after["t_s"] >= before["t_s"]  # still running, never sent back
    state = served.client.get(f"/api/rooms/{room['room_id']}/state").json()
    assert state["playing"] is True and state["time_scale"] == 1.0


def test_one_device_follows_a_room_in_at_most_its_share_of_tabs(client, room):
    """A room's one stream is shared, but each follower costs the worker a frame message: a device gets
    MAX_FOLLOWERS_PER_CLIENT tabs on it; the next is refused (a websocket refused before it opens is an HTTP 403) and
    a tab closed gives its place back."""
    url = client.websocket_url(f"/room-viewer/{room['room_id']}")
    opened = []
    for _ in range(MAX_FOLLOWERS_PER_CLIENT):
        ws = connect(url, subprotocols=VISER, open_timeout=10, source_address=(client.address, 0))  # type: ignore[list-item]
        ws.send(viewer_camera_message())
        opened.append(ws)
    with pytest.raises(Exception, match="403"):
        connect(url, subprotocols=VISER, open_timeout=10, source_address=(client.address, 0))  # type: ignore[list-item]
    opened.pop().close()

    def reopened() -> bool:
        try:
            opened.append(connect(url, subprotocols=VISER, open_timeout=10, source_address=(client.address, 0)))  # type: ignore[list-item]
            return True
        except Exception:
            return False

    wait_until(reopened, 10, what="the closed tab's place to be given back")
    for ws in opened:
        ws.close()


@pytest.mark.parametrize("message", [b"\xff\x00garbage", msgpack.encode({"type": "FileTransferStart", "source_component_id": None})],
                         ids=["garbage", "unknown-type"])  # fmt: skip
def test_a_viewer_that_sends_what_viser_cannot_use_ends_its_own_connection_without_a_traceback(served, client, message):
    """Anyone who may watch a session could make the server log a full traceback twice a second with a malformed
    frame; now it is one warning line, the sender's connection ends, and the session goes on."""
    sid = new_session()
    assert put(client, sid, {}).status_code == 200
    logged_before = served.log_path.stat().st_size
    ws = connect(client.websocket_url(f"/viewer/heavy-top/{sid}"), subprotocols=VISER, open_timeout=10, source_address=(client.address, 0))  # type: ignore[list-item]
    ws.send(viewer_camera_message())
    wait_until(lambda: client.get(f"/api/scenes/heavy-top/sessions/{sid}/playback").json()["viewers"] == 1, what="the viewer to connect")
    ws.send(message)
    wait_until(lambda: client.get(f"/api/scenes/heavy-top/sessions/{sid}/playback").json()["viewers"] == 0, what="the sender's viewer to end")
    ws.close()
    wait_until(lambda: "could not use" in served.log_path.read_bytes()[logged_before:].decode(errors="replace"), what="the warning line")
    assert "Traceback" not in served.log_path.read_bytes()[logged_before:].decode(errors="replace")
    assert client.get(f"/api/scenes/heavy-top/sessions/{sid}").status_code == 200  # the session itself is untouched


def test_a_page_viewer_cannot_open_a_rooms_shared_scene(client, room):
    with pytest.raises(Exception, match="403"):
        with connect(client.websocket_url(f"/viewer/heavy-top/room-{room['room_id']}"), subprotocols=VISER, open_timeout=10):  # type: ignore[list-item]
            pass


# -- a viewer never re-scenes a session (Found 3) ----------------------------------------------------------------------
def test_a_viewer_of_another_scene_is_refused_and_the_victims_session_is_untouched(served, client):
    victim = served.new_client()
    sid, key = new_session(), secrets.token_hex(16)
    assert put(victim, sid, {"spin_rad_s": 77.0}, key).status_code == 200
    with live_viewer(victim, "heavy-top", sid):
        wait_until(lambda: (victim.get(f"/api/scenes/heavy-top/sessions/{sid}/live").json().get("t_s") or 0) > 0.5, what="the victim's top to run")
        t_before = victim.get(f"/api/scenes/heavy-top/sessions/{sid}/live").json()["t_s"]
        with pytest.raises(Exception, match="403"):  # refused before the handshake completes
            with connect(client.websocket_url(f"/viewer/four-bar/{sid}"), subprotocols=VISER, open_timeout=10) as ws:  # type: ignore[list-item]
                ws.send(viewer_camera_message())
                ws.recv(timeout=5)
        answer = victim.get(f"/api/scenes/heavy-top/sessions/{sid}").json()
        assert answer["params"]["spin_rad_s"] == 77.0 and answer["viewers"] == 1
        assert victim.get(f"/api/scenes/heavy-top/sessions/{sid}/live").json()["t_s"] >= t_before  # not back at 0
        wait_until(lambda: victim.get(f"/api/scenes/heavy-top/sessions/{sid}/live").json()["t_s"] > t_before + 0.2,
                   what="the victim's top to run on from where it was (nothing restarted it)")  # fmt: skip
        assert put(victim, sid, {"spin_rad_s": 78.0}, key).json()["viewers"] == 1  # its own changes still reach it
    # A viewer of a session nobody opened is refused too: a viewer never creates one.
    with pytest.raises(Exception, match="403"):
        with connect(client.websocket_url(f"/viewer/four-bar/{new_session()}"), subprotocols=VISER, open_timeout=10):  # type: ignore[list-item]
            pass


# -- nothing a flood can evict (Found 4) --------------------------------------------------------------------------------
def test_a_flood_of_new_sessions_and_random_ids_evicts_nobody_elses_claim_or_pin(served):
    """Found 4: 2,010 new sessions from one client, then 2,100 GETs of random ids, used to evict a victim's claim and
    move its session to the other worker. Now the flood is rate limited and bounded to the attacker's own share."""
    victim, attacker = served.new_client(), served.new_client(timeout_s=10.0)
    sid, key = new_session(), secrets.token_hex(16)
    assert put(victim, sid, {"spin_rad_s": 88.0}, key).status_code == 200
    with live_viewer(victim, "heavy-top", sid):
        # The directory's bounds are exact at any size (below); here the flood on the real server goes past them:
        # more new sessions than a device may create at once and hold, then GETs of random ids.
        statuses: dict[int, int] = {}
        started = time.monotonic()
        for n in range(MAX_SESSIONS_PER_CLIENT + CREATE_BURST):
            code = put(attacker, f"flood-{n:05d}-{secrets.token_hex(3)}", {}, secrets.token_hex(16)).status_code
            statuses[code] = statuses.get(code, 0) + 1
        created_at_most = CREATE_BURST + CREATE_RATE_PER_S * (time.monotonic() - started) + 1
        assert statuses.get(200, 0) <= created_at_most and statuses.get(429, 0) >= 1, statuses
        assert not set(statuses) - {200, 429}, statuses
        for n in range(300):
            attacker.get(f"/api/scenes/heavy-top/sessions/{secrets.token_hex(8)}/playback")
        assert attacker.get("/api/health").status_code in (200, 429)  # a device over its rate is answered before any route
        # The victim's session: still claimed (tried from a device the flood did not slow), still on its worker with
        # its viewer and its motion.
        intruder = served.new_client()
        assert put(intruder, sid, {"spin_rad_s": 1.0}).status_code == 403
        assert put(intruder, sid, {"spin_rad_s": 1.0}, secrets.token_hex(16)).status_code == 403
        live = victim.get(f"/api/scenes/heavy-top/sessions/{sid}/live")
        assert live.status_code == 200 and live.json()["viewers"] == 1
        assert victim.get(f"/api/scenes/heavy-top/sessions/{sid}").json()["params"]["spin_rad_s"] == 88.0


def test_the_directory_bounds_each_client_to_its_own_sessions_and_never_evicts_a_connected_one():
    """The rules of the flood test, exactly, on the directory itself (no clock: the creation bucket is refilled)."""
    closed: list[str] = []
    now = [0.0]
    directory = SessionDirectory(max_sessions=100, close=closed.append, clock=lambda: now[0])
    directory.changed("victim", "heavy-top", "v" * 16, client="10.0.0.1")
    with directory.viewer("victim", "heavy-top", client="10.0.0.1"):
        for n in range(MAX_SESSIONS_PER_CLIENT + 10):
            now[0] += 1.0
            directory.check_change(f"a{n}", "k" * 16, client="10.0.0.66")
            directory.changed(f"a{n}", "heavy-top", "k" * 16, client="10.0.0.66")
        assert directory.sessions_of("10.0.0.66") == MAX_SESSIONS_PER_CLIENT
        assert closed == [f"a{n}" for n in range(10)]  # the attacker's own oldest went first
        for n in range(200):  # now fill the whole table from many addresses: the connected victim stays
            now[0] += 1.0
            directory.changed(f"b{n}", "heavy-top", None, client=f"10.0.1.{n}")
        assert directory.scene_of("victim") == "heavy-top" and directory.is_claimed("victim")
        assert len(directory) == 100
    assert all(len(h) == 32 for h in [directory._entries["victim"].key_hash])  # only a hash of the key is kept
    with pytest.raises(Refused) as refused:
        for n in range(CREATE_BURST + 1):
            directory.check_change(f"c{n}", None, client="10.0.0.99")
    assert refused.value.status == 429 and refused.value.retry_after_s >= 1


def test_a_session_watched_until_a_moment_ago_is_evicted_last_not_first():
    """Closing a viewer counts as use: a session watched for an hour then left was the first in line to go."""
    closed: list[str] = []
    directory = SessionDirectory(max_sessions=3, close=closed.append)
    directory.changed("watched", "heavy-top", None, client="10.0.2.1")
    with directory.viewer("watched", "heavy-top", client="10.0.2.1"):
        directory.changed("second", "heavy-top", None, client="10.0.2.2")  # opened while "watched" was being watched
        directory.changed("third", "heavy-top", None, client="10.0.2.3")
    directory.changed("fourth", "heavy-top", None, client="10.0.2.4")
    assert closed == ["second"]


def test_viewers_are_bounded_per_session_and_per_client():
    directory = SessionDirectory()
    for n in range(MAX_VIEWERS_PER_CLIENT + 1):
        directory.changed(f"s{n}", "four-bar", None, client="10.0.0.2")
    with contextlib.ExitStack() as stack:
        for _ in range(MAX_VIEWERS_PER_SESSION):
            stack.enter_context(directory.viewer("s0", "four-bar", client=None))
        with pytest.raises(Refused, match="viewers open already"):
            stack.enter_context(directory.viewer("s0", "four-bar", client=None))
    with contextlib.ExitStack() as stack:
        for n in range(MAX_VIEWERS_PER_CLIENT):
            stack.enter_context(directory.viewer(f"s{n}", "four-bar", client="10.0.0.3"))
        with pytest.raises(Refused) as refused:
            stack.enter_context(directory.viewer(f"s{MAX_VIEWERS_PER_CLIENT}", "four-bar", client="10.0.0.3"))
        assert refused.value.status == 429
    with directory.viewer("s1", "four-bar", client="10.0.0.3"):  # places come back when viewers close
        pass


# -- numbers are numbers ------------------------------------------------------------------------------------------------
def test_going_back_in_a_session_with_no_kept_motion_is_a_422_not_a_silent_200(client):
    """``seek_s`` goes back to a kept instant; a session with no viewer keeps none, and a seek answered 200 while
    doing nothing (an outside attack found it)."""
    sid, key = new_session(), secrets.token_hex(16)
    assert put(client, sid, {}, key).status_code == 200
    answer = client.put(f"/api/scenes/heavy-top/sessions/{sid}/playback", json={"seek_s": 1.0}, headers={"X-Session-Key": key})
    assert answer.status_code == 422 and answer.json()["detail"][0]["loc"] == ["body", "seek_s"], answer.text
    assert "no motion is kept" in answer.json()["detail"][0]["msg"]
    assert client.get(f"/api/scenes/heavy-top/sessions/{sid}/playback").json()["playing"] is True  # nothing changed


@pytest.mark.parametrize("field, value", [("go_to_s", "5"), ("go_to_s", True), ("seek_s", "0"), ("time_scale", "2"), ("time_scale", True), ("step", 1.0), ("playing", 1)])
def test_a_playback_number_or_switch_of_the_wrong_json_type_is_a_422(client, field, value):
    """Found 10: ``go_to_s`` accepted "5" and true."""
    sid, key = new_session(), secrets.token_hex(16)
    assert put(client, sid, {}, key).status_code == 200
    answer = client.put(f"/api/scenes/heavy-top/sessions/{sid}/playback", json={field: value}, headers={"X-Session-Key": key})
    assert answer.status_code == 422 and answer.json()["detail"][0]["loc"] == ["body", field]


# -- every door ---------------------------------------------------------------------------------------------------------
#: Every state-changing route and socket, and what it takes: "session-key" (a claimed page's X-Session-Key),
#: "instructor" (the instructor's cookie or key), "student-token" (X-Student-Token of the room), "room-code" (a room's
#: code: joining is public to whoever has it), "stateless" (computes an answer, changes nothing), "watch" (a socket
#: that only watches; nothing it sends changes anything another person sees), "learner-token" (X-Learner-Token:
#: changes only that learner's own progress), "new-learner" (anyone may become a learner: a new one, rate limited),
#: "resume-code" (a learner's resume code: whoever has it carries the progress).
DOORS = {
    ("PUT", "/api/scenes/{scene_id}/sessions/{session_id}"): "session-key",
    ("PUT", "/api/scenes/{scene_id}/sessions/{session_id}/playback"): "session-key",
    ("POST", "/api/scenes/{scene_id}/simulate"): "stateless",
    ("POST", "/api/examples/{example_id}/solve"): "stateless",
    ("POST", "/api/systems/{system_id}/derive"): "stateless",
    ("POST", "/api/systems/{system_id}/rhs"): "stateless",
    ("POST", "/api/systems/{system_id}/eigenvalues"): "stateless",
    ("POST", "/api/systems/custom/derive"): "stateless",
    ("POST", "/api/systems/custom/describe"): "stateless",
    ("POST", "/api/rooms"): "instructor",
    ("DELETE", "/api/rooms/{room_id}"): "instructor",
    ("POST", "/api/rooms/{room_id}/state"): "instructor",
    ("POST", "/api/rooms/{room_id}/polls"): "instructor",
    ("POST", "/api/rooms/{room_id}/polls/{poll_id}"): "instructor",
    ("DELETE", "/api/rooms/{room_id}/students/{student_id}"): "instructor",
    ("PUT", "/api/rooms/{room_id}/assignment"): "instructor",
    ("DELETE", "/api/rooms/{room_id}/assignment"): "instructor",
    ("POST", "/api/rooms/{room_id}/polls/{poll_id}/answers"): "student-token",
    ("POST", "/api/rooms/join"): "room-code",
    ("WS", "/viewer/{scene_id}/{session_id}"): "watch",
    ("WS", "/room-viewer/{room_id}"): "watch",
    ("WS", "/api/rooms/{room_id}/socket"): "instructor",
    ("POST", "/api/exercises/{exercise_id}/attempts"): "learner-token",
    ("POST", "/api/exercises/{exercise_id}/give-up"): "learner-token",
    ("DELETE", "/api/progress"): "learner-token",
    ("POST", "/api/learners"): "new-learner",
    ("POST", "/api/learners/resume"): "resume-code",
}


#: The exercise the learner doors are tried on.
EXERCISE = "5-2-plate-about-corner"


def every_route(routes) -> Iterator:
    """Every route of an app, those of included routers too (FastAPI keeps an included router's routes on it)."""
    for route in routes:
        included = getattr(route, "original_router", None)
        if included is not None:
            yield from every_route(included.routes)
        else:
            yield route


def test_every_state_changing_door_is_listed_with_the_credential_it_needs():
    found = set()
    for route in every_route(create_app().routes):
        if isinstance(route, APIRoute):
            for method in route.methods - {"GET", "HEAD", "OPTIONS"}:
                found.add((method, route.path))
        elif isinstance(route, APIWebSocketRoute):
            found.add(("WS", route.path))
    assert found == set(DOORS), f"unlisted: {sorted(found - set(DOORS))}; gone: {sorted(set(DOORS) - found)}"


def test_every_door_refuses_a_caller_without_its_credential_and_nothing_changes(served, client, room):
    """Each door of DOORS tried by a student with no credential (or the wrong one): 403 (or 404 for a code that is
    not a room's), and the victim's session and the room are as they were."""
    owner = served.new_client()
    sid, key = new_session(), secrets.token_hex(16)
    assert put(owner, sid, {"spin_rad_s": 66.0}, key).status_code == 200
    rid = room["room_id"]
    poll = served.client.post(f"/api/rooms/{rid}/polls", json={"question": "Which way?", "kind": "choice", "choices": ["up", "down"]},
                              headers=served.instructor_headers).json()  # fmt: skip
    state_before = served.client.get(f"/api/rooms/{rid}/state").json()
    made = served.client.post("/api/learners").json()
    learner = {"X-Learner-Token": made["token"]}  # a learner with progress
    own = learner_variant(EXERCISE, made["learner_id"])
    solved = served.client.post(f"/api/exercises/{EXERCISE}/attempts", json={"variant": own, "part": "ixx", "answer": {"value": 2.0, "unit": "kg*m^2"}}, headers=learner)
    assert solved.status_code == 200
    victim_parts = served.client.get("/api/progress", headers=learner).json()["parts"]
    assert len(victim_parts) == 1
    tried = set()
    for (method, path), credential in DOORS.items():
        url = path.format(scene_id="heavy-top", session_id=sid, room_id=rid, poll_id=poll["poll_id"], example_id="1.1", system_id="double-pendulum", student_id="s1", exercise_id=EXERCISE)
        if credential == "session-key":
            body = {"params": {"spin_rad_s": 1.0}} if path.endswith("{session_id}") else {"playing": False}
            for headers in ({}, {"X-Session-Key": secrets.token_hex(16)}):
                assert client.request(method, url, json=body, headers=headers).status_code == 403, (method, path)
        elif credential == "instructor":
            if method == "WS":
                with connect(client.websocket_url(url), open_timeout=10) as ws:
                    ws.recv(timeout=10)  # the room's state, which any member reads
                    ws.send(json.dumps({"type": "set_state", "playing": False}))
                    reply = json.loads(ws.recv(timeout=10))
                    while reply.get("type") != "error":
                        reply = json.loads(ws.recv(timeout=10))
                    assert reply["status"] == 403
            else:
                body = {"lesson_id": HEAVY_TOP_LESSON} if path == "/api/rooms" else {"exercise_ids": [EXERCISE]} if path.endswith("/assignment") else {"question": "x?", "kind": "choice", "choices": ["a", "b"]} if path.endswith("/polls") else {"playing": False} if path.endswith("/state") else {"open": False}
                assert client.request(method, url, json=body).status_code == 403, (method, path)
        elif credential == "student-token":
            for headers in ({}, {"X-Student-Token": secrets.token_urlsafe(18)}):
                assert client.post(url, json={"choice": 0}, headers=headers).status_code == 403, (method, path)
        elif credential == "room-code":
            assert client.post(url, json={"code": "ZZZZZZ", "name": ""}).status_code == 404
        elif credential == "learner-token":  # someone else's token cannot be guessed: a wrong one changes nothing
            body = {"variant": 0, "part": "ixx", "answer": {"value": 1.0, "unit": "kg*m^2"}} if path.endswith("attempts") else {"variant": 0}
            answer = client.request(method, url, json=None if method == "DELETE" else body, headers={"X-Learner-Token": secrets.token_urlsafe(24)})
            assert answer.status_code == 401, (method, path)
        elif credential == "resume-code":
            assert client.post(url, json={"code": "ZZZZZ-ZZZZZ"}).status_code == 404
        elif credential == "new-learner":
            assert client.post(url).status_code == 200
        tried.add((method, path))
    assert tried == set(DOORS)
    state_after = served.client.get(f"/api/rooms/{rid}/state").json()
    for field in ("lesson_id", "scene_id", "params", "playing", "time_scale", "mode", "revision", "assignment"):
        assert state_after[field] == state_before[field], field
    assert state_after["poll"]["open"] is True
    assert put(owner, sid, {}, key).json()["params"]["spin_rad_s"] == 66.0
    assert owner.get(f"/api/scenes/heavy-top/sessions/{sid}/playback").json()["playing"] is True
    assert served.client.get("/api/progress", headers=learner).json()["parts"] == victim_parts
