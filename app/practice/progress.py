"""Learners and their exercise progress, kept in the database: what the practice pages remember of a student working
alone (issue 27's exercises record here; ``GET /api/progress`` reads here).

A learner has no account. Their browser holds a secret token (the database keeps only its SHA-256); a short resume
code (kept as its digest too) gives another browser a token of its own for the same learner. Per exercise part the
store keeps the variant worked on, the attempts, whether it was solved or given up, and the named mistakes the wrong
answers matched. Learners nobody has used for the configured number of days are forgotten with their progress.
"""

from __future__ import annotations

import contextlib
import logging
import secrets
import threading
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from datetime import UTC, datetime, timedelta
from typing import Any

import sqlalchemy as sa
from sqlalchemy.exc import IntegrityError, SQLAlchemyError

from app.classroom.room import CODE_ALPHABET, digest
from app.storage.database import Database, StoreUnavailable
from app.storage.tables import exercise_progress, learner_tokens, learners, room_exercise_work

log = logging.getLogger(__name__)

#: Characters of a resume code (a code a student copies by hand: no I, L, O, 0, 1), in two groups of five.
RESUME_GROUP = 5
RESUME_GROUPS = 2
#: Named mistakes kept per part (the most recent): enough for an instructor's "common mistakes", bounded.
MAX_KEPT_MISTAKES = 20
#: Longest exercise or part id, and mistake id, the store takes (the exercise files' ids are shorter).
MAX_ID_LENGTH = 32


@dataclass(frozen=True)
class Learner:
    """A learner: ``learner_id`` (public, in the instructor's views) and, when just made or resumed, the secret
    ``token`` this browser keeps (None when found by a token the browser already has)."""

    learner_id: str
    token: str | None = None
    resume_code: str | None = None


@dataclass(frozen=True)
class PartProgress:
    """One exercise part as a learner left it."""

    exercise_id: str
    part_id: str
    variant: int
    attempts: int
    solved: bool
    gave_up: bool
    mistakes: tuple[str, ...]
    updated_at: datetime

    def public(self) -> dict[str, Any]:
        return {
            "exercise_id": self.exercise_id,
            "part": self.part_id,
            "variant": self.variant,
            "attempts": self.attempts,
            "solved": self.solved,
            "gave_up": self.gave_up,
            "mistakes": list(self.mistakes),
        }


def normal_resume_code(code: str) -> str | None:
    """A typed resume code in its kept form (capitals, no spaces or dashes); None if it cannot be one."""
    if not isinstance(code, str) or len(code) > 2 * RESUME_GROUP * RESUME_GROUPS:
        return None
    cleaned = "".join(c for c in code.upper() if c not in " -")
    if len(cleaned) != RESUME_GROUP * RESUME_GROUPS or any(c not in CODE_ALPHABET for c in cleaned):
        return None
    return cleaned


def _new_resume_code() -> str:
    groups = ("".join(secrets.choice(CODE_ALPHABET) for _ in range(RESUME_GROUP)) for _ in range(RESUME_GROUPS))
    return "-".join(groups)


def _checked_id(value: str, what: str) -> str:
    if not isinstance(value, str) or not 0 < len(value) <= MAX_ID_LENGTH or not value.isprintable():
        raise ValueError(f"{what}: 1 to {MAX_ID_LENGTH} printable characters")
    return value


class SqlProgressStore:
    """Learners and their progress in ``database``."""

    def __init__(self, database: Database) -> None:
        self.database = database
        self._parts = PartRecords(database, exercise_progress, ("learner_id",))

    def _writing(self, what: str) -> contextlib.AbstractContextManager[sa.Connection]:
        return _writing(self.database, what)

    # -- learners -------------------------------------------------------------------------------
    def new_learner(self) -> Learner:
        """A new learner, with this browser's token and their resume code (both shown once, kept as digests)."""
        learner_id = f"l{secrets.token_hex(8)}"
        token, code = secrets.token_urlsafe(24), _new_resume_code()
        now = datetime.now(UTC)
        with self._writing("a new learner") as connection:
            connection.execute(
                sa.insert(learners).values(
                    learner_id=learner_id,
                    resume_digest=digest(normal_resume_code(code) or ""),
                    created_at=now,
                    used_at=now,
                )
            )
            connection.execute(sa.insert(learner_tokens).values(token_digest=digest(token), learner_id=learner_id))
        return Learner(learner_id, token=token, resume_code=code)

    def learner(self, token: str | None) -> Learner | None:
        """The learner this browser's token belongs to (None: no such learner, or forgotten)."""
        if not token or not isinstance(token, str) or len(token) > 200:
            return None
        query = sa.select(learner_tokens.c.learner_id).where(learner_tokens.c.token_digest == digest(token))
        with self._writing("a learner's last use") as connection:
            learner_id = connection.execute(query).scalar()
            if learner_id is None:
                return None
            connection.execute(
                sa.update(learners).where(learners.c.learner_id == learner_id).values(used_at=datetime.now(UTC))
            )
        return Learner(learner_id)

    def resume(self, code: str) -> Learner | None:
        """The learner whose resume code this is, with a new token for this browser (the others keep theirs);
        None for a code no learner has."""
        kept = normal_resume_code(code)
        if kept is None:
            return None
        query = sa.select(learners.c.learner_id).where(learners.c.resume_digest == digest(kept))
        token = secrets.token_urlsafe(24)
        with self._writing("a resumed learner") as connection:
            learner_id = connection.execute(query).scalar()
            if learner_id is None:
                return None
            connection.execute(sa.insert(learner_tokens).values(token_digest=digest(token), learner_id=learner_id))
            connection.execute(
                sa.update(learners).where(learners.c.learner_id == learner_id).values(used_at=datetime.now(UTC))
            )
        return Learner(learner_id, token=token)

    def forget(self, learner_id: str) -> bool:
        """Forget a learner with all their progress and tokens; False if there was none."""
        with self._writing(f"the deletion of learner {learner_id}") as connection:
            return self._forget(connection, [learner_id]) > 0

    def forget_unused(self, *, days: float) -> int:
        """Forget every learner (with their progress) nobody has used for ``days``; returns how many."""
        cutoff = datetime.now(UTC) - timedelta(days=days)
        with self._writing("the removal of unused learners") as connection:
            old = [
                row[0]
                for row in connection.execute(sa.select(learners.c.learner_id).where(learners.c.used_at < cutoff))
            ]
            return self._forget(connection, old)

    @staticmethod
    def _forget(connection: sa.Connection, learner_ids: list[str]) -> int:
        if not learner_ids:
            return 0
        connection.execute(sa.delete(exercise_progress).where(exercise_progress.c.learner_id.in_(learner_ids)))
        connection.execute(sa.delete(learner_tokens).where(learner_tokens.c.learner_id.in_(learner_ids)))
        return connection.execute(sa.delete(learners).where(learners.c.learner_id.in_(learner_ids))).rowcount

    # -- progress -------------------------------------------------------------------------------
    def record(
        self,
        learner_id: str,
        *,
        exercise_id: str,
        part_id: str,
        variant: int,
        correct: bool = False,
        mistake_id: str | None = None,
        gave_up: bool = False,
    ) -> PartProgress:
        """An attempt at a part (``correct``, or matching the named ``mistake_id``), or giving up on it, kept as
        :meth:`PartRecords.record` says; the learner counts as used."""

        def used(connection: sa.Connection) -> None:
            connection.execute(
                sa.update(learners).where(learners.c.learner_id == learner_id).values(used_at=datetime.now(UTC))
            )

        return self._parts.record(
            (learner_id,),
            exercise_id=exercise_id,
            part_id=part_id,
            variant=variant,
            correct=correct,
            mistake_id=mistake_id,
            gave_up=gave_up,
            also=used,
        )

    def progress(self, learner_id: str) -> list[PartProgress]:
        """Every part the learner has worked on, by exercise then part."""
        return [part for _, part in self._parts.read(*self._parts.owner((learner_id,)), what="progress")]


class PartRecords:
    """Work on exercise parts in one ``table`` keyed by ``key_columns`` (a learner; a room and a student), then the
    exercise and the part: the variant worked on, attempts, solved or given up, and the named mistakes matched."""

    def __init__(self, database: Database, table: sa.Table, key_columns: tuple[str, ...]) -> None:
        self.database, self.table, self.key_columns = database, table, key_columns
        #: One write at a time in this process (SQLite would refuse a second writer's stale read; on PostgreSQL the
        #: row lock below orders the writes of several servers).
        self._recording = threading.Lock()

    def owner(self, key: tuple[str, ...]) -> list[sa.ColumnElement[bool]]:
        """The conditions that select ``key``'s rows."""
        return [self.table.c[name] == value for name, value in zip(self.key_columns, key, strict=True)]

    def record(
        self,
        key: tuple[str, ...],
        *,
        exercise_id: str,
        part_id: str,
        variant: int,
        correct: bool = False,
        mistake_id: str | None = None,
        gave_up: bool = False,
        also: Callable[[sa.Connection], None] | None = None,
    ) -> PartProgress:
        """An attempt at a part (``correct``, or matching the named ``mistake_id``), or giving up on it: kept in one
        transaction with the part's earlier work (and ``also``'s statements). Working on another variant starts the
        part afresh. Once solved a part stays solved; once given up, a right answer typed afterwards (the solution's,
        copied) is checked but does not make it solved."""
        _checked_id(exercise_id, "exercise_id")
        _checked_id(part_id, "part")
        if mistake_id is not None:
            _checked_id(mistake_id, "mistake")
        if isinstance(variant, bool) or not isinstance(variant, int) or not 0 <= variant < 2**31:
            raise ValueError("variant: an integer from 0 to 2³¹ − 1")
        where = (*self.owner(key), self.table.c.exercise_id == exercise_id, self.table.c.part_id == part_id)
        for attempt in range(2):  # two servers' first attempts at once: the second insert finds the first's row
            try:
                with self._recording, _writing(self.database, f"work on {exercise_id}") as connection:
                    row = connection.execute(sa.select(self.table).where(*where).with_for_update()).mappings().first()
                    earlier = row if row is not None and row["variant"] == variant else None
                    mistakes = list(earlier["mistakes"]) if earlier is not None else []
                    if mistake_id is not None:
                        mistakes = [*mistakes, mistake_id][-MAX_KEPT_MISTAKES:]
                    gave_up_before = earlier is not None and bool(earlier["gave_up"])
                    values: dict[str, Any] = {
                        "variant": variant,
                        "attempts": (earlier["attempts"] if earlier is not None else 0) + (0 if gave_up else 1),
                        "solved": (earlier is not None and bool(earlier["solved"])) or (correct and not gave_up_before),
                        "gave_up": gave_up_before or gave_up,
                        "mistakes": mistakes,
                        "updated_at": datetime.now(UTC),
                    }
                    if row is None:
                        owner = dict(zip(self.key_columns, key, strict=True))
                        connection.execute(
                            sa.insert(self.table).values(**owner, exercise_id=exercise_id, part_id=part_id, **values)
                        )
                    else:
                        connection.execute(sa.update(self.table).where(*where).values(**values))
                    if also is not None:
                        also(connection)
                break
            except StoreUnavailable as exc:
                if attempt or not isinstance(exc.__cause__, IntegrityError):
                    raise
        return PartProgress(
            exercise_id=exercise_id,
            part_id=part_id,
            variant=variant,
            attempts=values["attempts"],
            solved=values["solved"],
            gave_up=values["gave_up"],
            mistakes=tuple(values["mistakes"]),
            updated_at=values["updated_at"],
        )

    def read(self, *conditions: sa.ColumnElement[bool], what: str) -> list[tuple[Any, PartProgress]]:
        """``(row, part)`` for every row that meets ``conditions``, by exercise then part."""
        query = sa.select(self.table).where(*conditions).order_by(self.table.c.exercise_id, self.table.c.part_id)
        try:
            with self.database.engine.connect() as connection:
                rows = list(connection.execute(query).mappings())
        except SQLAlchemyError as exc:
            raise StoreUnavailable(f"the server could not read {what} just now: {exc}") from exc
        return [
            (
                row,
                PartProgress(
                    exercise_id=row["exercise_id"],
                    part_id=row["part_id"],
                    variant=row["variant"],
                    attempts=row["attempts"],
                    solved=row["solved"],
                    gave_up=row["gave_up"],
                    mistakes=tuple(row["mistakes"]),
                    updated_at=row["updated_at"],
                ),
            )
            for row in rows
        ]


class SqlRoomWorkStore:
    """A room's record of its students' work on the exercises it assigned (app.practice.in_room): by room and student,
    apart from each learner's own progress (which the learner may forget; this stays while the room does)."""

    def __init__(self, database: Database) -> None:
        self._parts = PartRecords(database, room_exercise_work, ("room_id", "student_id"))

    def record(
        self,
        room_id: str,
        student_id: str,
        *,
        exercise_id: str,
        part_id: str,
        variant: int,
        correct: bool = False,
        mistake_id: str | None = None,
        gave_up: bool = False,
    ) -> PartProgress:
        return self._parts.record(
            (room_id, student_id),
            exercise_id=exercise_id,
            part_id=part_id,
            variant=variant,
            correct=correct,
            mistake_id=mistake_id,
            gave_up=gave_up,
        )

    def work_of(self, room_id: str, exercise_ids: list[str]) -> list[tuple[str, PartProgress]]:
        """``(student_id, part)`` for every part of ``exercise_ids`` a student of room ``room_id`` worked on."""
        if not exercise_ids:
            return []
        table = self._parts.table
        work = self._parts.read(
            table.c.room_id == room_id, table.c.exercise_id.in_(exercise_ids), what="a room's results"
        )
        return [(row["student_id"], part) for row, part in work]


@contextmanager
def _writing(database: Database, what: str) -> Iterator[sa.Connection]:
    try:
        with database.transaction() as connection:
            yield connection
    except SQLAlchemyError as exc:
        log.error("the database did not keep %s: %s", what, exc)
        raise StoreUnavailable(f"the server could not keep {what} just now; try again in a moment") from exc
