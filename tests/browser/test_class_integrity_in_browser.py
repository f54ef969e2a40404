"""A class's integrity in a real browser, against ``dynlab serve`` as a user runs it (issue 24, Found 9 and 10).

- Two instructor tabs: a second tab opened on another lesson with the room follows the room's lesson instead of
  moving the class, and offers to show its lesson; the class moves only when that is chosen, and the first tab
  follows it there; a change a tab sends for a scene the room has left is refused (409).
- A student opens the QR code's address: the page shows the room's code and asks for a name, and joins only when
  asked; scanning again is the same student; the instructor removes the student from the panel's list, and the
  student's page says so and cannot join again.

Every check reads the server over HTTP or the pages' DOM; nothing reaches into the server's memory.
"""

from __future__ import annotations

import re

import httpx
import pytest

from tests.conftest import wait_until

pytestmark = pytest.mark.browser

TOP_LESSON = "10-2-spinning-top"
FOUR_BAR_LESSON = "4-3-four-bar-linkage"
# Viewers stay connected and get every frame but draw nothing (software WebGL would starve the pages' main threads).
NOT_DRAWING = """document.addEventListener("DOMContentLoaded", () => {
  const style = document.createElement("style");
  style.textContent = "#viewer { display: none !important; }";
  document.head.append(style);
});"""


def _context(browser, viewport=(1400, 1000)):
    context = browser.new_context(viewport={"width": viewport[0], "height": viewport[1]})
    context.add_init_script(NOT_DRAWING)
    return context


def _page(context):
    page = context.new_page()
    page.errors = []  # uncaught JavaScript errors
    page.on("pageerror", lambda exc: page.errors.append(str(exc)))
    return page


def _room_state(served, room_id: str) -> dict:
    return httpx.get(f"{served.url}/api/rooms/{room_id}/state").json()


def _instructor_on(browser, served, lesson_id: str):
    """The instructor's browser: the instructor link, then a room started on ``lesson_id``."""
    context = _context(browser)
    page = _page(context)
    page.goto(served.instructor_link)
    page.goto(f"{served.url}/lessons/{lesson_id}")
    page.get_by_role("button", name="Start a class room here").click()
    page.wait_for_url(re.compile(r"\?room=[0-9a-f]{16}"))
    page.wait_for_function("() => document.querySelector('.room-code')?.textContent")  # the room's state arrived
    return context, page, re.search(r"room=([0-9a-f]{16})", page.url).group(1)


def _set_control(page, name: str, value: str) -> None:
    page.fill(f"#ctl-{name}", value)
    page.dispatch_event(f"#ctl-{name}", "change")


def test_a_second_instructor_tab_follows_the_class_and_moves_it_only_when_asked(browser, served):
    """Found 9: opening another lesson with ?room=<id> in a second tab moved the class, and the first tab then drove
    its old lesson's controls at the new scene ("mass_kg: unknown input")."""
    context, first, room_id = _instructor_on(browser, served, TOP_LESSON)
    second = _page(context)  # the same browser: the instructor's cookie
    second.goto(f"{served.url}/lessons/{FOUR_BAR_LESSON}?room={room_id}")

    # The second tab goes to the class's lesson; the class stays where it was.
    second.wait_for_url(re.compile(rf"/lessons/{TOP_LESSON}\?room={room_id}&scene=heavy-top$"))
    offer = second.get_by_role("button", name=re.compile(r"Show “.*four-bar.*” to the class", re.IGNORECASE))
    offer.wait_for()
    state = _room_state(served, room_id)
    assert (state["lesson_id"], state["scene_id"]) == (TOP_LESSON, "heavy-top")
    assert first.url.endswith(f"/lessons/{TOP_LESSON}?room={room_id}&scene=heavy-top")

    # Both tabs drive the class's scene: a change from either reaches the room.
    _set_control(first, "spin_rad_s", "90")
    wait_until(lambda: _room_state(served, room_id)["params"]["spin_rad_s"] == 90, 10, what="the first tab's spin to reach the room")
    _set_control(second, "mass_kg", "2")
    wait_until(lambda: _room_state(served, room_id)["params"]["mass_kg"] == 2, 10, what="the second tab's mass to reach the room")

    # The instructor chooses to show the four-bar: the class moves, and the first tab follows it there.
    offer.click()
    for page in (first, second):
        page.wait_for_url(re.compile(rf"/lessons/{FOUR_BAR_LESSON}\?room={room_id}&scene=four-bar$"))
        page.wait_for_function("() => document.querySelector('.room-code')?.textContent")  # the room's state arrived
    state = _room_state(served, room_id)
    assert (state["lesson_id"], state["scene_id"]) == (FOUR_BAR_LESSON, "four-bar")

    # A change meant for the heavy top (a tab that had not yet followed) is refused with 409 and changes nothing.
    refusal = first.evaluate(
        """async (lesson) => {
          const room = (await import('/static/js/room.js')).classroom;
          return new Promise((resolve) => {
          document.addEventListener("dynlab:room", (e) => { if (e.detail.type === "error") resolve(e.detail); });
          room.send({type: "set_state", params: {mass_kg: 2}, if_lesson_id: lesson, if_scene_id: "heavy-top"});
        }); }""",
        TOP_LESSON,
    )
    assert refusal["status"] == 409 and "nothing changed" in refusal["detail"], refusal
    assert "the class had already moved on" in first.text_content(".room-panel .room-error")  # the panel says so in words
    assert _room_state(served, room_id)["revision"] == state["revision"]
    # The followed tab's controls are the four-bar's, and they work (no "unknown input").
    _set_control(first, "crank_speed_rad_s", "2.5")
    wait_until(lambda: _room_state(served, room_id)["params"]["crank_speed_rad_s"] == 2.5, 10, what="the four-bar's crank speed to reach the room")
    assert "unknown input" not in first.text_content(".room-panel .room-error")

    # The previous/next links move the class explicitly; both tabs follow.
    first.click(".prevnext a.next")
    for page in (first, second):
        page.wait_for_url(re.compile(rf"/lessons/(?!{FOUR_BAR_LESSON})[^?]+\?room={room_id}"))
    assert _room_state(served, room_id)["lesson_id"] != FOUR_BAR_LESSON
    assert not first.errors and not second.errors, (first.errors, second.errors)
    httpx.delete(f"{served.url}/api/rooms/{room_id}", headers=served.instructor_headers)

    # A room that shows no lesson yet (opened from the API): a lesson page offers itself, and nothing moves until asked.
    empty = httpx.post(f"{served.url}/api/rooms", json={}, headers=served.instructor_headers).json()["room_id"]
    second.goto(f"{served.url}/lessons/{FOUR_BAR_LESSON}?room={empty}")
    show = second.get_by_role("button", name=re.compile(r"Show “.*four-bar.*” to the class", re.IGNORECASE))
    show.wait_for()
    assert "no lesson yet" in second.text_content(".room-offer") and _room_state(served, empty)["lesson_id"] is None
    show.click()
    wait_until(lambda: _room_state(served, empty)["lesson_id"] == FOUR_BAR_LESSON, 10, what="the empty room to show the four-bar")
    second.wait_for_selector(".room-offer", state="hidden")
    assert second.url.endswith(f"/lessons/{FOUR_BAR_LESSON}?room={empty}")
    httpx.delete(f"{served.url}/api/rooms/{empty}", headers=served.instructor_headers)
    context.close()


def test_a_student_names_themself_rejoins_as_the_same_student_and_can_be_removed(browser, served):
    """Found 10: /join/<code> joined at once with no chance to give a name; re-scanning made a new student; the
    instructor could not remove anyone."""
    teacher_context, teacher, room_id = _instructor_on(browser, served, TOP_LESSON)
    code = teacher.text_content(".room-code")
    phone = _context(browser, (390, 844))
    student = _page(phone)

    # The QR code's address: the code shown, a name asked for, nothing joined until Join is pressed.
    student.goto(f"{served.url}/join/{code}", wait_until="networkidle")
    assert code in student.text_content(".join-lead")
    assert student.evaluate("document.activeElement.id") == "join-name"
    assert student.url.endswith(f"/join/{code}") and _room_state(served, room_id)["students"]["joined"] == 0
    student.fill("#join-name", "Ada Lovelace")
    student.click("#join-button")
    student.wait_for_url(re.compile(rf"/lessons/{TOP_LESSON}\?room={room_id}"))
    student.wait_for_selector('.room-bar[data-mode="follow"]')

    # Scanning the QR code again: the name is offered again, and the device is the same student.
    student.goto(f"{served.url}/join/{code}", wait_until="networkidle")
    assert student.input_value("#join-name") == "Ada Lovelace"
    student.click("#join-button")
    student.wait_for_url(re.compile(rf"/lessons/{TOP_LESSON}\?room={room_id}"))
    student.wait_for_selector('.room-bar[data-mode="follow"]')
    assert _room_state(served, room_id)["students"]["joined"] == 1

    # The instructor's list names the student; Remove takes them out.
    teacher.click(".room-students summary")
    row = teacher.locator(".room-student-list li", has_text="Ada Lovelace")
    row.wait_for()
    teacher.wait_for_selector(".room-student-list li[data-connected='true']")
    assert teacher.text_content(".room-students summary") == "Students (1)"
    teacher.once("dialog", lambda dialog: dialog.accept())
    row.get_by_role("button", name="Remove").click()
    student.wait_for_selector(".room-gone:has-text('The instructor removed you from this room')")
    teacher.wait_for_selector(".room-students summary:has-text('Students (0)')")
    assert _room_state(served, room_id)["students"]["joined"] == 0
    assert student.locator("#ctl-spin_rad_s").is_disabled()

    # The removed device cannot join again.
    student.goto(f"{served.url}/join/{code}")
    student.click("#join-button")
    student.wait_for_selector("#join-error:has-text('The instructor removed this device')")
    assert _room_state(served, room_id)["students"]["joined"] == 0
    assert not teacher.errors and not student.errors, (teacher.errors, student.errors)
    httpx.delete(f"{served.url}/api/rooms/{room_id}", headers=served.instructor_headers)
    phone.close()
    teacher_context.close()
