"""POST /api/scenes/cartesian-pendulum/simulate: DAE algorithm as `method`, the integrator, Baumgarte gains, consistent starts."""

from __future__ import annotations

import pytest

URL = "/api/scenes/cartesian-pendulum/simulate"
UNIT = {"mass_kg": 1.0, "length_m": 1.0, "g_m_s2": 1.0, "x0_m": 1.0, "y0_m": 0.0, "vx0_m_s": 0.0, "vy0_m_s": 0.0}


@pytest.mark.parametrize("method", ["uncorrected", "baumgarte", "projection", "partitioning", "minimal"])
def test_every_algorithm_answers_with_series_residuals_and_stats(client, method):
    body = {"params": UNIT, "t_end": 5.0, "frame_rate": 30.0, "method": method, "integrator": "rk4", "steps_per_frame": 4,
            "baumgarte_alpha_1_s": 5.0, "baumgarte_beta_1_s": 5.0}  # fmt: skip
    answer = client.post(URL, json=body)
    assert answer.status_code == 200, answer.text
    data = answer.json()
    assert set(data["series"]) >= {"x_m", "y_m", "vx_m_s", "vy_m_s", "multiplier"}
    assert set(data["invariants"]) == {"energy", "constraint_position", "constraint_velocity"}
    assert data["stats"]["method"] == method and data["stats"]["integrator"] == "rk4"
    assert data["stats"]["initial_conditions"] == []
    assert data["units"]["multiplier"] == "N/m" and data["units"]["invariants.constraint_position"] == "m²"
    assert max(data["invariants"]["constraint_position"]) < 1e-5  # 5 s at h = 8.3 ms: every method keeps the rod's length
    assert len(data["t"]) == 151


def test_inconsistent_start_reports_what_changed(client):
    answer = client.post(URL, json={"params": {**UNIT, "x0_m": 1.2, "y0_m": 0.4}, "t_end": 1.0})
    assert answer.status_code == 200, answer.text
    stats = answer.json()["stats"]
    assert stats["method"] == "projection" and {c["name"] for c in stats["initial_conditions"]} == {"x0_m", "y0_m"}
    assert all(set(c) == {"name", "requested", "consistent", "change", "unit"} for c in stats["initial_conditions"])


@pytest.mark.parametrize(
    ("scene", "extra", "field"),
    [
        ("cartesian-pendulum", {"method": "rk4"}, "method"),  # an integrator is not a DAE algorithm
        ("cartesian-pendulum", {"integrator": "splitting4"}, "integrator"),
        ("cartesian-pendulum", {"baumgarte_alpha_1_s": -1.0}, "baumgarte_alpha_1_s"),
        ("spherical-pendulum", {"baumgarte_beta_1_s": 5.0}, "baumgarte_beta_1_s"),  # a scene without the control
        ("spherical-pendulum", {"integrator": "rk4"}, "integrator"),
    ],
)
def test_bad_or_foreign_controls_get_a_422_naming_the_field(client, scene, extra, field):
    answer = client.post(f"/api/scenes/{scene}/simulate", json={"t_end": 1.0, **extra})
    assert answer.status_code == 422, answer.text
    assert answer.json()["detail"][0]["loc"][-1] == field


def test_start_at_the_pivot_is_refused(client):
    answer = client.post(URL, json={"params": {**UNIT, "x0_m": 0.0, "y0_m": 0.0}, "t_end": 1.0})
    assert answer.status_code == 422
    assert "pivot" in answer.text


def test_blow_up_stops_with_a_message_and_finite_numbers(client):
    body = {"params": {**UNIT, "g_m_s2": 9.81}, "t_end": 5.0, "method": "baumgarte", "steps_per_frame": 1,
            "baumgarte_alpha_1_s": 200.0, "baumgarte_beta_1_s": 200.0}  # fmt: skip
    data = client.post(URL, json=body).json()
    assert data["stats"]["status"] == "non_finite" and "blew up" in data["stats"]["message"]
    assert all(v is not None for v in data["series"]["x_m"])
