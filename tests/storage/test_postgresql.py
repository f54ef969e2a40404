"""The same code on PostgreSQL (``DYNLAB_DATABASE_URL``), as several servers of one class would share it: the
migrations give exactly the schema the code uses; a room with students, a removed student, polls and answers
round-trips, and is taken up whole by a second registry on the same database; a claimed page session is claimed for
a second directory too; a newer schema is refused untouched. Two servers changing one room keep both changes, and each
hears of the other's as it commits (LISTEN/NOTIFY). On a throwaway cluster (app/bench/loopback_postgres.py)."""

from __future__ import annotations

import pytest
import sqlalchemy as sa

from app.api.access import Refused, SessionDirectory
from app.api.kept_sessions import SqlSessionStore
from app.classroom.registry import Rooms
from app.classroom.room import RoomAlreadyClosed, StudentRemoved
from app.classroom.store import SqlRoomStore
from app.storage import open_database
from app.storage.database import DatabaseUnusable, head_revision
from app.storage.changes import Change, ChangeListener
from tests.classroom.test_room import FRICTION_LESSON, BusyWhenTold
from tests.conftest import wait_until
from tests.classroom.test_room_store import a_class
from app.bench.loopback_postgres import postgres_server
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
    with pytest.raises(KeyError):  # no room; never a question PostgreSQL refuses (its text cannot hold NUL)
        there.by_code("\x00" * 6)
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


def test_two_servers_changing_one_room_keep_both_changes(url, catalogue):
    """Server B holds an older version of the room when it writes: its write is refused, it takes A's version up
    (its stage follows A's parameters) and its change runs again on it."""
    here = Rooms(store=SqlRoomStore(open_database(url)))
    there = Rooms(store=SqlRoomStore(open_database(url)))
    host_here, host_there = BusyWhenTold(), BusyWhenTold()
    room, _ = here.create(join_base="http://lab.example:8000")
    room.change({"lesson_id": FRICTION_LESSON, "scene_id": "sliding-bar-friction"}, catalogue=catalogue, host=host_here)
    same = there.get(room.room_id)
    same.change({"playing": False}, catalogue=catalogue, host=host_there)  # B opens its stage: now B is current
    room.change({"params": {"mu": 0.6}}, catalogue=catalogue, host=host_here)  # over B's version: A takes it up first
    assert room.state()["playing"] is False and room.state()["params"]["mu"] == 0.6
    ada = same.join("Ada", device="device-of-ada")  # B is behind A now: its join runs again on A's version
    assert same.state()["params"]["mu"] == 0.6 and host_there.stage["params"]["mu"] == 0.3
    same.follow_stage(host_there)  # as B's sync does when A's announcement arrives
    assert host_there.stage["params"]["mu"] == 0.6 and host_there.stage["playing"] is False
    kept = Rooms(store=SqlRoomStore(open_database(url))).get(room.room_id)
    assert kept.state()["params"]["mu"] == 0.6 and kept.state()["playing"] is False
    assert kept.student(ada.token).name == "Ada"
    here.close(room.room_id)


def test_each_server_hears_of_the_others_changes_as_they_commit(url, catalogue):
    heard: list[Change] = []
    missed: list[bool] = []
    listening_database = open_database(url)
    listener = ChangeListener(listening_database, on_change=heard.append, on_missed=lambda: missed.append(True))
    listener.start()
    try:
        assert listener.listening.wait(10) and missed == [True]
        here = Rooms(store=SqlRoomStore(open_database(url)))
        room, _ = here.create(join_base="http://lab.example:8000")
        room.change({"lesson_id": FRICTION_LESSON}, catalogue=catalogue, host=BusyWhenTold())
        ada = room.join("Ada", device="device-of-ada")
        poll = room.open_poll({"question": "Does it stick?", "kind": "choice", "choices": ["yes", "no"]})
        room.answer(poll.poll_id, ada.token, {"choice": 0})
        here.close(room.room_id)
        wait_until(lambda: len(heard) >= 5, timeout_s=10, what="five changes heard")
        assert [(c.kind, c.key) for c in heard] == [("room", room.room_id)] * 3 + [
            ("answer", room.room_id),
            ("room_closed", room.room_id),
        ]
        assert [c.fields["version"] for c in heard[:3]] == [1, 2, 3]
        assert heard[3].fields == {"poll_id": poll.poll_id, "student_id": ada.student_id}
        # Its own changes are not handed back to a server.
        Rooms(store=SqlRoomStore(listening_database)).create(join_base="http://lab.example:8000")[0].join("x")
        other = Rooms(store=SqlRoomStore(open_database(url))).create(join_base="http://lab.example:8000")[0]
        other.join("y")
        wait_until(lambda: len(heard) >= 6, timeout_s=10, what="the other server's join heard")
        assert [c.key for c in heard[5:]] == [other.room_id]
    finally:
        listener.stop()


def test_a_session_changed_on_another_server_follows_there_and_here(url):
    """A page session open on two servers (a balancer moved its page): the change made on one reaches the other's
    scene (its reopen, the scene host's set_params) and its claim; one forgotten there is forgotten here."""
    applied: list = []
    closed: list = []
    here = SessionDirectory(store=SqlSessionStore(open_database(url)), reopen=lambda *args: applied.append(args),
                            close=closed.append)  # fmt: skip
    there = SessionDirectory(store=SqlSessionStore(open_database(url)))
    session_id = "m" * 32
    here.changed(session_id, "heavy-top", None, client="10.0.0.7", params={"spin_rad_s": 60.0})
    there.changed(session_id, "heavy-top", "a-page-key-0123456789", client="10.0.0.8", params={"spin_rad_s": 72.0})
    here.changed_elsewhere(session_id)
    assert applied == [(session_id, "heavy-top", {"spin_rad_s": 72.0})]
    with pytest.raises(Refused):  # the claim made there holds here now
        here.check_change(session_id, None, client="10.0.0.7")
    SqlSessionStore(open_database(url)).delete(session_id)
    here.changed_elsewhere(session_id)
    assert closed == [session_id] and not here.is_claimed(session_id)


def test_a_change_to_a_room_another_server_closed_is_refused_as_closed(url, catalogue):
    here = Rooms(store=SqlRoomStore(open_database(url)))
    there = Rooms(store=SqlRoomStore(open_database(url)))
    room, _ = here.create(join_base="http://lab.example:8000")
    there.get(room.room_id)
    there.close(room.room_id)
    with pytest.raises(RoomAlreadyClosed):  # answered 409 by the app's RoomError handler, never a 500
        room.open_poll({"question": "Still there?", "kind": "choice", "choices": ["yes", "no"]})


def test_a_class_joining_at_once_on_two_servers_all_get_in_as_distinct_students(url, catalogue):
    """80 joins at once, half on each server, while the instructor changes the room on one (once a change and a poll
    in one turn), then 80 answers: each change of the room takes its turn (the row's lock), so none is refused or lost,
    nothing deadlocks, and no two students share an id."""
    from concurrent.futures import ThreadPoolExecutor

    here = Rooms(store=SqlRoomStore(open_database(url)))
    there = Rooms(store=SqlRoomStore(open_database(url)))
    host = BusyWhenTold()
    room, _ = here.create(join_base="http://lab.example:8000")
    room.change({"lesson_id": FRICTION_LESSON, "scene_id": "sliding-bar-friction"}, catalogue=catalogue, host=host)
    copies = (room, there.get(room.room_id))

    def join(index: int):
        return copies[index % 2].join(f"student {index}", device=f"device-{index}")

    def change(index: int):
        return room.change({"params": {"mu": 0.1 + 0.01 * index}}, catalogue=catalogue, host=host)

    poll = room.open_poll({"question": "Does it stick?", "kind": "choice", "choices": ["yes", "no"]})

    def answer(student) -> None:
        copies[int(student.student_id[1:]) % 2].answer(poll.poll_id, student.token, {"choice": 1})

    def question_on_a_new_scene() -> None:  # the poll route: a change and a poll in one turn (no deadlock with others)
        with room.turn(), room.lock:
            change(99)
            room.update_poll(poll.poll_id, {"show_names": True}, host=host)

    with ThreadPoolExecutor(max_workers=16) as pool:
        joins = [pool.submit(join, i) for i in range(80)]
        changes = [pool.submit(change, i) for i in range(10)] + [pool.submit(question_on_a_new_scene)]
        joined = [future.result(timeout=60) for future in joins]
        answers = [pool.submit(answer, student) for student in joined]
        [future.result(timeout=60) for future in changes + answers]
    assert len({s.student_id for s in joined}) == 80
    kept = Rooms(store=SqlRoomStore(open_database(url))).get(room.room_id)
    assert kept.state()["students"]["joined"] == 80
    assert all(kept.student(s.token).student_id == s.student_id for s in joined)
    assert kept.poll(poll.poll_id).results()["answers"] == 80 and kept.poll(poll.poll_id).show_names
    here.close(room.room_id)


def test_while_the_shared_database_is_down_changes_are_refused_not_kept_only_here(url, catalogue):
    """A server that cannot reach the database several servers share refuses every change (503, Retry-After): one
    kept only in its memory would be undone when the others' version is read again. Its earlier state stands."""
    from app.storage.database import Database, StoreUnavailable

    here = Rooms(store=SqlRoomStore(open_database(url)))
    host = BusyWhenTold()
    room, _ = here.create(join_base="http://lab.example:8000")
    room.change({"lesson_id": FRICTION_LESSON, "scene_id": "sliding-bar-friction", "params": {"mu": 0.3}},
                catalogue=catalogue, host=host)  # fmt: skip
    ada = room.join("Ada", device="device-of-ada")
    poll = room.open_poll({"question": "Does it stick?", "kind": "choice", "choices": ["yes", "no"]})
    room.answer(poll.poll_id, ada.token, {"choice": 0})
    store = room.store
    reachable = store.database
    store.database = Database(sa.create_engine("postgresql+psycopg://dynlab@127.0.0.1:1/dynlab"))  # down
    try:
        with pytest.raises(StoreUnavailable):
            room.change({"params": {"mu": 0.9}}, catalogue=catalogue, host=host)
        with pytest.raises(StoreUnavailable):
            room.join("Ben", device="device-of-ben")
        with pytest.raises(StoreUnavailable):
            room.answer(poll.poll_id, ada.token, {"choice": 1})
        state = room.state()
        assert state["params"]["mu"] == 0.3 and state["students"]["joined"] == 1
        assert room.poll(poll.poll_id).answer_of(ada.student_id)["choice"] == 0  # her earlier answer stands
    finally:
        store.database = reachable
    room.change({"params": {"mu": 0.9}}, catalogue=catalogue, host=host)  # back: the same change goes through
    assert Rooms(store=SqlRoomStore(open_database(url))).get(room.room_id).state()["params"]["mu"] == 0.9
    here.close(room.room_id)


def test_a_turn_held_elsewhere_lets_answers_through_bounds_other_changes_and_closing_waits_for_it(url, catalogue):
    """Server A holds the room's turn (a change under way, or a server frozen in it). On server B an answer goes
    through at once (its row refers to the room's; the turn does not hold it); a change waits at most the lock timeout
    and is refused (503, nothing changed) instead of holding its request; closing the room waits for A's change, then
    closes it. Nothing deadlocks."""
    import threading
    import time as clock
    from concurrent.futures import ThreadPoolExecutor

    from app.classroom.room import TURN_WAIT_S
    from app.storage.database import PG_LOCK_TIMEOUT_MS, StoreUnavailable

    here = Rooms(store=SqlRoomStore(open_database(url)))
    there = Rooms(store=SqlRoomStore(open_database(url)))
    host = BusyWhenTold()
    room, _ = here.create(join_base="http://lab.example:8000")
    room.change({"lesson_id": FRICTION_LESSON, "scene_id": "sliding-bar-friction"}, catalogue=catalogue, host=host)
    ada = room.join("Ada", device="device-of-ada")
    poll = room.open_poll({"question": "Does it stick?", "kind": "choice", "choices": ["yes", "no"]})
    other = there.get(room.room_id)
    holding, release = threading.Event(), threading.Event()

    def hold_the_turn() -> None:
        def work() -> None:
            holding.set()
            assert release.wait(30)
            room.params = {**room.params, "mu": 0.77}
            room.revision += 1
            room._keep()

        room._changing(work, host=host)

    with ThreadPoolExecutor(max_workers=4) as pool:
        held = pool.submit(hold_the_turn)
        assert holding.wait(30)
        pool.submit(other.answer, poll.poll_id, ada.token, {"choice": 1}).result(timeout=10)  # not held back
        started = clock.monotonic()
        with pytest.raises(StoreUnavailable):
            other.change({"params": {"mu": 0.11}}, catalogue=catalogue, host=BusyWhenTold())
        assert clock.monotonic() - started < PG_LOCK_TIMEOUT_MS / 1000 + 5
        assert other.state()["params"].get("mu") != 0.11  # refused: nothing changed
        started = clock.monotonic()
        with pytest.raises(StoreUnavailable, match="busy"):  # queued behind the held turn on the same server
            room.change({"params": {"mu": 0.22}}, catalogue=catalogue, host=host)
        assert clock.monotonic() - started < TURN_WAIT_S + 5
        closing = pool.submit(there.close, room.room_id)
        release.set()
        held.result(timeout=30)
        closing.result(timeout=30)
    assert room.room_id not in {r["room_id"] for r in SqlRoomStore(open_database(url)).listing()}


def test_a_join_on_a_server_that_does_not_serve_the_room_does_not_open_it_there(url):
    """The balancer sends joins (a code in the body) to any server: the room is read for the join only, so a class
    joining through two servers does not fill both with every room. An answer racing the room's closing is told the
    room is closed (409), not that the database failed."""
    here = Rooms(store=SqlRoomStore(open_database(url)))
    there = Rooms(store=SqlRoomStore(open_database(url)), open_kept=False)  # as a server sharing the database
    room, _ = here.create(join_base="http://lab.example:8000")
    poll = room.open_poll({"question": "Does it stick?", "kind": "choice", "choices": ["yes", "no"]})
    read = there.by_code(room.code.lower(), open_here=False)
    assert there.by_code(room.code, open_here=False) is read  # one copy: a class's joins take their turns in order
    ada = read.join("Ada", device="device-of-ada")
    assert there.all() == [] and room.student(ada.token).name == "Ada"  # here reads the join it did not make
    here.close(room.room_id)  # (the other server's listener is not running here: its copy learns as it writes)
    with pytest.raises(RoomAlreadyClosed):
        read.answer(poll.poll_id, ada.token, {"choice": 0})
    with pytest.raises(RoomAlreadyClosed):
        read.join("Ben", device="device-of-ben")
    with pytest.raises(KeyError):
        there.by_code(room.code, open_here=False)
