"""The bouncing bar (section 6.4) through the API: the scene's schema, simulate, 422s and the live readout."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from app.physics.systems.ch06 import bouncing_bar
from tests.api.conftest import live_viewer
from tests.conftest import wait_until

SCENE = "bouncing-bar"
PARAMETER_NAMES = ["length_m", "mass_kg", "drop_height_m", "angle0_deg", "restitution", "friction_coefficient", "g_m_s2"]
SERIES = {"angle", "centre_height_m", "energy_J", "impact_count", "energy_lost_J"}
_ids = itertools.count()


def simulate(client, params=None, t_end=6.0, frame_rate=30.0, **extra):
    return client.post(f"/api/scenes/{SCENE}/simulate", json={"params": params or {}, "t_end": t_end, "frame_rate": frame_rate, **extra})


def test_the_scene_is_listed_with_its_parameters_and_presets(client):
    scenes = {s["id"]: s for s in client.get("/api/scenes").json()}
    scene = scenes[SCENE]
    assert scene["chapter"] == 6 and scene["integrated"] and scene["animated"] and scene["readout"]
    names = [p["name"] for p in scene["parameters"]]
    assert names[: len(PARAMETER_NAMES)] == PARAMETER_NAMES
    assert {p["name"] for p in scene["presets"]} == {"flat", "tilted-45", "nearly-vertical", "frictionless", "rough"}


def test_simulate_returns_the_series_and_keeps_the_energy_ledger(client):
    response = simulate(client, {"angle0_deg": 45.0})
    assert response.status_code == 200
    body = response.json()
    assert set(body["series"]) == SERIES
    assert body["stats"]["method"] == "dopri5" and body["stats"]["status"] == "ok"
    # The same run as the physics module gives (JSON carries doubles exactly).
    params = bouncing_bar.PARAMETERS.validate({"angle0_deg": 45.0})
    report = bouncing_bar.BouncingBar().simulate(params, {}, t_end_s=6.0, frame_rate_hz=30.0)
    for name in SERIES:
        assert np.array_equal(np.array(body["series"][name]), report.series[name])
    energy = np.array(body["series"]["energy_J"]) + np.array(body["series"]["energy_lost_J"])
    # Kinetic + potential + lost: m g h₀ = 9.807 J throughout (1e-9 relative: see the physics tests).
    np.testing.assert_allclose(energy, 9.807, rtol=1e-9)
    impacts = np.array(body["series"]["impact_count"])
    assert impacts[-1] >= 5 and np.all(np.diff(impacts) >= 0)
    assert body["stats"]["max_invariant_drift"] < 1e-9


@pytest.mark.parametrize(
    ("params", "field", "words"),
    [
        ({"drop_height_m": 0.2, "angle0_deg": 45.0}, "drop_height_m", "above the floor"),
        ({"restitution": 1.5}, "restitution", "between 0 and 1"),
        ({"friction_coefficient": -0.1}, "friction_coefficient", "between"),
        ({"length_m": 0.0}, "length_m", "between"),
        ({"mass_kg": float("nan")}, "mass_kg", ""),
        ({"spin_rad_s": 1.0}, "spin_rad_s", "unknown input"),
    ],
)
def test_bad_parameters_are_422_naming_the_field(client, params, field, words):
    if any(isinstance(v, float) and math.isnan(v) for v in params.values()):
        response = client.post(
            f"/api/scenes/{SCENE}/simulate", content=b'{"params": {"mass_kg": NaN}, "t_end": 1.0}', headers={"content-type": "application/json"}
        )
    else:
        response = simulate(client, params)
    assert response.status_code == 422
    detail = response.json()["detail"][0]
    assert field in detail["loc"] or field in detail["msg"]
    assert words in detail["msg"]


def test_a_method_without_events_is_refused(client):
    response = simulate(client, {}, method="rk4")
    assert response.status_code == 422
    assert "method" in response.json()["detail"][0]["loc"]


def test_live_readout_counts_impacts_and_says_when_the_bar_rests(inprocess_client):
    client = inprocess_client  # looks inside the scene instance: the app in this process
    sid = f"bar-session-{next(_ids):04d}"
    assert client.put(f"/api/scenes/{SCENE}/sessions/{sid}", json={"params": {"angle0_deg": 0.0}}).status_code == 200
    with live_viewer(client, SCENE, sid) as scene:
        wait_until(lambda: scene.run.t_s > 0.6, timeout_s=20.0)  # the flat bar lands at t = 0.452 s
        live = client.get(f"/api/scenes/{SCENE}/sessions/{sid}/live").json()
        values = {q["name"]: q for q in live["readout"]["quantities"]}
        assert values["impact_count"]["value"] >= 1 and values["impact_count"]["unit"] == "impacts"
        assert values["angle_deg"]["value"] == 0.0  # the flat landing creates no spin
        assert values["last_energy_loss_J"]["unit"] == "J" and values["last_energy_loss_J"]["value"] > 0.0
        assert all(q["unit"] or q.get("text") for q in live["readout"]["quantities"])
        wait_until(lambda: scene.run.y[bouncing_bar.MODE] == bouncing_bar.RESTING, timeout_s=30.0)
        live = client.get(f"/api/scenes/{SCENE}/sessions/{sid}/live").json()
        values = {q["name"]: q for q in live["readout"]["quantities"]}
        assert values["mode"]["text"] == "resting"
        assert "Resting" in live["readout"]["message"]
        assert live["invariants"]["energy_balance"]["relative_drift"] < 1e-9
