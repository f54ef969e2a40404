"""Simulated students: viewer websockets opened through the relay as a browser's viser client opens them.

A :class:`ViewerClient` is a student's lesson page: it first claims its own session as the
page does (``PUT /api/scenes/<scene_id>/sessions/<session_id>`` with a random
``X-Session-Key``: the page's first change creates the session), then connects to
``ws://<host>:<port>/viewer/<scene_id>/<session_id>``; or it connects to another
viewer path such as a room's ``/room-viewer/<room_id>`` (a follower of the room's
one shared scene), with the ``viser-v<version>`` subprotocol, offering permessage-deflate (the
``websockets`` default, as browsers do), sends the camera message a browser
sends first, then counts the binary messages the server streams: one per frame
window. Every 30th message is decoded (viser's framing: 8 bytes msgpack length,
8 bytes compressed length, zstd-compressed msgpack ``{"messages": [...]}``) to
measure viser messages per frame. A :class:`Classroom` is N such clients, each
with its own random session id, or all on one given viewer path; with
``distinct_addresses`` each student connects from its own loopback address
(:func:`student_address`: 127.0.1.1, 127.0.1.2, …; Linux routes all of
127.0.0.0/8 to the loopback device, so binding a socket's source address to any
of them needs no set-up), so the server's per-client limits, keyed on the
client's IP address, see a class of devices, not one. :func:`http_request` is a
raw HTTP/1.1 request (from a chosen source address, with a hard time limit);
:func:`probe_health` times ``GET /api/health`` with it. Loopback only; every
loop ends on a stop event, a closed connection or a timeout.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import secrets
import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any
from urllib.parse import urlsplit

import msgspec
import viser
import websockets
import zstandard

from app.api.access import KEY_HEADER as SESSION_KEY_HEADER

#: Hosts a load test may target: it never leaves the machine.
LOOPBACK_HOSTS = frozenset({"127.0.0.1", "localhost", "::1"})
#: Decode one message in this many to count viser messages per frame.
DECODE_EVERY = 30
#: Seconds a viewer may take to open its websocket (a loaded server is slow to accept).
CONNECT_TIMEOUT_S = 30.0
#: Seconds allowed for closing every viewer of a classroom.
CLOSE_TIMEOUT_S = 15.0
#: A health request slower than this counts as failed (s).
HEALTH_SLOW_S = 2.0
#: Period of the health probe (s).
HEALTH_PERIOD_S = 0.25
#: The source address of an attacking client (the load tool itself and its health probe use 127.0.0.1).
ATTACKER_ADDRESS = "127.0.0.2"
#: Students' source addresses are 127.0.<1 + i // 254>.<1 + i % 254>: this many of them.
MAX_STUDENT_ADDRESSES = 254 * 254
#: An answer's body is read to its end (its time is part of the latency) but only this much is kept (bytes).
KEPT_BODY_BYTES = 4096


def loopback_base(url: str) -> tuple[str, int]:
    """``(host, port)`` of an ``http://`` URL on this machine; ValueError naming ``url`` otherwise."""
    parts = urlsplit(url)
    if parts.scheme != "http" or parts.hostname is None:
        raise ValueError(f"url: expected http://127.0.0.1:<port>, got {url!r}")
    if parts.hostname not in LOOPBACK_HOSTS:
        raise ValueError(
            f"url: load tests target loopback only (127.0.0.1, localhost, ::1), got host {parts.hostname!r}"
        )
    try:
        port = parts.port or 80
    except ValueError:
        raise ValueError(f"url: malformed port in {url!r}") from None
    return parts.hostname, port


def new_session_id() -> str:
    """A random session id matching ``[A-Za-z0-9_-]{8,64}`` (22 characters)."""
    return secrets.token_urlsafe(16)


def new_session_key() -> str:
    """A random page key for ``X-Session-Key``, matching ``[A-Za-z0-9_-]{16,128}`` (32 characters)."""
    return secrets.token_urlsafe(24)


def student_address(index: int) -> str:
    """Student ``index``'s own loopback source address: 127.0.1.1, 127.0.1.2, …, 127.0.1.254, 127.0.2.1, …"""
    if not 0 <= index < MAX_STUDENT_ADDRESSES:
        raise ValueError(
            f"students: at most {MAX_STUDENT_ADDRESSES} distinct loopback addresses, asked for number {index}"
        )
    return f"127.0.{1 + index // 254}.{1 + index % 254}"


@dataclass(frozen=True)
class HttpAnswer:
    """What one request got: the status (None: no answer), the start of the body, and the time to the answer's end."""

    status: int | None
    body: bytes
    elapsed_ms: float
    #: Why there was no answer ("timeout", "ConnectionRefusedError", …); None when there was one.
    failure: str | None = None
    #: The answer's headers, names in lower case.
    headers: Mapping[str, str] = field(default_factory=dict)

    @property
    def label(self) -> str:
        """The status code as text, or why there was none."""
        return str(self.status) if self.status is not None else str(self.failure)

    def detail(self) -> str:
        """A refusal's message as one short line: its ``detail`` (FastAPI's error message), else the start of its
        body; empty for a success or no answer."""
        if self.status is None or self.status < 300:
            return ""
        text = self.body[:600].decode(errors="replace")
        with contextlib.suppress(ValueError, TypeError, AttributeError):
            detail = json.loads(self.body).get("detail", text)
            text = detail if isinstance(detail, str) else json.dumps(detail)
        return " ".join(text.split())[:200]


def _unchunked(body: bytes) -> bytes:
    """The payload of a ``Transfer-Encoding: chunked`` body (as much of it as was kept)."""
    out, rest = bytearray(), body
    while rest:
        size_line, _, rest = rest.partition(b"\r\n")
        try:
            size = int(size_line.split(b";")[0], 16)
        except ValueError:
            break
        if size == 0:
            break
        out += rest[:size]
        rest = rest[size + 2 :]
    return bytes(out)


async def http_request(
    host: str,
    port: int,
    method: str,
    path: str,
    *,
    body: Mapping | None = None,
    headers: Mapping[str, str] | None = None,
    source_address: str | None = None,
    timeout_s: float,
) -> HttpAnswer:
    """One HTTP/1.1 request on a new connection (``Connection: close``), from ``source_address`` if given, with a
    JSON ``body``; the whole exchange (connect, send, read to the end) is cut off after ``timeout_s``. Never raises
    for what the server does: a refusal is a status, a reset or a timeout a ``failure``."""
    started = time.perf_counter()
    payload = b"" if body is None else json.dumps(body).encode()
    lines = [f"{method} {path} HTTP/1.1", f"Host: {host}:{port}", "Connection: close"]
    if body is not None:
        lines += ["Content-Type: application/json", f"Content-Length: {len(payload)}"]
    lines += [f"{name}: {value}" for name, value in (headers or {}).items()]
    writer = None
    status, kept, failure = None, b"", None
    answer_headers: dict[str, str] = {}
    try:
        async with asyncio.timeout(timeout_s):
            reader, writer = await asyncio.open_connection(
                host, port, local_addr=(source_address, 0) if source_address else None
            )
            writer.write(("\r\n".join(lines) + "\r\n\r\n").encode() + payload)
            await writer.drain()
            head = await reader.readuntil(b"\r\n\r\n")
            status = int(head.split(b" ", 2)[1])
            for line in head.decode("latin-1").split("\r\n")[1:]:
                name, _, value = line.partition(":")
                if name:
                    answer_headers[name.strip().lower()] = value.strip()
            while chunk := await reader.read(64 * 1024):  # to the end: the answer's time includes its body
                if len(kept) < KEPT_BODY_BYTES:
                    kept += chunk[: KEPT_BODY_BYTES - len(kept)]
            if b"transfer-encoding: chunked" in head.lower():
                kept = _unchunked(kept)
    except TimeoutError:
        failure = "timeout"
    except (OSError, asyncio.IncompleteReadError, asyncio.LimitOverrunError, ValueError, IndexError) as exc:
        failure = type(exc).__name__
    finally:
        if writer is not None:
            writer.close()
            with contextlib.suppress(OSError, TimeoutError):
                async with asyncio.timeout(1.0):
                    await writer.wait_closed()
    if failure is not None and status is not None:
        failure = f"{status}, then {failure}"  # the status came, the body did not finish
        status = None
    elapsed_ms = 1e3 * (time.perf_counter() - started)
    return HttpAnswer(status=status, body=kept, elapsed_ms=elapsed_ms, failure=failure, headers=answer_headers)


def viser_messages_in_frame(data: bytes) -> int:
    """How many viser messages one binary frame window carries (its zstd-compressed msgpack header decoded)."""
    if len(data) < 16:
        raise ValueError(f"frame: {len(data)} bytes is shorter than viser's 16-byte header")
    inner_size = int.from_bytes(data[0:8], "little")
    compressed_size = int.from_bytes(data[8:16], "little")
    if 16 + compressed_size > len(data):
        raise ValueError(f"frame: header announces {compressed_size} compressed bytes, {len(data) - 16} present")
    inner = zstandard.ZstdDecompressor().decompress(data[16 : 16 + compressed_size], max_output_size=inner_size)
    payload = msgspec.msgpack.decode(inner)
    if not isinstance(payload, dict) or not isinstance(payload.get("messages"), list):
        raise ValueError("frame: decoded payload has no list of messages")
    return len(payload["messages"])


def connect_failure(exc: BaseException) -> str:
    """A short label for why a viewer websocket did not open: ``HTTP 403``, ``timeout``, ``ConnectionRefusedError``,
    …"""
    if isinstance(exc, websockets.InvalidStatus):
        return f"HTTP {exc.response.status_code}"
    if isinstance(exc, TimeoutError):
        return "timeout"
    return type(exc).__name__


@dataclass
class ViewerClient:
    """One student's viewer. ``frames``/``frame_bytes`` count binary messages received since connecting.

    ``path`` is the viewer websocket's path; empty: the student's own session, ``/viewer/<scene_id>/<session_id>``,
    which the client first claims with ``session_key`` as the lesson page does. ``source_address``: the loopback
    address it connects from (None: the system's choice, 127.0.0.1).
    """

    scene_id: str
    session_id: str = field(default_factory=new_session_id)
    path: str = ""
    source_address: str | None = None
    session_key: str = field(default_factory=new_session_key)
    frames: int = 0
    frame_bytes: int = 0
    decoded_frames: int = 0
    decoded_messages: int = 0
    connected: bool = False
    #: Why the viewer failed to connect or was closed before being told to stop; None while healthy.
    error: str | None = None
    #: The same as a short label (``claim 403``, ``HTTP 403``, ``close 1008``, ``timeout``, …); None while healthy.
    outcome: str | None = None
    #: True when the client opens its own session (and so claims it first).
    owns_session: bool = field(init=False)

    def __post_init__(self) -> None:
        self.owns_session = not self.path
        if not self.path:
            self.path = f"/viewer/{self.scene_id}/{self.session_id}"
        elif not self.path.startswith("/"):
            raise ValueError(f"path: a viewer websocket path starts with '/', got {self.path!r}")

    async def claim(self, host: str, port: int) -> bool:
        """The page's first change: ``PUT`` its session (default parameters) with its key; False (and ``error``) if
        refused. A viewer socket never creates a session, so this comes before :meth:`run` connects."""
        answer = await http_request(
            host,
            port,
            "PUT",
            f"/api/scenes/{self.scene_id}/sessions/{self.session_id}",
            body={"params": {}},
            headers={SESSION_KEY_HEADER: self.session_key},
            source_address=self.source_address,
            timeout_s=CONNECT_TIMEOUT_S,
        )
        if answer.status == 200:
            return True
        self.outcome = f"claim {answer.label}"
        self.error = f"claim: {answer.label} {answer.detail()}".rstrip()
        return False

    async def run(self, host: str, port: int, stop: asyncio.Event, camera_message: bytes) -> None:
        """Claim its own session (if it has one), connect, send ``camera_message`` as a browser does first, count
        frames until ``stop`` or the connection ends."""
        if self.owns_session and not await self.claim(host, port):
            return
        uri = f"ws://{host}:{port}{self.path}"
        socket_options: dict[str, Any] = {"local_addr": (self.source_address, 0)} if self.source_address else {}
        try:
            connection = await websockets.connect(
                uri,
                subprotocols=["viser-v" + viser.__version__],  # type: ignore[list-item]
                max_size=None,
                open_timeout=CONNECT_TIMEOUT_S,
                ping_interval=None,  # a browser sends no pings; the server's pings are still answered
                close_timeout=5,
                **socket_options,
            )
        except (OSError, websockets.InvalidHandshake, TimeoutError) as exc:
            self.outcome = connect_failure(exc)
            self.error = f"connect: {type(exc).__name__}: {exc}"
            return

        async def close_on_stop() -> None:
            await stop.wait()
            await connection.close()

        closer = asyncio.create_task(close_on_stop())
        try:
            await connection.send(camera_message)
            self.connected = True
            async for data in connection:  # ends when the connection closes (by us on stop, or by the server)
                self._count(data)
        except websockets.ConnectionClosed:
            pass
        finally:
            if not stop.is_set():
                self.outcome = f"close {connection.close_code}"
                self.error = (
                    f"closed by the server: code {connection.close_code} {connection.close_reason or ''}".rstrip()
                )
            closer.cancel()
            with contextlib.suppress(OSError, websockets.ConnectionClosed, TimeoutError):
                await connection.close()

    def _count(self, data: bytes | str) -> None:
        if not isinstance(data, bytes):
            return
        self.frames += 1
        self.frame_bytes += len(data)
        if self.frames % DECODE_EVERY == 0:
            try:
                self.decoded_messages += viser_messages_in_frame(data)
                self.decoded_frames += 1
            except (ValueError, zstandard.ZstdError, msgspec.DecodeError):
                pass  # a frame we cannot decode is still a delivered frame; it only leaves the sample smaller


@dataclass(frozen=True)
class ClassroomSnapshot:
    """Counters of every viewer at one instant (``time.monotonic()`` s)."""

    at_s: float
    frames: tuple[int, ...]
    frame_bytes: int
    decoded_frames: int
    decoded_messages: int


class Classroom:
    """``students`` viewers of one scene on the server at ``host:port``, connected ``connect_per_s`` per second.

    Each viewer claims and opens its own session of the scene, unless ``path`` names one viewer websocket path
    they all open (a room's followers: ``/room-viewer/<room_id>``). ``distinct_addresses``: each student connects
    from its own loopback address (:func:`student_address`), as a class of devices does.
    """

    def __init__(
        self,
        host: str,
        port: int,
        scene_id: str,
        students: int,
        *,
        connect_per_s: float,
        path: str = "",
        distinct_addresses: bool = False,
    ) -> None:
        # Imported here: importing app.scenes registers every scene (about 2 s), which only a running load needs.
        from app.scenes.viser_boundary import viewer_camera_message

        self.camera_message = viewer_camera_message()
        self.host, self.port = host, port
        self.clients = [
            ViewerClient(scene_id, path=path, source_address=student_address(index) if distinct_addresses else None)
            for index in range(students)
        ]
        self.connect_per_s = connect_per_s
        self._stop = asyncio.Event()
        self._tasks: list[asyncio.Task] = []

    async def open(self, *, timeout_s: float) -> None:
        """Start every viewer, ``1/connect_per_s`` apart; return once all connected or failed, or after
        ``timeout_s``."""
        for client in self.clients:
            self._tasks.append(asyncio.create_task(client.run(self.host, self.port, self._stop, self.camera_message)))
            await asyncio.sleep(1.0 / self.connect_per_s)
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline and not all(c.connected or c.error or t.done() for c, t in self._pairs()):
            await asyncio.sleep(0.1)
        # A viewer connected at the socket level may wait a moment for its first frame; give the stragglers it.
        while time.monotonic() < deadline and any(
            c.connected and c.frames == 0 and not t.done() for c, t in self._pairs()
        ):
            await asyncio.sleep(0.1)

    def _pairs(self) -> list[tuple[ViewerClient, asyncio.Task]]:
        return list(zip(self.clients, self._tasks))

    def snapshot(self) -> ClassroomSnapshot:
        return ClassroomSnapshot(
            at_s=time.monotonic(),
            frames=tuple(c.frames for c in self.clients),
            frame_bytes=sum(c.frame_bytes for c in self.clients),
            decoded_frames=sum(c.decoded_frames for c in self.clients),
            decoded_messages=sum(c.decoded_messages for c in self.clients),
        )

    def healthy(self) -> list[bool]:
        """Per viewer: connected and not closed with an error."""
        return [c.connected and c.error is None for c in self.clients]

    def errors(self) -> list[str]:
        return [c.error or "never connected" for c in self.clients if c.error or not c.connected]

    async def close(self) -> None:
        """Tell every viewer to stop and wait (bounded) for their sockets to close."""
        self._stop.set()
        if not self._tasks:
            return
        done, pending = await asyncio.wait(self._tasks, timeout=CLOSE_TIMEOUT_S)
        for task in pending:
            task.cancel()
        await asyncio.gather(*pending, return_exceptions=True)


@dataclass
class HealthLatency:
    """Latencies (ms) of ``GET /api/health`` requests; ``failures`` counts errors, non-200 answers and slow requests."""

    latencies_ms: list[float] = field(default_factory=list)
    failures: int = 0


async def health_request_ms(host: str, port: int, *, timeout_s: float = HEALTH_SLOW_S) -> tuple[float, bool]:
    """One raw HTTP/1.1 ``GET /api/health``: (elapsed ms, answered 200 within ``timeout_s``)."""
    answer = await http_request(host, port, "GET", "/api/health", timeout_s=timeout_s)
    return answer.elapsed_ms, answer.status == 200


async def probe_health(host: str, port: int, stop: asyncio.Event, into: HealthLatency) -> None:
    """``GET /api/health`` every :data:`HEALTH_PERIOD_S` until ``stop`` is set, recording into ``into``."""
    while not stop.is_set():
        started = time.monotonic()
        elapsed_ms, ok = await health_request_ms(host, port)
        into.latencies_ms.append(elapsed_ms)
        into.failures += 0 if ok else 1
        with contextlib.suppress(TimeoutError):
            async with asyncio.timeout(max(0.0, HEALTH_PERIOD_S - (time.monotonic() - started))):
                await stop.wait()


class ReconnectingViewer:
    """A viewer that stays, in a thread: it connects to ``base_url`` + ``path`` (``/viewer/<scene>/<session>`` or
    ``/room-viewer/<room>``) from ``address``, sends the first camera message (``camera``: position, look_at in m),
    reads every frame, and reconnects half a second after a drop, as viser's client does, until :meth:`close`
    (``frames``, ``connections`` and ``last_frame_s``, a monotonic time, say how it went)."""

    def __init__(
        self,
        base_url: str,
        path: str,
        *,
        address: str = "127.0.0.1",
        camera: tuple | None = None,
        reconnect_base_url: str | None = None,
    ) -> None:
        import threading

        self.url = base_url.replace("http://", "ws://") + path
        #: Where it reconnects after a drop (a balancer in front of the server it first reached); else the same.
        self.reconnect_url = (reconnect_base_url or base_url).replace("http://", "ws://") + path
        self.address = address
        self.camera = camera
        self.frames = 0
        self.connections = 0
        self.last_frame_s = 0.0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name=f"viewer {path}", daemon=True)
        self._thread.start()

    def _run(self) -> None:
        from websockets.sync.client import connect

        from app.scenes.viser_boundary import viewer_camera_message

        message = viewer_camera_message(
            **({"position": self.camera[0], "look_at": self.camera[1]} if self.camera else {})
        )
        while not self._stop.is_set():
            try:
                with connect(
                    self.url if self.connections == 0 else self.reconnect_url,
                    subprotocols=[f"viser-v{viser.__version__}"],  # type: ignore[list-item]
                    max_size=None,
                    open_timeout=10,
                    source_address=(self.address, 0),
                ) as socket:
                    self.connections += 1
                    socket.send(message)
                    while not self._stop.is_set():
                        try:
                            socket.recv(timeout=0.5)
                        except TimeoutError:
                            continue
                        self.frames += 1
                        self.last_frame_s = time.monotonic()
            except Exception:
                pass
            self._stop.wait(0.5)

    def close(self) -> None:
        self._stop.set()
        self._thread.join(timeout=10)
