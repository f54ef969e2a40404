"""Real-browser tests: Debian's Chromium, headless, against a live server.

These are few and serial (one viser tab costs about a core of software
rendering). They wait on the server's own client list, not on page text.
"""

from __future__ import annotations

import json
import math

import pytest

from app.physics.systems import worked_examples
from tests.browser.conftest import let_webgl_draw, open_lesson, readout_quantity, screenshot, wait_for_polls
from tests.conftest import wait_until

EXAMPLES = worked_examples()

pytestmark = pytest.mark.browser

LESSON_11 = "/lessons/1-1-vector-operations"


def _panel_outputs(page) -> dict:
    cells = page.query_selector_all("#solution [data-output]")
    return {c.get_attribute("data-output"): json.loads(c.get_attribute("data-value")) for c in cells}


def _close(a, b) -> bool:
    if isinstance(a, list):
        return len(a) == len(b) and all(_close(x, y) for x, y in zip(a, b))
    return math.isclose(a, b, rel_tol=1e-12, abs_tol=1e-9)


def test_example_11_theta_control_updates_solution_and_scene(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, LESSON_11, viewport=(1500, 950), timeout_s=30)
    host = live_server.host
    page.wait_for_selector('#solution [data-output="M_AB_Nm"]', timeout=20_000)
    before = _panel_outputs(page)
    defaults = EXAMPLES["1.1"].solve(EXAMPLES["1.1"].inputs.defaults()).as_dict()["outputs"]
    assert all(_close(before[k], defaults[k]) for k in defaults), (before, defaults)

    # Move the θ slider with the keyboard: 5 steps of 1° from 25° to 30°.
    slider = page.locator('.control[data-name="theta_deg"] input[type=range]')
    slider.focus()
    for _ in range(5):
        page.keyboard.press("ArrowRight")
    page.wait_for_function("document.getElementById('ctl-theta_deg').value === '30'")
    page.wait_for_function(
        "() => { const box = document.querySelector('#solution [data-example=\"1.1\"]');"
        " return box && JSON.parse(box.dataset.inputs).theta_deg === 30; }"
    )

    expected = page.request.post(live_server.url + "/api/examples/1.1/solve", data={"inputs": {"theta_deg": 30}}).json()
    after = _panel_outputs(page)
    for name, value in expected["outputs"].items():
        assert _close(after[name], value), (name, after[name], value)
    assert not _close(after["M_AB_Nm"], before["M_AB_Nm"])

    # The scene this browser is watching received the same θ.
    wait_until(lambda: host.session_params(session_id)["theta_deg"] == 30.0, 10, what="the scene to take θ = 30°")
    let_webgl_draw(page, 2500)  # the new pose
    screenshot(page, shots / "lesson-1-1-vector-operations.png")
    assert not errors, errors
    context.close()


def test_two_browsers_get_independent_scenes(browser, live_server):
    contexts = [browser.new_context(viewport={"width": 1200, "height": 800}) for _ in range(2)]
    opened = [open_lesson(browser, live_server, LESSON_11, context=c, viewer=False)[1:] for c in contexts]
    host = live_server.host
    (page_a, session_a, _), (page_b, session_b, _) = opened
    assert session_a != session_b
    wait_until(lambda: host.viewer_count(session_a) == 1 and host.viewer_count(session_b) == 1, 40, what="both viewers")

    page_a.fill("#ctl-gamma_deg", "60")
    page_a.press("#ctl-gamma_deg", "Enter")
    page_a.locator("#ctl-gamma_deg").blur()
    wait_until(lambda: host.session_params(session_a)["gamma_deg"] == 60.0, 10, what="scene A to take γ = 60°")
    wait_for_polls(page_b, 1)  # a readout poll of B's later, B's scene is untouched
    assert host.session_params(session_b)["gamma_deg"] == 40.0
    assert page_b.input_value("#ctl-gamma_deg") == "40"
    # And each has its own scene: one viewer each, its own motion.
    assert host.viewer_count(session_a) == 1 and host.viewer_count(session_b) == 1
    for c in contexts:
        c.close()
    wait_until(lambda: host.viewer_count(session_a) == 0 and host.viewer_count(session_b) == 0, 20, what="clients to leave")


@pytest.mark.parametrize(
    "path, name, has_scene",
    [
        ("/", "course", False),
        ("/lessons/1-1-vector-calculus", "lesson-1-1-vector-calculus", True),
        ("/lessons/1-2-newtonian-mechanics", "lesson-1-2-newtonian-mechanics", True),
        ("/lessons/1-3-biographical-perspective", "lesson-1-3-biographical-perspective", False),
    ],
)
def test_pages_render_without_errors(browser, live_server, shots, path, name, has_scene):
    if has_scene:
        context, page, _, errors = open_lesson(browser, live_server, path, viewport=(1500, 950), timeout_s=30)
        page.wait_for_selector("#solution .step", timeout=20_000)
        let_webgl_draw(page, 3000)
    else:
        context = browser.new_context(viewport={"width": 1500, "height": 950})
        page = context.new_page()
        errors: list[str] = []
        page.on("pageerror", lambda exc: errors.append(str(exc)))
        page.goto(live_server.url + path)
        page.wait_for_load_state("networkidle")
    # KaTeX rendered every math span (no raw TeX left, no KaTeX error nodes).
    assert page.locator(".katex-error").count() == 0
    screenshot(page, shots / f"{name}.png")
    assert not errors, errors
    context.close()


def test_heavy_top_live_invariants_and_blow_up_pause(browser, live_server, shots):
    """The heavy-top lesson shows method, invariants and drift live; a far-too-large RK4 step pauses the
    scene with a reason instead of drawing non-physical motion; choosing the splitting method resumes it."""
    context, page, session_id, errors = open_lesson(browser, live_server, "/lessons/10-2-spinning-top", timeout_s=30)
    host = live_server.host
    page.wait_for_selector('#live [data-drift="energy"]', timeout=20_000)
    description = page.text_content('#live [data-live="description"]')
    assert description.startswith("Splitting, order")  # splitting4 by the h·ω rule at first, then the pilot's cheapest (splitting8)
    energy_drift = float(page.text_content('#live [data-drift="energy"]'))
    assert energy_drift < 1e-6  # the default method keeps energy to far better than 1e-6 (measured ~1e-10)
    let_webgl_draw(page, 2500)
    screenshot(page, shots / "lesson-10-2-spinning-top.png")

    # RK4 with one step per frame at a 300 rad/s spin: h·ω ≈ 10, far beyond RK4's stability limit.
    page.select_option("#ctl-method", "rk4")
    page.fill("#ctl-steps_per_frame", "1")
    page.dispatch_event("#ctl-steps_per_frame", "change")
    page.fill("#ctl-spin_rad_s", "300")
    page.dispatch_event("#ctl-spin_rad_s", "change")
    wait_until(lambda: host.session_params(session_id)["spin_rad_s"] == 300.0, 10, what="the scene to take the new spin")
    page.wait_for_function("() => !document.querySelector('#live [data-live=\"status\"]').hidden", timeout=20_000)
    status = page.text_content('#live [data-live="status"]')
    assert "steps per frame" in status and "RK4" in status, status
    live = host.live(session_id)
    assert live["status"] and not live["running"]
    assert all(math.isfinite(i["value"]) for i in live["invariants"].values())  # paused before anything blew up
    page.evaluate("document.getElementById('viewer-wrap').scrollIntoView()")
    let_webgl_draw(page, 1500)
    screenshot(page, shots / "lesson-10-2-spinning-top-paused.png")

    page.select_option("#ctl-method", "splitting4")
    page.wait_for_function("() => document.querySelector('#live [data-live=\"status\"]').hidden", timeout=20_000)
    assert host.live(session_id)["status"] == ""
    assert not errors, errors
    context.close()


def test_heavy_top_spin_changes_the_nutation_band_readout(browser, live_server, shots):
    """Changing the spin on the lesson page changes the quadrature nutation band shown beside the scene,
    to the values the quadrature gives; the sleeping threshold sits on the spin slider as a mark."""
    from app.physics.systems.ch10 import heavy_top

    context, page, session_id, errors = open_lesson(browser, live_server, "/lessons/10-2-spinning-top", timeout_s=30)
    page.wait_for_selector('#readout [data-quantity="theta_max_deg"]', timeout=20_000)
    defaults = heavy_top.PARAMETERS.defaults()
    expected = heavy_top.quadrature(defaults)
    before = readout_quantity(page, "theta_max_deg")
    assert before == pytest.approx(math.degrees(expected.theta_max_rad), rel=1e-12)
    assert readout_quantity(page, "locus") == "cusps"
    mark = page.locator('.control[data-name="spin_rad_s"] .mark:not([hidden])').first
    assert float(mark.get_attribute("data-value")) == pytest.approx(heavy_top.critical_spin_rad_s(defaults), rel=1e-12)

    page.fill("#ctl-spin_rad_s", "25")
    page.dispatch_event("#ctl-spin_rad_s", "change")
    page.wait_for_function(
        f"() => {{ const c = document.querySelector('#readout [data-quantity=\"theta_max_deg\"]'); return c && JSON.parse(c.dataset.value) !== {before!r}; }}",
        timeout=20_000,
    )
    after = readout_quantity(page, "theta_max_deg")
    slower = heavy_top.quadrature(dict(defaults, spin_rad_s=25.0))
    assert after == pytest.approx(math.degrees(slower.theta_max_rad), rel=1e-12)
    assert after > before + 3.0  # a slower top dips much further: about 31.0° → 37.5°
    assert readout_quantity(page, "nutation_period_s") == pytest.approx(slower.nutation_period_s, rel=1e-12)
    let_webgl_draw(page, 4000)  # and the trail show a few nutation cycles
    screenshot(page.locator("#controls"), shots / "lesson-10-2-spinning-top-controls.png")
    page.evaluate("window.scrollTo(0, 0); document.querySelector('.lesson-live').scrollTop = 0")
    let_webgl_draw(page, 1000)
    screenshot(page, shots / "lesson-10-2-spinning-top-readout.png")
    assert not errors, errors
    context.close()


def test_equinox_precession_lesson_scene_and_worked_solution(browser, live_server, shots):
    """The equinox lesson shows the worked solution (contract outputs) and the scene's readout agrees with it."""
    context, page, session_id, errors = open_lesson(browser, live_server, "/lessons/10-2-precession-of-the-equinoxes", timeout_s=30)
    page.wait_for_selector('#solution [data-output="rate_arcsec_per_year"]', timeout=20_000)
    page.wait_for_selector('#readout [data-quantity="rate_arcsec_per_year"]', timeout=20_000)
    outputs = _panel_outputs(page)
    assert outputs["rate_arcsec_per_year"] == pytest.approx(50.307, abs=1e-3)
    assert readout_quantity(page, "rate_arcsec_per_year") == pytest.approx(outputs["rate_arcsec_per_year"], rel=1e-12)
    assert readout_quantity(page, "moon_share") == pytest.approx(outputs["moon_share"], rel=1e-12)
    let_webgl_draw(page, 3000)
    page.evaluate("window.scrollTo(0, 0); document.querySelector('.lesson-live').scrollTop = 0")
    screenshot(page, shots / "lesson-10-2-precession-of-the-equinoxes.png")
    assert not errors, errors
    context.close()
