"""POST /api/scenes/sliding-ladder/simulate, the scene's listing and its live readout: contract names, units, 422s."""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.systems.ch06 import sliding_ladder as sl
from tests.api.conftest import live_viewer
from tests.conftest import wait_until

URL = "/api/scenes/sliding-ladder/simulate"


def simulate(client, params, t_end=2.0, frame_rate=60.0, **extra):
    return client.post(URL, json={"params": params, "t_end": t_end, "frame_rate": frame_rate, **extra})


def test_listed_with_its_parameters_and_presets(client):
    scene = {s["id"]: s for s in client.get("/api/scenes").json()}["sliding-ladder"]
    assert scene["chapter"] == 6 and scene["animated"] and scene["integrated"] and scene["readout"]
    params = {p["name"]: p for p in scene["parameters"]}
    assert list(params)[:6] == ["length_m", "mass_kg", "angle0_deg", "mu_wall", "mu_floor", "g_m_s2"]
    assert params["length_m"]["unit"] == "m" and params["mass_kg"]["unit"] == "kg" and params["angle0_deg"]["unit"] == "deg"
    assert params["mu_wall"]["min"] == 0.0 and params["mu_floor"]["min"] == 0.0  # 0 allowed
    assert params["g_m_s2"]["unit"] == "m/s²"
    assert params["angle0_deg"]["max"] >= 89.9
    assert {"smooth", "nearly-upright", "rough-floor", "held"} <= {p["name"] for p in scene["presets"]}


def test_simulate_returns_the_contract_series_through_the_separation_and_the_landing(client):
    response = simulate(client, {})
    assert response.status_code == 200, response.text
    body = response.json()
    assert set(body["series"]) == {"angle_from_floor", "wall_force_N", "floor_force_N", "top_height_m"}
    assert body["units"] == {
        "t": "s", "angle_from_floor": "rad", "wall_force_N": "N", "floor_force_N": "N", "top_height_m": "m",
        "invariants.energy_budget_J": "J",
    }
    assert body["stats"]["method"] == "dopri5" and body["stats"]["status"] == "ok"
    t = np.array(body["t"])
    theta = np.array(body["series"]["angle_from_floor"])
    wall = np.array(body["series"]["wall_force_N"])
    params = sl.PARAMETERS.defaults()
    release, landing = sl.phase_changes(params, t_end_s=2.0)
    # Up to the release the wall pushes; after it the wall force is exactly zero; after the landing the bar lies flat.
    assert np.all(wall[(t > 0.0) & (t < release.t_s)] > 0.0) and np.all(wall[t > release.t_s] == 0.0)
    assert np.all(theta[t > landing.t_s] == 0.0) and np.all(np.array(body["series"]["top_height_m"])[t > landing.t_s] == 0.0)
    # The frames before the release follow the smooth ladder's energy equation (rtol 1e-8 run: 1e-7 rad).
    before = t < release.t_s
    assert theta[0] == pytest.approx(math.radians(60.0), abs=1e-15)
    assert np.min(theta[before]) > sl.separation_angle_frictionless_rad(math.radians(60.0))
    # Energy accounted for over every phase (observed drift ~1e-9 at the default rtol 1e-8).
    assert body["stats"]["max_invariant_drift"] < 1e-6
    energy = np.array(body["invariants"]["energy_budget_J"])
    assert energy[0] == pytest.approx(params["mass_kg"] * params["g_m_s2"] * 0.5 * params["length_m"] * math.sin(math.radians(60.0)), rel=1e-14)


def test_held_ladder_stays_where_it_is(client):
    body = simulate(client, {"mu_wall": 0.2, "mu_floor": 0.3, "angle0_deg": 60.0}, t_end=1.0).json()
    assert body["stats"]["status"] == "ok"
    assert set(body["series"]["angle_from_floor"]) == {math.radians(60.0)}


@pytest.mark.parametrize(
    ("params", "field", "words"),
    [
        ({"mu_floor": -0.5}, "mu_floor", "between 0 and 1"),
        ({"angle0_deg": 95.0}, "angle0_deg", "between 1 and 89.9 deg"),
        ({"length_m": "long"}, "length_m", "number"),
        ({"ladder_m": 3.0}, "ladder_m", "unknown input"),
    ],
)
def test_bad_input_is_a_422_naming_the_field(client, params, field, words):
    response = simulate(client, params)
    assert response.status_code == 422
    detail = response.json()["detail"][0]
    assert detail["loc"][-1] == field and words in detail["msg"], detail


def test_live_readout_reports_phase_forces_energy_and_the_closed_form_angle(inprocess_client):
    client = inprocess_client  # looks inside the scene instance: the app in this process
    sid = "sliding-ladder-api-01"
    assert client.put(f"/api/scenes/sliding-ladder/sessions/{sid}", json={"params": {}}).status_code == 200
    with live_viewer(client, "sliding-ladder", sid) as scene:
        wait_until(lambda: scene.run.t_s > 1.2, what="the ladder to land")
        live = client.get(f"/api/scenes/sliding-ladder/sessions/{sid}/live").json()
    quantities = {q["name"]: q for q in live["readout"]["quantities"]}
    assert all(q["unit"] for q in quantities.values() if q["value"] is not None and q["name"] not in ("phase",))
    assert quantities["phase"]["text"] == "lying"
    assert quantities["separation_angle_closed_form_deg"]["value"] == pytest.approx(math.degrees(math.asin(2 / 3 * math.sin(math.radians(60.0)))), rel=1e-14)
    assert quantities["separation_angle_deg"]["value"] == pytest.approx(quantities["separation_angle_closed_form_deg"]["value"], abs=1e-8)
    assert quantities["separation_time_s"]["value"] == pytest.approx(0.6501608238, abs=1e-9)
    total = quantities["energy_total_J"]["value"]
    parts = sum(quantities[n]["value"] for n in ("kinetic_energy_J", "potential_energy_J", "friction_work_J", "impact_loss_J"))
    assert parts == pytest.approx(total, rel=1e-12) and total == pytest.approx(10.0 * 9.807 * 2.0 * math.sin(math.radians(60.0)), rel=1e-6)
    assert quantities["impact_loss_J"]["value"] > 0.0 and quantities["wall_force_N"]["value"] == 0.0
