"""The typed-Lagrangian lesson in a real browser: type a kinetic energy, the equations and the motion follow it."""

from __future__ import annotations

import math

import pytest

from tests.browser.conftest import dismiss_webgl_notice, open_lesson, readout_values, show_scene_and_keep_screenshot
from tests.conftest import wait_until

pytestmark = pytest.mark.browser

LESSON = "7-5-typed-lagrangian"
#: Twice the default double pendulum's kinetic energy: heavier bobs, the same V.
HEAVIER = "m*l^2*(2*q1d^2 + q2d^2 + 2*cos(q1 - q2)*q1d*q2d)"
#: The default start: at rest with q = (1, 0) rad, m = 1 kg, l = 0.5 m, g = 9.81 m/s², so h = T + V = V(q0) (J).
H_AT_START_J = -1.0 * 9.81 * 0.5 * (2.0 * math.cos(1.0) + 1.0)


def _message(page) -> str:
    """The readout message's source (its $$…$$ parts are shown as KaTeX equations)."""
    return page.evaluate("() => document.querySelector('#readout .readout-message').dataset.source || ''")


def test_typing_a_kinetic_energy_rederives_the_equations_and_runs_them(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, f"/lessons/{LESSON}")
    dismiss_webgl_notice(page)
    page.wait_for_selector('#readout [data-quantity="jacobi_integral_J"]', timeout=40_000)
    before = readout_values(page)
    # h is conserved: the automatic step keeps its drift below 1e-4 of its scale (~10 J) over the first seconds.
    assert before["jacobi_integral_J"] == pytest.approx(H_AT_START_J, abs=1e-3)
    first_equations = _message(page)
    assert "Lagrange's equations" in first_equations and "2 l^{2} m" in first_equations

    page.fill("#ctl-kinetic_energy", HEAVIER)
    page.press("#ctl-kinetic_energy", "Enter")
    host = live_server.host
    wait_until(lambda: host.session_params(session_id)["kinetic_energy"] == HEAVIER, 60, what="the scene to take the typed T")
    # Doubling T doubles every inertia term: the first equation now starts 4 l² m q̈₁.
    page.wait_for_function("() => (document.querySelector('#readout .readout-message').dataset.source || '').includes('4 l^{2} m')", timeout=30_000)
    assert page.locator("#readout .readout-equation .katex").count() == 2  # shown as equations, not as LaTeX source
    assert page.locator("#readout .katex-error").count() == 0
    after = readout_values(page)
    assert after["jacobi_integral_J"] == pytest.approx(H_AT_START_J, abs=1e-3)  # same start at rest, same V
    assert page.locator("#control-error").is_hidden()

    # A singular mass matrix is refused with a message naming the field, and the scene keeps the last good T.
    page.fill("#ctl-kinetic_energy", "m*(q1d + q2d)^2/2")
    page.press("#ctl-kinetic_energy", "Enter")
    page.wait_for_selector("#control-error:not([hidden])", timeout=30_000)
    assert "singular" in page.locator("#control-error").text_content()
    assert host.session_params(session_id)["kinetic_energy"] == HEAVIER

    show_scene_and_keep_screenshot(page, shots / f"lesson-{LESSON}.png")
    assert not errors, errors
    context.close()
