"""Scene workers: several :class:`SceneHost` processes behind one front, each session pinned to one.

The front process (FastAPI: pages, API, the viewer relay) keeps no scene. A
session is pinned to a worker by the call that creates it (the page's first
parameters, a room's stage) — the worker with the fewest sessions pinned, so a
class that arrives at once is spread evenly — and keeps it until it is closed.
Every call of :class:`~app.scenes.host.interface.SceneHostInterface` that names a
session goes to its worker; the forwarders are derived from the interface's
declarations. A call about a session nobody created never reaches a worker.

No call waits forever and a sick worker stays sick alone:

* each worker has its own share of the front's threads (:data:`CALLS_PER_WORKER`
  calls at once; a call that cannot get a place within :data:`PLACE_WAIT_S` is
  answered 503), so a stopped worker never takes the threads the other worker, the
  pages and ``/api/health`` need;
* every call has connect and answer timeouts (:mod:`app.scenes.host.rpc`);
* a supervisor pings each worker every second; one that does not answer within
  :data:`~app.scenes.host.interface.PING_TIMEOUT_S` twice in a row (:data:`MISSED_PINGS`)
  is marked *not answering* and its calls fail at once (503 with Retry-After) until
  it answers again.

Nothing is lost when a worker dies: the supervisor keeps a snapshot of every
session (parameters, play state, time scale, motion, camera), refreshed every
second and after every change, and restores each one in the restarted worker
before it takes calls again; its viewers reconnect through the relay (the viewer
retries by itself) and find their scene as it was.
"""

from __future__ import annotations

import inspect
import logging
import multiprocessing
import queue
import secrets
import threading
import time
import zlib
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from multiprocessing import AuthenticationError
from multiprocessing.connection import Connection
from typing import TYPE_CHECKING, Any

from app.physics.core.bounded import (
    DEFAULT_PRELOAD,
    forkserver_context,
    process_stat_fields,
    yield_only_to_live_scenes,
)
from app.scenes.host.host import UnknownSceneError, check_session_id
from app.scenes.host.interface import CALLS, RAISE, Call, SceneHostInterface
from app.scenes.host.rpc import WorkerUnavailableError, connect, raise_answer
from app.scenes.host.worker import run_worker
from app.scenes.kit import Scene

log = logging.getLogger(__name__)

#: How long a worker may take to start and bind its ports (s); the forkserver's first import of the scenes with a cold
#: numba cache is the slow part.
START_TIMEOUT_S = 180.0
#: What the forkserver the workers are forked from imports once: every scene (their numba kernels load from the disk
#: cache then) and the worker's entry, besides what bounded work needs. A worker then starts in about 0.1 s, not the
#: 2 s of CPU a new interpreter took to import them (measured on the 2-core test machine, warm caches), and one killed
#: mid-class is back that much sooner.
WORKER_PRELOAD = (*DEFAULT_PRELOAD, "app.scenes.host.worker", "app.scenes")
#: Calls one worker may have in flight from the front at once: its share of the front's threads (AnyIO's pool has 40).
CALLS_PER_WORKER = 8
#: Longest a call waits for one of its worker's places before the front answers 503 (s).
PLACE_WAIT_S = 1.0
#: The supervisor's period (s): pings, snapshots, restarts.
SUPERVISE_PERIOD_S = 1.0
#: Pings missed in a row before a worker is marked not answering: one slow ping (a freshly restarted worker loading
#: its compiled kernels on a loaded machine) is not a stopped worker, and marking it so cut its class off with 503s.
MISSED_PINGS = 2
#: Longest a read or write on a call's connection may make no progress (s), once its answer has begun.
IO_TIMEOUT_S = 10.0
#: Longest ``stop`` waits for the workers to exit by themselves before killing them (s).
STOP_TIMEOUT_S = 2.0


def _is_stopped(pid: int | None) -> bool:
    """Whether process ``pid`` is stopped (SIGSTOP: state ``T``, or ``t`` under a debugger), from Linux's
    ``/proc/<pid>/stat``; False if it cannot be read (gone already)."""
    try:
        return process_stat_fields(pid)[0] in ("T", "t")
    except (OSError, IndexError):
        return False


@dataclass
class _Worker:
    index: int
    process: Any  # multiprocessing.Process (forkserver context)
    start_pipe: Connection
    viewer_url: str
    rpc_address: tuple[str, int]
    idle_connections: queue.SimpleQueue = field(default_factory=queue.SimpleQueue)
    places: threading.BoundedSemaphore = field(default_factory=lambda: threading.BoundedSemaphore(CALLS_PER_WORKER))
    #: False from :data:`MISSED_PINGS` missed pings in a row (or while its sessions are being restored) until it
    #: answers again: calls fail fast.
    answering: bool = False
    missed_pings: int = 0


class WorkerPool(SceneHostInterface):
    """``workers`` scene-worker processes on loopback and the calls that reach them."""

    if TYPE_CHECKING:  # the session calls installed after the class, each forwarded to the session's worker
        session_params = SceneHostInterface.session_params
        session_scene = SceneHostInterface.session_scene
        playback = SceneHostInterface.playback
        camera = SceneHostInterface.camera
        live_readout = SceneHostInterface.live_readout
        viewer_count = SceneHostInterface.viewer_count
        graph = SceneHostInterface.graph
        recording_html = SceneHostInterface.recording_html
        motion_state = SceneHostInterface.motion_state
        stage_viewer_url = SceneHostInterface.stage_viewer_url
        stage_viewers = SceneHostInterface.stage_viewers

    def __init__(
        self,
        scenes: Mapping[str, type[Scene]],
        *,
        workers: int,
        frame_rate_hz: float = 30.0,
        max_sessions: int = 2000,
        log_level: str = "WARNING",
    ) -> None:
        if workers < 1:
            raise ValueError("workers: at least one scene worker (0 means no pool: one in-process host)")
        self.scenes = dict(scenes)
        self.worker_count = workers
        self.max_sessions = max_sessions
        # A worker's own eviction is only a backstop: the front's session directory bounds sessions and closes them.
        self._options = {"frame_rate_hz": frame_rate_hz, "max_sessions": 2 * max_sessions, "log_level": log_level}
        self._authkey = secrets.token_bytes(32)
        # Workers are forked from the forkserver (a process of its own, with no threads, that imported the scenes
        # once), never from this process, which runs threads.
        self._context: multiprocessing.context.ForkServerContext | None = None
        self._workers: list[_Worker | None] = [None] * workers
        self._restarting: set[int] = set()
        #: Session id -> the worker it is pinned to, and sessions pinned per worker (a creating call pins).
        self._pinned: dict[str, int] = {}
        self._pinned_count = [0] * workers
        self._pin_lock = threading.Lock()
        #: Sessions a creating call has made (a refused first call pins nothing), and each one's latest snapshot.
        self._created: set[str] = set()
        self._snapshots: dict[str, dict[str, Any]] = {}
        self._stopping = threading.Event()
        self._supervisor: threading.Thread | None = None

    # -- life cycle ---------------------------------------------------------------
    def start(self) -> None:
        """Start every worker (in parallel) and wait until each reports its ports."""
        launched = [self._launch(index) for index in range(self.worker_count)]
        for index, (process, pipe) in enumerate(launched):
            self._workers[index] = self._await_ready(index, process, pipe)
            self._workers[index].answering = True  # type: ignore[union-attr]
        self._supervisor = threading.Thread(target=self._supervise, name="scene-worker-supervisor", daemon=True)
        self._supervisor.start()
        yield_only_to_live_scenes(lambda: self.total_viewers() > 0)  # the front's derivations: as in each worker
        log.info("%d scene workers ready", self.worker_count)

    def stop(self) -> None:
        """Stop every worker within :data:`STOP_TIMEOUT_S` (then kill what is left; a stopped one at once: waiting for
        it cost Ctrl+C 2 of its 5 s); calls in flight fail at once."""
        self._stopping.set()
        workers = [worker for worker in self._workers if worker is not None]
        for worker in workers:
            worker.answering = False
            try:
                worker.start_pipe.send("stop")
            except (OSError, EOFError):
                pass
        for worker in workers:
            if _is_stopped(worker.process.pid):  # SIGSTOP'd by someone: it cannot stop by itself, so do not wait for it
                worker.process.kill()
        deadline = time.monotonic() + STOP_TIMEOUT_S
        for worker in workers:
            worker.process.join(timeout=max(0.0, deadline - time.monotonic()))
        for worker in workers:
            if worker.process.is_alive():
                worker.process.kill()
                worker.process.join(timeout=1.0)
            self._close_connections(worker)

    def _launch(self, index: int) -> tuple[Any, Connection]:
        if self._context is None:
            self._context = forkserver_context(WORKER_PRELOAD)
        front_end, worker_end = self._context.Pipe()
        process = self._context.Process(
            target=run_worker,
            args=(index, worker_end, self._authkey, self._options),
            name=f"dynlab-scene-worker-{index}",
            # a worker starts children of its own (a typed Lagrangian's bounded derivation);
            # it ends with the front by its pipe
            daemon=False,
        )
        process.start()
        worker_end.close()
        return process, front_end

    def _await_ready(self, index: int, process: Any, pipe: Connection) -> _Worker:
        if not pipe.poll(START_TIMEOUT_S):
            process.kill()
            raise RuntimeError(f"scene worker {index} did not start within {START_TIMEOUT_S:.0f} s")
        try:
            ready = pipe.recv()
        except EOFError:
            raise RuntimeError(
                f"scene worker {index} exited while starting (exit code {process.exitcode}); see its log"
            ) from None
        return _Worker(index, process, pipe, ready["viewer_url"], tuple(ready["rpc_address"]))

    # -- supervision: pings, snapshots, restarts ----------------------------------------------
    def _supervise(self) -> None:
        while not self._stopping.wait(SUPERVISE_PERIOD_S):
            for index, worker in enumerate(self._workers):
                if worker is None or index in self._restarting or self._stopping.is_set():
                    continue
                if not worker.process.is_alive():
                    self._restarting.add(index)
                    threading.Thread(
                        target=self._restart, args=(index, worker), name=f"restart-worker-{index}", daemon=True
                    ).start()
                    continue
                self._check(worker)

    def _check(self, worker: _Worker) -> None:
        """Ping the worker (marking it answering or not) and, if it answers, keep its sessions' snapshots."""
        try:
            self._call(worker.index, CALLS["ping"], (), {}, checking=True)
        except WorkerUnavailableError as exc:
            worker.missed_pings += 1
            if worker.answering and worker.missed_pings >= MISSED_PINGS:
                log.error(
                    "scene worker %d is not answering (%s): its sessions get 503 until it does", worker.index, exc
                )
                worker.answering = False
            return
        worker.missed_pings = 0
        if not worker.answering:
            log.warning("scene worker %d answers again", worker.index)
        worker.answering = True
        try:
            snapshots = self._call(worker.index, CALLS["snapshot"], (), {})
        except Exception as exc:
            log.warning("snapshot of scene worker %d failed: %s", worker.index, exc)
            return
        with self._pin_lock:
            for session_id, snapshot in snapshots.items():
                if self._pinned.get(session_id) == worker.index:
                    self._snapshots[session_id] = snapshot

    def _restart(self, index: int, dead: _Worker) -> None:
        """Start a new worker in ``dead``'s place and restore every session pinned to it before it takes calls."""
        try:
            log.error("scene worker %d exited (code %s): restarting it", index, dead.process.exitcode)
            self._close_connections(dead)
            # Its start pipe too: a worker reported dead because the forkserver that reports its exit died (killed)
            # is in fact alive; the pipe's end tells it to stop (and no descriptor is kept per restart).
            try:
                dead.start_pipe.close()
            except OSError:
                pass
            self._workers[index] = None
            while not self._stopping.is_set():
                try:
                    worker = self._await_ready(index, *self._launch(index))
                    break
                except RuntimeError:
                    log.exception("restarting scene worker %d failed; trying again", index)
            else:
                return
            worker.answering = False  # calls wait for the restore below (503 meanwhile)
            self._workers[index] = worker
            with self._pin_lock:
                pinned = [(sid, self._snapshots.get(sid)) for sid, where in self._pinned.items() if where == index]
            restored = 0
            for session_id, snapshot in pinned:
                if snapshot is None:
                    continue
                try:
                    self._call(index, CALLS["restore"], (session_id, snapshot), {}, checking=True)
                    restored += 1
                except Exception:
                    log.exception("restoring session %s in scene worker %d failed", session_id, index)
            worker.answering = True
            log.warning("scene worker %d restarted; %d of %d sessions restored", index, restored, len(pinned))
        finally:
            self._restarting.discard(index)

    def worker_states(self) -> list[dict[str, Any]]:
        """Each worker's state as the front last saw it (no call is made): for ``/api/health``."""
        states = []
        for index, worker in enumerate(self._workers):
            state = (
                "restarting"
                if worker is None or index in self._restarting
                else "answering"
                if worker.answering
                else "not answering"
            )
            states.append({"index": index, "state": state})
        return states

    # -- pinning and calls ----------------------------------------------------------
    def worker_index(self, session_id: str, *, create: bool = False) -> int | None:
        """The worker that holds ``session_id``; with ``create``, a new session is pinned to the least loaded of the
        workers answering now (a stopped or restarting worker takes no new page while another answers)."""
        with self._pin_lock:
            index = self._pinned.get(session_id)
            if index is not None or not create:
                return index
            open_to_new = [
                i
                for i, worker in enumerate(self._workers)
                if worker is not None and worker.answering and i not in self._restarting
            ]
            counts = {i: self._pinned_count[i] for i in (open_to_new or range(len(self._workers)))}
            fewest = min(counts.values())
            candidates = [i for i, count in counts.items() if count == fewest]
            index = candidates[zlib.crc32(session_id.encode()) % len(candidates)]
            self._pinned[session_id] = index
            self._pinned_count[index] += 1
            return index

    def _unpin(self, session_id: str) -> None:
        with self._pin_lock:
            index = self._pinned.pop(session_id, None)
            if index is not None:
                self._pinned_count[index] -= 1
            self._created.discard(session_id)
            self._snapshots.pop(session_id, None)

    def _call(self, index: int, call: Call, args: tuple, kwargs: dict, *, checking: bool = False) -> Any:
        """``call`` in worker ``index``, within its share of places and its answer timeout; ``checking`` calls (the
        supervisor's) go to a worker not marked answering too, and take no place: a worker whose places are all held
        by long calls (paced jumps, recordings, derivations) is busy, not sick, and its ping still answers."""
        worker = self._workers[index]
        if worker is None or not (worker.answering or checking):
            raise WorkerUnavailableError(
                f"scene worker {index} is {'restarting' if worker is None else 'not answering'}"
            )
        if not checking and not worker.places.acquire(timeout=PLACE_WAIT_S):
            raise WorkerUnavailableError(f"scene worker {index} has {CALLS_PER_WORKER} calls waiting already")
        try:
            try:
                connection = worker.idle_connections.get_nowait()
            except queue.Empty:
                try:
                    connection = connect(worker.rpc_address, self._authkey, io_timeout_s=IO_TIMEOUT_S)
                except (OSError, EOFError, AuthenticationError) as exc:
                    raise WorkerUnavailableError(f"scene worker {index} is not answering ({exc})") from None
            try:
                connection.send((call.name, args, kwargs))
                if not connection.poll(call.answer_timeout_s):
                    raise TimeoutError(f"no answer within {call.answer_timeout_s:g} s")
                answer = connection.recv()
            except (OSError, EOFError, TimeoutError) as exc:
                connection.close()
                raise WorkerUnavailableError(f"scene worker {index} did not answer {call.name} ({exc})") from None
            worker.idle_connections.put(connection)
        finally:
            if not checking:
                worker.places.release()
        return raise_answer(answer)

    @staticmethod
    def _close_connections(worker: _Worker) -> None:
        while True:
            try:
                worker.idle_connections.get_nowait().close()
            except queue.Empty:
                return

    def _forward(self, call: Call, session_id: str, args: tuple, kwargs: dict) -> Any:
        """A session's call, in the worker that holds it; :attr:`Call.unknown` for a session none holds."""
        index = self.worker_index(session_id, create=call.creates)
        if index is None:
            if call.unknown is RAISE:
                raise ValueError(f"session {session_id!r} has no scene yet: set its parameters first")
            return call.unknown
        try:
            answer = self._call(index, call, args, kwargs)
        except Exception:  # refused (bad input, busy, unreachable) before it existed: nothing to keep
            if call.creates and session_id not in self._created:
                self._unpin(session_id)
            raise
        if call.creates:
            with self._pin_lock:
                self._created.add(session_id)
        return answer

    def _keep_snapshot(self, session_id: str) -> None:
        """After a change: the session's snapshot now, so a restart right after it restores the change."""
        index = self.worker_index(session_id)
        if index is None:
            return
        try:
            found = self._call(index, CALLS["snapshot"], ([session_id],), {})
        except Exception as exc:  # the supervisor's next snapshot will do
            log.debug("snapshot of %s after a change failed: %s", session_id, exc)
            return
        with self._pin_lock:
            if session_id in found and self._pinned.get(session_id) == index:
                self._snapshots[session_id] = found[session_id]

    # -- the interface: what is answered here, and what changes the session table ------------------
    def scene_class(self, scene_id: str) -> type[Scene]:
        try:
            return self.scenes[scene_id]
        except KeyError:
            raise UnknownSceneError(scene_id) from None

    def set_params(
        self, scene_id: str, session_id: str, raw: Mapping[str, Any], *, stage: bool = False
    ) -> dict[str, Any]:
        check_session_id(session_id, stage=stage)
        self.scene_class(scene_id)
        params = self._forward(CALLS["set_params"], session_id, (scene_id, session_id, dict(raw)), {"stage": stage})
        self._keep_snapshot(session_id)
        return params

    def open_stage(self, session_id: str, scene_id: str, raw: Mapping[str, Any]) -> dict[str, Any]:
        self.scene_class(scene_id)
        answer = self._forward(CALLS["open_stage"], session_id, (session_id, scene_id, dict(raw)), {})
        self._keep_snapshot(session_id)
        return answer

    def set_playback(self, session_id: str, **playback: Any) -> dict[str, Any]:
        answer = self._forward(CALLS["set_playback"], session_id, (session_id,), playback)
        self._keep_snapshot(session_id)
        return answer

    def resume_from(self, session_id: str, motion: Mapping[str, Any]) -> None:
        self._forward(CALLS["resume_from"], session_id, (session_id, dict(motion)), {})
        self._keep_snapshot(session_id)

    def close_session(self, session_id: str) -> None:
        try:
            self._forward(CALLS["close_session"], session_id, (session_id,), {})
        finally:
            self._unpin(session_id)

    def close_stage(self, session_id: str) -> None:
        try:
            self._forward(CALLS["close_stage"], session_id, (session_id,), {})
        finally:
            self._unpin(session_id)

    def restore(self, session_id: str, snapshot: Mapping[str, Any]) -> None:
        self._forward(CALLS["restore"], session_id, (session_id, dict(snapshot)), {})
        self._keep_snapshot(session_id)

    def snapshot(self, session_ids: list[str] | None = None) -> dict[str, dict[str, Any]]:
        """The snapshots the supervisor keeps (no call is made): every session's, or the ones named."""
        with self._pin_lock:
            if session_ids is None:
                return dict(self._snapshots)
            return {sid: self._snapshots[sid] for sid in session_ids if sid in self._snapshots}

    def ping(self) -> float:
        return time.monotonic()

    def total_viewers(self) -> int:
        """Viewers of every answering worker (a worker not answering counts none)."""
        total = 0
        for index, worker in enumerate(self._workers):
            if worker is not None and worker.answering:
                try:
                    total += self._call(index, CALLS["total_viewers"], (), {})
                except WorkerUnavailableError:
                    pass
        return total

    def viewer_url(self, session_id: str) -> str:
        """The loopback websocket address of the worker that holds ``session_id`` (503 while it restarts)."""
        index = self.worker_index(session_id)
        if index is None:
            raise ValueError(f"session {session_id!r} has no scene yet: set its parameters first")
        worker = self._workers[index]
        if worker is None or not worker.answering:
            raise WorkerUnavailableError(f"scene worker {index} is not answering")
        return worker.viewer_url

    def worker_pids(self) -> list[int]:
        """Process ids of the running workers (for capacity reports)."""
        return [worker.process.pid for worker in self._workers if worker is not None]


def _forwarder(call: Call) -> Callable[..., Any]:
    """A pool method that sends ``call`` to the worker holding the session its arguments name."""
    signature = inspect.signature(getattr(SceneHostInterface, call.name))

    def forward(self: WorkerPool, *args: Any, **kwargs: Any) -> Any:
        session_id = signature.bind(self, *args, **kwargs).arguments["session_id"]
        return self._forward(call, session_id, args, kwargs)

    forward.__name__ = forward.__qualname__ = call.name
    forward.__doc__ = f"As ``SceneHost.{call.name}``, in the session's worker."
    return forward


# Every session call the pool does not answer itself goes to the session's worker.
for _call in CALLS.values():
    if _call.name not in WorkerPool.__dict__:
        assert not _call.every_worker, f"{_call.name}: a call to every worker needs its own pool method"
        setattr(WorkerPool, _call.name, _forwarder(_call))
