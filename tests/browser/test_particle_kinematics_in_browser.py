"""Chapter 2's particle scenes in a real browser: lessons 2.2, 2.3 and 2.4 each open their own scene and readout.

Waits on the server's own state (the scene's parameters) and on the readout's data
attributes, never on rendered text. Numbers are the closed forms of each preset, to
1e-12 relative (the readout carries the model's double-precision value).
"""

from __future__ import annotations

import json
import math

import pytest

from tests.browser.conftest import open_lesson, show_scene_and_keep_screenshot
from tests.conftest import wait_until

pytestmark = pytest.mark.browser


def wait_for_quantity(page, name, expected, *, rel=1e-12, abs_=0.0):
    """Wait until the readout's ``name`` is ``expected`` (the page polls about once a second); return it."""
    page.wait_for_function(
        """([name, expected, rel, abs]) => {
            const cell = document.querySelector(`#readout [data-quantity="${name}"]`);
            if (!cell) return false;
            const v = JSON.parse(cell.dataset.value);
            return typeof v === "number" && Math.abs(v - expected) <= Math.max(rel * Math.abs(expected), abs);
        }""",
        arg=[name, expected, rel, abs_],
        timeout=20_000,
    )
    return json.loads(page.get_attribute(f'#readout [data-quantity="{name}"]', "data-value"))


def press_preset(page, host, session_id, preset, expected_params):
    page.click(f'button[data-preset="{preset}"]')
    wait_until(
        lambda: all(host.session_params(session_id)[k] == v for k, v in expected_params.items()),
        15,
        what=f"the preset {preset} to reach the scene",
    )


def test_cartesian_components_lesson_shows_the_projectile_s_constant_acceleration(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, "/lessons/2-2-rectangular-cartesian")
    host = live_server.host
    assert host.session_scene(session_id) == "cartesian-components"
    # The default sine slot: ẍ = 0 and ẋ = 0.5 m/s at every instant.
    assert wait_for_quantity(page, "x_dot", 0.5) == pytest.approx(0.5, rel=1e-12)
    assert wait_for_quantity(page, "x_ddot", 0.0, abs_=1e-15) == 0.0
    press_preset(page, host, session_id, "projectile", {"motion": "projectile"})
    alpha, psi = math.radians(50.0), math.radians(30.0)
    assert wait_for_quantity(page, "x_dot", 8.0 * math.cos(alpha) * math.cos(psi)) == pytest.approx(4.453363193811356, rel=1e-12)
    assert wait_for_quantity(page, "z_ddot", -9.81) == pytest.approx(-9.81, rel=1e-12)
    assert wait_for_quantity(page, "acceleration_magnitude", 9.81) == pytest.approx(9.81, rel=1e-12)
    show_scene_and_keep_screenshot(page, shots / "lesson-2-2-rectangular-cartesian.png")
    assert not errors, errors
    context.close()


def test_curvilinear_lesson_shows_the_loxodrome_in_spherical_components(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, "/lessons/2-3-curvilinear-coordinates")
    host = live_server.host
    assert host.session_scene(session_id) == "curvilinear-coordinates"
    press_preset(page, host, session_id, "loxodrome", {"path": "loxodrome", "frame": "spherical"})
    # On the sphere: r = 1 m and v_r = 0; the magnitudes from the components equal the Cartesian ones.
    assert wait_for_quantity(page, "r", 1.0) == pytest.approx(1.0, rel=1e-12)
    assert wait_for_quantity(page, "v_r", 0.0, abs_=1e-12) == pytest.approx(0.0, abs=1e-12)
    values = page.evaluate(
        "() => Object.fromEntries([...document.querySelectorAll('#readout [data-quantity]')]"
        ".map((cell) => [cell.dataset.quantity, JSON.parse(cell.dataset.value)]))"
    )
    assert values["speed_from_components"] == pytest.approx(values["speed"], rel=1e-12)
    # The bearing: every meridian crossed at 75° from north, v_φ / v_θ = −cot 75°.
    assert values["v_phi"] / values["v_theta"] == pytest.approx(-1.0 / math.tan(math.radians(75.0)), rel=1e-9)
    show_scene_and_keep_screenshot(page, shots / "lesson-2-3-spherical-unit-vectors.png")
    # On the pole the readout says why a row has no number instead of showing one.
    press_preset(page, host, session_id, "on-the-pole", {"path": "latitude-circle", "path_angle_deg": 0.0})
    page.wait_for_function(  # a row without a number carries its words as the cell's value
        """() => { const cell = document.querySelector('#readout [data-quantity="v_theta"]');
                   return cell && typeof JSON.parse(cell.dataset.value) === "string"; }""",
        timeout=20_000,
    )
    assert json.loads(page.get_attribute('#readout [data-quantity="v_theta"]', "data-value")) == "no value here (see the message below)"
    assert "polar axis" in page.text_content("#readout")
    assert not errors, errors
    context.close()


def test_mixed_description_lesson_shows_the_rotating_arm_and_its_coriolis_term(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, "/lessons/2-4-mixed-descriptions")
    host = live_server.host
    assert host.session_scene(session_id) == "rotating-arm"
    press_preset(page, host, session_id, "fixed-collar", {"collar_amplitude_m": 0.0, "collar_mean_m": 1.0})
    # A clamped collar at r = 1 m on an arm at 1 rad/s: only the centripetal term, −r θ̇² = −1 m/s²; no Coriolis.
    assert wait_for_quantity(page, "a_centripetal", -1.0) == pytest.approx(-1.0, rel=1e-12)
    assert wait_for_quantity(page, "a_coriolis", 0.0, abs_=1e-15) == 0.0
    press_preset(page, host, session_id, "sliding-collar", {"collar_amplitude_m": 0.6})
    page.wait_for_selector('#readout [data-quantity="a_coriolis"]')
    show_scene_and_keep_screenshot(page, shots / "lesson-2-4-mixed-descriptions.png")
    # The lesson's second scene, the typed curve, is one link away.
    assert page.locator('.scene-picker a[href$="?scene=space-curve"]').count() == 1
    assert not errors, errors
    context.close()


def test_a_busy_server_is_waited_out_and_the_students_preset_still_reaches_the_scene(browser, live_server):
    """The scene's worker busy or restarting answers the page's change with 503 and Retry-After: the page says so in
    its error line, waits as told and sends the change again, so a student's preset is not lost (it was: the page
    showed the refusal and the scene kept its old parameters)."""
    context, page, session_id, errors = open_lesson(browser, live_server, "/lessons/2-4-mixed-descriptions")
    refused: list[str] = []

    def busy_once(route):
        if route.request.method == "PUT" and not refused:
            refused.append(route.request.post_data or "")
            route.fulfill(status=503, headers={"Retry-After": "1"}, content_type="application/json",
                          body=json.dumps({"detail": "this scene's worker is busy; try again shortly"}))
        else:
            route.continue_()

    route = f"**/api/scenes/rotating-arm/sessions/{session_id}"
    page.route(route, busy_once)
    page.click('button[data-preset="fixed-collar"]')  # once: the page itself must send it again
    page.wait_for_function("() => /server is busy; sending your change again in 1 s/.test(document.getElementById('control-error').textContent)")
    # The page's next request goes straight to the server (a routed one would wait for this thread's Playwright calls).
    page.unroute(route)
    preset = {"collar_amplitude_m": 0.0, "collar_mean_m": 1.0}
    params = live_server.host.session_params
    wait_until(lambda: all(params(session_id)[k] == v for k, v in preset.items()), 15, what="the preset sent again")
    assert len(refused) == 1 and json.loads(refused[0])["params"]["collar_amplitude_m"] == 0.0
    page.wait_for_function("() => document.getElementById('control-error').hidden")
    assert not errors, errors
    context.close()
