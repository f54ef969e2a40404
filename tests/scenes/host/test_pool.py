"""The worker pool's routing, checked without starting a worker: one interface, derived forwarders, pins only by
calls that create a session, and no call about an unknown session ever reaching a worker.

What the pool does with real workers (restarts that restore, a stopped worker, timeouts, Ctrl+C) is checked against
``dynlab serve`` itself in tests/api/test_faults.py.
"""

from __future__ import annotations

import inspect
import secrets
import socket
import time

import pytest

from app.scenes.host.host import SceneHost
from app.scenes.host.interface import CALLS, RAISE, WORKER_CALLS, HostBusy, SceneHostInterface
from app.scenes.host.pool import WorkerPool
from app.scenes.host.rpc import WorkerUnavailableError, connect


class Recorder:
    """Stands in for ``WorkerPool._call``: records (worker, call, args, kwargs) and answers ``answer``."""

    def __init__(self, answer=None) -> None:
        self.calls: list[tuple] = []
        self.answer = answer

    def __call__(self, index, call, args, kwargs, *, checking=False):
        self.calls.append((index, call.name, args, kwargs))
        return self.answer


@pytest.fixture
def pool(monkeypatch) -> tuple[WorkerPool, Recorder]:
    from app.scenes import SCENES

    pool = WorkerPool(SCENES, workers=2)  # not started: routing needs no process
    recorder = Recorder(answer={"params": {}, "viewer_url": "ws://x"})
    monkeypatch.setattr(pool, "_call", recorder)
    return pool, recorder


def test_the_in_process_host_and_the_pool_offer_every_declared_call_with_the_same_signature():
    for name in CALLS:
        declared = inspect.signature(getattr(SceneHostInterface, name))
        implemented = inspect.signature(getattr(SceneHost, name))
        assert list(declared.parameters) == list(implemented.parameters), name
        assert callable(getattr(WorkerPool, name)), name
    assert set(WORKER_CALLS) == set(CALLS)
    for name in ("viewer_url", "worker_states"):  # answered by each host itself, not worker calls
        declared = inspect.signature(getattr(SceneHostInterface, name))
        for host_class in (SceneHost, WorkerPool):
            assert list(inspect.signature(getattr(host_class, name)).parameters) == list(declared.parameters), (host_class, name)
        assert name not in CALLS


def test_a_call_about_a_session_nobody_created_never_reaches_a_worker_and_pins_nothing(pool):
    pool, recorder = pool
    unknown = "never-made-" + secrets.token_hex(4)
    for name, call in CALLS.items():
        if call.creates or call.every_worker:
            continue
        args = {"session_id": unknown, "scene_id": "heavy-top", "motion": {"t_s": 0.0}, "seconds": 5.0}
        bound = [args[p] for p in inspect.signature(getattr(SceneHostInterface, name)).parameters if p in args and p != "seconds"]
        kwargs = {"seconds": 5.0} if name == "recording_html" else {}
        if call.unknown is RAISE:
            with pytest.raises(ValueError, match="has no scene yet"):
                getattr(pool, name)(*bound, **kwargs)
        else:
            assert getattr(pool, name)(*bound, **kwargs) == call.unknown, name
    assert recorder.calls == [] and pool.worker_index(unknown) is None and sum(pool._pinned_count) == 0


def test_sessions_are_pinned_by_the_call_that_creates_them_and_a_class_is_spread_evenly(pool):
    pool, recorder = pool
    ids = [f"class-{secrets.token_hex(4)}-{n:03d}" for n in range(100)]
    for session_id in ids:
        pool.set_params("heavy-top", session_id, {})
    assert sorted(pool._pinned_count) == [50, 50]
    workers = [pool.worker_index(i) for i in ids]
    for session_id, worker in zip(ids, workers, strict=True):  # every later call goes to the same worker
        pool.playback(session_id)
        assert recorder.calls[-1][:2] == (worker, "playback")
    pool.close_session(ids[0])
    assert pool.worker_index(ids[0]) is None and sum(pool._pinned_count) == 99


@pytest.mark.parametrize("refusal", [
    ValueError("crank_m: must be positive"),
    HostBusy("the derivations' places are taken", status=429),
    RuntimeError("scene worker failed"),
    WorkerUnavailableError("scene worker 0 is not answering"),
], ids=lambda exc: type(exc).__name__)  # fmt: skip
def test_a_first_change_refused_by_the_worker_pins_nothing(pool, monkeypatch, refusal):
    """Whatever refused it (bad input, a busy worker, a failure), a session that never came to exist holds no pin:
    a device could otherwise leak pins, and skew where new pages go, with refused first changes."""
    pool, _ = pool

    def refuse(index, call, args, kwargs, *, checking=False):
        raise refusal

    monkeypatch.setattr(pool, "_call", refuse)
    with pytest.raises(type(refusal)):
        pool.set_params("four-bar", "refused-first", {"crank_m": -1})
    assert pool.worker_index("refused-first") is None and sum(pool._pinned_count) == 0


def _answering_workers(pool, *answering: bool) -> list:
    from app.scenes.host.pool import _Worker

    pool._workers = [
        _Worker(n, process=None, start_pipe=None, viewer_url="ws://x", rpc_address=("127.0.0.1", 1), answering=up)  # type: ignore[arg-type]
        for n, up in enumerate(answering)
    ]
    return pool._workers


def test_new_pages_go_to_an_answering_worker_while_the_other_is_stopped(pool):
    """A stopped or restarting worker takes no new session while another answers (every new page got 503 before)."""
    pool, _ = pool
    _answering_workers(pool, False, True)
    assert {pool.worker_index(f"new-page-{n}", create=True) for n in range(20)} == {1}
    pool._restarting.add(1)
    pool._workers[0].answering = True
    assert {pool.worker_index(f"later-page-{n}", create=True) for n in range(20)} == {0}


def test_a_ping_needs_no_place_so_a_busy_worker_is_not_taken_for_a_sick_one(pool, monkeypatch):
    """Eight long calls (paced jumps, recordings, derivations) hold every place of a worker: its ping still goes
    through, so the supervisor never marks a busy worker "not answering" (which answered 503 to its whole class)."""
    pool, _ = pool
    monkeypatch.undo()
    from app.scenes.host import pool as pool_module
    from app.scenes.host.pool import CALLS_PER_WORKER

    class Answering:
        def send(self, message):
            self.asked = message

        def poll(self, timeout_s):
            return True

        def recv(self):
            return ("ok", 12.5)

        def close(self):
            pass

    (worker,) = _answering_workers(pool, True)
    for _ in range(CALLS_PER_WORKER):
        worker.places.acquire()
    monkeypatch.setattr(pool_module, "connect", lambda *args, **kwargs: Answering())
    monkeypatch.setattr(pool_module, "PLACE_WAIT_S", 0.2)
    pool._check(worker)
    assert worker.answering
    with pytest.raises(WorkerUnavailableError, match="calls waiting"):  # an ordinary call still waits its turn
        pool._call(0, CALLS["playback"], ("s",), {})


def test_a_worker_that_accepts_but_never_answers_costs_a_caller_a_bounded_wait():
    """A listener whose process never accepts or answers (a stopped worker): the key handshake times out."""
    silent = socket.create_server(("127.0.0.1", 0), backlog=8)
    try:
        started = time.monotonic()
        with pytest.raises(OSError):
            connect(silent.getsockname(), b"k" * 32, io_timeout_s=1.0)
        assert time.monotonic() - started < 5.0
    finally:
        silent.close()


def test_a_worker_whose_places_are_all_taken_answers_503_at_once_instead_of_queueing(pool, monkeypatch):
    pool, _ = pool
    monkeypatch.undo()
    from app.scenes.host import pool as pool_module
    from app.scenes.host.pool import CALLS_PER_WORKER, _Worker

    worker = _Worker(0, process=None, start_pipe=None, viewer_url="ws://x", rpc_address=("127.0.0.1", 1), answering=True)  # type: ignore[arg-type]
    pool._workers = [worker, None]
    pool.worker_index("busy-session-1", create=True)
    pool._pinned["busy-session-1"] = 0
    for _ in range(CALLS_PER_WORKER):
        worker.places.acquire()
    monkeypatch.setattr(pool_module, "PLACE_WAIT_S", 0.2)
    started = time.monotonic()
    with pytest.raises(WorkerUnavailableError, match="calls waiting"):
        pool.playback("busy-session-1")
    assert time.monotonic() - started < 1.0
    worker.answering = False
    with pytest.raises(WorkerUnavailableError, match="not answering"):
        pool.playback("busy-session-1")


def test_one_slow_ping_is_not_a_stopped_worker_but_two_in_a_row_are(pool, monkeypatch):
    """A freshly restarted worker loading its kernels on a loaded machine may miss one ping: marking it not answering
    then cut its class off with 503s for a moment. Two missed in a row mark it; one answered clears the count."""
    pool, _ = pool
    monkeypatch.undo()
    from app.scenes.host import pool as pool_module
    from app.scenes.host.pool import MISSED_PINGS

    (worker,) = _answering_workers(pool, True)

    def unreachable(*args, **kwargs):
        raise OSError("no answer")

    monkeypatch.setattr(pool_module, "connect", unreachable)
    for _ in range(MISSED_PINGS - 1):
        pool._check(worker)
    assert worker.answering
    pool._check(worker)
    assert not worker.answering


def test_a_stopped_process_is_told_from_a_running_or_gone_one():
    """What ``WorkerPool.stop`` asks before it waits for a worker: one SIGSTOP'd by someone cannot exit by itself and is
    killed at once (waiting STOP_TIMEOUT_S for it cost Ctrl+C 2 of its 5 s: tests/api/test_faults.py)."""
    import signal
    import subprocess
    import sys

    from app.scenes.host.pool import _is_stopped
    from tests.conftest import wait_until

    child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    try:
        assert not _is_stopped(child.pid)
        child.send_signal(signal.SIGSTOP)
        wait_until(lambda: _is_stopped(child.pid), 10, what="the child to be stopped")
        child.send_signal(signal.SIGCONT)
        wait_until(lambda: not _is_stopped(child.pid), 10, what="the child to run again")
    finally:
        child.kill()
        child.wait()
    assert not _is_stopped(child.pid)  # gone
