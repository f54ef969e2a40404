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
    room.take_presence("server-b", {"connected": [ben.student_id, cy.student_id, "s99"],
                                    "following": [ben.student_id], "instructor_sockets": 1})  # fmt: skip
    state = room.state()
    assert state["students"] == {"joined": 3, "connected": 3, "following": 2}  # s99 is no student of this room
    assert state["instructor_connected"] is True
    listed = {s["student_id"]: (s["connected"], s["following"]) for s in room.student_list()}
    assert listed == {ada.student_id: (True, True), ben.student_id: (True, True), cy.student_id: (True, False)}
    assert room.presence_here() == {"connected": [ada.student_id], "following": [ada.student_id],
                                    "instructor_sockets": 0}  # fmt: skip

    said = room.remote_presence["server-b"]
    room.remote_presence["server-b"] = type(said)(said.connected, said.following, said.instructor_sockets,
                                                  time.monotonic() - PRESENCE_HOLDS_S - 0.1)  # fmt: skip
    assert room.state()["students"] == {"joined": 3, "connected": 1, "following": 1}
    assert room.state()["instructor_connected"] is False and room.remote_presence == {}

    room.take_presence("server-c", {"connected": "everyone", "following": [], "instructor_sockets": 1})
    assert room.remote_presence == {}
