"""The slider-crank kinetics scene through the API: series contract, physics of the answer, 422s, the live readout.

The series names are contracts: a lesson page or a student's script reads them by name.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from app.physics.systems.ch06 import mechanism_kinetics as physics
from tests.api.conftest import live_viewer
from tests.conftest import wait_until

SCENE = "slider-crank-kinetics"
CONTRACT_SERIES = {
    "crank_angle": "rad",
    "crank_speed_rad_s": "rad/s",
    "driving_torque_N_m": "N·m",
    "pin_force_O_N": "N",
    "pin_force_A_N": "N",
    "pin_force_B_N": "N",
    "guide_force_N": "N",
    "kinetic_energy_J": "J",
    "work_energy_residual_J": "J",
}
_ids = itertools.count()


def simulate(client, params, **request):
    body = {"params": params, "t_end": 2.0, "frame_rate": 30.0, **request}
    return client.post(f"/api/scenes/{SCENE}/simulate", json=body)


@pytest.mark.parametrize("drive", physics.DRIVES)
def test_simulate_returns_the_contract_series_with_units(client, drive):
    response = simulate(client, {"drive": drive})
    assert response.status_code == 200, response.text
    body = response.json()
    assert set(body["series"]) == set(CONTRACT_SERIES)
    assert {name: body["units"][name] for name in CONTRACT_SERIES} == CONTRACT_SERIES
    frames = len(body["t"])
    assert frames == 61
    assert all(len(v) == frames and None not in v for v in body["series"].values())
    assert body["stats"]["status"] == "ok" and body["stats"]["method"] == "rk4"
    # Work–energy: the residual is integration error only (measured ~1e-8 J speed, ~1e-6 J torque; energy in play ~30 J).
    assert max(abs(v) for v in body["series"]["work_energy_residual_J"]) < 1e-4


def test_constant_speed_answer_is_newton_euler_at_each_frame(client):
    """The API's torque and forces are the physics module's inverse-dynamics solve at the frame's crank angle (to 1e-9)."""
    params = {"drive": "speed", "crank_speed_rad_s": -6.0, "offset_m": 0.1}
    body = simulate(client, params).json()
    values = physics.PARAMETERS.validate(params)
    links = physics.SliderCrankLinks.from_params(values)
    theta = np.asarray(body["series"]["crank_angle"])
    assert theta == pytest.approx(math.radians(values["crank_angle0_deg"]) - 6.0 * np.asarray(body["t"]), abs=1e-12)
    forces = physics.newton_euler(links, theta, -6.0, crank_acceleration_rad_s2=0.0)
    assert body["series"]["driving_torque_N_m"] == pytest.approx(forces.driving_torque_N_m.tolist(), rel=1e-9, abs=1e-9)
    assert body["series"]["pin_force_A_N"] == pytest.approx(np.linalg.norm(forces.crank_pin_A_N, axis=-1).tolist(), rel=1e-9)
    assert body["series"]["guide_force_N"] == pytest.approx(forces.guide_force_N.tolist(), rel=1e-9)


@pytest.mark.parametrize(
    "params, field, words",
    [
        ({"drive": "brake"}, "drive", "one of 'speed', 'torque'"),
        ({"slider_mass_kg": -1.0}, "slider_mass_kg", "between"),
        ({"drive_torque_N_m": 1e9}, "drive_torque_N_m", "between"),
        ({"crank_speed_rad_s": "fast"}, "crank_speed_rad_s", "number"),
        ({"flywheel_kg": 1.0}, "flywheel_kg", "unknown input"),
        ({"crank_m": 0.5, "rod_m": 0.6, "offset_m": 0.2}, None, "connecting rod"),
    ],
)
def test_bad_input_is_a_422_naming_the_field(client, params, field, words):
    response = simulate(client, params)
    assert response.status_code == 422, response.text
    detail = response.json()["detail"][0]
    assert words in detail["msg"]
    if field is not None:
        assert detail["loc"][-1] == field
    sid = f"kinetics-bad-{next(_ids):04d}"
    url = f"/api/scenes/{SCENE}/sessions/{sid}"
    before = client.put(url, json={"params": {}}).json()["params"]
    refused = client.put(url, json={"params": params})
    assert refused.status_code == 422 and words in refused.json()["detail"][0]["msg"]
    assert client.put(url, json={"params": {}}).json()["params"] == before


def test_every_preset_simulates(client):
    from app.scenes import SCENES

    for preset in SCENES[SCENE].presets:
        response = simulate(client, dict(preset.values))
        assert response.status_code == 200, (preset.name, response.text)
        assert response.json()["stats"]["status"] == "ok"


def test_live_readout_carries_units_and_the_work_energy_balance(inprocess_client):
    client = inprocess_client  # looks inside the scene instance: the app in this process
    sid = f"kinetics-live-{next(_ids):04d}"
    host = client.app.state.scene_host
    assert client.put(f"/api/scenes/{SCENE}/sessions/{sid}", json={"params": {"drive": "torque"}}).status_code == 200
    with live_viewer(client, SCENE, sid) as scene:
        wait_until(lambda: scene.run.t_s > 0.3)
        live = client.get(f"/api/scenes/{SCENE}/sessions/{sid}/live").json()
        values = {q["name"]: q for q in live["readout"]["quantities"]}
        units = {name: q["unit"] for name, q in values.items()}
        assert units["driving_torque_N_m"] == "N·m" and units["crank_speed_rad_s"] == "rad/s"
        assert {units[n] for n in ("pin_force_O_N", "pin_force_A_N", "pin_force_B_N", "guide_force_N")} == {"N"}
        assert {units[n] for n in ("kinetic_energy_J", "potential_energy_J", "torque_work_J", "work_energy_residual_J")} == {"J"}
        assert values["driving_torque_N_m"]["value"] == pytest.approx(2.0, abs=1e-9)
        # ΔT + ΔV − W from the readout's own numbers (J): initial T₀ = ½ M(0) ω₀² = 4.5 J, V₀ = 0 at θ = 0.
        balance = values["kinetic_energy_J"]["value"] + values["potential_energy_J"]["value"] - 4.5 - values["torque_work_J"]["value"]
        assert balance == pytest.approx(values["work_energy_residual_J"]["value"], abs=1e-9)
        assert abs(balance) < 1e-4
        assert "frictionless" in live["readout"]["message"]
        assert math.isfinite(live["physics_us_per_frame"])  # the < 50 µs budget is measured in the physics tests
        with host.inspect(sid):
            assert scene.force_labels[1].text.endswith(" N")


def test_a_runaway_torque_pauses_the_live_scene_and_says_why(inprocess_client):
    """Frictionless and driven by 100 N·m, the crank speeds up without limit: the scene stops at the speed its step was chosen for."""
    client = inprocess_client  # looks inside the scene instance: the app in this process
    sid = f"kinetics-runaway-{next(_ids):04d}"
    params = {"drive": "torque", "drive_torque_N_m": 100.0}
    assert client.put(f"/api/scenes/{SCENE}/sessions/{sid}", json={"params": params}).status_code == 200
    limit = physics.speed_limit_rad_s(physics.PARAMETERS.validate(params))
    with live_viewer(client, SCENE, sid) as scene:
        wait_until(lambda: not scene.run.running)
        live = client.get(f"/api/scenes/{SCENE}/sessions/{sid}/live").json()
        assert "speeds the crank up without limit" in live["readout"]["message"]
        speed = {q["name"]: q["value"] for q in live["readout"]["quantities"]}["crank_speed_rad_s"]
        assert limit < abs(speed) < 1.5 * limit  # stopped within a frame of passing the limit
        assert abs(live["invariants"]["work_energy_residual"]["relative_drift"]) < 1e-4
