"""Faults a class meets, on ``dynlab serve`` itself: a burst at start-up, a stopped worker, a killed worker, Ctrl+C.

Each test starts its own server (they stop and kill its workers). Found items 5, 7 and 8 of issue 24, and its chaos
test (Build 9): a class of viewers and a room with followers, then SIGKILL of one worker and SIGSTOP of the other
for 10 s; the state after recovery must equal the state before, and ``/api/health`` must never take over 1 s.
"""

from __future__ import annotations

import concurrent.futures
import json
import math
import os
import secrets
import signal
import threading
import time
from pathlib import Path

import httpx
import pytest
from websockets.sync.client import connect as websocket_connect

from app.scenes.host.pool import PLACE_WAIT_S
from tests.conftest import wait_until
from tests.served import ServedApp, Viewer, children_running

HEAVY_TOP_LESSON = "10-2-spinning-top"
#: A typed kinetic energy whose derivation runs to its 20 s bound.
SLOW_KINETIC = "q1d^2*(1+q1^2)^17*(2+sin(q1))^13*(3+cos(q1))^11/2"
#: How long the health probe may take at most, at any moment (s).
HEALTH_LIMIT_S = 1.0


class HealthProbe:
    """Polls ``/api/health`` every 0.1 s in a thread and keeps the slowest answer (s; a failure counts as infinite)."""

    def __init__(self, app: ServedApp) -> None:
        self.url = f"{app.url}/api/health"
        self.slowest_s = 0.0
        self.answers = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self) -> None:
        with httpx.Client(timeout=10.0) as client:
            while not self._stop.wait(0.1):
                started = time.monotonic()
                try:
                    ok = client.get(self.url).status_code == 200
                except httpx.HTTPError:
                    ok = False
                took = time.monotonic() - started if ok else float("inf")
                self.slowest_s = max(self.slowest_s, took)
                self.answers += 1

    def close(self) -> float:
        self._stop.set()
        self._thread.join(timeout=15)
        return self.slowest_s


class Page:
    """A student's lesson page on the served app: its device, session and key."""

    def __init__(self, app: ServedApp, scene_id: str = "heavy-top", params: dict | None = None) -> None:
        self.app, self.scene_id = app, scene_id
        self.device = app.new_client(timeout_s=30.0)
        self.session_id, self.key = "fault-" + secrets.token_hex(6), secrets.token_hex(16)
        answer = self.device.put(self.base, json={"params": params or {}}, headers={"X-Session-Key": self.key})
        assert answer.status_code == 200, answer.text
        self.viewer: Viewer | None = None

    @property
    def base(self) -> str:
        return f"/api/scenes/{self.scene_id}/sessions/{self.session_id}"

    def open_viewer(self, camera: tuple | None = None) -> None:
        self.viewer = Viewer(self.app, f"/viewer/{self.scene_id}/{self.session_id}", address=self.device.address, camera=camera)
        wait_until(lambda: self.playback().get("viewers", 0) >= 1, 30, what="the page's viewer to connect")

    def playback(self, **change) -> dict:
        if change:
            answer = self.device.put(f"{self.base}/playback", json=change, headers={"X-Session-Key": self.key})
        else:
            answer = self.device.get(f"{self.base}/playback")
        return answer.json() if answer.status_code == 200 else {"status": answer.status_code}

    def state(self) -> dict:
        """What must survive: parameters, play state, time scale, simulated time, camera."""
        params = self.device.get(self.base).json()["params"]
        playback = self.playback()
        return {"params": params, **{k: playback.get(k) for k in ("playing", "time_scale", "t_s", "camera")}}

    def close(self) -> None:
        if self.viewer is not None:
            self.viewer.close()
        self.device.close()


def open_room(app: ServedApp, params: dict) -> str:
    answer = app.client.post("/api/rooms", json={"lesson_id": HEAVY_TOP_LESSON, "scene_id": "heavy-top"}, headers=app.instructor_headers)
    assert answer.status_code == 200, answer.text
    room_id = answer.json()["room_id"]
    change = app.client.post(f"/api/rooms/{room_id}/state", json={"params": params}, headers=app.instructor_headers)
    assert change.status_code == 200, change.text
    return room_id


def stage_state(app: ServedApp, room_id: str) -> dict:
    answer = app.client.get(f"/api/scenes/heavy-top/sessions/room-{room_id}/playback")
    return answer.json() if answer.status_code == 200 else {"status": answer.status_code}


# -- Found 5: a burst right after start; Ctrl+C whatever is in flight ----------------------------------------------------
def test_forty_requests_at_once_right_after_start_are_all_answered_and_ctrl_c_stops_within_5_s():
    """Found 5: 40 concurrent GETs of …/playback right after start left 18 unanswered (the worker's listener had a
    backlog of 1 and the front no timeout); 40 concurrent recording.html left 27 stuck; Ctrl+C could not stop it.
    Now every request is answered, and Ctrl+C stops the server within 5 s with a worker stopped, viewers open,
    recordings asked for and a 20 s derivation in flight."""
    app = ServedApp(name="faults-burst").start()
    try:
        pages = [Page(app) for _ in range(4)]
        paths = [f"{p.base}/playback" for p in pages] + [f"/api/scenes/heavy-top/sessions/{secrets.token_hex(8)}/playback"]
        recordings = [f"{p.base}/recording.html?seconds=2" for p in pages]
        devices = [app.new_client(timeout_s=30.0) for _ in range(40)]

        def get(n: int, path: str) -> tuple[int, float]:
            started = time.monotonic()
            try:
                return devices[n].get(path).status_code, time.monotonic() - started
            except httpx.HTTPError:
                return -1, time.monotonic() - started

        for targets, allowed in ((paths, {200, 404}), (recordings, {200, 503})):
            with concurrent.futures.ThreadPoolExecutor(40) as burst:
                answers = list(burst.map(lambda n: get(n, targets[n % len(targets)]), range(40)))
            assert {code for code, _ in answers} <= allowed, answers
            assert max(took for _, took in answers) < 20.0, answers
        # Ctrl+C with requests in flight: a worker stopped (its calls hang), viewers open, a recording asked for.
        pages[0].open_viewer()
        os.kill(app.worker_pids()[0], signal.SIGSTOP)
        in_flight = concurrent.futures.ThreadPoolExecutor(9)
        waiting = [in_flight.submit(get, n, recordings[n % len(recordings)]) for n in range(8)]
        slow = {"coordinates": ["q1"], "kinetic_energy": SLOW_KINETIC, "potential_energy": "0", "parameters": {}}
        derivation = in_flight.submit(devices[39].post, "/api/systems/custom/derive", json=slow)  # up to its 20 s bound
        time.sleep(0.5)  # let the requests reach the stopped worker (what is measured is the stop, below)
        took = app.stop(timeout_s=15.0)
        assert took <= 5.0, f"dynlab serve took {took:.1f} s to stop after Ctrl+C\n{app.log_tail()}"
        assert app.process is not None and app.process.returncode is not None
        # Each request still waiting was answered: "the server is stopping" (503, Retry-After), not uvicorn's 500.
        answer = derivation.result(timeout=5.0)
        assert answer.status_code == 503 and "stopping" in answer.json()["detail"] and answer.headers["Retry-After"], answer.text
        assert {future.result(timeout=5.0)[0] for future in waiting} <= {200, 503}
        assert "Exception in ASGI application" not in app.log_tail(400)
        in_flight.shutdown(wait=False, cancel_futures=True)
        for device in devices:
            device.close()
    finally:
        app.stop()


# -- Found 7: a stopped worker stalls nobody else ------------------------------------------------------------------------
def _running(pid: int) -> bool:
    """Whether process ``pid`` exists and has not ended (a zombie has)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


def test_ctrl_c_in_a_terminal_stops_every_process_of_the_server_without_a_traceback():
    """Ctrl+C in a terminal signals the server's whole process group, its scene workers too, and each worker printed a
    KeyboardInterrupt traceback. The front alone stops them, in order; the log tells of no interrupt."""
    app = ServedApp(name="faults-terminal").start()
    try:
        page = Page(app)
        page.open_viewer()
        processes = [app.process.pid, *app.worker_pids()]
        started = time.monotonic()
        os.killpg(app.process.pid, signal.SIGINT)  # the served app is a session of its own: its group is the terminal's
        app.process.wait(timeout=15.0)
        took = time.monotonic() - started
        page.close()
        log = app.log_tail(400)
        assert took <= 5.0 and app.process.returncode == 0, (took, app.process.returncode, log)
        assert "Traceback" not in log and "KeyboardInterrupt" not in log, log
        wait_until(lambda: not any(map(_running, processes)), 10, what="every process of the server to end")
    finally:
        app.stop()


@pytest.fixture(scope="module")
def app():
    with ServedApp(name="faults") as served:
        yield served


def test_a_stopped_worker_delays_neither_the_other_worker_nor_health(app):
    """Found 7: with one worker SIGSTOPped for 20 s, /api/health took 21 s and sessions on the other worker waited 21 s
    (the front's thread pool filled). Now: health stays under 1 s, the other worker's sessions answer at once, and the
    stopped worker's sessions get 503 with Retry-After within a bounded wait; pages opened meanwhile work."""
    pages = [Page(app) for _ in range(6)]  # spread over both workers (each new session goes to the less loaded)
    victim_pid = app.worker_pids()[0]
    probe = HealthProbe(app)
    os.kill(victim_pid, signal.SIGSTOP)
    try:
        stopped_since = time.monotonic()
        results: dict[str, list[tuple[int, float]]] = {p.session_id: [] for p in pages}

        def ask(page: Page) -> None:
            with app.new_client(timeout_s=30.0) as tab:  # a tab of its own: a device polls a few times a second
                while time.monotonic() - stopped_since < 10.0:
                    started = time.monotonic()
                    code = tab.get(f"{page.base}/playback").status_code
                    results[page.session_id].append((code, time.monotonic() - started))
                    time.sleep(0.1)  # a page's poll

        with concurrent.futures.ThreadPoolExecutor(len(pages) * 4) as askers:  # 24 callers, as a class polling does
            for page in pages * 4:
                askers.submit(ask, page)
        healthy = [sid for sid, answers in results.items() if all(code == 200 for code, _ in answers)]
        stuck = [sid for sid, answers in results.items() if any(code == 503 for code, _ in answers)]
        assert healthy and stuck and set(healthy) | set(stuck) == set(results)
        for sid in healthy:
            # 12 pollers share the healthy worker's CALLS_PER_WORKER places: a poll may wait up to PLACE_WAIT_S for
            # one (then 503), so an answer takes that wait plus the call (CI measured 1.1 s once); before, 21 s.
            assert max(took for _, took in results[sid]) < PLACE_WAIT_S + 1.0, results[sid]
        for sid in stuck:
            assert max(took for _, took in results[sid]) < 7.0, results[sid]
            assert {code for code, _ in results[sid]} <= {200, 503}
        stuck_page = next(p for p in pages if p.session_id == stuck[0])
        refused = stuck_page.device.get(f"{stuck_page.base}/playback")
        assert refused.status_code == 503 and int(refused.headers["Retry-After"]) >= 1
        health = app.client.get("/api/health").json()
        assert "not answering" in {w["state"] for w in health["workers"]}
        newcomers = [Page(app) for _ in range(4)]  # pages opened meanwhile go to the worker that answers
        assert all(p.playback()["playing"] for p in newcomers)  # (each got 503 before: new sessions went to the stopped one)
        pages += newcomers
    finally:
        os.kill(victim_pid, signal.SIGCONT)
    wait_until(lambda: all(p.device.get(f"{p.base}/playback").status_code == 200 for p in pages), 20, what="the stopped worker to answer again")
    assert probe.close() < HEALTH_LIMIT_S
    for page in pages:
        page.close()


# -- Found 8 and the chaos test: a killed worker loses nothing ------------------------------------------------------------
def test_chaos_a_class_survives_a_killed_worker_and_a_stopped_one_with_every_state_as_it_was(app):
    """A class of viewers (each with its own camera, some paused at a time, one at 0.5×) and a room with followers
    (paused at 0.5× by its instructor). SIGKILL of one worker, then SIGSTOP of the other for 10 s. After recovery every
    session's parameters, play state, time scale, simulated time (paused ones exactly) and camera are as before, the
    room's stage matches the room's state exactly, followers see it again, and health never took over 1 s.
    (Found 8: a killed worker's sessions came back playing at 1× with no history or camera after 21 s or more, and a
    room's stage playing at 1× while the room said paused at 0.5×.)"""
    pages = []
    for n in range(6):
        page = Page(app, params={"spin_rad_s": 60.0 + n})
        page.open_viewer(camera=((4.0 + n, -3.0, 2.0), (0.0, 0.0, 0.5)))
        pages.append(page)
    for page in pages:  # let each move, then pause most of them at a known instant; one runs on at half speed
        wait_until(lambda page=page: (page.playback().get("t_s") or 0.0) > 0.3, 20, what="the class's tops to move")
    for page in pages[:4]:
        page.playback(playing=False)
    pages[4].playback(time_scale=0.5)
    room_id = open_room(app, {"spin_rad_s": 95.0})
    followers = [Viewer(app, f"/room-viewer/{room_id}", address=f"127.2.0.{n + 1}") for n in range(3)]
    wait_until(lambda: all(f.frames > 5 for f in followers), 30, what="the followers to get the room's frames")
    change = app.client.post(f"/api/rooms/{room_id}/state", json={"playing": False, "time_scale": 0.5}, headers=app.instructor_headers)
    assert change.status_code == 200
    time.sleep(1.5)  # the supervisor's snapshot period is 1 s: what a student changed a moment ago must survive too
    before = {p.session_id: p.state() for p in pages}
    room_before = app.client.get(f"/api/rooms/{room_id}/state").json()
    stage_before = stage_state(app, room_id)
    assert stage_before["playing"] is False and stage_before["time_scale"] == 0.5

    probe = HealthProbe(app)
    killed, stopped = app.worker_pids()
    os.kill(killed, signal.SIGKILL)
    wait_until(lambda: killed not in app.worker_pids() and len(app.worker_pids()) == 2, 60, what="the killed worker to be replaced")
    os.kill(stopped, signal.SIGSTOP)
    time.sleep(10.0)  # the 10 s stop: what is measured is health meanwhile and the state after
    os.kill(stopped, signal.SIGCONT)
    wait_until(lambda: all(w["state"] == "answering" for w in app.client.get("/api/health").json()["workers"]), 60,
               what="both workers to answer again")  # fmt: skip
    wait_until(lambda: all(p.playback().get("viewers", 0) >= 1 for p in pages), 30, what="every viewer to reconnect")

    for page in pages:
        after = page.state()
        was = before[page.session_id]
        assert after["params"] == was["params"]
        assert (after["playing"], after["time_scale"]) == (was["playing"], was["time_scale"])
        assert was["camera"] is not None and after["camera"] is not None
        for part in ("position", "look_at"):
            assert after["camera"][part] == pytest.approx(was["camera"][part], abs=1e-9)
        if not was["playing"]:
            assert after["t_s"] == pytest.approx(was["t_s"], abs=1e-9)  # paused: exactly the instant it was paused at
        else:
            assert after["t_s"] >= was["t_s"] - 1.0  # running: from its last snapshot (≤ 1 s old) on, never from 0
    room_after = app.client.get(f"/api/rooms/{room_id}/state").json()
    for field in ("lesson_id", "scene_id", "params", "playing", "time_scale", "mode", "revision"):
        assert room_after[field] == room_before[field], field
    wait_until(lambda: stage_state(app, room_id).get("playing") is False, 30, what="the room's stage to be back")
    stage_after = stage_state(app, room_id)
    assert (stage_after["playing"], stage_after["time_scale"]) == (room_after["playing"], room_after["time_scale"]) == (False, 0.5)
    assert stage_after["t_s"] == pytest.approx(stage_before["t_s"], abs=1e-9)
    late = Viewer(app, f"/room-viewer/{room_id}", address="127.2.0.9")  # a student who joins now gets the scene as it is
    wait_until(lambda: late.frames > 0, 30, what="a follower joining after the faults to get the room's scene")
    followers.append(late)
    assert probe.close() < HEALTH_LIMIT_S, "health took longer than 1 s during the faults"
    for follower in followers:
        follower.close()
    for page in pages:
        page.close()
    app.client.delete(f"/api/rooms/{room_id}", headers=app.instructor_headers)


def test_a_watchers_unusable_camera_is_never_shown_kept_or_restored(app):
    """Anyone may watch a session; a watcher's viewer that reports a NaN (or 1e300) camera was kept as the session's
    camera, answered as ``[null, null, null]``, and on a worker restart failed the session's restore half-way: the
    victim's paused top at 2.5× came back playing at 1×."""
    victim = Page(app)
    victim.playback(playing=False, time_scale=2.5)
    watcher = Viewer(app, f"/viewer/heavy-top/{victim.session_id}", address="127.2.1.1", camera=((math.nan,) * 3, (0.0, 0.0, 0.0)))
    wait_until(lambda: victim.playback().get("viewers") == 1, 30, what="the watcher's viewer to connect")
    victim.open_viewer(camera=((4.0, -3.0, 2.0), (0.0, 0.0, 0.5)))  # the watcher's viewer is the first
    wait_until(lambda: victim.playback().get("viewers") == 2, 30, what="the victim's viewer to connect")
    assert victim.playback()["camera"] == {"position": [4.0, -3.0, 2.0], "look_at": [0.0, 0.0, 0.5]}
    time.sleep(1.5)  # the supervisor's snapshot period is 1 s
    for pid in app.worker_pids():
        os.kill(pid, signal.SIGKILL)
    wait_until(lambda: all(w["state"] == "answering" for w in app.client.get("/api/health").json()["workers"]) and len(app.worker_pids()) == 2,
               60, what="both workers to be back")  # fmt: skip
    wait_until(lambda: "playing" in victim.playback(), 30, what="the victim's session to answer again")  # as its page retries a 503
    after = victim.playback()
    assert (after["playing"], after["time_scale"]) == (False, 2.5), after
    assert None not in after["camera"]["position"]
    watcher.close()
    victim.close()


def test_the_instructors_socket_stays_open_and_the_room_unchanged_while_its_scene_worker_is_stopped(app):
    """An instructor's action over the room socket that its scene worker cannot take now is answered with an error
    (503, retry_after_s) on the socket, which stays open; the room still says what its stage does. Before, the busy
    worker's error closed the instructor's socket silently, and the room said paused while its stage played."""
    room_id = open_room(app, {"spin_rad_s": 95.0})
    before = app.client.get(f"/api/rooms/{room_id}/state").json()
    pids = app.worker_pids()
    with websocket_connect(f"ws://127.0.0.1:{app.port}/api/rooms/{room_id}/socket", additional_headers=app.instructor_headers, open_timeout=30) as socket:
        for pid in pids:
            os.kill(pid, signal.SIGSTOP)
        try:
            wait_until(lambda: all(w["state"] == "not answering" for w in app.client.get("/api/health").json()["workers"]), 20,
                       what="both workers to be marked not answering")  # fmt: skip
            socket.send(json.dumps({"type": "set_state", "playing": False, "time_scale": 0.5}))
            deadline = time.monotonic() + 15
            while (reply := json.loads(socket.recv(timeout=max(0.1, deadline - time.monotonic())))).get("type") != "error":
                pass
            assert reply["status"] == 503 and reply["action"] == "set_state" and reply["retry_after_s"] >= 1, reply
        finally:
            for pid in pids:
                os.kill(pid, signal.SIGCONT)
        socket.send(json.dumps({"type": "ping"}))  # the socket is still open
        deadline = time.monotonic() + 15
        while json.loads(socket.recv(timeout=max(0.1, deadline - time.monotonic()))).get("type") != "pong":
            pass
    after = app.client.get(f"/api/rooms/{room_id}/state").json()
    assert (after["playing"], after["time_scale"], after["revision"]) == (before["playing"], before["time_scale"], before["revision"])
    wait_until(lambda: stage_state(app, room_id).get("playing") is True, 30, what="the stage to answer again")
    app.client.delete(f"/api/rooms/{room_id}", headers=app.instructor_headers)


def test_a_killed_forkserver_costs_the_class_a_worker_restart_and_leaves_no_worker_behind(app):
    """The scene workers are forks of the front's forkserver, which also reports their exit: killed, it reports both
    as gone. Both are replaced (the forkserver is started again), every session comes back as it was, and the old
    workers, alive after all, stop when the front closes their start pipes instead of running on beside the new."""
    page = Page(app, params={"spin_rad_s": 77.0})
    page.playback(playing=False, time_scale=2.0)
    time.sleep(1.5)  # the supervisor's snapshot period is 1 s
    before = app.worker_pids()
    (forkserver,) = children_running(app.process.pid, b"forkserver")
    os.kill(forkserver, signal.SIGKILL)
    wait_until(lambda: len(app.worker_pids()) == 2 and not set(app.worker_pids()) & set(before)
               and all(w["state"] == "answering" for w in app.client.get("/api/health").json()["workers"]), 30,
               what="both workers to be replaced")  # fmt: skip
    wait_until(lambda: not [pid for pid in before if _running(pid)], 10, what="the old workers to stop")
    wait_until(lambda: "playing" in page.playback(), 30, what="the session to answer again")
    after = page.state()
    assert (after["params"]["spin_rad_s"], after["playing"], after["time_scale"]) == (77.0, False, 2.0), after
    page.close()


def _running(pid: int) -> bool:
    """Whether ``pid`` is a live process (not gone, not a zombie waiting to be reaped)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False
