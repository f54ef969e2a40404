"""The room sockets: every page in a room gets each change as it happens, and the room's readout twice a second.

A route or socket action that changes a room calls :meth:`RoomHub.publish_state`
(from any thread); the hub hands the message to the event loop, which queues it
for every socket of the room. Each socket has its own sender task and a bounded
queue: a browser that stops reading is disconnected (its page reconnects and
reads the state afresh) instead of holding everyone else's messages. One pump
per room, running while the room has sockets, reads the room's scene readout
from the scene host twice a second and publishes it, and coalesces presence
(who is connected and following) into at most two state messages a second, so a
class of 100 joining at once costs 2 broadcasts a second, not 100.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Annotated, Any

from fastapi import Depends, WebSocket
from starlette.concurrency import run_in_threadpool
from starlette.requests import HTTPConnection

from app.classroom.polls import Poll
from app.classroom.room import PRESENCE_EVERY_S, Room

log = logging.getLogger(__name__)

#: Messages a socket may have waiting before it is dropped as not reading (about 30 s of readouts).
QUEUE_LIMIT = 64
#: Seconds between readout and presence messages.
PUMP_PERIOD_S = 0.5
#: The last message a removed student's page gets before its socket closes.
REMOVED_MESSAGE = {"type": "removed", "detail": "The instructor removed you from this room."}


def finite_json(message: Any) -> str:
    """``message`` as strict JSON, every non-finite number sent as null (nothing non-finite reaches a client)."""

    def clean(value: Any) -> Any:
        if isinstance(value, float) and not math.isfinite(value):
            return None
        if isinstance(value, dict):
            return {k: clean(v) for k, v in value.items()}
        if isinstance(value, list | tuple):
            return [clean(v) for v in value]
        return value

    try:
        return json.dumps(message, allow_nan=False)
    except ValueError:
        return json.dumps(clean(message), allow_nan=False)


@dataclass(eq=False)
class Member:
    """One open room socket: a student's page or the instructor's."""

    websocket: WebSocket
    instructor: bool
    student_token: str | None = None
    #: The student's public id, once their hello named them (``student_token``).
    student_id: str | None = None
    queue: asyncio.Queue[str | None] = field(default_factory=lambda: asyncio.Queue(QUEUE_LIMIT))
    sender: asyncio.Task[None] | None = None
    #: Closed for not reading, or dismissed: nothing more is queued for it.
    closing: bool = False
    #: Set when the server ends the socket after its last queued message (:meth:`RoomHub.dismiss`).
    close_code: int | None = None
    close_reason: str = ""

    async def send_all(self) -> None:
        while (text := await self.queue.get()) is not None:
            await self.websocket.send_text(text)


class RoomHub:
    """Sockets by room, and the pumps that feed them (one event loop; publishing is thread-safe)."""

    def __init__(self, host_of: Any, *, say_presence: Callable[[Room], None] | None = None) -> None:
        #: Called with no arguments: the scene host (read at pump time, as the app sets it in its lifespan).
        self._host_of = host_of
        #: Tells the other servers sharing the database who this one's sockets of a room hold (in a thread; None:
        #: no other server): on each change, and every PRESENCE_EVERY_S while the room has sockets here.
        self._say_presence = say_presence
        self._loop: asyncio.AbstractEventLoop | None = None
        self._members: dict[str, set[Member]] = {}
        self._pumps: dict[str, asyncio.Task[None]] = {}
        #: Rooms whose presence (here or on another server) changed since their pump last published it.
        self._presence_changed: set[str] = set()
        #: Rooms whose sockets here changed since their pump last told the other servers.
        self._presence_to_say: set[str] = set()

    # -- sockets (event loop) -------------------------------------------------------------
    def join(self, room: Room, websocket: WebSocket, *, instructor: bool) -> Member:
        self._loop = asyncio.get_running_loop()
        member = Member(websocket, instructor)
        member.sender = asyncio.create_task(self._send(member, room.room_id))
        self._members.setdefault(room.room_id, set()).add(member)
        if instructor:
            with room.lock:
                room.instructor_sockets += 1
        if room.room_id not in self._pumps:
            self._pumps[room.room_id] = asyncio.create_task(self._pump(room))
        self._queue(member, finite_json({"type": "state", "state": room.state()}))
        if instructor:
            self._queue(member, finite_json(students_message(room)))
        self.presence_changed(room)
        return member

    async def leave(self, room: Room, member: Member) -> None:
        members = self._members.get(room.room_id, set())
        members.discard(member)
        with room.lock:
            if member.instructor:
                room.instructor_sockets -= 1
            student = room.students.get(member.student_id) if member.student_id else None
            if student is not None:
                student.sockets -= 1
        self.presence_changed(room)
        if member.sender is not None:
            member.sender.cancel()
            with contextlib.suppress(asyncio.CancelledError, Exception):
                await member.sender

    def presence_changed(self, room: Room) -> None:
        """Who this server's sockets of the room hold changed: published at the room's next pump, and said to the
        other servers (nothing for a room no socket here has joined: a join read on this server for itself)."""
        if room.room_id not in self._members:
            return
        self._presence_changed.add(room.room_id)
        self._presence_to_say.add(room.room_id)

    def others_presence_changed(self, room: Room) -> None:
        """Another server said who its sockets hold: published at the room's next pump (nothing to say back)."""
        if room.room_id in self._members:
            self._presence_changed.add(room.room_id)

    def reply(self, member: Member, message: dict[str, Any]) -> None:
        self._queue(member, finite_json(message))

    def _queue(self, member: Member, text: str) -> None:
        if member.closing:
            return
        try:
            member.queue.put_nowait(text)
        except asyncio.QueueFull:  # not reading: drop it; its page reconnects and reads the state afresh
            member.closing = True
            log.info("room socket not reading: closing it")
            if member.sender is not None:
                member.sender.cancel()
            asyncio.create_task(member.websocket.close(code=1013, reason="too far behind: reconnect"))

    async def _send(self, member: Member, room_id: str) -> None:
        with contextlib.suppress(Exception):
            await member.send_all()
            if member.close_code is not None:
                await member.websocket.close(code=member.close_code, reason=member.close_reason)

    def dismiss(self, member: Member, message: dict[str, Any], *, code: int = 1008, reason: str = "") -> None:
        """Send ``message`` as the socket's last, then close it with ``code`` (event loop)."""
        if member.closing:
            return
        member.close_code, member.close_reason = code, reason[:120]
        try:
            member.queue.put_nowait(finite_json(message))
            member.queue.put_nowait(None)
        except asyncio.QueueFull:  # not reading anyway: close it now
            if member.sender is not None:
                member.sender.cancel()
            asyncio.create_task(member.websocket.close(code=code, reason=member.close_reason))
        member.closing = True

    def dismiss_student(self, room: Room, student_id: str, message: dict[str, Any]) -> None:
        """Close every socket of the student ``student_id`` (removed by the instructor), ``message`` last (any
        thread)."""

        def dismiss_all() -> None:
            for member in list(self._members.get(room.room_id, ())):
                if member.student_id == student_id:
                    self.dismiss(member, message, reason="removed from the room by the instructor")

        self._in_loop(dismiss_all)

    async def _pump(self, room: Room) -> None:
        """While the room has sockets: its readout and (coalesced) presence, every :data:`PUMP_PERIOD_S`; who its
        sockets here hold, to the other servers (and once more, nobody, when the last has gone)."""
        said_s = -math.inf
        try:
            while self._members.get(room.room_id):
                now = time.monotonic()
                if room.room_id in self._presence_to_say or now - said_s >= PRESENCE_EVERY_S:
                    self._presence_to_say.discard(room.room_id)
                    said_s = now
                    await self._say(room)
                if said_s == now and room.remote_presence:  # as often: another server's word may have lapsed (it died)
                    self._presence_changed.add(room.room_id)
                if room.room_id in self._presence_changed:
                    self._presence_changed.discard(room.room_id)
                    self._deliver(room.room_id, finite_json({"type": "state", "state": room.state()}), False)
                    if any(member.instructor for member in self._members.get(room.room_id, ())):
                        self._deliver(room.room_id, finite_json(students_message(room)), True)
                scene_id = room.scene_id
                if scene_id is not None:
                    try:
                        live = await run_in_threadpool(self._host_of().live_readout, scene_id, room.stage_id)
                    except Exception:  # a worker restarting: the next pump tries again
                        live = None
                    if live is not None and room.scene_id == scene_id:
                        self._deliver(
                            room.room_id, finite_json({"type": "readout", "scene_id": scene_id, "data": live}), False
                        )
                await asyncio.sleep(PUMP_PERIOD_S)
            await self._say(room)  # nobody here any more
        finally:
            self._pumps.pop(room.room_id, None)

    async def _say(self, room: Room) -> None:
        if self._say_presence is None:
            return
        try:
            await run_in_threadpool(self._say_presence, room)
        except Exception as exc:  # the database not answering: the next pump says it again
            log.info("room %s: presence not said to the other servers (%s)", room.code, exc)

    # -- publishing (any thread) ---------------------------------------------------------------
    def _in_loop(self, work: Any, *args: Any) -> None:
        """Run ``work(*args)`` in the sockets' event loop: now if this is it, else soon (thread-safe)."""
        loop = self._loop
        if loop is None:
            return
        try:
            running = asyncio.get_running_loop()
        except RuntimeError:
            running = None
        if running is loop:
            work(*args)
        else:
            with contextlib.suppress(RuntimeError):  # the loop has closed (shutting down)
                loop.call_soon_threadsafe(work, *args)

    def publish(self, room_id: str, message: dict[str, Any], *, instructors_only: bool = False) -> None:
        if self._loop is None or not self._members.get(room_id):
            return
        self._in_loop(self._deliver, room_id, finite_json(message), instructors_only)

    def publish_state(self, room: Room, *, presence_only: bool = False) -> None:
        """The room's state to every page now; ``presence_only`` changes wait for the next pump (coalesced)."""
        if presence_only:
            self.presence_changed(room)
            return
        self.publish(room.room_id, {"type": "state", "state": room.state()})

    def publish_poll(self, room: Room, poll: Poll) -> None:
        """A poll changed: the room's state to every page (its public view) and the results to the instructor."""
        self.publish_state(room)
        self.publish_results(room, poll)

    def publish_students(self, room: Room) -> None:
        """The list of students to the instructor's sockets only (students never see who else is in the room)."""
        self.publish(room.room_id, students_message(room), instructors_only=True)

    def publish_results(self, room: Room, poll: Poll) -> None:
        """A poll's results to the instructor's sockets only (students never see others' answers)."""
        self.publish(room.room_id, {"type": "results", "results": poll.results()}, instructors_only=True)

    def _deliver(self, room_id: str, text: str, instructors_only: bool) -> None:
        for member in list(self._members.get(room_id, ())):
            if member.instructor or not instructors_only:
                self._queue(member, text)

    def socket_count(self, room_id: str) -> int:
        return len(self._members.get(room_id, ()))


def students_message(room: Room) -> dict[str, Any]:
    return {"type": "students", "students": room.student_list()}


def get_room_hub(request: HTTPConnection) -> RoomHub:
    return request.app.state.room_hub


RoomHubDep = Annotated[RoomHub, Depends(get_room_hub)]
