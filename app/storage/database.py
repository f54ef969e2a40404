"""Opening the database: where it is, its connection rules, and its schema brought up to date at start-up."""

from __future__ import annotations

import json
import logging
import os
import secrets
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import sqlalchemy as sa
from alembic import command
from alembic.config import Config
from alembic.runtime.migration import MigrationContext
from alembic.script import ScriptDirectory
from sqlalchemy.exc import SQLAlchemyError

from app.storage.tables import server_values

log = logging.getLogger(__name__)

MIGRATIONS_DIR = Path(__file__).resolve().parent / "migrations"
#: The SQLite file in the data directory.
SQLITE_FILE = "dynlab.sqlite3"
#: The PostgreSQL channel servers sharing a database announce their changes on (app.storage.changes).
CHANGES_CHANNEL = "dynlab_changes"
#: The PostgreSQL advisory lock held while the schema is brought forward: servers starting together migrate in turn.
MIGRATION_LOCK = 0x64796E6C6162
#: On PostgreSQL: longest wait for a lock (another server's turn at a room), and longest a transaction may sit idle
#: (a server frozen inside its turn) before the database ends it (ms).
PG_LOCK_TIMEOUT_MS = 3_000
PG_IDLE_IN_TRANSACTION_MS = 20_000
#: Longest wait for another server's migration, or for the tables a migration alters (ms).
MIGRATION_LOCK_TIMEOUT_MS = 60_000
#: How long a write waits for another process's write to finish before it fails (ms): SQLite lets one write at a time.
SQLITE_BUSY_TIMEOUT_MS = 10_000


class DatabaseUnusable(RuntimeError):
    """The data directory or database cannot be used (not a directory, not a database, newer than this code)."""


def default_data_dir() -> Path:
    """Where a user's data lives unless ``--data-dir`` or ``DYNLAB_DATA_DIR`` says: ``$XDG_DATA_HOME/dynlab``, else
    ``~/.local/share/dynlab`` (the XDG base directory default)."""
    base = os.environ.get("XDG_DATA_HOME") or str(Path.home() / ".local" / "share")
    return Path(base) / "dynlab"


def sqlite_url(data_dir: Path) -> str:
    """The default database: one SQLite file in ``data_dir`` (created, readable by its owner only, if missing)."""
    try:
        data_dir.mkdir(parents=True, exist_ok=True, mode=0o700)
    except (FileExistsError, NotADirectoryError):
        raise DatabaseUnusable(f"the data directory {data_dir} is a file, not a directory") from None
    database = data_dir / SQLITE_FILE
    # SQLite gives its -wal and -shm files the database file's permissions: made owner-only here, they are too, even
    # in a data directory others may read (a container's volume).
    database.touch(mode=0o600, exist_ok=True)
    database.chmod(0o600)
    return f"sqlite:///{database}"


def _on_sqlite_connect(connection: Any, _record: Any) -> None:
    """Every SQLite connection: write-ahead log (readers never wait for the writer, a crash mid-write loses nothing
    committed), fsync at checkpoints (NORMAL: safe in WAL mode), foreign keys enforced, and waits for a lock."""
    cursor = connection.cursor()
    cursor.execute("PRAGMA journal_mode=WAL")
    cursor.execute("PRAGMA synchronous=NORMAL")
    cursor.execute("PRAGMA foreign_keys=ON")
    cursor.execute(f"PRAGMA busy_timeout={SQLITE_BUSY_TIMEOUT_MS}")
    cursor.close()


class Database:
    r"""The open database. Every write is one transaction (:meth:`transaction`): all of it is kept, or none.

    ``origin`` names this process among the servers that may share the database (PostgreSQL): what it
    :meth:`announce`\ s carries it, so a server can tell its own changes from others' (app.storage.changes)."""

    def __init__(self, engine: sa.Engine) -> None:
        self.engine = engine
        self.origin = secrets.token_hex(6)

    @property
    def shared(self) -> bool:
        """True for a database server several ``dynlab serve`` may share (PostgreSQL); False for the SQLite file one
        server holds (its data directory's lock says so)."""
        return self.engine.dialect.name != "sqlite"

    def announce(self, connection: sa.Connection, kind: str, key: str, **fields: Any) -> None:
        """Tell the other servers sharing the database, when ``connection``'s transaction commits, that this one
        changed ``kind`` ``key`` (app.storage.changes). Nothing on SQLite: no other server can share it."""
        if not self.shared:
            return
        payload = json.dumps({"kind": kind, "key": key, "origin": self.origin, **fields}, separators=(",", ":"))
        connection.execute(sa.select(sa.func.pg_notify(CHANGES_CHANNEL, payload)))

    @property
    def url(self) -> str:
        """The database's URL without its password (for logs and messages)."""
        return self.engine.url.render_as_string(hide_password=True)

    @contextmanager
    def transaction(self) -> Iterator[sa.Connection]:
        with self.engine.begin() as connection:
            yield connection

    def notify(self, kind: str, key: str, **fields: Any) -> None:
        """:meth:`announce` something nothing is written for (who a server's sockets hold), in a transaction of its
        own. Nothing on SQLite."""
        if self.shared:
            with self.transaction() as connection:
                self.announce(connection, kind, key, **fields)

    def kept_value(self, name: str, make: Callable[[], str]) -> str:
        """The server value ``name``; made by ``make`` and kept the first time it is asked for."""
        with self.transaction() as connection:
            found = connection.execute(sa.select(server_values.c.value).where(server_values.c.name == name)).scalar()
            if found is not None:
                return str(found)
            value = make()
            connection.execute(sa.insert(server_values).values(name=name, value=value, updated_at=datetime.now(UTC)))
            return value

    def set_value(self, name: str, value: str) -> None:
        """Keep ``value`` as the server value ``name`` (replacing any)."""
        with self.transaction() as connection:
            connection.execute(sa.delete(server_values).where(server_values.c.name == name))
            connection.execute(sa.insert(server_values).values(name=name, value=value, updated_at=datetime.now(UTC)))

    def schema_revision(self) -> str | None:
        """The Alembic revision the database's schema is at (None for an empty database)."""
        with self.engine.connect() as connection:
            return MigrationContext.configure(connection).get_current_revision()


def _alembic_config(connection: sa.Connection) -> Config:
    config = Config()
    config.set_main_option("script_location", str(MIGRATIONS_DIR))
    config.attributes["connection"] = connection
    return config


def head_revision() -> str:
    """The newest schema revision this code knows."""
    head = ScriptDirectory.from_config(_alembic_config(None)).get_current_head()  # type: ignore[arg-type]
    assert head is not None
    return head


def migrate(database: Database, *, to: str = "head") -> None:
    """Bring the schema forward to ``to`` (forward only: this code never downgrades a database). A database newer
    than this code (a later version ran on it) is refused rather than touched."""
    known = ScriptDirectory.from_config(_alembic_config(None))  # type: ignore[arg-type]
    current = database.schema_revision()
    if current is not None and current not in {script.revision for script in known.walk_revisions()}:
        raise DatabaseUnusable(
            f"the database at {database.url} has schema revision {current!r}, newer than this version of Dynamics Lab "
            "knows: run the newer version, or give another --data-dir"
        )
    logging.getLogger("alembic").setLevel(logging.WARNING)  # its step-by-step notes; ours below says what changed
    with database.engine.begin() as connection:
        if database.shared:  # another server starting now waits here, then finds the schema current
            connection.execute(sa.text(f"SET LOCAL lock_timeout = {MIGRATION_LOCK_TIMEOUT_MS}"))
            connection.execute(sa.select(sa.func.pg_advisory_xact_lock(MIGRATION_LOCK)))
        command.upgrade(_alembic_config(connection), to)
    now = database.schema_revision()
    if now != current:
        log.info("database %s: schema %s → %s", database.url, current or "empty", now)


def postgresql_connect_args() -> dict[str, Any]:
    """Every PostgreSQL connection's bounds: a wait for a lock (another server's turn at a room) ends after
    :data:`PG_LOCK_TIMEOUT_MS` (the change answers 503, try again) instead of holding a request, and so a thread, for
    as long as that server is stuck; a server frozen inside a transaction loses it after
    :data:`PG_IDLE_IN_TRANSACTION_MS`; TCP keepalives find a dead link in about half a minute; connecting gives up
    after 5 s."""
    return {
        "options": (
            f"-c lock_timeout={PG_LOCK_TIMEOUT_MS} -c idle_in_transaction_session_timeout={PG_IDLE_IN_TRANSACTION_MS}"
        ),
        "connect_timeout": 5,
        "keepalives": 1,
        "keepalives_idle": 10,
        "keepalives_interval": 5,
        "keepalives_count": 3,
    }


def open_database(url: str, *, migrate_to: str = "head") -> Database:
    """The database at ``url``, its schema brought up to date; :class:`DatabaseUnusable` saying why not."""
    try:
        postgresql = sa.engine.make_url(url).get_backend_name() == "postgresql"
        engine = sa.create_engine(url, connect_args=postgresql_connect_args() if postgresql else {})
        if engine.dialect.name == "sqlite":
            sa.event.listen(engine, "connect", _on_sqlite_connect)
        database = Database(engine)
        migrate(database, to=migrate_to)
    except (SQLAlchemyError, OSError) as exc:
        shown = sa.engine.make_url(url).render_as_string(hide_password=True)
        raise DatabaseUnusable(f"the database at {shown} cannot be used: {str(exc).splitlines()[0]}") from exc
    except ImportError as exc:  # a database whose driver is not installed (PostgreSQL's is in the `postgres` group)
        raise DatabaseUnusable(
            f"no driver for {sa.engine.make_url(url).drivername}: {exc.name} is not installed (for PostgreSQL: "
            "python3 -m uv run --group postgres dynlab serve)"
        ) from exc
    return database


class StoreUnavailable(RuntimeError):
    """The database did not take a write (locked by another process past its timeout, a full disk, a lost
    connection): answered 503 with ``Retry-After``."""

    retry_after_s = 2


class DataDirInUse(RuntimeError):
    """Another ``dynlab serve`` keeps its class's data in this data directory."""


class DataDirLock:
    """The data directory held by one ``dynlab serve`` (an exclusive ``flock`` on ``serve.lock`` in it, released when
    the process ends however it ends): two servers writing one SQLite file would each serve rooms the other changes."""

    def __init__(self, data_dir: Path) -> None:
        import fcntl

        try:
            data_dir.mkdir(parents=True, exist_ok=True, mode=0o700)
        except (FileExistsError, NotADirectoryError):
            raise DatabaseUnusable(f"the data directory {data_dir} is a file, not a directory") from None
        self._file = (data_dir / "serve.lock").open("a+")
        try:
            fcntl.flock(self._file, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            self._file.seek(0)
            holder = self._file.read().strip() or "another process"
            self._file.close()
            raise DataDirInUse(
                f"another dynlab serve ({holder}) keeps its data in {data_dir}: stop it, or give this one another "
                "--data-dir"
            ) from None
        self._file.seek(0)
        self._file.truncate()
        self._file.write(f"pid {os.getpid()}")
        self._file.flush()

    def release(self) -> None:
        import fcntl

        fcntl.flock(self._file, fcntl.LOCK_UN)
        self._file.close()
