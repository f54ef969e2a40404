"""What an instructor and a student trip over in a room (issue 29), in a real browser against ``dynlab serve``.

- A room on a scene without ready questions of its own (the gyrocompass, the free gyroscope) offers its chapter's;
  one on a scene with its own lists those first, then the rest of its chapter's.
"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

from tests.browser.test_classroom_in_browser import NOT_DRAWING

pytestmark = pytest.mark.browser

LAPTOP = {"width": 1366, "height": 768}
POLLS_TOML = Path(__file__).resolve().parents[2] / "lessons" / "polls.toml"


def _chapter_questions(chapter: int) -> list[dict]:
    """The ready questions of ``chapter``, in the file's order."""
    questions = tomllib.loads(POLLS_TOML.read_text(encoding="utf-8"))["question"]
    return [q for q in questions if q["chapter"] == chapter]


def _instructor_room(browser, live_server, lesson: str, *, viewport=LAPTOP, drawing: bool = False):
    """An instructor's page that opened a room on ``lesson`` (its own scene); ``(context, page, errors, room_id)``.

    Unless ``drawing``, the page's viewer stays connected but is not laid out (it draws nothing)."""
    context = browser.new_context(viewport=viewport)
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


def _ready_offered(page) -> list[str]:
    """The ready questions the instructor's panel offers (their ids), once it has loaded them ([] for none)."""
    page.wait_for_function("() => !document.querySelector('#room-ready').options[0].text.startsWith('Loading')")
    return page.eval_on_selector_all("#room-ready option", "(options) => options.map((o) => o.value).filter(Boolean)")


def _close_room(page, live_server, room_id: str) -> None:
    page.request.delete(f"{live_server.url}/api/rooms/{room_id}")


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
