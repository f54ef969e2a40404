"""Chapter 1's readouts on a real headless viewer: what a student reads beside each scene, checked against
closed forms, an independent finite difference, or the worked example's own outputs.

Each scene is built with its defaults or a preset and run for one second of demo (30 frames), as in class.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.systems.ch01 import projectile, radar_tracking, robot_arm_cable
from app.scenes.ch01.projectile_drag import ProjectileDragScene
from app.scenes.ch01.radar_tracking import RadarTrackingScene
from app.scenes.ch01.robot_arm_cable import RobotArmCableScene
from app.scenes.kit import FRAME_DT_S

DEMO_FRAMES = 30


def read_after(scene_cls, client, values=None, *, preset=None, frames=DEMO_FRAMES):
    """Build the scene (defaults, then ``preset``, then ``values``), run ``frames`` frames, close it:
    ``(readout, params)``."""
    params = dict(next(p for p in scene_cls.presets if p.name == preset).values) if preset else {}
    scene = scene_cls(client, scene_cls.parameters.validate({**params, **(values or {})}))
    try:
        for _ in range(frames):
            with client.atomic():
                scene.advance(FRAME_DT_S)
        return scene.readout(), scene.params
    finally:
        scene.close()


def by_name(readout) -> dict:
    return {q.name: q for q in readout.quantities}


# ---- projectile with drag -------------------------------------------------------------------------


def test_vacuum_preset_reads_the_parabolas_closed_form(client):
    read, p = read_after(ProjectileDragScene, client, preset="vacuum")
    v0, alpha, g = p["speed0_m_s"], math.radians(p["elevation_deg"]), p["g_m_s2"]
    # Range v₀² sin 2α / g, flight 2 v₀ sin α / g, apex (v₀ sin α)²/(2g): the integrator flies a quadratic in t
    # exactly up to rounding and locates the events to ~1e-13 s, so 1e-10 relative.
    expected = {
        "range_m": v0**2 * math.sin(2 * alpha) / g,
        "flight_time_s": 2 * v0 * math.sin(alpha) / g,
        "apex_height_m": (v0 * math.sin(alpha)) ** 2 / (2 * g),
        "climb_time_s": v0 * math.sin(alpha) / g,
        "fall_time_s": v0 * math.sin(alpha) / g,
        "range_percent_of_vacuum": 100.0,
    }
    for name, value in expected.items():
        assert read.value(name) == pytest.approx(value, rel=1e-10), name
    assert read.value("vacuum_range_m") == pytest.approx(expected["range_m"], rel=1e-14)  # the closed form itself
    assert by_name(read)["longer_leg"].text == "neither: equal"
    assert read.value("work_drag_J") == 0.0 and "No drag" in read.message


def test_baseball_reads_its_flight_beside_the_vacuums(client):
    read, p = read_after(ProjectileDragScene, client, preset="baseball")
    out = projectile.solve(p).outputs
    # The flight's numbers are the worked example's (the same integration: equal to rounding).
    assert read.value("range_m") == pytest.approx(out["range_m"], rel=1e-14)
    assert read.value("flight_time_s") == pytest.approx(out["flight_time_s"], rel=1e-14)
    # The located apex is the true maximum; the example's is the highest of 241 samples, lower by at most
    # |z''| (dt/2)²/2; near the top z'' = −g − (c|v|/m) v_z, and within half a sample (v_z ≲ 0.1 m/s) the drag's
    # part is ≈ 1e-3 g, so 1.1 g bounds |z''| with margin.
    dt = out["flight_time_s"] / 240
    assert 0.0 <= read.value("apex_height_m") - out["max_height_m"] <= 1.1 * p["g_m_s2"] * (dt / 2) ** 2 / 2
    # The question's "153 m in a vacuum" and the answer's share of it.
    vacuum_range = p["speed0_m_s"] ** 2 * math.sin(math.radians(2 * p["elevation_deg"])) / p["g_m_s2"]
    assert read.value("vacuum_range_m") == pytest.approx(vacuum_range, rel=1e-14) and round(vacuum_range) == 153
    assert read.value("range_percent_of_vacuum") == pytest.approx(100 * out["range_m"] / vacuum_range, rel=1e-14)
    assert 50.0 < read.value("range_percent_of_vacuum") < 80.0  # drag costs a baseball about a third of its range
    assert by_name(read)["longer_leg"].text == "the fall" and read.value("fall_time_s") > read.value("climb_time_s")
    assert read.value("t_s") == pytest.approx(DEMO_FRAMES * FRAME_DT_S, rel=1e-12)


def test_the_instant_on_screen_keeps_the_work_energy_balance(client):
    # T − T₀ = W_g + W_d holds at every sample to 1e-9 of T₀ (see the physics tests); the readout interpolates
    # each column linearly between samples, and a linear blend of balanced rows stays balanced to the same 1e-9.
    read, params = read_after(ProjectileDragScene, client, preset="baseball", frames=47)
    kinetic0 = 0.5 * params["mass_kg"] * params["speed0_m_s"] ** 2
    balance = read.value("kinetic_energy_J") - kinetic0 - read.value("work_gravity_J") - read.value("work_drag_J")
    assert abs(balance) <= 1e-9 * kinetic0
    assert read.value("work_drag_J") < -0.1 * kinetic0  # drag has done real work by 1.6 s


def test_a_vertical_launch_has_no_range_share(client):
    # Straight up, both ranges are rounding noise (cos 90° ≈ 6e-17): the share is undefined and says why.
    read, _ = read_after(ProjectileDragScene, client, {"elevation_deg": 90.0}, frames=0)
    share = by_name(read)["range_percent_of_vacuum"]
    assert share.value is None and "vertical launch" in share.text
    assert abs(read.value("range_m")) < 1e-9 and by_name(read)["longer_leg"].text == "the fall"


# ---- radar tracking -------------------------------------------------------------------------------


def test_radar_readout_at_the_instant_on_screen(client):
    read, _ = read_after(RadarTrackingScene, client)
    t = read.value("t_s")
    assert t == pytest.approx(1.0, rel=1e-12)
    assert read.value("range_m") == pytest.approx(2000.0 + 100.0 * t, rel=1e-14)
    assert read.value("range_rate_m_s") == 100.0
    assert read.value("elevation_rate_rad_s") == pytest.approx(-0.05 / math.sqrt(t), rel=1e-12)
    # Speed from r, θ, β and their rates against the xyz chain rule (|v| two ways: 1e-12 relative, a few ulps).
    assert read.value("speed_m_s") == pytest.approx(np.linalg.norm(radar_tracking.velocity_exact(t)), rel=1e-12)
    # Acceleration against a central difference of the exact velocity, h = 1e-4 s: truncation (h²/6)|v'''| and
    # round-off ε|v|/h are both ≲ 1e-8 m/s² against |a| ≈ 93 m/s², so 1e-7 relative holds with margin.
    h = 1e-4
    a_fd = (radar_tracking.velocity_exact(t + h) - radar_tracking.velocity_exact(t - h)) / (2 * h)
    assert read.value("acceleration_m_s2") == pytest.approx(np.linalg.norm(a_fd), rel=1e-7)


def test_radar_readout_at_the_chosen_instant_is_the_worked_examples(client):
    read, _ = read_after(RadarTrackingScene, client, {"t_s": 2.0, "dt_s": 1e-3})
    out = radar_tracking.solve({"t_s": 2.0, "dt_s": 1e-3}).outputs
    # The colleague's hand solution, 6 significant figures (1e-5 relative): v = (19.0374, 266.266, 30.6933) m/s.
    assert read.value("instant_speed_m_s") == pytest.approx(np.linalg.norm([19.0374, 266.266, 30.6933]), rel=1e-5)
    assert read.value("fd_error_m_s") == out["fd_error_m_s"]
    assert read.value("optimal_dt_s") == out["optimal_dt_s"]
    (mark,) = read.marks["dt_s"]
    assert mark.value == out["optimal_dt_s"]


def test_radar_readout_at_the_first_instant_says_what_is_undefined(client):
    read = by_name(read_after(RadarTrackingScene, client, frames=0)[0])
    assert read["t_s"].value == 0.0 and read["range_rate_m_s"].value == 100.0
    for name in ("elevation_rate_rad_s", "speed_m_s", "acceleration_m_s2"):
        assert read[name].value is None and "infinite at t = 0" in read[name].text, name


# ---- robotic arm and cable ------------------------------------------------------------------------


def test_robot_arm_readout_is_the_worked_examples_answer(client):
    read, _ = read_after(RobotArmCableScene, client, frames=0)
    out = robot_arm_cable.solve(robot_arm_cable.INPUTS.defaults()).outputs
    for k, axis in enumerate("xyz"):
        assert read.value(f"F_{axis}_N") == out["F_N"][k]
    assert (read.value("F_BC_N"), read.value("M_z_Nm"), read.value("M_AB_Nm")) == (out["F_BC_N"], out["M_z_Nm"], out["M_AB_Nm"])
    assert read.value("M_A_Nm") == pytest.approx(np.linalg.norm(out["M_A_Nm"]), rel=1e-15)
    # The hand solution (4 significant figures, 5e-4 relative): M_z = −1.319e4 N·m, so clockwise seen from above;
    # F_BC = −1705 N: the pull runs from C toward B and compresses BC.
    assert read.value("M_z_Nm") == pytest.approx(-1.319e4, rel=5e-4)
    assert by_name(read)["turning_about_z"].text == "clockwise"
    assert "1,705 N toward B: it compresses BC" in read.message


@pytest.mark.parametrize(("theta_deg", "word"), [(-30.0, "counter-clockwise"), (0.0, "none")])
def test_robot_arm_turning_follows_the_arm(client, theta_deg, word):
    read, _ = read_after(RobotArmCableScene, client, {"theta_deg": theta_deg}, frames=0)
    assert by_name(read)["turning_about_z"].text == word
    assert (read.value("M_z_Nm") > 0.0) if word == "counter-clockwise" else read.value("M_z_Nm") == 0.0

