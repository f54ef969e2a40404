"""POST /api/examples/equinox-precession/solve: the contract outputs and its 422s."""

from __future__ import annotations

import pytest

from app.physics.systems.ch10.equinox_precession import EXAMPLE

URL = "/api/examples/equinox-precession/solve"


def test_contract_outputs_with_defaults(client):
    response = client.post(URL, json={})
    assert response.status_code == 200
    data = response.json()
    outputs = data["outputs"]
    for name in ("rate_arcsec_per_year", "period_years", "sun_share", "moon_share"):
        assert name in outputs
    expected = EXAMPLE.solve(EXAMPLE.inputs.defaults()).outputs
    assert outputs["rate_arcsec_per_year"] == pytest.approx(expected["rate_arcsec_per_year"], rel=1e-15)
    assert data["inputs"]["obliquity_deg"] == 23.439
    assert [step["title"] for step in data["steps"]]  # the derivation comes with it
    assert data["plots"][0]["x_label"] == "obliquity ε (deg)"


def test_inputs_change_the_answer(client):
    low = client.post(URL, json={"inputs": {"moon_mass_ratio": 0.0}}).json()["outputs"]
    assert low["moon_share"] == 0.0
    assert low["rate_arcsec_per_year"] == pytest.approx(15.95, abs=0.01)  # the Sun alone


@pytest.mark.parametrize(
    "inputs, field",
    [
        ({"obliquity_deg": 95.0}, "obliquity_deg"),
        ({"dynamical_ellipticity": 0.0}, "dynamical_ellipticity"),
        ({"earth_spin_rad_s": "fast"}, "earth_spin_rad_s"),
        ({"moon_mass_ratio": -0.1}, "moon_mass_ratio"),
        ({"planet_count": 8}, "planet_count"),
    ],
)
def test_bad_inputs_get_422_naming_the_field(client, inputs, field):
    response = client.post(URL, json={"inputs": inputs})
    assert response.status_code == 422
    assert response.json()["detail"][0]["loc"][-1] == field


def test_non_finite_number_is_rejected(client):
    response = client.post(URL, content='{"inputs": {"obliquity_deg": NaN}}', headers={"content-type": "application/json"})
    assert response.status_code == 422
