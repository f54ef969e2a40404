"""The rattleback over HTTP, against ``dynlab serve`` as README starts it: the catalogue, its eigenvalues about steady
spin, its state derivative by both formulations, and its scene's simulate answer through the reversal."""

from __future__ import annotations

import numpy as np
import pytest


def test_the_catalogue_lists_the_rattleback_with_its_dependent_coordinate_and_speeds(client):
    rattleback = {s["id"]: s for s in client.get("/api/systems").json()}["rattleback"]
    names = {p["name"] for p in rattleback["parameters"]}
    assert {"semi_axis_a_m", "inertia_xy_kg_m2", "spin_rad_s"} <= names
    assert rattleback["chapter"] == 8 and rattleback["formulations"] == ["kane", "lagrange"]
    assert rattleback["dependent_coordinates"] == ["z"] and set(rattleback["dependent_speeds"]) == {"x", "y", "z"}
    assert rattleback["reference"]["states"] == ["roll", "pitch", "yaw_d", "roll_d", "pitch_d"]


@pytest.mark.parametrize(
    ("spin_rad_s", "growth_1_s", "frequency_rad_s"), [(5.0, 2.1207, 109.392), (-5.0, 0.2025, 34.144)]
)
def test_spun_either_way_a_rocking_mode_grows_fast_one_way_slowly_the_other(
    client, spin_rad_s, growth_1_s, frequency_rad_s
):
    """Against the independent Newton–Euler model's linearisation (tests/physics/.../test_rattleback.py), 1e-4."""
    answer = client.post("/api/systems/rattleback/eigenvalues", json={"params": {"spin_rad_s": spin_rad_s}})
    assert answer.status_code == 200, answer.text
    body = answer.json()
    values = np.array([e["re"] + 1j * e["im"] for e in body["eigenvalues"]])
    worst = values[np.argmax(values.real)]
    assert worst.real == pytest.approx(growth_1_s, abs=1e-4) and abs(worst.imag) == pytest.approx(
        frequency_rad_s, abs=1e-3
    )
    assert body["stable"] is False and "spinning" in body["about"]


def test_kane_and_lagrange_answer_the_same_state_derivative_over_http(client):
    # Upright at rest with G at c − h = 0.01 m: every constraint met; gravity alone, so nothing accelerates.
    state = [0.0, 0.0, 0.01, 0.0, 0.0, 0.0] + [0.0] * 6
    answers = [
        client.post("/api/systems/rattleback/rhs", json={"formulation": f, "state": state}).json()["state_derivative"]
        for f in ("kane", "lagrange")
    ]
    assert np.max(np.abs(np.array(answers[0]) - np.array(answers[1]))) < 1e-12
    assert np.max(np.abs(answers[0])) < 1e-12
    # Off the floor: refused, saying by how much.
    lifted = client.post("/api/systems/rattleback/rhs", json={"formulation": "kane", "state": [0, 0, 0.5] + [0.0] * 9})
    assert lifted.status_code == 422 and "constraints" in lifted.text


def test_the_scene_simulates_the_reversal_with_its_energy_kept(client):
    answer = client.post(
        "/api/scenes/rattleback/simulate",
        json={"params": {"spin_0_rad_s": 5.0}, "t_end": 4.0, "frame_rate": 20},
    )
    assert answer.status_code == 200, answer.text
    body = answer.json()
    spin, energy = np.array(body["series"]["spin_rad_s"]), np.array(body["series"]["energy_J"])
    assert spin[0] == pytest.approx(5.0, abs=0.1) and spin[-1] < -1.0  # reversed by 4 s (through zero at 2.35 s)
    assert np.max(np.abs(energy - energy[0])) < 1e-6 * abs(energy[0])
    assert min(body["series"]["normal_force_N"]) > 0.0


def test_a_body_no_rigid_body_could_be_is_refused_naming_the_product(client):
    answer = client.post("/api/scenes/rattleback/simulate", json={"params": {"inertia_xy_kg_m2": 0.5}, "t_end": 1.0})
    assert answer.status_code == 422, answer.text
    assert "inertia_xy_kg_m2" in answer.text
