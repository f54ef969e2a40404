"""Lesson 8.1 in a real browser: both linkages in absolute coordinates run, and the readout's pin forces are the physics.

The readout's pin forces (the multipliers' sizes) are checked against independent computations at the
crank angle and speed the same readout shows: chapter 6's Newton–Euler solve for the slider-crank, and
for the four-bar the force balance ``Cᵀλ = M a − f`` with ``a`` from chapter 4's loop closure and the
one-degree-of-freedom equation's θ̈. The four-bar's page also switches the DAE algorithm, the integrator
and the Baumgarte gains and finds them in the running scene.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from app.physics.systems.ch06 import mechanism_kinetics as chapter6
from app.physics.systems.ch08 import massive_four_bar as four_bar
from app.physics.systems.ch08 import slider_crank_dae as slider_crank
from tests.browser.conftest import open_lesson, readout_values, show_scene_and_keep_screenshot
from tests.conftest import wait_until

pytestmark = pytest.mark.browser

LESSON = "8-1-constrained-lagrange"
#: The live state keeps g and C v at round-off (projection, the default); its pin forces differ from the independent
#: ones at the same crank angle and speed by ≤ 7e-10 N of up to 5000 N (measured over the 4 s before the speed-limit
#: pause, 1.5e-13 relative). 1e-6 of the largest force is far above that and far below a wrong sign, mass or pin point.
FORCE_RTOL = 1e-6


def _open_scene(browser, live_server, path: str, force_quantity: str):
    """Open the lesson at ``path``; once the readout shows ``force_quantity``, check its counts and residuals.
    Returns ``(context, page, session_id, errors, readout values)``."""
    context, page, session_id, errors = open_lesson(browser, live_server, path)
    page.wait_for_selector(f'#readout [data-quantity="{force_quantity}"]', timeout=30_000)
    values = readout_values(page)
    assert (values["coordinates"], values["constraints"], values["degrees_of_freedom"]) == (9.0, 8.0, 1.0)
    assert 0.0 <= values["constraint_position"] < 1e-10  # projection: round-off, measured ≤ 2.2e-16 m
    assert 0.0 <= values["constraint_velocity"] < 1e-9  # measured ≤ 2.7e-15 m/s
    # RK4 at the automatic step: measured ≤ 3.1e-4 J (slider-crank) and 4.3e-5 J (four-bar) over the 4 s before the
    # pause (after which nothing moves), while the torque does ~300 J of work.
    assert abs(values["work_energy_residual_J"]) < 1e-3
    return context, page, session_id, errors, values


def _assert_pin_forces(values: dict, expected: dict[str, np.ndarray]) -> None:
    """The readout's |λ| of each pin (by plain joint name) against the expected force vectors (N)."""
    largest = max(float(np.linalg.norm(force)) for force in expected.values())
    for joint, force in expected.items():
        assert values[f"pin_force_{joint}_N"] == pytest.approx(float(np.linalg.norm(force)), abs=FORCE_RTOL * largest), joint


def test_slider_crank_readout_shows_chapter_6_pin_forces(browser, live_server, shots):
    context, page, session_id, errors, values = _open_scene(browser, live_server, f"/lessons/{LESSON}", "pin_force_O_N")
    params = slider_crank.PARAMETERS.defaults()
    theta = np.array([math.radians(values["crank_angle"])])
    forces = chapter6.newton_euler(
        slider_crank.chapter6_links(params), theta, np.array([values["crank_speed_rad_s"]]), drive_torque_N_m=params["drive_torque_N_m"]
    )
    _assert_pin_forces(values, {"O": forces.pivot_O_N[0], "A": forces.crank_pin_A_N[0], "B": forces.wrist_pin_B_N[0]})
    units = {row["name"]: row["unit"] for row in _readout_rows(page)}
    assert units["pin_force_O_N"] == "N" and units["constraint_position"] == "m" and units["work_energy_residual_J"] == "J"
    # The algorithm has a row of its own: the message under the table may already be the speed-limit pause.
    assert "projection" in page.text_content('#readout [data-quantity="algorithm"]')
    # Under the default 2 N·m the frictionless crank speeds up until the scene pauses at its step's speed limit
    # (after about 4 s); the kept picture shows the mechanism coasting instead, which runs for ever.
    _set_number(page, "drive_torque_N_m", "0")
    wait_until(lambda: live_server.host.session_params(session_id)["drive_torque_N_m"] == 0.0, 15, what="the scene to coast")
    show_scene_and_keep_screenshot(page, shots / f"lesson-{LESSON}.png")
    assert not errors, errors
    json.dumps(readout_values(page))
    context.close()


def test_four_bar_pin_forces_and_the_controls_reach_the_scene(browser, live_server, shots):
    context, page, session_id, errors, values = _open_scene(browser, live_server, f"/lessons/{LESSON}?scene=four-bar-dae", "pin_force_O4_N")
    params = four_bar.PARAMETERS.defaults()
    _assert_pin_forces(values, _four_bar_pin_forces(params, math.radians(values["crank_angle"]), values["crank_speed_rad_s"]))

    page.select_option("#ctl-method", "baumgarte")
    page.select_option("#ctl-integrator", "dopri5")
    _set_number(page, "baumgarte_alpha_1_s", "12")
    _set_number(page, "drive_torque_N_m", "0")  # coasting: no pause at the step's speed limit before the picture
    host = live_server.host

    def scene_took_the_controls() -> bool:
        scene = host.instances(session_id)[0]
        return scene.params["baumgarte_alpha_1_s"] == 12.0 and scene.params["drive_torque_N_m"] == 0.0 and scene.run.integrator.name == "dopri5"

    wait_until(scene_took_the_controls, 15, what="the scene to take the method, integrator and gain")
    scene = host.instances(session_id)[0]
    assert scene.run_model.algorithm() == "baumgarte"
    page.wait_for_function(
        "() => (document.querySelector('#readout .readout-message').textContent || '').includes('α = 12/s')", timeout=20_000
    )
    message = page.text_content("#readout .readout-message")
    assert "baumgarte (α = 12/s, β = 5/s)" in message, message
    values = readout_values(page)
    assert values["constraint_position"] < 1e-6  # Baumgarte holds the drift near the integrator's error, not at round-off
    show_scene_and_keep_screenshot(page, shots / f"lesson-{LESSON}-four-bar.png")
    assert not errors, errors
    context.close()


def _set_number(page, name: str, value: str) -> None:
    """Type ``value`` into the number control ``name`` and send it, as a student does."""
    page.fill(f"#ctl-{name}", value)
    page.dispatch_event(f"#ctl-{name}", "change")


def _readout_rows(page) -> list[dict]:
    """Each readout row's quantity name and unit as the page shows them."""
    return page.evaluate(
        "() => [...document.querySelectorAll('#readout tbody tr')].map((tr) => "
        "({name: tr.children[1].dataset.quantity, unit: tr.children[2].textContent}))"
    )


def _four_bar_pin_forces(params, theta_rad: float, omega_rad_s: float) -> dict[str, np.ndarray]:
    """Pin forces (N, 2 each) by Newton–Euler: θ̈ from the one-DOF equation, every link's acceleration from
    chapter 4's loop closure, then the 8 pin-force components from the 9 equations Cᵀλ = M a − f."""
    theta, omega = np.array([theta_rad]), np.array([omega_rad_s])
    alpha = four_bar.crank_acceleration_rad_s2(params, theta, omega)
    q, v, a = (x[0] for x in four_bar.four_bar_absolute_motion(params, theta, omega, alpha))
    system = four_bar.massive_four_bar_system(params)
    mass, forces = system.mass_and_forces(0.0, q, v)
    _, jacobian, _ = system.constraint_terms(q, v)
    multipliers, *_ = np.linalg.lstsq(jacobian.T, mass @ a - forces, rcond=None)
    rows = four_bar.massive_four_bar_linkage(params).multiplier_rows()
    return {joint.translate(str.maketrans("₂₄", "24")): multipliers[rows[joint]] for joint in four_bar.JOINT_NAMES}
