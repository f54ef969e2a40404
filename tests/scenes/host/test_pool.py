"""Scene workers: an app whose scenes run in two worker processes answers exactly as the in-process one does.

One app with ``workers=2`` is started for the module (spawning two workers takes
a few seconds). Checked: sessions are pinned to one worker by their id; setting
parameters, refusing bad ones, viewers through the relay and live readouts all
work across the process boundary; a worker that dies is restarted and its
sessions get their parameters back.
"""

from __future__ import annotations

import os
import secrets
import signal
from collections.abc import Iterator

import pytest
import viser
from fastapi.testclient import TestClient

from app.main import create_app
from app.scenes.host.pool import WorkerPool
from app.scenes.host.viser_compat import viewer_camera_message
from app.settings import Settings
from tests.conftest import wait_until


@pytest.fixture(scope="module")
def client() -> Iterator[TestClient]:
    with TestClient(create_app(Settings(workers=2))) as client:
        yield client


@pytest.fixture
def pool(client) -> WorkerPool:
    host = client.app.state.scene_host
    assert isinstance(host, WorkerPool) and host.worker_count == 2
    return host


def session_on(pool: WorkerPool, worker: int) -> str:
    """A fresh session id that the pool pins to ``worker``."""
    while True:
        session_id = "pool-" + secrets.token_hex(6)
        if pool.worker_index(session_id) == worker:
            return session_id


def test_sessions_are_pinned_on_first_sight_and_a_class_is_spread_evenly(pool):
    ids = [f"class-{secrets.token_hex(4)}-{n:03d}" for n in range(100)]
    first = [pool.worker_index(i) for i in ids]
    assert first == [pool.worker_index(i) for i in reversed(ids)][::-1]  # the same answer every time, in any order
    assert abs(pool._pinned_count[0] - pool._pinned_count[1]) <= 1  # each new session went to the less loaded worker
    assert abs(first.count(0) - first.count(1)) <= 2


def test_the_pin_table_is_bounded_and_forgets_the_least_recently_used():
    small = WorkerPool({}, workers=3, max_sessions=5)  # not started: pinning needs no process
    for n in range(8):
        small.worker_index(f"session-{n}")
    assert list(small._pinned) == [f"session-{n}" for n in range(3, 8)] and sum(small._pinned_count) == 5
    assert sorted(small._pinned_count) == [1, 2, 2]


def test_parameters_and_refusals_cross_the_process_boundary(client, pool):
    for worker in (0, 1):
        sid = session_on(pool, worker)
        url = f"/api/scenes/four-bar/sessions/{sid}"
        assert client.put(url, json={"params": {"crank_m": 0.12}}).json()["params"]["crank_m"] == 0.12
        bad = client.put(url, json={"params": {"crank_m": -1.0}})
        assert bad.status_code == 422 and bad.json()["detail"][0]["loc"] == ["body", "params", "crank_m"]
        impossible = client.put(url, json={"params": {"ground_m": 10.0}})
        assert impossible.status_code == 422 and "cannot be assembled" in impossible.json()["detail"][0]["msg"]
        assert client.put(url, json={"params": {}}).json()["params"]["crank_m"] == 0.12  # nothing changed


def test_a_viewer_through_the_relay_reaches_its_session_in_its_worker(client, pool):
    sid = session_on(pool, 1)
    assert client.put(f"/api/scenes/heavy-top/sessions/{sid}", json={"params": {"spin_rad_s": 75.0}}).status_code == 200
    with client.websocket_connect(f"/viewer/heavy-top/{sid}", subprotocols=["viser-v" + viser.__version__]) as socket:
        socket.receive()
        socket.send_bytes(viewer_camera_message())
        wait_until(lambda: pool.viewer_count(sid) == 1, what="the worker to count the viewer")
        for _ in range(10):  # frames keep coming through the relay
            socket.receive()
        live = client.get(f"/api/scenes/heavy-top/sessions/{sid}/live")
        assert live.status_code == 200 and live.json()["viewers"] == 1 and live.json()["t_s"] > 0.0
        assert pool.viewer_count() >= 1
    wait_until(lambda: pool.viewer_count(sid) == 0, what="the worker to drop the viewer")


def test_a_dead_worker_is_restarted_and_its_sessions_keep_their_parameters(client, pool):
    sid = session_on(pool, 0)
    assert client.put(f"/api/scenes/heavy-top/sessions/{sid}", json={"params": {"spin_rad_s": 66.0}}).status_code == 200
    old_pid = pool.worker_pids()[0]
    os.kill(old_pid, signal.SIGKILL)
    wait_until(lambda: pool.worker_pids()[0] != old_pid, timeout_s=60.0, what="the supervisor to restart worker 0")
    wait_until(lambda: (pool.session_params(sid) or {}).get("spin_rad_s") == 66.0, timeout_s=30.0, what="the session's parameters to come back")
    assert client.put(f"/api/scenes/heavy-top/sessions/{sid}", json={"params": {"spin_rad_s": 67.0}}).status_code == 200


def test_a_rooms_stage_in_a_worker_streams_to_followers_and_survives_a_worker_restart(client, pool):
    """The room's scene runs in a worker; followers share the front's one stream; a killed worker's stage is opened
    again with the room's parameters, and a follower arriving after that gets the scene afresh."""
    from app.web.room_relay import ends_replay

    instructor = {"X-Instructor-Key": client.app.state.instructor_key.secret}
    lesson = next(l.id for l in client.app.state.catalogue.lessons.values() if "heavy-top" in l.scenes)
    room = client.post("/api/rooms", json={"lesson_id": lesson, "scene_id": "heavy-top"}, headers=instructor).json()
    stage = f"room-{room['room_id']}"
    client.post(f"/api/rooms/{room['room_id']}/state", json={"params": {"spin_rad_s": 71.0}}, headers=instructor)

    def follow_once() -> None:
        with client.websocket_connect(f"/room-viewer/{room['room_id']}", subprotocols=["viser-v" + viser.__version__]) as socket:
            socket.send_bytes(viewer_camera_message())
            window = socket.receive_bytes()
            while not ends_replay(window):
                window = socket.receive_bytes()
            for _ in range(5):
                socket.receive_bytes()

    follow_once()
    assert pool.stage_viewers(stage) == 1  # the front's stream stays open for the next follower
    worker = pool.worker_index(stage)
    old_pid = pool.worker_pids()[worker]
    os.kill(old_pid, signal.SIGKILL)
    wait_until(lambda: pool.worker_pids()[worker] != old_pid, timeout_s=60.0, what="the supervisor to restart the stage's worker")
    wait_until(lambda: pool.stage_viewer_url(stage) is not None, timeout_s=30.0, what="the stage to be opened again")
    assert pool.session_params(stage)["spin_rad_s"] == 71.0
    wait_until(lambda: _follows(follow_once), timeout_s=30.0, what="a follower to get the reopened stage")
    client.delete(f"/api/rooms/{room['room_id']}", headers=instructor)


def _follows(follow_once) -> bool:
    try:
        follow_once()
    except Exception:  # the old stream is still closing: the viewer would reconnect, and so does this
        return False
    return True


def test_a_session_whose_worker_is_down_gets_a_503_with_retry_after(client, pool, monkeypatch):
    sid = session_on(pool, 1)
    monkeypatch.setattr(pool._workers[1], "rpc_address", ("127.0.0.1", 1))  # nothing listens there: as if the worker were gone
    monkeypatch.setattr(pool._workers[1], "idle_connections", type(pool._workers[1].idle_connections)())
    response = client.put(f"/api/scenes/heavy-top/sessions/{sid}", json={"params": {}})
    assert response.status_code == 503 and response.headers["Retry-After"] == "2"
    assert "restarting" in response.json()["detail"]


def test_a_caller_without_the_key_is_refused_and_the_worker_keeps_answering(client, pool):
    from multiprocessing import AuthenticationError
    from multiprocessing.connection import Client

    address = pool._workers[0].rpc_address
    with pytest.raises(AuthenticationError):
        Client(address, authkey=b"not the pool's key")
    sid = session_on(pool, 0)
    assert client.put(f"/api/scenes/four-bar/sessions/{sid}", json={"params": {"crank_m": 0.11}}).status_code == 200
    pool._close_connections(pool._workers[0])  # a new connection: the listener must still accept
    assert pool.session_params(sid)["crank_m"] == 0.11
