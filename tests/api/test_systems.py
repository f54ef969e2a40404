"""/api/systems: the catalogue, derivations, right-hand sides and the typed Lagrangian, as a client sees them."""

from __future__ import annotations

import math
import time

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from app.physics.core import bounded
from app.physics.core.bounded import BoundedRunner
from app.physics.mechanics import typed

FORMULATIONS = ["newton-euler", "lagrange", "hamilton", "gibbs-appell", "kane"]
DOUBLE_PENDULUM_T = "(m1+m2)*l1^2*q1d^2/2 + m2*l2^2*q2d^2/2 + m2*l1*l2*q1d*q2d*cos(q1-q2)"
DOUBLE_PENDULUM_V = "-(m1+m2)*g*l1*cos(q1) - m2*g*l2*cos(q2)"


def test_the_catalogue_lists_every_system_with_its_contract_fields(client):
    body = client.get("/api/systems").json()
    by_id = {s["id"]: s for s in body}
    double = by_id["double-pendulum"]
    assert set(double) >= {"id", "title", "chapter", "coordinates", "speeds", "formulations", "parameters"}
    assert [c["name"] for c in double["coordinates"]] == ["theta1", "theta2"]
    assert {p["name"] for p in double["parameters"]} >= {"m1_kg", "m2_kg", "l1_m", "l2_m", "g_m_s2"}
    assert set(FORMULATIONS) <= set(double["formulations"]) and "routh" in double["unavailable"]
    hoop = by_id["bead-on-rotating-hoop"]
    assert [c["name"] for c in hoop["coordinates"]] == ["theta"]
    assert {p["name"] for p in hoop["parameters"]} >= {"hoop_radius_m", "hoop_speed_rad_s", "g_m_s2"}
    assert by_id["rolling-disk"]["formulations"] == ["newton-euler", "gibbs-appell", "kane"]


@pytest.mark.parametrize("formulation", FORMULATIONS)
def test_derive_answers_the_contract_and_a_second_request_comes_from_the_cache(client, formulation):
    request = {"formulation": formulation, "params": {"m1_kg": 2.0}}
    first = client.post("/api/systems/double-pendulum/derive", json=request)
    assert first.status_code == 200, first.text
    body = first.json()
    assert set(body) >= {"coordinates", "speeds", "equations_latex", "mass_matrix_latex", "forcing_latex", "steps", "derive_s", "compile_s"}
    assert body["coordinates"] == ["theta1", "theta2"] and body["equations_latex"] and body["steps"]
    assert all(set(step) == {"title", "latex"} for step in body["steps"])
    again = client.post("/api/systems/double-pendulum/derive", json=request).json()
    assert again["cached"] is True and again["derive_s"] == 0.0
    assert again["equations_latex"] == body["equations_latex"]


def test_every_formulation_answers_the_same_state_derivative(client):
    state = [0.4, -1.1, 0.7, 2.0]
    params = {"m1_kg": 1.5, "l2_m": 0.7}
    answers = [
        client.post("/api/systems/double-pendulum/rhs", json={"formulation": f, "params": params, "state": state, "t": 0.0}).json()["state_derivative"]
        for f in FORMULATIONS
    ]
    for answer in answers[1:]:
        assert answer == pytest.approx(answers[0], rel=1e-12)
    assert answers[0][:2] == pytest.approx(state[2:], rel=1e-15)


def test_the_hoop_is_rheonomic_and_its_rhs_depends_on_nothing_but_theta(client):
    """θ̈ = sin θ (Ω² cos θ − g/R): at cos θ = g/(RΩ²) the bead is in relative equilibrium."""
    R, Omega, g = 0.5, 6.0, 9.81
    theta = math.acos(g / (R * Omega**2))
    for t in (0.0, 1.3):
        answer = client.post("/api/systems/bead-on-rotating-hoop/rhs", json={"formulation": "hamilton", "state": [theta, 0.0], "t": t}).json()
        assert answer["state_derivative"] == pytest.approx([0.0, 0.0], abs=1e-12)


@pytest.mark.parametrize(
    ("path", "body", "status", "words"),
    [
        ("/api/systems/no-such/derive", {}, 404, "no system"),
        ("/api/systems/rolling-disk/derive", {"formulation": "lagrange"}, 422, "multipliers"),
        ("/api/systems/double-pendulum/derive", {"formulation": "routh"}, 422, "ignorable"),
        ("/api/systems/double-pendulum/derive", {"params": {"m1_kg": -1}}, 422, "m1_kg"),
        ("/api/systems/double-pendulum/derive", {"formulation": "euler"}, 422, "formulation"),
        ("/api/systems/double-pendulum/rhs", {"state": [0.1, 0.2]}, 422, "give 4 numbers"),
        ("/api/systems/spherical-pendulum/rhs", {"state": [0.0, 0.0, 0.1, 0.1]}, 422, "singular"),
    ],
)
def test_bad_requests_are_refused_with_the_reason(client, path, body, status, words):
    answer = client.post(path, json=body)
    assert answer.status_code == status, answer.text
    assert words in answer.text


def test_a_typed_double_pendulum_derives_the_catalogue_s_equations(client):
    """The same physics typed as energies gives the catalogue's q̈ at the check state, to rounding."""
    params = {"m1": 1.2, "m2": 0.8, "l1": 1.1, "l2": 0.6, "g": 9.81}
    answer = client.post(
        "/api/systems/custom/derive",
        json={"coordinates": ["q1", "q2"], "kinetic_energy": DOUBLE_PENDULUM_T, "potential_energy": DOUBLE_PENDULUM_V, "parameters": params},
    )
    assert answer.status_code == 200, answer.text
    body = answer.json()
    check = body["rhs_check"]
    catalogue = client.post(
        "/api/systems/double-pendulum/rhs",
        json={"formulation": "lagrange", "state": check["state"], "params": {"m1_kg": 1.2, "m2_kg": 0.8, "l1_m": 1.1, "l2_m": 0.6, "g_m_s2": 9.81}},
    ).json()["state_derivative"]
    assert check["state_derivative"] == pytest.approx(catalogue, rel=1e-12)
    assert len(body["equations_latex"]) == 2 and body["steps"]


@pytest.mark.parametrize(
    ("request_body", "field", "words"),
    [
        ({"kinetic_energy": "__import__('os').system('ls')"}, "kinetic_energy", "underscores"),
        ({"kinetic_energy": "m*theta^2"}, "kinetic_energy", "q1"),
        ({"kinetic_energy": "q1d^2", "potential_energy": "q1d*q1"}, "potential_energy", "rates"),
        ({"kinetic_energy": "(q1d+q2d)^2/2", "coordinates": ["q1", "q2"]}, "kinetic_energy", "singular"),
        ({"kinetic_energy": "m*q1d^2/2", "parameters": {"lambda": 1.0, "m": 1.0}}, "parameters", "lambda"),
        ({"kinetic_energy": "m*q1d^2/2", "parameters": {"m": 1e300}}, "parameters", "magnitude"),
        ({"kinetic_energy": "q1d^2*(" + "+".join(f"q1^{k}" for k in range(1, 67)) + ")"}, "kinetic_energy", "operations"),
        ({"coordinates": ["q2"]}, "coordinates", "in order"),
    ],
)
def test_a_typed_lagrangian_is_refused_clearly(client, request_body, field, words):
    body = {"coordinates": ["q1"], "kinetic_energy": "m*q1d^2/2", "potential_energy": "0", "parameters": {"m": 1.0}} | request_body
    answer = client.post("/api/systems/custom/derive", json=body)
    assert answer.status_code == 422, answer.text
    detail = answer.json()["detail"]
    assert any(field in [str(x) for x in d["loc"]] or field in d["msg"] for d in detail), detail
    assert words in answer.text


def test_a_derivation_over_its_time_bound_is_refused_and_the_server_answers_after(inprocess_client, monkeypatch):
    client = inprocess_client  # looks inside the scene instance: the app in this process
    monkeypatch.setattr(typed, "runner", BoundedRunner(max_jobs=1, timeout_s=0.05, memory_mb=1024))
    monkeypatch.setattr(bounded, "_server_busy", lambda: False)  # the 422 path: no pauses, however busy the suite,
    monkeypatch.setattr(bounded, "STARVED_SHARE", math.inf)  # and never "busy" for a child the machine starved
    start = time.perf_counter()
    answer = client.post(
        "/api/systems/custom/derive",
        json={"coordinates": ["q1", "q2", "q3"], "kinetic_energy": DOUBLE_PENDULUM_T + "+q3d^2*cos(q3)^2", "potential_energy": DOUBLE_PENDULUM_V,
              "parameters": {"m1": 1.0, "m2": 1.0, "l1": 1.0, "l2": 1.0, "g": 9.81}},
    )  # fmt: skip
    assert answer.status_code == 422 and "longer than its limit" in answer.text, answer.text
    assert time.perf_counter() - start < 5.0
    assert client.get("/api/health").status_code == 200


_ALPHABET = st.sampled_from(["q1", "q1d", "q2", "t", "m", "g", "+", "-", "*", "/", "^", "(", ")", "cos", "sin", "sqrt", "exp", "log", "2", "0.5", "1e9", " ", "_", "'", ".", "[", "x"])


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(kinetic=st.lists(_ALPHABET, max_size=25).map("".join), potential=st.one_of(st.text(max_size=40), st.lists(_ALPHABET, max_size=15).map("".join)))
def test_fuzzed_energies_get_an_answer_or_a_clear_refusal_within_the_bound(served, kinetic, potential):
    start = time.perf_counter()
    with served.new_client() as device:  # each example a student of its own: the derive rate limit is per device
        answer = device.post(
            "/api/systems/custom/derive",
            json={"coordinates": ["q1", "q2"], "kinetic_energy": kinetic, "potential_energy": potential, "parameters": {"m": 1.0, "g": 9.81}},
        )
    assert answer.status_code in (200, 422, 429), answer.text  # 429: out of time while a busy machine paused it
    if answer.status_code == 429:
        assert int(answer.headers["Retry-After"]) >= 1 and "busy" in answer.json()["detail"]
    assert time.perf_counter() - start < typed.DERIVE_TIMEOUT_S + 5.0
    if answer.status_code == 200:
        assert np.all(np.isfinite(answer.json()["rhs_check"]["state_derivative"]))
    else:
        assert answer.json()["detail"][0]["msg"]
