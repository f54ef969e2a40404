"""Rooms kept in the database come back whole after a restart: state, students (known by their tokens' and devices'
digests, never the secrets), removals, polls with their answers and revealed results; the shared scene as it was. In
process, on a real SQLite database in a temporary data directory and the room's in-memory host of test_room.py."""

from __future__ import annotations

import json
import time
from datetime import UTC, datetime, timedelta

import pytest
import sqlalchemy as sa

from app.classroom.registry import NoPlaceHere, Rooms
from app.classroom.room import RoomAlreadyClosed, RoomChangedElsewhere, StudentRemoved, digest
from app.classroom.store import SqlRoomStore
from app.storage import open_database
from app.storage.database import StoreUnavailable, sqlite_url
from app.storage.tables import answers
from app.storage.tables import rooms as rooms_table
from tests.classroom.test_room import FRICTION_LESSON, BusyWhenTold


@pytest.fixture(scope="module")
def catalogue():
    from app.course import load_catalogue

    return load_catalogue()


def restarted(data_dir, *, join_base: str = "http://lab.example:8000") -> Rooms:
    """The rooms a new server run at ``join_base`` finds in ``data_dir``."""
    return Rooms(store=SqlRoomStore(open_database(sqlite_url(data_dir))), join_base=join_base)


def a_class(rooms: Rooms, catalogue, host) -> dict:
    """A room in use: a scene with changed parameters, paused, exploring; three students (one named, one removed);
    a revealed choice poll and an open number poll, with answers."""
    room, _ = rooms.create(join_base="http://lab.example:8000")
    room.change(
        {"lesson_id": FRICTION_LESSON, "scene_id": "sliding-bar-friction", "params": {"mu": 0.45}},
        catalogue=catalogue,
        host=host,
    )
    room.change({"playing": False, "time_scale": 0.5, "mode": "explore"}, catalogue=catalogue, host=host)
    ada = room.join("Ada", device="device-of-ada")
    ben = room.join("", device="device-of-ben")
    cy = room.join("Cy", device="device-of-cy")
    first = room.open_poll({"question": "Does it stick?", "kind": "choice", "choices": ["yes", "no"]})
    room.answer(first.poll_id, ada.token, {"choice": 0})
    room.answer(first.poll_id, ben.token, {"choice": 1})
    room.answer(first.poll_id, cy.token, {"choice": 1})
    room.update_poll(first.poll_id, {"show_names": True}, host=host)
    room.update_poll(first.poll_id, {"open": False}, host=host)
    second = room.open_poll({"question": "How far does it slide?", "kind": "number", "unit": "m"})
    room.answer(second.poll_id, ada.token, {"value": 1.25})
    room.answer(second.poll_id, ben.token, {"value": 0.75})
    room.answer(second.poll_id, ada.token, {"value": 1.5})  # changed while open: one answer, the last
    room.remove(cy.student_id)
    return {"room": room, "ada": ada, "ben": ben, "cy": cy, "polls": (first.poll_id, second.poll_id)}


def test_a_restart_brings_every_room_back_as_it_was(tmp_path, catalogue):
    host = BusyWhenTold()
    made = a_class(restarted(tmp_path), catalogue, host)
    before = made["room"]
    (after,) = restarted(tmp_path).all()

    state_before, state_after = before.state(), after.state()
    assert state_after["revision"] == state_before["revision"] + 1  # pages that knew the room take its state again
    for name in ("room_id", "code", "join_url", "lesson_id", "scene_id", "params", "playing", "time_scale", "mode",
                 "explore_start", "reset_count", "poll"):  # fmt: skip
        assert state_after[name] == state_before[name], name
    assert state_after["params"]["mu"] == 0.45 and state_after["playing"] is False and state_after["mode"] == "explore"
    assert after.student_list() == [dict(s, connected=False) for s in before.student_list()]
    assert [s["name"] for s in after.student_list()] == ["Ada", ""]
    for poll_id in made["polls"]:
        assert after.poll(poll_id).results() == before.poll(poll_id).results()
        assert after.poll(poll_id).to_csv() == before.poll(poll_id).to_csv()
    assert after.poll(made["polls"][1]).results()["answers"] == 2

    # Students come back as themselves: by the token their page kept, or by their device (a new token beside the old).
    assert after.student(made["ada"].token).student_id == made["ada"].student_id
    again = after.join("", device="device-of-ben")
    assert again.student_id == made["ben"].student_id and again.token not in (None, made["ben"].token)
    assert after.student(made["ben"].token) is after.student(again.token)
    # Whom the instructor removed stays removed.
    with pytest.raises(StudentRemoved):
        after.student(made["cy"].token)
    with pytest.raises(StudentRemoved):
        after.join("Cy", device="device-of-cy")


def test_changes_after_a_restart_are_kept_too_and_a_new_student_takes_a_new_number(tmp_path, catalogue):
    host = BusyWhenTold()
    made = a_class(restarted(tmp_path), catalogue, host)
    (room,) = restarted(tmp_path).all()
    room.answer(made["polls"][1], made["ben"].token, {"value": 2.0})
    newcomer = room.join("Dee", device="device-of-dee")
    assert newcomer.student_id == "s4"  # s3 was removed: its number is never given again
    room.change({"params": {"mu": 0.3}}, catalogue=catalogue, host=host)
    (again,) = restarted(tmp_path).all()
    assert again.state()["params"]["mu"] == 0.3
    assert [s["name"] for s in again.student_list()] == ["Ada", "", "Dee"]
    assert again.poll(made["polls"][1]).results()["answers"] == 2
    assert again.poll(made["polls"][1]).answer_of(made["ben"].student_id)["value"] == 2.0


def test_the_shared_scene_comes_back_with_its_parameters_and_play_state(tmp_path, catalogue):
    a_class(restarted(tmp_path), catalogue, BusyWhenTold())
    (room,) = restarted(tmp_path).all()
    host = BusyWhenTold()
    host.busy = {"open_stage"}  # a worker still starting: the room's next change opens it instead
    room.put_stage_back(host)
    assert host.stage is None
    host.busy = set()
    room.put_stage_back(host)
    assert host.stage is not None
    assert host.stage["scene_id"] == "sliding-bar-friction" and host.stage["params"]["mu"] == 0.45
    assert host.stage["playing"] is False and host.stage["time_scale"] == 0.5


def test_the_database_holds_no_token_or_device_id_and_a_closed_room_leaves_nothing(tmp_path, catalogue):
    rooms = restarted(tmp_path)
    made = a_class(rooms, catalogue, BusyWhenTold())
    database_bytes = b"".join(path.read_bytes() for path in (tmp_path).iterdir())
    for secret in (made["ada"].token, made["ben"].token, "device-of-ada", "device-of-ben"):
        assert secret.encode() not in database_bytes
    assert b"Ada" in database_bytes  # what the student chose to show is kept
    rooms.close(made["room"].room_id)
    assert restarted(tmp_path).all() == []
    with rooms.store.database.engine.connect() as connection:
        assert connection.execute(sa.select(sa.func.count()).select_from(answers)).scalar() == 0


def test_dynlab_rooms_lists_exports_and_deletes_a_kept_room(tmp_path, catalogue, capsys):
    from app import cli

    made = a_class(restarted(tmp_path / "data"), catalogue, BusyWhenTold())
    code = made["room"].code
    assert cli.main(["rooms", "--data-dir", str(tmp_path / "data")]) == 0
    listed = capsys.readouterr().out
    assert code in listed and "8-2-coulomb-friction" in listed
    assert [line.split()[3:6] for line in listed.splitlines() if line.startswith(code)] == [["2", "2", "4"]]

    out = tmp_path / "export"
    assert cli.main(["export", code.lower(), "--out", str(out), "--data-dir", str(tmp_path / "data")]) == 0
    document = json.loads((out / f"room-{code}.json").read_text())
    assert [s["name"] for s in document["students"]] == ["Ada", ""]
    assert document["params"]["mu"] == 0.45 and [p["results"]["answers"] for p in document["polls"]] == [2, 2]
    table = (out / f"room-{code}-answers.csv").read_text().splitlines()
    assert table[0].startswith("poll_id,question") and len(table) == 1 + 4
    assert "Ada" in table[1] or "Ada" in table[2]  # the first poll showed names
    written = (out / f"room-{code}.json").read_text() + "\n".join(table)
    for secret in (made["ada"].token, made["ben"].token, "device-of-ada"):
        assert secret not in written
    assert digest(made["ada"].token) not in written

    assert cli.main(["rooms", "delete", code, "--data-dir", str(tmp_path / "data")]) == 0
    assert restarted(tmp_path / "data").all() == []
    assert cli.main(["rooms", "delete", code, "--data-dir", str(tmp_path / "data")]) == 1


def test_a_room_unused_for_the_kept_days_is_forgotten_with_its_answers(tmp_path, catalogue):
    rooms = restarted(tmp_path)
    made = a_class(rooms, catalogue, BusyWhenTold())
    with rooms.store.database.transaction() as connection:
        connection.execute(sa.update(rooms_table).values(used_at=datetime.now(UTC) - timedelta(days=31)))
    assert len(Rooms(store=SqlRoomStore(open_database(sqlite_url(tmp_path))), keep_days=60).all()) == 1
    assert Rooms(store=SqlRoomStore(open_database(sqlite_url(tmp_path))), keep_days=30).all() == []
    with rooms.store.database.engine.connect() as connection:
        assert connection.execute(sa.select(sa.func.count()).select_from(answers)).scalar() == 0
    assert made["room"].code not in [r["code"] for r in rooms.store.listing()]


def test_a_kept_room_is_joined_at_the_servers_address_now_and_keeps_its_last_use(tmp_path, catalogue):
    """A laptop back on another network address projects a QR code that works; a room unused for a day before the
    restart is idle at once (it makes way for a new room), not as if just used."""
    made = a_class(restarted(tmp_path), catalogue, BusyWhenTold())
    (moved,) = restarted(tmp_path, join_base="http://10.0.0.9:8000").all()
    assert moved.state()["join_url"] == f"http://10.0.0.9:8000/join/{made['room'].code}"
    store = SqlRoomStore(open_database(sqlite_url(tmp_path)))
    with store.database.transaction() as connection:
        connection.execute(sa.update(rooms_table).values(used_at=datetime.now(UTC) - timedelta(days=1)))
    rooms = Rooms(store=store, max_rooms=1)
    (idle,) = rooms.all()
    assert 23 * 3600 < time.monotonic() - idle.last_used_s < 25 * 3600
    fresh, made_way = rooms.create(join_base="http://10.0.0.9:8000")
    assert made_way == [idle] and [r.room_id for r in rooms.all()] == [fresh.room_id]
    assert {r["code"] for r in store.listing()} == {idle.code, fresh.code}  # made way, still kept


def test_a_change_racing_the_closing_of_its_room_is_refused_and_the_room_stays_forgotten(tmp_path, catalogue):
    rooms = restarted(tmp_path)
    made = a_class(rooms, catalogue, BusyWhenTold())
    room = made["room"]
    rooms.close(room.room_id)
    with pytest.raises(RoomAlreadyClosed):
        room.change({"params": {"mu": 0.2}}, catalogue=catalogue, host=BusyWhenTold())
    room.answer(made["polls"][1], made["ada"].token, {"value": 3.0})  # a late answer: harmless, and not kept
    with pytest.raises(RoomAlreadyClosed):  # a join racing the closing is told the room is closed (409)
        room.join("Late", device="device-late")
    assert restarted(tmp_path).all() == [] and rooms.store.listing() == []


def test_a_write_the_database_refuses_is_kept_by_the_rooms_next_write(tmp_path, catalogue):
    rooms = restarted(tmp_path)
    made = a_class(rooms, catalogue, BusyWhenTold())
    room, store = made["room"], rooms.store
    real_save, real_answer = store.save, store.save_answer

    def refuse(*args, **kwargs):
        raise StoreUnavailable("the database is locked")

    store.save, store.save_answer = refuse, refuse  # a disk full, a lock held past its timeout
    room.answer(made["polls"][1], made["ben"].token, {"value": 9.0})
    room.remove(made["ben"].student_id)
    store.save, store.save_answer = real_save, real_answer
    room.answer(made["polls"][1], made["ada"].token, {"value": 4.0})  # an answer alone does not rewrite the room
    room.join("Dee", device="device-of-dee")  # the room's next write
    (after,) = restarted(tmp_path).all()
    assert [s["name"] for s in after.student_list()] == ["Ada", "Dee"]
    with pytest.raises(StudentRemoved):
        after.student(made["ben"].token)
    assert after.poll(made["polls"][1]).results()["answers"] == 1  # Ada's; Ben's left with him


def test_a_room_kept_by_another_server_or_made_way_for_is_taken_up_when_asked(tmp_path, catalogue):
    """Two servers sharing one database (as behind a balancer with PostgreSQL): a room the first keeps opens on the
    second when its class is sent there (by id, or by its code from the join page), whole; and a room that made way
    for others on a full server opens again when asked, if there is a place."""
    here = restarted(tmp_path)
    there = restarted(tmp_path)  # started before the room existed
    made = a_class(here, catalogue, BusyWhenTold())
    room = made["room"]
    taken = there.get(room.room_id)
    assert there.by_code(room.code.lower()) is taken
    assert taken.student_list() == [dict(s, connected=False) for s in room.student_list()]
    assert taken.poll(made["polls"][0]).results() == room.poll(made["polls"][0]).results()
    assert taken.student(made["ada"].token).student_id == made["ada"].student_id
    with pytest.raises(KeyError):
        there.get("0" * 16)
    with pytest.raises(KeyError):
        there.by_code("NOSUCH")

    full = Rooms(store=SqlRoomStore(open_database(sqlite_url(tmp_path / "full"))), max_rooms=1)
    first, _ = full.create(join_base="http://127.0.0.1:8000")
    first.last_used_s -= 7 * 3600  # idle: it makes way
    second, made_way = full.create(join_base="http://127.0.0.1:8000")
    assert made_way == [first]
    with pytest.raises(NoPlaceHere, match="no place for room"):  # 503, try again: not "no such room"
        full.get(first.room_id)
    second.last_used_s -= 7 * 3600
    assert full.get(first.room_id).code == first.code


def test_a_closed_room_is_never_taken_up_or_written_back_even_if_its_deletion_failed(tmp_path, catalogue):
    rooms = restarted(tmp_path)
    made = a_class(rooms, catalogue, BusyWhenTold())
    room, store = made["room"], rooms.store
    real_delete = store.delete

    def refuse(room_id):
        raise StoreUnavailable("the database is locked")

    store.delete = refuse
    assert rooms.close(room.room_id) is room  # closed here all the same; the failure is logged
    store.delete = real_delete
    with pytest.raises(KeyError):
        rooms.get(room.room_id)  # the database still holds it: not taken up again in this run
    with pytest.raises(KeyError):
        rooms.by_code(room.code)
    store.delete(room.room_id)
    with pytest.raises(RoomChangedElsewhere):  # a save racing the deletion adds nothing (only insert adds a room)
        store.save(room)
    assert store.listing() == []
