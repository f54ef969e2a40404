"""Page sessions kept in the database (app.api.access.SessionDirectory writes through this): a restart keeps each
page's scene, its parameters and who claimed it (a key's digest, never the key), so the page's viewer reconnects to
the same scene and a claimed session still refuses a keyless change. The address that made a session is not kept:
after a restart a kept session counts against no device's share until its page changes it again."""

from __future__ import annotations

import logging
from dataclasses import dataclass
from datetime import UTC, datetime, timedelta
from typing import Any

import sqlalchemy as sa
from sqlalchemy.exc import SQLAlchemyError

from app.storage.database import Database
from app.storage.tables import sessions

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class KeptSession:
    session_id: str
    scene_id: str
    key_hash: bytes | None
    params: dict[str, Any]


class SqlSessionStore:
    """Page sessions in ``database``. A failed write is logged, not raised: a page's change still applies, and only a
    restart before its next change could forget it."""

    def __init__(self, database: Database) -> None:
        self.database = database

    def save(self, kept: KeptSession) -> None:
        values = {
            "scene_id": kept.scene_id,
            "key_digest": kept.key_hash.hex() if kept.key_hash is not None else None,
            "params": kept.params,
            "used_at": datetime.now(UTC),
        }
        try:
            with self.database.transaction() as connection:
                where = sessions.c.session_id == kept.session_id
                if connection.execute(sa.update(sessions).where(where).values(**values)).rowcount == 0:
                    connection.execute(sa.insert(sessions).values(session_id=kept.session_id, **values))
                self.database.announce(connection, "session", kept.session_id)
        except SQLAlchemyError as exc:
            log.error("the database did not keep session %s: %s", kept.session_id, exc)

    def delete(self, session_id: str) -> None:
        try:
            with self.database.transaction() as connection:
                connection.execute(sa.delete(sessions).where(sessions.c.session_id == session_id))
                self.database.announce(connection, "session", session_id)
        except SQLAlchemyError as exc:
            log.error("the database did not forget session %s: %s", session_id, exc)

    def forget_unused(self, *, days: float) -> None:
        """Forget every session nobody has used for ``days``."""
        cutoff = datetime.now(UTC) - timedelta(days=days)
        try:
            with self.database.transaction() as connection:
                connection.execute(sa.delete(sessions).where(sessions.c.used_at < cutoff))
        except SQLAlchemyError as exc:
            log.error("the database did not forget unused sessions: %s", exc)

    def load_one(self, session_id: str) -> KeptSession | None:
        """One kept session (None if none is kept, or its row is not one this code wrote)."""
        query = sa.select(sessions).where(sessions.c.session_id == session_id)
        try:
            with self.database.engine.connect() as connection:
                row = connection.execute(query).mappings().first()
        except SQLAlchemyError as exc:
            log.error("the database did not answer for session %s: %s", session_id, exc)
            return None
        return None if row is None else _kept(row)

    def load(self, limit: int) -> list[KeptSession]:
        """The ``limit`` most recently used sessions, least recent first."""
        query = sa.select(sessions).order_by(sessions.c.used_at.desc()).limit(limit)
        with self.database.engine.connect() as connection:
            rows = list(connection.execute(query).mappings())
        return [kept for kept in map(_kept, reversed(rows)) if kept is not None]


def _kept(row: Any) -> KeptSession | None:
    """A session's row as kept; None (and said) for one this code did not write."""
    if not isinstance(row["params"], dict):
        log.warning("session %s: its kept parameters are not an object; it is not restored", row["session_id"])
        return None
    return KeptSession(
        session_id=row["session_id"],
        scene_id=row["scene_id"],
        key_hash=bytes.fromhex(row["key_digest"]) if row["key_digest"] else None,
        params=dict(row["params"]),
    )
