"""Every open room, found by id (the API) or by its short code (a student joining)."""

from __future__ import annotations

import logging
import secrets
import threading
import time
from collections import OrderedDict
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from app.classroom.room import (
    CODE_ALPHABET,
    CODE_LENGTH,
    DEFAULT_JOIN_BASE,
    MAX_TYPED_CODE_LENGTH,
    Room,
    RoomError,
)
from app.settings import Settings
from app.storage.database import StoreUnavailable

log = logging.getLogger(__name__)

if TYPE_CHECKING:
    from app.classroom.store import SqlRoomStore

#: Rooms one server keeps open at once (each has its own stage: a viser server in a scene worker).
MAX_ROOMS = 16
#: A room nobody has used for this long (s) is closed when a new one needs its place (the database still keeps it).
IDLE_ROOM_S = 6 * 3600.0
#: Rooms kept read for joins only (:meth:`Rooms.by_code`), beyond the open ones.
MAX_READ_FOR_JOINS = 64
#: On a database several servers share, a room with no socket here unused this long (s) makes way when all places
#: are taken (its class is on another server; it is taken up again if the class comes back).
MAKE_WAY_AFTER_S = 60.0
#: A room's id: this many random hex digits (the API's paths and the room viewer's accept only this form).
ROOM_ID_HEX_DIGITS = 16
ROOM_ID_PATTERN = rf"^[0-9a-f]{{{ROOM_ID_HEX_DIGITS}}}$"


class NoPlaceHere(StoreUnavailable):
    """A kept room this server has no place to open now (every place taken by rooms in use): 503, Retry-After."""

    retry_after_s = 30


class Rooms:
    """Open rooms (thread-safe). ``join_base`` is the address students use (``Settings.public_url`` or the
    request's). With a ``store``, the rooms it kept are open again and every room is kept there as it changes."""

    def __init__(
        self,
        *,
        max_rooms: int = MAX_ROOMS,
        store: SqlRoomStore | None = None,
        keep_days: float = Settings.keep_rooms_days,
        join_base: str = DEFAULT_JOIN_BASE,
        open_kept: bool = True,
        stop_stage: Callable[[Room], object] = lambda room: None,
    ) -> None:
        self.max_rooms = max_rooms
        #: Stops the scene of a room taken out of memory to make way for another (the scene host's).
        self._stop_stage = stop_stage
        self.store = store
        self.keep_days = keep_days
        self.join_base = join_base
        #: Rooms closed in this run: never taken up from the database again, whatever it still holds.
        self._closed: set[str] = set()
        #: Rooms read only for students joining here (:meth:`by_code`), by id, least recently used first: one copy
        #: per room, so a class joining at once takes its turns in order on this server too.
        self._read_for_joins: OrderedDict[str, Room] = OrderedDict()
        if store is not None:
            store.forget_unused(days=keep_days)
        # One server on its own database opens every kept room at once (a restart); servers sharing one (``open_kept``
        # False) each take a room up when a balancer first sends it that room's class.
        kept = store.load(join_base=join_base, limit=max_rooms) if store is not None and open_kept else []
        self._rooms: dict[str, Room] = {room.room_id: room for room in kept}
        self._lock = threading.Lock()

    def create(self, *, join_base: str) -> tuple[Room, list[Room]]:
        """A new room, and the idle rooms closed to make space for it (their stages are the caller's to close)."""
        if self.store is not None:
            try:
                self.store.forget_unused(days=self.keep_days)
            except StoreUnavailable as exc:  # housekeeping: the next room's creation tries again
                log.warning("unused rooms not forgotten this time: %s", exc)
        with self._lock:
            closed = self._drop_idle()
            if len(self._rooms) >= self.max_rooms:
                raise RoomError(
                    "room",
                    f"{self.max_rooms} rooms are open already: close one first (a room unused for "
                    f"{IDLE_ROOM_S / 3600:g} h makes way by itself; `dynlab export` keeps a copy of a room's answers)",
                )
            codes = {room.code for room in self._rooms.values()}
            code = "".join(secrets.choice(CODE_ALPHABET) for _ in range(CODE_LENGTH))
            while code in codes:
                code = "".join(secrets.choice(CODE_ALPHABET) for _ in range(CODE_LENGTH))
            room_id = secrets.token_hex(ROOM_ID_HEX_DIGITS // 2)
            room = Room(room_id=room_id, code=code, join_url=f"{join_base.rstrip('/')}/join/{code}", store=self.store)
            if self.store is not None:
                self.store.insert(room)
            self._rooms[room_id] = room
            return room, closed

    def _drop_idle(self) -> list[Room]:
        """Rooms taken out of memory to make way (the database keeps them, to be taken up again): every room unused
        for :data:`IDLE_ROOM_S` with no instructor here; and on a database several servers share, while every place
        is taken, the least recently used with no socket here, unused for :data:`MAKE_WAY_AFTER_S` (a class another
        server serves now)."""
        now = time.monotonic()
        idle = [
            room
            for room in self._rooms.values()
            if now - room.last_used_s > IDLE_ROOM_S and not room.instructor_sockets
        ]
        for room in idle:  # its scene stops; the database keeps it (dynlab rooms, dynlab export) for keep_days
            del self._rooms[room.room_id]
        if self.store is not None and self.store.shared and len(self._rooms) >= self.max_rooms:
            elsewhere = sorted(
                (
                    room
                    for room in self._rooms.values()
                    if now - room.last_used_s > MAKE_WAY_AFTER_S
                    and not room.instructor_sockets
                    and not any(s.sockets for s in room.students.values())
                ),
                key=lambda room: room.last_used_s,
            )
            for room in elsewhere[: len(self._rooms) - self.max_rooms + 1]:
                del self._rooms[room.room_id]
                idle.append(room)
        return idle

    def get(self, room_id: str) -> Room:
        made_way: list[Room] = []
        with self._lock:
            room = self._rooms.get(room_id) or self._take_up_locked(made_way, room_id=room_id)
            if room is not None and room.closed:  # found deleted by its last change (closed elsewhere): gone here too
                self._forget_closed_locked(room)
                room = None
            if room is not None:
                room.last_used_s = time.monotonic()
        self._stop_stages(made_way)
        if room is None:
            raise KeyError(f"no room {room_id!r} (it may have been closed)")
        return room

    def _stop_stages(self, rooms: list[Room]) -> None:
        for room in rooms:
            try:
                self._stop_stage(room)
            except Exception as exc:  # a worker restarting forgets it anyway
                log.warning("room %s: its scene did not stop as it made way (%s)", room.code, exc)

    def _take_up_locked(
        self, made_way: list[Room], *, room_id: str | None = None, code: str | None = None
    ) -> Room | None:
        """A room kept in the store but not open here: one that made way for others (idle), or one another server
        sharing the database kept, whose class a balancer now sends here. It opens here (its stage with its first
        follower or change) if there is a place for it."""
        if self.store is None:
            return None
        room = self.store.load_one(join_base=self.join_base, room_id=room_id, code=code)
        if room is None or room.room_id in self._closed:
            return None
        read = self._read_for_joins.pop(room.room_id, None)
        if read is not None and not read.closed:  # the copy joins took their turns on: one copy of the room here
            read.take_up(room)
            room = read
        made_way += self._drop_idle()
        if len(self._rooms) >= self.max_rooms:
            log.warning("room %s is kept but %d rooms are open here: it stays closed", room.code, self.max_rooms)
            raise NoPlaceHere(
                f"this server has {self.max_rooms} rooms open and no place for room {room.code} just now: try again "
                "in a minute (a room nobody here has used for a minute makes way)"
            )
        room.last_used_s = time.monotonic()
        self._rooms[room.room_id] = room
        return room

    def explore_start(self, room_id: str, scene_id: str) -> dict[str, Any]:
        """Where the room's explorers start on ``scene_id``: its parameters and motion when exploring began
        (``explore_start`` of :meth:`Room.state`); ValueError saying why not (no such room, not exploring, other scene).
        """
        try:
            room = self.get(room_id)
        except KeyError as exc:
            raise ValueError(exc.args[0]) from None
        start = room.state()["explore_start"]
        if start is None:
            raise ValueError(f"room {room_id} is not exploring: its students follow the instructor's scene")
        if start["scene_id"] != scene_id:
            raise ValueError(f"room {room_id} explores {start['scene_id']!r}, not {scene_id!r}")
        return start

    def by_code(self, code: str, *, open_here: bool = True) -> Room:
        """The room with this code (KeyError if none). One kept in the database but not open here is opened here; or,
        with ``open_here`` False (a student joining: the balancer sends joins anywhere, and the room's class to one
        server), read for this request only, so joins do not fill every server with every room."""
        wanted = code.strip().upper()
        made_way: list[Room] = []
        can_be_a_code = len(wanted) <= MAX_TYPED_CODE_LENGTH and all(c in CODE_ALPHABET for c in wanted)
        with self._lock:
            room = next((r for r in self._rooms.values() if r.code == wanted), None)
            if room is None and not open_here:
                room = next((r for r in self._read_for_joins.values() if r.code == wanted and not r.closed), None)
            if room is not None:
                return room
        if can_be_a_code and not open_here and self.store is not None:
            room = self.store.load_one(join_base=self.join_base, code=wanted)
            if room is None or room.room_id in self._closed:
                raise KeyError(f"no open room has the code {wanted!r}")
            with self._lock:  # one copy: a join racing this one may have read the room too
                room = self._read_for_joins.setdefault(room.room_id, room)
                self._read_for_joins.move_to_end(room.room_id)
                while len(self._read_for_joins) > MAX_READ_FOR_JOINS:
                    self._read_for_joins.popitem(last=False)
            return room
        with self._lock:
            room = next((r for r in self._rooms.values() if r.code == wanted), None)
            if room is None and can_be_a_code:
                room = self._take_up_locked(made_way, code=wanted)
            if room is not None and room.closed:
                self._forget_closed_locked(room)
                room = None
        self._stop_stages(made_way)
        if room is None:
            raise KeyError(f"no open room has the code {wanted!r}")
        return room

    def _forget_closed_locked(self, room: Room) -> None:
        self._rooms.pop(room.room_id, None)
        self._read_for_joins.pop(room.room_id, None)
        self._closed.add(room.room_id)

    def close(self, room_id: str, *, room: Room | None = None) -> Room | None:
        """Close a room and forget it, with every answer in it (a change still in flight finishes first; later ones
        are refused, and nothing of the room is written again). ``room``: the copy a request found, closed and
        deleted even if it made way meanwhile."""
        with self._lock:
            room = self._rooms.pop(room_id, None) or self._read_for_joins.pop(room_id, None) or room
            if room is not None:
                self._closed.add(room_id)  # never taken up again in this run, even if its deletion fails
        if room is not None:
            try:
                with room.turn(), room.lock:  # a change under way, here or on another server, finishes first
                    room.closed = True
                    if self.store is not None:
                        self.store.delete(room_id)
            except StoreUnavailable as exc:  # closed here; the database keeps it until it answers again
                room.closed = True
                log.error("room %s is closed but still kept in the database: %s", room.code, exc)
        return room

    def held(self, room_id: str) -> Room | None:
        """The room if it is open here (never taken up from the store)."""
        with self._lock:
            return self._rooms.get(room_id)

    def closed_elsewhere(self, room_id: str) -> Room | None:
        """Another server sharing the database closed this room: it closes here too (nothing is deleted: that server
        did). Its stage and sockets are the caller's to close."""
        with self._lock:
            room = self._rooms.pop(room_id, None)
            read = self._read_for_joins.pop(room_id, None)
            self._closed.add(room_id)
        for copy in (room, read):
            if copy is not None:
                with copy.lock:
                    copy.closed = True
        return room

    def all(self) -> list[Room]:
        with self._lock:
            return list(self._rooms.values())
