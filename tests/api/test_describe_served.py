"""A system described by its parts over HTTP (``POST /api/systems/custom/describe``) and the derive route for systems
built of parts, against ``dynlab serve`` as README starts it: derived in the bounded child, loaded by the front."""

from __future__ import annotations

import numpy as np
import pytest

from tests.physics.mechanics.multibody.test_data import BICYCLE_TOML, DOUBLE_PENDULUM
from tests.physics.mechanics.multibody.test_whipple_bicycle import TABLE_EIGENVALUES


def _values(listed) -> np.ndarray:
    return np.sort_complex(np.array([e["re"] + 1j * e["im"] for e in listed]))


def test_a_described_double_pendulum_linearises_as_the_shipped_two_link_chain_to_1e_10(client):
    answer = client.post("/api/systems/custom/describe", json={"description": DOUBLE_PENDULUM, "linearise": True})
    assert answer.status_code == 200, answer.text
    body = answer.json()
    assert body["degrees_of_freedom"] == {"configuration": 2, "speeds": 2}
    assert body["state_is"].startswith("rest") and body["energies"]["total_J"] == pytest.approx(-9.81 * (0.25 + 0.75))
    assert body["operations"]["after_cse"] < body["operations"]["before_cse"]
    shipped = client.post(
        "/api/systems/n-link-pendulum/eigenvalues",
        json={"params": {"links": 2, "link_mass_kg": 1.0, "link_length_m": 0.5, "gravity_m_s2": 9.81}},
    ).json()
    assert np.max(np.abs(_values(body["linear"]["eigenvalues"]) - _values(shipped["eigenvalues"]))) < 1e-10
    # Asked again: nothing derived, the same answer.
    again = client.post("/api/systems/custom/describe", json={"description": DOUBLE_PENDULUM, "linearise": True})
    assert again.json()["cached"] is True and again.json()["linear"] == body["linear"]


def test_the_bicycle_described_in_toml_has_the_published_eigenvalues_at_5_m_s(client):
    answer = client.post(
        "/api/systems/custom/describe",
        json={"toml": BICYCLE_TOML.read_text(), "params": {"speed_m_s": 5.0}, "linearise": True},
    )
    assert answer.status_code == 200, answer.text
    got = _values(answer.json()["linear"]["eigenvalues"])
    assert np.max(np.abs(got - np.sort_complex(np.array(TABLE_EIGENVALUES[5.0], dtype=complex)))) < 1e-8


@pytest.mark.parametrize(
    ("body", "loc"),
    [
        ({"description": {**DOUBLE_PENDULUM, "gravity": "G"}}, ["body", "description", "gravity"]),
        ({"description": DOUBLE_PENDULUM, "toml": "id = 'x'"}, ["body", "description"]),
        ({"toml": "id = "}, ["body", "toml"]),
        ({"description": DOUBLE_PENDULUM, "params": {"m": -1}}, ["body", "params", "m"]),
        ({"description": DOUBLE_PENDULUM, "state": [0.1, 0.2, 0.0, 0.0], "linearise": True}, ["body", "linearise"]),
        ({"description": DOUBLE_PENDULUM, "state": [0.0, 0.0]}, ["body", "state"]),
    ],
)
def test_refusals_are_422_naming_the_field(client, body, loc):
    answer = client.post("/api/systems/custom/describe", json=body)
    assert answer.status_code == 422, answer.text
    assert answer.json()["detail"][0]["loc"][: len(loc)] == loc, answer.json()


@pytest.mark.parametrize(("system_id", "formulation"), [("whipple-bicycle", "kane"), ("rattleback", "lagrange")])
def test_the_derive_route_shows_a_parts_systems_kinematics_and_equations(client, system_id, formulation):
    answer = client.post(f"/api/systems/{system_id}/derive", json={"formulation": formulation})
    assert answer.status_code == 200, answer.text
    body = answer.json()
    titles = " ".join(step["title"] for step in body["steps"])
    assert "Angular velocity" in titles and "Velocity constraint" in titles
    assert body["operations"]["after_cse"] < body["operations"]["before_cse"]
    assert len(body["equations_latex"]) == body["operations"]["speeds"] + body["operations"]["constraints"]
