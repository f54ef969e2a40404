"""The classroom in a real browser, several contexts at once: an instructor opens a room on the heavy-top
lesson, three students join it by its code and follow; the instructor's changes reach every student's page
within 200 ms; a student cannot change the room; explore gives each student their own scene; a poll's
answers reach the instructor's histogram. Screenshots go to docs/screenshots/ with DYNLAB_UPDATE_SCREENSHOTS=1."""

from __future__ import annotations

import re

import httpx
import pytest

from tests.browser.conftest import keeping_screenshots, let_webgl_draw, readout_quantity, room_followers, screenshot
from tests.conftest import wait_until

pytestmark = pytest.mark.browser


LESSON = "10-2-spinning-top"
SCENE = "heavy-top"
SPIN = "spin_rad_s"
#: The issue's acceptance: a student's scene and controls follow the instructor within 200 ms.
FOLLOW_LATENCY_MS = 200

# Records, in a student's page, when its controls and status line first show a change (Date.now(), ms): checked
# on every room message the page has applied, so the time is when the page showed it, not when the test looked.
WATCH = """([name, value]) => {
  window.seen = {};
  const check = () => {
    const now = Date.now();
    if (window.seen.value === undefined && Number(document.getElementById(`ctl-${name}`).value) === value) window.seen.value = now;
    if (window.seen.paused === undefined && document.querySelector(".room-status").textContent.includes("paused")) window.seen.paused = now;
  };
  document.addEventListener("dynlab:room", check);
}"""


# Four pages drawing viser's scene in software WebGL on this 2-core machine starve each page's main thread for
# seconds (a classroom's devices draw on a GPU). Each viewer stays connected and receives every frame, but is
# not laid out (display: none, so it draws nothing) except while a screenshot is taken.
NOT_DRAWING = """document.addEventListener("DOMContentLoaded", () => {
  const style = document.createElement("style");
  style.id = "test-not-drawing";
  style.textContent = "#viewer { display: none !important; }";
  document.head.append(style);
});"""


def _new_context(browser, viewport):
    context = browser.new_context(viewport={"width": viewport[0], "height": viewport[1]})
    context.add_init_script(NOT_DRAWING)
    return context


def _screenshot_with_scene(page, path) -> None:
    """Let ``page``'s viewer draw, keep a screenshot (only when screenshots are kept), then stop it drawing again."""
    if not keeping_screenshots():
        return
    page.evaluate("document.getElementById('test-not-drawing').disabled = true")
    let_webgl_draw(page, 4000)
    # viser's "software WebGL" notice would cover part of the scene (the room's viewer is /room-viewer/…).
    page.frame_locator("#viewer").locator(".mantine-Notification-closeButton").evaluate_all("(buttons) => buttons.forEach((b) => b.click())")
    screenshot(page, path)
    page.evaluate("document.getElementById('test-not-drawing').disabled = false")


def instructor_room(browser, live_server, lesson: str, *, viewport=None, drawing: bool = False):
    """An instructor's page that opened a room on ``lesson`` (its own scene); ``(context, page, errors, room_id)``.

    Unless ``drawing``, the page's viewer stays connected but is not laid out (it draws nothing)."""
    context = browser.new_context(viewport=viewport or {"width": 1366, "height": 768})
    if not drawing:
        context.add_init_script(NOT_DRAWING)
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda exc: errors.append(str(exc)))
    page.goto(live_server.instructor_link)
    page.goto(f"{live_server.url}/lessons/{lesson}")
    page.get_by_role("button", name="Start a class room here").click()
    page.wait_for_url(re.compile(r"\?room=[0-9a-f]{16}"))
    page.wait_for_function("() => document.querySelector('.room-code')?.textContent")  # the room's state arrived
    room_id = re.search(r"room=([0-9a-f]{16})", page.url).group(1)
    return context, page, errors, room_id


def _instructor(browser, live_server):
    context, page, errors, room_id = instructor_room(browser, live_server, LESSON, viewport={"width": 1500, "height": 1000})
    return context, page, errors, room_id, page.text_content(".room-code")


def _student(browser, live_server, code, viewport):
    context = _new_context(browser, viewport)
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda exc: errors.append(str(exc)))
    page.goto(f"{live_server.url}/join/{code}")
    page.click("#join-button")  # the QR code's address asks for an optional name first
    page.wait_for_url(re.compile(rf"/lessons/{LESSON}\?room=[0-9a-f]{{16}}"))
    page.wait_for_selector('.room-bar[data-mode="follow"]')
    return context, page, errors


def _room_state(live_server, room_id) -> dict:
    return httpx.get(f"{live_server.url}/api/rooms/{room_id}/state").json()


def _control(page, name=SPIN) -> float:
    return float(page.input_value(f"#ctl-{name}"))


def test_a_class_follows_explores_and_answers_a_poll(browser, live_server, shots):
    teacher_context, teacher, teacher_errors, room_id, code = _instructor(browser, live_server)
    assert len(code) == 6
    # One student on a laptop, two on phones.
    students = [_student(browser, live_server, code, viewport) for viewport in ((1280, 900), (390, 844), (390, 844))]
    pages = [page for _, page, _ in students]
    presence = ".room-presence[data-connected='3'][data-following='3']"
    teacher.wait_for_selector(presence)

    # Following: the room's one scene in every viewer, the controls locked, the room's readout from the socket.
    for page in pages:
        assert page.get_attribute("#viewer", "src") == f"/room-viewer/{room_id}/?hideViserLogo"
        assert page.locator(f"#ctl-{SPIN}").is_disabled()
        assert "Following the instructor" in page.text_content(".room-banner")
        page.wait_for_selector('#readout [data-quantity="t_s"]')
    assert teacher.get_attribute("#viewer", "src") == f"/room-viewer/{room_id}/?hideViserLogo"
    t_before = readout_quantity(pages[0], "t_s")
    wait_until(lambda: readout_quantity(pages[0], "t_s") > t_before, 5, what="the room's scene time to advance while playing")
    # Every viewer is connected to the room's one stream: three students and the instructor.
    wait_until(lambda: room_followers(live_server, room_id) == 4, 30, what="four viewers to follow the room's scene")
    _screenshot_with_scene(teacher, shots / "classroom-instructor.png")
    _screenshot_with_scene(pages[0], shots / "classroom-student-following.png")

    # The instructor sets the spin, then pauses; each action shows on every student's page within 200 ms of it.
    for page in pages:
        page.evaluate(WATCH, [SPIN, 120])
    changed = teacher.evaluate(
        """() => {
          const box = document.getElementById("ctl-spin_rad_s");
          box.value = "120";
          const sent = Date.now();
          box.dispatchEvent(new Event("change"));
          return sent;
        }"""
    )
    for page in pages:
        page.wait_for_function("window.seen.value !== undefined", timeout=5000)
    paused = teacher.evaluate("""() => { const sent = Date.now(); document.querySelector('[data-room="play"]').click(); return sent; }""")
    for page in pages:
        page.wait_for_function("window.seen.paused !== undefined", timeout=5000)
        seen = page.evaluate("window.seen")
        assert seen["value"] - changed < FOLLOW_LATENCY_MS, (seen, changed)
        assert seen["paused"] - paused < FOLLOW_LATENCY_MS, (seen, paused)
        assert page.locator(f"#ctl-{SPIN}").is_disabled()
        assert "paused by the instructor" in page.text_content(".room-status")
    state = _room_state(live_server, room_id)
    assert state["params"][SPIN] == 120 and state["playing"] is False
    # Paused: the room's scene time stops (readouts come twice a second; one in flight may still be later).
    teacher.wait_for_timeout(1200)
    frozen = [readout_quantity(page, "t_s") for page in pages]
    teacher.wait_for_timeout(1200)
    assert [readout_quantity(page, "t_s") for page in pages] == frozen

    # A student cannot change the room, by request or by socket; nothing changes.
    student = pages[0]
    status = student.evaluate(
        """async (roomId) => (await fetch(`/api/rooms/${roomId}/state`, {
          method: "POST", headers: {"Content-Type": "application/json"}, body: JSON.stringify({playing: true}),
        })).status""",
        room_id,
    )
    assert status == 403
    for action in (
        {"type": "set_state", "playing": True, "params": {SPIN: 5}},
        {"type": "open_poll", "question": "Mine?", "kind": "number", "unit": "rad/s"},
        {"type": "update_poll", "poll_id": "p1", "open": False},
    ):
        refusal = student.evaluate(
            """async (action) => {
              const room = (await import('/static/js/room.js')).classroom;
              return new Promise((resolve) => {
              document.addEventListener("dynlab:room", (e) => { if (e.detail.type === "error") resolve(e.detail); });
              room.send(action);
            }); }""",
            action,
        )
        assert refusal["status"] == 403, refusal
    after = _room_state(live_server, room_id)
    assert (after["revision"], after["params"], after["playing"], after["poll"]) == (state["revision"], state["params"], False, None)

    # Following, the class's scene is the instructor's: no time controls, recording or graphs on a student's page.
    for page in pages:
        assert page.locator(".time-controls").is_hidden() and page.locator(".recording-controls").is_hidden()
        assert page.locator("#graphs").is_hidden()

    # Explore: each student gets their own scene, started from the room's (spin 120 rad/s).
    teacher.get_by_role("button", name="Let everyone explore").click()
    sessions = []
    for page in pages:
        page.wait_for_selector('.room-bar[data-mode="explore"]')
        session_id = page.evaluate("async () => (await import('/static/js/lesson.js')).lesson.session.id")
        assert page.get_attribute("#viewer", "src") == f"/viewer/{SCENE}/{session_id}/?hideViserLogo"
        assert not page.locator(f"#ctl-{SPIN}").is_disabled()
        assert _control(page) == 120
        sessions.append(session_id)
    assert len(set(sessions)) == 3
    for session_id in sessions:
        assert live_server.host.session_params(session_id)[SPIN] == 120
    teacher.wait_for_selector(".room-presence[data-following='0']")
    pages[0].fill(f"#ctl-{SPIN}", "30")
    pages[0].dispatch_event(f"#ctl-{SPIN}", "change")
    wait_until(lambda: live_server.host.session_params(sessions[0])[SPIN] == 30, 10, what="student B's own scene to take spin 30")
    assert live_server.host.session_params(sessions[1])[SPIN] == 120
    assert _control(pages[1]) == 120 and _control(pages[2]) == 120
    assert _room_state(live_server, room_id)["params"][SPIN] == 120

    # Exploring, a student's own scene has its time controls, graphs and recording (issue 29, item 5), and they act
    # on that scene alone: student B pauses theirs, and the room and the other students play on.
    explorer = pages[0]
    for page in pages:
        page.wait_for_selector(".time-controls", state="visible")
        page.wait_for_selector(".recording-controls .rec-save", state="visible")
        page.wait_for_selector("#graphs > summary", state="visible")
    playing = [live_server.host.playback(session_id)["playing"] for session_id in sessions]
    room_playing = _room_state(live_server, room_id)["playing"]
    # viser's client connects only when laid out: B's viewer is shown (drawing at the test's slow frame rate).
    explorer.evaluate("document.getElementById('test-not-drawing').disabled = true")
    wait_until(lambda: live_server.host.viewer_count(sessions[0]) == 1, 30, what="student B's own viewer to connect")
    explorer.wait_for_selector(f'.tc-play[data-playing="{str(playing[0]).lower()}"]')
    explorer.click(".tc-play")
    explorer.wait_for_selector(f'.tc-play[data-playing="{str(not playing[0]).lower()}"]')
    wait_until(lambda: live_server.host.playback(sessions[0])["playing"] is not playing[0], 10, what="student B's play state to toggle")
    assert [live_server.host.playback(session_id)["playing"] for session_id in sessions[1:]] == playing[1:]
    assert _room_state(live_server, room_id)["playing"] is room_playing
    if playing[0]:  # B's scene is paused now: played again, its graph grows
        explorer.click(".tc-play")
        explorer.wait_for_selector('.tc-play[data-playing="true"]')
    explorer.click("#graphs > summary")
    explorer.wait_for_selector("#graph-y1 option[value='theta']", state="attached", timeout=15_000)
    explorer.wait_for_function("() => Number(document.querySelector('#graphs .time-graph').dataset.points) > 10", timeout=30_000)
    assert explorer.evaluate(
        "async () => (await fetch(document.querySelector('#graphs .graph-csv').href)).status"
    ) == 200
    recording = explorer.evaluate(
        "async (sid) => { const r = await fetch(`/api/scenes/heavy-top/sessions/${sid}/recording.html?seconds=5`);"
        " return [r.status, (await r.text()).length]; }",
        sessions[0],
    )
    assert recording[0] == 200 and recording[1] > 10_000, recording
    explorer.evaluate("document.getElementById('test-not-drawing').disabled = false")

    # Back to follow: locked again, the room's viewer and values.
    teacher.get_by_role("button", name="Bring everyone back").click()
    for page in pages:
        page.wait_for_selector('.room-bar[data-mode="follow"]')
        assert page.get_attribute("#viewer", "src") == f"/room-viewer/{room_id}/?hideViserLogo"
        assert page.locator(f"#ctl-{SPIN}").is_disabled()
    wait_until(lambda: _control(pages[0]) == 120, 5, what="student B's controls to show the room's spin again")
    teacher.wait_for_selector(presence)
    for page in pages:
        assert page.locator(".time-controls").is_hidden() and page.locator(".recording-controls").is_hidden()
        assert page.locator("#graphs").is_hidden()

    # A poll: a ready number question in rad/s; three answers reach the instructor's histogram.
    teacher.select_option("#room-ready", "heavy-top-sleeping-threshold")
    teacher.click('[data-room="ask-ready"]')
    for page, answer in zip(pages, ("10", "20", "35"), strict=True):
        page.wait_for_selector(".room-poll:not([hidden]) input[type=number]")
        assert "rad/s" in page.text_content(".room-poll-number")
        page.fill(".room-poll input[type=number]", answer)
        page.click(".room-poll-send")
        page.wait_for_selector(f".room-poll-mine:has-text('Your answer: {answer} rad/s')")
    teacher.wait_for_selector(".room-results-count[data-answers='3']")
    counts = teacher.evaluate("[...document.querySelectorAll('.room-histogram li[data-count]')].map((li) => Number(li.dataset.count))")
    assert sum(counts) == 3
    screenshot(teacher.locator(".room-panel"), shots / "classroom-poll-histogram.png")
    teacher.click('[data-room="reveal"]')
    for page in pages:
        page.wait_for_selector(".room-poll-revealed:not([hidden])")
        assert "computed by the scene" in page.text_content(".room-poll-revealed")
        assert page.locator(".room-poll-send").is_disabled()

    # The instructor moves on to the next lesson (its link keeps the room): every student's page follows.
    teacher.click(".prevnext a.next")
    teacher.wait_for_url(re.compile(rf"/lessons/(?!{LESSON})[^?]+\?room={room_id}"))
    next_lesson = teacher.evaluate("JSON.parse(document.getElementById('dynlab-config').textContent).lesson_id")
    for page in pages:
        page.wait_for_url(re.compile(rf"/lessons/{next_lesson}\?room={room_id}"))
        page.wait_for_selector(".room-bar .room-banner")
    assert _room_state(live_server, room_id)["lesson_id"] == next_lesson

    assert not teacher_errors, teacher_errors
    for context, _, errors in students:
        assert not errors, errors
        context.close()
    teacher_context.close()
