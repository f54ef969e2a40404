"""POST /api/scenes/torque-free-body/simulate and the scene's listing: contract names, units, 422s."""

from __future__ import annotations

import numpy as np
import pytest

from app.physics.systems.ch10 import torque_free_body as tfb

URL = "/api/scenes/torque-free-body/simulate"


def simulate(client, params, t_end=5.0, frame_rate=30.0, **extra):
    return client.post(URL, json={"params": params, "t_end": t_end, "frame_rate": frame_rate, **extra})


def test_listed_with_its_parameters_presets_and_ghost_toggle(client):
    scenes = {s["id"]: s for s in client.get("/api/scenes").json()}
    scene = scenes["torque-free-body"]
    assert scene["chapter"] == 10 and scene["animated"] and scene["readout"] and not scene["integrated"]
    params = {p["name"]: p for p in scene["parameters"]}
    assert list(params) == ["I1", "I2", "I3", "omega0_rad_s", "ghost"]
    assert all(params[n]["unit"] == "kg·m²" for n in ("I1", "I2", "I3"))
    assert params["omega0_rad_s"]["kind"] == "vector" and params["omega0_rad_s"]["length"] == 3
    assert params["omega0_rad_s"]["unit"] == "rad/s"
    assert params["ghost"]["choices"] == ["off", "on"] and params["ghost"]["default"] == "off"
    assert {p["name"] for p in scene["presets"]} == {"tennis-racket", "major-axis", "minor-axis"}


def test_simulate_returns_the_closed_form_under_the_contract_names(client):
    response = simulate(client, {})
    assert response.status_code == 200, response.text
    body = response.json()
    assert set(body["series"]) == {"omega1", "omega2", "omega3"}
    assert set(body["invariants"]) == {"energy", "angular_momentum"}
    assert body["units"] == {
        "t": "s", "omega1": "rad/s", "omega2": "rad/s", "omega3": "rad/s",
        "invariants.energy": "J", "invariants.angular_momentum": "kg·m²/s",
    }
    assert body["stats"]["method"] == "closed-form" and body["stats"]["steps"] == 0
    assert len(body["t"]) == 151 and body["t"][-1] == pytest.approx(5.0)
    params = tfb.PARAMETERS.defaults()
    reference = tfb.motion(params)
    omega = np.array([body["series"][f"omega{i}"] for i in (1, 2, 3)]).T
    assert np.abs(omega - reference.omega_body(np.array(body["t"]))).max() == 0.0  # the same formula, to the bit
    assert omega[0] == pytest.approx(params["omega0_rad_s"], rel=1e-15)
    energy = np.array(body["invariants"]["energy"])
    assert energy == pytest.approx(np.full_like(energy, reference.energy_J), rel=1e-13)
    assert body["stats"]["max_invariant_drift"] < 1e-13
    assert body["events"] == []


def test_tennis_racket_reports_its_flips_as_events(client):
    params = {"omega0_rad_s": [0.1, 4.0, 0.1]}
    body = simulate(client, params, t_end=20.0).json()
    flips = tfb.flip_times_s(tfb.motion(tfb.PARAMETERS.validate(params)), 20.0)
    assert len(body["events"]) == len(flips) >= 4
    assert [e["kind"] for e in body["events"]] == ["flip"] * len(flips)
    assert [e["t_s"] for e in body["events"]] == pytest.approx(flips, abs=1e-12)
    omega2 = np.array(body["series"]["omega2"])
    assert np.sum(np.signbit(omega2[1:]) != np.signbit(omega2[:-1])) == len(flips)


@pytest.mark.parametrize(
    ("params", "field", "words"),
    [
        ({"I1": 1.0, "I2": 1.0, "I3": 2.5}, "I3", "triangle inequality"),
        ({"omega0_rad_s": [0.0, 0.0, 0.0]}, "omega0_rad_s", "must not be zero"),
        ({"omega0_rad_s": 3.0}, "omega0_rad_s", "list of 3 numbers"),
        ({"omega0_rad_s": [1.0, 2.0]}, "omega0_rad_s", "list of 3 numbers"),
        ({"omega0_rad_s": [1.0, 2.0, 3.0, 4.0]}, "omega0_rad_s", "list of 3 numbers"),
        ({"omega0_rad_s": "spin"}, "omega0_rad_s", "list of 3 numbers"),
        ({"omega0_rad_s": [1.0, "fast", 0.0]}, "omega0_rad_s", "component 1"),
        ({"I2": "heavy"}, "I2", "number"),
        ({"ghost": "on"}, "ghost", "unknown input"),  # a display choice of the scene, not a physical input
    ],
)
def test_bad_input_is_a_422_naming_the_field(client, params, field, words):
    response = simulate(client, params)
    assert response.status_code == 422
    detail = response.json()["detail"][0]
    assert detail["loc"][-1] == field and words in detail["msg"], detail


def test_session_refuses_an_impossible_body_and_keeps_its_parameters(client):
    sid = "tfb-api-session-01"
    url = f"/api/scenes/torque-free-body/sessions/{sid}"
    before = client.put(url, json={"params": {"I1": 0.003, "ghost": "on"}}).json()["params"]
    response = client.put(url, json={"params": {"I3": 0.5}})
    assert response.status_code == 422 and "triangle inequality" in response.text
    assert client.put(url, json={"params": {}}).json()["params"] == before
