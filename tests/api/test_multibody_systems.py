"""/api/systems for systems built of parts (the Whipple bicycle), against ``dynlab serve`` as README starts it."""

from __future__ import annotations

import numpy as np
import pytest

from tests.physics.mechanics.multibody.test_whipple_bicycle import TABLE_EIGENVALUES, _published_eigenvalues


def test_the_catalogue_lists_the_bicycle_with_its_speed_and_its_reference_motion(client):
    by_id = {s["id"]: s for s in client.get("/api/systems").json()}
    bicycle = by_id["whipple-bicycle"]
    names = {p["name"] for p in bicycle["parameters"]}
    assert {"speed_m_s", "wheelbase_m", "trail_m", "steer_axis_tilt_rad", "rear_frame_mass_kg"} <= names
    assert bicycle["chapter"] == 9 and bicycle["formulations"] == ["kane", "lagrange"]
    assert bicycle["dependent_coordinates"] == ["pitch"]
    assert set(bicycle["dependent_speeds"]) == {"x", "y", "yaw", "pitch", "front_spin"}
    assert bicycle["reference"]["states"] == ["lean", "steer", "lean_d", "steer_d"]
    # The older systems keep their shape: no reference, no dependent coordinates.
    assert by_id["double-pendulum"]["reference"] is None and by_id["double-pendulum"]["dependent_coordinates"] == []


@pytest.mark.parametrize("speed_m_s", sorted(TABLE_EIGENVALUES))
def test_eigenvalues_answer_the_contract_and_the_published_table(client, speed_m_s):
    answer = client.post("/api/systems/whipple-bicycle/eigenvalues", json={"params": {"speed_m_s": speed_m_s}})
    assert answer.status_code == 200, answer.text
    body = answer.json()
    assert set(body) >= {"eigenvalues", "states", "about"} and body["states"] == ["lean", "steer", "lean_d", "steer_d"]
    got = np.array([e["re"] + 1j * e["im"] for e in body["eigenvalues"]])
    assert np.max(np.abs(got - np.array(TABLE_EIGENVALUES[speed_m_s], dtype=complex))) < 1e-8
    # Standing still it falls over; at 5 m/s it is inside the self-stable band (4.29–6.02 m/s).
    assert body["stable"] is (speed_m_s == 5.0) and body["unit"] == "1/s" and "upright" in body["about"]


@pytest.mark.parametrize(("speed_m_s", "stable"), [(3.0, False), (5.5, True), (8.0, False)])
def test_the_answer_says_stable_only_inside_the_band_and_matches_the_published_equations(client, speed_m_s, stable):
    body = client.post("/api/systems/whipple-bicycle/eigenvalues", json={"params": {"speed_m_s": speed_m_s}}).json()
    got = np.array([e["re"] + 1j * e["im"] for e in body["eigenvalues"]])
    assert body["stable"] is stable and np.max(np.abs(got - _published_eigenvalues(speed_m_s))) < 1e-8


@pytest.mark.parametrize(
    ("path", "body", "status", "field"),
    [
        ("/api/systems/no-such/eigenvalues", {"params": {}}, 404, None),
        ("/api/systems/whipple-bicycle/eigenvalues", {"params": {"speed_m_s": 1e9}}, 422, "speed_m_s"),
        ("/api/systems/whipple-bicycle/eigenvalues", {"params": {"speed_m_s": "fast"}}, 422, "speed_m_s"),
        ("/api/systems/whipple-bicycle/eigenvalues", {"params": {"wheels": 3}}, 422, "wheels"),
        ("/api/systems/whipple-bicycle/eigenvalues", {"params": {}, "extra": 1}, 422, None),
        ("/api/systems/double-pendulum/eigenvalues", {"params": {}}, 422, "system_id"),
        ("/api/systems/whipple-bicycle/derive", {"formulation": "hamilton"}, 422, "formulation"),
        ("/api/systems/whipple-bicycle/rhs", {"formulation": "hamilton", "state": [0.0] * 16}, 422, "formulation"),
        ("/api/systems/whipple-bicycle/rhs", {"formulation": "kane", "state": [0.0] * 3}, 422, "state"),
        # Lying flat: the front contact's geometry divides by zero in the generated code (a 422, never a 500).
        (
            "/api/systems/whipple-bicycle/rhs",
            {"formulation": "kane", "state": [0, 0, 0, 1.5707963267948966] + [0.0] * 12},
            422,
            "state",
        ),
    ],
)
def test_bad_requests_get_a_clear_4xx(client, path, body, status, field):
    answer = client.post(path, json=body)
    assert answer.status_code == status, answer.text
    if field:
        assert field in answer.text


def test_rhs_answers_at_a_state_on_the_constraints_and_refuses_one_off_them(client):
    """Upright rolling at 5 m/s: no lean or steer acceleration; the same with the pitch off by 1 mm is refused."""
    n = 8
    names = ["x", "y", "yaw", "lean", "rear_spin", "pitch", "steer", "front_spin"]
    q, u = [0.0] * n, [0.0] * n
    u[names.index("x")] = 5.0
    u[names.index("rear_spin")] = 5.0 / 0.3
    u[names.index("front_spin")] = 5.0 / 0.35
    for formulation in ("kane", "lagrange"):
        answer = client.post("/api/systems/whipple-bicycle/rhs", json={"formulation": formulation, "state": q + u})
        assert answer.status_code == 200, answer.text
        derivative = answer.json()["state_derivative"]
        assert derivative[:n] == u and max(abs(a) for a in derivative[n:]) < 1e-9
    q[names.index("pitch")] = 1e-3
    off = client.post("/api/systems/whipple-bicycle/rhs", json={"formulation": "kane", "state": q + u})
    assert off.status_code == 422 and "constraints" in off.text and "pitch" in off.text


def test_the_chain_is_listed_with_links_and_planar_and_its_eigenvalues_are_its_frequencies(client):
    from tests.physics.mechanics.multibody.test_n_link_pendulum import frequencies_by_hand

    chain = {s["id"]: s for s in client.get("/api/systems").json()}["n-link-pendulum"]
    assert {"links", "planar", "link_mass_kg", "link_length_m"} <= {p["name"] for p in chain["parameters"]}
    answer = client.post("/api/systems/n-link-pendulum/eigenvalues", json={"params": {"links": 4}})
    assert answer.status_code == 200, answer.text
    body = answer.json()
    assert body["states"] == ["theta1", "theta2", "theta3", "theta4", "theta1_d", "theta2_d", "theta3_d", "theta4_d"]
    omega = np.sort([e["im"] for e in body["eigenvalues"] if e["im"] > 0])
    np.testing.assert_allclose(omega, frequencies_by_hand(4, 1.0, 0.5, 9.81), rtol=1e-8)
    assert body["stable"] is False  # undamped: every real part is zero, none negative
    refused = client.post("/api/systems/n-link-pendulum/eigenvalues", json={"params": {"links": 50}})
    assert refused.status_code == 422 and "links" in refused.text
    too_long = client.post(
        "/api/systems/n-link-pendulum/eigenvalues", json={"params": {"links": 11, "planar": "spatial"}}
    )
    assert too_long.status_code == 422 and "at most 10 links" in too_long.text
    swept = client.post(
        "/api/systems/n-link-pendulum/eigenvalues",
        json={"params": {"links": 3}, "sweep": {"parameter": "links", "low": 2, "high": 5}},
    )
    assert swept.status_code == 422 and "sweep" in swept.text
