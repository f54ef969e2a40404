"""One class on several servers: each server brings the rooms and page sessions it holds up to date with what the
others change (app.storage.changes delivers their announcements; this module takes them up).

A room another server changed is read anew from the database, its stage here follows (parameters, play state, a
reset, another scene), and every page here gets the new state; an answer given there reaches this server's
instructor; who is connected there counts here (each server says who its sockets hold, app.classroom.hub); a room
closed there closes here. A room held here that no page here follows any more stops its scene here (the balancer sends
its class to another server), and opens it again with its next follower; the room itself stays, one copy per server,
so no request or socket still using it is left with a copy nobody keeps in step.
"""

from __future__ import annotations

import logging
from typing import Any

from fastapi import FastAPI

from app.classroom.hub import REMOVED_MESSAGE, RoomHub
from app.classroom.registry import Rooms
from app.classroom.relay import follower_count
from app.classroom.room import Room
from app.storage.changes import Change

log = logging.getLogger(__name__)


class ClassSync:
    """Takes other servers' changes up into ``app``'s rooms, room sockets and page sessions (called from the change
    listener's thread, one change at a time)."""

    def __init__(self, app: FastAPI) -> None:
        self.app = app

    @property
    def _rooms(self) -> Rooms:
        return self.app.state.rooms

    @property
    def _hub(self) -> RoomHub:
        return self.app.state.room_hub

    @property
    def _host(self) -> Any:
        return self.app.state.scene_host

    def on_change(self, change: Change) -> None:
        if change.kind == "session":
            self.app.state.sessions.changed_elsewhere(change.key)
            return
        room = self._rooms.held(change.key)
        if change.kind == "room_closed":  # closes here too, with any copy read for joins only
            self._rooms.closed_elsewhere(change.key)
            if room is not None:
                self._closed_elsewhere(room)
            return
        if room is None:
            return
        if change.kind == "presence":  # who that server's sockets hold: this server's pages count them too
            room.take_presence(change.origin, change.fields)
            self._hub.others_presence_changed(room)
        elif change.kind == "answer":
            self._answer(room, poll_id=change.fields["poll_id"], student_id=change.fields["student_id"])
        elif change.kind == "room":
            # This server may have read that version already (a change of its own that had to take it up first, or a
            # student it had to look up): its stage and pages are brought to it all the same.
            self._take_up(room, read=change.fields.get("version", 0) > room.kept_version)

    def on_missed(self) -> None:
        """Changes may have been missed (the listening connection was lost): every room held here is read anew."""
        for room in self._rooms.all():
            self._take_up(room)

    def _in_use_here(self, room: Room) -> bool:
        return self._hub.socket_count(room.room_id) > 0 or follower_count(self.app, room.room_id) > 0

    def _take_up(self, room: Room, *, read: bool = True) -> None:
        students_before = set(room.students)
        if read and not room.take_up_newer():
            self._closed_elsewhere(room)
            return
        self._hub.publish_state(room)  # the pages first; the scene here follows next (a call to its worker)
        self._hub.publish_students(room)
        if room.poll_id is not None:
            self._hub.publish_results(room, room.poll(room.poll_id))
        if self._in_use_here(room):
            room.follow_stage(self._host)
        elif room.rest_stage(self._host):  # nobody here follows it: its scene stops here until someone does
            log.info("room %s: nobody here follows its scene; it stops here until someone does", room.code)
        for student_id in students_before - set(room.students):  # removed on the other server: out here too
            self._hub.dismiss_student(room, student_id, REMOVED_MESSAGE)

    def _answer(self, room: Room, *, poll_id: str, student_id: str) -> None:
        answer = room.store.load_answer(room.room_id, poll_id, student_id) if room.store is not None else None
        if answer is None:
            return
        with room.lock:
            poll = room.polls.get(poll_id)
            if poll is None or student_id not in room.students:  # a poll or student this server has not taken up yet
                self._take_up(room)
                return
            poll.take_kept_answer(student_id, answer)
        self._hub.publish_results(room, poll)
        self._hub.presence_changed(room)

    def _closed_elsewhere(self, room: Room) -> None:
        self._rooms.closed_elsewhere(room.room_id)
        self._close_stage(room)
        self._hub.publish(room.room_id, {"type": "closed"})

    def _close_stage(self, room: Room) -> None:
        if room.scene_id is None:
            return
        try:
            self._host.close_stage(room.stage_id)
        except Exception as exc:  # a worker restarting forgets it anyway
            log.warning("room %s: its stage here did not close (%s)", room.code, exc)
