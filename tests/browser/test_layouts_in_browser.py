"""Layouts in Chromium: a phone, a laptop and a projector (issue 15, item 5).

One sweep opens every page of ours once with the 3D viewer stubbed (layout does not depend on what viser draws) and
no scene started on the server (the page's PUT of its parameters is answered in the browser), and measures it at 390×844 and, resized, at 1366×768. On the phone nothing is wider than the screen except inside a box
that scrolls sideways on its own, and a lesson's scene starts within the first screen and a half. On the laptop a
lesson's scene and its first control are in view together. One lesson with the real viewer then checks projector
mode at 1920×1080 (a larger viewer, readout and labels) and that the heavy top's two slider marks keep apart, and
keeps the three screenshots of docs/screenshots when asked to.
"""

from __future__ import annotations

import json
import re
from urllib.parse import urlsplit

import pytest

from tests.browser.conftest import MATH_TYPESET, dismiss_webgl_notice, let_webgl_draw, open_lesson, screenshot, wait_for_polls
from tests.browser.test_accessibility_in_browser import _stub_viewer, our_pages
from tests.conftest import wait_until

pytestmark = pytest.mark.browser

PHONE = {"width": 390, "height": 844}
LAPTOP = {"width": 1366, "height": 768}
PROJECTOR = {"width": 1920, "height": 1080}
#: The phone's scene must start within this many screen heights of the top of the page (it used to be 5–8 down).
PHONE_SCENE_WITHIN_SCREENS = 1.5
#: Projector mode: the viewer's share of a 1920 px wide screen at least (the issue's "enlarges the viewer").
PROJECTOR_VIEWER_SHARE = 0.6
#: Sub-pixel layout: a box may end this far past the edge from rounding alone.
ROUNDING_PX = 1.0
LESSON = "/lessons/10-2-spinning-top"
#: A lesson's own scene session: PUT here sets its parameters (and starts its scene on the server).
SCENE_SESSION = re.compile(r"/api/scenes/[^/]+/sessions/[^/]+")

#: The page has drawn what decides its layout: a lesson with a scene has shown its viewer (after the first PUT of
#: its parameters) or the error that stopped it.
def _answer_scene_parameters(context) -> None:
    """Answer a lesson's PUT of its scene's parameters as the server would when it takes them unchanged, without
    starting a scene on the server (one lesson derives its equations with sympy first, for 20 s); other requests pass."""
    def answer(route):
        if route.request.method == "PUT" and SCENE_SESSION.fullmatch(urlsplit(route.request.url).path):
            route.fulfill(status=200, content_type="application/json", body=json.dumps({"params": {}}))
        else:
            route.continue_()
    context.route("**/api/scenes/**", answer)


PAGE_READY = """() => {
  if (document.readyState !== 'complete') return false;
  if (document.getElementById('exercise') && document.body.dataset.exerciseReady !== 'true') return false;
  if (!(%s)()) return false;
  const config = document.getElementById('dynlab-config');
  if (!config || !JSON.parse(config.textContent).scene) return true;
  return !document.getElementById('viewer-wrap').hidden || !document.getElementById('control-error').hidden;
}""" % MATH_TYPESET

#: The smallest a touch target may be on a phone (px): a finger's width, as WCAG 2.5.5 and the platforms' guides ask.
TOUCH_TARGET_PX = 44.0
#: The targets a student touches to run a lesson: the header's toggle, the scene's and the time controls' buttons,
#: every control's boxes and slider (a range input is as tall as its thumb's target).
TOUCH_TARGETS = (
    "#large-text, #viewer-wrap button, .time-controls :is(button, select, input), "
    "#controls :is(button, select, input[type=number], input[type=text], input[type=range])"
)
#: What is wider than the window: every box (not inline text, whose block is measured) that reaches past either edge,
#: unless it is inside a box that scrolls sideways on its own and itself fits (an equation, a wide table), or inside
#: KaTeX's visually hidden MathML copy. The skip link waits off screen until it is focused.
MEASURE = """(edge) => {
  const TOUCH_TARGETS = '%s';
  const width = document.documentElement.clientWidth;
  const scrollsOnItsOwn = (el) => ['auto', 'scroll'].includes(getComputedStyle(el).overflowX);
  const fits = (r) => r.left >= -edge && r.right <= width + edge;
  const inScrollBox = (el) => {
    for (let p = el.parentElement; p && p !== document.body; p = p.parentElement) if (scrollsOnItsOwn(p) && fits(p.getBoundingClientRect())) return true;
    return false;
  };
  const describe = (el) => {
    const path = [];
    for (let e = el; e && e !== document.body && path.length < 4; e = e.parentElement) path.unshift(e.tagName.toLowerCase() + (e.id ? '#' + e.id : '') + (typeof e.className === 'string' && e.className ? '.' + e.className.trim().replace(/\\s+/g, '.') : ''));
    const r = el.getBoundingClientRect();
    return `${path.join(' > ')} (${Math.round(r.left)} to ${Math.round(r.right)} px)`;
  };
  const wide = [];
  for (const el of document.body.querySelectorAll('*')) {
    const r = el.getBoundingClientRect();
    if (!(r.width || r.height) || fits(r) || el.closest('.katex-mathml, .skip') || getComputedStyle(el).display === 'inline') continue;
    if (!inScrollBox(el)) wide.push(describe(el));
  }
  const viewer = document.getElementById('viewer-wrap');
  const firstControl = document.querySelector('#control-list :is(input, select, button)');
  const box = (el) => { const r = el.getBoundingClientRect(); return { top: r.top, bottom: r.bottom }; };
  const targets = [...document.querySelectorAll(TOUCH_TARGETS)].map((el) => el.getBoundingClientRect()).filter((r) => r.width && r.height);
  return {
    scroll_width: document.documentElement.scrollWidth,
    wide: wide.slice(0, 5),
    viewer_top_px: viewer && !viewer.hidden ? viewer.getBoundingClientRect().top + scrollY : null,
    viewer: viewer && !viewer.hidden ? box(document.getElementById('viewer')) : null,
    first_control: firstControl && !document.getElementById('controls').hidden ? box(firstControl) : null,
    smallest_target_px: targets.length ? Math.min(...targets.map((r) => Math.min(r.width, r.height))) : null,
  };
}""" % TOUCH_TARGETS


@pytest.fixture(scope="module")
def layouts(browser, live_server) -> dict[str, dict[str, dict]]:
    """Every page of ours measured (``MEASURE``) at the phone's size and then, the same page resized, at the laptop's."""
    context = browser.new_context(viewport=PHONE)
    _stub_viewer(context)
    _answer_scene_parameters(context)
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda exc: errors.append(str(exc)))
    measured = {}
    for path in our_pages(live_server):
        page.set_viewport_size(PHONE)
        page.goto(live_server.url + path)
        page.wait_for_function(PAGE_READY, timeout=30_000)
        phone = page.evaluate(MEASURE, ROUNDING_PX)
        page.set_viewport_size(LAPTOP)
        measured[path] = {"phone": phone, "laptop": page.evaluate(MEASURE, ROUNDING_PX)}
    context.close()
    assert errors == [], errors
    return measured


def test_no_page_is_wider_than_a_phone_and_the_scene_comes_first(layouts):
    """At 390×844: the page does not scroll sideways, no box is cut off at the edge (wide equations and tables scroll
    in their own boxes), a lesson's scene starts within the first screen and a half, not after the whole text, and
    every button, box and slider of the scene and its controls is at least 44 px across."""
    assert len(layouts) >= 3 + 40, sorted(layouts)
    too_wide = {path: (m["phone"]["scroll_width"], m["phone"]["wide"]) for path, m in layouts.items()
                if m["phone"]["scroll_width"] > PHONE["width"] or m["phone"]["wide"]}
    assert not too_wide, too_wide
    scenes = {path: m["phone"]["viewer_top_px"] for path, m in layouts.items() if m["phone"]["viewer_top_px"] is not None}
    assert len(scenes) >= 40, sorted(scenes)
    far = {path: top for path, top in scenes.items() if top > PHONE_SCENE_WITHIN_SCREENS * PHONE["height"]}
    assert not far, far
    small = {path: m["phone"]["smallest_target_px"] for path, m in layouts.items()
             if m["phone"]["smallest_target_px"] is not None and m["phone"]["smallest_target_px"] < TOUCH_TARGET_PX - ROUNDING_PX}
    assert not small, small


def test_on_a_laptop_the_scene_and_its_first_control_are_in_view_together(layouts):
    """At 1366×768, without scrolling: the whole viewer and the first control (its first box) of every lesson with both."""
    inside = lambda box: box["top"] >= 0 and box["bottom"] <= LAPTOP["height"]
    lessons = {path: m["laptop"] for path, m in layouts.items() if m["laptop"]["viewer"] and m["laptop"]["first_control"]}
    assert len(lessons) >= 35, sorted(lessons)
    hidden = {path: (round(m["viewer"]["top"]), round(m["first_control"]["bottom"])) for path, m in lessons.items()
              if not (inside(m["viewer"]) and inside(m["first_control"]))}
    assert not hidden, hidden
    too_wide = {path: (m["laptop"]["scroll_width"], m["laptop"]["wide"]) for path, m in layouts.items()
                if m["laptop"]["scroll_width"] > LAPTOP["width"] or m["laptop"]["wide"]}
    assert not too_wide, too_wide


def _viewer_width_px(page) -> float:
    return page.evaluate("document.getElementById('viewer').getBoundingClientRect().width")


def _readout_font_px(page) -> float:
    return page.evaluate("parseFloat(getComputedStyle(document.querySelector('#readout td')).fontSize)")


def _viewer_pixel_ratio(page) -> float:
    """The device pixel ratio the viewer's page renders at: viser draws its labels in that page's CSS pixels."""
    frame = next(f for f in page.frames if "/viewer/" in f.url)
    return frame.evaluate("devicePixelRatio")


def _spin_mark_labels(page) -> list[dict]:
    """The heavy top's spin-slider mark labels on show, as boxes (px)."""
    return page.eval_on_selector_all(
        '.control[data-name="spin_rad_s"] .mark:not([hidden]) > span:not([hidden])',
        "(els) => els.map((el) => { const r = el.getBoundingClientRect(); return { left: r.left, right: r.right, top: r.top, bottom: r.bottom, text: el.textContent }; })",
    )


def _assert_apart(labels: list[dict]) -> None:
    """Both sleeping thresholds (±ω₃) are labelled, and no two labels share a pixel."""
    assert [label["text"] for label in labels] == ["sleeping threshold"] * 2, labels
    for i, a in enumerate(labels):
        for b in labels[i + 1:]:
            overlap = a["left"] < b["right"] and b["left"] < a["right"] and a["top"] < b["bottom"] and b["top"] < a["bottom"]
            assert not overlap, (a, b)


def test_projector_mode_enlarges_the_viewer_its_labels_and_the_readout(browser, live_server, shots):
    """The heavy top with its real viewer, on a laptop, a projector (Alt+L's projector mode) and a phone: projector mode
    makes the viewer wider (≥ 60 % of 1920 px) and taller, renders the viewer's page 1.5× (its labels), and enlarges
    the readout; the spin slider's two sleeping-threshold marks never overlap."""
    context, page, session_id, errors = open_lesson(browser, live_server, LESSON, viewport=(LAPTOP["width"], LAPTOP["height"]))
    page.wait_for_selector('.control[data-name="spin_rad_s"] .mark', state="attached", timeout=20_000)
    page.wait_for_selector("#readout td")
    _assert_apart(_spin_mark_labels(page))
    first_control = page.locator("#control-list input").first.bounding_box()
    viewer = page.locator("#viewer").bounding_box()
    assert viewer["y"] >= 0 and first_control["y"] + first_control["height"] <= LAPTOP["height"]  # with viser's own client
    dismiss_webgl_notice(page)
    let_webgl_draw(page, 3000)
    screenshot(page, shots / "lesson-laptop.png")

    page.set_viewport_size(PROJECTOR)
    width, height = _viewer_width_px(page), page.evaluate("document.getElementById('viewer').getBoundingClientRect().height")
    font, ratio = _readout_font_px(page), _viewer_pixel_ratio(page)
    page.click("#large-text")
    page.wait_for_selector('#large-text[aria-pressed="true"]')
    assert _viewer_width_px(page) > width and _viewer_width_px(page) >= PROJECTOR_VIEWER_SHARE * PROJECTOR["width"]
    assert page.evaluate("document.getElementById('viewer').getBoundingClientRect().height") > height
    assert _readout_font_px(page) > font
    wait_until(lambda: _viewer_pixel_ratio(page) >= 1.5 * ratio - 1e-6, timeout_s=5, what="the viewer's page to render larger")
    # The marks are placed again on the next readout (about a second), with projector mode's larger text.
    wait_for_polls(page, 2)
    _assert_apart(_spin_mark_labels(page))
    dismiss_webgl_notice(page)
    let_webgl_draw(page, 3000)
    screenshot(page, shots / "lesson-projector.png")

    page.click("#large-text")
    page.wait_for_selector('#large-text[aria-pressed="false"]')
    page.set_viewport_size(PHONE)
    assert page.evaluate("document.getElementById('viewer-wrap').getBoundingClientRect().top") < PHONE["height"] / 2
    wait_for_polls(page, 2)
    _assert_apart(_spin_mark_labels(page))
    let_webgl_draw(page, 3000)
    screenshot(page, shots / "lesson-phone.png")
    assert errors == []
    context.close()
