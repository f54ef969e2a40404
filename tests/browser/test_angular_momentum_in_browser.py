"""Sections 5.1 and 5.3 in a real browser: both lesson pages load the angular-momentum scene and read out its physics.

One test per lesson page; each waits for the scene's readout and checks its numbers
against app.physics at the defaults, then saves the page's screenshot.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from app.physics.systems.ch05 import angular_momentum as am
from app.scenes.ch05.angular_momentum import AngularMomentumScene
from tests.browser.conftest import (
    let_webgl_draw,
    open_lesson,
    readout_values,
    screenshot,
    show_scene_and_keep_screenshot,
)

pytestmark = pytest.mark.browser

SPIN = am.ShaftSpin.from_params(am.PARAMETERS.validate({}))


def _check_momentum(values: dict) -> None:
    # The page shows numbers rounded for reading; 1e-4 relative is well inside any display rounding of 4+ digits.
    assert values["angle_omega_H"] == pytest.approx(math.degrees(SPIN.angle_between_omega_and_H), rel=1e-4)
    assert values["angular_momentum"] == pytest.approx(SPIN.angular_momentum_magnitude_kg_m2_s, rel=1e-4)
    assert values["kinetic_energy"] == pytest.approx(float(SPIN.at(np.zeros(1)).kinetic_energy_J[0]), rel=1e-4)
    assert values["kinetic_energy_centre"] == 0.0


def _check_rate(values: dict) -> None:
    assert values["bearing_moment"] == pytest.approx(SPIN.bearing_moment_N_m, rel=1e-4)
    assert values["bearing_force"] == pytest.approx(SPIN.bearing_moment_N_m / SPIN.bearing_span_m, rel=1e-4)


def _particles_preset(page, shots) -> None:
    """5.1 also shows the particle view: the preset's particle sums match the rigid-body formulas."""
    page.click('button[data-preset="particles"]')
    page.wait_for_selector('#readout [data-quantity="linear_momentum"]', timeout=15_000)
    values = readout_values(page)
    assert "8 point masses of 0.5 kg" in page.text_content("#readout .readout-message")
    assert values["linear_momentum"] == pytest.approx(4.0 * 0.3, rel=1e-4)  # m |v_G| at the preset
    assert values["kinetic_energy_centre"] == pytest.approx(0.5 * 4.0 * 0.3**2, rel=1e-4)
    assert values["particle_sum_mismatch"] < 1e-12 and values["particle_energy_mismatch"] < 1e-12
    preset = next(p for p in AngularMomentumScene.presets if p.name == "particles")
    moving = am.ShaftSpin.from_params(am.PARAMETERS.validate(dict(preset.values)))
    # H_O = H_G + r_G(0) × m v_G is constant in time, so any instant the page shows must match it.
    assert values["angular_momentum_O"] == pytest.approx(float(np.linalg.norm(moving.at(np.zeros(1)).angular_momentum_O)), rel=1e-4)
    page.evaluate("document.getElementById('viewer-wrap').scrollIntoView()")
    let_webgl_draw(page, 2500)
    screenshot(page, shots / "lesson-5-1-linear-and-angular-momentum-particles.png")


LESSONS = [
    ("5-1-linear-and-angular-momentum", "angular_momentum", _check_momentum, _particles_preset),
    ("5-3-rate-of-change-of-angular-momentum", "bearing_moment", _check_rate, None),
]


@pytest.mark.parametrize("lesson_id, quantity, check, then", LESSONS, ids=[lesson[0] for lesson in LESSONS])
def test_lesson_scene_connects_and_its_readout_matches_the_physics(browser, live_server, shots, lesson_id, quantity, check, then):
    context, page, session_id, errors = open_lesson(browser, live_server, f"/lessons/{lesson_id}")
    page.wait_for_selector(f'#readout [data-quantity="{quantity}"]', timeout=30_000)
    check(readout_values(page))
    show_scene_and_keep_screenshot(page, shots / f"lesson-{lesson_id}.png")
    if then is not None:
        then(page, shots)
    assert not errors, errors
    json.dumps(readout_values(page))  # the readout stays plain JSON while the scene runs
    context.close()
