"""Unusual but valid inputs in the chapter-10 scenes: built, run and read out, with words where numbers fail.

The heavy top without gravity (a torque-free top), the undamped rate gyro driven at
resonance (β grows without bound; the readout warns once it leaves the small-angle
model) and an equinox precession faster than the model allows.
"""

from __future__ import annotations

import json
import math

import numpy as np

from app.physics.systems.ch10 import rate_gyro as rg
from app.scenes.ch10.equinox_precession import EquinoxPrecessionScene
from app.scenes.ch10.heavy_top import HeavyTopScene
from app.scenes.ch10.rate_gyro import RateGyroScene
from app.scenes.kit import FRAME_DT_S


def run(scene, frames: int) -> None:
    for _ in range(frames):
        scene.advance(FRAME_DT_S)


def test_heavy_top_without_gravity_builds_runs_and_reads_out_in_words(client):
    scene = HeavyTopScene(client, HeavyTopScene.parameters.validate({"g_m_s2": 0.0, "nutation_rate0_rad_s": 1.0}))
    run(scene, 90)
    assert scene.status == ""
    readout = scene.readout()
    threshold = next(q for q in readout.quantities if q.name == "critical_spin_rad_s")
    assert threshold.value is None and threshold.text == "none: no gravity"
    assert "no gravity" in readout.message and readout.marks == {}
    live = scene.live_readout()
    assert "angular_momentum" in live["invariants"]
    json.dumps(live, allow_nan=False)
    # |L| is conserved to round-off by the splitting's exact free flow (1e-12 relative: 1e4 × eps).
    assert live["invariants"]["angular_momentum"]["relative_drift"] < 1e-12
    # An upright top at rest without gravity: nothing moves, nothing divides by zero.
    scene.set_params(HeavyTopScene.parameters.validate({"spin_rad_s": 0.0, "theta0_deg": 0.0, "nutation_rate0_rad_s": 0.0}, base=scene.params))
    run(scene, 10)
    json.dumps(scene.readout().as_dict(), allow_nan=False)
    scene.close()


def test_rate_gyro_at_resonance_runs_and_warns_once_outside_the_small_angle_model(client):
    params = {"input_kind": "sine", "damping_N_m_s_rad": 0.0, "stiffness_N_m_rad": 0.5, "gimbal_inertia_kg_m2": 5e-3, "input_frequency_rad_s": 10.0}
    scene = RateGyroScene(client, RateGyroScene.parameters.validate(params))
    run(scene, 3)  # β is still small
    readout = scene.readout()
    assert "Outside the model" not in readout.message and "resonance" in readout.message
    ratio = next(q for q in readout.quantities if q.name == "amplitude_ratio_s")
    assert ratio.value is None and ratio.text == "none: grows without bound"
    run(scene, 60)  # 2.1 s: the envelope G Ω₀ ω_n t / 2 is past 0.35 rad
    beta = rg.gimbal_response(scene.params, np.array([scene.t_s])).beta_rad[0]
    assert scene.readout().value("beta_rad") == beta
    assert scene.readout().message.startswith("Outside the model")
    json.dumps(scene.readout().as_dict(), allow_nan=False)
    assert math.isfinite(beta)
    scene.close()


def test_equinox_scene_warns_when_precession_is_not_slow_beside_the_spin(client):
    fast = {"dynamical_ellipticity": 0.1, "moon_orbital_period_days": 0.1, "moon_mass_ratio": 1.0, "earth_spin_rad_s": 1e-7}
    scene = EquinoxPrecessionScene(client, EquinoxPrecessionScene.parameters.validate(fast))
    run(scene, 5)
    assert scene.readout().message.startswith("Outside the model")
    scene.set_params(EquinoxPrecessionScene.parameters.validate({}))
    assert "Outside the model" not in scene.readout().message
    scene.close()
