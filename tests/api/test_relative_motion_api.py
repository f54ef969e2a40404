"""Chapter 3.5–3.6 scenes over HTTP: the simulate contracts, the 422s, and the live readouts of a connected viewer."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from app.physics.systems import earth
from app.physics.systems.ch03 import eastward_deflection as deflection
from app.physics.systems.ch03 import foucault_pendulum as foucault
from app.physics.systems.ch03 import moving_frame as moving
from tests.api.conftest import live_viewer
from tests.conftest import wait_until

_ids = itertools.count()


def new_session() -> str:
    return f"relmotion-{next(_ids):04d}"


def simulate(client, scene_id, body):
    return client.post(f"/api/scenes/{scene_id}/simulate", json=body)


# -- simulate contracts ------------------------------------------------------------------------
def test_moving_frame_simulate_returns_each_term_and_their_sum(client):
    params = {"tilt_deg": 20.0, "precession_rate_rad_s": 0.5, "cart_amplitude_m": 0.2, "cart_frequency_hz": 0.5}
    response = simulate(client, "moving-frame-acceleration", {"params": params, "t_end": 4.0, "frame_rate": 10})
    assert response.status_code == 200, response.text
    body = response.json()
    assert body["stats"]["method"] == "closed-form" and body["stats"]["status"] == "ok"
    assert len(body["t"]) == 41 and body["units"]["a_coriolis_x"] == "m/s²" and body["units"]["omega_z"] == "rad/s"
    series = {k: np.asarray(v) for k, v in body["series"].items()}
    for c in "xyz":
        parts = sum(series[f"a_{name}_{c}"] for name in moving.TERM_NAMES)
        np.testing.assert_allclose(series[f"a_total_{c}"], parts, atol=1e-12)
    expected = moving.MovingFrameMotion.from_params(moving.PARAMETERS.validate(params)).acceleration_terms(np.asarray(body["t"]))
    np.testing.assert_allclose(series["a_coriolis_y"], expected["coriolis"][:, 1], rtol=0, atol=1e-12)


def test_foucault_simulate_integrates_and_reports_the_jacobi_integral(client):
    response = simulate(client, "foucault-pendulum", {"params": {"latitude_deg": 60.0}, "t_end": 30.0, "frame_rate": 30})
    assert response.status_code == 200, response.text
    body = response.json()
    assert body["stats"]["method"] == "rk4" and body["stats"]["status"] == "ok"
    assert body["stats"]["max_invariant_drift"] < 1e-6  # RK4 at h·ω ≤ 0.1 over 30 s (measured ~2e-8)
    assert set(body["series"]) == {"bob_east", "bob_north", "bob_up", "swing_plane_bearing"}
    assert body["units"]["invariants.jacobi_integral"] == "J/kg" and body["units"]["swing_plane_bearing"] == "deg"
    bearing = np.asarray(body["series"]["swing_plane_bearing"])
    rate = math.radians(np.polyfit(body["t"], bearing, 1)[0])  # the smooth per-frame plane, clockwise positive
    expected = 1000.0 * earth.vertical_earth_rate_rad_s(60.0)
    assert rate == pytest.approx(expected, rel=0.01)  # 30 s is under half a turn; amplitude lag 0.4 %


def test_eastward_deflection_simulate_lands_and_holds(client):
    response = simulate(client, "eastward-deflection", {"params": {"height_m": 100.0, "latitude_deg": 45.0}, "t_end": 6.0, "frame_rate": 20})
    assert response.status_code == 200, response.text
    body = response.json()
    assert body["stats"]["method"] == "closed-form" and body["stats"]["status"] == "ok"
    (landed,) = body["events"]
    assert landed["kind"] == "landed" and landed["t_s"] == pytest.approx(math.sqrt(200.0 / earth.STANDARD_GRAVITY_M_S2), rel=1e-7)
    east = np.asarray(body["series"]["east_deflection"])
    assert 1000.0 * east[-1] == pytest.approx(15.524, abs=1e-3)
    after = np.asarray(body["t"]) > landed["t_s"]
    assert np.all(east[after] == east[-1]) and np.all(np.abs(np.asarray(body["series"]["up"])[after]) < 1e-9)
    assert body["stats"]["max_invariant_drift"] < 1e-12


@pytest.mark.parametrize(
    "scene_id, body, loc_end",
    [
        ("moving-frame-acceleration", {"params": {"spin_rate_rad_s": 60.0}, "t_end": 1.0}, "spin_rate_rad_s"),
        ("moving-frame-acceleration", {"params": {"table_radius_m": 0.5, "slider_amplitude_m": 0.5, "groove_offset_m": 0.3}, "t_end": 1.0}, "slider_amplitude_m"),
        ("moving-frame-acceleration", {"params": {"time_s": 1.0}, "t_end": 1.0}, "time_s"),  # a display control, not physics
        ("moving-frame-acceleration", {"params": {}, "t_end": 1.0, "method": "rk4"}, "method"),
        ("foucault-pendulum", {"params": {"latitude_deg": 91.0}, "t_end": 1.0}, "latitude_deg"),
        ("foucault-pendulum", {"params": {"length_m": 2.0, "amplitude_m": 1.9}, "t_end": 1.0}, "amplitude_m"),
        ("foucault-pendulum", {"params": {"release": "thrown"}, "t_end": 1.0}, "release"),
        ("foucault-pendulum", {"params": {}, "t_end": 700.0}, "t_end"),
        ("eastward-deflection", {"params": {"launch_velocity_m_s": [0.0, 1.0]}, "t_end": 1.0}, "launch_velocity_m_s"),
        ("eastward-deflection", {"params": {"height_m": "tall"}, "t_end": 1.0}, "height_m"),
        ("eastward-deflection", {"params": {"g_m_s2": float("inf")}, "t_end": 1.0}, None),
    ],
)
def test_bad_requests_get_a_422_naming_the_field(client, scene_id, body, loc_end):
    if loc_end is None:  # JSON cannot carry infinity: send the text a careless client would
        response = client.post(f"/api/scenes/{scene_id}/simulate", content=b'{"params": {"g_m_s2": Infinity}, "t_end": 1.0}', headers={"content-type": "application/json"})
        assert response.status_code == 422
        return
    response = simulate(client, scene_id, body)
    assert response.status_code == 422, response.text
    detail = response.json()["detail"][0]
    assert detail["loc"][-1] == loc_end and detail["msg"]


# -- a connected viewer: the scene builds and its readout is the physics ----------------------------
def _readout(client, scene_id, sid) -> dict:
    live = client.get(f"/api/scenes/{scene_id}/sessions/{sid}/live")
    assert live.status_code == 200
    quantities = live.json()["readout"]["quantities"]
    for q in quantities:  # every number carries its unit; a quantity without a number says why in words
        assert (q["value"] is None and q["text"]) or (math.isfinite(q["value"]) and (q["unit"] or q["name"] == "turning_points")), q
    return {q["name"]: q["value"] if q["value"] is not None else q["text"] for q in quantities}


def test_moving_frame_viewer_holds_an_instant_and_reads_out_its_terms(inprocess_client):
    client = inprocess_client  # looks inside the scene instance: the app in this process
    sid = new_session()
    params = {
        "spin_acceleration_rad_s2": 1.0, "tilt_deg": 25.0, "precession_rate_rad_s": 0.6,
        "cart_amplitude_m": 0.2, "cart_frequency_hz": 0.5, "playback_speed": 0.0, "time_s": 1.5, "replay_s": 3.0,
    }
    assert client.put(f"/api/scenes/moving-frame-acceleration/sessions/{sid}", json={"params": params}).status_code == 200
    with live_viewer(client, "moving-frame-acceleration", sid) as scene:
        values = _readout(client, "moving-frame-acceleration", sid)
        physical = moving.PARAMETERS.validate({k: v for k, v in params.items() if k in moving.PARAMETERS.by_name})
        motion = moving.MovingFrameMotion.from_params(physical)
        terms = {k: v[0] for k, v in motion.acceleration_terms(np.array([1.5])).items()}
        assert values["t_s"] == 1.5
        for name in (*moving.TERM_NAMES, "total"):
            assert values[f"a_{name}_magnitude"] == pytest.approx(float(np.linalg.norm(terms[name])), rel=1e-12)
            shown = [float(c) for c in values[f"a_{name}"].strip("()").split(",")]
            np.testing.assert_allclose(shown, terms[name], atol=5e-4)  # printed to 3 decimals
        # The drawn arrows: the five terms head to tail from P, and a_P from P to the same end point.
        with client.app.state.scene_host.inspect(sid):
            points = np.asarray(scene.accel._node.points, dtype=float)
            drawn = scene.accel._drawn
        # Terms shorter than their own arrowhead are listed but not drawn; at this instant most are drawn.
        assert {"centripetal", "coriolis", "relative", "reference", "total"} <= set(drawn)
        p = motion.position_world(np.array([1.5]))[0]
        scale = values["arrow_scale"]
        tail = p
        for name in moving.TERM_NAMES:
            head = tail + scale * terms[name]
            if name in drawn:
                np.testing.assert_allclose(points[drawn.index(name)], [tail, head], atol=1e-5)  # float32 on the wire
            tail = head
        np.testing.assert_allclose(points[drawn.index("total")], [p, p + scale * terms["total"]], atol=1e-5)
        np.testing.assert_allclose(tail, p + scale * terms["total"], atol=1e-12)  # the chain closes on a_P


def test_foucault_viewer_reads_out_the_predicted_rates(inprocess_client):
    client = inprocess_client  # looks inside the scene instance: the app in this process
    sid = new_session()
    with live_viewer(client, "foucault-pendulum", sid) as scene:
        wait_until(lambda: scene.run.t_s > 0.3)
        values = _readout(client, "foucault-pendulum", sid)
        defaults = foucault.PARAMETERS.defaults()
        assert values["real_rate_deg_h"] == pytest.approx(math.degrees(earth.vertical_earth_rate_rad_s(48.85)) * 3600.0, rel=1e-12)
        assert values["real_full_turn_h"] == pytest.approx(360.0 / values["real_rate_deg_h"], rel=1e-12)
        assert values["scene_rate_deg_s"] == pytest.approx(math.degrees(foucault.clockwise_precession_rate_rad_s(defaults)), rel=1e-12)
        assert values["period_s"] == pytest.approx(2 * math.pi * math.sqrt(10.0 / earth.STANDARD_GRAVITY_M_S2), rel=1e-12)
        live = client.get(f"/api/scenes/foucault-pendulum/sessions/{sid}/live").json()
        assert live["invariants"]["jacobi_integral"]["relative_drift"] < 1e-6
        # At the equator the real Earth has no full turn to report.
        assert client.put(f"/api/scenes/foucault-pendulum/sessions/{sid}", json={"params": {"latitude_deg": 0.0}}).status_code == 200
        assert _readout(client, "foucault-pendulum", sid)["real_full_turn_h"] == "never (equator)"


def test_eastward_viewer_reads_out_exact_and_series_deflections(client):
    sid = new_session()
    assert client.put(f"/api/scenes/eastward-deflection/sessions/{sid}", json={"params": {}}).status_code == 200  # the page opens its scene first
    with live_viewer(client, "eastward-deflection", sid):
        values = _readout(client, "eastward-deflection", sid)
        flight = deflection.Flight.from_params(deflection.PARAMETERS.defaults())
        assert values["east_mm"] == pytest.approx(1000.0 * flight.deflection()[0], rel=1e-12)
        assert values["east_first_order_mm"] == pytest.approx(
            1000.0 * deflection.drop_east_deflection_first_order_m(height_m=100.0, latitude_deg=45.0, g_m_s2=earth.STANDARD_GRAVITY_M_S2), rel=1e-9
        )
        assert values["south_second_order_mm"] == pytest.approx(
            1000.0 * deflection.drop_south_deflection_second_order_m(height_m=100.0, latitude_deg=45.0, g_m_s2=earth.STANDARD_GRAVITY_M_S2), rel=1e-6
        )
        assert values["exaggeration"] >= 100.0
        thrown = {"launch_velocity_m_s": [0.0, 0.0, 40.0], "height_m": 1.0}
        assert client.put(f"/api/scenes/eastward-deflection/sessions/{sid}", json={"params": thrown}).status_code == 200
        assert _readout(client, "eastward-deflection", sid)["east_mm"] < 0.0  # thrown up, it lands west
        # At the pole Ω is parallel to the fall: no deflection, and nothing to enlarge.
        pole = {"latitude_deg": 90.0, "launch_velocity_m_s": [0.0, 0.0, 0.0]}
        assert client.put(f"/api/scenes/eastward-deflection/sessions/{sid}", json={"params": pole}).status_code == 200
        values = _readout(client, "eastward-deflection", sid)
        assert abs(values["east_mm"]) < 1e-9 and values["exaggeration"] == 1.0
