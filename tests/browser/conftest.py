"""A real server on a free loopback port and Debian's Chromium driven by Playwright."""

from __future__ import annotations

import json
import os
import socket
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
import uvicorn

from app.main import create_app
from app.settings import Settings
from tests.conftest import wait_until

CHROMIUM = "/usr/bin/chromium"
CHROMIUM_ARGS = (
    "--no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking "
    "--disable-component-update --disable-sync --enable-unsafe-swiftshader --use-gl=angle --use-angle=swiftshader"
).split()
RESULTS = Path(__file__).resolve().parents[2] / "test-results"
SCREENSHOTS = Path(__file__).resolve().parents[2] / "docs" / "screenshots"


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class LiveServer:
    def __init__(self) -> None:
        self.port = _free_port()
        self.app = create_app(Settings(port=self.port))
        config = uvicorn.Config(self.app, host="127.0.0.1", port=self.port, log_level="warning")
        self.server = uvicorn.Server(config)
        self.thread = threading.Thread(target=self.server.run, daemon=True)

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    @property
    def host(self):
        return self.app.state.scene_host

    def __enter__(self) -> "LiveServer":
        self.thread.start()
        deadline = time.monotonic() + 20
        while not self.server.started:
            if time.monotonic() > deadline:
                raise RuntimeError("server did not start within 20 s")
            time.sleep(0.05)
        return self

    def __exit__(self, *exc: object) -> None:
        self.server.should_exit = True
        self.thread.join(timeout=10)


@pytest.fixture(scope="session")
def live_server() -> Iterator[LiveServer]:
    with LiveServer() as server:
        yield server


@pytest.fixture(scope="session")
def browser():
    if not Path(CHROMIUM).exists():
        pytest.fail(f"{CHROMIUM} is missing: run the README's test command (tests/run.sh), which installs it")
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        yield browser
        browser.close()


@pytest.fixture
def shots() -> Path:
    """Where screenshots go: docs/screenshots when DYNLAB_UPDATE_SCREENSHOTS=1, else test-results/."""
    target = SCREENSHOTS if os.environ.get("DYNLAB_UPDATE_SCREENSHOTS") == "1" else RESULTS
    target.mkdir(parents=True, exist_ok=True)
    return target


def open_lesson(browser, live_server, path: str, *, viewport=(1500, 1000), context=None, viewer: bool = True, timeout_s: float = 40.0):
    """Open ``path`` (e.g. ``/lessons/3-1-rotation-sequences``) in a new page; returns ``(context, page, session_id, errors)``.

    A new browser context of ``viewport`` (width, height) px is made unless ``context`` is given.
    ``errors`` collects the page's uncaught JavaScript errors. With ``viewer`` it waits on the
    server's own client list until the lesson's 3D viewer has connected through the relay.
    """
    context = context or browser.new_context(viewport={"width": viewport[0], "height": viewport[1]})
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda exc: errors.append(str(exc)))
    page.goto(live_server.url + path)
    page.wait_for_function("window.dynlabLesson !== undefined")
    session_id = page.evaluate("window.dynlabLesson.session.id")
    if viewer:
        wait_until(lambda: live_server.host.viewer_count(session_id) == 1, timeout_s, what="the 3D viewer to connect through the relay")
    return context, page, session_id, errors


def readout_values(page) -> dict:
    """Every readout cell as {quantity: value}, read in one JavaScript call: the page rebuilds the
    table about once a second, so reading cells one round trip at a time could mix two instants."""
    return page.evaluate(
        "() => Object.fromEntries([...document.querySelectorAll('#readout [data-quantity]')]"
        ".map((cell) => [cell.dataset.quantity, JSON.parse(cell.dataset.value)]))"
    )


def readout_quantity(page, name: str):
    """The readout cell ``name``'s value, or None while the page does not show it."""
    cell = page.query_selector(f'#readout [data-quantity="{name}"]')
    return None if cell is None else json.loads(cell.get_attribute("data-value"))


def let_webgl_draw(page, milliseconds: int) -> None:
    """Give software WebGL time to draw before a screenshot: the full ``milliseconds`` when the pictures
    are kept (DYNLAB_UPDATE_SCREENSHOTS=1, docs/screenshots), 300 ms otherwise — the test-results
    pictures are for a person debugging a run, and no assertion depends on them."""
    page.wait_for_timeout(milliseconds if os.environ.get("DYNLAB_UPDATE_SCREENSHOTS") == "1" else min(milliseconds, 300))


@pytest.fixture(autouse=True)
def _close_pages_left_open(request):
    """After each test, close every browser context it left open (a failed assertion skips its own
    ``context.close()``): a viewer tab left rendering would slow every later test by a core."""
    yield
    if "browser" in request.fixturenames:
        for context in list(request.getfixturevalue("browser").contexts):
            context.close()


def dismiss_webgl_notice(page) -> None:
    """Close viser's "software WebGL" notice if it is showing (headless Chromium draws in software;
    the notice only covers part of the scene in a screenshot). Never waits for it to appear."""
    for frame in page.frames:
        if "/viewer/" in frame.url:
            frame.evaluate("() => document.querySelectorAll('.mantine-Notification-closeButton').forEach((b) => b.click())")
