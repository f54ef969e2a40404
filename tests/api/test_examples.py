"""GET /api/examples and POST /api/examples/{id}/solve, including every 422 path."""

from __future__ import annotations

import numpy as np
import pytest

from app.physics.systems import worked_examples

EXAMPLES = worked_examples()


def solve(client, example_id, body=None, *, raw=None):
    if raw is not None:
        return client.post(
            f"/api/examples/{example_id}/solve", content=raw, headers={"content-type": "application/json"}
        )
    return client.post(f"/api/examples/{example_id}/solve", json=body)


def direct(example_id, inputs=None):
    """The same solution from app.physics, through JSON-ready Python values."""
    example = EXAMPLES[example_id]
    return example.solve(example.inputs.validate(inputs or {})).as_dict()


def test_list_examples(client):
    response = client.get("/api/examples")
    assert response.status_code == 200
    listed = response.json()
    # The first six (ids outside checks rely on) and every one found since, in chapter order.
    chapters = {"1.1": 1, "1.2": 1, "particle-work-energy": 1, "inertia-of-composite-body": 5, "planar-collision": 6, "equinox-precession": 10}
    assert [e["id"] for e in listed] == list(EXAMPLES) and set(chapters) <= set(EXAMPLES)
    assert [e["chapter"] for e in listed] == sorted(e["chapter"] for e in listed)
    for e in listed:
        assert e["title"] and e["chapter"] == chapters.get(e["id"], EXAMPLES[e["id"]].chapter)
        for p in e["inputs"]:
            assert {"name", "unit", "default", "description", "kind"} <= set(p)
            assert {"min", "max"} <= set(p) or p["kind"] in ("choice", "text", "list")


@pytest.mark.parametrize("body", [{}, {"inputs": {}}])
def test_solve_1_1_with_defaults(client, body):
    response = solve(client, "1.1", body)
    assert response.status_code == 200
    data = response.json()
    out = data["outputs"]
    for name in ("F_N", "M_A_Nm"):
        assert isinstance(out[name], list) and len(out[name]) == 3
    for name in ("F_BC_N", "M_z_Nm", "M_AB_Nm"):
        assert isinstance(out[name], float)
    # Python's json writes floats with repr, so the HTTP numbers equal the direct ones exactly.
    assert out == direct("1.1")["outputs"]
    assert data["inputs"] == EXAMPLES["1.1"].inputs.defaults()
    assert data["steps"]
    for step in data["steps"]:
        assert step["title"] and step["latex"] and isinstance(step["values"], dict)


def test_solve_1_1_with_changed_inputs(client):
    inputs = {"theta_deg": 60, "tension_N": 1234.5, "D_x_m": -2.0}
    response = solve(client, "1.1", {"inputs": inputs})
    assert response.status_code == 200
    data = response.json()
    assert data["outputs"] == direct("1.1", inputs)["outputs"]
    assert data["inputs"]["theta_deg"] == 60.0 and data["inputs"]["gamma_deg"] == 40.0
    assert data["outputs"] != direct("1.1")["outputs"]


@pytest.mark.parametrize("body", [{}, {"inputs": {}}, {"inputs": {"t_s": 5.0, "dt_s": 1e-4}}])
def test_solve_1_2(client, body):
    response = solve(client, "1.2", body)
    assert response.status_code == 200
    out = response.json()["outputs"]
    for name in ("position_m", "velocity_fd_m_s", "velocity_exact_m_s"):
        assert isinstance(out[name], list) and len(out[name]) == 3
    assert out == direct("1.2", body.get("inputs"))["outputs"]
    # fd_error is |fd - exact| of the two vectors returned (1e-12 relative: one norm of a
    # difference recomputed from the same doubles).
    gap = np.linalg.norm(np.subtract(out["velocity_fd_m_s"], out["velocity_exact_m_s"]))
    assert out["fd_error_m_s"] == pytest.approx(gap, rel=1e-12)


def test_solve_particle_work_energy(client):
    response = solve(client, "particle-work-energy", {})
    assert response.status_code == 200
    assert response.json()["outputs"] == direct("particle-work-energy")["outputs"]


def test_unknown_example_is_404(client):
    response = solve(client, "9.9", {})
    assert response.status_code == 404
    assert "9.9" in response.json()["detail"]


def assert_422(response, field, *, msg_contains=()):
    assert response.status_code == 422, response.text
    detail = response.json()["detail"][0]
    assert field in detail["loc"], detail
    for text in msg_contains:
        assert text in detail["msg"], detail


@pytest.mark.parametrize(
    ("example_id", "raw", "field", "msg"),
    [
        ("1.1", '{"inputs": {"theta_deg": NaN}}', "theta_deg", ["finite"]),
        ("1.1", '{"inputs": {"theta_deg": Infinity}}', "theta_deg", ["finite"]),
        ("1.1", '{"inputs": {"tension_N": -Infinity}}', "tension_N", ["finite"]),
        ("1.1", '{"inputs": {"theta_deg": 1e999}}', "theta_deg", ["finite"]),
        ("1.1", '{"inputs": {"theta_deg": 400}}', "theta_deg", ["between -180 and 180 deg"]),
        ("1.1", '{"inputs": {"tension_N": -1}}', "tension_N", ["between 0 and 100000 N"]),
        ("1.1", '{"inputs": {"theta_deg": "25"}}', "theta_deg", ["between -180 and 180 deg"]),
        ("1.1", '{"inputs": {"theta_deg": true}}', "theta_deg", ["between -180 and 180 deg"]),
        ("1.1", '{"inputs": {"theta_deg": null}}', "theta_deg", []),
        ("1.1", '{"inputs": {"thetta_deg": 20}}', "thetta_deg", ["theta_deg"]),
        ("1.2", '{"inputs": {"dt_s": 0}}', "dt_s", ["between 1e-12 and 1 s"]),
        ("1.2", '{"inputs": {"dt_s": 2}}', "dt_s", ["between 1e-12 and 1 s"]),
        ("1.2", '{"inputs": {"t_s": 0.5}}', "t_s", ["between 1 and 60 s"]),
        ("1.1", '{"inputs": {}, "foo": 1}', "foo", []),
    ],
)
def test_bad_input_is_422_naming_the_field(client, example_id, raw, field, msg):
    assert_422(solve(client, example_id, raw=raw), field, msg_contains=msg)


def test_dt_longer_than_t_is_422_naming_dt(client):
    # With t_s >= 1 s and dt_s <= 1 s by their ranges, dt_s > t_s is refused by dt_s's own range
    # check before the combined check runs; either way the field named is dt_s.
    assert_422(solve(client, "1.2", {"inputs": {"t_s": 1.0, "dt_s": 1.5}}), "dt_s")
    # dt_s = t_s is allowed (t - dt = 0 is still in the elevation formula's domain).
    assert solve(client, "1.2", {"inputs": {"t_s": 1.0, "dt_s": 1.0}}).status_code == 200


def test_cable_with_no_length_is_422_naming_d_x(client):
    body = {"inputs": {"theta_deg": 0, "gamma_deg": 0, "AB_m": 2.0, "BC_m": 1.5, "D_x_m": 3.5}}
    assert_422(solve(client, "1.1", body), "D_x_m")


@pytest.mark.parametrize("raw", ['{"inputs": [1, 2]}', '{"inputs": 5}', "[]", "not json"])
def test_malformed_bodies_are_422(client, raw):
    assert solve(client, "1.1", raw=raw).status_code == 422


@pytest.mark.parametrize("raw", ['{"inputs": {}, "foo": NaN}', '{"inputs": NaN}'])
def test_nan_outside_inputs_is_422_not_500(client, raw):
    # The validation error echoes the NaN input, which strict JSON cannot carry; the reply must
    # still be a 422 rather than a server error.
    assert solve(client, "1.1", raw=raw).status_code == 422


@pytest.mark.parametrize(("inputs", "zero"), [({"gamma_deg": 45.0}, ("M_A_Nm", 0)), ({"theta_deg": 180.0, "gamma_deg": 0.0}, ("M_z_Nm", None))])
def test_solve_1_1_shows_round_off_as_zero(client, inputs, zero):
    """θ = 25°, γ = 45°: M_A's x component is 4.5e-13 N·m of 1.6e4 N·m, round-off of the cross product; θ = 180°, γ = 0:
    M_z is −1.1e-12 N·m of a 17 500 N·m scale (|r_C| |F|). Both answer exactly 0, in the outputs and in the steps."""
    response = solve(client, "1.1", {"inputs": inputs})
    assert response.status_code == 200
    data = response.json()
    name, index = zero
    shown = data["outputs"][name] if index is None else data["outputs"][name][index]
    assert shown == 0.0
    step_values = {key: value for step in data["steps"] for key, value in step["values"].items()}
    symbol = name.removesuffix("_Nm")
    assert (step_values[symbol] if index is None else step_values[symbol][index]) == 0.0
    assert all(abs(v) > 1e3 for v in data["outputs"]["M_A_Nm"] if v != 0.0)  # the other components are the moment


def test_inputs_impossible_together_found_while_solving_are_a_422_not_a_500(inprocess_client, monkeypatch):
    """WorkedExample.solve may raise ValueError for inputs in range but impossible together (its contract): the route
    answers 422 naming the inputs, never 500 (a helper session writing examples found the route let it through)."""
    import dataclasses

    def impossible(inputs):
        raise ValueError("these links cannot be assembled: the coupler is shorter than the gap")

    examples = inprocess_client.app.state.catalogue.examples
    monkeypatch.setitem(examples, "planar-collision", dataclasses.replace(examples["planar-collision"], solve=impossible))
    answer = solve(inprocess_client, "planar-collision", {"inputs": {}})
    assert answer.status_code == 422
    detail = answer.json()["detail"][0]
    assert detail["loc"] == ["body", "inputs"] and "cannot be assembled" in detail["msg"]
