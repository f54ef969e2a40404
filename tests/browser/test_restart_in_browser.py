"""Issue 26, point 3, in Chromium: ``dynlab serve`` restarted under a class loses nothing.

An instructor's page runs a room on the heavy top with two students following on phones and a poll they answered.
The server is stopped with Ctrl+C and started again on the same port and data directory (no instructor key given: it
keeps its own). Then, with no page reloaded: the instructor's page is still the instructor's and shows the same room,
its two followers and the poll's two answers; the students' pages are back as the same two students (the room still
has two, not four); a student's changed answer replaces their own; and the instructor's change of the spin reaches
both phones. How long the class waited (Ctrl+C until both followers were back) is printed.
"""

from __future__ import annotations

import shutil
import time
from types import SimpleNamespace

import pytest

from tests.browser.test_classroom_in_browser import LESSON, SPIN, _control, _student, instructor_room
from tests.conftest import wait_until
from tests.served import RESULTS, ServedApp

pytestmark = pytest.mark.browser
PHONE = (390, 844)


def _answer(page, value: str) -> None:
    page.wait_for_selector(".room-poll:not([hidden]) input[type=number]")
    page.fill(".room-poll input[type=number]", value)
    page.click(".room-poll-send")
    page.wait_for_selector(f".room-poll-mine:has-text('Your answer: {value} rad/s')")


def test_a_restart_under_a_class_loses_nothing_in_the_browser(browser, tmp_path):
    data_dir = RESULTS / f"data-restart-browser-{tmp_path.name}"
    first = ServedApp(name="restart-browser", data_dir=data_dir, env={"DYNLAB_INSTRUCTOR_KEY": ""}).start()
    site = SimpleNamespace(url=first.url, instructor_link=first.printed_instructor_link())
    second = None
    contexts = []
    try:
        context, teacher, teacher_errors, room_id = instructor_room(browser, site, LESSON)
        contexts.append(context)
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

        stopped_at = time.monotonic()
        first.stop()
        second = ServedApp(name="restart-browser", data_dir=data_dir, env={"DYNLAB_INSTRUCTOR_KEY": ""}, port=first.port).start()

        def class_back() -> bool:  # every page's room socket is open again, as the same students
            state = second.client.get(f"/api/rooms/{room_id}/state").json()
            return state["instructor_connected"] and state["students"]["following"] == 2

        wait_until(class_back, 60, what="the instructor's page and both phones to be back in the room")
        print(f"the class waited {time.monotonic() - stopped_at:.1f} s from Ctrl+C until both phones followed again")
        teacher.wait_for_selector(".room-presence[data-following='2']")

        assert teacher.text_content(".room-code") == code
        assert second.printed_instructor_link() == site.instructor_link
        teacher.wait_for_selector(".room-results-count[data-answers='2']")
        state = second.client.get(f"/api/rooms/{room_id}/state").json()
        assert state["students"]["joined"] == 2 and state["poll"]["answers"] == 2

        _answer(students[0][0], "25")  # the same student: their answer is replaced, not added
        wait_until(lambda: second.client.get(f"/api/rooms/{room_id}/state").json()["poll"]["answers"] == 2, 10, what="the answer count")
        teacher.wait_for_selector(".room-results-count[data-answers='2']")

        teacher.fill(f"#ctl-{SPIN}", "120")
        teacher.dispatch_event(f"#ctl-{SPIN}", "change")
        for page, _ in students:
            wait_until(lambda page=page: _control(page) == 120, 10, what="the instructor's spin on a phone")
        assert teacher_errors == [] and all(errors == [] for _, errors in students)
    finally:
        for context in contexts:
            context.close()
        (second or first).stop()
        shutil.rmtree(data_dir, ignore_errors=True)
