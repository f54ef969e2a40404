"""Section 10.3 scenes through the API: the simulate contract, 422s, and the live scenes' readouts.

Closed-form scenes (free-gyroscope, rate-gyro) must return the model's formulas at the frame times
(JSON carries doubles exactly, so agreement is to the last bit); the gyrocompass is integrated and
checked against a tight scipy integration of the same reduced equation.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from app.physics.systems.ch10 import free_gyroscope, gyrocompass, rate_gyro
from tests.api.conftest import live_viewer
from tests.conftest import wait_until

_ids = itertools.count()


def new_session() -> str:
    return f"gyro-session-{next(_ids):04d}"


def simulate(client, scene_id, params=None, t_end=10.0, frame_rate=30.0, **extra):
    body = {"params": params or {}, "t_end": t_end, "frame_rate": frame_rate, **extra}
    return client.post(f"/api/scenes/{scene_id}/simulate", json=body)


# -- simulate: the contract ----------------------------------------------------------------------
def test_free_gyroscope_simulate_returns_the_closed_form_and_the_lock_event(client):
    params = {"vehicle_rate_rad_s": [0.3, 0.0, 0.0]}
    response = simulate(client, "free-gyroscope", params, t_end=8.0, frame_rate=30.0)
    assert response.status_code == 200
    body = response.json()
    assert set(body["series"]) == set(free_gyroscope.FreeGyroscope.series_units)
    assert body["units"]["inner_gimbal_rad"] == "rad" and body["units"]["outer_gimbal_rate_rad_s"] == "rad/s"
    assert body["stats"]["method"] == "closed-form" and body["stats"]["status"] == "ok"
    t = np.array(body["t"])
    assert len(t) == 241
    expected = free_gyroscope.gimbal_motion(free_gyroscope.PARAMETERS.validate(params), t)
    assert np.array_equal(np.array(body["series"]["inner_gimbal_rad"]), expected.inner_rad)
    # A pure roll: the inner ring turns back at the roll rate until the lock at (π/2)/0.3 s.
    before_lock = t < 5.0
    assert np.allclose(np.array(body["series"]["inner_gimbal_rad"])[before_lock], -0.3 * t[before_lock], atol=1e-12)
    assert [e["kind"] for e in body["events"]] == ["gimbal-lock"]
    assert body["events"][0]["t_s"] == pytest.approx(0.5 * math.pi / 0.3, abs=1e-12)
    assert body["stats"]["max_invariant_drift"] < 1e-12  # the spin axis rebuilt from the rings never moves


def test_rate_gyro_simulate_returns_the_step_response(client):
    response = simulate(client, "rate-gyro", {"input_rate_rad_s": 0.4}, t_end=20.0, frame_rate=20.0)
    assert response.status_code == 200
    body = response.json()
    assert body["stats"]["method"] == "closed-form"
    assert body["units"]["beta_rad"] == "rad" and body["units"]["indicated_rate_rad_s"] == "rad/s"
    params = rate_gyro.PARAMETERS.validate({"input_rate_rad_s": 0.4})
    t = np.array(body["t"])
    assert np.array_equal(np.array(body["series"]["beta_rad"]), rate_gyro.gimbal_response(params, t).beta_rad)
    # ζ = 0.2, ω_n = 10 rad/s: after 20 s (40 time constants) β = I_a ω_s Ω / k = 2e-4·1000·0.4/0.5 = 0.16 rad.
    assert body["series"]["beta_rad"][-1] == pytest.approx(0.16, abs=1e-12)
    assert body["series"]["indicated_rate_rad_s"][-1] == pytest.approx(0.4, abs=1e-11)


def test_gyrocompass_simulate_integrates_the_reduced_equation(client):
    params = {"alpha0_deg": 30.0, "damping_N_m_s_rad": 0.002}
    response = simulate(client, "gyrocompass", params, t_end=300.0, frame_rate=2.0)
    assert response.status_code == 200
    body = response.json()
    assert body["stats"]["method"] == "rk4" and body["stats"]["status"] == "ok"
    assert body["units"]["alpha_rad"] == "rad" and body["units"]["invariants.energy_plus_dissipated_J"] == "J"
    validated = gyrocompass.PARAMETERS.validate(params)
    k, i_t, c = gyrocompass.restoring_moment_N_m(validated), validated["vertical_inertia_kg_m2"], 0.002
    t = np.array(body["t"])
    reference = solve_ivp(
        lambda _, y: [y[1], (-k * math.sin(y[0]) - c * y[1]) / i_t], (0.0, 300.0), [math.radians(30.0), 0.0],
        t_eval=t, method="DOP853", rtol=1e-12, atol=1e-12,
    )
    # RK4 with h·ω_n ≈ 0.03 (one step per 0.5 s frame): measured error 4.4e-8 rad; allowed 1e-6.
    assert np.max(np.abs(np.array(body["series"]["alpha_rad"]) - reference.y[0])) < 1e-6
    assert body["stats"]["max_invariant_drift"] < 1e-6


# -- simulate: bad input is a 422 naming the field -----------------------------------------------
@pytest.mark.parametrize(
    ("scene_id", "params", "field", "words"),
    [
        ("free-gyroscope", {"spin_rad_s": 0}, "spin_rad_s", "non-zero"),
        ("free-gyroscope", {"vehicle_rate_rad_s": [0.1, 0.2]}, "vehicle_rate_rad_s", "list of 3 numbers"),
        ("free-gyroscope", {"rotor_inertia_kg_m2": -1.0}, "rotor_inertia_kg_m2", "between"),
        ("gyrocompass", {"latitude_deg": 90}, "latitude_deg", "horizontal component"),
        ("gyrocompass", {"spin_rad_s": 0}, "spin_rad_s", "non-zero"),
        ("gyrocompass", {"vertical_inertia_kg_m2": 0}, "vertical_inertia_kg_m2", "between"),
        ("gyrocompass", {"time_scale": 10}, "time_scale", "unknown input"),
        ("rate-gyro", {"spin_rad_s": 0}, "spin_rad_s", "non-zero"),
        ("rate-gyro", {"input_kind": "ramp"}, "input_kind", "one of"),
        ("rate-gyro", {"stiffness_N_m_rad": 0}, "stiffness_N_m_rad", "between"),
        # The undamped gimbal driven at resonance is valid input (finite for finite time): answered with a
        # warning, see tests/api/test_hardening_physics.py (issue 16, item 8).
    ],
)
def test_bad_parameters_are_422_with_a_sentence(client, scene_id, params, field, words):
    response = simulate(client, scene_id, params)
    assert response.status_code == 422
    detail = response.json()["detail"][0]
    assert detail["loc"][-1] == field
    assert words in detail["msg"]


@pytest.mark.parametrize(
    ("scene_id", "extra", "field"),
    [
        ("free-gyroscope", {"t_end": 601.0}, "t_end"),
        ("rate-gyro", {"frame_rate": 0.5}, "frame_rate"),
        ("rate-gyro", {"method": "rk4"}, "method"),  # a closed form has no integrator to choose
        ("gyrocompass", {"method": "splitting4"}, "method"),  # the geometric splitting is for rigid bodies only
    ],
)
def test_bad_requests_are_422(client, scene_id, extra, field):
    body = {"t_end": 10.0, "frame_rate": 30.0, **extra}
    response = client.post(f"/api/scenes/{scene_id}/simulate", json={"params": {}, **body})
    assert response.status_code == 422
    assert field in response.json()["detail"][0]["loc"]


# -- live scenes ----------------------------------------------------------------------------------
def _readout(client, scene_id, sid):
    live = client.get(f"/api/scenes/{scene_id}/sessions/{sid}/live")
    assert live.status_code == 200
    quantities = live.json()["readout"]["quantities"]
    assert all(isinstance(q["unit"], str) for q in quantities)
    return {q["name"]: q["value"] for q in quantities}, live.json()


def test_live_free_gyroscope_reads_out_the_closed_form(inprocess_client):
    client = inprocess_client  # looks inside the scene instance: the app in this process
    host = client.app.state.scene_host
    sid = new_session()
    assert client.put(f"/api/scenes/free-gyroscope/sessions/{sid}", json={"params": {"vehicle_rate_rad_s": [0.0, 0.0, 0.5]}}).status_code == 200
    with live_viewer(client, "free-gyroscope", sid) as scene:
        wait_until(lambda: scene.t_s > 0.3)
        with host.inspect(sid):  # the frame loop waits while the drawn state is read
            # A copy: viser updates a node's wxyz array in place, so a view would show a later frame by the time it is
            # compared (the rare failure with the ring one frame ahead of the clock).
            t_drawn, drawn_outer = scene.t_s, np.array(scene.outer.wxyz)
        values, _ = _readout(client, "free-gyroscope", sid)  # one readout is one consistent instant
        t_s = values["t_s"]
        # Yaw at 0.5 rad/s: the outer ring turns back by the heading change, the inner ring stays level.
        assert values["outer_gimbal_deg"] == pytest.approx(math.degrees(math.remainder(-0.5 * t_s, 2 * math.pi)), abs=1e-9)
        assert values["inner_gimbal_deg"] == pytest.approx(0.0, abs=1e-9)
        assert values["outer_gimbal_rate_rad_s"] == pytest.approx(-0.5, abs=1e-12)
        expected = np.array([math.cos(-0.25 * t_drawn), 0.0, 0.0, math.sin(-0.25 * t_drawn)])
        assert min(np.abs(drawn_outer - expected).max(), np.abs(drawn_outer + expected).max()) < 1e-6  # float32 on the wire
        assert values["torque_on_rotor_N_m"] == 0.0
        # A bad PUT is refused and changes nothing.
        bad = client.put(f"/api/scenes/free-gyroscope/sessions/{sid}", json={"params": {"spin_rad_s": 0}})
        assert bad.status_code == 422
        assert host.instances(sid)[0].params["spin_rad_s"] == 2000.0


def test_live_rate_gyro_reads_out_gain_frequency_damping_and_beta(inprocess_client):
    client = inprocess_client  # looks inside the scene instance: the app in this process
    sid = new_session()
    with live_viewer(client, "rate-gyro", sid) as scene:
        wait_until(lambda: scene.t_s > 0.3)
        values, live = _readout(client, "rate-gyro", sid)  # one readout is one consistent instant
        t_s = values["t_s"]
        params = rate_gyro.PARAMETERS.defaults()
        assert values["steady_gain_s"] == pytest.approx(2e-4 * 1000.0 / 0.5, rel=1e-15)
        assert values["natural_frequency_rad_s"] == pytest.approx(10.0, rel=1e-14)
        assert values["damping_ratio"] == pytest.approx(0.2, rel=1e-14)
        assert t_s < scene._hold_s  # still in the first "turntable running" phase
        assert values["beta_rad"] == pytest.approx(float(rate_gyro.gimbal_response(params, t_s).beta_rad[0]), abs=1e-15)
        marks = live["readout"]["marks"]["damping_N_m_s_rad"]
        assert marks[0]["value"] == pytest.approx(0.1, rel=1e-14)


def test_live_gyrocompass_runs_time_scaled_and_reads_out_the_period(inprocess_client):
    client = inprocess_client  # looks inside the scene instance: the app in this process
    sid = new_session()
    assert client.put(f"/api/scenes/gyrocompass/sessions/{sid}", json={"params": {"time_scale": 50.0}}).status_code == 200
    with live_viewer(client, "gyrocompass", sid) as scene:
        wait_until(lambda: scene.run.t_s > 20.0)  # 50× real time: 20 simulated seconds in about 0.4 s
        values, live = _readout(client, "gyrocompass", sid)  # one readout is one consistent instant
        t_s, alpha = values["t_s"], math.radians(values["alpha_deg"])
        params = gyrocompass.PARAMETERS.defaults()
        assert values["time_scale"] == 50.0
        assert t_s > 20.0
        assert values["small_angle_period_s"] == pytest.approx(gyrocompass.small_angle_period_s(params), rel=1e-15)
        assert values["swing_period_s"] == pytest.approx(gyrocompass.large_amplitude_period_s(params, math.radians(40.0)), rel=1e-12)
        # The integration panel: RK4 at the scaled frame, energy kept to round-off.
        assert "50× real time" in live["description"]
        assert live["invariants"]["energy_plus_dissipated_J"]["relative_drift"] < 1e-8
        # α from the live run matches a tight integration of the reduced equation at the same simulated time.
        k, i_t = gyrocompass.restoring_moment_N_m(params), params["vertical_inertia_kg_m2"]
        reference = solve_ivp(lambda _, y: [y[1], -k * math.sin(y[0]) / i_t], (0.0, t_s), [math.radians(40.0), 0.0], method="DOP853", rtol=1e-12, atol=1e-12)
        assert alpha == pytest.approx(reference.y[0, -1], abs=1e-6)
