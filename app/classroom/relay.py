"""A room's scene, fanned out: one stream from the room's stage, the same bytes sent to every follower.

Following students all see one simulation (the room's *stage*, a scene drawn on
its own viser server in a scene worker). Rather than each follower being a
viewer of that server — which would pack and relay every frame once per
student — the front holds one upstream viewer per room (:class:`StageStream`)
and sends each frame it receives, unchanged, to every follower: a class of 100
costs the worker one viewer, and the front one websocket send per student per
frame.

A follower that joins late needs the scene as it is now. It first gets a
*snapshot*: a second, short-lived viewer of the stage, to which viser replays
the stage's current state and then a ``ReplayDoneMessage``. Frames of the shared
stream that arrive meanwhile are held for that follower and sent after the
snapshot. Every scene message sets state (add, move, update or remove a node),
so a frame both in the snapshot and among the held ones only sets the same
state twice. A follower that cannot keep up (its queue full) is disconnected;
its viewer reconnects by itself and starts again from a snapshot.

Nothing a follower's viewer sends reaches the stage.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
import re
from dataclasses import dataclass, field

import websockets
import zstandard
from fastapi import APIRouter, FastAPI, WebSocket
from starlette.concurrency import run_in_threadpool
from starlette.websockets import WebSocketDisconnect
from websockets.typing import Subprotocol

from app.api.access import Refused
from app.api.rate_limit import client_address
from app.classroom.registry import ROOM_ID_PATTERN
from app.scenes.host.interface import HostBusy
from app.scenes.viser_boundary import viewer_camera_message
from app.storage.database import StoreUnavailable
from app.web.relay import UPSTREAM_CLOSE_TIMEOUT_S, close_refused, viser_protocol

log = logging.getLogger(__name__)
router = APIRouter(tags=["viewer"])

#: Frames a follower may have waiting (about 4 s at 30 frames/s) before it is dropped to reconnect.
FOLLOWER_QUEUE = 120
#: Longest a late joiner's snapshot may take (s).
SNAPSHOT_TIMEOUT_S = 10.0
ROOM_ID = re.compile(ROOM_ID_PATTERN)
#: How viser names the end of its replay of a server's state (the message's type, as it is on the wire).
REPLAY_DONE = b"ReplayDoneMessage"


def ends_replay(window: bytes) -> bool:
    """True if a viser message window carries the end-of-replay marker.

    A window is two little-endian uint64 (the msgpack's size, the compressed
    size), then the zstd-compressed msgpack of its messages, then raw buffers.
    """
    if len(window) < 16:
        return False
    compressed = int.from_bytes(window[8:16], "little")
    try:
        inner = zstandard.ZstdDecompressor().decompress(
            window[16 : 16 + compressed], max_output_size=int.from_bytes(window[:8], "little")
        )
    except zstandard.ZstdError:
        return False
    return REPLAY_DONE in inner


@dataclass(eq=False)
class Follower:
    websocket: WebSocket
    #: Shared frames held while this follower's snapshot is sent; None once it is live.
    held: list[bytes] | None = field(default_factory=list)
    queue: asyncio.Queue[bytes | None] = field(default_factory=lambda: asyncio.Queue(FOLLOWER_QUEUE))
    dropped: bool = False

    def offer(self, window: bytes) -> None:
        if self.dropped:
            return
        if self.held is not None:
            self.held.append(window)
            return
        try:
            self.queue.put_nowait(window)
        except asyncio.QueueFull:
            self.drop()

    def go_live(self) -> None:
        held, self.held = self.held or [], None
        for window in held:
            self.offer(window)

    def drop(self) -> None:
        """Too far behind, or the stream ended: close (the viewer reconnects and starts from a snapshot)."""
        if self.dropped:
            return
        self.dropped = True
        while not self.queue.empty():  # what it has not sent is void: it reconnects and starts from a snapshot
            self.queue.get_nowait()
        self.queue.put_nowait(None)


class StageStream:
    """One upstream viewer of a room's stage, every frame it receives offered to each follower."""

    def __init__(self, room_id: str, url: str, protocol: str) -> None:
        self.room_id = room_id
        self.url = url
        self.protocol = protocol
        self.followers: set[Follower] = set()
        self.windows = 0
        self.task: asyncio.Task[None] | None = None

    async def connect(self) -> websockets.ClientConnection:
        upstream = await websockets.connect(
            self.url,
            subprotocols=[Subprotocol(self.protocol)],
            max_size=None,
            compression=None,
            open_timeout=10,
            close_timeout=UPSTREAM_CLOSE_TIMEOUT_S,
        )
        await upstream.send(
            viewer_camera_message()
        )  # viser counts a viewer as connected after its first camera message
        return upstream

    async def run(self, upstream: websockets.ClientConnection) -> None:
        """Offer every frame to the followers; frames of the stage's own replay only to those still waiting on a
        snapshot."""
        replaying = True
        try:
            async for window in upstream:
                if not isinstance(window, bytes):
                    continue
                self.windows += 1
                for follower in list(self.followers):
                    if not replaying or follower.held is not None:
                        follower.offer(window)
                if replaying and ends_replay(window):
                    replaying = False
        except websockets.ConnectionClosed:
            pass
        finally:
            await upstream.close()
            for follower in list(self.followers):
                follower.drop()  # the stage went (its scene worker restarted, the room closed): everyone reconnects

    async def snapshot(self, follower: Follower) -> None:
        """Send ``follower`` the stage's current state from a viewer of its own, then the frames held meanwhile."""
        snapshot = await self.connect()
        try:
            async with asyncio.timeout(SNAPSHOT_TIMEOUT_S):
                async for window in snapshot:
                    if isinstance(window, bytes):
                        await follower.websocket.send_bytes(window)
                        if ends_replay(window):
                            break
        finally:
            await snapshot.close()
        follower.go_live()


def _streams(app: FastAPI) -> dict[str, StageStream]:
    if not hasattr(app.state, "stage_streams"):
        app.state.stage_streams = {}
    return app.state.stage_streams


async def close_streams(app: FastAPI) -> None:
    """At shutdown: stop every room's upstream viewer."""
    for stream in list(_streams(app).values()):
        if stream.task is not None:
            stream.task.cancel()
            with contextlib.suppress(asyncio.CancelledError, Exception):
                await stream.task


async def _stream_for(app: FastAPI, room_id: str, stage_id: str, protocol: str) -> StageStream:
    """The room's stream, started by the first follower (a class arriving at once shares the one it starts)."""
    if not hasattr(app.state, "stage_stream_lock"):
        app.state.stage_stream_lock = asyncio.Lock()
    async with app.state.stage_stream_lock:
        return await _start_stream(app, room_id, stage_id, protocol)


async def _start_stream(app: FastAPI, room_id: str, stage_id: str, protocol: str) -> StageStream:
    streams = _streams(app)
    stream = streams.get(room_id)
    if stream is not None and stream.task is not None and not stream.task.done():
        return stream
    url = await run_in_threadpool(app.state.scene_host.stage_viewer_url, stage_id)
    if url is None:
        raise OSError("the room's scene is not running")
    stream = StageStream(room_id, url, protocol)
    upstream = await stream.connect()

    async def run_then_forget() -> None:
        try:
            await stream.run(upstream)
        finally:
            if streams.get(room_id) is stream:
                del streams[room_id]

    stream.task = asyncio.create_task(run_then_forget())
    streams[room_id] = stream
    return stream


def follower_count(app: FastAPI, room_id: str) -> int:
    """Viewers following the room's scene now (in this front process)."""
    stream = _streams(app).get(room_id)
    return 0 if stream is None else len(stream.followers)


@router.websocket("/room-viewer/{room_id}")
async def room_viewer(websocket: WebSocket, room_id: str) -> None:
    """A follower's viewer: the room's one scene. What the viewer sends is read and dropped."""
    app = websocket.app
    if not ROOM_ID.match(room_id):
        await websocket.close(code=1008, reason="malformed room id")
        return
    try:  # off the event loop: a room not open here is looked up in the database
        room = await run_in_threadpool(app.state.rooms.get, room_id)
    except KeyError:
        await websocket.close(code=1008, reason="no open room has this id")
        return
    except StoreUnavailable:
        await websocket.close(code=1013, reason="the server could not read its rooms just now: try again")
        return
    protocol = await viser_protocol(websocket)
    if protocol is None:
        return
    if room.scene_id is None:
        await websocket.close(code=1013, reason="the room shows no scene now")
        return
    client = client_address(websocket.scope, trust_forwarded_for=app.state.settings.trust_forwarded_for)
    try:
        with app.state.sessions.follower(client=client):
            # A room kept from the last run whose scene a busy worker could not open at start-up: open it now.
            await run_in_threadpool(room.put_stage_back, app.state.scene_host)
            await _follow(websocket, app, room_id, room.stage_id, protocol)
    except Refused as exc:
        await close_refused(websocket, exc)


async def _follow(websocket: WebSocket, app: FastAPI, room_id: str, stage_id: str, protocol: str) -> None:
    try:
        stream = await _stream_for(app, room_id, stage_id, protocol)
    except (OSError, websockets.InvalidHandshake, TimeoutError, HostBusy) as exc:
        log.warning("room %s: its scene is unreachable: %s", room_id, exc)
        await websocket.close(code=1013, reason="the room's scene is unreachable: try again in a moment")
        return
    await websocket.accept(subprotocol=protocol)
    follower = Follower(websocket)
    stream.followers.add(follower)

    async def send_frames() -> None:
        await stream.snapshot(follower)
        while (window := await follower.queue.get()) is not None:
            await websocket.send_bytes(window)

    async def read_and_drop() -> None:
        while (await websocket.receive())["type"] != "websocket.disconnect":
            pass

    tasks = [asyncio.create_task(send_frames()), asyncio.create_task(read_and_drop())]
    try:
        await asyncio.wait(tasks, return_when=asyncio.FIRST_COMPLETED)
    finally:
        stream.followers.discard(follower)
        for task in tasks:
            task.cancel()
        for task in tasks:
            with contextlib.suppress(
                asyncio.CancelledError,
                WebSocketDisconnect,
                websockets.ConnectionClosed,
                RuntimeError,
                OSError,
                TimeoutError,
            ):
                await task
        with contextlib.suppress(RuntimeError, WebSocketDisconnect):
            await websocket.close(code=1000 if not follower.dropped else 1013)
