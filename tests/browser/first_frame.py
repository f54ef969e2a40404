"""How long a lesson takes to show its scene: from opening the lesson page to the viewer's first frame of the scene,
split into where the time goes. Used by ``test_first_frame_bench.py``; the page is driven as a student opens it (a
new browser context each time: nothing cached, a new session, a scene built for it in a worker).

Every instant is read in the browser as wall-clock ms (``performance.timeOrigin + performance.now()``, which the
lesson page and its viewer frame share) and reported in ms after the lesson's navigation started.
"""

from __future__ import annotations

import json
import statistics
import time

#: Lessons measured: a closed-form scene with a worked example (1.1), the heavy top, the double pendulum (a derived
#: model) and the rolling disk (with its derivations panel).
LESSONS = (
    "1-1-vector-operations",
    "10-2-spinning-top",
    "7-5-lagranges-equations",
    "9-3-gibbs-appell-and-kane",
)

#: The nodes viser's client has in its scene tree before a scene sends any (a scene's own are the others).
VIEWER_BUILT_IN_NODES = ("", "/WorldAxes")

#: Added to every frame of the measuring context. In the viewer's frame: when the client opened its websocket, when
#: it opened and brought the first message (the socket lives in a web worker: its messages to the page), and the
#: first frame drawn once the scene's own nodes are in viser's scene
#: tree (a node beyond the ones viser's client always has), checked after each of the client's animation frames.
MARKS_SCRIPT = """(() => {
  if (!/^\\/(room-)?viewer\\//.test(location.pathname)) return;
  const now = () => performance.timeOrigin + performance.now();
  const marks = window.__firstFrameMarks = { navigation: performance.timeOrigin };
  // viser's client keeps its websocket in a web worker, which tells the page "connected" and then hands it messages.
  const NativeWorker = window.Worker;
  window.Worker = class extends NativeWorker {
    constructor(...args) {
      super(...args);
      if (marks.socket_created === undefined) marks.socket_created = now();
      this.addEventListener("message", (event) => {
        const type = event.data && event.data.type;
        if (type === "connected") { if (marks.socket_open === undefined) marks.socket_open = now(); }
        else if (type !== "closed" && marks.socket_open !== undefined && marks.first_message === undefined) {
          marks.first_message = now();
        }
      });
    }
  };
  const builtIn = new Set(%s);
  const check = () => {
    if (marks.first_frame !== undefined) return;
    const tree = window.__viserSceneTree, points = window.__viserTestpoints;
    if (!tree || !points) return;
    if (marks.client_ready === undefined) marks.client_ready = now();
    const names = Object.keys(tree.getState());
    if (names.some((name) => !builtIn.has(name)) && points.rendererInfo.render.frame > 0) {
      marks.first_frame = now();
      marks.nodes = names.length;
    }
  };
  const requestFrame = window.requestAnimationFrame.bind(window);
  window.requestAnimationFrame = (draw) => requestFrame((t) => { draw(t); check(); });
})();""" % json.dumps(VIEWER_BUILT_IN_NODES)

#: Read in the lesson page once the viewer has drawn: the page's own instants and the viewer frame's marks.
READ_MARKS = """() => {
  const origin = performance.timeOrigin;
  const at = (epoch) => (typeof epoch === "number" ? epoch - origin : null);
  const paint = performance.getEntriesByType("paint").find((e) => e.name === "first-contentful-paint");
  const nav = performance.getEntriesByType("navigation")[0];
  const session = /\\/api\\/scenes\\/[^/]+\\/sessions\\/[^/]+$/;
  const put = performance.getEntriesByType("resource").find((e) => session.test(e.name));
  const frame = document.getElementById("viewer");
  const marks = (frame && frame.contentWindow && frame.contentWindow.__firstFrameMarks) || {};
  const viewerNav = frame && frame.contentWindow && frame.contentWindow.performance.getEntriesByType("navigation")[0];
  return {
    page_html_ms: nav ? nav.responseEnd : null,
    page_paint_ms: paint ? paint.startTime : null,
    page_scripts_done_ms: nav ? nav.domContentLoadedEventEnd : null,
    session_put_start_ms: put ? put.startTime : null,
    session_put_end_ms: put ? put.responseEnd : null,
    viewer_start_ms: at(marks.navigation),
    viewer_html_ms: viewerNav ? at(marks.navigation + viewerNav.responseEnd) : null,
    viewer_client_ready_ms: at(marks.client_ready),
    socket_created_ms: at(marks.socket_created),
    socket_open_ms: at(marks.socket_open),
    first_message_ms: at(marks.first_message),
    first_frame_ms: at(marks.first_frame),
  };
}"""

WAIT_FIRST_FRAME = """() => {
  const frame = document.getElementById("viewer");
  const marks = frame && frame.contentWindow && frame.contentWindow.__firstFrameMarks;
  return Boolean(marks && marks.first_frame !== undefined);
}"""

def measure_once(browser, url: str, lesson_id: str, *, timeout_s: float = 30.0) -> dict:
    """Open ``/lessons/<lesson_id>`` in a new context (1366×768, the viewer drawing at the browser's own rate) and
    return the marks (ms after navigation start) once the viewer has drawn the scene; after ``timeout_s`` without a
    first frame, the marks reached so far with ``timed_out``."""
    from playwright.sync_api import TimeoutError as PlaywrightTimeout

    context = browser.new_context(viewport={"width": 1366, "height": 768}, viewer_frames_per_s=None, viewer_draws=True)
    try:
        context.add_init_script(MARKS_SCRIPT)
        page = context.new_page()
        errors: list[str] = []
        page.on("pageerror", lambda exc: errors.append(str(exc)))
        page.on("console", lambda message: errors.append(message.text) if message.type == "error" else None)
        page.goto(f"{url}/lessons/{lesson_id}", wait_until="commit")
        try:
            page.wait_for_function(WAIT_FIRST_FRAME, timeout=timeout_s * 1000, polling=50)
            timed_out = False
        except PlaywrightTimeout:
            timed_out = True
        marks = page.evaluate(READ_MARKS)
        marks["errors"] = errors
        marks["timed_out"] = timed_out
        return marks
    finally:
        context.close()


def load_average() -> list[float]:
    with open("/proc/loadavg", encoding="ascii") as f:
        return [float(x) for x in f.read().split()[:3]]


def summarise(lesson_id: str, runs: list[dict]) -> dict:
    """One lesson's loads: each first frame (None: not drawn in time) and the median of every mark over the drawn."""
    drawn = [r for r in runs if not r["timed_out"]]
    keys = [k for k in runs[0] if k.endswith("_ms")]
    median = {k: statistics.median(v) for k in keys if (v := [r[k] for r in drawn if r[k] is not None])}
    return {
        "lesson_id": lesson_id,
        "first_frame_ms": [None if r["timed_out"] else round(r["first_frame_ms"]) for r in runs],
        "median_ms": {k: round(v, 1) for k, v in median.items()},
        "console_errors": sorted({e for r in runs for e in r["errors"]}),
    }


def measure(browser, url: str, *, lessons=LESSONS, loads: int = 3) -> dict:
    """``loads`` openings of each lesson (one warm-up opening of each first, not counted: numba and the browser's
    own first start); per lesson the median of each mark, and the load average before and after."""
    for lesson_id in lessons:
        measure_once(browser, url, lesson_id)
    before = load_average()
    started = time.time()
    results = [
        summarise(lesson_id, [measure_once(browser, url, lesson_id) for _ in range(loads)]) for lesson_id in lessons
    ]
    return {"load_average_before": before, "load_average_after": load_average(),
            "seconds": round(time.time() - started, 1), "lessons": results}
