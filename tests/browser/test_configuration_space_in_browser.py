"""The virtual-displacements lesson in a real browser: the readout's numbers for the fixed wire, the sliding hoop and
the parking knife edge match the physics, and the nonholonomic case is what the screenshot keeps."""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.systems.ch07 import configuration_space as physics
from tests.browser.conftest import let_webgl_draw, open_lesson, readout_values, show_scene_and_keep_screenshot
from tests.conftest import wait_until

pytestmark = pytest.mark.browser

LESSON = "7-3-virtual-displacements"
SCENE = "configuration-space-constraints"


def _choose(page, host, session_id, constraint: str, shown) -> dict:
    """Pick ``constraint`` and return the first readout for which ``shown(values)`` holds (the table refreshes ~1/s)."""
    page.select_option("#ctl-constraint", constraint)
    wait_until(lambda: host.session_params(session_id)["constraint"] == constraint, 10, what=f"the scene to show {constraint}")
    found: list[dict] = []

    def new_table() -> bool:
        values = readout_values(page)
        found[:] = [values]
        return shown(values)

    wait_until(new_table, 20, interval_s=0.2, what=f"the readout of the {constraint} case")
    return found[0]


def test_lesson_readouts_match_the_three_constraints_and_the_knife_edge_parks_sideways(browser, live_server, shots):
    context, page, session_id, errors = open_lesson(browser, live_server, f"/lessons/{LESSON}")
    host = live_server.host
    page.wait_for_selector('#readout [data-quantity="bead_speed_m_s"]', timeout=30_000)
    values = readout_values(page)
    # The readout's time and numbers come from one frame and JSON carries floats exactly: only summation order differs.
    snap = physics.FixedEllipse(1.5, 1.0, 0.6).snapshot(values["t_s"])
    assert values["bead_speed_m_s"] == pytest.approx(float(np.linalg.norm(snap.velocity)), rel=1e-12)
    assert values["bead_x_m"] == pytest.approx(float(snap.position[0]), abs=1e-12)
    assert abs(values["virtual_variation"]) < 1e-12 and abs(values["actual_variation_1_s"]) < 1e-12

    values = _choose(page, host, session_id, "rheonomic", lambda v: v.get("constraint_time_rate_1_s", 0.0) != 0.0)
    snap = physics.SlidingHoop(1.0, 0.8, 1.5, 0.6).snapshot(values["t_s"])
    assert values["constraint_time_rate_1_s"] == pytest.approx(snap.time_rate, abs=1e-12)
    assert values["angle_dr_virtual_deg"] == pytest.approx(snap.angle_between_deg, abs=1e-9)
    assert abs(values["virtual_variation"]) < 1e-12 and abs(values["actual_variation_1_s"]) < 1e-12

    values = _choose(page, host, session_id, "nonholonomic", lambda v: "sideways_drift_m" in v)
    # The lesson's numbers: s = 0.8 m, α = 30°: s sin α = 0.4 m sideways, s α = 0.4189 m to leading order.
    assert values["sideways_drift_m"] == pytest.approx(0.8 * math.sin(math.radians(30.0)), rel=1e-12)
    assert values["sideways_drift_leading_m"] == pytest.approx(0.41888, abs=1e-5)
    assert values["bracket_out_of_plane"] == pytest.approx(1.0, abs=1e-15)
    assert abs(values["slip_rate_m_s"]) < 1e-12
    let_webgl_draw(page, 2500)  # into the manoeuvre, so the screenshot shows the blade away from its start
    show_scene_and_keep_screenshot(page, shots / f"lesson-{LESSON}.png")
    assert not errors, errors
    context.close()
