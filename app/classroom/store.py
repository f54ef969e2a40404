"""Rooms kept in the database: each room's record (app.classroom.room.Room.record) and its polls' answers.

A room is written whole (one row) after each change the room makes, in one transaction with the rows that change
touches (a removed student's answers go with them); an answer is one row of its own, since a class answers in bursts.
At start-up every kept room comes back (:meth:`SqlRoomStore.load`), its students known by their tokens' digests.
"""

from __future__ import annotations

import logging
import threading
from collections import defaultdict
from collections.abc import Iterator
from contextlib import contextmanager
from datetime import UTC, datetime, timedelta
from typing import Any

import sqlalchemy as sa
from sqlalchemy.exc import IntegrityError, SQLAlchemyError

from app.classroom.room import DEFAULT_JOIN_BASE, Room, RoomAlreadyClosed, RoomChangedElsewhere
from app.storage.database import Database, StoreUnavailable
from app.storage.tables import answers, room_exercise_work, rooms

log = logging.getLogger(__name__)

#: PostgreSQL's codes for a wait that reached its bound (lock_not_available, idle_in_transaction_session_timeout):
#: a busy room, answered 503 like any other, but not a database failure worth an error in the log.
BUSY_SQLSTATES = frozenset({"55P03", "25P03"})


def _utc(seconds: float) -> datetime:
    return datetime.fromtimestamp(seconds, UTC)


class SqlRoomStore:
    """Rooms in ``database`` (the :class:`~app.classroom.room.RoomStore` every kept room writes to)."""

    def __init__(self, database: Database) -> None:
        self.database = database
        #: The connection of the turn this thread holds (:meth:`turn`), which this thread's writes join.
        self._turn = threading.local()

    @property
    def shared(self) -> bool:
        """True if other servers may change the rooms too (a shared PostgreSQL)."""
        return self.database.shared

    @contextmanager
    def _writing(self, what: str) -> Iterator[sa.Connection]:
        held = getattr(self._turn, "connection", None)
        if held is not None:  # part of this thread's turn: written when the turn commits
            yield held
            return
        try:
            with self.database.transaction() as connection:
                yield connection
        except IntegrityError as exc:  # a row the write refers to is gone (the room closed meanwhile): the caller says
            raise StoreUnavailable(f"the server could not keep {what}: what it belongs to is gone") from exc
        except SQLAlchemyError as exc:
            cause = getattr(exc, "orig", None)  # the driver's own error (a DBAPIError's)
            if getattr(cause, "sqlstate", None) in BUSY_SQLSTATES:  # a turn (another's, or this one) overran
                log.warning("%s not kept: a turn at the room was held past its bound (%s)", what, type(cause).__name__)
                raise StoreUnavailable(f"the server could not keep {what}: busy elsewhere just now; try again") from exc
            log.error("the database did not keep %s: %s", what, exc)
            raise StoreUnavailable(f"the server could not keep {what} just now; try again in a moment") from exc

    @contextmanager
    def turn(self, room: Room) -> Iterator[int | None]:
        """This server's turn to change ``room``. On a database several servers share: one transaction that holds
        the room's row (``SELECT … FOR UPDATE``), so the other servers' changes of the room wait for it, and that
        this thread's writes of the room join (written, and announced, when the turn ends; taken through
        :meth:`app.classroom.room.Room.turn`, which orders it before the room's lock); it yields the version
        kept now (None: the room is no longer kept). On SQLite, which one server holds, nothing waits: it yields the
        version the room read."""
        if not self.shared:
            yield room.kept_version
            return
        with self._writing(f"room {room.code}") as connection:
            # FOR NO KEY UPDATE: other servers' changes of the room wait; an answer's row (whose key refers to the
            # room's) does not.
            query = sa.select(rooms.c.version).where(rooms.c.room_id == room.room_id).with_for_update(key_share=True)
            version = connection.execute(query).scalar()
            self._turn.connection = connection
            try:
                yield version
            finally:
                self._turn.connection = None

    def insert(self, room: Room) -> None:
        """Keep a new room (at version 0)."""
        with self._writing(f"room {room.code}") as connection:
            connection.execute(
                sa.insert(rooms).values(
                    room_id=room.room_id,
                    code=room.code,
                    created_at=_utc(room.created_at),
                    used_at=datetime.now(UTC),
                    record=room.record(),
                    version=0,
                )
            )
        room.kept_version = 0

    def save(self, room: Room, *, withdrawn_student: str | None = None) -> None:
        """Keep a kept room as it is now, over the version it last read. :class:`RoomChangedElsewhere` if another
        server sharing the database wrote a newer version, or deleted the room (only :meth:`insert` adds one): nothing
        is written, and the room takes that version up before its change runs again, or is closed."""
        record = room.record()
        with self._writing(f"room {room.code}") as connection:
            now = datetime.now(UTC)
            this_version = (rooms.c.room_id == room.room_id) & (rooms.c.version == room.kept_version)
            written = connection.execute(
                sa.update(rooms).where(this_version).values(used_at=now, record=record, version=rooms.c.version + 1)
            ).rowcount
            if written == 0:  # a newer version, or the room deleted (closed on another server, `dynlab rooms delete`)
                raise RoomChangedElsewhere(room.room_id)
            if withdrawn_student is not None:
                connection.execute(
                    sa.delete(answers).where(
                        answers.c.room_id == room.room_id, answers.c.student_id == withdrawn_student
                    )
                )
                work = room_exercise_work.c
                connection.execute(
                    sa.delete(room_exercise_work).where(
                        work.room_id == room.room_id, work.student_id == withdrawn_student
                    )
                )
            self.database.announce(connection, "room", room.room_id, version=room.kept_version + 1)
        room.kept_version += 1

    def save_answer(self, room: Room, poll_id: str, student_id: str) -> None:
        kept = room.poll(poll_id).answer_of(student_id)
        if kept is None:
            return
        try:
            with self._writing(f"an answer in room {room.code}") as connection:
                key = (
                    answers.c.room_id == room.room_id,
                    answers.c.poll_id == poll_id,
                    answers.c.student_id == student_id,
                )
                connection.execute(sa.delete(answers).where(*key))
                connection.execute(
                    sa.insert(answers).values(room_id=room.room_id, poll_id=poll_id, student_id=student_id, **kept)
                )
                self.database.announce(connection, "answer", room.room_id, poll_id=poll_id, student_id=student_id)
        except StoreUnavailable as exc:
            if isinstance(exc.__cause__, IntegrityError):  # the room's row is gone: closed meanwhile (409)
                raise RoomAlreadyClosed("room", f"room {room.code} was closed; the answer was not kept") from None
            raise

    def load_answer(self, room_id: str, poll_id: str, student_id: str) -> dict[str, Any] | None:
        """One kept answer (as :meth:`app.classroom.polls.Poll.answer_of` gives it), None if none is kept."""
        key = (answers.c.room_id == room_id, answers.c.poll_id == poll_id, answers.c.student_id == student_id)
        columns = (answers.c.number, answers.c.name, answers.c.choice, answers.c.value, answers.c.answered_at)
        try:
            with self.database.engine.connect() as connection:
                row = connection.execute(sa.select(*columns).where(*key)).mappings().first()
        except SQLAlchemyError as exc:
            raise StoreUnavailable(f"the server could not read an answer just now: {exc}") from exc
        return None if row is None else dict(row)

    def delete(self, room_id: str) -> bool:
        """Forget a room and every answer in it; False if there was no such room."""
        with self._writing(f"the deletion of room {room_id}") as connection:
            connection.execute(sa.delete(answers).where(answers.c.room_id == room_id))
            connection.execute(sa.delete(room_exercise_work).where(room_exercise_work.c.room_id == room_id))
            deleted = connection.execute(sa.delete(rooms).where(rooms.c.room_id == room_id)).rowcount > 0
            if deleted:
                self.database.announce(connection, "room_closed", room_id)
            return deleted

    def forget_unused(self, *, days: float) -> int:
        """Forget every room (with its answers) nobody has used for ``days``; returns how many."""
        cutoff = datetime.now(UTC) - timedelta(days=days)
        with self._writing("the removal of unused rooms") as connection:
            old = [row[0] for row in connection.execute(sa.select(rooms.c.room_id).where(rooms.c.used_at < cutoff))]
            if old:
                connection.execute(sa.delete(answers).where(answers.c.room_id.in_(old)))
                connection.execute(sa.delete(room_exercise_work).where(room_exercise_work.c.room_id.in_(old)))
                connection.execute(sa.delete(rooms).where(rooms.c.room_id.in_(old)))
        if old:
            log.info("forgot %d room(s) unused for %g days", len(old), days)
        return len(old)

    def load_one(self, *, join_base: str, room_id: str | None = None, code: str | None = None) -> Room | None:
        """The kept room with this id or code (None if none is kept)."""
        where = rooms.c.room_id == room_id if room_id is not None else rooms.c.code == code
        return next(iter(self._load(sa.select(rooms).where(where), join_base=join_base)), None)

    def load_newer(self, room: Room) -> Room | None:
        """``room`` as the database keeps it now (a version another server wrote), joined at the same address; None
        if it is no longer kept (closed)."""
        return self.load_one(join_base=room.join_url.rsplit("/join/", 1)[0], room_id=room.room_id)

    def load(self, *, join_base: str = DEFAULT_JOIN_BASE, limit: int | None = None) -> list[Room]:
        """The kept rooms (the ``limit`` most recently used), with their answers, written to this store again as they
        change; oldest first. Students join them at ``join_base``."""
        recent = sa.select(rooms).order_by(rooms.c.used_at.desc()).limit(limit)
        return list(reversed(self._load(recent, join_base=join_base)))

    def _load(self, query: sa.Select[Any], *, join_base: str) -> list[Room]:
        try:
            return self._load_from(query, join_base=join_base)
        except SQLAlchemyError as exc:
            log.error("the database did not answer for rooms: %s", exc)
            raise StoreUnavailable("the server could not read its rooms just now; try again in a moment") from exc

    def _load_from(self, query: sa.Select[Any], *, join_base: str) -> list[Room]:
        with self.database.engine.connect() as connection:
            loaded = []
            for row in connection.execute(query).mappings():
                kept_answers: dict[str, dict[str, dict[str, Any]]] = defaultdict(dict)
                in_room = sa.select(answers).where(answers.c.room_id == row["room_id"])
                for answer in connection.execute(in_room).mappings():
                    kept_answers[answer["poll_id"]][answer["student_id"]] = dict(answer)
                created = row["created_at"]
                created = created if created.tzinfo else created.replace(tzinfo=UTC)
                used = row["used_at"] if row["used_at"].tzinfo else row["used_at"].replace(tzinfo=UTC)
                room = Room.from_record(
                    room_id=row["room_id"],
                    code=row["code"],
                    created_at=created.timestamp(),
                    used_at=used.timestamp(),
                    join_base=join_base,
                    record=row["record"],
                    answers=kept_answers,
                )
                room.store = self
                room.kept_version = row["version"]
                loaded.append(room)
            return loaded

    def listing(self) -> list[dict[str, Any]]:
        """Every kept room in brief (``dynlab rooms``): id, code, lesson, students, polls, answers, created, used."""
        with self.database.engine.connect() as connection:
            counted = connection.execute(sa.select(answers.c.room_id, sa.func.count()).group_by(answers.c.room_id))
            counts: dict[str, int] = {room_id: count for room_id, count in counted}
            listed = []
            for row in connection.execute(sa.select(rooms).order_by(rooms.c.created_at)).mappings():
                record = row["record"]
                listed.append(
                    {
                        "room_id": row["room_id"],
                        "code": row["code"],
                        "lesson_id": record["lesson_id"],
                        "students": len(record["students"]),
                        "polls": len(record["polls"]),
                        "answers": counts.get(row["room_id"], 0),
                        "created_at": row["created_at"],
                        "used_at": row["used_at"],
                    }
                )
            return listed
