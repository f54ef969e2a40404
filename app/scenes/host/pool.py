"""Scene workers: several :class:`SceneHost` processes behind one front, each session pinned to one.

The front process (FastAPI: pages, API, the viewer relay) keeps no scene. A
session is pinned to one worker the first time the front sees its id — the
worker with the fewest sessions pinned so far — and keeps it (a bounded table,
least recently used dropped first), so a session's page, its viewers and its
parameter changes all meet in one process, and a class that arrives at once is
spread evenly (hashing ids left one worker with a third more students than the
other). :class:`WorkerPool` offers the
in-process host's interface (``set_params``, ``live_readout``, ``viewer_count``,
``viewer_url``, ``scene_class``, ``scenes``) by calling the pinned worker.

A worker that dies is restarted by a supervisor thread; the parameters last set
on each of its sessions are applied again, and its viewers reconnect through the
relay (the viewer retries by itself), so students see a short pause, not a loss.
"""

from __future__ import annotations

import logging
import multiprocessing
import queue
import secrets
import threading
import zlib
from collections import OrderedDict
from collections.abc import Mapping
from dataclasses import dataclass, field
from multiprocessing.connection import Client, Connection
from typing import Any

from app.scenes.host.host import UnknownSceneError, check_session_id
from app.scenes.host.rpc import WorkerUnavailableError, raise_answer
from app.scenes.host.worker import run_worker
from app.scenes.kit import Scene

log = logging.getLogger(__name__)

#: How long a worker may take to import the scenes and bind its ports (s); a cold numba cache is the slow part.
START_TIMEOUT_S = 180.0
#: How long a call may wait for its answer (s); validating a typed curve compiles it, the slowest call.
CALL_TIMEOUT_S = 30.0


@dataclass
class _Worker:
    index: int
    process: Any  # multiprocessing.Process (spawn context)
    start_pipe: Connection
    viewer_url: str
    rpc_address: tuple[str, int]
    idle_connections: queue.SimpleQueue = field(default_factory=queue.SimpleQueue)


class WorkerPool:
    """``workers`` scene-worker processes on loopback and the calls that reach them."""

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
        self._options = {"frame_rate_hz": frame_rate_hz, "max_sessions": max_sessions, "log_level": log_level}
        self._authkey = secrets.token_bytes(32)
        self._context = multiprocessing.get_context("spawn")  # never fork a process that runs threads
        self._workers: list[_Worker | None] = [None] * workers
        #: Session id -> the worker it is pinned to (least recently used first), and sessions pinned per worker.
        self._pinned: OrderedDict[str, int] = OrderedDict()
        self._pinned_count = [0] * workers
        self._pin_lock = threading.Lock()
        #: The parameters last set on each session (front-side copy, applied again after a worker restart).
        self._session_params: OrderedDict[str, tuple[str, dict[str, Any]]] = OrderedDict()
        #: Sessions that are stages (a room's shared scene): opened again, not merely re-parameterised, after a restart.
        self._stages: set[str] = set()
        self._params_lock = threading.Lock()
        self._restart_lock = threading.Lock()
        self._stopping = threading.Event()
        self._supervisor: threading.Thread | None = None

    # -- life cycle ---------------------------------------------------------------
    def start(self) -> None:
        """Start every worker (in parallel) and wait until each reports its ports."""
        launched = [self._launch(index) for index in range(self.worker_count)]
        for index, (process, pipe) in enumerate(launched):
            self._workers[index] = self._await_ready(index, process, pipe)
        self._supervisor = threading.Thread(target=self._supervise, name="scene-worker-supervisor", daemon=True)
        self._supervisor.start()
        log.info("%d scene workers ready", self.worker_count)

    def stop(self) -> None:
        self._stopping.set()
        for worker in self._workers:
            if worker is None:
                continue
            try:
                worker.start_pipe.send("stop")
            except (OSError, EOFError):
                pass
        for worker in self._workers:
            if worker is None:
                continue
            worker.process.join(timeout=5.0)
            if worker.process.is_alive():
                worker.process.terminate()
                worker.process.join(timeout=2.0)
            self._close_connections(worker)

    def _launch(self, index: int) -> tuple[Any, Connection]:
        front_end, worker_end = self._context.Pipe()
        process = self._context.Process(
            target=run_worker, args=(index, worker_end, self._authkey, self._options), name=f"dynlab-scene-worker-{index}", daemon=False
        )
        process.start()
        worker_end.close()
        return process, front_end

    def _await_ready(self, index: int, process: Any, pipe: Connection) -> _Worker:
        if not pipe.poll(START_TIMEOUT_S):
            process.terminate()
            raise RuntimeError(f"scene worker {index} did not start within {START_TIMEOUT_S:.0f} s")
        try:
            ready = pipe.recv()
        except EOFError:
            raise RuntimeError(f"scene worker {index} exited while starting (exit code {process.exitcode}); see its log") from None
        return _Worker(index, process, pipe, ready["viewer_url"], tuple(ready["rpc_address"]))

    def _supervise(self) -> None:
        while not self._stopping.wait(1.0):
            for index, worker in enumerate(self._workers):
                if worker is not None and not worker.process.is_alive() and not self._stopping.is_set():
                    self._restart(index, worker)

    def _restart(self, index: int, dead: _Worker) -> None:
        with self._restart_lock:
            log.error("scene worker %d exited (code %s): restarting it", index, dead.process.exitcode)
            self._close_connections(dead)
            try:
                self._workers[index] = self._await_ready(index, *self._launch(index))
            except RuntimeError:
                log.exception("restarting scene worker %d failed; trying again", index)
                return
        with self._params_lock:
            pinned = [(sid, scene_id, params) for sid, (scene_id, params) in self._session_params.items() if self.worker_index(sid) == index]
        for session_id, scene_id, params in pinned:
            try:
                self._call(index, "open_stage" if session_id in self._stages else "set_params", *(
                    (session_id, scene_id, params) if session_id in self._stages else (scene_id, session_id, params)
                ))
            except Exception:
                log.exception("applying session %s's parameters again failed", session_id)

    # -- pinning and calls ----------------------------------------------------------
    def worker_index(self, session_id: str) -> int:
        """The worker that serves ``session_id``: pinned on first sight to the least loaded, then always the same."""
        with self._pin_lock:
            index = self._pinned.get(session_id)
            if index is not None:
                self._pinned.move_to_end(session_id)
                return index
            fewest = min(self._pinned_count)
            candidates = [i for i, count in enumerate(self._pinned_count) if count == fewest]
            index = candidates[zlib.crc32(session_id.encode()) % len(candidates)]
            self._pinned[session_id] = index
            self._pinned_count[index] += 1
            while len(self._pinned) > self.max_sessions:
                _, dropped = self._pinned.popitem(last=False)
                self._pinned_count[dropped] -= 1
            return index

    def _worker(self, index: int) -> _Worker:
        worker = self._workers[index]
        if worker is None:
            raise WorkerUnavailableError(f"scene worker {index} is not running")
        return worker

    def _call(self, index: int, method: str, *args: Any, **kwargs: Any) -> Any:
        worker = self._worker(index)
        try:
            connection = worker.idle_connections.get_nowait()
        except queue.Empty:
            try:
                connection = Client(worker.rpc_address, authkey=self._authkey)
            except OSError as exc:
                raise WorkerUnavailableError(f"scene worker {index} is not answering ({exc})") from None
        try:
            connection.send((method, args, kwargs))
            if not connection.poll(CALL_TIMEOUT_S):
                raise TimeoutError(f"no answer within {CALL_TIMEOUT_S:.0f} s")
            answer = connection.recv()
        except (OSError, EOFError, TimeoutError) as exc:
            connection.close()
            raise WorkerUnavailableError(f"scene worker {index} did not answer {method} ({exc})") from None
        worker.idle_connections.put(connection)
        return raise_answer(answer)

    @staticmethod
    def _close_connections(worker: _Worker) -> None:
        while True:
            try:
                worker.idle_connections.get_nowait().close()
            except queue.Empty:
                return

    # -- the host interface the routes and the relay use ------------------------------
    def scene_class(self, scene_id: str) -> type[Scene]:
        try:
            return self.scenes[scene_id]
        except KeyError:
            raise UnknownSceneError(scene_id) from None

    def set_params(self, scene_id: str, session_id: str, raw: Mapping[str, Any], *, stage: bool = False) -> dict[str, Any]:
        """As :meth:`SceneHost.set_params`, in the session's worker."""
        check_session_id(session_id, stage=stage)
        self.scene_class(scene_id)
        params = self._call(self.worker_index(session_id), "set_params", scene_id, session_id, dict(raw), stage=stage)
        self._remember(session_id, scene_id, params)
        return params

    def _remember(self, session_id: str, scene_id: str, params: dict[str, Any]) -> None:
        with self._params_lock:
            self._session_params[session_id] = (scene_id, params)
            self._session_params.move_to_end(session_id)
            while len(self._session_params) > self.max_sessions:
                self._session_params.popitem(last=False)

    def open_stage(self, session_id: str, scene_id: str, raw: Mapping[str, Any]) -> dict[str, Any]:
        """As :meth:`SceneHost.open_stage`, in the session's worker (opened again there if the worker restarts)."""
        self.scene_class(scene_id)
        answer = self._call(self.worker_index(session_id), "open_stage", session_id, scene_id, dict(raw))
        with self._params_lock:
            self._stages.add(session_id)
        self._remember(session_id, scene_id, answer["params"])
        return answer

    def close_stage(self, session_id: str) -> None:
        with self._params_lock:
            self._stages.discard(session_id)
            self._session_params.pop(session_id, None)
        self._call(self.worker_index(session_id), "close_stage", session_id)

    def stage_viewer_url(self, session_id: str) -> str | None:
        """The stage's loopback websocket address now (it changes when its worker restarts), or None."""
        return self._call(self.worker_index(session_id), "stage_viewer_url", session_id)

    def set_playback(self, session_id: str, **playback: Any) -> dict[str, Any]:
        return self._call(self.worker_index(session_id), "set_playback", session_id, **playback)

    def playback(self, session_id: str) -> dict[str, Any] | None:
        return self._call(self.worker_index(session_id), "playback", session_id)

    def graph(self, session_id: str, **options: Any) -> dict[str, Any] | None:
        return self._call(self.worker_index(session_id), "graph", session_id, **options)

    def stage_viewers(self, session_id: str) -> int:
        return self._call(self.worker_index(session_id), "stage_viewers", session_id)

    def camera(self, session_id: str) -> dict[str, list[float]] | None:
        return self._call(self.worker_index(session_id), "camera", session_id)

    def motion_state(self, session_id: str) -> dict[str, Any] | None:
        return self._call(self.worker_index(session_id), "motion_state", session_id)

    def resume_from(self, session_id: str, motion: Mapping[str, Any]) -> None:
        self._call(self.worker_index(session_id), "resume_from", session_id, dict(motion))

    def recording_html(self, scene_id: str, session_id: str, *, seconds: float) -> str | None:
        """As :meth:`SceneHost.recording_html`, in the session's worker (under a second for 60 s of motion, measured)."""
        return self._call(self.worker_index(session_id), "recording_html", scene_id, session_id, seconds=seconds)

    def session_params(self, session_id: str) -> dict[str, Any] | None:
        return self._call(self.worker_index(session_id), "session_params", session_id)

    def live_readout(self, scene_id: str, session_id: str) -> dict[str, Any] | None:
        return self._call(self.worker_index(session_id), "live_readout", scene_id, session_id)

    def viewer_count(self, session_id: str | None = None) -> int:
        if session_id is not None:
            return self._call(self.worker_index(session_id), "viewer_count", session_id)
        return sum(self._call(index, "viewer_count") for index in range(self.worker_count))

    def viewer_url(self, session_id: str) -> str:
        """The loopback websocket address of the worker that serves ``session_id``."""
        return self._worker(self.worker_index(session_id)).viewer_url

    def worker_pids(self) -> list[int]:
        """Process ids of the running workers (for capacity reports)."""
        return [worker.process.pid for worker in self._workers if worker is not None]
