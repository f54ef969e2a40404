"""The same code on PostgreSQL (``DYNLAB_DATABASE_URL``), as several servers of one class would share it: the
migrations give exactly the schema the code uses; a room with students, a removed student, polls and answers
round-trips, and is taken up whole by a second registry on the same database; a claimed page session is claimed for
a second directory too; a newer schema is refused untouched. On a throwaway cluster (tests/storage/postgres.py)."""

from __future__ import annotations

import pytest
import sqlalchemy as sa

from app.api.access import Refused, SessionDirectory
from app.api.kept_sessions import SqlSessionStore
from app.classroom.registry import Rooms
from app.classroom.room import StudentRemoved
from app.classroom.store import SqlRoomStore
from app.storage import open_database
from app.storage.database import DatabaseUnusable, head_revision
from tests.classroom.test_room import BusyWhenTold
from tests.classroom.test_room_store import a_class
from tests.storage.postgres import postgres_server
from tests.storage.test_database import schema_differences


@pytest.fixture(scope="module")
def url():
    with postgres_server() as url:
        yield url


@pytest.fixture(scope="module")
def catalogue():
    from app.course import load_catalogue

    return load_catalogue()


def test_the_migrations_give_postgresql_the_schema_the_code_uses(url):
    database = open_database(url)
    assert database.engine.dialect.name == "postgresql"
    assert database.schema_revision() == head_revision() and schema_differences(database) == []
    assert open_database(url).kept_value("instructor_secret", lambda: "made-once") == "made-once"
    assert open_database(url).kept_value("instructor_secret", lambda: "made-twice") == "made-once"


def test_a_class_round_trips_and_a_second_server_takes_it_up(url, catalogue):
    here = Rooms(store=SqlRoomStore(open_database(url)), join_base="http://lab.example:8000")
    there = Rooms(store=SqlRoomStore(open_database(url)), join_base="http://lab.example:8000")
    made = a_class(here, catalogue, BusyWhenTold())
    room = made["room"]
    taken = there.get(room.room_id)
    assert taken.state()["params"] == room.state()["params"] and taken.state()["playing"] is False
    assert taken.student_list() == [dict(s, connected=False) for s in room.student_list()]
    for poll_id in made["polls"]:
        assert taken.poll(poll_id).results() == room.poll(poll_id).results()
        assert taken.poll(poll_id).to_csv() == room.poll(poll_id).to_csv()
    assert taken.student(made["ada"].token).student_id == made["ada"].student_id
    with pytest.raises(StudentRemoved):
        taken.student(made["cy"].token)
    here.close(room.room_id)
    assert Rooms(store=SqlRoomStore(open_database(url))).all() == []


def test_a_claim_made_on_one_server_holds_on_another(url):
    reopened: list = []
    there = SessionDirectory(store=SqlSessionStore(open_database(url)), reopen=lambda *args: reopened.append(args))
    here = SessionDirectory(store=SqlSessionStore(open_database(url)))
    here.changed("s" * 32, "heavy-top", "a-page-key-0123456789", client="10.0.0.7", params={"spin_rad_s": 66.0})
    with pytest.raises(Refused):
        there.check_change("s" * 32, None, client="10.0.0.9")
    there.reopen_kept("s" * 32)
    assert reopened == [("s" * 32, "heavy-top", {"spin_rad_s": 66.0})]


def test_a_newer_schema_on_postgresql_is_refused_untouched(url):
    database = open_database(url)
    with database.transaction() as connection:
        connection.execute(sa.text("UPDATE alembic_version SET version_num = '9999'"))
    try:
        with pytest.raises(DatabaseUnusable, match="newer than this version"):
            open_database(url)
    finally:
        with database.transaction() as connection:
            connection.execute(sa.text(f"UPDATE alembic_version SET version_num = '{head_revision()}'"))
