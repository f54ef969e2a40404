"""Chapter 4 scenes through the API: simulate contracts, 422s for impossible linkages, live scenes.

The series names are contracts: a lesson page or a student's script reads them by name.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from app.physics.systems.ch04 import four_bar
from app.physics.systems.ch04.rolling import SteadyRolling
from tests.api.conftest import live_viewer
from tests.conftest import wait_until

_ids = itertools.count()

CONTRACT_SERIES = {
    "four-bar": {"crank_angle", "coupler_angle", "rocker_angle", "coupler_rate", "rocker_rate"},
    "cardan-joint": {"input_angle", "output_angle", "speed_ratio"},
    "slider-crank": {"crank_angle", "slider_position_m", "slider_velocity_m_s", "slider_acceleration_m_s2"},
    "rolling": {"contact_point_speed", "angular_velocity_x", "angular_velocity_y", "angular_velocity_z"},
}
NON_GRASHOF = {"ground_m": 1.2, "crank_m": 0.9, "coupler_m": 0.7, "rocker_m": 0.6, "crank_angle0_deg": 0.0}


def new_session() -> str:
    return f"linkage-session-{next(_ids):04d}"


def simulate(client, scene_id, params, t_end=6.0, frame_rate=30.0):
    return client.post(f"/api/scenes/{scene_id}/simulate", json={"params": params, "t_end": t_end, "frame_rate": frame_rate})


@pytest.mark.parametrize("scene_id", sorted(CONTRACT_SERIES))
def test_simulate_returns_the_contract_series(client, scene_id):
    response = simulate(client, scene_id, {})
    assert response.status_code == 200, response.text
    body = response.json()
    assert CONTRACT_SERIES[scene_id] <= set(body["series"])
    frames = len(body["t"])
    assert frames == 181
    assert all(len(values) == frames and None not in values for values in body["series"].values())
    assert all(name in body["units"] for name in body["series"])
    assert body["stats"]["method"] == "closed-form" and body["stats"]["status"] == "ok" and body["stats"]["steps"] == 0
    assert body["stats"]["max_invariant_drift"] < 1e-13


def test_four_bar_series_have_their_units_and_match_the_physics(client):
    params = {"crank_speed_rad_s": 2.0, "branch": "crossed"}
    body = simulate(client, "four-bar", params, t_end=3.0).json()
    assert body["units"]["crank_angle"] == body["units"]["coupler_angle"] == body["units"]["rocker_angle"] == "rad"
    assert body["units"]["coupler_rate"] == body["units"]["rocker_rate"] == "rad/s"
    motion = four_bar.FourBarMotion.from_params(four_bar.PARAMETERS.validate(params))
    state = motion.at(np.asarray(body["t"]))
    assert body["series"]["rocker_angle"] == pytest.approx(state.rocker_angle.tolist(), abs=1e-15)
    assert body["series"]["rocker_rate"] == pytest.approx(state.rocker_rate.tolist(), abs=1e-15)
    assert max(body["invariants"]["loop_closure_residual"]) < 1e-14


def test_cardan_series_span_its_bounds(client):
    body = simulate(client, "cardan-joint", {"shaft_angle_deg": 40.0, "input_speed_rad_s": 2 * math.pi}, t_end=1.0, frame_rate=240.0).json()
    ratio = body["series"]["speed_ratio"]
    # 240 frames per turn hold φ₁ = 0° and 90° exactly.
    assert min(ratio) == pytest.approx(math.cos(math.radians(40.0)), rel=1e-12)
    assert max(ratio) == pytest.approx(1 / math.cos(math.radians(40.0)), rel=1e-12)
    assert body["series"]["output_angle"][-1] == pytest.approx(2 * math.pi, abs=1e-12)


def test_non_grashof_four_bar_reports_its_toggle_positions(client):
    body = simulate(client, "four-bar", NON_GRASHOF, t_end=6.0).json()
    toggles = [e for e in body["events"] if e["kind"] == "toggle"]
    motion = four_bar.FourBarMotion.from_params(four_bar.PARAMETERS.validate(NON_GRASHOF))
    assert [e["t_s"] for e in toggles] == pytest.approx([t for t, _ in motion.drive.reversal_times(6.0)], abs=1e-12)
    assert len(toggles) >= 3
    assert all("rocker rate is unbounded here" in e["message"] for e in toggles)
    lower, upper = (math.degrees(x) for x in motion.drive.limits_rad)
    assert max(body["series"]["crank_angle"]) <= math.radians(upper) + 1e-12
    assert min(body["series"]["crank_angle"]) >= math.radians(lower) - 1e-12


@pytest.mark.parametrize(
    "scene_id, params, field, words",
    [
        ("four-bar", {"ground_m": 10.0, "crank_m": 1.0, "coupler_m": 1.0, "rocker_m": 1.0}, None, "cannot be assembled"),
        ("four-bar", {**NON_GRASHOF, "crank_angle0_deg": 180.0}, None, "cannot close with the crank at 180.0°"),
        ("four-bar", {"branch": "sideways"}, "branch", "one of 'open', 'crossed'"),
        ("four-bar", {"crank_m": -1.0}, "crank_m", "between"),
        ("cardan-joint", {"shaft_angle_deg": 90.0}, None, "90"),
        ("slider-crank", {"crank_m": 0.5, "rod_m": 0.6, "offset_m": 0.2}, None, "must be longer than crank + |offset|"),
        ("rolling", {"body": "cone", "tilt_deg": 1.0}, None, "half-angle"),
    ],
)
def test_impossible_input_is_a_422_that_says_why(client, scene_id, params, field, words):
    response = simulate(client, scene_id, params)
    assert response.status_code == 422, response.text
    detail = response.json()["detail"][0]
    assert words in detail["msg"]
    if field is not None:
        assert detail["loc"][-1] == field
    # The same input for a live session is refused too, and the session keeps its values.
    sid = new_session()
    url = f"/api/scenes/{scene_id}/sessions/{sid}"
    before = client.put(url, json={"params": {}}).json()["params"]
    refused = client.put(url, json={"params": params})
    assert refused.status_code == 422 and words in refused.json()["detail"][0]["msg"]
    assert client.put(url, json={"params": {}}).json()["params"] == before


def test_every_preset_assembles_and_simulates(served):
    from app.scenes import SCENES

    for scene_id in CONTRACT_SERIES:
        for preset in SCENES[scene_id].presets:
            with served.new_client() as student:  # one student per preset: simulate is rate limited per device
                response = simulate(student, scene_id, dict(preset.values), t_end=2.0)
            assert response.status_code == 200, (scene_id, preset.name, response.text)


# ---- live scenes ---------------------------------------------------------------------------------


def test_live_four_bar_draws_the_closed_form_and_reads_out_its_numbers(inprocess_client):
    client = inprocess_client  # looks inside the scene instance: the app in this process
    sid = new_session()
    host = client.app.state.scene_host
    with live_viewer(client, "four-bar", sid) as scene:
        wait_until(lambda: scene.t_s > 0.2)  # the frame loop is advancing it
        with host.inspect(sid):  # the frame loop waits while the drawn state is read
            t_s = scene.t_s
            links = np.asarray(scene.links.points)
        state = scene.motion.at(np.array([t_s]))
        a, b = state.positions.crank_pin[0], state.positions.rocker_pin[0]
        # Crank O₂A and coupler AB drawn on the plane y = 0 where the closed form puts them (float32 on the wire).
        assert links[0, 1] == pytest.approx([a[0], 0.0, a[1]], abs=1e-6)
        assert links[1, 1] == pytest.approx([b[0], 0.0, b[1]], abs=1e-6)

        live = client.get(f"/api/scenes/four-bar/sessions/{sid}/live").json()
        values = {q["name"]: q for q in live["readout"]["quantities"]}
        assert values["grashof_class"]["text"] == "crank-rocker" and values["grashof_class"]["value"] is None
        assert values["transmission_angle"]["unit"] == "deg" and values["rocker_rate"]["unit"] == "rad/s"
        t_read = values["t_s"]["value"]
        expected = scene.motion.at(np.array([t_read]))
        # t is shown to 1 ms and μ to 0.01°: |dμ/dt| ≤ 32°/s here, so the two agree to 0.016° + 0.005°.
        assert values["transmission_angle"]["value"] == pytest.approx(math.degrees(expected.transmission_angle[0]), abs=0.03)

        # The non-Grashof preset: the crank rocks, its limits are marked on the start-angle slider.
        assert client.put(f"/api/scenes/four-bar/sessions/{sid}", json={"params": NON_GRASHOF}).status_code == 200
        live = client.get(f"/api/scenes/four-bar/sessions/{sid}/live").json()["readout"]
        values = {q["name"]: q["value"] if q["value"] is not None else q["text"] for q in live["quantities"]}
        assert values["grashof_class"] == "non-Grashof"
        limits = four_bar.FourBarMotion.from_params(four_bar.PARAMETERS.validate(NON_GRASHOF)).drive.limits_rad
        assert [m["value"] for m in live["marks"]["crank_angle0_deg"]] == pytest.approx([math.degrees(x) for x in limits], abs=0.006)
        assert [m["label"] for m in live["marks"]["crank_angle0_deg"]] == ["toggle", "toggle"]


def test_live_rolling_scene_reports_a_computed_zero_contact_velocity(inprocess_client):
    client = inprocess_client  # looks inside the scene instance: the app in this process
    sid = new_session()
    host = client.app.state.scene_host
    assert client.put(f"/api/scenes/rolling/sessions/{sid}", json={"params": {"body": "cone", "tilt_deg": 25.0}}).status_code == 200
    with live_viewer(client, "rolling", sid) as scene:
        wait_until(lambda: scene.t_s > 0.2)
        readout = client.get(f"/api/scenes/rolling/sessions/{sid}/live").json()["readout"]
        values = {q["name"]: q for q in readout["quantities"]}
        assert values["contact_point_velocity"]["text"] == "0.000" and values["contact_point_velocity"]["unit"] == "m/s"
        assert 0.0 <= values["contact_point_speed"]["value"] < 1e-14
        rolling = SteadyRolling.from_params(scene.params)
        assert values["path_radius"]["value"] == pytest.approx(rolling.rim_radius_m / math.sin(math.radians(25.0)), abs=1e-6)
        assert abs(values["axis_misalignment"]["value"]) < 1e-9
        with host.inspect(sid):
            assert scene.contact_label.text == "C: v_C = 0.000 m/s"
            assert scene.contact_arrow.visible is False  # a zero-length arrow: drawn as the dot at C
