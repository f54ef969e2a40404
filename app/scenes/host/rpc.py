"""The wire between the front process and a scene worker: one call, one answer, never an endless wait.

A call is ``(method, args, kwargs)`` sent over a ``multiprocessing.connection``
on loopback, authenticated with the pool's random key. The answer is
``("ok", value)`` or an error the front raises again as the same kind of
exception the in-process host would have raised, so routes do not care where
the scene lives. Only the calls declared in
:mod:`app.scenes.host.interface` may be called.

Every socket on either side carries operating-system timeouts
(``SO_RCVTIMEO``/``SO_SNDTIMEO``): a connect, the key handshake, a send or a
read that gets no progress for that long fails instead of waiting forever, so a
stopped or stuck worker costs its caller a bounded wait (and the front marks it
as not answering), never a thread.
"""

from __future__ import annotations

import socket
import struct
from multiprocessing.connection import Connection, answer_challenge, deliver_challenge
from typing import Any

from app.physics.core.bounded import WorkBusy, WorkInterrupted
from app.physics.core.parameters import ParameterError
from app.scenes.host.host import UnknownSceneError
from app.scenes.host.interface import HostBusy

Answer = tuple[Any, ...]
#: Longest a connect or the key handshake may take on loopback (s): a healthy worker answers in microseconds.
CONNECT_TIMEOUT_S = 2.0


class WorkerUnavailableError(HostBusy):
    """The scene worker that serves a session did not answer (it is stopped, being restarted, or full): a 503."""


def set_io_timeout(sock: socket.socket, seconds: float) -> None:
    """Make every blocking read and write on ``sock`` fail after ``seconds`` without progress (0: never).

    Set at the operating-system level, so it holds for ``multiprocessing``'s Connection, which reads the raw file
    descriptor (a Python-level ``settimeout`` would make the descriptor non-blocking instead)."""
    whole = int(seconds)
    value = struct.pack("ll", whole, int((seconds - whole) * 1e6))
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVTIMEO, value)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_SNDTIMEO, value)


def connect(address: tuple[str, int], authkey: bytes, *, io_timeout_s: float) -> Connection:
    """A connection to a worker's call listener, authenticated, whose reads and writes time out after ``io_timeout_s``.

    Raises ``OSError`` (a timeout included) or ``multiprocessing.AuthenticationError``."""
    sock = socket.create_connection(address, timeout=CONNECT_TIMEOUT_S)
    return _authenticated(sock, authkey, caller=True, io_timeout_s=io_timeout_s)


def accept(sock: socket.socket, authkey: bytes) -> Connection:
    """Authenticate a worker-side socket the listener accepted (in the connection's own thread, so one slow caller
    never holds the listener); its reads wait for calls without a limit afterwards. Raises on a bad key or timeout."""
    return _authenticated(sock, authkey, caller=False, io_timeout_s=0.0)


def _authenticated(sock: socket.socket, authkey: bytes, *, caller: bool, io_timeout_s: float) -> Connection:
    """``sock`` as a ``multiprocessing`` Connection once both ends proved they hold ``authkey`` (the handshake itself
    bounded by :data:`CONNECT_TIMEOUT_S`), its reads and writes then bounded by ``io_timeout_s`` (0: unbounded)."""
    sock.settimeout(None)  # blocking again; the operating system's timeouts bound every read and write
    set_io_timeout(sock, CONNECT_TIMEOUT_S)
    connection = Connection(sock.detach())
    try:
        if caller:  # the caller answers the listener's challenge first, as multiprocessing's Client does
            answer_challenge(connection, authkey)
            deliver_challenge(connection, authkey)
        else:
            deliver_challenge(connection, authkey)
            answer_challenge(connection, authkey)
    except BaseException:
        connection.close()
        raise
    with socket.socket(fileno=connection.fileno()) as view:  # the same descriptor, to set its timeouts again
        set_io_timeout(view, io_timeout_s)
        view.detach()
    return connection


def encode_error(exc: BaseException) -> Answer:
    """An exception raised by the host, as data that crosses a process boundary."""
    if isinstance(exc, ParameterError):
        return ("parameter_error", *exc.carried())
    if isinstance(exc, UnknownSceneError):
        return ("unknown_scene", exc.args[0] if exc.args else "")
    if isinstance(exc, ValueError):
        return ("value_error", str(exc))
    if isinstance(exc, HostBusy):
        return ("busy", str(exc), exc.retry_after_s, exc.status)
    if isinstance(exc, WorkBusy):  # every place for a bounded derivation is taken: a full queue
        return ("busy", str(exc), exc.retry_after_s, 429)
    if isinstance(exc, WorkInterrupted):  # the derivation was stopped from outside: try again
        return ("busy", str(exc), exc.retry_after_s, 503)
    return ("internal_error", f"{type(exc).__name__}: {exc}")


def raise_answer(answer: Answer) -> Any:
    """The value of an ``("ok", value)`` answer, or the error it carries raised again."""
    kind = answer[0]
    if kind == "ok":
        return answer[1]
    if kind == "parameter_error":
        raise ParameterError.from_carried(answer[1:])
    if kind == "unknown_scene":
        raise UnknownSceneError(answer[1])
    if kind == "value_error":
        raise ValueError(answer[1])
    if kind == "busy":
        raise HostBusy(answer[1], retry_after_s=answer[2], status=answer[3])
    raise RuntimeError(f"scene worker failed: {answer[1]}")
