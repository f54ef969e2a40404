"""The angular-momentum scene through the API: the simulate contract, 422s naming the field, a live readout."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from app.physics.systems.ch05 import angular_momentum as am
from app.scenes import SCENES
from tests.api.conftest import live_viewer

_ids = itertools.count()
#: The contract: series names grouped by their unit.
CONTRACT_UNITS = {
    "rad": {"spin_angle", "angle_between_omega_and_H"},
    "kg·m²/s": {f"angular_momentum_{axis}_kg_m2_s" for axis in "xyz"},
    "N·m": {"bearing_moment_N_m"},
    "J": {"kinetic_energy_J"},
}


def simulate(client, params, t_end=3.0, frame_rate=30.0):
    return client.post("/api/scenes/angular-momentum/simulate", json={"params": params, "t_end": t_end, "frame_rate": frame_rate})


def test_scene_is_listed_in_chapter_5_with_its_parameters(client):
    scenes = {s["id"]: s for s in client.get("/api/scenes").json()}
    scene = scenes["angular-momentum"]
    assert scene["chapter"] == 5 and scene["animated"] and scene["readout"]
    names = {p["name"] for p in scene["parameters"]}
    assert {"body", "tilt_deg", "spin_rate_rad_s", "view", "centre_velocity_m_s"} <= names
    lessons = {lesson["id"] for chapter in client.get("/api/chapters").json() for lesson in chapter["lessons"]}
    assert {"5-1-linear-and-angular-momentum", "5-3-rate-of-change-of-angular-momentum"} <= lessons


def test_simulate_returns_the_contract_series_matching_the_physics(client):
    response = simulate(client, {})
    assert response.status_code == 200, response.text
    body = response.json()
    assert set(body["series"]) == set().union(*CONTRACT_UNITS.values())
    assert all(body["units"][name] == unit for unit, names in CONTRACT_UNITS.items() for name in names)
    assert len(body["t"]) == 91 and body["stats"]["method"] == "closed-form" and body["stats"]["status"] == "ok"
    state = am.ShaftSpin.from_params(am.PARAMETERS.validate({})).at(np.asarray(body["t"]))
    # JSON carries floats exactly (shortest repr round-trips), so the numbers are the physics' own.
    assert body["series"]["angular_momentum_y_kg_m2_s"] == state.angular_momentum_G[:, 1].tolist()
    assert body["series"]["bearing_moment_N_m"] == pytest.approx(state.bearing_moment_N_m.tolist(), rel=1e-15)
    assert body["series"]["angle_between_omega_and_H"][0] == pytest.approx(math.radians(10.605747207331412), rel=1e-12)
    assert body["stats"]["max_invariant_drift"] < 4e-15


def test_zero_spin_and_principal_shaft_are_finite_zeros_but_no_spin_has_no_angle(client):
    for params in ({"spin_rate_rad_s": 0.0}, {"tilt_deg": 0.0}):
        body = simulate(client, params).json()
        assert max(body["series"]["bearing_moment_N_m"]) == 0.0
        assert all(None not in values for name, values in body["series"].items() if name != "angle_between_omega_and_H")
    principal = simulate(client, {"tilt_deg": 0.0}).json()
    assert principal["stats"]["status"] == "ok" and max(principal["series"]["angle_between_omega_and_H"]) == 0.0
    still = simulate(client, {"spin_rate_rad_s": 0.0}).json()  # issue 24: was 0.0; ω = 0 and H = 0 have no angle
    assert set(still["series"]["angle_between_omega_and_H"]) == {None} and still["stats"]["status"] == "undefined"
    assert still["events"][0]["message"] == f"angle between ω and H_G: {am.NO_SPIN_ANGLE}"


@pytest.mark.parametrize(
    "params, field",
    [({"tilt_deg": 120.0}, "tilt_deg"), ({"body": "cube"}, "body"), ({"spin_rate_rad_s": "fast"}, "spin_rate_rad_s"),
     ({"centre_velocity_m_s": [0.0, 1e9, 0.0]}, "centre_velocity_m_s"), ({"view": "x-ray"}, "view"),
     ({"mass_kg": -2.0}, "mass_kg"), ({"spin_rate": 3.0}, "spin_rate")],
)  # fmt: skip
def test_bad_input_is_a_422_naming_the_field(client, params, field):
    response = simulate(client, params)
    assert response.status_code == 422, response.text
    detail = response.json()["detail"][0]
    assert detail["loc"][-1] == field
    # The message names the input as its control does (label and unit); an unknown name is echoed as it was sent.
    parameter = SCENES["angular-momentum"].parameters.by_name.get(field)
    assert detail["msg"].startswith(f"{parameter.display_name() if parameter else field}:"), detail


def test_live_readout_states_the_physics_and_the_principal_axis_case(client):
    sid = f"angular-momentum-{next(_ids):04d}"
    url = f"/api/scenes/angular-momentum/sessions/{sid}"
    assert client.put(url, json={"params": {}}).status_code == 200  # the page opens its scene, then its viewer connects
    with live_viewer(client, "angular-momentum", sid):
        readout = client.get(f"{url}/live").json()["readout"]
        values = {q["name"]: q for q in readout["quantities"]}
        assert values["angle_omega_H"]["value"] == pytest.approx(10.605747207331412, rel=1e-12)
        assert values["angle_omega_H"]["unit"] == "deg"
        assert values["bearing_force"]["value"] == pytest.approx(0.3695041722813606 / 0.8, rel=1e-12)
        assert all(q["unit"] for q in readout["quantities"])  # every number a student reads carries its unit
        assert "principal axis" not in readout["message"]
        # Tilt 0: the words say the shaft is principal, and the moment is zero.
        assert client.put(url, json={"params": {"tilt_deg": 0.0}}).status_code == 200
        readout = client.get(f"{url}/live").json()["readout"]
        values = {q["name"]: q["value"] for q in readout["quantities"]}
        assert "ω and H are parallel: the shaft is a principal axis" in readout["message"]
        assert values["bearing_moment"] == 0.0 and values["angle_omega_H"] == 0.0
        # No spin: the angle is undefined in words, not a number.
        assert client.put(url, json={"params": {"spin_rate_rad_s": 0.0}}).status_code == 200
        readout = client.get(f"{url}/live").json()["readout"]
        angle = next(q for q in readout["quantities"] if q["name"] == "angle_omega_H")
        assert angle["value"] is None and "no spin" in angle["text"]
        # The particles view: the particle sums agree with the rigid-body formulas to rounding.
        assert client.put(url, json={"params": {"spin_rate_rad_s": 4.0, "tilt_deg": 30.0, "view": "particles", "body": "box"}}).status_code == 200
        readout = client.get(f"{url}/live").json()["readout"]
        values = {q["name"]: q["value"] for q in readout["quantities"]}
        assert "8 point masses of 0.5 kg" in readout["message"]
        assert all(q["unit"] for q in readout["quantities"])
        assert values["linear_momentum"] == pytest.approx(1.2, rel=1e-14)
        assert values["particle_sum_mismatch"] < 1e-14 and values["particle_energy_mismatch"] < 1e-14
