"""The unbalanced rotor through the API: the simulate contract, 422s that name the field, a live balanced session.

Series and parameter names are contracts (issue 11): a lesson page or a student's script reads them by name.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from app.physics.systems.ch06 import unbalanced_rotor as rotor
from tests.api.conftest import live_viewer
from tests.conftest import wait_until

_ids = itertools.count()
CONTRACT_PARAMETERS = {
    "shaft_speed_rad_s", "disk_mass_kg", "disk_radius_m", "eccentricity_m", "skew_deg", "bearing_span_m",
    "disk_position_m", "g_m_s2", "correction_plane_1_m", "correction_plane_2_m", "correction_radius_m", "balanced",
}  # fmt: skip
CONTRACT_SERIES = {"spin_angle": "rad", "bearing_A_force_N": "N", "bearing_B_force_N": "N", "driving_torque_Nm": "N·m"}


def simulate(client, params, t_end=1.0, frame_rate=60.0):
    return client.post("/api/scenes/unbalanced-rotor/simulate", json={"params": params, "t_end": t_end, "frame_rate": frame_rate})


def test_the_scene_is_listed_with_its_contract_parameters(client):
    scenes = {s["id"]: s for s in client.get("/api/scenes").json()}
    scene = scenes["unbalanced-rotor"]
    assert scene["chapter"] == 6 and scene["animated"] and scene["readout"]
    assert {p["name"] for p in scene["parameters"]} == CONTRACT_PARAMETERS


def test_simulate_returns_the_contract_series_matching_the_physics(client):
    response = simulate(client, {})
    assert response.status_code == 200, response.text
    body = response.json()
    assert set(body["series"]) == set(CONTRACT_SERIES)
    assert all(body["units"][name] == unit for name, unit in CONTRACT_SERIES.items())
    assert body["stats"]["method"] == "closed-form" and body["stats"]["status"] == "ok" and len(body["t"]) == 61
    loads = rotor.UnbalancedRotor.from_params(rotor.PARAMETERS.defaults()).at(np.asarray(body["t"]))
    assert body["series"]["bearing_A_force_N"] == pytest.approx(loads.bearing_A_force_N.tolist(), rel=1e-14)
    assert body["series"]["bearing_B_force_N"] == pytest.approx(loads.bearing_B_force_N.tolist(), rel=1e-14)
    # Static imbalance under gravity: the drive cancels gravity's moment, T = m g e cos φ (10 kg, 9.81 m/s², 1 mm).
    spin = np.asarray(body["series"]["spin_angle"])
    assert body["series"]["driving_torque_Nm"] == pytest.approx((10.0 * 9.81 * 0.001 * np.cos(spin)).tolist(), abs=1e-15)


def test_a_rotor_at_rest_answers_its_weight_and_no_null(client):
    body = simulate(client, {"shaft_speed_rad_s": 0.0}).json()
    assert body["stats"]["status"] == "ok"
    # 10 kg at a = 0.2 m of a 0.6 m span: 2/3 of 98.1 N at A, 1/3 at B.
    assert body["series"]["bearing_A_force_N"] == pytest.approx([98.1 * 2 / 3] * 61, rel=1e-14)
    assert body["series"]["bearing_B_force_N"] == pytest.approx([98.1 / 3] * 61, rel=1e-14)


def test_the_balanced_rotor_without_gravity_loads_no_bearing(client):
    body = simulate(client, {"balanced": "on", "g_m_s2": 0.0}).json()
    # Before balancing the reactions are about 90 N; rounding leaves ~1e-13 N.
    assert max(body["series"]["bearing_A_force_N"] + body["series"]["bearing_B_force_N"]) < 1e-10


@pytest.mark.parametrize(
    "params, field, words",
    [
        ({"disk_mass_kg": -2.0}, "disk_mass_kg", "between"),
        ({"disk_position_m": 0.7}, "disk_position_m", "between the bearings"),
        ({"eccentricity_m": 0.25}, "eccentricity_m", "less than the disk's radius"),
        ({"skew_deg": "nan"}, "skew_deg", "number"),
        ({"correction_plane_2_m": 0.06}, "correction_plane_2_m", "apart"),
        ({"balanced": True}, "balanced", "one of 'off', 'on'"),
    ],
)
def test_bad_input_is_a_422_naming_the_field_and_changes_nothing(client, params, field, words):
    response = simulate(client, params)
    assert response.status_code == 422, response.text
    detail = response.json()["detail"][0]
    assert detail["loc"][-1] == field and words in detail["msg"]
    sid = f"rotor-session-{next(_ids):04d}"
    url = f"/api/scenes/unbalanced-rotor/sessions/{sid}"
    before = client.put(url, json={"params": {"skew_deg": 1.5}}).json()["params"]
    refused = client.put(url, json={"params": params})
    assert refused.status_code == 422 and refused.json()["detail"][0]["loc"][-1] == field
    assert client.put(url, json={"params": {}}).json()["params"] == before


def test_non_finite_json_numbers_are_refused(client):
    response = client.post(
        "/api/scenes/unbalanced-rotor/simulate",
        content='{"params": {"shaft_speed_rad_s": Infinity}, "t_end": 1.0}',
        headers={"content-type": "application/json"},
    )
    assert response.status_code == 422


def test_live_balanced_session_reads_the_corrections_and_zero_rotating_force(inprocess_client):
    client = inprocess_client  # looks inside the scene instance: the app in this process
    sid = f"rotor-session-{next(_ids):04d}"
    assert client.put(f"/api/scenes/unbalanced-rotor/sessions/{sid}", json={"params": {"balanced": "on"}}).status_code == 200
    with live_viewer(client, "unbalanced-rotor", sid) as scene:
        wait_until(lambda: scene.t_s > 0.1, what="the rotor to turn")
        readout = client.get(f"/api/scenes/unbalanced-rotor/sessions/{sid}/live").json()["readout"]
    values = {q["name"]: q for q in readout["quantities"]}
    assert values["imbalance_class"]["text"] == "balanced"
    correction = rotor.UnbalancedRotor.from_params(rotor.PARAMETERS.validate({"balanced": "on"})).correction
    assert values["correction_mass_1_kg"]["value"] == pytest.approx(float(correction.masses_kg[0]), rel=1e-12)
    assert values["correction_angle_2_deg"]["value"] == pytest.approx(math.degrees(correction.angles_rad[1]), rel=1e-12)
    assert values["bearing_A_rotating_force_N"]["value"] < 1e-10 and values["bearing_A_force_N"]["unit"] == "N"
    assert values["driving_torque_Nm"]["unit"] == "N·m" and abs(values["driving_torque_Nm"]["value"]) < 1e-12
