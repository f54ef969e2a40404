"""Chapter 6.4 lesson page in a real browser: the viewer connects and the readout shows the impact.

One test per lesson page scene: it waits for the scene's readout, checks its numbers against
app.physics, then saves the page's screenshot.
"""

from __future__ import annotations

import json

import pytest

from app.physics.systems.ch06.planar_collision import EXAMPLE, collide
from tests.browser.conftest import (
    open_lesson,
    readout_values,
    show_scene_and_keep_screenshot,
)

pytestmark = pytest.mark.browser


def _check_planar_collision(values: dict) -> None:
    c = collide(EXAMPLE.inputs.defaults())
    assert values["slip_state"] == "slid throughout"
    # The readout carries the floats themselves (JSON), so they match to double precision.
    assert values["energy_loss"] == pytest.approx(c.impact.energy_loss_J, rel=1e-12)
    assert values["impulse_x"] == pytest.approx(float(c.impulse_N_s[0]), rel=1e-12)
    assert values["v2_after_y"] == pytest.approx(float(c.after[1].velocity_m_s[1]), rel=1e-12)
    assert values["energy_loss"] == pytest.approx(1.768, abs=5e-4)  # the number the lesson quotes


LESSONS = [("6-4-collisions", "energy_loss", _check_planar_collision)]


@pytest.mark.parametrize("lesson_id, quantity, check", LESSONS, ids=[lesson for lesson, _, _ in LESSONS])
def test_lesson_scene_connects_and_its_readout_matches_the_physics(browser, live_server, shots, lesson_id, quantity, check):
    context, page, session_id, errors = open_lesson(browser, live_server, f"/lessons/{lesson_id}")
    page.wait_for_selector(f'#readout [data-quantity="{quantity}"]', timeout=30_000)
    check(readout_values(page))
    show_scene_and_keep_screenshot(page, shots / f"lesson-{lesson_id}.png")
    assert not errors, errors
    json.dumps(readout_values(page))  # the readout stays plain JSON while the scene runs
    context.close()
