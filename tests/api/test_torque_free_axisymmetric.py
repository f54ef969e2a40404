"""The torque-free axisymmetric scene through the API: simulate report, 422s, slider ranges, live scene and readout."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from app.physics.math.rotations import quaternion_from_euler_313, quaternion_multiply
from app.physics.systems.ch10 import torque_free_axisymmetric as physics
from app.scenes.ch10.torque_free_axisymmetric import TorqueFreeAxisymmetricScene
from tests.api.conftest import live_viewer
from tests.conftest import wait_until

SCENE = "torque-free-axisymmetric"
_ids = itertools.count()


def new_session() -> str:
    return f"tfa-session-{next(_ids):04d}"


def simulate(client, params, t_end=10.0, frame_rate=30.0):
    return client.post(f"/api/scenes/{SCENE}/simulate", json={"params": params, "t_end": t_end, "frame_rate": frame_rate})


def test_simulate_returns_the_contract_series_from_the_closed_form(client):
    params = {"I_transverse": 0.5, "I_axial": 0.99, "spin_rad_s": 1.0, "nutation_deg": 15.0}
    response = simulate(client, params)
    assert response.status_code == 200
    body = response.json()
    assert set(body["series"]) == {"theta", "phi", "psi"}
    assert set(body["invariants"]) == {"energy", "angular_momentum"}
    assert body["units"]["theta"] == body["units"]["phi"] == body["units"]["psi"] == "rad"
    assert body["units"]["invariants.energy"] == "J" and body["units"]["invariants.angular_momentum"] == "kg·m²/s"
    assert body["stats"]["method"] == "closed-form" and body["stats"]["steps"] == 0 and body["stats"]["status"] == "ok"
    t = np.array(body["t"])
    assert len(t) == 301 and t[-1] == pytest.approx(10.0)
    motion = physics.motion_from_params(params)
    # JSON carries doubles exactly; the series are the model's formulas at the frame times.
    assert np.allclose(body["series"]["theta"], math.radians(15.0), rtol=0, atol=1e-15)
    assert np.allclose(body["series"]["phi"], motion.precession_rate_rad_s * t, rtol=1e-15, atol=0)
    assert np.allclose(body["series"]["psi"], motion.spin_rate_rad_s * t, rtol=1e-15, atol=0)
    assert body["invariants"]["energy"][0] == pytest.approx(motion.energy_J, rel=1e-14)
    # Energy and |L| recomputed from the body-axis ω at every frame: constant to round-off.
    assert body["stats"]["max_invariant_drift"] < 1e-14


@pytest.mark.parametrize(
    "params, field, words",
    [
        ({"I_transverse": 1.0, "I_axial": 3.0}, "I_axial", "triangle inequality"),
        ({"I_transverse": -1.0}, "I_transverse", "between"),
        ({"spin_rad_s": 0}, "spin_rad_s", "must not be zero"),
        ({"spin_rad_s": -1.5}, "spin_rad_s", "must be positive"),
        ({"nutation_deg": 90}, "nutation_deg", "between 0 and 89"),
        ({"spin": 3.0}, "spin", "unknown input"),
    ],
)
def test_simulate_refuses_impossible_bodies_with_a_reason(client, params, field, words):
    response = simulate(client, params)
    assert response.status_code == 422
    detail = response.json()["detail"][0]
    assert detail["loc"] == ["body", "params", field] and words in detail["msg"], detail


@pytest.mark.parametrize("name", ["I_transverse", "I_axial", "spin_rad_s", "nutation_deg"])
def test_simulate_refuses_nan(client, name):
    response = client.post(
        f"/api/scenes/{SCENE}/simulate",
        content=f'{{"params": {{"{name}": NaN}}, "t_end": 5}}',
        headers={"Content-Type": "application/json"},
    )
    assert response.status_code == 422
    detail = response.json()["detail"][0]
    assert detail["loc"] == ["body", "params", name] and "finite" in detail["msg"]


def test_simulate_refuses_integrator_controls(client):
    response = client.post(f"/api/scenes/{SCENE}/simulate", json={"params": {}, "t_end": 5, "method": "rk4"})
    assert response.status_code == 422 and "closed form" in response.json()["detail"][0]["msg"]


def test_scene_schema_and_every_slider_combination_is_a_real_body(client):
    scenes = {s["id"]: s for s in client.get("/api/scenes").json()}
    schema = scenes[SCENE]
    assert schema["chapter"] == 10 and schema["animated"] and schema["readout"] and not schema["integrated"]
    assert [p["name"] for p in schema["parameters"]] == ["I_transverse", "I_axial", "spin_rad_s", "nutation_deg"]
    assert {p["name"] for p in schema["presets"]} >= {"coin", "football", "near-sphere"}
    # Each constraint is monotone in each input, so the corners of the slider box are the worst cases.
    ranges = [(p["min"], p["max"]) for p in schema["parameters"]]
    names = [p["name"] for p in schema["parameters"]]
    for corner in itertools.product(*ranges):
        physics.PARAMETERS.validate(dict(zip(names, corner)))  # raises if a slider setting were impossible
    # ... and the slider box lies inside the model's accepted ranges.
    for p in schema["parameters"]:
        wide = physics.PARAMETERS.by_name[p["name"]]
        assert wide.min <= p["min"] and p["max"] <= wide.max


def test_session_put_out_of_slider_range_is_422_and_changes_nothing(client):
    sid = new_session()
    url = f"/api/scenes/{SCENE}/sessions/{sid}"
    before = client.put(url, json={"params": {"nutation_deg": 30}}).json()["params"]
    response = client.put(url, json={"params": {"I_axial": 1.5}})
    assert response.status_code == 422 and "I_axial" in response.json()["detail"][0]["loc"]
    assert client.put(url, json={"params": {}}).json()["params"] == before


def test_live_scene_draws_the_closed_form_and_reads_out_its_numbers(inprocess_client):
    client = inprocess_client  # looks inside the scene instance: the app in this process
    host = client.app.state.scene_host
    sid = new_session()
    with live_viewer(client, SCENE, sid) as scene:
        assert isinstance(scene, TorqueFreeAxisymmetricScene)
        wait_until(lambda: scene.t_s > 0.2)  # the frame loop is advancing it

        # The drawn attitude (nodal frame ∘ body frame) is the closed form at the scene's own time.
        with host.inspect(sid):  # the frame loop waits while the drawn state is read
            t_s = scene.t_s
            drawn = quaternion_multiply(np.asarray(scene.nodal.wxyz), np.asarray(scene.body.wxyz))
        phi, theta, psi = (float(a) for a in scene.motion.euler_angles_313(t_s))
        expected = quaternion_from_euler_313(phi, theta, psi)
        assert min(np.abs(drawn - expected).max(), np.abs(drawn + expected).max()) < 1e-6  # float32 on the wire

        live = client.get(f"/api/scenes/{SCENE}/sessions/{sid}/live").json()
        values = {q["name"]: q for q in live["readout"]["quantities"]}
        motion = physics.motion_from_params(physics.PARAMETERS.defaults())
        assert values["precession_rate"]["value"] == pytest.approx(motion.precession_rate_rad_s, rel=1e-15)
        assert values["spin_rate"]["value"] == pytest.approx(1.8, rel=1e-15)
        assert values["sense"]["text"] == "direct" and values["sense"]["value"] is None
        assert values["body_cone_half_angle"]["unit"] == "deg"
        assert values["space_cone_half_angle"]["value"] == pytest.approx(math.degrees(motion.space_cone_half_angle_rad), rel=1e-15)
        assert all(q["unit"] or q["name"] == "sense" for q in values.values())
        assert [m["label"] for m in live["readout"]["marks"]["I_axial"]] == ["sphere", "flat disc"]

        # A preset for an oblate body: the readout turns retrograde and the cone angles follow.
        coin = next(p for p in TorqueFreeAxisymmetricScene.presets if p.name == "coin")
        assert client.put(f"/api/scenes/{SCENE}/sessions/{sid}", json={"params": dict(coin.values)}).status_code == 200
        values = {q["name"]: q["value"] if q["value"] is not None else q["text"] for q in client.get(f"/api/scenes/{SCENE}/sessions/{sid}/live").json()["readout"]["quantities"]}
        assert values["sense"] == "retrograde" and values["body_cone_half_angle"] > 15.0 > values["space_cone_half_angle"]
