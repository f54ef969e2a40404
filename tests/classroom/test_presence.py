"""One class on several servers counts every student where they are connected (app.classroom.room.Room presence):
another server's word on who its sockets hold adds to this server's own, until it lapses (that server died or
stopped saying), and a malformed word is ignored."""

from __future__ import annotations

import time

from app.classroom.room import PRESENCE_HOLDS_S, Room


def test_students_connected_on_another_server_count_here_until_its_word_lapses():
    room = Room(room_id="0" * 16, code="ABCDEF", join_url="http://lab.example:8000/join/ABCDEF")
    ada, ben, cy = (room.join(name, device=f"device-of-{name}") for name in ("Ada", "Ben", "Cy"))
    ada.sockets = 1  # Ada's page is on this server
    room.take_presence("server-b", {"connected": [2, 3, 99], "following": [2], "instructor_sockets": 1})
    state = room.state()
    assert state["students"] == {"joined": 3, "connected": 3, "following": 2}  # s99 is no student of this room
    assert state["instructor_connected"] is True
    listed = {s["student_id"]: (s["connected"], s["following"]) for s in room.student_list()}
    assert listed == {ada.student_id: (True, True), ben.student_id: (True, True), cy.student_id: (True, False)}
    assert (ben.student_id, cy.student_id) == ("s2", "s3")
    assert room.presence_here() == {"connected": [1], "following": [1], "instructor_sockets": 0}

    said = room.remote_presence["server-b"]
    room.remote_presence["server-b"] = type(said)(said.connected, said.following, said.instructor_sockets,
                                                  time.monotonic() - PRESENCE_HOLDS_S - 0.1)  # fmt: skip
    assert room.state()["students"] == {"joined": 3, "connected": 1, "following": 1}
    assert room.state()["instructor_connected"] is False and room.remote_presence == {}

    room.take_presence("server-c", {"connected": "everyone", "following": [], "instructor_sockets": 1})
    assert room.remote_presence == {}


def test_a_lecture_halls_presence_fits_one_postgresql_announcement():
    """PostgreSQL's NOTIFY takes at most 8000 bytes: the word on 500 students connected and following fits."""
    import json

    from app.classroom.room import MAX_STUDENTS

    room = Room(room_id="0" * 16, code="ABCDEF", join_url="http://lab.example:8000/join/ABCDEF")
    room._students_ever = 9000  # ids in the thousands, as in a room many have joined and left
    for index in range(MAX_STUDENTS):
        room.join(device=f"device-{index}").sockets = 1
    said = {"kind": "presence", "key": room.room_id, "origin": "0" * 12, **room.presence_here()}
    assert len(said["connected"]) == MAX_STUDENTS
    assert len(json.dumps(said, separators=(",", ":"))) < 8000
