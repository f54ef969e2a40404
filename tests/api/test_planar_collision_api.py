"""POST /api/examples/planar-collision/solve and the planar-collision scene: the contract and its 422s."""

from __future__ import annotations

import pytest

from app.physics.systems.ch06.planar_collision import EXAMPLE

URL = "/api/examples/planar-collision/solve"
OUTPUTS = ("v1_after_m_s", "v2_after_m_s", "omega1_after_rad_s", "omega2_after_rad_s", "impulse_N_s", "energy_loss_J", "slip_state")


def test_contract_outputs_with_defaults(client):
    response = client.post(URL, json={})
    assert response.status_code == 200
    data = response.json()
    outputs = data["outputs"]
    expected = EXAMPLE.solve(EXAMPLE.inputs.defaults()).outputs
    for name in OUTPUTS:
        assert name in outputs
    for name in ("v1_after_m_s", "v2_after_m_s", "impulse_N_s"):
        assert len(outputs[name]) == 3 and outputs[name][2] == 0.0
        assert outputs[name] == pytest.approx(list(expected[name]), rel=1e-15)
    assert outputs["energy_loss_J"] >= 0.0
    assert outputs["slip_state"] in ("slid throughout", "stuck", "reversed")
    assert [step["title"] for step in data["steps"]]


def test_high_friction_sticks_and_elastic_frictionless_loses_nothing(client):
    stuck = client.post(URL, json={"inputs": {"friction_coefficient": 1.5, "line_of_centres_deg": 60.0}}).json()["outputs"]
    assert stuck["slip_state"] == "stuck"
    elastic = client.post(URL, json={"inputs": {"restitution": 1.0, "friction_coefficient": 0.0}}).json()["outputs"]
    assert abs(elastic["energy_loss_J"]) <= 1e-12 * 9.5  # T before = ½·2·3² + ½·1·1² = 9.5 J at the defaults
    assert elastic["slip_state"] in ("slid throughout", "stuck")


@pytest.mark.parametrize(
    "inputs, field",
    [
        ({"m1_kg": -1.0}, "m1_kg"),
        ({"r1_m": 0.0}, "r1_m"),
        ({"v2_m_s": [1.0, 2.0, 0.3]}, "v2_m_s"),
        ({"v1_m_s": [1.0, 2.0]}, "v1_m_s"),
        ({"v1_m_s": [1.0, "x", 0.0]}, "v1_m_s"),
        ({"restitution": 1.01}, "restitution"),
        ({"restitution": -0.1}, "restitution"),
        ({"friction_coefficient": -1.0}, "friction_coefficient"),
        ({"v1_m_s": [-2.0, 0.0, 0.0]}, "v2_m_s"),  # separating at contact: no impact, refused
    ],
)
def test_bad_inputs_get_422_naming_the_field(client, inputs, field):
    response = client.post(URL, json={"inputs": inputs})
    assert response.status_code == 422
    detail = response.json()["detail"][0]
    assert detail["loc"][-1] == field
    if inputs.get("v1_m_s") == [-2.0, 0.0, 0.0]:
        assert "not approaching" in detail["msg"]


@pytest.mark.parametrize("body", ['{"inputs": {"v1_m_s": [NaN, 0, 0]}}', '{"inputs": {"omega1_rad_s": Infinity}}'])
def test_non_finite_numbers_are_rejected(client, body):
    response = client.post(URL, content=body, headers={"content-type": "application/json"})
    assert response.status_code == 422


def test_scene_is_listed_with_the_example_inputs(client):
    scenes = {s["id"]: s for s in client.get("/api/scenes").json()}
    scene = scenes["planar-collision"]
    names = [p["name"] for p in scene["parameters"]]
    assert names[: len(EXAMPLE.inputs.parameters)] == [p.name for p in EXAMPLE.inputs.parameters]
    assert scene["animated"] and scene["readout"]
    assert any(e["id"] == "planar-collision" for e in client.get("/api/examples").json())
