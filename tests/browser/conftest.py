"""``dynlab serve`` on a free loopback port (as README starts it, with its scene workers) and Debian's Chromium
driven by Playwright."""

from __future__ import annotations

import json
import os
import threading
import time
from collections.abc import Iterator
from pathlib import Path
from urllib.parse import urlsplit

import httpx
import pytest
import uvicorn

from app.bench.ports import free_loopback_port
from app.main import create_app
from app.settings import Settings
from tests.browser.first_frame import VIEWER_BUILT_IN_NODES
from tests.conftest import wait_until
from tests.served import INSTRUCTOR_KEY as SERVED_INSTRUCTOR_KEY
from tests.served import ServedApp

#: Debian's Chromium as its headless shell (package ``chromium-headless-shell``: the same Blink, V8 and SwiftShader
#: as ``/usr/bin/chromium``, without the browser's own window and pages). Playwright drives it the way it drives
#: Chromium headless by default. The full browser opened its omnibox's WebUI page in every new context: 0.6 CPU-s of a
#: lesson page's 3.3 (its browser process 0.42 CPU-s against 0.16, and a WebUI renderer of 0.24), measured over a
#: lesson's first 14 s on this machine.
CHROMIUM = "/usr/bin/chromium-headless-shell"
CHROMIUM_ARGS = (
    "--no-sandbox --disable-gpu --disable-quic --no-first-run --disable-background-networking "
    "--disable-component-update --disable-sync --enable-unsafe-swiftshader --use-gl=angle --use-angle=swiftshader"
).split()
RESULTS = Path(__file__).resolve().parents[2] / "test-results"
SCREENSHOTS = Path(__file__).resolve().parents[2] / "docs" / "screenshots"


#: The browser tests' instructor secret (the instructor link is ``{url}/instructor?key={INSTRUCTOR_KEY}``).
INSTRUCTOR_KEY = SERVED_INSTRUCTOR_KEY


class ServedHost:
    """What the browser tests ask of the scene host, asked of the served app over HTTP as a page would (the scenes
    run in its workers, out of this process's reach)."""

    def __init__(self, app: ServedApp) -> None:
        self._http = app.new_client(timeout_s=30.0)  # the tester's own device: the browser's limits are its own
        self._scene_of: dict[str, str] = {}
        self._scene_ids: list[str] | None = None

    @property
    def http(self) -> httpx.Client:
        return self._http

    def _get(self, path: str) -> httpx.Response:
        """GET as a patient page would: a 429 is waited out (its Retry-After) and asked again, for up to 10 s."""
        deadline = time.monotonic() + 10.0
        while (answer := self._http.get(path)).status_code == 429 and time.monotonic() < deadline:
            time.sleep(float(answer.headers.get("retry-after", "1")))
        return answer

    def remember(self, session_id: str, scene_id: str) -> None:
        self._scene_of[session_id] = scene_id

    def _scene(self, session_id: str) -> str | None:
        if session_id not in self._scene_of:
            if self._scene_ids is None:
                self._scene_ids = [s["id"] for s in self._get("/api/scenes").json()]
            for scene_id in self._scene_ids:
                if self._get(f"/api/scenes/{scene_id}/sessions/{session_id}").status_code == 200:
                    self._scene_of[session_id] = scene_id
                    break
        return self._scene_of.get(session_id)

    def _playback(self, session_id: str) -> dict | None:
        answer = self._get(f"/api/scenes/{self._scene(session_id) or 'heavy-top'}/sessions/{session_id}/playback")
        return answer.json() if answer.status_code == 200 else None

    def viewer_count(self, session_id: str) -> int:
        return (self._playback(session_id) or {}).get("viewers", 0)

    def playback(self, session_id: str) -> dict | None:
        return self._playback(session_id)

    def session_scene(self, session_id: str) -> str | None:
        return self._scene(session_id)

    def live(self, session_id: str) -> dict | None:
        """The session's live readout, as the page polls it."""
        answer = self._get(f"/api/scenes/{self._scene(session_id)}/sessions/{session_id}/live")
        return answer.json() if answer.status_code == 200 else None

    def session_params(self, session_id: str) -> dict | None:
        scene_id = self._scene(session_id)
        answer = self._get(f"/api/scenes/{scene_id}/sessions/{session_id}") if scene_id else None
        return answer.json()["params"] if answer is not None and answer.status_code == 200 else None

    def camera(self, session_id: str) -> dict | None:
        return (self._playback(session_id) or {}).get("camera")

    def motion_state(self, session_id: str) -> dict | None:
        playback = self._playback(session_id)
        return None if playback is None or playback.get("t_s") is None else {"t_s": playback["t_s"]}


class LiveServer:
    """A served app (``dynlab serve`` as README starts it: its own process, its scene workers) as the browser tests
    use it: its address, its instructor link and the scene host's state, asked over HTTP."""

    def __init__(self, app: ServedApp) -> None:
        self.app = app
        self.instructor_key = INSTRUCTOR_KEY
        self.host = ServedHost(self.app)

    @property
    def url(self) -> str:
        return self.app.url

    @property
    def instructor_link(self) -> str:
        return self.app.instructor_link


class InProcessLiveServer:
    """The same app in this test process (scenes included), beside the served one, for the few tests that look inside
    a scene instance (what it drew at one instant)."""

    def __init__(self) -> None:
        self.port = free_loopback_port()
        self.instructor_key = INSTRUCTOR_KEY
        self.app = create_app(Settings(port=self.port, instructor_key=INSTRUCTOR_KEY))
        config = uvicorn.Config(self.app, host="127.0.0.1", port=self.port, log_level="warning")
        self.server = uvicorn.Server(config)
        self.thread = threading.Thread(target=self.server.run, daemon=True)

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    @property
    def host(self):
        return self.app.state.scene_host

    def __enter__(self) -> "InProcessLiveServer":
        self.thread.start()
        wait_until(lambda: self.server.started, 20, what="the in-process server to start")
        return self

    def __exit__(self, *exc: object) -> None:
        self.server.should_exit = True
        self.thread.join(timeout=10)


@pytest.fixture(scope="session")
def inprocess_live_server() -> Iterator[InProcessLiveServer]:
    with InProcessLiveServer() as server:
        yield server


@pytest.fixture(scope="session")
def live_server(served: ServedApp) -> LiveServer:
    """The xdist worker's served app (``served``, which its API tests share): one server start a worker, not two."""
    return LiveServer(served)


#: Frames a second the tests' viewers draw: one in 4 s. (None at all saved 3.7 CPU-s of a lesson's first 10 s, but
#: then a lesson's first preset was lost twice in six fresh-clone runs, and never in many runs at this rate.)
VIEWER_FEW_FPS = 0.25


def limit_viewer_frames(frames_per_s: float | None, *, draws: bool = False) -> str:
    """An init script for the viewer's own page (a lesson's /viewer/… frame or a room's /room-viewer/…): its
    requestAnimationFrame calls back ``frames_per_s`` times a second (None: at the browser's own rate; 0: never, the
    callback is dropped), and unless ``draws``, WebGL's draw calls draw nothing. viser's renderer still runs each frame
    (three.js culls, sorts and counts it, binds its programs, and viser moves its camera) but software WebGL never
    builds the pipelines that would draw it: a scene's first frame cost the GPU process 4.2 CPU-s of SwiftShader's
    compiling, every time, in a fresh context or not; with no drawing, 0.3. Every other page keeps the browser's own
    frames."""
    lines = []
    if frames_per_s is not None:
        draw = "() => 0" if frames_per_s == 0 else f"(draw) => setTimeout(() => draw(performance.now()), {1000 / frames_per_s:g})"
        lines += [f"window.requestAnimationFrame = {draw};", "window.cancelAnimationFrame = (id) => clearTimeout(id);"]
    if not draws:
        lines += [
            "for (const context of [window.WebGLRenderingContext, window.WebGL2RenderingContext]) {",
            '  for (const name of ["drawArrays", "drawElements", "drawArraysInstanced", "drawElementsInstanced", "drawRangeElements"]) {',
            "    if (context && name in context.prototype) context.prototype[name] = () => undefined;",
            "  }",
            "}",
        ]
    body = "\n".join("  " + line for line in lines)
    return f"""(() => {{
  if (!/^\\/(room-)?viewer\\//.test(location.pathname)) return;
{body}
}})();"""


class ViewerFramesLimited:
    """The session's Chromium, whose new contexts let viser's viewer run a few frames (:data:`VIEWER_FEW_FPS`), none
    (``viewer_frames_per_s=0``) or every one (``viewer_frames_per_s=None``), drawing nothing in them unless
    ``viewer_draws`` (see :func:`limit_viewer_frames`); when screenshots are kept, every frame is drawn.

    Software WebGL (SwiftShader; there is no GPU here) spends 200–300 ms of CPU on each of viser's frames, so one open
    viewer asking for 60 frames a second keeps 1.7 of the machine's 2 cores busy at about 8 frames a second. At
    2 frames a second a lesson page still cost 0.5–1 core (its GPU process 0.4–0.8 core, measured over 10 s). One
    frame in 4 s cost 8.5 CPU-s over a lesson's first 10 s (its GPU process 4.0: the first frames compile the scene's
    shaders in software); no frame, 4.8 (GPU 0.3), but then a lesson's first preset was lost twice in six fresh-clone
    runs (never at one frame in 4 s). The tests read the scene's state from the server and the page, never from a
    drawing: a test that moves the camera by keys (viser moves it a step a frame while a key is held) asks for every
    frame, and only one that looks at the drawing itself (:func:`wait_for_scene_drawn`, a saved image) draws.
    """

    def __init__(self, browser) -> None:
        self._browser = browser

    def new_context(self, *, viewer_frames_per_s: float | None = VIEWER_FEW_FPS, viewer_draws: bool = False, **options):
        """A new context (Playwright's ``options``) whose viewer runs ``viewer_frames_per_s`` frames a second (None:
        the browser's own rate), drawn only if ``viewer_draws``."""
        context = self._browser.new_context(**options)
        if not keeping_screenshots() and not (viewer_frames_per_s is None and viewer_draws):
            context.add_init_script(limit_viewer_frames(viewer_frames_per_s, draws=viewer_draws))
        return context

    def __getattr__(self, name: str):
        return getattr(self._browser, name)


@pytest.fixture(scope="session")
def browser():
    if not Path(CHROMIUM).exists():
        pytest.fail(f"{CHROMIUM} is missing: run the README's test command (tests/run.sh), which installs it")
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        yield ViewerFramesLimited(browser)
        browser.close()


def keeping_screenshots() -> bool:
    """Screenshots are taken only to refresh docs/screenshots (DYNLAB_UPDATE_SCREENSHOTS=1): each costs 2–5 s
    of software WebGL and no assertion reads a picture. A failed test leaves one of every open page in test-results/."""
    return os.environ.get("DYNLAB_UPDATE_SCREENSHOTS") == "1"


@pytest.fixture
def shots() -> Path:
    """Where kept screenshots go (docs/screenshots)."""
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    return SCREENSHOTS


def screenshot(target, path: Path) -> None:
    """Save ``target`` (a page or a locator) to ``path`` when screenshots are kept; otherwise nothing."""
    if keeping_screenshots():
        target.screenshot(path=str(path))


def open_lesson(
    browser, live_server, path: str, *, viewport=(1500, 1000), context=None, viewer: bool = True, timeout_s: float = 40.0,
    viewer_frames_per_s: float | None = VIEWER_FEW_FPS, viewer_draws: bool = False,
):
    """Open ``path`` (e.g. ``/lessons/3-1-rotation-sequences``) in a new page; returns ``(context, page, session_id, errors)``.

    A new browser context of ``viewport`` (width, height) px is made unless ``context`` is given (its viewer runs
    ``viewer_frames_per_s`` frames a second, :data:`VIEWER_FEW_FPS` by default, drawn if ``viewer_draws``: see
    :class:`ViewerFramesLimited`).
    ``errors`` collects the page's uncaught JavaScript errors. With ``viewer`` it waits on the
    server's own client list until the lesson's 3D viewer has connected through the relay.
    """
    context = context or browser.new_context(
        viewport={"width": viewport[0], "height": viewport[1]}, viewer_frames_per_s=viewer_frames_per_s, viewer_draws=viewer_draws
    )
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda exc: errors.append(str(exc)))
    page.goto(live_server.url + path)
    # The page's lesson is static/js/lesson.js's export `lesson` (importing the module gives the page's own instance).
    session_id = page.evaluate("async () => (await import('/static/js/lesson.js')).lesson.session.id")
    if hasattr(live_server.host, "remember"):
        scene_id = page.evaluate("async () => (await import('/static/js/lesson.js')).lesson.scene?.id")
        live_server.host.remember(session_id, scene_id or "")
    if viewer:
        wait_until(lambda: live_server.host.viewer_count(session_id) == 1, timeout_s, what="the 3D viewer to connect through the relay")
    return context, page, session_id, errors


def room_followers(live_server, room_id: str) -> int:
    """The 3D viewers following a room's scene, as the room's state says (asked from the tester's own device)."""
    return live_server.host.http.get(f"/api/rooms/{room_id}/state").json()["followers"]


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


def wait_for_polls(page, count: int = 2, *, path_end: str = "/live", timeout_s: float = 30.0) -> None:
    """Wait until the page has had ``count`` more answers to its requests whose path ends with ``path_end`` (the
    readout's poll ``/live``, once a second while its viewer is connected; the graph's ``/graph``). A test that checks
    that something does *not* change watches it over the page's own polls, which a busy machine slows down together
    with the page, rather than over fixed seconds."""
    def polled(answer) -> bool:
        return urlsplit(answer.url).path.endswith(path_end)

    for _ in range(count):
        with page.expect_response(polled, timeout=timeout_s * 1000):
            pass


def let_webgl_draw(page, milliseconds: int) -> None:
    """Give software WebGL ``milliseconds`` to draw before a kept screenshot (no wait when none is taken)."""
    if keeping_screenshots():
        page.wait_for_timeout(milliseconds)


#: In a viewer's frame: how many frames viser's renderer has drawn since the scene's own nodes (beyond the ones its
#: client always has) arrived in its scene tree (0 while they have not).
FRAMES_WITH_THE_SCENE = """() => {
  const tree = window.__viserSceneTree, points = window.__viserTestpoints;
  if (!tree || !points) return 0;
  const frame = points.rendererInfo.render.frame;
  const builtIn = new Set(%s);
  if (!Object.keys(tree.getState()).some((name) => !builtIn.has(name))) return 0;
  if (window.__dynlabSceneFrom === undefined) window.__dynlabSceneFrom = frame;
  return frame - window.__dynlabSceneFrom;
}""" % json.dumps(VIEWER_BUILT_IN_NODES)


def wait_for_scene_drawn(page, *, frames: int = 3, timeout_s: float = 30.0) -> None:
    """Wait until the lesson's viewer (``#viewer``) has drawn ``frames`` frames with its scene in them (software
    WebGL draws the scene's first frames a while after its nodes arrive)."""
    viewer = page.locator("#viewer").element_handle().content_frame()
    wait_until(lambda: viewer.evaluate(FRAMES_WITH_THE_SCENE) >= frames, timeout_s, what=f"the viewer to draw {frames} frames of its scene")


@pytest.hookimpl(wrapper=True, tryfirst=True)
def pytest_runtest_makereport(item, call):
    """Keep each phase's report on the test item, so a fixture can tell that the test failed."""
    report = yield
    setattr(item, f"report_{report.when}", report)
    return report


@pytest.fixture(autouse=True)
def _close_pages_left_open(request):
    """After each test, close every browser context it left open (a failed assertion skips its own
    ``context.close()``): a viewer tab left rendering would slow every later test by a core. A failed
    test first leaves a screenshot of each open page in test-results/ for the person debugging it."""
    yield
    if "browser" not in request.fixturenames:
        return
    failed = getattr(request.node, "report_call", None) is not None and request.node.report_call.failed
    for context in list(request.getfixturevalue("browser").contexts):
        if failed:
            RESULTS.mkdir(parents=True, exist_ok=True)
            for index, page in enumerate(context.pages):
                page.screenshot(path=str(RESULTS / f"{request.node.name}-{index}.png"))
        context.close()


def dismiss_webgl_notice(page) -> None:
    """Close viser's "software WebGL" notice if it is showing (headless Chromium draws in software;
    the notice only covers part of the scene in a screenshot). Never waits for it to appear."""
    for frame in page.frames:
        if "/viewer/" in frame.url:
            frame.evaluate("() => document.querySelectorAll('.mantine-Notification-closeButton').forEach((b) => b.click())")


#: True once every ``.math`` element is typeset (static/js/katex.js draws those below the window when the page is idle).
MATH_TYPESET = "() => [...document.querySelectorAll('.math')].every((el) => el.querySelector('.katex, .katex-error'))"


def wait_for_math(page) -> None:
    """Wait until the page has typeset all its equations (a second or two after it opens, at most)."""
    page.wait_for_function(MATH_TYPESET, timeout=15_000)


def show_scene_and_keep_screenshot(page, path: Path) -> None:
    """The end of every lesson test: no KaTeX errors, the viewer scrolled into view and, when screenshots are kept,
    saved to ``path`` once software WebGL has drawn."""
    wait_for_math(page)
    assert page.locator(".katex-error").count() == 0
    page.evaluate("document.getElementById('viewer-wrap').scrollIntoView()")
    dismiss_webgl_notice(page)
    let_webgl_draw(page, 3000)
    screenshot(page, path)
