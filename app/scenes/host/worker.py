"""A scene worker: one process running a :class:`SceneHost` for the sessions pinned to it.

The front process (FastAPI, the relay) starts workers with :func:`run_worker`
as the target of a ``spawn`` process. Each worker binds its viser server and a
call listener on loopback, reports both addresses on its start pipe, then answers
the calls of :mod:`app.scenes.host.interface` (over :mod:`app.scenes.host.rpc`)
from one thread per connection. It exits when told to, or by itself when the
front process's end of the start pipe closes (the front died), so no worker
outlives its server. Workers are not daemonic processes: a worker starts
children of its own (the bounded derivation of a typed Lagrangian).
"""

from __future__ import annotations

import gc
import logging
import os
import signal
import socket
import threading
from multiprocessing import AuthenticationError
from multiprocessing.connection import Connection
from typing import Any

log = logging.getLogger(__name__)

#: Connections the worker's call listener queues before accepting (each is accepted at once, then authenticated in
#: its own thread); the front opens at most a few per worker (:data:`app.scenes.host.pool.CALLS_PER_WORKER`).
CALL_BACKLOG = 128


class ViewerMessageRefused(logging.Filter):
    """A viewer that sends what viser cannot decode (garbage bytes, a message type it does not take) ends its own
    connection; websockets logs that with a full traceback, which anyone who may watch a session could make the server
    write twice a second. Such a record becomes one warning line naming the error."""

    def filter(self, record: logging.LogRecord) -> bool:
        if record.msg == "connection handler failed" and record.exc_info and record.exc_info[1] is not None:
            error = record.exc_info[1]
            record.msg, record.args = (
                "a viewer's connection ended on a message it could not use (%s: %s)",
                (type(error).__name__, error),
            )
            record.levelno, record.levelname = logging.WARNING, "WARNING"
            record.exc_info = record.exc_text = None
        return True


#: Scene worker ``N`` is called ``dynlab-worker<N>`` in ``ps`` and ``top`` (Linux's process name, at most 15 bytes).
PROCESS_NAME_PREFIX = "dynlab-worker"


def process_name(index: int) -> str:
    """What scene worker ``index`` is called in ``ps`` and ``top``."""
    return f"{PROCESS_NAME_PREFIX}{index}"


def _name_this_process(name: str) -> None:
    """Every worker is a fork of the same forkserver, with its command line: its name says which process it is."""
    try:
        with open("/proc/self/comm", "w", encoding="ascii") as comm:
            comm.write(name[:15])
    except OSError:  # not Linux: the name is only a convenience
        pass


def run_worker(index: int, start_pipe: Connection, authkey: bytes, options: dict[str, Any]) -> None:
    """Process entry: serve scenes until ``"stop"`` arrives on ``start_pipe`` or it closes.

    Ctrl+C in a terminal reaches every process of ``dynlab serve``'s group, this one too: it is ignored here (it printed
    a KeyboardInterrupt traceback per worker), as the front stops its workers through their pipes, in order."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    _name_this_process(process_name(index))
    logging.basicConfig(
        level=options.get("log_level", "WARNING"), format=f"%(levelname)s worker{index} %(name)s: %(message)s"
    )
    logging.getLogger("websockets.server").addFilter(ViewerMessageRefused())
    from app.physics.core.bounded import stop_all_work
    from app.scenes import SCENES  # imported by the forkserver already: every numba kernel is loaded
    from app.scenes.host.host import SceneHost
    from app.scenes.host.warm import warm_compiled_models

    host = SceneHost(SCENES, frame_rate_hz=options["frame_rate_hz"], max_sessions=options["max_sessions"])
    host.start()
    threading.Thread(target=warm_compiled_models, args=(SCENES,), name="warm-models", daemon=True).start()
    tune_garbage_collection()
    listener = socket.create_server(("127.0.0.1", 0), backlog=CALL_BACKLOG)
    closing = threading.Event()
    threading.Thread(
        target=_accept_calls, args=(listener, authkey, host, closing), name="worker-rpc", daemon=True
    ).start()
    start_pipe.send({"viewer_url": host.url, "rpc_address": listener.getsockname(), "pid": os.getpid()})
    try:
        start_pipe.recv()  # "stop", or EOFError when the front process has gone
    except (EOFError, OSError):
        log.warning("worker %d stopping: the front closed its start pipe (it stopped, or replaced this worker)", index)
    finally:
        closing.set()
        listener.close()
        stop_all_work()
        host.stop()


def tune_garbage_collection() -> None:
    """Fewer, cheaper garbage collections for a server that allocates small objects at every frame.

    Every message to every viewer allocates; Python's default (a young-generation
    pass every 700 allocations) then runs thousands of collections a second.
    Objects that live for the whole run (modules, kernels, scene classes) are
    moved out of the collector's way with ``gc.freeze()``, and the young
    generation is collected every 50 000 allocations. Measured with 100 viewers
    of the heavy top on two cores: about a tenth less server CPU per frame.
    """
    gc.freeze()
    gc.set_threshold(50_000, 20, 20)


def _accept_calls(listener: socket.socket, authkey: bytes, host: Any, closing: threading.Event) -> None:
    """Accept callers at once and authenticate each in its own thread: one slow or silent caller holds only itself."""
    while True:
        try:
            sock, _ = listener.accept()
        except OSError:  # closed at shutdown
            if closing.is_set():
                return
            continue
        threading.Thread(target=_answer_calls, args=(sock, authkey, host), name="worker-call", daemon=True).start()


def _answer_calls(sock: socket.socket, authkey: bytes, host: Any) -> None:
    from app.physics.core.bounded import WorkBusy, WorkInterrupted
    from app.scenes.host.interface import WORKER_CALLS, HostBusy
    from app.scenes.host.rpc import accept, encode_error

    try:
        connection = accept(sock, authkey)
    except (OSError, EOFError, AuthenticationError):  # a caller without the pool's key, or one that went silent
        sock.close()
        return
    with connection:
        while True:
            try:
                method, args, kwargs = connection.recv()
            except (EOFError, OSError):
                return
            if method not in WORKER_CALLS:
                answer: tuple[Any, ...] = ("internal_error", f"no worker call {method!r}")
            else:
                try:
                    answer = ("ok", getattr(host, method)(*args, **kwargs))
                except Exception as exc:  # every error goes back to the caller, which raises it again
                    if not isinstance(
                        exc, ValueError | KeyError | HostBusy | WorkBusy | WorkInterrupted
                    ):  # answers, not faults
                        log.exception("worker call %s failed", method)
                    answer = encode_error(exc)
            try:
                connection.send(answer)
            except OSError:  # the front gave up on this call (its answer timeout) and closed the connection
                return
