"""A room: what the instructor shows, the students in it, and its polls.

The room's scene runs once, on a *stage* of the scene host (one simulation,
broadcast to every follower); the room keeps the state every page needs to
follow it — lesson, scene, parameters, play/pause, time scale, follow or
explore — and a revision number that grows with every change. A change is
checked whole before anything is applied: a bad field answers with a
:class:`RoomError` naming it and the room stays as it was.
"""

from __future__ import annotations

import contextlib
import hashlib
import logging
import math
import secrets
import threading
import time
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any, Protocol, TypeVar

from app.classroom.assignment import Assignment
from app.classroom.polls import Poll
from app.course import Catalogue
from app.scenes.host.host import STAGE_PREFIX, TIME_SCALE_RANGE
from app.scenes.host.interface import SceneHostInterface
from app.storage.database import StoreUnavailable

log = logging.getLogger(__name__)
T = TypeVar("T")

#: Characters of a room code: capitals and digits a student cannot misread (no I, L, O, 0, 1).
CODE_ALPHABET = "ABCDEFGHJKMNPQRSTUVWXYZ23456789"
CODE_LENGTH = 6
#: Longest code a student may type or the join address may carry (a code with stray spaces); longer is refused.
MAX_TYPED_CODE_LENGTH = 12
MODES = ("follow", "explore")
#: Conditions a state change may carry: the lesson and scene the sending page shows (a stale page's change is refused).
CONDITIONS = ("if_lesson_id", "if_scene_id")
#: Fields a state change may carry (``preset`` and ``reset`` are actions, not state; the conditions are checks).
STATE_FIELDS = ("lesson_id", "scene_id", "params", "playing", "time_scale", "mode", "preset", "reset", *CONDITIONS)
#: Students one room admits (a lecture hall's worth; a device joining again is the same student and takes no seat).
MAX_STUDENTS = 500
MAX_NAME_LENGTH = 40
#: The address students join at when no other is known (``dynlab serve``'s default address).
DEFAULT_JOIN_BASE = "http://127.0.0.1:8000"


#: Characters that turn the direction of the text after them (a name "\u202eecilA" shows as "Alice" and reverses what
#: follows it on the instructor's page): refused in names.
BIDI_CONTROLS = frozenset("\u061c\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069")


class RoomError(ValueError):
    """A state change or request the room refuses; ``field`` names what is wrong, nothing changed."""

    def __init__(self, field: str, message: str) -> None:
        super().__init__(message)
        self.field = field
        self.message = message


class RoomMovedOn(RoomError):
    """A change meant for a lesson or scene the room no longer shows (a stale instructor tab); nothing changed."""


class RoomAlreadyClosed(RoomMovedOn):
    """A change to a room its instructor has closed meanwhile (answered 409); nothing changed."""


class RoomChangedElsewhere(Exception):
    """The store refused a write: another server sharing the database wrote the room since this one read it. The
    room takes that version up and the change runs again on it (:meth:`Room._changing`)."""


class NotCurrentPoll(RoomError):
    """Opening or closing a poll that is no longer the room's current one (a newer poll was asked); nothing changed."""


class StudentRemoved(PermissionError):
    """The instructor removed this student (their token) or this device from the room."""


def digest(secret: str) -> str:
    """What the room keeps of a student's token or a device's id: its SHA-256 (hex). The database holds only these,
    so a copy of it lets nobody act as a student."""
    return hashlib.sha256(secret.encode()).hexdigest()


#: Times a change runs when its room's row changed under it outside a turn (two copies of the room in one server, or
#: a room deleted meanwhile): each time the room takes the kept version up first.
CHANGE_ATTEMPTS = 4
#: Longest wait for the room's turn in this server (s): a change queued behind one stuck at another server's turn
#: (see app.storage.database.PG_LOCK_TIMEOUT_MS) is refused (503, try again) instead of holding its request longer.
TURN_WAIT_S = 5.0
#: Seconds between a server's words on who its sockets of a room hold (app.classroom.hub), and how long one holds:
#: a server that stopped saying (it died) no longer counts its students as connected after this.
PRESENCE_EVERY_S = 2.0
PRESENCE_HOLDS_S = 5.0
#: Most student ids one server's word on presence carries (the room's limit: a word always fits PostgreSQL's NOTIFY).
MAX_PRESENCE_IDS = 500


class RoomStore(Protocol):
    """Where a room is kept as it changes (app.classroom.store): called with the room's lock held, after each change.
    ``save`` writes over the version the room last read (:attr:`Room.kept_version`) and raises
    :class:`RoomChangedElsewhere` if another server wrote a newer one; ``load_newer`` reads that one."""

    def save(self, room: Room, *, withdrawn_student: str | None = None) -> None: ...

    def save_answer(self, room: Room, poll_id: str, student_id: str) -> None: ...

    def load_newer(self, room: Room) -> Room | None: ...

    def load_answer(self, room_id: str, poll_id: str, student_id: str) -> dict[str, Any] | None: ...

    def turn(self, room: Room) -> contextlib.AbstractContextManager[int | None]: ...

    @property
    def shared(self) -> bool: ...


@dataclass
class Student:
    """One student: one device, known to the room by the secret token it got on joining (kept across reconnects
    and re-joins from that device) and to the instructor by ``student_id``, which reveals nothing of the token.
    ``token`` is known only in the server run that gave it (the room keeps its digest); a student kept from an
    earlier run who joins again from their device gets a new token beside the old one."""

    student_id: str
    token: str | None
    device_digest: str | None = None
    name: str = ""
    sockets: int = 0
    following: bool = True
    joined_s: float = field(default_factory=time.time)

    def listing(self, *, connected: bool, following: bool) -> dict[str, Any]:
        """What the instructor's list shows (never the token or the device), connected and following on any server."""
        return {"student_id": self.student_id, "name": self.name, "connected": connected, "following": following}


@dataclass(frozen=True)
class Presence:
    """Who one server's sockets of a room hold (another server sharing the database said so, at ``seen_s``,
    monotonic): the students connected there, those of them following, and the instructor's sockets."""

    connected: frozenset[str]
    following: frozenset[str]
    instructor_sockets: int
    seen_s: float


@dataclass
class Room:
    room_id: str
    code: str
    join_url: str
    lesson_id: str | None = None
    scene_id: str | None = None
    params: dict[str, Any] = field(default_factory=dict)
    playing: bool = True
    time_scale: float = 1.0
    mode: str = "follow"
    revision: int = 0
    reset_count: int = 0
    #: Where explorers start (set on each switch to explore, and on each new scene while exploring): scene, parameters
    #: and the stage's motion then (None: from the scene's start).
    explore_start: dict[str, Any] | None = None
    #: By student id; ``_by_token`` and ``_by_device`` find a student from a token's or a device's digest, the
    #: ``_removed_*`` sets remember (as digests) whom the instructor removed.
    students: dict[str, Student] = field(default_factory=dict)
    _by_token: dict[str, str] = field(default_factory=dict, repr=False)
    _by_device: dict[str, str] = field(default_factory=dict, repr=False)
    _removed_tokens: set[str] = field(default_factory=set, repr=False)
    _removed_devices: set[str] = field(default_factory=set, repr=False)
    _students_ever: int = 0
    instructor_sockets: int = 0
    polls: dict[str, Poll] = field(default_factory=dict)
    poll_id: str | None = None
    #: The exercises the instructor assigned (app.classroom.assignment; None: none), and the seed of the class's one
    #: set of numbers, kept while the assignment changes, is taken back or turns the class's numbers off and on.
    assignment: Assignment | None = None
    class_seed: int | None = None
    last_used_s: float = field(default_factory=time.monotonic)
    #: True after a change refused midway whose stage could not be put back: the next change opens the stage afresh.
    _stage_unsure: bool = field(default=False, repr=False)
    #: Held while the room's state changes (routes run in threads, sockets in the event loop's executor).
    lock: threading.RLock = field(default_factory=threading.RLock, repr=False)
    #: Held for a change's whole turn (:meth:`turn`), taken before :attr:`lock`.
    turn_lock: threading.RLock = field(default_factory=threading.RLock, repr=False)
    _turn_depth: int = field(default=0, repr=False)
    #: Where the room is kept (None: in this process's memory only).
    store: RoomStore | None = field(default=None, repr=False)
    #: When the room was opened (UTC, for the database and ``dynlab rooms``).
    created_at: float = field(default_factory=time.time)
    #: Set when the room is closed: nothing more is kept of it, and a change that raced the closing is refused.
    closed: bool = field(default=False, repr=False)
    #: Answers the store could not take (poll id, student id): written with the room's next successful write.
    _unsaved_answers: set[tuple[str, str]] = field(default_factory=set, repr=False)
    #: The version of the room's row this server last read or wrote (app.classroom.store).
    kept_version: int = field(default=0, repr=False)
    #: Who other servers' sockets of this room hold, by server (app.classroom.sync): one class on several servers.
    remote_presence: dict[str, Presence] = field(default_factory=dict, repr=False)
    #: What the stage showed before this server took up another's version (:meth:`take_up`), until
    #: :meth:`follow_stage` brings the stage to the room; None: the stage shows the room.
    _stage_behind: dict[str, Any] | None = field(default=None, repr=False)

    @property
    def stage_id(self) -> str:
        """The scene host's session id for this room's shared scene."""
        return f"{STAGE_PREFIX}{self.room_id}"

    # -- kept --------------------------------------------------------------------------
    def record(self) -> dict[str, Any]:
        """What the database keeps of the room (app.classroom.store): its shared scene's lesson, scene, parameters and
        play state, its students (digests of their tokens and devices, never the secrets), whom the instructor removed,
        and its polls without their answers (kept one row each)."""
        with self.lock:
            return {
                **self._shown(),
                "students": [
                    {
                        "student_id": s.student_id,
                        "name": s.name,
                        "device_digest": s.device_digest,
                        "joined_s": s.joined_s,
                    }
                    for s in self.students.values()
                ],
                "students_ever": self._students_ever,
                "token_digests": dict(self._by_token),
                "removed_tokens": sorted(self._removed_tokens),
                "removed_devices": sorted(self._removed_devices),
                "polls": [poll.record() for poll in self.polls.values()],
                "poll_id": self.poll_id,
                "assignment": self.assignment.record() if self.assignment is not None else None,
                "class_seed": self.class_seed,
            }

    @classmethod
    def from_record(
        cls,
        *,
        room_id: str,
        code: str,
        created_at: float,
        used_at: float,
        join_base: str,
        record: Mapping[str, Any],
        answers: Mapping[str, Mapping[str, Mapping[str, Any]]],
    ) -> Room:
        """The room :meth:`record` kept, with its polls' answers (by poll id, then student id), last used at
        ``used_at`` (UTC s) and joined at ``join_base`` now (this server's address may differ from the last run's).
        Its stage is not open yet: :meth:`put_stage_back` opens it at start-up, or a follower or the next change."""
        room = cls(
            room_id=room_id,
            code=code,
            join_url=f"{join_base.rstrip('/')}/join/{code}",
            lesson_id=record["lesson_id"],
            scene_id=record["scene_id"],
            params=dict(record["params"]),
            playing=record["playing"],
            time_scale=record["time_scale"],
            mode=record["mode"],
            revision=record["revision"] + 1,  # pages that saw the room before the restart take its state again
            reset_count=record["reset_count"],
            explore_start=record["explore_start"],
            poll_id=record["poll_id"],
            created_at=created_at,
            last_used_s=time.monotonic() - max(0.0, time.time() - used_at),
        )
        for kept in record["students"]:
            student = Student(
                student_id=kept["student_id"],
                token=None,
                device_digest=kept["device_digest"],
                name=kept["name"],
                joined_s=kept["joined_s"],
            )
            room.students[student.student_id] = student
            if student.device_digest is not None:
                room._by_device[student.device_digest] = student.student_id
        room._students_ever = record["students_ever"]
        room._by_token = dict(record["token_digests"])
        room._removed_tokens = set(record["removed_tokens"])
        room._removed_devices = set(record["removed_devices"])
        for kept_poll in record["polls"]:  # answers of students no longer in the room (removed) stay out
            kept_answers = answers.get(kept_poll["poll_id"], {})
            poll = Poll.from_record(kept_poll, {s: a for s, a in kept_answers.items() if s in room.students})
            room.polls[poll.poll_id] = poll
        kept_assignment = record.get("assignment")  # rooms kept before exercises were assigned have none
        room.assignment = Assignment.from_record(kept_assignment) if kept_assignment else None
        room.class_seed = record.get("class_seed")
        room._stage_unsure = room.scene_id is not None
        return room

    def put_stage_back(self, host: SceneHostInterface) -> None:
        """Open the room's stage as the room says it is (a room kept from an earlier run): its scene, parameters and
        play state. A worker that refuses leaves it for the room's next change."""
        with self.lock:
            if self.scene_id is not None and self._stage_unsure:
                self._stage_unsure = False
                self._put_stage_back(host, scene_changed=True)  # sets it again if the worker refused

    # -- several servers, one database ----------------------------------------------------
    def take_up(self, kept: Room) -> None:
        """Become ``kept``, the version another server sharing the database wrote (app.classroom.sync): its state,
        students and polls with their answers. What this server alone knows stays: open sockets, tokens it gave.
        The stage is brought to the new state by :meth:`follow_stage`."""
        with self.lock:
            before = self._shown()
            sockets = {s.student_id: s for s in self.students.values()}
            self.lesson_id, self.scene_id, self.params = kept.lesson_id, kept.scene_id, dict(kept.params)
            self.playing, self.time_scale, self.mode = kept.playing, kept.time_scale, kept.mode
            self.reset_count, self.explore_start = kept.reset_count, kept.explore_start
            self.revision = max(self.revision, kept.revision) + 1  # every page here takes the new state
            for student in kept.students.values():
                known = sockets.get(student.student_id)
                if known is not None:
                    student.sockets, student.following = known.sockets, known.following
                    if known.token is not None and kept._by_token.get(digest(known.token)) == student.student_id:
                        student.token = known.token  # one this server gave and wrote (else the change runs again)
            self.students = kept.students
            self._by_token, self._by_device = kept._by_token, kept._by_device
            self._removed_tokens, self._removed_devices = kept._removed_tokens, kept._removed_devices
            self._students_ever = kept._students_ever
            self.polls, self.poll_id = kept.polls, kept.poll_id
            self.assignment, self.class_seed = kept.assignment, kept.class_seed
            self.kept_version = kept.kept_version
            self.last_used_s = time.monotonic()
            stage_fields = ("scene_id", "params", "playing", "time_scale", "reset_count")
            if self._stage_behind is None and any(before[f] != getattr(self, f) for f in stage_fields):
                self._stage_behind = before

    def take_up_newer(self) -> bool:
        """Read the room's newest version from its store and take it up; False if the store no longer has the room
        (another server closed it)."""
        with self.lock:
            kept = self.store.load_newer(self) if self.store is not None else None
            if kept is None:
                return self.store is None
            self.take_up(kept)
            return True

    def follow_stage(self, host: SceneHostInterface) -> None:
        """Bring the stage to the room after :meth:`take_up`: another scene opens afresh, new parameters and play
        state are set, a reset restarts the motion. A stage not open here opens with its first follower as the room
        is then (:meth:`put_stage_back`)."""
        with self.lock:
            before, self._stage_behind = self._stage_behind, None
            if before is None or self._stage_unsure:
                return
            try:
                if self.scene_id is None:
                    if before["scene_id"] is not None:
                        host.close_stage(self.stage_id)
                    return
                if self.scene_id != before["scene_id"]:
                    host.open_stage(self.stage_id, self.scene_id, self.params)
                elif self.params != before["params"]:
                    host.set_params(self.scene_id, self.stage_id, self.params, stage=True)
                host.set_playback(
                    self.stage_id,
                    playing=self.playing,
                    time_scale=self.time_scale,
                    reset=self.reset_count != before["reset_count"],
                )
            except Exception as exc:  # busy, or restarting: the room's next change or follower opens it afresh
                self._stage_unsure = True
                log.warning("room %s: its stage did not follow another server's change (%s)", self.code, exc)

    def rest_stage(self, host: SceneHostInterface) -> bool:
        """Stop the room's scene on this server (nobody here follows it); it opens again, as the room is then, with
        its next follower or change. Under the room's lock: a change under way finishes first. True if it stopped."""
        with self.lock:
            if self.scene_id is None or self._stage_unsure:
                return False
            self._stage_unsure, self._stage_behind = True, None
            try:
                host.close_stage(self.stage_id)
            except Exception as exc:  # a worker restarting forgets it anyway
                log.warning("room %s: its scene here did not stop (%s)", self.code, exc)
            return True

    def _changing(self, work: Callable[[], T], *, host: SceneHostInterface | None = None) -> T:
        """Run ``work`` (one change, ending in :meth:`_keep`) with the room's lock held, in the room's turn at its
        store (:meth:`RoomStore.turn`): on a database several servers share, the others' changes of this room wait
        until this one is written, and a version another server wrote first is taken up before ``work`` runs (its
        stage follows, given ``host``), so no server's change is lost or refused. A store that cannot give the turn,
        or keep the change, refuses it (:class:`StoreUnavailable`, a 503): the room reads its kept version again."""
        for _ in range(CHANGE_ATTEMPTS):
            if self.closed:
                raise RoomAlreadyClosed("room", f"room {self.code} was closed by its instructor; nothing changed")
            in_turn = False
            try:
                # The turn first, then the lock: while another server's change holds the turn, this server's pages
                # (and its event loop, which reads the room under its lock) do not wait with it.
                with self.turn() as kept_version, self.lock:
                    in_turn = True
                    if self.closed:
                        continue
                    if kept_version is None:  # deleted: closed on another server, or by `dynlab rooms delete`
                        self.closed = True
                        continue
                    if kept_version != self.kept_version and self.take_up_newer() and host is not None:
                        self.follow_stage(host)
                    return work()
            except RoomChangedElsewhere:  # written outside any turn meanwhile (one server's copies of the room)
                with self.lock:
                    if not self.take_up_newer():
                        self.closed = True
                    if host is not None:
                        self.follow_stage(host)
            except StoreUnavailable:
                if in_turn and self.store is not None and self.store.shared:  # not kept: nor does it stand here
                    with contextlib.suppress(StoreUnavailable):
                        self.take_up_newer()
                raise
        if self.closed:
            raise RoomAlreadyClosed("room", f"room {self.code} was closed by its instructor; nothing changed")
        raise StoreUnavailable(f"room {self.code} is changing on other servers too fast to keep this change")

    @contextlib.contextmanager
    def turn(self) -> Iterator[int | None]:
        """This server's turn to change the room: one thread of this server at a time and, on a database several
        servers share, one server at a time (:meth:`RoomStore.turn`); yields the version kept now (None: the room is
        no longer kept). Taken before the room's lock, never while holding it; a thread already in the turn (a change
        made of changes) stays in it."""
        if not self.turn_lock.acquire(timeout=TURN_WAIT_S):  # queued behind a turn stuck at another server's
            raise StoreUnavailable(f"room {self.code} is busy with another change just now; try again in a moment")
        try:
            if self._turn_depth or self.store is None:
                self._turn_depth += 1
                try:
                    yield self.kept_version
                finally:
                    self._turn_depth -= 1
                return
            with self.store.turn(self) as version:
                self._turn_depth += 1
                try:
                    yield version
                finally:
                    self._turn_depth -= 1
        finally:
            self.turn_lock.release()

    # -- state ---------------------------------------------------------------------
    def _shown(self) -> dict[str, Any]:
        """What the room shows its class (its state's and its record's common part): lesson, scene, parameters, play
        state, follow or explore, where explorers start, and the revision that counts changes."""
        return {
            "lesson_id": self.lesson_id,
            "scene_id": self.scene_id,
            "params": dict(self.params),
            "playing": self.playing,
            "time_scale": self.time_scale,
            "mode": self.mode,
            "revision": self.revision,
            "reset_count": self.reset_count,
            "explore_start": self.explore_start,
        }

    def state(self) -> dict[str, Any]:
        """The room's state as every page reads it (``GET /api/rooms/{room_id}/state``)."""
        with self.lock:
            connected, following, instructor = self._presence()
            poll = self.polls.get(self.poll_id) if self.poll_id else None
            return {
                "room_id": self.room_id,
                "code": self.code,
                "join_url": self.join_url,
                **self._shown(),
                "students": {
                    "joined": len(self.students),
                    "connected": len(connected),
                    "following": len(following) if self.mode == "follow" else 0,
                },
                "instructor_connected": instructor,
                "poll": poll.public() if poll is not None else None,
                "assignment": self.assignment.public() if self.assignment is not None else None,
            }

    # -- presence: who is connected, on this server and on the others ----------------------------
    def presence_here(self) -> dict[str, Any]:
        """Who this server's sockets of the room hold (what it tells the others sharing the database): the numbers of
        the students connected (``s12`` is 12, so a class of 500 fits one PostgreSQL announcement), those following,
        and the instructor's sockets."""
        with self.lock:
            here = [s for s in self.students.values() if s.sockets > 0]
            return {
                "connected": [int(s.student_id[1:]) for s in here],
                "following": [int(s.student_id[1:]) for s in here if s.following],
                "instructor_sockets": self.instructor_sockets,
            }

    def take_presence(self, server: str, said: Mapping[str, Any]) -> None:
        """Another server's word on who its sockets of the room hold (:meth:`presence_here` there)."""
        connected, following = said.get("connected"), said.get("following")
        sockets = said.get("instructor_sockets")
        if not (isinstance(connected, list) and isinstance(following, list) and isinstance(sockets, int)):
            return
        ids = lambda numbers: frozenset(f"s{n}" for n in numbers[:MAX_PRESENCE_IDS] if isinstance(n, int))  # noqa: E731
        with self.lock:
            self.remote_presence[server] = Presence(
                connected=ids(connected),
                following=ids(following),
                instructor_sockets=max(0, sockets),
                seen_s=time.monotonic(),
            )

    def _presence(self) -> tuple[set[str], set[str], bool]:
        """Students connected (on any server), those of them following, and whether the instructor is connected."""
        connected = {s.student_id for s in self.students.values() if s.sockets > 0}
        following = {s.student_id for s in self.students.values() if s.sockets > 0 and s.following}
        instructor = self.instructor_sockets > 0
        now = time.monotonic()
        for server, said in list(self.remote_presence.items()):
            if now - said.seen_s > PRESENCE_HOLDS_S:  # that server stopped saying: it has no sockets, or died
                del self.remote_presence[server]
                continue
            connected |= said.connected
            following |= said.following
            instructor = instructor or said.instructor_sockets > 0
        connected &= self.students.keys()
        return connected, following & connected, instructor

    def change(self, raw: Mapping[str, Any], *, catalogue: Catalogue, host: SceneHostInterface) -> dict[str, Any]:
        """Apply an instructor's change (any of :data:`STATE_FIELDS`), checked whole first; returns the new state."""
        unknown = sorted(set(raw) - set(STATE_FIELDS))
        if unknown:
            raise RoomError(unknown[0], f"{unknown[0]}: not a room field (fields: {', '.join(STATE_FIELDS)})")

        def work() -> None:
            plan = self._plan(raw, catalogue=catalogue, host=host)
            self._apply(plan, host=host)
            self.revision += 1
            self.last_used_s = time.monotonic()
            self._keep()

        self._changing(work, host=host)
        return self.state()

    def _keep(self, *, withdrawn_student: str | None = None) -> None:
        """Write the room to its store (with its lock held, so the store sees changes in the order they were made).

        A write the database refuses (locked past its timeout, a full disk) is logged and the change stands: the
        room is written whole, so its next write keeps this change too, with any answers not kept meanwhile. Only a
        restart before that would lose it. On a database several servers share the write's failure refuses the change
        instead (the others could not see it, and would write over it)."""
        if self.store is None or self.closed:
            return
        try:
            self.store.save(self, withdrawn_student=withdrawn_student)
            for poll_id, student_id in sorted(self._unsaved_answers):
                self.store.save_answer(self, poll_id, student_id)
                self._unsaved_answers.discard((poll_id, student_id))
        except StoreUnavailable as exc:
            if self.store.shared:  # the other servers would never see it: the change is refused (503)
                raise
            log.error("room %s: not kept this time (%s); its next change writes it again", self.code, exc)

    def _keep_answer(self, poll_id: str, student_id: str) -> None:
        """Write one answer to the store; one it cannot take now goes with the room's next write (on a database
        several servers share, :class:`StoreUnavailable`: the caller takes the answer back)."""
        if self.store is None or self.closed:
            return
        try:
            self.store.save_answer(self, poll_id, student_id)
        except StoreUnavailable as exc:
            if self.store.shared:
                raise
            self._unsaved_answers.add((poll_id, student_id))
            log.error("room %s: an answer not kept this time (%s); the room's next change writes it", self.code, exc)

    def _check_conditions(self, raw: Mapping[str, Any]) -> None:
        """:class:`RoomMovedOn` if the change names a lesson or scene (``if_lesson_id``, ``if_scene_id``) that the room
        no longer shows: its parameters or controls were meant for another scene."""
        believed = {name: raw[f"if_{name}"] for name in ("lesson_id", "scene_id") if f"if_{name}" in raw}
        actual = {"lesson_id": self.lesson_id, "scene_id": self.scene_id}
        stale = [name for name, value in believed.items() if value != actual[name]]
        if stale:
            shows = (
                f"lesson {self.lesson_id!r}" + (f", scene {self.scene_id!r}" if self.scene_id else "")
                if self.lesson_id
                else "no lesson"
            )
            thought = ", ".join(
                f"{name.removesuffix('_id')} {believed[name]!r}"
                for name in ("lesson_id", "scene_id")
                if name in believed
            )
            raise RoomMovedOn(
                f"if_{stale[0]}",
                f"the class has moved on: the room shows {shows}, not {thought} as this page does; nothing changed "
                "(the page follows the class to its lesson)",
            )

    def _plan(self, raw: Mapping[str, Any], *, catalogue: Catalogue, host: SceneHostInterface) -> dict[str, Any]:
        """Everything the change will do, every field checked; raises :class:`RoomError` before any effect."""
        self._check_conditions(raw)  # first: a stale page's parameters were meant for another scene's inputs
        lesson_id = raw.get("lesson_id", self.lesson_id)
        if lesson_id is None:
            raise RoomError("lesson_id", "lesson_id: the room shows no lesson yet; name one")
        lesson = catalogue.lessons.get(lesson_id) if isinstance(lesson_id, str) else None
        if lesson is None:
            raise RoomError("lesson_id", f"lesson_id: no lesson {lesson_id!r}")
        if "scene_id" in raw and raw["scene_id"] is not None:
            scene_id = raw["scene_id"]
            if scene_id not in lesson.scenes:
                named = ", ".join(lesson.scenes) or "none"
                raise RoomError(
                    "scene_id", f"scene_id: lesson {lesson_id!r} has no scene {scene_id!r} (its scenes: {named})"
                )
        elif lesson_id != self.lesson_id or self.scene_id not in lesson.scenes:
            scene_id = lesson.scene  # a new lesson opens on its first scene (None for a lesson without one)
        else:
            scene_id = self.scene_id
        new_scene = scene_id != self.scene_id
        params: dict[str, Any] | None = None
        wants_params = new_scene or "params" in raw or "preset" in raw
        if scene_id is not None and wants_params:
            cls = host.scenes[scene_id]
            values: dict[str, Any] = {} if new_scene else dict(self.params)
            preset = raw.get("preset")
            if preset is not None:
                found = next((p for p in cls.presets if p.name == preset), None)
                if found is None:
                    names = ", ".join(p.name for p in cls.presets) or "none"
                    raise RoomError(
                        "preset", f"preset: scene {scene_id!r} has no preset {preset!r} (its presets: {names})"
                    )
                values.update(found.values)
            given = raw.get("params") or {}
            if not isinstance(given, Mapping):
                raise RoomError("params", "params: must be an object of parameter names and values")
            values.update(given)
            try:
                params = cls.parameters.validate(values)
            except ValueError as exc:
                raise RoomError(f"params.{getattr(exc, 'field', '')}".rstrip("."), str(exc)) from None
        elif "params" in raw or "preset" in raw:
            raise RoomError("params", f"params: lesson {lesson_id!r} has no scene to set parameters on")
        playing = raw.get("playing")
        if playing is not None and not isinstance(playing, bool):
            raise RoomError("playing", "playing: must be true or false")
        time_scale = raw.get("time_scale")
        if time_scale is not None:
            low, high = TIME_SCALE_RANGE
            if (
                isinstance(time_scale, bool)
                or not isinstance(time_scale, int | float)
                or not math.isfinite(time_scale)
                or not low <= time_scale <= high
            ):
                raise RoomError(
                    "time_scale", f"time_scale: a number from {low:g} to {high:g} (× real time), got {time_scale!r}"
                )
        mode = raw.get("mode")
        if mode is not None and mode not in MODES:
            raise RoomError("mode", f"mode: 'follow' or 'explore', got {mode!r}")
        reset = raw.get("reset", False)
        if not isinstance(reset, bool):
            raise RoomError("reset", "reset: must be true or false")
        return {
            "lesson_id": lesson_id,
            "scene_id": scene_id,
            "new_scene": new_scene,
            "params": params,
            "playing": playing,
            "time_scale": time_scale,
            "mode": mode,
            "reset": reset,
        }

    def _apply(self, plan: dict[str, Any], *, host: SceneHostInterface) -> None:
        """Carry out a checked plan: every call to the scene host first (any may answer :class:`HostBusy`, a worker
        busy or restarting), then the room's own fields, all at once. A call refused after others have changed the
        stage puts the stage back as the room says it is, so a 503 changes nothing and the same change can be sent
        again; if even that is refused, the room's next change opens its stage afresh."""
        scene_id, params = plan["scene_id"], plan["params"]
        playing = self.playing if plan["playing"] is None else plan["playing"]
        time_scale = self.time_scale if plan["time_scale"] is None else float(plan["time_scale"])
        mode = self.mode if plan["mode"] is None else plan["mode"]
        # A stage that could not be put back after a refused change shows something else than the room: open it again.
        reopen = scene_id is not None and (plan["new_scene"] or self._stage_unsure)
        stage_changed = playback_changed = False
        try:
            if reopen:
                opened = host.open_stage(self.stage_id, scene_id, self.params if params is None else params)
                params, stage_changed = opened["params"], True
            elif scene_id is not None and params is not None:
                params = host.set_params(scene_id, self.stage_id, params, stage=True)
                stage_changed = True
            elif scene_id is None and (self.scene_id is not None or self._stage_unsure):
                host.close_stage(self.stage_id)  # the change's last call: nothing after it can be refused
            if scene_id is not None and (
                reopen or plan["reset"] or plan["playing"] is not None or plan["time_scale"] is not None
            ):
                # A new stage starts playing at 1×: it takes the room's own playback, and any reset.
                host.set_playback(self.stage_id, playing=playing, time_scale=time_scale, reset=plan["reset"])
                playback_changed = True
            new_params = dict(params) if params is not None else {} if scene_id is None else dict(self.params)
            explore_start = self.explore_start if mode == "explore" else None
            if mode == "explore" and (self.mode != "explore" or plan["new_scene"]):
                # Explorers start from the stage's motion now; on a scene the room has just opened (another lesson or
                # scene while they explore), from its start with its parameters: the scene their pages go to.
                fresh = scene_id is None or plan["new_scene"]
                motion = None if fresh else host.motion_state(self.stage_id)
                explore_start = {"scene_id": scene_id, "params": new_params, "motion": motion}
        except Exception:
            if stage_changed or playback_changed:
                self._put_stage_back(host, scene_changed=stage_changed)
            raise
        self.lesson_id, self.scene_id, self.params = plan["lesson_id"], scene_id, new_params
        self.playing, self.time_scale, self.mode, self.explore_start = playing, time_scale, mode, explore_start
        self._stage_unsure = False
        if plan["reset"]:
            self.reset_count += 1

    def _put_stage_back(self, host: SceneHostInterface, *, scene_changed: bool) -> None:
        """After a change refused midway: the stage as the room says it is (its scene and parameters if the change
        had reached them, and its playback). A worker that refuses this too leaves the stage unsure: the room's next
        change opens it afresh."""
        try:
            if self.scene_id is None:
                if scene_changed:
                    host.close_stage(self.stage_id)
                return
            if scene_changed:
                host.open_stage(self.stage_id, self.scene_id, self.params)
            host.set_playback(self.stage_id, playing=self.playing, time_scale=self.time_scale)
        except Exception as exc:  # busy again, or gone: the next change puts it right
            self._stage_unsure = True
            log.warning("room %s: its stage could not be put back after a refused change (%s)", self.room_id, exc)

    # -- students --------------------------------------------------------------------
    def student_of_device(self, device: str | None) -> Student | None:
        """The student this device joined as, if it has (None for no device)."""
        with self.lock:
            student_id = self._by_device.get(digest(device)) if device else None
            return self.students.get(student_id) if student_id else None

    def join(self, name: str = "", *, device: str | None = None) -> Student:
        """The device's student: the one it joined as before (a QR code scanned again, a reload, the code typed
        again), its name updated if one is given; else a new student. :class:`StudentRemoved` for a device the
        instructor removed."""
        if (
            not isinstance(name, str)
            or len(name) > MAX_NAME_LENGTH
            or any(ord(c) < 32 or 0x7F <= ord(c) < 0xA0 or c in BIDI_CONTROLS for c in name)
        ):
            raise RoomError(
                "name", f"name: at most {MAX_NAME_LENGTH} printable characters, without text-direction controls"
            )
        name = name.strip()

        def work() -> Student:
            self.last_used_s = time.monotonic()
            if device is not None and digest(device) in self._removed_devices:
                raise StudentRemoved(f"the instructor removed this device from room {self.code}")
            known = self.student_of_device(device)
            if known is not None:
                changed = known.token is None or bool(name and name != known.name)
                if known.token is None:  # kept from an earlier run, which gave the token: a new one, beside it
                    known.token = secrets.token_urlsafe(18)
                    self._by_token[digest(known.token)] = known.student_id
                if name:
                    known.name = name
                if changed:
                    self._keep()
                return known
            if len(self.students) >= MAX_STUDENTS:
                raise RoomError("code", f"this room is full ({MAX_STUDENTS} students)")
            self._students_ever += 1
            device_digest = digest(device) if device is not None else None
            student = Student(
                student_id=f"s{self._students_ever}",
                token=secrets.token_urlsafe(18),
                device_digest=device_digest,
                name=name,
            )
            assert student.token is not None
            self.students[student.student_id] = student
            self._by_token[digest(student.token)] = student.student_id
            if device_digest is not None:
                self._by_device[device_digest] = student.student_id
            self._keep()
            return student

        return self._changing(work)

    def student(self, token: str | None) -> Student | None:
        """The student holding ``token``; :class:`StudentRemoved` if the instructor removed them."""
        if not token:
            return None
        with self.lock:
            if digest(token) not in self._by_token and self.store is not None and self.store.shared:
                self.take_up_newer()  # a student who joined on another server a moment ago
            if digest(token) in self._removed_tokens:
                raise StudentRemoved("the instructor removed you from this room")
            return self.student_of_token(token)

    def student_of_token(self, token: str | None) -> Student | None:
        """The student holding ``token`` now (None if none, or removed)."""
        with self.lock:
            student_id = self._by_token.get(digest(token)) if token else None
            return self.students.get(student_id) if student_id else None

    def student_list(self) -> list[dict[str, Any]]:
        """Every student, in the order they joined, as the instructor's list shows them."""
        with self.lock:
            connected, following, _ = self._presence()
            return [
                s.listing(
                    connected=s.student_id in connected,
                    following=s.student_id in following if s.student_id in connected else s.following,
                )
                for s in sorted(self.students.values(), key=lambda s: int(s.student_id[1:]))
            ]

    def remove(self, student_id: str) -> Student:
        """Remove a student: their token stops working, their device cannot join again, and their answers leave
        every poll's results (KeyError if the room has no such student)."""

        def work() -> Student:
            student = self.students.pop(student_id, None)
            if student is None:
                raise KeyError(f"room {self.code} has no student {student_id!r}")
            for token_digest in [t for t, owner in self._by_token.items() if owner == student_id]:
                del self._by_token[token_digest]
                self._removed_tokens.add(token_digest)
            if student.device_digest is not None:
                self._by_device.pop(student.device_digest, None)
                self._removed_devices.add(student.device_digest)
            for poll in self.polls.values():
                poll.withdraw(student.student_id)
            self.revision += 1
            self._keep(withdrawn_student=student_id)
            return student

        return self._changing(work)

    # -- assigned exercises ------------------------------------------------------------------
    def assign(self, assignment: Assignment | None) -> Assignment | None:
        """Assign exercises (replacing what was assigned), or none: every page sees it with the room's next state."""

        def work() -> Assignment | None:
            self.assignment = assignment
            if assignment is not None and assignment.class_seed is not None:
                self.class_seed = assignment.class_seed
            self.revision += 1
            self._keep()
            return assignment

        return self._changing(work)

    # -- polls -------------------------------------------------------------------------
    def open_poll(self, raw: Mapping[str, Any]) -> Poll:
        """A new poll (closing the one open before it); it becomes the room's current poll."""

        def work() -> Poll:
            poll = Poll.create(raw, poll_id=f"p{len(self.polls) + 1}")
            current = self.polls.get(self.poll_id) if self.poll_id else None
            if current is not None and current.open:
                current.close()
            self.polls[poll.poll_id] = poll
            self.poll_id = poll.poll_id
            self.revision += 1
            self._keep()
            return poll

        return self._changing(work)

    def poll(self, poll_id: str) -> Poll:
        with self.lock:
            try:
                return self.polls[poll_id]
            except KeyError:
                raise KeyError(f"room {self.room_id} has no poll {poll_id!r}") from None

    def answer(self, poll_id: str, token: str | None, raw: Mapping[str, Any]) -> None:
        """A student's answer (one per student, replaced until the poll closes)."""
        with self.lock:
            student = self.student(token)
            if student is None:
                raise PermissionError("answering needs the X-Student-Token this room gave when you joined")
            poll = self.poll(poll_id)
            earlier = poll.answer_of(student.student_id)
            poll.submit(student.student_id, raw, name=student.name)
            try:
                self._keep_answer(poll_id, student.student_id)
            except StoreUnavailable:  # not kept (a shared database): the student's earlier answer stands
                poll.withdraw(student.student_id)
                if earlier is not None:
                    poll.take_kept_answer(student.student_id, earlier)
                raise

    def update_poll(self, poll_id: str, raw: Mapping[str, Any], *, host: Any) -> Poll:
        """Close or reopen the current poll, reveal a poll's answer (computed by the room's scene now), show or hide
        names; :class:`NotCurrentPoll` for opening or closing an older poll."""
        unknown = sorted(set(raw) - {"open", "reveal", "show_names"})
        if unknown:
            raise RoomError(unknown[0], f"{unknown[0]}: not a poll field (fields: open, reveal, show_names)")
        for name in ("open", "reveal", "show_names"):
            if name in raw and not isinstance(raw[name], bool):
                raise RoomError(name, f"{name}: must be true or false")

        def work() -> Poll:
            poll = self.poll(poll_id)
            if "open" in raw and poll_id != self.poll_id:  # students see, and answer, only the current poll
                raise NotCurrentPoll(
                    "open",
                    f"open: poll {poll_id} can no longer be closed or reopened: {self.poll_id} is the room's current "
                    "poll, and only it takes answers; nothing changed",
                )
            if raw.get("reveal"):
                live = host.live_readout(self.scene_id, self.stage_id) if self.scene_id else None
                poll.reveal((live or {}).get("readout"))
            if "open" in raw and not raw.get("reveal"):
                poll.reopen() if raw["open"] else poll.close()
            if "show_names" in raw:
                poll.show_names = raw["show_names"]
            self.revision += 1
            self._keep()
            return poll

        return self._changing(work)
