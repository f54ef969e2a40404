"""Simulated students: viewer websockets opened through the relay as a browser's viser client opens them.

A :class:`ViewerClient` connects to ``ws://<host>:<port>/viewer/<scene_id>/<session_id>``
(a student's own scene), or to another viewer path such as a room's
``/room-viewer/<room_id>`` (a follower of the room's one shared scene),
with the ``viser-v<version>`` subprotocol, offering permessage-deflate (the
``websockets`` default, as browsers do), sends the camera message a browser
sends first, then counts the binary messages the server streams: one per frame
window. Every 30th message is decoded (viser's framing: 8 bytes msgpack length,
8 bytes compressed length, zstd-compressed msgpack ``{"messages": [...]}``) to
measure viser messages per frame. A :class:`Classroom` is N such clients, each
with its own random session id, or all on one given viewer path. :func:`probe_health` times ``GET /api/health``
with a raw HTTP/1.1 request. Loopback only; every loop ends on a stop event, a
closed connection or a timeout.
"""

from __future__ import annotations

import asyncio
import contextlib
import secrets
import time
from dataclasses import dataclass, field
from urllib.parse import urlsplit

import msgspec
import viser
import websockets
import zstandard

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


def loopback_base(url: str) -> tuple[str, int]:
    """``(host, port)`` of an ``http://`` URL on this machine; ValueError naming ``url`` otherwise."""
    parts = urlsplit(url)
    if parts.scheme != "http" or parts.hostname is None:
        raise ValueError(f"url: expected http://127.0.0.1:<port>, got {url!r}")
    if parts.hostname not in LOOPBACK_HOSTS:
        raise ValueError(f"url: load tests target loopback only (127.0.0.1, localhost, ::1), got host {parts.hostname!r}")
    try:
        port = parts.port or 80
    except ValueError:
        raise ValueError(f"url: malformed port in {url!r}") from None
    return parts.hostname, port


def new_session_id() -> str:
    """A random session id matching ``[A-Za-z0-9_-]{8,64}`` (22 characters)."""
    return secrets.token_urlsafe(16)


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


@dataclass
class ViewerClient:
    """One student's viewer. ``frames``/``frame_bytes`` count binary messages received since connecting.

    ``path`` is the viewer websocket's path; empty: the student's own session, ``/viewer/<scene_id>/<session_id>``.
    """

    scene_id: str
    session_id: str = field(default_factory=new_session_id)
    path: str = ""
    frames: int = 0
    frame_bytes: int = 0
    decoded_frames: int = 0
    decoded_messages: int = 0
    connected: bool = False
    #: Why the viewer failed to connect or was closed before being told to stop; None while healthy.
    error: str | None = None

    def __post_init__(self) -> None:
        if not self.path:
            self.path = f"/viewer/{self.scene_id}/{self.session_id}"
        elif not self.path.startswith("/"):
            raise ValueError(f"path: a viewer websocket path starts with '/', got {self.path!r}")

    async def run(self, host: str, port: int, stop: asyncio.Event, camera_message: bytes) -> None:
        """Connect, send ``camera_message`` as a browser does first, count frames until ``stop`` or the connection ends."""
        uri = f"ws://{host}:{port}{self.path}"
        try:
            connection = await websockets.connect(
                uri,
                subprotocols=["viser-v" + viser.__version__],  # type: ignore[list-item]
                max_size=None,
                open_timeout=CONNECT_TIMEOUT_S,
                ping_interval=None,  # a browser sends no pings; the server's pings are still answered
                close_timeout=5,
            )
        except (OSError, websockets.InvalidHandshake, TimeoutError) as exc:
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
                self.error = f"closed by the server: code {connection.close_code} {connection.close_reason or ''}".rstrip()
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

    Each viewer opens its own session of the scene, unless ``path`` names one viewer websocket path they all
    open (a room's followers: ``/room-viewer/<room_id>``).
    """

    def __init__(self, host: str, port: int, scene_id: str, students: int, *, connect_per_s: float, path: str = "") -> None:
        # Imported here: importing app.scenes registers every scene (about 2 s), which only a running load needs.
        from app.scenes.host.viser_compat import viewer_camera_message

        self.camera_message = viewer_camera_message()
        self.host, self.port = host, port
        self.clients = [ViewerClient(scene_id, path=path) for _ in range(students)]
        self.connect_per_s = connect_per_s
        self._stop = asyncio.Event()
        self._tasks: list[asyncio.Task] = []

    async def open(self, *, timeout_s: float) -> None:
        """Start every viewer, ``1/connect_per_s`` apart; return once all connected or failed, or after ``timeout_s``."""
        for client in self.clients:
            self._tasks.append(asyncio.create_task(client.run(self.host, self.port, self._stop, self.camera_message)))
            await asyncio.sleep(1.0 / self.connect_per_s)
        deadline = time.monotonic() + timeout_s
        while time.monotonic() < deadline and not all(c.connected or c.error or t.done() for c, t in self._pairs()):
            await asyncio.sleep(0.1)
        # A viewer connected at the socket level may wait a moment for its first frame; give the stragglers it.
        while time.monotonic() < deadline and any(c.connected and c.frames == 0 and not t.done() for c, t in self._pairs()):
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
    started = time.perf_counter()
    writer = None
    try:
        async with asyncio.timeout(timeout_s):
            reader, writer = await asyncio.open_connection(host, port)
            writer.write(f"GET /api/health HTTP/1.1\r\nHost: {host}:{port}\r\nConnection: close\r\n\r\n".encode())
            await writer.drain()
            status_line = await reader.readline()
            await reader.read(64 * 1024)  # headers and body, until the server closes
        ok = status_line.split(b" ")[1:2] == [b"200"]
    except (OSError, TimeoutError, asyncio.IncompleteReadError):
        ok = False
    finally:
        if writer is not None:
            writer.close()
            with contextlib.suppress(OSError):
                await writer.wait_closed()
    return 1e3 * (time.perf_counter() - started), ok


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
