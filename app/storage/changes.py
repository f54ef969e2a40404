"""What other servers sharing the database changed, as they commit it: PostgreSQL's LISTEN/NOTIFY.

Several ``dynlab serve`` on one PostgreSQL database serve one course: a balancer sends each room's and each page
session's traffic to one of them, but a room's students may reach another (a balancer's health check moving a room
between servers, a rolling restart). Every write of a room, an answer or a page session announces itself in its own
transaction (:meth:`app.storage.database.Database.announce`); PostgreSQL delivers the announcement to every listening
server when, and only if, the transaction commits, in commit order. Each server listens here and brings what it holds
up to date (app.classroom.sync). The database already had to be shared, so this adds no server and no protocol of
our own; Redis pub/sub would add both a server to run and a second source of truth to keep in step.

An announcement is a hint, never the data: a server reads what changed from the database. A server that lost its
listening connection missed some, so on reconnecting it is told to read everything it holds again.
"""

from __future__ import annotations

import json
import logging
import threading
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from app.storage.database import CHANGES_CHANNEL, Database, postgresql_connect_args

log = logging.getLogger(__name__)

#: Seconds between attempts to listen again after the listening connection is lost (doubling up to the last).
RECONNECT_DELAYS_S = (0.2, 0.5, 1.0, 2.0, 5.0)


@dataclass(frozen=True)
class Change:
    """One change another server committed: ``kind`` (``room``, ``answer``, ``room_closed``, ``session``,
    ``presence``) of ``key`` (a room or session id), with what the kind adds (a room's ``version``; an answer's
    ``poll_id``, ``student_id``; who the server's sockets of a room hold)."""

    kind: str
    key: str
    #: The server that made it (:attr:`app.storage.database.Database.origin` there).
    origin: str = ""
    fields: dict[str, Any] = field(default_factory=dict)


class ChangeListener:
    """Listens for other servers' changes on ``database`` (PostgreSQL) in a thread of its own, and hands each to
    ``on_change``, one at a time in commit order. Each time it starts listening (first, and after a lost connection)
    it calls ``on_missed``: changes made before are unknown to it."""

    def __init__(
        self,
        database: Database,
        *,
        on_change: Callable[[Change], None],
        on_missed: Callable[[], None],
    ) -> None:
        self.database = database
        self._on_change = on_change
        self._on_missed = on_missed
        self._stopping = threading.Event()
        self._connection: Any = None
        self.listening = threading.Event()
        self._thread = threading.Thread(target=self._run, name="dynlab-changes", daemon=True)

    def start(self) -> None:
        self._thread.start()

    def stop(self) -> None:
        self._stopping.set()
        connection = self._connection
        if connection is not None:
            try:
                connection.close()
            except Exception:  # noqa: BLE001 - closing a connection already lost
                pass
        self._thread.join(timeout=5)

    def _conninfo(self) -> str:
        url = self.database.engine.url.set(drivername="postgresql")
        return url.render_as_string(hide_password=False)

    def _run(self) -> None:
        import psycopg

        attempt = 0
        while not self._stopping.is_set():
            try:
                bounds = {k: v for k, v in postgresql_connect_args().items() if k != "options"}
                with psycopg.connect(self._conninfo(), autocommit=True, **bounds) as connection:
                    self._connection = connection
                    connection.execute(f"LISTEN {CHANGES_CHANNEL}")
                    if attempt:
                        log.warning("listening to the other servers' changes again")
                    attempt = 0
                    # Whatever this server took up before it listened (or while it did not) may be behind: read anew.
                    self._on_missed()
                    self.listening.set()
                    while not self._stopping.is_set():
                        for notify in connection.notifies(timeout=1.0):
                            self._hand_on(notify.payload)
            except Exception as exc:  # noqa: BLE001 - a lost connection: listen again, and read anew
                self.listening.clear()
                if self._stopping.is_set():
                    break
                delay = RECONNECT_DELAYS_S[min(attempt, len(RECONNECT_DELAYS_S) - 1)]
                attempt += 1
                log.warning("not listening to the other servers' changes (%s): again in %g s", exc, delay)
                self._stopping.wait(delay)
            finally:
                self._connection = None

    def _hand_on(self, payload: str) -> None:
        try:
            message = json.loads(payload)
            origin = message.pop("origin")
            if origin == self.database.origin:
                return  # this server's own change: it already holds it
            change = Change(kind=message.pop("kind"), key=message.pop("key"), origin=str(origin), fields=message)
        except (ValueError, KeyError, TypeError, AttributeError):
            log.warning("an announcement that is not one of ours on %s: %.80r", CHANGES_CHANNEL, payload)
            return
        try:
            self._on_change(change)
        except Exception:  # one change not taken up must not stop the listening
            log.exception("taking up %s %s from another server failed", change.kind, change.key)
