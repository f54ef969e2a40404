"""Acceptance (issue 15): a recording plays with the server stopped.

The heavy top plays for a few seconds; "Save recording" (last 5 s) downloads one HTML file through the page.
That file is then opened by ``file://`` in a fresh browser context that cannot reach any server: the context is
offline, and every http(s) request and every websocket it tries is aborted (and counted: the recording must not
even try). The viewer must draw (the canvas's screenshot is not blank) and its playback bar must show time
advancing over the recording's 5 s.
"""

from __future__ import annotations

import io
import re
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from app.scenes.host.interface import SLOW_ANSWER_S
from tests.browser.conftest import let_webgl_draw, open_lesson, screenshot
from tests.conftest import wait_until

pytestmark = pytest.mark.browser
LESSON = "/lessons/10-2-spinning-top"
SECONDS = 5.0
FRAME_S = 1.0 / 30.0
AXE = Path(__file__).resolve().parents[2] / "static" / "vendor" / "axe-core" / "axe.min.js"
#: axe-core's violations (rule id, impact) inside the page's recording controls.
AXE_ON_RECORDING_CONTROLS = """async () => (await axe.run({ include: [['.recording-controls']] }, { resultTypes: ['violations'] }))
  .violations.map((v) => [v.id, v.impact])"""


def playback_times(page) -> tuple[float, float]:
    """viser's playback bar: (time now, recording length) in s, read from its slider."""
    now, length = page.eval_on_selector("[role=slider]", "(el) => [el.getAttribute('aria-valuenow'), el.getAttribute('aria-valuemax')]")
    return float(now), float(length)


def test_a_saved_recording_plays_offline_with_no_server(browser, live_server, tmp_path, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, LESSON)
    wait_until(lambda: live_server.host.motion_state(session_id)["t_s"] > SECONDS + 0.5, timeout_s=30, what="the top to play 5 s")
    page.select_option(".rec-seconds", str(int(SECONDS)))
    # The worker may take up to SLOW_ANSWER_S to answer a recording (then 503): wait for that answer, with room for a
    # busy browser to turn it into a download (CI timed out once at 30 s with nothing in the server's log).
    with page.expect_download(timeout=(SLOW_ANSWER_S + 15.0) * 1000) as download_info:
        page.click(".rec-save")
    download = download_info.value
    assert download.suggested_filename == "heavy-top-recording.html"
    saved = tmp_path / download.suggested_filename
    download.save_as(saved)
    page.wait_for_selector('.rec-status[data-state="saved"]')
    assert "offline" in page.inner_text(".rec-status")
    page.add_script_tag(path=str(AXE))
    violations = page.evaluate(AXE_ON_RECORDING_CONTROLS)
    assert not [v for v in violations if v[1] in ("serious", "critical")], violations
    page.locator(".recording-controls").screenshot(path=str(tmp_path / "controls.png"))
    assert errors == []
    context.close()

    offline = browser.new_context(viewport={"width": 1200, "height": 760})
    attempts: list[str] = []
    offline.set_offline(True)
    offline.route(re.compile(r"^(https?|wss?)://"), lambda route: (attempts.append(route.request.url), route.abort()))
    offline.route_web_socket(re.compile(".*"), lambda ws: (attempts.append(ws.url), ws.close()))
    player = offline.new_page()
    player_errors: list[str] = []
    player.on("pageerror", lambda exc: player_errors.append(str(exc)))
    player.goto(saved.as_uri())
    player.wait_for_selector("canvas", timeout=30_000)
    player.wait_for_selector("[role=slider]", state="attached", timeout=30_000)  # the thumb shows on hover only
    _, length = playback_times(player)
    assert length == pytest.approx(SECONDS, abs=FRAME_S)

    seen: list[float] = []

    def advanced() -> bool:  # sampled a second apart: software WebGL plays slowly, and the recording loops
        seen.append(playback_times(player)[0])
        return any(later > earlier + 0.2 for earlier, later in zip(seen, seen[1:]))

    try:
        wait_until(advanced, timeout_s=45, interval_s=1.0, what="the recording's playback time to advance")
    except AssertionError:
        raise AssertionError(f"the recording's playback time did not advance: read {seen} s, a second apart") from None
    assert all(0.0 <= t <= length + 1e-9 for t in seen)

    player.evaluate("() => document.querySelectorAll('.mantine-Notification-closeButton').forEach((b) => b.click())")
    pixels = np.asarray(Image.open(io.BytesIO(player.locator("canvas").first.screenshot())).convert("L"), float)
    assert pixels.std() > 10.0, "the recording's canvas is blank"  # a uniform picture has std 0; the top, grid and labels give far more
    assert attempts == [] and player_errors == []
    let_webgl_draw(player, 1000)
    screenshot(player, shots / "recording-playing.png")
    offline.close()
