"""Chapter 2 in a real browser: a curve typed into the lesson page drives the scene and its readout.

Waits on the server's own state (viewer list, the scene's parameters) and on
the readout's data attributes, never on rendered text.
"""

from __future__ import annotations

import json

import pytest

from tests.browser.conftest import dismiss_webgl_notice, let_webgl_draw, open_lesson, screenshot, wait_for_polls
from tests.conftest import wait_until

pytestmark = pytest.mark.browser


def _open_lesson(browser, live_server, path):
    opened = open_lesson(browser, live_server, path, timeout_s=30)
    dismiss_webgl_notice(opened[1])
    return opened


def _type(page, name, text):
    page.fill(f"#ctl-{name}", text)
    page.press(f"#ctl-{name}", "Enter")


def _wait_for_quantity(page, name, expected, rel=1e-9):
    """Wait until the readout's ``name`` equals ``expected`` (the page polls once a second)."""
    page.wait_for_function(
        """([name, expected, rel]) => {
            const cell = document.querySelector(`#readout [data-quantity="${name}"]`);
            if (!cell) return false;
            const v = JSON.parse(cell.dataset.value);
            return typeof v === "number" && Math.abs(v - expected) <= rel * Math.abs(expected);
        }""",
        arg=[name, expected, rel],
        timeout=20_000,
    )
    return json.loads(page.get_attribute(f'#readout [data-quantity="{name}"]', "data-value"))


def _screenshot(page, path):
    dismiss_webgl_notice(page)
    page.evaluate("window.scrollTo(0, 0); const live = document.querySelector('.lesson-live'); if (live) live.scrollTop = 0")
    let_webgl_draw(page, 2500)
    screenshot(page, path)


def test_typed_helix_gives_the_closed_form_curvature_and_torsion(browser, live_server, shots):
    """Type x = 2 cos t, y = 2 sin t, z = 0.5 t: κ = a/(a²+c²) = 2/4.25 and τ = c/(a²+c²) = 0.5/4.25
    (1/m) in the readout; then a bad formula shows an inline error and changes nothing."""
    context, page, session_id, errors = _open_lesson(browser, live_server, "/lessons/2-1-path-variables")
    host = live_server.host
    # The default helix (a = 1 m, c = 0.2 m) first.
    _wait_for_quantity(page, "curvature", 1 / 1.04)

    for name, text in (("x_of_t", "2*cos(t)"), ("y_of_t", "2*sin(t)"), ("z_of_t", "0.5*t")):
        _type(page, name, text)
    wait_until(lambda: host.session_params(session_id)["z_of_t"] == "0.5*t", 15, what="the scene to take the typed helix")
    # Exact symbolic derivatives: the readout carries the closed form to rounding (1e-12 relative).
    assert _wait_for_quantity(page, "curvature", 2 / 4.25) == pytest.approx(2 / 4.25, rel=1e-12)
    assert _wait_for_quantity(page, "torsion", 0.5 / 4.25) == pytest.approx(0.5 / 4.25, rel=1e-12)
    assert _wait_for_quantity(page, "speed", 4.25**0.5) == pytest.approx(4.25**0.5, rel=1e-12)
    assert _wait_for_quantity(page, "a_normal", 2.0) == pytest.approx(2.0, rel=1e-12)
    assert page.locator("#control-error").is_hidden()
    _screenshot(page, shots / "lesson-2-1-path-variables.png")

    # The same curve through the simulate API: a series of the same constant curvature.
    report = page.request.post(
        live_server.url + "/api/scenes/space-curve/simulate",
        data={"params": {"x_of_t": "2*cos(t)", "y_of_t": "2*sin(t)", "z_of_t": "0.5*t"}, "t_end": 3.0, "frame_rate": 10.0},
    ).json()
    assert report["units"]["curvature"] == "1/m"
    assert report["series"]["torsion"] == pytest.approx([0.5 / 4.25] * 31, rel=1e-12)

    # A bad formula: inline error naming the character, the control marked, the scene untouched.
    before = dict(host.session_params(session_id))
    _type(page, "x_of_t", "2*cos(t")
    page.wait_for_function("() => !document.getElementById('control-error').hidden", timeout=10_000)
    message = page.text_content("#control-error")
    # The page names the formula as its control does (its label and unit), never by its parameter name.
    assert message.startswith("x(t) (m):") and "x_of_t" not in message, message
    assert "never closed" in message and "character 6" in message, message
    assert "invalid" in (page.get_attribute('.control[data-name="x_of_t"]', "class") or "")
    wait_for_polls(page, 2)  # two readout polls later, the scene still has its parameters
    assert host.session_params(session_id) == before
    assert host.session_params(session_id) == before
    assert _wait_for_quantity(page, "curvature", 2 / 4.25) == pytest.approx(2 / 4.25, rel=1e-12)

    # Something that is not mathematics at all is refused the same way.
    _type(page, "x_of_t", "__import__('os').system('ls')")
    page.wait_for_function("() => document.getElementById('control-error').textContent.includes('underscores are not allowed')", timeout=10_000)
    assert page.text_content("#control-error").startswith("x(t) (m):")  # named as the control is, not x_of_t
    assert host.session_params(session_id) == before
    assert not errors, errors
    context.close()


def test_cylindrical_components_of_the_conical_spiral(browser, live_server, shots):
    """The conical-spiral preset (R = 0.1 t m, θ = 2t rad) in cylindrical unit vectors:
    v_R = Ṙ = 0.1 m/s and a_θ = 2 Ṙ θ̇ = 0.4 m/s² at every instant."""
    context, page, session_id, errors = _open_lesson(browser, live_server, "/lessons/2-3-curvilinear-coordinates")
    host = live_server.host
    page.click('button[data-preset="conical-spiral"]')
    wait_until(lambda: host.session_params(session_id)["frame"] == "cylindrical", 15, what="the preset to reach the scene")
    assert _wait_for_quantity(page, "v_R", 0.1) == pytest.approx(0.1, rel=1e-12)
    assert _wait_for_quantity(page, "a_theta", 0.4) == pytest.approx(0.4, rel=1e-12)
    assert json.loads(page.get_attribute('#readout [data-quantity="a_z"]', "data-value")) == pytest.approx(0.0, abs=1e-12)
    _screenshot(page, shots / "lesson-2-3-curvilinear-coordinates.png")
    assert not errors, errors
    context.close()


#: Where the control error is, against the input of the control it names and the screen (px).
ERROR_PLACE = """(name) => {
  const input = document.getElementById(`ctl-${name}`).getBoundingClientRect();
  const box = document.getElementById('control-error').getBoundingClientRect();
  return { below_input_px: box.top - input.bottom, top: box.top, bottom: box.bottom, screen: window.innerHeight };
}"""


def test_on_a_phone_a_controls_error_shows_under_that_control(browser, live_server):
    # Issue 29, item 7: on a phone the message appeared under the whole control list, far below the control (about
    # 1,600 px on long lists), out of view. Now it is inside the control's row, under its input, and in view.
    context = browser.new_context(viewport={"width": 390, "height": 844}, is_mobile=True, has_touch=True)
    context, page, _, errors = open_lesson(browser, live_server, "/lessons/2-1-path-variables", context=context)
    dismiss_webgl_notice(page)
    page.locator("#ctl-x_of_t").scroll_into_view_if_needed()
    _type(page, "x_of_t", "2*cos(t")
    page.wait_for_function("() => !document.getElementById('control-error').hidden", timeout=10_000)
    place = page.evaluate(ERROR_PLACE, "x_of_t")
    assert page.evaluate("() => document.getElementById('control-error').closest('.control')?.dataset.name") == "x_of_t"
    assert 0 <= place["below_input_px"] <= 120 and 0 <= place["top"] and place["bottom"] <= place["screen"], place
    # Corrected, the message goes; a later message about no control in particular is under the list again.
    _type(page, "x_of_t", "2*cos(t)")
    page.wait_for_function("() => document.getElementById('control-error').hidden", timeout=10_000)
    assert not errors, errors
    context.close()
