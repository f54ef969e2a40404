"""The viewer websocket relay: the only way a browser reaches the loopback viser server.

The viser client opens a websocket at its own page URL, so the viewer page at
``/viewer/{scene_id}/{session_id}/`` connects to ``/viewer/{scene_id}/{session_id}``
here. The relay copies the ``viser-v<version>`` subprotocol (viser refuses a
mismatch with close code 1002), forwards the path so the scene host knows which
scene to build for which session, and drops share-tunnel requests so no browser
can open a public tunnel to the server.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging

import msgspec
import websockets
from fastapi import APIRouter, WebSocket
from starlette.concurrency import run_in_threadpool
from starlette.websockets import WebSocketDisconnect

from app.api.access import Refused
from app.api.deps import SceneHostDep, SessionsDep
from app.api.rate_limit import client_address
from app.scenes.host.host import SESSION_ID_PATTERN
from app.scenes.host.interface import HostBusy, SceneHostInterface

log = logging.getLogger(__name__)
#: Longest a closing relay waits for its scene worker's close frame (s): the worker is on this machine, so a longer
#: wait means it is stopped or stuck, and a Ctrl+C must not wait websockets' default 10 s for it.
UPSTREAM_CLOSE_TIMEOUT_S = 1.0
router = APIRouter(tags=["viewer"])

#: Client-to-server message types that never reach viser.
BLOCKED_MESSAGE_TYPES = frozenset({"ShareUrlRequest", "ShareUrlDisconnect"})


def is_blocked_message(data: bytes) -> bool:
    """True for a viser client message whose type is in :data:`BLOCKED_MESSAGE_TYPES`."""
    if b"ShareUrl" not in data:  # cheap filter: camera and GUI updates pass untouched
        return False
    try:
        message = msgspec.msgpack.decode(data)
    except msgspec.DecodeError:
        return False
    return isinstance(message, dict) and message.get("type") in BLOCKED_MESSAGE_TYPES


async def viser_protocol(websocket: WebSocket) -> str | None:
    """The ``viser-v<version>`` subprotocol the browser's viewer offered; None after closing with 1002 if it offered
    none."""
    offered = websocket.scope.get("subprotocols") or []
    protocol = next((p for p in offered if p.startswith("viser-v")), None)
    if protocol is None:
        await websocket.close(code=1002, reason="expected a viser-v<version> subprotocol")
    return protocol


@router.websocket("/viewer/{scene_id}/{session_id}")
async def viewer_relay(
    websocket: WebSocket, scene_id: str, session_id: str, host: SceneHostDep, sessions: SessionsDep
) -> None:
    """A page's viewer: relayed to the scene worker that holds the session, if :mod:`app.api.access` lets it open."""
    if scene_id not in host.scenes or not SESSION_ID_PATTERN.match(session_id):
        await websocket.close(code=1008, reason="unknown scene or malformed session id")
        return
    protocol = await viser_protocol(websocket)
    if protocol is None:
        return
    client = client_address(websocket.scope, trust_forwarded_for=websocket.app.state.settings.trust_forwarded_for)
    await run_in_threadpool(sessions.scene_of, session_id)  # a session kept in the database is read in, off the loop
    try:
        with sessions.viewer(session_id, scene_id, client=client):
            # A session kept from the server's last run opens in the scene host first (a page reconnecting after a
            # restart); a host too busy to open it closes this socket with "try again", as _relay would.
            try:
                await run_in_threadpool(sessions.reopen_kept, session_id)
            except HostBusy as exc:
                raise Refused(503, str(exc), retry_after_s=exc.retry_after_s) from None
            await _relay(websocket, host, scene_id, session_id, protocol, client)
    except Refused as exc:
        await close_refused(websocket, exc)


async def close_refused(websocket: WebSocket, exc: Refused) -> None:
    """Close a websocket before accepting it, as the door said: 1013 (try again later) for 429/503, else 1008."""
    log.info("refused websocket %s: %s", websocket.url.path, exc.message)
    with contextlib.suppress(RuntimeError, WebSocketDisconnect):
        await websocket.close(code=1013 if exc.status in (429, 503) else 1008, reason=exc.message[:120])


async def _relay(
    websocket: WebSocket, host: SceneHostInterface, scene_id: str, session_id: str, protocol: str, client: str | None
) -> None:
    query = f"?client={client}" if client is not None else ""  # the worker gives each client its fair share
    try:
        url = await run_in_threadpool(host.viewer_url, session_id)
        upstream = await websockets.connect(
            f"{url}/{scene_id}/{session_id}{query}",
            subprotocols=[protocol],  # type: ignore[list-item]
            max_size=None,
            compression=None,
            open_timeout=10,
            close_timeout=UPSTREAM_CLOSE_TIMEOUT_S,
        )
    except (OSError, websockets.InvalidHandshake, TimeoutError, HostBusy, ValueError) as exc:
        log.warning("scene server unreachable: %s", exc)
        await websocket.close(code=1013, reason="scene server unreachable: try again in a moment")
        return
    await websocket.accept(subprotocol=protocol)

    async def browser_to_scene() -> None:
        while True:
            message = await websocket.receive()
            if message["type"] == "websocket.disconnect":
                return
            data = message.get("bytes")
            if data is not None and not is_blocked_message(data):
                await upstream.send(data)

    async def scene_to_browser() -> None:
        async for data in upstream:
            if isinstance(data, bytes):
                await websocket.send_bytes(data)
            else:
                await websocket.send_text(data)

    tasks = [asyncio.create_task(browser_to_scene()), asyncio.create_task(scene_to_browser())]
    try:
        await asyncio.wait(tasks, return_when=asyncio.FIRST_COMPLETED)
    finally:
        for task in tasks:
            task.cancel()
        for task in tasks:
            with contextlib.suppress(
                asyncio.CancelledError, WebSocketDisconnect, websockets.ConnectionClosed, RuntimeError
            ):
                await task
        await upstream.close()
        close_code = upstream.close_code if upstream.close_code not in (None, 1000, 1005, 1006) else 1000
        with contextlib.suppress(RuntimeError, WebSocketDisconnect):
            await websocket.close(code=close_code)
