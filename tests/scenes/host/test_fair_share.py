"""Fair shares of a scene worker (app/scenes/host/fair_share.py), frame by frame, exactly.

An in-process host whose frames are run by hand (``start(frame_loop=False)``), and scenes whose cost a frame is
set by the test (their ``advance`` waits a known time): so the number of frames each viewer advanced is exact, not a
wall-clock rate. Found 6 of issue 24 on the served app is in tests/api/test_fair_share_served.py.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Iterator

import pytest
import viser
from websockets.sync.client import connect

from app.scenes import SCENES
from app.scenes.host.fair_share import (
    LONG_STEP_FRAMES,
    CLASS_DEVICES,
    CLASS_FLOOR_S,
    CLASS_MULTIPLE,
    COST_WARM_UP,
    FRAME_LOOP_SHARE,
    REQUEST_COMPUTE_S,
    FrameCost,
    allowances,
)
from app.scenes.host.host import SceneHost
from app.scenes.host.interface import HostBusy
from app.scenes.viser_boundary import viewer_camera_message
from tests.conftest import wait_until

FRAME_S = 1.0 / 30.0


@pytest.fixture(scope="module")
def host() -> Iterator[SceneHost]:
    host = SceneHost(SCENES)
    host.start(frame_loop=False)
    yield host
    host.stop()


class Viewer:
    """A viewer websocket on the host (from ``client`` as the relay would say), read and dropped in a thread."""

    def __init__(self, host: SceneHost, scene_id: str, session_id: str, *, client: str | None = None) -> None:
        query = f"?client={client}" if client else ""
        self._socket = connect(f"{host.url}/{scene_id}/{session_id}{query}", subprotocols=[f"viser-v{viser.__version__}"], max_size=None)  # type: ignore[list-item]
        self._socket.send(viewer_camera_message())
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._drain, daemon=True)
        self._thread.start()

    def _drain(self) -> None:
        while not self._stop.is_set():
            try:
                self._socket.recv(timeout=0.2)
            except TimeoutError:
                continue
            except Exception:
                return

    def close(self) -> None:
        self._stop.set()
        self._socket.close()
        self._thread.join(timeout=5)


def costly(scene, seconds: float) -> None:
    """Make one scene instance cost ``seconds`` of wall time a frame (its motion still advances normally)."""
    advance = scene.advance

    def slow_advance(dt_s: float) -> None:
        until = time.perf_counter() + seconds
        advance(dt_s)
        while time.perf_counter() < until:
            pass

    scene.advance = slow_advance


def open_page(host: SceneHost, session_id: str, *, client: str | None = None, scene_id: str = "heavy-top") -> Viewer:
    host.set_params(scene_id, session_id, {})
    viewer = Viewer(host, scene_id, session_id, client=client or f"10.8.0.{sum(map(ord, session_id)) % 250 + 1}")
    wait_until(lambda: host.viewer_count(session_id) == 1, what="the viewer to connect")
    return viewer


def t_of(host: SceneHost, session_id: str) -> float:
    return host.playback(session_id)["t_s"]


CAPACITY_S = FRAME_LOOP_SHARE * FRAME_S  # what the viewers of one worker share each frame (s)


def advanced_frames(host: SceneHost, session_id: str, since_t_s: float) -> float:
    return (t_of(host, session_id) - since_t_s) / FRAME_S


def rate_of(host: SceneHost, session_id: str) -> float:
    """The share of a frame the session's scene was given in the last frame (1 when not slowed)."""
    return host.playback(session_id).get("slowed", {"rate": 1.0})["rate"]


def test_a_device_alone_is_never_slowed_however_dear_its_scene(host):
    alone = open_page(host, "share-alone-1", client="10.9.0.1")
    costly(host.instances("share-alone-1")[0], 1.2 * CAPACITY_S)
    for _ in range(COST_WARM_UP + 2):
        host.run_frame(FRAME_S)
    t0 = t_of(host, "share-alone-1")
    for _ in range(20):
        host.run_frame(FRAME_S)
    assert advanced_frames(host, "share-alone-1", t0) == pytest.approx(20, abs=1e-6)
    assert "slowed" not in host.playback("share-alone-1")
    alone.close()


def test_a_dear_scene_in_a_class_runs_slower_and_says_so_while_the_cheap_ones_keep_every_frame(host):
    dear = open_page(host, "share-dear-1", client="10.9.1.1")
    cheap = [open_page(host, f"share-cheap-{n}", client=f"10.9.1.{n + 2}") for n in range(3)]
    dear_cost = 1.5 * CAPACITY_S
    costly(host.instances("share-dear-1")[0], dear_cost)
    for _ in range(COST_WARM_UP + 2):
        host.run_frame(FRAME_S)
    before = {sid: t_of(host, sid) for sid in ("share-dear-1", "share-cheap-0", "share-cheap-1", "share-cheap-2")}
    frames = 60
    rates = []  # the dear one's rate in each frame
    for _ in range(frames):
        host.run_frame(FRAME_S)
        rates.append(rate_of(host, "share-dear-1"))
    for n in range(3):  # every frame, exactly
        assert advanced_frames(host, f"share-cheap-{n}", before[f"share-cheap-{n}"]) == pytest.approx(frames, abs=1e-6)
    # The dear one gets what the cheap ones leave of the capacity: its rate is that over its cost, as measured before
    # each frame (the costs of one more frame, below, are the ones the last frame's rate was computed from).
    costs = {sid: next(iter(host._sessions[sid].shares.values())).frame_s for sid in before}
    host.run_frame(FRAME_S)
    rates.append(rate_of(host, "share-dear-1"))
    rate = (CAPACITY_S - sum(costs[f"share-cheap-{n}"] for n in range(3))) / costs["share-dear-1"]
    slowed = host.playback("share-dear-1")["slowed"]
    assert slowed["rate"] == pytest.approx(rate, rel=1e-12) and "ms of computing a frame" in slowed["note"]
    # Slowed in every frame, and advanced by the rates it was given (under a frame carries over as credit). The rates
    # follow the measured wall-clock costs, which a busy machine moves from frame to frame.
    assert max(rates) < 1.0
    assert advanced_frames(host, "share-dear-1", before["share-dear-1"]) == pytest.approx(sum(rates), abs=1.0)
    assert all("slowed" not in host.playback(f"share-cheap-{n}") for n in range(3))
    for viewer in (dear, *cheap):
        viewer.close()


def test_a_device_with_many_tabs_shares_one_allowance_and_the_other_device_keeps_its_own(host):
    greedy = [open_page(host, f"share-greedy-{n}", client="10.9.2.1") for n in range(3)]
    other = open_page(host, "share-other-1", client="10.9.2.2")
    for n in range(3):  # 3 tabs of half the capacity each; the other device a fifth of it
        costly(host.instances(f"share-greedy-{n}")[0], 0.5 * CAPACITY_S)
    costly(host.instances("share-other-1")[0], 0.2 * CAPACITY_S)
    for _ in range(COST_WARM_UP + 2):
        host.run_frame(FRAME_S)
    before = {sid: t_of(host, sid) for sid in (*[f"share-greedy-{n}" for n in range(3)], "share-other-1")}
    frames = 30
    rates: dict[int, list[float]] = {n: [] for n in range(3)}  # each greedy tab's rate in each frame
    for _ in range(frames):
        host.run_frame(FRAME_S)
        for n in range(3):
            rates[n].append(rate_of(host, f"share-greedy-{n}"))
    # The costs of one more frame are the ones its rates are computed from.
    costs = {sid: next(iter(host._sessions[sid].shares.values())).frame_s for sid in before}
    host.run_frame(FRAME_S)
    for n in range(3):
        rates[n].append(rate_of(host, f"share-greedy-{n}"))
    greedy_demand = sum(costs[f"share-greedy-{n}"] for n in range(3))
    expected = allowances({"greedy": greedy_demand, "other": costs["share-other-1"]}, capacity_s=CAPACITY_S)
    assert expected["other"] == float("inf") and expected["greedy"] < greedy_demand
    assert advanced_frames(host, "share-other-1", before["share-other-1"]) == pytest.approx(frames + 1, abs=1e-6)
    for n in range(3):  # one allowance for the device, shared by its tabs; each advanced by the rates it was given
        assert rates[n][-1] == pytest.approx(expected["greedy"] / greedy_demand, rel=1e-12)
        assert max(rates[n]) < 1.0
        assert advanced_frames(host, f"share-greedy-{n}", before[f"share-greedy-{n}"]) == pytest.approx(sum(rates[n]), abs=1.0)
    assert "this device's 3 scenes cost" in host.playback("share-greedy-0")["slowed"]["note"]
    for viewer in (*greedy, other):
        viewer.close()


def test_fair_shares():
    assert allowances({"a": 1.0, "b": 2.0}, capacity_s=4.0) == {"a": float("inf"), "b": float("inf")}
    assert allowances({"solo": 100.0}, capacity_s=1.0) == {"solo": float("inf")}  # alone: never slowed
    # A few devices, one dear: max-min fair shares of the frame loop's share.
    few = allowances({"a": 1e-3, "b": 1.2e-3, "dear": 30e-3}, capacity_s=16e-3)
    assert few["a"] == few["b"] == float("inf") and few["dear"] == pytest.approx(16e-3 - 2.2e-3)
    # A class whose scenes cost alike is never slowed, however many it is and however full the frame.
    assert set(allowances({f"s{n}": 0.25e-3 for n in range(150)}, capacity_s=16e-3).values()) == {float("inf")}
    # A worker serving a class: a dearer device gets at most the larger of the floor and a few times the median.
    class_of_50 = {f"s{n}": 0.3e-3 for n in range(50)} | {"attacker": 12e-3}
    shares = allowances(class_of_50, capacity_s=40e-3)
    assert shares["attacker"] == pytest.approx(max(CLASS_FLOOR_S, CLASS_MULTIPLE * 0.3e-3)) and shares["s0"] == float("inf")
    shares = allowances({f"s{n}": 2e-3 for n in range(CLASS_DEVICES - 1)} | {"dear": 12e-3}, capacity_s=40e-3)
    assert shares["dear"] == pytest.approx(CLASS_MULTIPLE * 2e-3)  # a class on a dearer lesson: its median sets it


def test_a_request_over_its_compute_limit_is_refused_before_anything_moves(host):
    viewer = open_page(host, "share-request-1")
    scene = host.instances("share-request-1")[0]
    costly(scene, 0.02)  # 20 ms a drawn frame: 300 steps would take 6 s
    scene.motion_cost_s = lambda: 0.001  # 1 ms a frame without drawing: 600 s (18 000 frames) would take 18 s
    for _ in range(COST_WARM_UP + 2):
        host.run_frame(FRAME_S)
    host.set_playback("share-request-1", playing=False)
    t0 = t_of(host, "share-request-1")
    with pytest.raises(ValueError, match=rf"step: .* at most {REQUEST_COMPUTE_S:g} s"):
        host.set_playback("share-request-1", step=300)
    with pytest.raises(ValueError, match=rf"go_to_s: .* at most {REQUEST_COMPUTE_S:g} s"):
        host.set_playback("share-request-1", go_to_s=600.0)
    assert t_of(host, "share-request-1") == t0 and host.playback("share-request-1")["playing"] is False
    stepped = host.set_playback("share-request-1", step=10)  # within the limit: done, exactly
    assert stepped["t_s"] == pytest.approx(t0 + 10 * FRAME_S, abs=1e-9)
    viewer.close()


def test_the_frame_loop_never_waits_for_a_session_busy_with_a_request(host):
    busy, free = open_page(host, "share-busy-1"), open_page(host, "share-free-1")
    session = host._sessions["share-busy-1"]
    held = threading.Event()
    release = threading.Event()

    def hold() -> None:
        with session.lock:  # as a long request holds it
            held.set()
            release.wait(10)

    holder = threading.Thread(target=hold)
    holder.start()
    held.wait(5)
    t_busy, t_free = t_of(host, "share-busy-1"), t_of(host, "share-free-1")
    started = time.perf_counter()
    for _ in range(30):
        host.run_frame(FRAME_S)
    took = time.perf_counter() - started
    release.set()
    holder.join()
    assert took < 1.0  # the 30 frames were drawn without waiting for the busy session
    assert t_of(host, "share-free-1") - t_free == pytest.approx(30 * FRAME_S, abs=1e-9)
    assert t_of(host, "share-busy-1") == t_busy  # it missed those frames
    busy.close()
    free.close()


def test_a_frame_cost_is_the_least_of_the_recent_frames_after_a_warm_up():
    cost = FrameCost()
    cost.add(0.5)  # the first frame compiles and draws everything: never counted
    assert cost.seconds == 0.0
    cost.add(0.004)
    cost.add(0.010)  # interrupted by another thread
    assert cost.seconds == pytest.approx(0.004)
    for _ in range(20):
        cost.add(0.001)
    assert cost.seconds == pytest.approx(0.001)


def test_the_step_button_never_waits_for_another_students_long_request(host):
    """Long requests (a jump, a step of more than LONG_STEP_FRAMES frames) run one at a time in a worker; a one-frame
    step is not one of them: it is answered at once while another student's long jump is running, not 503 after 1 s."""
    viewer = open_page(host, "step-while-long-1")
    assert host._long_request.acquire(timeout=5)  # another student's paced jump holds the worker's long place
    try:
        started = time.monotonic()
        answer = host.set_playback("step-while-long-1", step=1)
        assert time.monotonic() - started < 0.5 and answer["playing"] is False
        with pytest.raises(HostBusy):
            host.set_playback("step-while-long-1", step=LONG_STEP_FRAMES + 1)
    finally:
        host._long_request.release()
        viewer.close()
        host.close_session("step-while-long-1")
