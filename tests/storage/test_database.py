"""The database a class's data is kept in: its schema comes only from the migrations, which agree with the tables the
code uses, step by step; a database from a newer version is refused untouched; SQLite runs in WAL mode."""

from __future__ import annotations

import pytest
import sqlalchemy as sa
from alembic.autogenerate import compare_metadata
from alembic.runtime.migration import MigrationContext
from alembic.script import ScriptDirectory

from app.storage import open_database
from app.storage.database import MIGRATIONS_DIR, head_revision, migrate, sqlite_url
from app.storage.tables import metadata, server_values


def revisions_oldest_first() -> list[str]:
    from alembic.config import Config

    config = Config()
    config.set_main_option("script_location", str(MIGRATIONS_DIR))
    return [script.revision for script in reversed(list(ScriptDirectory.from_config(config).walk_revisions()))]


def schema_differences(database) -> list:
    with database.engine.connect() as connection:
        return compare_metadata(MigrationContext.configure(connection), metadata)


def test_an_empty_database_migrates_to_exactly_the_schema_the_code_uses(tmp_path):
    database = open_database(sqlite_url(tmp_path / "data"))
    assert database.schema_revision() == head_revision()
    assert schema_differences(database) == []
    assert (tmp_path / "data").stat().st_mode & 0o777 == 0o700  # the data directory is its owner's alone
    shared = tmp_path / "volume"  # a directory others may read (a container's volume): the files are still owner-only
    shared.mkdir(mode=0o755)
    open_database(sqlite_url(shared)).set_value("instructor_secret", "not for others")
    assert {path.name: path.stat().st_mode & 0o777 for path in shared.iterdir()} == {
        name: 0o600 for name in ("dynlab.sqlite3", "dynlab.sqlite3-wal", "dynlab.sqlite3-shm")
    }


def test_each_version_migrates_forward_to_the_next_keeping_what_was_kept(tmp_path):
    """From each earlier version's database (its schema and a kept value), one step at a time, to the newest."""
    revisions = revisions_oldest_first()
    assert revisions[-1] == head_revision()
    database = open_database(sqlite_url(tmp_path / "data"), migrate_to=revisions[0])
    database.set_value("instructor_secret", "kept-since-the-first-version")
    for revision in revisions[1:]:
        migrate(database, to=revision)
        assert database.schema_revision() == revision
    assert schema_differences(database) == []
    assert database.kept_value("instructor_secret", lambda: "new") == "kept-since-the-first-version"
    again = open_database(sqlite_url(tmp_path / "data"))  # a restart: nothing to do, nothing lost
    assert again.schema_revision() == head_revision()
    assert again.kept_value("instructor_secret", lambda: "new") == "kept-since-the-first-version"


def test_a_database_from_a_newer_version_is_refused_and_left_as_it_was(tmp_path):
    url = sqlite_url(tmp_path / "data")
    database = open_database(url)
    with database.transaction() as connection:
        connection.execute(sa.text("UPDATE alembic_version SET version_num = '9999'"))
    with pytest.raises(RuntimeError, match="newer than this version"):
        open_database(url)
    with database.engine.connect() as connection:
        assert connection.execute(sa.text("SELECT version_num FROM alembic_version")).scalar() == "9999"


def test_sqlite_writes_ahead_and_enforces_foreign_keys(tmp_path):
    database = open_database(sqlite_url(tmp_path / "data"))
    with database.engine.connect() as connection:
        assert connection.execute(sa.text("PRAGMA journal_mode")).scalar() == "wal"
        assert connection.execute(sa.text("PRAGMA foreign_keys")).scalar() == 1


def test_a_value_is_made_once_and_a_failed_write_keeps_nothing(tmp_path):
    database = open_database(sqlite_url(tmp_path / "data"))
    made = []
    assert database.kept_value("a", lambda: made.append(1) or "first") == "first"
    assert database.kept_value("a", lambda: made.append(1) or "second") == "first"
    assert made == [1]
    with pytest.raises(RuntimeError), database.transaction() as connection:
        connection.execute(sa.update(server_values).values(value="half-written"))
        raise RuntimeError("a crash between two writes of one transaction")
    assert database.kept_value("a", lambda: "third") == "first"


def test_a_room_kept_before_rooms_had_versions_loads_and_is_written_at_version_0(tmp_path):
    """A room written by the version before 0003 (no version column) comes back at version 0 and is written on."""
    import json as json_module
    from datetime import UTC, datetime

    import sqlalchemy as sa

    from app.classroom.room import Room
    from app.classroom.store import SqlRoomStore

    database = open_database(sqlite_url(tmp_path / "data"), migrate_to="0002")
    record = Room(room_id="a" * 16, code="ABCDEF", join_url="http://lab.example:8000/join/ABCDEF").record()
    with database.transaction() as connection:
        connection.execute(
            sa.text("INSERT INTO rooms (room_id, code, created_at, used_at, record) VALUES (:i, :c, :t, :t, :r)"),
            {"i": "a" * 16, "c": "ABCDEF", "t": datetime.now(UTC), "r": json_module.dumps(record)},
        )
    migrate(database, to=head_revision())
    (room,) = SqlRoomStore(database).load()
    assert room.kept_version == 0 and room.code == "ABCDEF"
    room.join("Ada", device="device-of-ada")
    (again,) = SqlRoomStore(open_database(sqlite_url(tmp_path / "data"))).load()
    assert again.kept_version == 1 and [s["name"] for s in again.student_list()] == ["Ada"]
