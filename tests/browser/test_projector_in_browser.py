"""The classroom's projector view and the join page, in a real browser with several contexts at once.

The instructor opens a room on the heavy-top lesson and asks a question; two students join by the
QR code's link (/join/<code>) and answer; the projector shows the join code, the QR code, the room's
scene large and the live (anonymous) histogram of their answers.
"""

from __future__ import annotations

import json

import pytest

from tests.browser.conftest import let_webgl_draw, room_followers, screenshot
from tests.conftest import wait_until

pytestmark = pytest.mark.browser


LESSON_ID = "10-2-spinning-top"
CHOICES = ["It falls over", "It precesses about the vertical", "It stays still"]
#: The scene's share of the projector's width at 1920×1080 (the brief: "the scene LARGE").
MIN_SCENE_WIDTH_SHARE = 0.6


def _stub_lesson_pages(context) -> None:
    """Students land on a stub instead of the lesson page: its room mode (another test's subject) would
    start one more software-WebGL viewer per student; this test is about joining and the projector."""
    context.route("**/lessons/**", lambda route: route.fulfill(status=200, content_type="text/html", body="<!doctype html><title>lesson</title><p>lesson</p>"))


def _student_joins_and_answers(browser, live_server, code: str, room_id: str, poll_id: str, choice: int):
    """A phone joins by the QR code's link, answers, and stays in the room (its page's socket said hello); returns its context."""
    context = browser.new_context(viewport={"width": 390, "height": 844})
    _stub_lesson_pages(context)
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda exc: errors.append(str(exc)))
    page.goto(f"{live_server.url}/join/{code}")
    # The QR code's link fills in the code and asks for a name; Join keeps the token and goes to the room's lesson and scene.
    page.click("#join-button")
    page.wait_for_url(f"**/lessons/{LESSON_ID}?room={room_id}&scene=heavy-top", timeout=15_000)
    kept = json.loads(page.evaluate(f"localStorage.getItem('dynlab.room.{room_id}')"))
    # Answer and stay from a page the server served (Chromium blocks loopback sockets from a stubbed page).
    page.goto(f"{live_server.url}/join")
    answer = page.evaluate(
        """async ([roomId, pollId, token, choice]) => {
            const response = await fetch(`/api/rooms/${roomId}/polls/${pollId}/answers`, {
                method: "POST", headers: {"Content-Type": "application/json", "X-Student-Token": token},
                body: JSON.stringify({choice})});
            window.roomSocket = new WebSocket(`ws://${location.host}/api/rooms/${roomId}/socket`);
            window.roomSocket.onopen = () => window.roomSocket.send(JSON.stringify({type: "hello", student_token: token, following: true}));
            return [response.status, await response.json()];
        }""",
        [room_id, poll_id, kept["student_token"], choice],
    )
    assert answer[0] == 200, answer
    assert not errors, errors
    return context


def test_students_join_by_code_and_the_projector_shows_their_answers(browser, live_server, shots):
    instructor = browser.new_context(viewport={"width": 1920, "height": 1080})
    page = instructor.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda exc: errors.append(str(exc)))
    page.goto(live_server.instructor_link)
    created = page.request.post(f"{live_server.url}/api/rooms", data={"lesson_id": LESSON_ID})
    assert created.status == 200, created.text()
    room = created.json()
    room_id, code = room["room_id"], room["code"]
    poll = page.request.post(
        f"{live_server.url}/api/rooms/{room_id}/polls",
        data={"question": "A spinning top leans over. What does it do?", "kind": "choice", "choices": CHOICES, "answer_choice": 1},
    )
    assert poll.status == 200, poll.text()
    poll_id = poll.json()["poll_id"]

    page.goto(f"{live_server.url}/rooms/{room_id}/projector")
    assert page.text_content("#projector-code").strip() == code
    # Polling on a timer, not on animation frames: the scene's software WebGL can starve those for seconds.
    page.wait_for_function("() => { const qr = document.getElementById('projector-qr'); return qr.complete && qr.naturalWidth > 0; }", polling=100, timeout=15_000)
    scene = page.locator("#projector-viewer").bounding_box()
    assert scene is not None and scene["width"] >= MIN_SCENE_WIDTH_SHARE * 1920, scene
    page.wait_for_function("() => !document.getElementById('projector-poll').hidden", polling=100, timeout=15_000)
    assert page.text_content("#projector-question").startswith("A spinning top leans over")
    labels = page.eval_on_selector_all("#projector-histogram .label", "(els) => els.map((el) => el.textContent)")
    assert labels == CHOICES

    students = [_student_joins_and_answers(browser, live_server, code, room_id, poll_id, choice=1) for _ in range(2)]

    # The answers reach the projector's histogram over the (instructor's) room socket: counts only.
    page.wait_for_function("() => document.getElementById('projector-answers').dataset.count === '2'", polling=100, timeout=15_000)
    counts = page.eval_on_selector_all("#projector-histogram li", "(els) => els.map((el) => Number(el.dataset.count))")
    assert counts == [0, 2, 0]
    page.wait_for_function("() => document.getElementById('projector-students').textContent === '2 students connected · 2 following'", polling=100, timeout=15_000)
    revealed = page.request.post(f"{live_server.url}/api/rooms/{room_id}/polls/{poll_id}", data={"reveal": True})
    assert revealed.status == 200, revealed.text()
    page.wait_for_function("() => !document.getElementById('projector-revealed').hidden", polling=100, timeout=15_000)
    assert page.text_content("#projector-revealed") == f"Answer: {CHOICES[1]} — given by the instructor"
    assert page.eval_on_selector_all("#projector-histogram li", "(els) => els.map((el) => el.classList.contains('is-answer'))") == [False, True, False]
    # The room's scene streams into the projector's viewer and its readout arrives over the socket.
    wait_until(lambda: room_followers(live_server, room_id) >= 1, 30, what="the projector's viewer to follow the room's stream")
    page.wait_for_function("() => document.querySelector('#projector-quantities [data-quantity]') !== null", polling=200, timeout=30_000)
    assert page.text_content("#projector-play").startswith("▶")

    # J hides the join code (and shows it again).
    page.locator("body").press("j")
    assert page.locator("#projector-join").is_hidden()
    page.locator("body").press("j")
    assert page.locator("#projector-join").is_visible()

    for frame in page.frames:  # viser's "software WebGL" notice would cover part of the scene in the screenshot
        if "/room-viewer/" in frame.url:
            frame.evaluate("() => document.querySelectorAll('.mantine-Notification-closeButton').forEach((b) => b.click())")
    let_webgl_draw(page, 4000)
    screenshot(page, shots / "classroom-projector.png")
    assert not errors, errors

    phone = browser.new_context(viewport={"width": 390, "height": 844})
    join = phone.new_page()
    join.goto(f"{live_server.url}/join")
    typed = "ABC234" if code != "ABC234" else "ABC235"  # a code no room has
    join.fill("#join-code", f"{typed[:3].lower()} {typed[3:]}")
    assert join.input_value("#join-code") == typed, "the code box keeps capitals and digits only"
    join.fill("#join-name", "Ada")
    screenshot(join, shots / "classroom-join-phone.png")
    join.click("#join-button")
    join.wait_for_function("() => document.getElementById('join-error').textContent !== ''", polling=100, timeout=15_000)
    assert f"No open room has the code {typed}" in join.text_content("#join-error")
    phone.close()
    for student in students:
        student.close()
    instructor.close()
