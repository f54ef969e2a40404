"""Real browser: the chapter-3 rotation lessons (3.1 and 3.4) and their rotation-sequence scene.

Readout values on the page are checked against scipy's ``Rotation`` (an independent
implementation of intrinsic sequences) and against the 3-2-1 rate matrix written out
by hand. Two tests, serial, like the other browser tests.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from tests.browser.conftest import let_webgl_draw, open_lesson, readout_quantity, screenshot
from tests.conftest import wait_until

pytestmark = pytest.mark.browser


def _wait_for_quantity(page, name: str, predicate_js: str, timeout_ms: int = 30_000) -> None:
    """Poll in the page: the readout table is rebuilt every second, so element handles go stale."""
    page.wait_for_function(
        f"() => {{ const c = document.querySelector('#readout [data-quantity=\"{name}\"]'); "
        f"if (!c) return false; const v = JSON.parse(c.dataset.value); return {predicate_js}; }}",
        timeout=timeout_ms,
    )


def _screenshot(page, path) -> None:
    page.evaluate("document.getElementById('viewer-wrap').scrollIntoView()")
    let_webgl_draw(page, 2500)
    screenshot(page, path)


def test_rotation_sequences_lesson_readout_and_gimbal_lock(browser, inprocess_live_server, shots):
    live_server = inprocess_live_server  # the third turn's drawn label is read from the scene instance
    context, page, session_id, errors = open_lesson(browser, live_server, "/lessons/3-1-rotation-sequences", timeout_s=30)
    host = live_server.host
    _wait_for_quantity(page, "rotation_angle_deg", "true")

    # Default 3-1-3 (80°, 35°, 60°): the single equivalent turn, as scipy computes it.
    expected = Rotation.from_euler("ZXZ", [80.0, 35.0, 60.0], degrees=True)
    assert readout_quantity(page, "rotation_angle_deg") == pytest.approx(math.degrees(expected.magnitude()), abs=1e-9)  # 141.92°
    assert readout_quantity(page, "gimbal_lock_distance_deg") == pytest.approx(35.0, abs=1e-9)
    assert readout_quantity(page, "recovered_angles_deg") == "80.00, 35.00, 60.00"
    assert page.locator(".katex-error").count() == 0

    # Hold the finished sequence for the picture: all four frames, three turn axes and arcs.
    page.select_option("#ctl-stage", "after turn 3")
    wait_until(lambda: host.session_params(session_id)["stage"] == "after turn 3", 10, what="the scene to take the stage")
    _screenshot(page, shots / "lesson-3-1-rotation-sequences.png")

    # Gimbal-lock preset: 3-2-1 at pitch 90°, only yaw − roll is determined.
    page.click('button[data-preset="gimbal-lock"]')
    wait_until(lambda: host.session_params(session_id)["angle2_deg"] == 90.0, 15, what="the scene to take the preset")
    _wait_for_quantity(page, "rate_gain", 'v === "unbounded"')
    locked = Rotation.from_euler("ZYX", [30.0, 90.0, 10.0], degrees=True)
    assert readout_quantity(page, "rotation_angle_deg") == pytest.approx(math.degrees(locked.magnitude()), abs=1e-9)
    assert readout_quantity(page, "gimbal_lock_distance_deg") < 1e-9
    message = page.text_content("#readout .readout-message")
    assert "Gimbal lock" in message and "Only θ1 − θ3 = 20° is determined" in message
    marks = [float(m.get_attribute("data-value")) for m in page.query_selector_all('.control[data-name="angle2_deg"] .mark')]
    assert sorted(marks) == [-90.0, 90.0]
    assert host.instances(session_id)[0].turn_labels[2].text.endswith("gimbal lock)")
    _screenshot(page, shots / "lesson-3-1-rotation-sequences-gimbal-lock.png")
    assert not errors, errors
    context.close()


def test_angular_velocity_lesson_rate_gain_near_lock(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, "/lessons/3-4-angular-velocity?scene=rotation-sequence", timeout_s=30)
    host = live_server.host
    _wait_for_quantity(page, "rate_gain", "true")
    page.select_option("#ctl-sequence", "3-2-1")
    for name, value in (("angle1_deg", "30"), ("angle2_deg", "85"), ("angle3_deg", "10")):
        page.fill(f"#ctl-{name}", value)
        page.dispatch_event(f"#ctl-{name}", "change")
    page.select_option("#ctl-stage", "after turn 3")
    wait_until(
        lambda: (p := host.session_params(session_id))["sequence"] == "3-2-1" and p["angle2_deg"] == 85.0 and p["stage"] == "after turn 3",
        15, what="the scene to take 3-2-1 at 85°",
    )
    _wait_for_quantity(page, "gimbal_lock_distance_deg", "Math.abs(v - 5) < 1e-9")
    # 3-2-1 body rates written out: ωx = θ̇3 − θ̇1 s2, ωy = θ̇2 c3 + θ̇1 c2 s3, ωz = −θ̇2 s3 + θ̇1 c2 c3.
    t2, t3 = math.radians(85.0), math.radians(10.0)
    J = np.array([[-math.sin(t2), 0.0, 1.0], [math.cos(t2) * math.sin(t3), math.cos(t3), 0.0], [math.cos(t2) * math.cos(t3), -math.sin(t3), 0.0]])
    assert readout_quantity(page, "rate_gain") == pytest.approx(1.0 / np.linalg.svd(J, compute_uv=False)[-1], rel=1e-12)  # 16.2
    assert "Near gimbal lock (5° away)" in page.text_content("#readout .readout-message")
    assert page.locator(".katex-error").count() == 0
    _screenshot(page, shots / "lesson-3-4-angular-velocity.png")
    assert not errors, errors
    context.close()
