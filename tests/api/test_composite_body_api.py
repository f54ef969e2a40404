"""``POST /api/examples/inertia-of-composite-body/solve``: the outputs' contract and the 422 discipline for structured input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.bodies import inertia
from app.physics.systems.ch05.composite_body import DEFAULT_BODIES

URL = "/api/examples/inertia-of-composite-body/solve"


def _solve(client, **inputs):
    return client.post(URL, json={"inputs": inputs})


def test_schema_describes_the_body_records(client):
    example = next(e for e in client.get("/api/examples").json() if e["id"] == "inertia-of-composite-body")
    bodies = next(p for p in example["inputs"] if p["name"] == "bodies")
    assert bodies["kind"] == "list" and bodies["default"] == DEFAULT_BODIES
    shapes = {s["shape"]: s for s in bodies["item_schema"]["shapes"]}
    assert set(shapes) == {"sphere", "spherical-shell", "cylinder", "tube", "box", "rod", "plate", "disk", "cone"}
    assert shapes["tube"]["dimensions"] == ["radius_m", "inner_radius_m", "length_m"]
    assert shapes["cone"]["symmetry_axis"] == "z" and "centre of mass" in shapes["cone"]["description"]
    assert "3-2-1" in bodies["item_schema"]["sequences"] and len(bodies["item_schema"]["sequences"]) == 12


def test_a_cube_built_from_eight_cubes_has_the_big_cubes_inertia(client):
    """Eight 1 kg cubes of side 0.1 m at (±0.05, ±0.05, ±0.05): one 8 kg cube of side 0.2 m, triple-degenerate, about a corner too."""
    bodies = [
        {"shape": "box", "mass_kg": 1.0, "length_m": 0.1, "width_m": 0.1, "height_m": 0.1, "position_m": [sx * 0.05, sy * 0.05, sz * 0.05]}
        for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)
    ]
    response = _solve(client, bodies=bodies, about_point_m=[0.1, 0.1, 0.1])
    assert response.status_code == 200, response.text
    out = response.json()["outputs"]
    big = 8.0 * 0.2**2 / 6.0
    assert out["mass_kg"] == pytest.approx(8.0, rel=1e-15)
    assert np.allclose(out["centre_of_mass_m"], 0.0, atol=1e-16)
    assert np.allclose(out["inertia_cm_kg_m2"], big * np.eye(3), rtol=0, atol=1e-15)
    assert out["principal_moments_kg_m2"] == pytest.approx([big] * 3, rel=1e-14)
    assert out["principal_axes"] == np.eye(3).tolist()
    assert out["principal_degeneracy"] == "spherical"
    corner = inertia.parallel_axis(big * np.eye(3), 8.0, np.array([-0.1, -0.1, -0.1]))
    assert np.allclose(out["inertia_point_kg_m2"], corner, rtol=0, atol=1e-15)


def test_a_turned_shaft_gives_products_of_inertia_with_the_stated_sign(client):
    """A 3 kg, 1 m thin cylinder turned by 3-2-1 (45°, 90°, 0°) so its own z lies along (1, 1, 0)/√2.

    With a = ½ m r² about its axis e and t = m(3r² + L²)/12 across it, I = t 1 + (a − t) e eᵀ:
    the xy entry is (a − t)/2 < 0, i.e. I_xy = ∫ x y dm = (t − a)/2 > 0 as a body along x = y must have.
    """
    m, r, L = 3.0, 0.01, 1.0
    shaft = {"shape": "cylinder", "mass_kg": m, "radius_m": r, "length_m": L, "sequence": "3-2-1", "angles_deg": [45.0, 90.0, 0.0]}
    out = _solve(client, bodies=[shaft]).json()["outputs"]
    a, t = 0.5 * m * r**2, m * (3 * r**2 + L**2) / 12.0
    tensor = np.array(out["inertia_cm_kg_m2"])
    assert tensor[0, 1] == pytest.approx((a - t) / 2.0, rel=1e-12)
    assert tensor[2, 2] == pytest.approx(t, rel=1e-12)
    axes = np.array(out["principal_axes"])
    assert abs(abs(axes[0] @ np.array([1.0, 1.0, 0.0]) / math.sqrt(2)) - 1.0) < 1e-12  # least inertia along the shaft
    assert np.linalg.det(axes) == pytest.approx(1.0, abs=1e-12)


def test_a_lone_slender_rod_is_refused_with_the_reason(client):
    response = _solve(client, bodies=[{"shape": "rod", "mass_kg": 3.0, "length_m": 1.0}])
    assert response.status_code == 422
    assert response.json()["detail"][0]["loc"] == ["body", "inputs", "bodies"]
    assert "thin cylinder" in response.json()["detail"][0]["msg"]


def _default_with(index: int, **changes) -> list[dict]:
    bodies = [dict(b) for b in DEFAULT_BODIES]
    bodies[index].update(changes)
    return bodies


@pytest.mark.parametrize(
    "inputs, loc",
    [
        ({"bodies": _default_with(0, mass_kg=-2.0)}, ["bodies", 0, "mass_kg"]),
        ({"bodies": _default_with(1, radius_m=0.3)}, ["bodies", 1]),  # a hole bigger than its plate
        ({"bodies": [{"shape": "tube", "mass_kg": 1.0, "radius_m": 0.1, "inner_radius_m": 0.12, "length_m": 0.2}]}, ["bodies", 0, "inner_radius_m"]),
        ({"bodies": _default_with(2, position_m=[0.0, "inf", 0.0])}, ["bodies", 2, "position_m", 1]),
        ({"bodies": _default_with(2, shape="torus")}, ["bodies", 2, "shape"]),
        ({"bodies": _default_with(0, sequence="3-2-2")}, ["bodies", 0, "sequence"]),
        ({"bodies": "plate"}, ["bodies"]),
        ({"about_point_m": [0.0, 0.0]}, ["about_point_m"]),
        ({"about_point": [0.0, 0.0, 0.0]}, ["about_point"]),
    ],
)
def test_bad_bodies_get_a_422_naming_the_field_path(client, inputs, loc):
    response = _solve(client, **inputs)
    assert response.status_code == 422, response.text
    detail = response.json()["detail"][0]
    assert detail["loc"] == ["body", "inputs", *loc]
    assert detail["msg"]


def test_non_finite_json_numbers_are_refused_before_the_physics(client):
    """JSON has no NaN; a client that sends one anyway gets a 422, not a crash."""
    body = '{"inputs": {"about_point_m": [NaN, 0, 0]}}'
    response = client.post(URL, content=body, headers={"Content-Type": "application/json"})
    assert response.status_code == 422


def test_a_bad_body_sent_to_the_explorer_scene_names_its_path_under_params_and_changes_nothing(client):
    sid = "c0ffee" * 5 + "00"
    url = f"/api/scenes/inertia-explorer/sessions/{sid}"
    first = client.put(url, json={"params": {"about_point_m": [0.1, 0.0, 0.0]}})
    assert first.status_code == 200, first.text
    bad = client.put(url, json={"params": {"bodies": [{"shape": "sphere", "mass_kg": -1.0, "radius_m": 0.1}]}})
    assert bad.status_code == 422
    assert bad.json()["detail"][0]["loc"] == ["body", "params", "bodies", 0, "mass_kg"]
    again = client.put(url, json={"params": {}})
    assert again.json()["params"]["bodies"] == DEFAULT_BODIES and again.json()["params"]["about_point_m"] == [0.1, 0.0, 0.0]
