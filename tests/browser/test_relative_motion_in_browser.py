"""Chapter 3.5–3.6 lesson pages in a real browser: each scene connects, its readout shows the physics, screenshots.

One test per lesson page, serial. Each waits on the server's own client list,
drives the page through its own control path (``lesson.schedule`` of static/js/lesson.js), and
compares a readout cell with the value computed here from app.physics.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from app.physics.systems import earth
from app.physics.systems.ch03 import eastward_deflection as deflection
from app.physics.systems.ch03 import moving_frame as moving
from tests.browser.conftest import dismiss_webgl_notice, let_webgl_draw, open_lesson, screenshot
from tests.conftest import wait_until

pytestmark = pytest.mark.browser


def _open(browser, live_server, lesson_id):
    return open_lesson(browser, live_server, f"/lessons/{lesson_id}", viewport=(1500, 950))


def _set_controls(page, values: dict) -> None:
    """Set several controls the way the page's own widgets do (session values, then one scheduled PUT)."""
    page.evaluate(
        "async (values) => { const { lesson } = await import('/static/js/lesson.js');"
        " Object.assign(lesson.session.values, values); lesson.schedule(); }",
        values,
    )


def _readout_value(page, name: str):
    cell = page.wait_for_selector(f'#readout [data-quantity="{name}"]', timeout=60_000)
    return json.loads(cell.get_attribute("data-value"))


def _wait_for_readout(page, live_server, name: str, condition_js: str, arg=None, timeout_ms: int = 60_000) -> None:
    """Wait until the readout cell ``name`` satisfies ``condition_js`` (JS using ``value`` and ``arg``).

    On timeout, fail with what the server's live endpoint says, so a slow poll and a wrong value look different.
    """
    script = (
        "([name, arg]) => { const c = document.querySelector(`#readout [data-quantity=\"${name}\"]`);"
        f" if (!c) return false; const value = JSON.parse(c.dataset.value); return {condition_js}; }}"
    )
    try:
        page.wait_for_function(script, arg=[name, arg], timeout=timeout_ms)
    except Exception as exc:
        session_id = page.evaluate("async () => (await import('/static/js/lesson.js')).lesson.session.id")
        scene_id = page.evaluate("document.getElementById('viewer').src.split('/')[4]")
        live = page.request.get(f"{live_server.url}/api/scenes/{scene_id}/sessions/{session_id}/live")
        raise AssertionError(f"readout {name!r} never satisfied {condition_js} (arg {arg!r}); live endpoint: {live.status} {live.text()[:400]}") from exc


def _finish(page, context, shots, lesson_id, errors) -> None:
    dismiss_webgl_notice(page)
    let_webgl_draw(page, 2500)
    screenshot(page, shots / f"lesson-{lesson_id}.png")
    assert page.locator(".katex-error").count() == 0
    assert not errors, errors
    context.close()


def test_moving_frame_lesson_reads_out_the_five_terms(browser, live_server, shots):
    context, page, session_id, errors = _open(browser, live_server, "3-5-moving-frame")
    held = {  # the shaking-cart preset with a little spin-up, held at one instant
        "spin_rate_rad_s": 1.0, "spin_acceleration_rad_s2": 0.15, "tilt_deg": 0.0, "precession_rate_rad_s": 0.0,
        "groove_offset_m": 0.3, "slider_amplitude_m": 0.6, "slider_frequency_hz": 0.25,
        "cart_amplitude_m": 0.3, "cart_frequency_hz": 0.6, "playback_speed": 0.0, "time_s": 2.6,
    }
    _set_controls(page, held)
    host = live_server.host
    wait_until(lambda: host.session_params(session_id)["time_s"] == 2.6, 20, what="the scene to hold t = 2.6 s")
    physical = moving.PARAMETERS.validate({k: v for k, v in held.items() if k in moving.PARAMETERS.by_name})
    terms = moving.MovingFrameMotion.from_params(physical).acceleration_terms(np.array([2.6]))
    expected = float(np.linalg.norm(terms["total"][0]))
    _wait_for_readout(page, live_server, "a_total_magnitude", "Math.abs(value - arg) < 1e-9 * arg", expected)
    assert _readout_value(page, "a_coriolis_magnitude") == pytest.approx(float(np.linalg.norm(terms["coriolis"][0])), rel=1e-12)
    assert _readout_value(page, "t_s") == 2.6
    _finish(page, context, shots, "3-5-moving-frame", errors)


def test_foucault_lesson_measures_the_swing_plane_turning(browser, live_server, shots):
    context, page, session_id, errors = _open(browser, live_server, "3-6-rotating-earth")
    predicted = math.degrees(1000.0 * earth.vertical_earth_rate_rad_s(48.85))  # deg/s at the default ×1000
    assert _readout_value(page, "scene_rate_deg_s") == pytest.approx(predicted, rel=1e-12)
    # Six turning points take about 19 s of swinging (period 6.3 s): the time controls' 4× gets there in about 5 s.
    page.evaluate("async () => (await import('/static/js/lesson.js')).lesson.setPlayback({time_scale: 4})")
    _wait_for_readout(page, live_server, "turning_points", "value >= 6", timeout_ms=90_000)
    measured = _readout_value(page, "measured_rate_deg_s")
    assert measured == pytest.approx(predicted, rel=0.02)  # a fit over ~6 turning points; the lag from a/L = 0.1 is 0.4 %
    drift = float(page.text_content('#live [data-drift="jacobi_integral"]'))
    assert drift < 1e-6
    _finish(page, context, shots, "3-6-rotating-earth", errors)


def test_eastward_deflection_lesson_reads_out_the_deflection(browser, live_server, shots):
    context, page, session_id, errors = _open(browser, live_server, "3-6-eastward-deflection")
    flight = deflection.Flight.from_params(deflection.PARAMETERS.defaults())
    assert _readout_value(page, "east_mm") == pytest.approx(1000.0 * flight.deflection()[0], rel=1e-12)
    assert _readout_value(page, "east_mm") == pytest.approx(15.52, abs=0.01)
    assert _readout_value(page, "exaggeration") == 500.0
    _finish(page, context, shots, "3-6-eastward-deflection", errors)
