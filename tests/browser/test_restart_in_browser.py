"""Issue 26, points 2 and 3: ``dynlab serve`` restarted under a class loses nothing, checked in Chromium and over HTTP.

A served app with a data directory of its own and no instructor key given (so it makes and keeps one) runs a class:
the instructor's page in a room on the heavy top (the room's scene paused at half speed), two students following on
phones who answered a poll, and a student working alone whose lesson scene (spin changed) is claimed by its page's
key. The server is stopped with Ctrl+C and started again on the same port and data directory, as an instructor whose
laptop restarted would. Then, with no page reloaded:

* the printed instructor link is the same, and the instructor's cookie and key still work;
* the instructor's page and both phones are back in the same room as the same two students (the room has two, not
  four), with the poll and its two answers; a student's changed answer replaces their own; the instructor's change of
  the spin reaches both phones; the room's scene kept its play state and time scale;
* the lone student's scene comes back with its spin when its viewer reconnects, and still refuses a keyless change.

How long the class waited (Ctrl+C until both phones followed again) is printed.
"""

from __future__ import annotations

import shutil
import time
from types import SimpleNamespace

import pytest

from tests.browser.test_classroom_in_browser import LESSON, SCENE, SPIN, _control, _student, instructor_room
from tests.conftest import wait_until
from tests.served import RESULTS, ServedApp, Viewer

pytestmark = pytest.mark.browser
PHONE = (390, 844)
#: A lesson page's session id and the key its page claims it with (the page makes both with crypto.getRandomValues).
SOLO_SESSION = "5e55107e" * 4
SOLO_KEY = "0123456789abcdef" * 2


def _answer(page, value: str) -> None:
    page.wait_for_selector(".room-poll:not([hidden]) input[type=number]")
    page.fill(".room-poll input[type=number]", value)
    page.click(".room-poll-send")
    page.wait_for_selector(f".room-poll-mine:has-text('Your answer: {value} rad/s')")


def _served(data_dir, port: int | None = None) -> ServedApp:
    return ServedApp(name="restart", data_dir=data_dir, env={"DYNLAB_INSTRUCTOR_KEY": ""}, port=port).start()


def test_a_restart_under_a_class_loses_nothing(browser, tmp_path):
    data_dir = RESULTS / f"data-restart-{tmp_path.name}"
    first = _served(data_dir)
    link = first.printed_instructor_link()
    site = SimpleNamespace(url=first.url, instructor_link=link)
    second = None
    contexts = []
    alone = first.new_client()
    try:
        context, teacher, teacher_errors, room_id = instructor_room(browser, site, LESSON)
        contexts.append(context)
        instructor_api = context.request  # the instructor's browser: its cookie
        code = teacher.text_content(".room-code")
        students = []
        for _ in range(2):
            student_context, page, errors = _student(browser, site, code, PHONE)
            contexts.append(student_context)
            students.append((page, errors))
        teacher.wait_for_selector(".room-presence[data-following='2']")
        teacher.select_option("#room-ready", "heavy-top-sleeping-threshold")
        teacher.click('[data-room="ask-ready"]')
        for (page, _), value in zip(students, ("10", "20"), strict=True):
            _answer(page, value)
        teacher.wait_for_selector(".room-results-count[data-answers='2']")
        paused = instructor_api.post(f"{first.url}/api/rooms/{room_id}/state", data={"playing": False, "time_scale": 0.5})
        assert paused.ok, paused.text()
        state_before = first.client.get(f"/api/rooms/{room_id}/state").json()
        poll_id = state_before["poll"]["poll_id"]
        results_before = instructor_api.get(f"{first.url}/api/rooms/{room_id}/polls/{poll_id}/results").json()
        solo = alone.put(f"/api/scenes/{SCENE}/sessions/{SOLO_SESSION}", json={"params": {SPIN: 66.0}}, headers={"X-Session-Key": SOLO_KEY})
        assert solo.status_code == 200, solo.text

        stopped_at = time.monotonic()
        first.stop()
        second = _served(data_dir, port=first.port)

        def class_back() -> bool:  # every page's room socket is open again, as the same students
            state = second.client.get(f"/api/rooms/{room_id}/state").json()
            return state["instructor_connected"] and state["students"]["following"] == 2

        wait_until(class_back, 60, what="the instructor's page and both phones to be back in the room")
        print(f"the class waited {time.monotonic() - stopped_at:.1f} s from Ctrl+C until both phones followed again")

        # The instructor: the same link; the cookie from before, and the key, still make them the instructor.
        assert second.printed_instructor_link() == link
        assert instructor_api.get(f"{second.url}/api/me").json() == {"role": "instructor"}
        assert second.client.get("/api/me", headers={"X-Instructor-Key": link.rsplit("=", 1)[1]}).json() == {"role": "instructor"}
        assert teacher.text_content(".room-code") == code
        teacher.wait_for_selector(".room-presence[data-following='2']")

        # The room: its state, students, poll and answers; its scene's play state.
        state = second.client.get(f"/api/rooms/{room_id}/state").json()
        for name in ("code", "lesson_id", "scene_id", "params", "playing", "time_scale", "mode", "poll"):
            assert state[name] == state_before[name], name
        assert state["students"]["joined"] == 2
        assert instructor_api.get(f"{second.url}/api/rooms/{room_id}/polls/{poll_id}/results").json() == results_before
        playback = second.client.get(f"/api/scenes/{SCENE}/sessions/room-{room_id}/playback").json()
        assert playback["playing"] is False and playback["time_scale"] == 0.5
        _answer(students[0][0], "25")  # the same student: their answer is replaced, not added
        teacher.wait_for_selector(".room-results-count[data-answers='2']")
        assert second.client.get(f"/api/rooms/{room_id}/state").json()["poll"]["answers"] == 2
        teacher.fill(f"#ctl-{SPIN}", "120")
        teacher.dispatch_event(f"#ctl-{SPIN}", "change")
        for page, _ in students:
            wait_until(lambda page=page: _control(page) == 120, 10, what="the instructor's spin on a phone")
        assert teacher_errors == [] and all(errors == [] for _, errors in students)

        # The student working alone: their scene comes back as their viewer reconnects, still theirs alone.
        viewer = Viewer(second, f"/viewer/{SCENE}/{SOLO_SESSION}", address=alone.address)
        try:
            wait_until(lambda: viewer.frames > 0, timeout_s=30, what="the lone student's viewer to reconnect")
        finally:
            viewer.close()
        assert alone.get(f"/api/scenes/{SCENE}/sessions/{SOLO_SESSION}").json()["params"][SPIN] == 66.0
        for headers in ({}, {"X-Session-Key": "k" * 32}):
            taken = second.client.put(f"/api/scenes/{SCENE}/sessions/{SOLO_SESSION}", json={"params": {SPIN: 5.0}}, headers=headers)
            assert taken.status_code == 403, taken.text
        owner = alone.put(f"/api/scenes/{SCENE}/sessions/{SOLO_SESSION}", json={"params": {SPIN: 70.0}}, headers={"X-Session-Key": SOLO_KEY})
        assert owner.status_code == 200 and owner.json()["params"][SPIN] == 70.0
    finally:
        for context in contexts:
            context.close()
        alone.close()
        (second or first).stop()
        shutil.rmtree(data_dir, ignore_errors=True)
