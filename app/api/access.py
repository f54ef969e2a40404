"""Who may change which scene, and how much of the server one client may hold: the rule every door asks.

The doors are the page routes of a session (``PUT /api/scenes/{scene}/sessions/{id}``
and ``…/playback``) and the viewer websocket (``/viewer/{scene}/{id}``); the room
routes and the room socket ask :mod:`app.classroom.routes`'s instructor rule.

* **A room's shared scene** (a session id beginning ``room-``) is changed only
  through its room, by the room's instructor: every page route refuses it (403),
  and no page viewer may open it.
* **A page's session** is made by the page's first change, which pins it to a
  scene worker. The first change carrying a key (``X-Session-Key``) claims it: from
  then on only that key changes it (403 otherwise). A session nobody claimed stays
  open to keyless changes (scripts, the API's examples).
* **A viewer** may watch any page session it is given, of the scene that session
  shows; it never creates, replaces or re-scenes one (a viewer of a session that
  does not exist, or shows another scene, is refused).
* **Nothing a flood can evict.** Each client address (:func:`app.api.rate_limit.client_address`)
  may create :data:`CREATE_BURST` sessions at once and :data:`CREATE_RATE_PER_S` a
  second after that (429), and hold :data:`MAX_SESSIONS_PER_CLIENT`: beyond that its
  own least recently used idle session makes room. When the server's table is full,
  the session idle longest goes; a session whose viewer is connected is never
  evicted. Viewers are bounded per session and per client; room followers per client.

The directory lives in the front process; a session's scene lives in its worker,
which the directory tells when it evicts one (``close_session``).
"""

from __future__ import annotations

import hashlib
import hmac
import logging
import re
import threading
import time
from collections import OrderedDict
from collections.abc import Callable, Iterator, Mapping
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

from app.api.kept_sessions import KeptSession, SqlSessionStore
from app.api.rate_limit import InFlight, TokenBuckets, retry_after_s
from app.scenes.host.host import MAX_VIEWERS_PER_SESSION, STAGE_PREFIX

log = logging.getLogger(__name__)

#: 16–128 letters, digits, '-' or '_' (the lesson page sends 32 hex digits from crypto.getRandomValues).
SESSION_KEY_PATTERN = re.compile(r"^[A-Za-z0-9_-]{16,128}$")
KEY_HEADER = "X-Session-Key"

#: Sessions one client address may hold (a student who opens every lesson holds about 50); beyond, its own least
#: recently used session without a viewer makes room.
MAX_SESSIONS_PER_CLIENT = 64
#: New sessions one client may create at once, and per second after that (a student opening lessons one after
#: another never meets it; a script claiming thousands does).
CREATE_BURST = 60
CREATE_RATE_PER_S = 2.0
#: Viewers one client may have open in all (a few tabs); one session's are :data:`MAX_VIEWERS_PER_SESSION` (the
#: scene host's rule, checked here first).
MAX_VIEWERS_PER_CLIENT = 8
#: Room followers (``/room-viewer/…``) one client may have open (a student, a projector and a spare tab).
MAX_FOLLOWERS_PER_CLIENT = 8
#: Recordings one client may ask for at once, and one every this many seconds after that (a recording redraws up
#: to 60 s of frames in the student's scene worker: about a second of its computing).
RECORDING_BURST = 2
RECORDING_EVERY_S = 30.0
#: Long computations (:func:`app.scenes.host.fair_share.is_long_request`: a long step, a jump to a time) one client
#: may ask for at once, and one every this many seconds after that (a share link opens with one).
LONG_REQUEST_BURST = 3
LONG_REQUEST_EVERY_S = 10.0


class Refused(Exception):
    """A door said no: ``status`` (403 forbidden, 404 no such session, 409 another scene, 429 too many, 503 full),
    a message naming what to do, and for 429/503 the seconds to wait."""

    def __init__(self, status: int, message: str, *, retry_after_s: int | None = None) -> None:
        super().__init__(message)
        self.status = status
        self.message = message
        self.retry_after_s = retry_after_s


@dataclass
class SessionEntry:
    """What the front knows of one page's session."""

    scene_id: str
    #: The address that created it (None: an in-process caller, not limited per client).
    client: str | None
    key_hash: bytes | None = None
    viewers: int = 0
    #: Parameters kept from an earlier server run, not yet opened in the scene host of this one (None: open).
    kept_params: dict[str, Any] | None = None


@contextmanager
def _place(counter: InFlight, client: str | None, refusal: Refused) -> Iterator[None]:
    """Hold one of ``client``'s places in ``counter`` while the block runs; ``refusal`` is raised if none is free. An
    in-process caller (no client) is not counted."""
    if client is None:
        yield
        return
    if not counter.try_enter(client):
        raise refusal
    try:
        yield
    finally:
        counter.leave(client)


def _hash(key: str) -> bytes:
    return hashlib.sha256(key.encode()).digest()


class SessionDirectory:
    """Page sessions by id (thread-safe, bounded): who created and owns each, and its viewers.

    ``close`` is called, outside the directory's lock, with each session the directory evicts (the scene host's
    ``close_session``). With a ``store`` every session is kept there as it changes, and the sessions it kept are known
    again from the start: each is opened in the scene host (``reopen``: session id, scene id, kept parameters) when its
    page or viewer first asks for it (:meth:`reopen_kept`)."""

    def __init__(
        self,
        *,
        max_sessions: int = 2000,
        close: Callable[[str], None] = lambda session_id: None,
        clock: Callable[[], float] = time.monotonic,
        max_clients: int = 10_000,
        store: SqlSessionStore | None = None,
        reopen: Callable[[str, str, dict[str, Any]], None] = lambda session_id, scene_id, params: None,
    ) -> None:
        self.max_sessions = max_sessions
        self._close = close
        self._store = store
        self._reopen = reopen
        self._clock = clock
        self._entries: OrderedDict[str, SessionEntry] = OrderedDict()  # least recently used first
        self._by_client: dict[str, OrderedDict[str, None]] = {}
        self._viewers_of_client = InFlight(limit=MAX_VIEWERS_PER_CLIENT)
        self._followers = InFlight(limit=MAX_FOLLOWERS_PER_CLIENT)
        self._creations = TokenBuckets(
            burst=CREATE_BURST, rate_per_s=CREATE_RATE_PER_S, max_clients=max_clients, clock=clock
        )
        #: The one long computation a device may have running: a simulation, a derivation (both counted by the request
        #: guard, :class:`app.web.guard.RequestGuard`, which is given this counter) or a typed scene's change.
        self.heavy_work = InFlight(limit=1)
        self._recordings = TokenBuckets(
            burst=RECORDING_BURST, rate_per_s=1.0 / RECORDING_EVERY_S, max_clients=max_clients, clock=clock
        )
        self._recording_now = InFlight(limit=1)
        self._long_requests = TokenBuckets(
            burst=LONG_REQUEST_BURST, rate_per_s=1.0 / LONG_REQUEST_EVERY_S, max_clients=max_clients, clock=clock
        )
        self._lock = threading.Lock()
        for kept in store.load(max_sessions) if store is not None else []:
            self._entries[kept.session_id] = SessionEntry(kept.scene_id, None, kept.key_hash, kept_params=kept.params)

    def _known_locked(self, session_id: str) -> SessionEntry | None:
        """The session's entry: in memory, else kept in the store (by another server sharing the database, whose
        sessions this one takes over when a balancer sends their pages here), so its claim holds here too."""
        entry = self._entries.get(session_id)
        if entry is None and self._store is not None and not session_id.startswith(STAGE_PREFIX):
            kept = self._store.load_one(session_id)
            if kept is not None:
                entry = SessionEntry(kept.scene_id, None, kept.key_hash, kept_params=kept.params)
                self._entries[session_id] = entry
        return entry

    def __len__(self) -> int:
        return len(self._entries)

    # -- changes --------------------------------------------------------------------------------------
    def check_change(self, session_id: str, key: str | None, *, client: str | None, creating: bool = True) -> None:
        """Raise :class:`Refused` unless a change to ``session_id`` with ``key`` from ``client`` may go ahead.

        ``creating``: the change may create the session (a page's parameters); otherwise it must exist (404)."""
        if session_id.startswith(STAGE_PREFIX):
            raise Refused(
                403,
                f"session {session_id!r} is a classroom room's shared "
                "scene: only its instructor changes it, through the room",
            )
        with self._lock:
            entry = self._known_locked(session_id)
            if entry is None:
                if not creating:
                    raise Refused(404, f"session {session_id!r} has no scene yet: set its parameters first")
                if client is not None:
                    wait_s = self._creations.take(client)
                    if wait_s > 0:
                        retry = retry_after_s(wait_s)
                        raise Refused(
                            429, f"too many new scenes from this device: try again in {retry} s", retry_after_s=retry
                        )
                return
            if entry.key_hash is None:
                return
            if key is None:
                raise Refused(
                    403, f"session {session_id!r} belongs to another page: changing it needs its {KEY_HEADER} header"
                )
            if not hmac.compare_digest(entry.key_hash, _hash(key)):
                raise Refused(403, f"session {session_id!r} belongs to another page: the {KEY_HEADER} does not match")

    def changed(
        self,
        session_id: str,
        scene_id: str,
        key: str | None,
        *,
        client: str | None,
        params: Mapping[str, Any] | None = None,
    ) -> None:
        """After a successful change: record the session (created by ``client``) with its ``params`` (kept in the
        store), the first key claims it, and make room for it (evicting as the rules say; each evicted session is
        closed in the host)."""
        evicted: list[str] = []
        with self._lock:
            entry = self._known_locked(session_id)
            if entry is None:
                entry = SessionEntry(scene_id, client)
                self._entries[session_id] = entry
                if client is not None:
                    owned = self._by_client.setdefault(client, OrderedDict())
                    owned[session_id] = None
                    while len(owned) > MAX_SESSIONS_PER_CLIENT:
                        oldest = next(
                            (sid for sid in owned if sid != session_id and self._entries[sid].viewers == 0), None
                        )
                        if oldest is None:
                            break
                        evicted.append(self._forget_locked(oldest))
                while len(self._entries) > self.max_sessions:
                    oldest = next(
                        (sid for sid, e in self._entries.items() if sid != session_id and e.viewers == 0), None
                    )
                    if oldest is None:
                        break
                    evicted.append(self._forget_locked(oldest))
            entry.scene_id = scene_id
            entry.kept_params = None  # the host has it now, with these parameters
            if entry.key_hash is None and key is not None:
                entry.key_hash = _hash(key)
            self._touch_locked(session_id, entry)
            if self._store is not None and params is not None:  # in the lock: two changes are kept in their order
                self._store.save(KeptSession(session_id, scene_id, entry.key_hash, dict(params)))
        for old in evicted:
            self._close(old)

    def reopen_kept(self, session_id: str) -> None:
        """Open in the scene host a session kept from an earlier server run, with its kept parameters, the first time
        its page or viewer asks for it in this run (nothing for any other session). Parameters this version refuses
        give way to the scene's defaults; a busy host's :class:`HostBusy` is raised, and the next ask tries again."""
        with self._lock:
            entry = self._known_locked(session_id)
            params = entry.kept_params if entry is not None else None
            if entry is None or params is None:
                return
            entry.kept_params = None
        try:
            try:
                self._reopen(session_id, entry.scene_id, params)
            except ValueError as exc:
                log.warning(
                    "session %s: its kept parameters were refused (%s); it opens with the defaults", session_id, exc
                )
                self._reopen(session_id, entry.scene_id, {})
        except KeyError:  # a scene this version no longer has: the session is forgotten, its page starts afresh
            log.warning("session %s: its kept scene %r no longer exists; it is forgotten", session_id, entry.scene_id)
            with self._lock:
                if self._entries.get(session_id) is entry:
                    self._forget_locked(session_id)
            return
        except Exception:  # a busy host (or defaults it refused too): the next ask tries again with the kept ones
            with self._lock:
                if entry.kept_params is None:
                    entry.kept_params = params
            raise

    def changed_elsewhere(self, session_id: str) -> None:
        """Another server sharing the database changed this session (a balancer sent its page there): if it is open
        here too, it takes that server's scene, parameters and claim, and its scene here shows them now; a session
        that server forgot is forgotten here."""
        if self._store is None:
            return
        with self._lock:
            entry = self._entries.get(session_id)
            if entry is None:
                return
            kept = self._store.load_one(session_id)
            if kept is None:
                self._forget_locked(session_id, from_store=False)
            else:
                entry.scene_id, entry.key_hash, entry.kept_params = kept.scene_id, kept.key_hash, dict(kept.params)
        if kept is None:
            self._close(session_id)
            return
        try:
            self.reopen_kept(session_id)
        except Exception as exc:  # a busy host: the page's next ask opens it with the kept parameters
            log.info("session %s: not brought to another server's change yet (%s)", session_id, exc)

    def touched(self, session_id: str) -> None:
        """The session was used (a playback change): it is the last to be evicted."""
        with self._lock:
            entry = self._known_locked(session_id)
            if entry is not None:
                self._touch_locked(session_id, entry)

    def _touch_locked(self, session_id: str, entry: SessionEntry) -> None:
        self._entries.move_to_end(session_id)
        if entry.client is not None and session_id in self._by_client.get(entry.client, {}):
            self._by_client[entry.client].move_to_end(session_id)

    def _forget_locked(self, session_id: str, *, from_store: bool = True) -> str:
        entry = self._entries.pop(session_id)
        if self._store is not None and from_store:
            self._store.delete(session_id)
        if entry.client is not None:
            owned = self._by_client.get(entry.client)
            if owned is not None:
                owned.pop(session_id, None)
                if not owned:
                    del self._by_client[entry.client]
        return session_id

    def is_claimed(self, session_id: str) -> bool:
        with self._lock:
            entry = self._known_locked(session_id)
            return entry is not None and entry.key_hash is not None

    def scene_of(self, session_id: str) -> str | None:
        with self._lock:
            entry = self._known_locked(session_id)
            return None if entry is None else entry.scene_id

    def sessions_of(self, client: str) -> int:
        with self._lock:
            return len(self._by_client.get(client, ()))

    @contextmanager
    def heavy_change(self, *, client: str | None) -> Iterator[None]:
        """Hold the client's one place for a change that compiles what a student typed (a typed Lagrangian's
        derivation may take its whole 20 s): a second one from the same device meanwhile is :class:`Refused` (429)."""
        busy = Refused(
            429,
            "your previous change, simulation or derivation is still running: wait for it, then try again",
            retry_after_s=2,
        )
        with _place(self.heavy_work, client, busy):
            yield

    @contextmanager
    def recording(self, *, client: str | None) -> Iterator[None]:
        """Hold the client's place for a recording: one at a time, :data:`RECORDING_BURST` at once and then one
        every :data:`RECORDING_EVERY_S`; :class:`Refused` (429, Retry-After) beyond."""
        busy = Refused(429, "your previous recording is still being made: wait for it, then try again", retry_after_s=2)
        with _place(self._recording_now, client, busy):
            wait_s = self._recordings.take(client) if client is not None else 0.0
            if wait_s > 0:
                retry = retry_after_s(wait_s)
                raise Refused(
                    429, f"too many recordings from this device: the next one in {retry} s", retry_after_s=retry
                )
            yield

    def check_long_request(self, *, client: str | None) -> None:
        """Count one long computation for the client; :class:`Refused` (429, Retry-After) beyond its share."""
        if client is None:
            return
        wait_s = self._long_requests.take(client)
        if wait_s > 0:
            retry = retry_after_s(wait_s)
            raise Refused(
                429, f"too many long steps or jumps from this device: the next one in {retry} s", retry_after_s=retry
            )

    # -- viewers -------------------------------------------------------------------------------------------
    @contextmanager
    def viewer(self, session_id: str, scene_id: str, *, client: str | None) -> Iterator[None]:
        """Hold a viewer's place while the block runs; :class:`Refused` if it may not open (stage: 403, no such
        session: 404, another scene: 409, too many: 429)."""
        with self._lock:
            if session_id.startswith(STAGE_PREFIX):
                raise Refused(403, "a classroom room's shared scene is watched through the room (/room-viewer/…)")
            entry = self._known_locked(session_id)
            if entry is None:
                raise Refused(404, "this scene has not been opened by its page yet (or was closed): reload the page")
            if entry.scene_id != scene_id:
                raise Refused(409, f"this session shows {entry.scene_id!r}, not {scene_id!r}: reload the page")
            if entry.viewers >= MAX_VIEWERS_PER_SESSION:
                raise Refused(
                    429, f"this scene has {MAX_VIEWERS_PER_SESSION} viewers open already: close a tab", retry_after_s=5
                )
            if client is not None and not self._viewers_of_client.try_enter(client):
                raise Refused(
                    429, f"this device has {MAX_VIEWERS_PER_CLIENT} scenes open already: close a tab", retry_after_s=5
                )
            entry.viewers += 1
            self._touch_locked(session_id, entry)
        try:
            yield
        finally:
            with self._lock:
                entry.viewers -= 1
                if self._entries.get(session_id) is entry:  # watched until now: the last to be evicted, not the first
                    self._touch_locked(session_id, entry)
            if client is not None:
                self._viewers_of_client.leave(client)

    @contextmanager
    def follower(self, *, client: str | None) -> Iterator[None]:
        """Hold a room follower's place while the block runs; :class:`Refused` (429) beyond the client's share."""
        with _place(
            self._followers,
            client,
            Refused(429, f"this device follows the room in {MAX_FOLLOWERS_PER_CLIENT} tabs already", retry_after_s=5),
        ):
            yield
