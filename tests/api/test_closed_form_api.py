"""POST /api/scenes/{id}/simulate for a closed-form model: same report shape, no integrator, events, nulls."""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution, Event
from app.physics.core.parameters import Parameter, ParameterSet
from app.scenes.kit import Scene


def _check(values):
    if values["radius_m"] > 5.0 and values["rate_rad_s"] > 5.0:
        raise ValueError("this circle cannot be drawn: radius and rate are both too large together")


class Circle(ClosedFormModel):
    """x = R cos ωt, y = R sin ωt; the speed Rω is conserved; t = 1 s is flagged; y/x is undefined where x = 0."""

    parameters = ParameterSet(
        (Parameter("radius_m", "m", 2.0, 0.1, 10.0), Parameter("rate_rad_s", "rad/s", 1.0, -10.0, 10.0)), check=_check
    )
    series_units = {"x_m": "m", "slope": ""}
    invariant_units = {"speed_m_s": "m/s"}
    description = "uniform circular motion (closed form)"

    def evaluate(self, params, t_s):
        R, w = params["radius_m"], params["rate_rad_s"]
        x, y = R * np.cos(w * t_s), R * np.sin(w * t_s)
        with np.errstate(divide="ignore", invalid="ignore"):
            slope = np.where(np.abs(x) < 1e-12, np.nan, y / x)
        events = [Event(1.0, "marker", "one second")] if t_s[-1] >= 1.0 else []
        return ClosedFormSolution({"x_m": x, "slope": slope}, {"speed_m_s": np.full_like(t_s, abs(R * w))}, events)


class CircleScene(Scene):
    id = "test-circle"
    title = "Circle (test)"
    chapter = 1
    parameters = Circle.parameters
    model = Circle

    def build(self) -> None: ...

    def update(self) -> None: ...


@pytest.fixture
def circle(inprocess_client):
    """The app in this process, with a test scene registered in its host."""
    scenes = inprocess_client.app.state.scene_host.scenes
    scenes[CircleScene.id] = CircleScene
    yield inprocess_client
    del scenes[CircleScene.id]


def test_report_has_the_integrated_shape_with_closed_form_stats(circle):
    response = circle.post("/api/scenes/test-circle/simulate", json={"params": {"radius_m": 3.0}, "t_end": 2.0, "frame_rate": 10})
    assert response.status_code == 200
    data = response.json()
    assert len(data["t"]) == 21 and data["t"][-1] == pytest.approx(2.0)
    assert data["series"]["x_m"] == pytest.approx((3.0 * np.cos(np.array(data["t"]))).tolist(), abs=1e-15)
    assert data["stats"]["method"] == "closed-form" and data["stats"]["steps"] == 0 and data["stats"]["rhs_evals"] == 0
    assert data["stats"]["max_invariant_drift"] == 0.0 and data["stats"]["status"] == "ok"
    assert data["events"] == [{"t_s": 1.0, "kind": "marker", "message": "one second"}]
    assert data["units"]["x_m"] == "m" and data["units"]["invariants.speed_m_s"] == "m/s"
    assert data["params"] == {"radius_m": 3.0, "rate_rad_s": 1.0}


def test_undefined_values_are_null_and_the_status_says_so(circle):
    # ω = π/2 rad/s: x = 0 at t = 1 s, where the slope y/x is undefined.
    data = circle.post("/api/scenes/test-circle/simulate", json={"params": {"rate_rad_s": math.pi / 2}, "t_end": 2.0, "frame_rate": 2}).json()
    assert data["series"]["slope"][2] is None
    assert data["stats"]["status"] == "undefined" and "undefined" in data["stats"]["message"]


@pytest.mark.parametrize(
    "body, loc",
    [
        ({"params": {"radius_m": 0.0}, "t_end": 1.0}, ["body", "params", "radius_m"]),
        ({"params": {"radius_m": 8.0, "rate_rad_s": 8.0}, "t_end": 1.0}, ["body", "params"]),
        ({"t_end": 700.0}, ["body", "t_end"]),
        ({"t_end": 1.0, "frame_rate": 0.5}, ["body", "frame_rate"]),
        ({"t_end": 600.0, "frame_rate": 240.0}, ["body", "t_end"]),
        ({"t_end": 1.0, "method": "rk4"}, ["body", "method"]),
        ({"t_end": 1.0, "steps_per_frame": 4}, ["body", "steps_per_frame"]),
    ],
)
def test_bad_requests_get_422_naming_the_field(circle, body, loc):
    response = circle.post("/api/scenes/test-circle/simulate", json=body)
    assert response.status_code == 422, response.text
    detail = response.json()["detail"][0]
    assert detail["loc"] == loc and detail["msg"]


def test_scene_schema_says_not_integrated_and_no_readout(circle):
    listed = {s["id"]: s for s in circle.get("/api/scenes").json()}
    assert listed["test-circle"]["integrated"] is False and listed["test-circle"]["readout"] is False
    assert listed["heavy-top"]["integrated"] is True and listed["heavy-top"]["readout"] is True
