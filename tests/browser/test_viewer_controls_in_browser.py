"""The viewer is ours: viser's control panel hidden, its useful buttons (Reset view, Save image) under the scene,
and the camera driven from the keyboard.

The panel selectors are viser 1.1.1's (app/web/pages.py VIEWER_CSS): each test first finds the element they
hide, so a viser whose DOM changed fails here instead of showing its panel again. Camera poses are read from
the server (GET …/playback: the browser reports its camera to viser); a reset is compared with the scene's own
start pose to 1e-3 m, the browser's report being float32 (about 1e-7 m here) after a short animation.
"""

from __future__ import annotations

import io
import math
import os
import signal

import numpy as np
import pytest
from PIL import Image

from tests.browser.conftest import dismiss_webgl_notice, open_lesson, screenshot, wait_for_scene_drawn
from tests.conftest import wait_until

pytestmark = pytest.mark.browser

LESSON = "/lessons/1-1-vector-operations"  # the robot-arm cable: a scene that is not animated
SCENE = "robot-arm-cable"
CONTROL_PANEL_TAB = '[data-dock-tab="viser-control-panel"]'
BOTTOM_SHEET = "#root .mantine-Paper-root:not([data-floating-window]):has(> div > .mantine-ScrollArea-root)"
CANVAS = "canvas[data-engine]"


def viewer_frame(page):
    return page.locator("#viewer").element_handle().content_frame()


def camera(live_server, session_id) -> dict:
    answer = live_server.host.camera(session_id)
    assert answer is not None, "the viewer has not reported its camera"
    return {name: np.array(value) for name, value in answer.items()}


def start_pose(live_server, session_id) -> dict:
    """The scene's start pose (its class's: the robot arm's view does not depend on its parameters)."""
    from app.scenes import SCENES

    scene = SCENES[SCENE]
    assert "camera_view" not in vars(scene)
    return {"position": np.array(scene.camera_position), "look_at": np.array(scene.camera_look_at)}


def moved_from(pose: dict, live_server, session_id, *, by_m: float = 0.05) -> bool:
    now = camera(live_server, session_id)
    return max(np.linalg.norm(now[k] - pose[k]) for k in pose) > by_m


def at_pose(pose: dict, live_server, session_id, *, within_m: float = 1e-3) -> bool:
    now = camera(live_server, session_id)
    return all(np.allclose(now[k], pose[k], rtol=0, atol=within_m) for k in pose)


def hold(page, key: str, milliseconds: int) -> None:
    page.keyboard.down(key)
    page.wait_for_timeout(milliseconds)
    page.keyboard.up(key)


def test_viser_panel_is_hidden_and_the_scene_shows(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, LESSON)
    frame = viewer_frame(page)
    tab = frame.locator(CONTROL_PANEL_TAB)
    panel_shown: list[bool] = []  # viser draws its floating panel a second or more before the panel's tab exists

    def tab_found() -> bool:
        panel_shown.append(frame.get_by_text("Connected").is_visible())
        return tab.count() == 1

    wait_until(tab_found, 15, interval_s=0.02, what="viser's control panel tab, found by VIEWER_CSS's selector")
    assert not any(panel_shown), f"viser's panel showed in {sum(panel_shown)} of {len(panel_shown)} looks before its tab appeared"
    frame.wait_for_selector(CANVAS)
    assert not tab.is_visible() and not frame.get_by_text("Connected").is_visible()
    box = frame.locator(CANVAS).bounding_box()
    assert frame.locator(CANVAS).is_visible() and box["width"] > 300 and box["height"] > 200
    assert frame.evaluate("document.title") == "3D scene — Dynamics Lab"
    for name in ("Reset view", "Save image"):  # a scene that is not animated has them too
        assert page.get_by_role("button", name=name).is_visible()
    dismiss_webgl_notice(page)
    screenshot(page.locator("#viewer-wrap"), shots / "viewer-panel-hidden.png")
    assert errors == []
    context.close()

    # A viewer under 576 px wide: viser shows a bottom sheet instead (websocket URL, dev settings); hidden too.
    phone = browser.new_context(viewport={"width": 380, "height": 640})
    viewer = phone.new_page()
    viewer.goto(f"{live_server.url}/viewer/{SCENE}/{session_id}/")
    wait_until(lambda: live_server.host.viewer_count(session_id) >= 1, 30, what="the narrow viewer to connect")
    viewer.wait_for_selector(CANVAS)
    sheet = viewer.locator(BOTTOM_SHEET)
    wait_until(lambda: sheet.count() == 1, 10, what="viser's bottom sheet in the DOM")
    assert not sheet.is_visible() and not viewer.get_by_text("Connected").is_visible()
    assert viewer.locator(CANVAS).is_visible()
    phone.close()


def test_keyboard_orbits_and_zooms_and_reset_view_restores_the_start_pose(browser, live_server):
    # Every frame: viser moves the camera a step a frame while a key is held, and our zoom eases over frames.
    context, page, session_id, errors = open_lesson(browser, live_server, LESSON, viewer_frames_per_s=None)
    viewer_frame(page).wait_for_selector(CANVAS)
    wait_until(lambda: live_server.host.camera(session_id) is not None, 20, what="the viewer's first camera report")
    start = start_pose(live_server, session_id)
    wait_until(lambda: at_pose(start, live_server, session_id), 10, what="the viewer to start at the scene's pose")

    # The keys first, from the pose the viewer itself reported: after "Reset view" the server's copy of the camera is
    # the start pose at once, while the viewer may still be on its way there (under load a key pressed then was
    # undone when the reset landed).
    distance = np.linalg.norm(np.asarray(start["position"]) - np.asarray(start["look_at"]))
    page.locator("#viewer").focus()  # Tab into the scene: the keys go to the viewer's document
    page.keyboard.press("+")  # zoom in: 15 % closer to the point looked at, which stays
    wait_until(lambda: moved_from(start, live_server, session_id), 10, what="+ to zoom the camera in")
    zoom_ratio = lambda: np.linalg.norm(camera(live_server, session_id)["position"] - start["look_at"]) / distance  # noqa: E731
    wait_until(lambda: abs(zoom_ratio() - 0.85) < 1e-4, 10, what="the zoom to finish 15 % closer")
    zoomed = camera(live_server, session_id)
    np.testing.assert_allclose(zoomed["look_at"], start["look_at"], rtol=0, atol=1e-3)
    zoomed_distance = np.linalg.norm(zoomed["position"] - zoomed["look_at"])
    hold(page, "ArrowLeft", 700)
    wait_until(lambda: moved_from(zoomed, live_server, session_id), 10, what="the arrow key to orbit the camera")
    orbited = camera(live_server, session_id)
    np.testing.assert_allclose(orbited["look_at"], start["look_at"], rtol=0, atol=1e-3)  # orbiting keeps the target
    assert np.linalg.norm(orbited["position"] - orbited["look_at"]) == pytest.approx(zoomed_distance, rel=1e-3)  # and the distance

    page.get_by_role("button", name="Reset view").click()
    wait_until(lambda: at_pose(start, live_server, session_id), 10, what="Reset view to restore the start pose")

    page.locator("#viewer").focus()
    hold(page, "w", 400)  # W moves the camera and the point it looks at forward together
    wait_until(lambda: moved_from({"look_at": start["look_at"]}, live_server, session_id), 10, what="W to move the camera forward")
    page.keyboard.press("r")  # R, with the viewer focused, resets too
    wait_until(lambda: at_pose(start, live_server, session_id), 10, what="R to restore the start pose")
    assert errors == []
    context.close()


def test_save_image_downloads_a_png_of_the_view(browser, live_server):
    context, page, session_id, errors = open_lesson(browser, live_server, LESSON, viewer_frames_per_s=None, viewer_draws=True)
    viewer_frame(page).wait_for_selector(CANVAS)
    wait_for_scene_drawn(page)
    with page.expect_download() as download_info:
        page.get_by_role("button", name="Save image").click()
    download = download_info.value
    assert download.suggested_filename == f"{SCENE}.png"
    image = Image.open(io.BytesIO(open(download.path(), "rb").read()))
    assert image.format == "PNG" and image.width > 300 and image.height > 200
    pixels = np.asarray(image.convert("RGB"), dtype=float)
    # Not blank: the scene's bodies, lines and labels differ from the background over a visible share of the view.
    background = np.median(pixels.reshape(-1, 3), axis=0)
    drawn = np.mean(np.abs(pixels - background).sum(axis=2) > 30)
    assert drawn > 0.005, f"only {drawn:.2%} of the saved image differs from its background"
    assert math.isfinite(drawn) and errors == []
    context.close()


def test_a_viewer_reconnects_by_itself_after_its_scene_worker_is_killed(browser, live_server):
    # Found in issue 29's attack: viser's client retries only while its own document has the focus, so with the focus
    # on the lesson page (a student reading) the viewer of a restarted worker stayed disconnected for 40 s and more.
    context, page, session_id, errors = open_lesson(browser, live_server, LESSON)
    page.click("h1")  # the focus is the lesson page's, not the viewer's
    assert viewer_frame(page).evaluate("document.visibilityState") == "visible"
    assert page.evaluate("document.hasFocus()")
    before = live_server.app.worker_pids()
    for pid in before:
        os.kill(pid, signal.SIGKILL)
    wait_until(
        lambda: not set(live_server.app.worker_pids()) & set(before) and len(live_server.app.worker_pids()) == len(before),
        30,
        what="the killed scene workers to be replaced",
    )
    wait_until(lambda: live_server.host.viewer_count(session_id) == 1, 30, what="the viewer to reconnect by itself")
    assert not errors, errors
    context.close()
