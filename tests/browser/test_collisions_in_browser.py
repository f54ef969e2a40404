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
    keeping_screenshots,
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


def test_the_worked_example_tells_its_story_and_recomputes_its_check_from_the_controls(browser, live_server, shots):
    """Issue 27, point 1, on the page: the collision's worked example shows its situation, what is wanted and why this
    approach before the steps, the check and "what if" after them; moving the friction control (the what-if's input)
    recomputes the steps, whose Check step keeps the pair's momentum (the numbers shown are the server's)."""
    context, page, _, errors = open_lesson(browser, live_server, "/lessons/6-4-collisions", viewer=False)
    example = page.locator(".example[data-example='planar-collision']")
    example.wait_for()
    titles = example.locator(".story h3").all_inner_texts()
    assert titles == ["The situation", "What is wanted", "Why this approach", "The check", "What if"]
    assert example.locator(".story-approach .katex").count() > 0  # the math is typeset
    steps = example.locator(".step h3").all_inner_texts()
    assert steps[-1].startswith("Check")
    before = example.get_attribute("data-inputs")
    page.fill("#ctl-friction_coefficient", "0.9")
    page.press("#ctl-friction_coefficient", "Enter")
    page.wait_for_function(
        "(before) => { const e = document.querySelector(\".example[data-example='planar-collision']\");"
        " return e && e.dataset.inputs !== before; }",
        arg=before,
    )
    inputs = json.loads(page.get_attribute(".example[data-example='planar-collision']", "data-inputs"))
    assert inputs["friction_coefficient"] == 0.9
    solved = EXAMPLE.solve(EXAMPLE.inputs.validate(inputs))
    check_step = solved.steps[-1].values
    assert check_step["p_after"][0] == pytest.approx(check_step["p_before"][0], rel=1e-12)
    shown = page.locator(".example[data-example='planar-collision'] .story-what-if").inner_text()
    assert "friction coefficient" in shown.lower()
    if keeping_screenshots():  # tall enough that the live column does not scroll: the example as a student reads it
        page.set_viewport_size({"width": 1500, "height": 6000})
        box = example.bounding_box()
        assert box is not None
        clip = {"x": box["x"], "y": box["y"], "width": box["width"], "height": min(box["height"], 2000)}
        page.screenshot(path=str(shots / "worked-example-collision.png"), clip=clip)
    assert not errors, errors
    context.close()
