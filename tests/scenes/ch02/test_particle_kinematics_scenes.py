"""The three chapter-2 particle scenes on a real (loopback) viser server: readouts, singular points, the clock.

Numbers are compared with the closed forms of each motion (rounding tolerance,
1e-12 relative: the readout carries the model's double-precision value).
"""

from __future__ import annotations

import math

import pytest

from app.scenes.ch02.cartesian_components import CartesianComponentsScene
from app.scenes.ch02.curvilinear_coordinates import CurvilinearCoordinatesScene
from app.scenes.ch02.rotating_arm import RotatingArmScene


def build(cls, client, preset: str | None = None, **values):
    chosen = dict(next(p.values for p in cls.presets if p.name == preset)) if preset else {}
    return cls(client, cls.parameters.validate({**chosen, **values}))


def quantities(scene) -> dict:
    """What the student reads in each row: the number, or the text where there is none."""
    return {q.name: q.value if q.value is not None else q.text for q in scene.readout().quantities}


def test_the_pin_in_the_slot_has_no_acceleration_along_its_drive(client):
    scene = build(CartesianComponentsScene, client, "sine-slot")
    scene.go_to(0.5)  # x = ẋ t = 0.25 m: a quarter of the way to the first crest
    values = quantities(scene)
    k = math.pi / 1.0
    assert values["t_s"] == pytest.approx(0.5)
    assert values["x_dot"] == pytest.approx(0.5, rel=1e-12) and values["x_ddot"] == 0.0
    assert values["y_dot"] == pytest.approx(0.3 * k * 0.5 * math.cos(k * 0.25), rel=1e-12)
    assert values["y_ddot"] == pytest.approx(-0.3 * k**2 * 0.25 * math.sin(k * 0.25), rel=1e-12)
    assert values["speed"] == pytest.approx(math.hypot(values["x_dot"], values["y_dot"]), rel=1e-12)
    assert "ẍ = 0" in scene.readout().message
    scene.close()


def test_the_projectile_keeps_its_horizontal_velocity_and_loops_at_landing(client):
    scene = build(CartesianComponentsScene, client, "projectile")
    run = quantities(scene)["run"]
    assert run == pytest.approx(2 * 8.0 * math.sin(math.radians(50.0)) / 9.81, rel=1e-12)
    scene.go_to(run + 0.25)  # the second run: the formulas' t starts again from 0
    values = quantities(scene)
    assert values["t_s"] == pytest.approx(0.25)
    assert values["z_ddot"] == pytest.approx(-9.81) and values["acceleration_magnitude"] == pytest.approx(9.81)
    assert values["x_dot"] == pytest.approx(8.0 * math.cos(math.radians(50.0)) * math.cos(math.radians(30.0)), rel=1e-12)
    assert values["z_dot"] == pytest.approx(8.0 * math.sin(math.radians(50.0)) - 9.81 * 0.25, rel=1e-12)
    assert scene.motion_state() == {"t_s": pytest.approx(run + 0.25)}
    with pytest.raises(ValueError, match="t_s"):
        scene.resume_from({"t_s": float("nan")})
    scene.close()


def test_the_conical_spiral_reads_the_coriolis_like_term_and_both_magnitudes_agree(client):
    scene = build(CurvilinearCoordinatesScene, client, "conical-spiral")
    for t in (0.3, 2.0, 7.1):
        scene.go_to(t)
        values = quantities(scene)
        assert values["v_R"] == pytest.approx(0.1, rel=1e-12)  # Ṙ = a θ̇ / 2π with a = 0.1π m
        assert values["a_theta"] == pytest.approx(0.4, rel=1e-12)  # 2 Ṙ θ̇ with θ̇ = 2 rad/s
        assert values["a_z"] == pytest.approx(0.0, abs=1e-12)
        assert values["speed_from_components"] == pytest.approx(values["speed"], rel=1e-12)
        assert values["acceleration_from_components"] == pytest.approx(values["acceleration_magnitude"], rel=1e-12)
    cylindrical_v_theta = values["v_theta"]
    scene.set_params({**scene.params, "frame": "spherical"})
    scene.go_to(7.1)
    spherical = quantities(scene)
    assert spherical["v_theta"] == pytest.approx(cylindrical_v_theta, rel=1e-12)  # the same e_θ in both systems
    assert spherical["phi"] == pytest.approx(math.radians(40.0), rel=1e-12) and spherical["v_phi"] == pytest.approx(0.0, abs=1e-12)
    scene.close()


def test_on_the_pole_the_readout_says_what_is_undefined_and_hides_those_unit_vectors(client):
    scene = build(CurvilinearCoordinatesScene, client, "on-the-pole")
    readout = scene.readout()
    values = quantities(scene)
    assert "polar axis" in readout.message and "e_r still points along ±Z" in readout.message
    assert values["r"] == pytest.approx(1.0) and values["v_r"] == pytest.approx(0.0, abs=1e-12)
    assert values["theta"] == values["v_theta"] == values["a_phi"] == "no value here (see the message below)"
    assert [node.visible for node in scene._triad_nodes] == [True, True, False, False, False, False]
    scene.set_params({**scene.params, "frame": "cylindrical"})
    assert "Z axis (R = 0)" in scene.readout().message
    assert quantities(scene)["z"] == pytest.approx(1.0) and [node.visible for node in scene._triad_nodes] == [False, False, False, False, True, True]
    scene.close()


def test_through_the_pivot_the_arm_description_stays_defined_and_is_all_coriolis(client):
    scene = build(RotatingArmScene, client, "through-the-pivot")  # r = 1.2 sin t m, θ̇ = 0.6 rad/s: r = 0 at t = 0
    values = quantities(scene)
    assert values["r"] == 0.0 and "passing the pivot" in scene.readout().message
    assert values["a_coriolis"] == pytest.approx(2 * 1.2 * 0.6, rel=1e-12)
    assert values["a_theta"] == pytest.approx(values["a_coriolis"], rel=1e-15)
    assert values["a_centripetal"] == values["a_sliding"] == values["a_angular"] == 0.0
    assert values["acceleration_magnitude"] == pytest.approx(1.44, rel=1e-12)
    scene.go_to(math.pi + 0.5)  # sin < 0: the collar is beyond the pivot
    assert quantities(scene)["r"] < 0 and "other half" in scene.readout().message
    scene.close()


def test_a_clamped_collar_reads_only_the_centripetal_term_and_is_its_own_path_normal(client):
    scene = build(RotatingArmScene, client, "fixed-collar")
    scene.go_to(2.0)
    values = quantities(scene)
    assert values["a_centripetal"] == pytest.approx(-1.0, rel=1e-12) and values["a_coriolis"] == 0.0
    assert values["a_normal"] == pytest.approx(1.0, rel=1e-12) and values["a_tangential"] == pytest.approx(0.0, abs=1e-12)
    scene.close()
