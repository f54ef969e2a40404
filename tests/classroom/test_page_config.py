"""The classroom's rules handed to the page scripts are the rules the server enforces, not a second copy of them
(with the web layer's time scales and socket rule, which the classroom's pages use too)."""

from __future__ import annotations

import json

import pytest
from pydantic import ValidationError

from app.api.schemas.scenes import PlaybackRequest
from app.classroom.page_config import classroom_page_config
from app.classroom.polls import Poll, PollError
from app.classroom.registry import Rooms
from app.classroom.room import RoomError
from app.classroom.schemas import JoinRequest, PollRequest, RoomStateChange
from app.scenes.host.host import TIME_SCALE_RANGE
from app.web.page_config import SOCKET_RECONNECT, TIME_SCALES, page_config

CONFIG = classroom_page_config()


def test_it_is_plain_json_with_the_keys_the_scripts_read():
    assert json.loads(json.dumps(CONFIG)) == CONFIG
    assert set(CONFIG) == {"socket_ping_interval_ms", "room_code_length", "student_name_max_chars", "poll"}
    assert set(CONFIG["poll"]) == {
        "question_max_chars", "choice_max_chars", "choices_min", "choices_max", "unit_max_chars"
    }


def test_the_time_scales_offered_span_the_range_every_door_accepts():
    scales = list(TIME_SCALES)
    assert scales == sorted(scales) and 1 in scales  # slowest to fastest, real time among them
    assert (scales[0], scales[-1]) == TIME_SCALE_RANGE
    for scale in scales:  # a page's time controls, and the instructor's for the room
        PlaybackRequest(time_scale=scale)
        RoomStateChange(time_scale=scale)
    for outside in (TIME_SCALE_RANGE[0] * 0.99, TIME_SCALE_RANGE[1] * 1.01):
        with pytest.raises(ValidationError):
            PlaybackRequest(time_scale=outside)
        with pytest.raises(ValidationError):
            RoomStateChange(time_scale=outside)


def test_the_room_socket_waits_longer_after_each_failed_try_up_to_its_longest_wait():
    rule = SOCKET_RECONNECT
    waits = [rule["initial_ms"]]
    while waits[-1] < rule["cap_ms"]:
        waits.append(min(rule["cap_ms"], waits[-1] * rule["factor"]))
    assert waits == [500, 1000, 2000, 4000, 8000, 10_000]
    assert 0 < CONFIG["socket_ping_interval_ms"]


def test_every_page_is_handed_the_classroom_section_once_the_app_is_made():
    from app.main import create_app

    create_app()
    assert page_config()["classroom"] == CONFIG


def _question(**fields) -> dict:
    return {"question": "Which way does the top precess?", "kind": "choice", "choices": ["left", "right"], **fields}


def test_the_poll_limits_are_the_ones_a_poll_and_its_request_enforce():
    limits = CONFIG["poll"]
    longest = {
        "question": "q" * limits["question_max_chars"],
        "choices": [f"{k}".ljust(limits["choice_max_chars"], "c") for k in range(limits["choices_max"])],
    }
    Poll.create(_question(**longest), poll_id="p1")
    PollRequest(**_question(**longest))
    for too_long in (
        {"question": "q" * (limits["question_max_chars"] + 1)},
        {"choices": ["c" * (limits["choice_max_chars"] + 1), "b"]},
        {"choices": [f"c{k}" for k in range(limits["choices_max"] + 1)]},
        {"choices": [f"c{k}" for k in range(limits["choices_min"] - 1)]},
    ):
        with pytest.raises(PollError):
            Poll.create(_question(**too_long), poll_id="p1")
    too_many = [f"c{k}" for k in range(limits["choices_max"] + 1)]
    for too_long in ({"question": "q" * (limits["question_max_chars"] + 1)}, {"choices": too_many}):
        with pytest.raises(ValidationError):
            PollRequest(**_question(**too_long))
    number = {"question": "How fast, in the end?", "kind": "number"}
    Poll.create({**number, "unit": "u" * limits["unit_max_chars"]}, poll_id="p1")
    with pytest.raises(PollError):
        Poll.create({**number, "unit": "u" * (limits["unit_max_chars"] + 1)}, poll_id="p1")
    with pytest.raises(ValidationError):
        PollRequest(**number, unit="u" * (limits["unit_max_chars"] + 1))


def test_a_room_code_and_a_students_name_are_as_long_as_the_pages_say():
    room, _ = Rooms().create(join_base="http://lab.test")
    assert len(room.code) == CONFIG["room_code_length"]
    name = "n" * CONFIG["student_name_max_chars"]
    assert room.join(name).name == name
    JoinRequest(code=room.code, name=name)
    with pytest.raises(RoomError):
        room.join(name + "n")
    with pytest.raises(ValidationError):
        JoinRequest(code=room.code, name=name + "n")
