"""The N-link pendulum lesson in a real browser: the readout's frequencies are the closed form's, and a longer chain
started in another mode is prepared and shown."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import eigh

from tests.browser.conftest import dismiss_webgl_notice, open_lesson, readout_values, show_scene_and_keep_screenshot
from tests.physics.mechanics.multibody.test_n_link_pendulum_model import linear_model_by_hand

pytestmark = pytest.mark.browser

LESSON = "9-4-n-link-pendulum"


def _closed_form(links: int) -> np.ndarray:
    mass, stiffness = linear_model_by_hand(links)
    return np.sqrt(eigh(stiffness, mass, eigvals_only=True))


def _set(page, name: str, value: str) -> None:
    page.fill(f"#ctl-{name}", value)
    page.press(f"#ctl-{name}", "Enter")


def test_the_readout_gives_the_closed_form_frequencies_and_a_longer_chain_in_another_mode(browser, live_server, shots):
    context, page, _, errors = open_lesson(browser, live_server, f"/lessons/{LESSON}")
    dismiss_webgl_notice(page)
    page.wait_for_selector('#readout [data-quantity="lowest_frequency_rad_s"]', timeout=40_000)
    six = _closed_form(6)
    shown = readout_values(page)
    assert abs(shown["lowest_frequency_rad_s"] - six[0]) < 1e-9 * six[0]
    assert abs(shown["highest_frequency_rad_s"] - six[-1]) < 1e-9 * six[-1]
    assert shown["member"] == "6-link planar chain" and shown["small_oscillations"].startswith("holds")

    _set(page, "links", "8")
    _set(page, "mode", "3")
    page.wait_for_function(
        "() => { const v = document.querySelector('#readout [data-quantity=\"mode_frequency_rad_s\"]')?.dataset.value;"
        " const m = document.querySelector('#readout [data-quantity=\"member\"]')?.dataset.value;"
        " return m === '\"8-link planar chain\"' && v && JSON.parse(v) > 6; }",
        timeout=60_000,
    )
    eight = _closed_form(8)
    shown = readout_values(page)
    assert abs(shown["mode_frequency_rad_s"] - eight[2]) < 1e-9 * eight[2]
    assert "written out" in shown["operations"]
    show_scene_and_keep_screenshot(page, shots / f"lesson-{LESSON}.png")
    assert not errors, errors
    context.close()
