"""Real browser: lessons 3.2 (finite rotations), 3.3 (vector derivatives) and 3.4 (angle rates) with their scenes.

Each test opens the lesson, presses a preset the lesson text uses, and compares the readout with
numbers computed here independently (scipy's ``Rotation``, closed forms worked by hand). Serial,
one viewer at a time, like the other browser tests.
"""

from __future__ import annotations

import math

import pytest
from scipy.spatial.transform import Rotation

from tests.browser.conftest import let_webgl_draw, open_lesson, readout_values, show_scene_and_keep_screenshot
from tests.browser.test_rotation_sequence_in_browser import _wait_for_quantity
from tests.conftest import wait_until

pytestmark = pytest.mark.browser


def _press_preset(page, host, session_id, preset: str, check) -> None:
    page.click(f'button[data-preset="{preset}"]')
    wait_until(lambda: check(host.session_params(session_id)), 15, what=f"the scene to take the preset {preset}")


def test_finite_rotation_lesson(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, "/lessons/3-2-displacement", timeout_s=30)
    host = live_server.host
    _wait_for_quantity(page, "rotation_angle_deg", "true")
    values = readout_values(page)
    expected = Rotation.from_euler("ZXZ", [80.0, 35.0, 60.0], degrees=True)
    assert values["rotation_angle_deg"] == pytest.approx(math.degrees(expected.magnitude()), abs=1e-9)  # 141.92°
    axis = expected.as_rotvec() / expected.magnitude()
    assert [values[f"axis_{c}"] for c in "xyz"] == pytest.approx(list(axis), abs=1e-12)
    assert values["rodrigues_mismatch"] < 1e-12

    _press_preset(page, host, session_id, "quarter-turns", lambda p: p["second_angle_deg"] == 90.0 and p["sequence"] == "1-2-3")
    _wait_for_quantity(page, "order_gap_deg", "Math.abs(v - 120) < 1e-9")
    values = readout_values(page)
    a, b = Rotation.from_euler("X", 90, degrees=True), Rotation.from_euler("Z", 90, degrees=True)
    assert values["a_then_b_angle_deg"] == pytest.approx(math.degrees((b * a).magnitude()), abs=1e-9)  # 120°
    assert values["b_then_a_angle_deg"] == pytest.approx(math.degrees((a * b).magnitude()), abs=1e-9)
    assert values["a_then_b_axis"] == "(+0.5774, +0.5774, +0.5774)" and values["b_then_a_axis"] == "(+0.5774, -0.5774, +0.5774)"
    assert "do not commute" in page.text_content("#readout .readout-message")
    let_webgl_draw(page, 4500)  # both copies through their first turn and into the second
    show_scene_and_keep_screenshot(page, shots / "lesson-3-2-displacement.png")
    assert not errors, errors
    context.close()


def test_vector_derivative_lesson(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, "/lessons/3-3-time-derivatives", timeout_s=30)
    host = live_server.host
    _wait_for_quantity(page, "dA_fixed_magnitude", "v > 0")
    _press_preset(page, host, session_id, "fixed-in-frame", lambda p: p["stretch_amplitude_m"] == 0.0 and p["relative_turn_rate_rad_s"] == 0.0)
    _wait_for_quantity(page, "dA_relative_magnitude", "v === 0")
    # A at 30° elevation, the axis tilted 20°: 40° apart at every instant, so |dA/dt| = Ω L sin 40°.
    expected = 0.8 * 1.0 * math.sin(math.radians(40.0))
    _wait_for_quantity(page, "dA_fixed_magnitude", f"Math.abs(v - {expected!r}) < 1e-12")
    values = readout_values(page)
    assert values["dA_transport_magnitude"] == pytest.approx(expected, abs=1e-12)
    assert "ω × A alone" in page.text_content("#readout .readout-message")
    # Back to the defaults' moving vector for the picture: all three arrows at the tip.
    _press_preset(page, host, session_id, "stretching-only", lambda p: p["stretch_amplitude_m"] == 0.5)
    _wait_for_quantity(page, "dA_relative_magnitude", "v > 0")
    show_scene_and_keep_screenshot(page, shots / "lesson-3-3-time-derivatives.png")
    assert not errors, errors
    context.close()


def test_angle_rates_lesson(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, "/lessons/3-4-angular-velocity", timeout_s=30)
    host = live_server.host
    _wait_for_quantity(page, "omega_magnitude", "true")
    _press_preset(page, host, session_id, "steady-top", lambda p: p["rate1_rad_s"] == 0.8 and p["angle2_deg"] == 30.0)
    # Constant rates: |α| = φ̇ψ̇ sin θ = 0.8 rad/s², |ω|² = φ̇² + ψ̇² + 2φ̇ψ̇ cos θ, at every instant.
    _wait_for_quantity(page, "alpha_magnitude", "Math.abs(v - 0.8) < 1e-12")
    values = readout_values(page)
    assert values["omega_magnitude"] == pytest.approx(math.sqrt(0.8**2 + 2.0**2 + 2 * 0.8 * 2.0 * math.cos(math.radians(30.0))), abs=1e-12)
    assert values["alpha_along_axes"] == "(+0.000, +0.000, +0.000)"
    marks = [float(m.get_attribute("data-value")) for m in page.query_selector_all('.control[data-name="angle2_deg"] .mark')]
    assert sorted(marks) == [-180.0, 0.0, 180.0]
    show_scene_and_keep_screenshot(page, shots / "lesson-3-4-angular-velocity-rates.png")

    _press_preset(page, host, session_id, "euler-lock", lambda p: p["angle2_deg"] == 0.0 and p["rate2_rad_s"] == 0.0)
    _wait_for_quantity(page, "recovered_rates", 'typeof v === "string" && v.startsWith("the rates cannot be recovered here")')
    values = readout_values(page)
    assert values["rate_gain"].startswith("unbounded") and values["omega_world"] == "(+0.000, +0.000, +1.500)"
    assert "only θ̇1 + θ̇3" in page.text_content("#readout .readout-message")
    assert not errors, errors
    context.close()
