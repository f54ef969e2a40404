"""Real browser: lessons 4.1 (points of a rigid body) and 4.2 (Eulerian angles), and the course page's section marks.

Each lesson test opens the page, presses presets the lesson text uses, and compares the readout with numbers
worked here by hand (closed forms, not the module under test). Serial, one viewer at a time, like the other
browser tests. Screenshots with DYNLAB_UPDATE_SCREENSHOTS=1.
"""

from __future__ import annotations

import math

import pytest

from tests.browser.conftest import let_webgl_draw, open_lesson, readout_values, screenshot, show_scene_and_keep_screenshot
from tests.browser.test_rotation_sequence_in_browser import _wait_for_quantity
from tests.conftest import wait_until

pytestmark = pytest.mark.browser


def _press_preset(page, host, session_id, preset: str, check) -> None:
    page.click(f'button[data-preset="{preset}"]')
    wait_until(lambda: check(host.session_params(session_id)), 15, what=f"the scene to take the preset {preset}")


def test_rigid_body_points_lesson(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, "/lessons/4-1-general-equations", timeout_s=30)
    host = live_server.host
    _wait_for_quantity(page, "v_B_magnitude", "v > 0")
    # Every term of both formulas is in the readout, with its unit.
    units = dict(page.evaluate("() => [...document.querySelectorAll('#readout tr')].map((tr) => [tr.children[1].dataset.quantity, tr.children[2].textContent])"))
    for name in ("v_A", "omega_cross_r", "v_B"):
        assert units[name] == units[f"{name}_magnitude"] == "m/s"
    for name in ("a_A", "alpha_cross_r", "omega_cross_omega_cross_r", "a_B"):
        assert units[name] == units[f"{name}_magnitude"] == "m/s²"
    # B at the centre: r_B/A = 0, so v_B = v_A = ω₁ L cos β at every instant (ω₁ = 1.2 + 0.3 t rad/s).
    _press_preset(page, host, session_id, "centre-point", lambda p: p["point_radius_fraction"] == 0.0)
    _wait_for_quantity(page, "omega_cross_r_magnitude", "v === 0")
    values = readout_values(page)
    assert values["v_B_magnitude"] == pytest.approx(values["v_A_magnitude"], abs=1e-12)
    assert values["v_A_magnitude"] == pytest.approx(values["turntable_rate"] * 0.8 * math.cos(math.radians(30.0)), rel=1e-12)
    # Back to the rim, steady rates: |v_A| = 1.2 × 0.8 cos 30° = 0.8314 m/s at every instant.
    page.evaluate(
        "async () => { const { lesson } = await import('/static/js/lesson.js');"
        " Object.assign(lesson.session.values, {point_radius_fraction: 1.0}); lesson.schedule(); }"
    )
    _press_preset(page, host, session_id, "steady", lambda p: p["turntable_acceleration_rad_s2"] == 0.0 and p["shaft_elevation_deg"] == 0.0)
    _wait_for_quantity(page, "omega_cross_r_magnitude", "v > 0")
    _wait_for_quantity(page, "v_A_magnitude", f"Math.abs(v - {1.2 * 0.8!r}) < 1e-12")
    let_webgl_draw(page, 1500)
    show_scene_and_keep_screenshot(page, shots / "lesson-4-1-general-equations.png")
    assert not errors, errors
    context.close()


def test_eulerian_angles_lesson(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, "/lessons/4-2-eulerian-angles", timeout_s=30)
    host = live_server.host
    _wait_for_quantity(page, "angular_speed", "v > 0")
    _press_preset(page, host, session_id, "steady-precession", lambda p: p["nutation_rate_rad_s"] == 0.0)
    # θ = 35° fixed, φ̇ = 0.8, ψ̇ = 4 rad/s: |ω|² = φ̇² + ψ̇² + 2 φ̇ ψ̇ cos θ and |α| = φ̇ ψ̇ sin θ at every instant.
    omega = math.sqrt(0.8**2 + 4.0**2 + 2 * 0.8 * 4.0 * math.cos(math.radians(35.0)))
    _wait_for_quantity(page, "angular_speed", f"Math.abs(v - {omega!r}) < 1e-12")
    values = readout_values(page)
    assert values["angular_acceleration"] == pytest.approx(0.8 * 4.0 * math.sin(math.radians(35.0)), abs=1e-12)
    assert values["nutation_deg"] == pytest.approx(35.0, abs=1e-9)
    assert "away from the singularity" in page.text_content("#readout .readout-message")
    let_webgl_draw(page, 1500)
    show_scene_and_keep_screenshot(page, shots / "lesson-4-2-eulerian-angles.png")

    _press_preset(page, host, session_id, "singular", lambda p: p["nutation_deg"] == 0.0 and p["nutation_rate_rad_s"] == 0.0)
    _wait_for_quantity(page, "rates_from_omega", "String(v).startsWith('undefined')")
    assert "only φ ± ψ" in page.text_content("#readout .readout-message")
    assert readout_values(page)["angular_speed"] == pytest.approx(0.8 + 4.0, abs=1e-12)
    assert not errors, errors
    context.close()


def test_course_page_marks_sections_with_and_without_a_lesson(browser, live_server, shots):
    context = browser.new_context(viewport={"width": 1366, "height": 900})
    page = context.new_page()
    page.goto(live_server.url + "/")
    card = page.locator("#chapter-4")
    card.locator("details summary").click()
    items = card.locator("ul.sections > li")
    assert items.count() == 4
    assert "lesson:" in items.nth(0).inner_text() and "General equations" in items.nth(0).inner_text()
    assert items.nth(1).locator('a[href="/lessons/4-2-eulerian-angles"]').is_visible()
    assert "4 of 4 with a lesson" in card.locator("details summary").inner_text()
    chapter5 = page.locator("#chapter-5")
    chapter5.locator("details summary").click()
    texts = [chapter5.locator("ul.sections > li").nth(i).inner_text() for i in range(chapter5.locator("ul.sections > li").count())]
    assert all(("no lesson yet" in t) != ("lesson" in t.replace("no lesson yet", "")) for t in texts), texts
    card.scroll_into_view_if_needed()
    screenshot(page.locator("#chapter-4"), shots / "course-sections-marked.png")
    context.close()
