"""What an instructor and a student trip over in a room (issue 29), in a real browser against ``dynlab serve``.

- A room on a scene without ready questions of its own (the gyrocompass, the free gyroscope) offers its chapter's;
  one on a scene with its own lists those first, then the rest of its chapter's.
- The instructor's own question carries an optional answer (the right choice, or a number in the poll's unit) that
  Reveal shows; a bad answer is a clear 422 whichever way it is sent, and the form shows the server's refusal in its
  own error line; a poll without one still says so; the panel's errors go once a later action is taken.
- At 1366×768 the instructor's 3D scene and the room panel (code, playback, ready questions) are in view together
  without scrolling; the page still fits a phone, and projector mode still gives the scene most of the width.
- A phone following the room passes axe-core (colour contrast included) while its controls are locked, and they
  still look locked.

Screenshots (docs/screenshots/, with DYNLAB_UPDATE_SCREENSHOTS=1): the instructor's room page at 1366×768 and a phone
following a room.
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

from tests.browser.conftest import keeping_screenshots, let_webgl_draw, screenshot, wait_for_math
from tests.browser.test_accessibility_in_browser import _failing, _report, run_axe
from tests.browser.test_classroom_in_browser import instructor_room as _instructor_room

pytestmark = pytest.mark.browser

LAPTOP = {"width": 1366, "height": 768}
PHONE = {"width": 375, "height": 812}
PROJECTOR = {"width": 1920, "height": 1080}
POLLS_TOML = Path(__file__).resolve().parents[2] / "lessons" / "polls.toml"
#: Sub-pixel layout: a box may end this far past the edge from rounding alone.
ROUNDING_PX = 1.0
#: Projector mode on the instructor's page: the scene's share of a 1920 px wide screen at least.
PROJECTOR_VIEWER_SHARE = 0.5
#: An error the instructor's panel shows is gone this soon after a later action is taken (it times out after 10 s).
ERROR_CLEARED_MS = 5000


def _chapter_questions(chapter: int) -> list[dict]:
    """The ready questions of ``chapter``, in the file's order."""
    questions = tomllib.loads(POLLS_TOML.read_text(encoding="utf-8"))["question"]
    return [q for q in questions if q["chapter"] == chapter]


def _ready_offered(page) -> list[str]:
    """The ready questions the instructor's panel offers (their ids), once it has loaded them ([] for none)."""
    page.wait_for_function("() => !document.querySelector('#room-ready').options[0].text.startsWith('Loading')")
    return page.eval_on_selector_all("#room-ready option", "(options) => options.map((o) => o.value).filter(Boolean)")


def _close_room(page, live_server, room_id: str) -> None:
    page.request.delete(f"{live_server.url}/api/rooms/{room_id}")


def _keep_screenshot(page, path: Path) -> None:
    """When screenshots are kept: let the room's viewer draw, close viser's "software WebGL" notice, keep ``path``."""
    if not keeping_screenshots():
        return
    let_webgl_draw(page, 4000)
    page.frame_locator("#viewer").locator(".mantine-Notification-closeButton").evaluate_all("(buttons) => buttons.forEach((b) => b.click())")
    screenshot(page, path)


# ---- 1. every scene of a chapter offers its chapter's ready questions -----------------------------------------------
def test_a_room_on_a_scene_without_its_own_questions_offers_its_chapters(browser, live_server):
    chapter_10 = [q["id"] for q in _chapter_questions(10)]
    assert len(chapter_10) >= 3 and not {"gyrocompass", "free-gyroscope"} & {q["scene"] for q in _chapter_questions(10)}
    context, page, errors, room_id = _instructor_room(browser, live_server, "10-3-gyrocompass")
    offered = _ready_offered(page)
    assert offered == chapter_10, offered
    assert not page.locator('[data-room="ask-ready"]').is_disabled()

    # The room moves to the free gyroscope (another lesson of the chapter): this page follows and offers the same.
    moved = page.request.post(
        f"{live_server.url}/api/rooms/{room_id}/state", data={"lesson_id": "10-3-free-gyroscope", "scene_id": "free-gyroscope"}
    )
    assert moved.status == 200, moved.text()
    page.wait_for_url(re.compile(r"/lessons/10-3-free-gyroscope\?room="))
    page.wait_for_function("() => document.querySelector('.room-code')?.textContent")
    assert _ready_offered(page) == chapter_10

    # Asking one of them takes the class to its scene, where that scene's own questions come first.
    page.select_option("#room-ready", "equinox-precession-period")
    page.click('[data-room="ask-ready"]')
    page.wait_for_url(re.compile(r"scene=equinox-precession"))
    page.wait_for_function("() => document.querySelector('.room-code')?.textContent")
    offered = _ready_offered(page)
    own = [q["id"] for q in _chapter_questions(10) if q["scene"] == "equinox-precession"]
    assert offered == own + [i for i in chapter_10 if i not in own], offered
    page.wait_for_selector(".room-results:not([hidden])")
    state = page.request.get(f"{live_server.url}/api/rooms/{room_id}/state").json()
    assert state["scene_id"] == "equinox-precession" and state["poll"]["open"], state
    _close_room(page, live_server, room_id)
    assert not errors, errors
    context.close()


# ---- 2. the instructor's own question can carry its answer --------------------------------------------------------
def _ask_own(page, question: str, kind: str, *, choices: str = "", unit: str = "", answer: str | None = None) -> None:
    """Fill in and send the panel's own-question form; ``answer`` is the right choice's text or the number."""
    details = page.locator(".room-polls details")
    if not details.evaluate("(d) => d.open"):
        details.locator("summary").click()
    page.fill("#room-own-question", question)
    page.select_option("#room-own-kind", kind)
    if kind == "choice":
        page.fill("#room-own-choices", choices)
        page.select_option("#room-own-answer-choice", label=answer or "No answer given")
    else:
        page.fill("#room-own-unit", unit)
        page.fill("#room-own-answer-value", answer or "")
    page.click('[data-room="ask-own"]')
    page.wait_for_function(
        "(q) => document.querySelector('.room-results:not([hidden]) .room-results-question')?.textContent.startsWith(q)", arg=question
    )


def _revealed(page) -> str:
    page.click('[data-room="reveal"]')
    page.wait_for_selector(".room-results-revealed:not([hidden])")
    return page.text_content(".room-results-revealed")


def test_the_instructors_own_question_reveals_the_answer_they_gave(browser, live_server):
    context, page, errors, room_id = _instructor_room(browser, live_server, "10-2-spinning-top")
    state_url = f"{live_server.url}/api/rooms/{room_id}/state"

    # A choice poll: the right choice is picked from the choices typed above it.
    _ask_own(page, "Which way does the top's axis go first?", "choice", choices="Up\nDown\nSideways", answer="Sideways")
    assert page.eval_on_selector_all("#room-own-answer-choice option", "(os) => os.map((o) => o.text)")[1:] == ["Up", "Down", "Sideways"]
    assert _revealed(page) == "Answer: Sideways — given by the instructor"
    revealed = page.request.get(state_url).json()["poll"]["revealed"]  # what every student's page is sent
    assert revealed["choice"] == 2 and revealed["source"] == "given by the instructor", revealed

    # A number poll: the value, in the poll's unit.
    _ask_own(page, "How long until it has turned once about the vertical?", "number", unit="s", answer="2.5")
    assert _revealed(page) == "Answer: 2.50 s — given by the instructor"  # to three significant digits, as every answer
    revealed = page.request.get(state_url).json()["poll"]["revealed"]
    assert (revealed["value"], revealed["unit"]) == (2.5, "s"), revealed

    # The server's refusal (an answer over 1e12) shows in the form's own error line, not the panel's, and asks nothing;
    # a later action the room takes (reopening the poll) clears it.
    page.fill("#room-own-question", "And for ten turns?")
    page.fill("#room-own-answer-value", "1e13")
    page.click('[data-room="ask-own"]')
    page.wait_for_selector(".room-own-error:not([hidden])")
    assert "answer_value" in page.text_content(".room-own-error") and page.locator(".room-panel .room-error").is_hidden()
    assert page.request.get(state_url).json()["poll"]["question"].startswith("How long")
    page.click('[data-room="close-poll"]')
    page.wait_for_selector(".room-own-error", state="hidden", timeout=ERROR_CLEARED_MS)

    # Something typed in the answer box that is not a number is not sent as "no answer": the form says so.
    page.fill("#room-own-question", "And the next turn?")
    page.fill("#room-own-answer-value", "")
    page.locator("#room-own-answer-value").press_sequentially("1e")
    page.click('[data-room="ask-own"]')
    page.wait_for_selector(".room-own-error:not([hidden])")
    assert "type a number" in page.text_content(".room-own-error")
    assert page.request.get(state_url).json()["poll"]["question"].startswith("How long")

    # Without an answer: Reveal still says, in words, that there is none to show, and shows nothing.
    _ask_own(page, "Did you expect that?", "choice", choices="Yes\nNo")
    page.click('[data-room="reveal"]')
    page.wait_for_selector(".room-panel .room-error:not([hidden])")
    assert "no answer to show" in page.text_content(".room-panel .room-error")
    assert page.locator(".room-results-revealed").is_hidden()
    assert page.request.get(state_url).json()["poll"]["revealed"] is None
    # A later action the room takes (names shown) clears the panel's error, well before it would time out.
    page.check("#room-show-names")
    page.wait_for_selector(".room-panel .room-error", state="hidden", timeout=ERROR_CLEARED_MS)

    # A bad answer is a 422 naming the field, by request or on the room socket, and opens no poll.
    polls = f"{live_server.url}/api/rooms/{room_id}/polls"
    choice = {"question": "Q?", "kind": "choice", "choices": ["a", "b"]}
    number = {"question": "Q?", "kind": "number", "unit": "s"}
    for body, field in (
        (choice | {"answer_choice": 2}, "answer_choice"),
        (choice | {"answer_choice": "1"}, "answer_choice"),
        (choice | {"answer_value": 1.0}, "answer_value"),
        (number | {"answer_value": "2.5"}, "answer_value"),
        (number | {"answer_value": True}, "answer_value"),
        (number | {"answer_value": 1e13}, "answer_value"),
        (number | {"answer_choice": 0}, "answer_choice"),
    ):
        answer = page.request.post(polls, data=body)
        assert answer.status == 422 and field in answer.text(), (body, answer.status, answer.text())
    refusal = page.evaluate(
        """async (action) => {
          const room = (await import('/static/js/room.js')).classroom;
          return new Promise((resolve) => {
            document.addEventListener("dynlab:room", (e) => { if (e.detail.type === "error") resolve(e.detail); });
            room.send(action);
          });
        }""",
        {"type": "open_poll", **choice, "answer_choice": 5},
    )
    assert refusal["status"] == 422 and "answer_choice" in refusal["detail"], refusal
    assert page.request.get(state_url).json()["poll"]["question"] == "Did you expect that?"
    _close_room(page, live_server, room_id)
    assert not errors, errors
    context.close()


# ---- 3. the instructor's scene and room panel in view together at 1366×768 ------------------------------------------
#: Boxes (px, in the window) of what the instructor needs at once, and how far the page and the live column scrolled.
INSTRUCTOR_BOXES = """() => {
  const box = (selector) => {
    const el = document.querySelector(selector);
    if (!el) return null;
    const r = el.getBoundingClientRect();
    return { left: r.left, right: r.right, top: r.top, bottom: r.bottom, width: r.width, height: r.height };
  };
  const live = document.querySelector('.lesson-live');
  return {
    scrolled: window.scrollY + live.scrollTop + (document.querySelector('.room-panel')?.scrollTop || 0),
    scroll_width: document.documentElement.scrollWidth,
    viewer: box('#viewer'),
    panel: box('.room-panel'),
    parts: {
      code: box('.room-code'), play: box('[data-room="play"]'), mode: box('[data-room="mode"]'),
      ready: box('#room-ready'), ask: box('[data-room="ask-ready"]'),
    },
    first_control: box('#control-list input'),
  };
}"""


def _in_view(box: dict, viewport: dict) -> bool:
    return (
        box["width"] > 0 and box["height"] > 0
        and box["left"] >= -ROUNDING_PX and box["top"] >= -ROUNDING_PX
        and box["right"] <= viewport["width"] + ROUNDING_PX and box["bottom"] <= viewport["height"] + ROUNDING_PX
    )


def _overlap(a: dict, b: dict) -> bool:
    return a["left"] < b["right"] - ROUNDING_PX and b["left"] < a["right"] - ROUNDING_PX and a["top"] < b["bottom"] - ROUNDING_PX and b["top"] < a["bottom"] - ROUNDING_PX


def test_at_1366x768_the_instructor_sees_the_scene_and_the_room_panel_together(browser, live_server, shots):
    context, page, errors, room_id = _instructor_room(browser, live_server, "10-2-spinning-top", drawing=True)
    page.wait_for_selector("#viewer-wrap:not([hidden])")
    _ready_offered(page)
    boxes = page.evaluate(INSTRUCTOR_BOXES)
    assert boxes["scrolled"] == 0, boxes
    assert _in_view(boxes["viewer"], LAPTOP), boxes["viewer"]
    assert boxes["viewer"]["height"] >= 250 and boxes["viewer"]["width"] >= 450, boxes["viewer"]
    hidden = {name: box for name, box in boxes["parts"].items() if box is None or not _in_view(box, LAPTOP)}
    assert not hidden, (hidden, boxes["viewer"])
    assert not _overlap(boxes["viewer"], boxes["panel"]), boxes
    assert _in_view(boxes["first_control"], LAPTOP), boxes["first_control"]  # the scene and what drives it
    assert boxes["scroll_width"] <= LAPTOP["width"], boxes
    _keep_screenshot(page, shots / "classroom-instructor-laptop.png")

    # Projector mode (Alt+L) on a projector: the scene still takes most of the width, the panel stays in view.
    page.set_viewport_size(PROJECTOR)
    page.click("#large-text")
    page.wait_for_selector('#large-text[aria-pressed="true"]')
    boxes = page.evaluate(INSTRUCTOR_BOXES)
    assert boxes["viewer"]["width"] >= PROJECTOR_VIEWER_SHARE * PROJECTOR["width"], boxes["viewer"]
    assert _in_view(boxes["viewer"], PROJECTOR) and _in_view(boxes["parts"]["play"], PROJECTOR), boxes
    page.click("#large-text")
    page.wait_for_selector('#large-text[aria-pressed="false"]')

    # A phone: one column, nothing wider than the screen, the room panel and then the scene first.
    page.set_viewport_size(PHONE)
    boxes = page.evaluate(INSTRUCTOR_BOXES)
    assert boxes["scroll_width"] <= PHONE["width"], boxes
    text_top = page.evaluate("document.querySelector('.lesson-text').getBoundingClientRect().top")
    assert boxes["panel"]["top"] < boxes["viewer"]["top"] < text_top, (boxes, text_top)
    _close_room(page, live_server, room_id)
    assert not errors, errors
    context.close()


# ---- 4. a phone following the room: locked controls that pass axe-core -------------------------------------------
def test_a_phone_following_the_room_passes_axe_with_its_controls_locked(browser, live_server, shots):
    http = live_server.host.http
    created = http.post("/api/rooms", json={"lesson_id": "10-2-spinning-top", "scene_id": "heavy-top"}, headers=live_server.app.instructor_headers)
    assert created.status_code == 200, created.text
    room_id, code = created.json()["room_id"], created.json()["code"]
    context = browser.new_context(viewport=PHONE, is_mobile=True, has_touch=True)
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda exc: errors.append(str(exc)))
    page.goto(f"{live_server.url}/join/{code}")
    page.click("#join-button")
    page.wait_for_url(re.compile(rf"\?room={room_id}"))
    page.wait_for_selector('.room-bar[data-mode="follow"]')
    page.wait_for_selector(".controls.locked .control .desc")
    page.wait_for_selector('#readout [data-quantity="t_s"]')
    assert page.locator("#control-list input").first.is_disabled()
    assert page.locator(".controls-locked").is_visible()

    wait_for_math(page)  # a wide equation's box is made focusable once typeset (an idle-time race otherwise)
    # static/js/scroll_boxes.js marks overflowing boxes on the next animation frame after a change.
    page.evaluate("() => new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done)))")
    violations = run_axe(page)
    _report("a phone following a room", violations)
    contrast = [v for v in violations if v["id"] == "color-contrast"]
    assert not contrast, contrast
    assert not _failing(violations), violations

    # Still visibly locked: a locked row and its boxes look different from the same row unlocked.
    looks = page.evaluate(
        """() => {
          const form = document.getElementById('controls'), row = form.querySelector('.control');
          const look = () => {
            const r = getComputedStyle(row), box = getComputedStyle(row.querySelector('input'));
            return [r.opacity, r.backgroundColor, box.opacity].join(' | ');
          };
          const locked = look();
          form.classList.remove('locked');
          const unlocked = look();
          form.classList.add('locked');
          return [locked, unlocked];
        }"""
    )
    assert looks[0] != looks[1], looks
    page.evaluate("window.scrollTo(0, 0)")
    _keep_screenshot(page, shots / "classroom-student-phone-following.png")
    page.evaluate("document.getElementById('controls').scrollIntoView()")
    screenshot(page, shots / "classroom-student-phone-locked-controls.png")
    http.delete(f"/api/rooms/{room_id}", headers=live_server.app.instructor_headers)
    assert not errors, errors
    context.close()
