"""A room change that is refused changes nothing, and one that is taken leaves the class able to go on (issue 29's
hostile tester), against ``dynlab serve`` as a user runs it:

- a ready question refused with 422 (the instructor's overrides do not fit it) leaves the class on its lesson, scene
  and parameters, by request and on the instructor's socket;
- a scene changed while the class explores gives the students a start on the new scene;
- only the room's current poll can be closed or reopened: an old one is refused with 409.
"""

from __future__ import annotations

import json
import secrets
from collections.abc import Iterator

import pytest

from tests.api.test_class_integrity import device, join, messages_until, room_socket, state_of

FRICTION_LESSON = "8-2-coulomb-friction"
#: What a refused change must leave as it was.
KEPT = ("lesson_id", "scene_id", "params", "playing", "mode", "revision", "explore_start", "poll")


@pytest.fixture
def friction_room(served) -> Iterator[dict]:
    """A room on the sliding bar with friction, its friction changed from the default (a reset would show)."""
    instructor = served.instructor_headers
    created = served.client.post(
        "/api/rooms", json={"lesson_id": FRICTION_LESSON, "scene_id": "sliding-bar-friction"}, headers=instructor
    )
    assert created.status_code == 200, created.text
    room = created.json()
    changed = served.client.post(f"/api/rooms/{room['room_id']}/state", json={"params": {"mu": 0.45}}, headers=instructor)
    assert changed.status_code == 200 and changed.json()["params"]["mu"] == 0.45, changed.text
    yield room
    served.client.delete(f"/api/rooms/{room['room_id']}", headers=instructor)


def kept(state: dict) -> dict:
    return {name: state[name] for name in KEPT}


# ---- F1: a refused ready question does not move the class ---------------------------------------------------------
#: Ready questions of other lessons, each with an override that does not fit it, and the field the 422 names.
REFUSED_READY = (
    ({"ready_id": "ladder-leaves-wall", "answer_value": 3}, "answer_value"),  # the scene computes its answer
    ({"ready_id": "hoop-critical-spin", "question": ""}, "question"),
    ({"ready_id": "four-bar-class", "answer_choice": 7}, "answer_choice"),
    ({"ready_id": "baseball-range-with-drag", "choices": ["a", "b"]}, "choices"),  # a number question
)


def test_a_ready_question_refused_with_422_leaves_the_class_where_it_was(served, friction_room):
    room_id, instructor = friction_room["room_id"], served.instructor_headers
    before = state_of(served, room_id)
    assert (before["scene_id"], before["params"]["mu"]) == ("sliding-bar-friction", 0.45)
    for body, field in REFUSED_READY:
        answer = served.client.post(f"/api/rooms/{room_id}/polls", json=body, headers=instructor)
        assert answer.status_code == 422, (body, answer.text)
        assert answer.json()["detail"][0]["loc"] == ["body", field], (body, answer.text)
        assert kept(state_of(served, room_id)) == kept(before), body

    with room_socket(served, room_id, instructor=True) as socket:
        messages_until(socket, lambda m: m["type"] == "state")
        for body, field in REFUSED_READY:
            socket.send(json.dumps({"type": "open_poll", **body}))
            refusal = messages_until(socket, lambda m: m["type"] == "error")
            assert (refusal["status"], refusal["action"]) == (422, "open_poll") and field in refusal["detail"], refusal
    assert kept(state_of(served, room_id)) == kept(before)

    # The same question without the override that does not fit it moves the class and asks it.
    asked = served.client.post(f"/api/rooms/{room_id}/polls", json={"ready_id": "ladder-leaves-wall"}, headers=instructor)
    assert asked.status_code == 200, asked.text
    after = state_of(served, room_id)
    assert (after["scene_id"], after["poll"]["poll_id"]) == ("sliding-ladder", asked.json()["poll_id"]), after


# ---- F3: a new scene while the class explores -----------------------------------------------------------------------
def test_a_scene_changed_while_the_class_explores_gives_the_students_the_new_scene(served, friction_room):
    """The room explored the sliding bar and the instructor showed the stick-slip belt: the students' pages went to the
    belt, but the room's explore start still named the bar, so every student's own copy was refused (422)."""
    room_id, instructor = friction_room["room_id"], served.instructor_headers
    exploring = served.client.post(f"/api/rooms/{room_id}/state", json={"mode": "explore"}, headers=instructor).json()
    assert exploring["explore_start"]["scene_id"] == "sliding-bar-friction"
    student = device(served)
    own = f"explore-{secrets.token_hex(6)}"

    moved = served.client.post(f"/api/rooms/{room_id}/state", json={"scene_id": "stick-slip-belt"}, headers=instructor)
    assert moved.status_code == 200, moved.text
    state = moved.json()
    assert state["mode"] == "explore" and state["scene_id"] == "stick-slip-belt"
    # The new scene as the room opened it: its parameters, from its start (t = 0).
    assert state["explore_start"] == {"scene_id": "stick-slip-belt", "params": state["params"], "motion": None}
    copy = student.put(f"/api/scenes/stick-slip-belt/sessions/{own}", json={"params": {}, "from_room": room_id})
    assert copy.status_code == 200 and copy.json()["params"] == state["params"], copy.text
    old = student.put(f"/api/scenes/sliding-bar-friction/sessions/{own}-old", json={"params": {}, "from_room": room_id})
    assert old.status_code == 422 and "explores 'stick-slip-belt'" in old.text, old.text

    # Another lesson, the same: its scene is what the students explore.
    lesson = served.client.post(f"/api/rooms/{room_id}/state", json={"lesson_id": "10-2-spinning-top"}, headers=instructor).json()
    assert lesson["explore_start"] == {"scene_id": "heavy-top", "params": lesson["params"], "motion": None}
    top = student.put(f"/api/scenes/heavy-top/sessions/{own}-top", json={"params": {}, "from_room": room_id})
    assert top.status_code == 200, top.text
    # Parameters changed on the same scene leave the students' start as it was (they explore their own copies).
    spun = served.client.post(f"/api/rooms/{room_id}/state", json={"params": {"spin_rad_s": 80.0}}, headers=instructor).json()
    assert spun["explore_start"] == lesson["explore_start"]
    student.close()


# ---- F6: only the current poll opens and closes ---------------------------------------------------------------------
def test_only_the_rooms_current_poll_can_be_closed_or_reopened(served, friction_room):
    """An old poll (even a revealed one) could be reopened while a newer one stayed current, and a student could then
    answer it. Opening and closing belong to the current poll alone; an old one is 409 and nothing changes."""
    room_id, instructor = friction_room["room_id"], served.instructor_headers
    polls = f"/api/rooms/{room_id}/polls"
    choice = {"kind": "choice", "choices": ["left", "right"], "answer_choice": 1}
    first = served.client.post(polls, json={"question": "First?", **choice}, headers=instructor).json()["poll_id"]
    assert served.client.post(f"{polls}/{first}", json={"reveal": True}, headers=instructor).status_code == 200
    current = served.client.post(polls, json={"question": "Second?", **choice}, headers=instructor).json()["poll_id"]
    phone = device(served)
    token = join(phone, friction_room["code"])["student_token"]
    before, old_results = state_of(served, room_id), served.client.get(f"{polls}/{first}/results", headers=instructor).json()

    for body in ({"open": True}, {"open": False}, {"open": True, "show_names": True}):
        refused = served.client.post(f"{polls}/{first}", json=body, headers=instructor)
        assert refused.status_code == 409, (body, refused.text)
        assert f"{current} is the room's current poll" in refused.json()["detail"], refused.text
    with room_socket(served, room_id, instructor=True) as socket:
        messages_until(socket, lambda m: m["type"] == "state")
        socket.send(json.dumps({"type": "update_poll", "poll_id": first, "open": True}))
        refusal = messages_until(socket, lambda m: m["type"] == "error")
        assert (refusal["status"], refusal["action"]) == (409, "update_poll") and current in refusal["detail"], refusal
    assert state_of(served, room_id)["revision"] == before["revision"]
    assert served.client.get(f"{polls}/{first}/results", headers=instructor).json() == old_results
    answer = phone.post(f"{polls}/{first}/answers", json={"choice": 0}, headers={"X-Student-Token": token})
    assert answer.status_code == 409, answer.text

    # The current poll closes and reopens; an old one's names can still be shown (for its CSV).
    for is_open in (False, True):
        toggled = served.client.post(f"{polls}/{current}", json={"open": is_open}, headers=instructor)
        assert toggled.status_code == 200 and toggled.json()["open"] is is_open, toggled.text
    named = served.client.post(f"{polls}/{first}", json={"show_names": True}, headers=instructor)
    assert named.status_code == 200 and named.json()["show_names"] is True, named.text
    phone.close()
