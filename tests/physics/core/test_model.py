"""The one model contract: every scene's model keeps it, and no caller asks which kind of model it has."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from app.physics.core.model import Model
from app.physics.core.parameters import Parameter, ParameterError
from app.physics.core.report import SimulationReport
from app.physics.systems.ch10.torque_free_axisymmetric import TorqueFreeAxisymmetric
from app.scenes import SCENES

APP = Path(__file__).resolve().parents[3] / "app"
#: A test of a model's kind: isinstance/issubclass naming a model class (the contract's methods answer instead).
KIND_TEST = re.compile(
    r"\b(?:isinstance|issubclass)\([^)]*\b(?:Model|ClosedFormModel|IntegratedModel|ConstrainedModel|DerivedModel)\b"
)
MODELS = sorted({cls.model for cls in SCENES.values() if cls.model is not None}, key=lambda m: m.__qualname__)


@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.__qualname__)
def test_every_scene_model_keeps_the_contract(model):
    assert issubclass(model, Model)
    assert model.parameters.parameters and model.series_units
    assert isinstance(model.integrated, bool) and model.how_computed
    assert all(isinstance(control, Parameter) for control in model.controls())
    assert not {c.name for c in model.controls()} & set(model.parameters.by_name), "a control shadows a parameter"
    assert model.validate_controls({}) == {c.name: c.default for c in model.controls()}


def test_a_closed_form_refuses_integrator_controls_and_answers_through_simulate():
    model = TorqueFreeAxisymmetric
    assert model.controls() == () and model.validate_controls({"method": "auto", "steps_per_frame": 0}) == {}
    with pytest.raises(ParameterError) as refused:
        model.validate_controls({"method": "rk4"})
    assert refused.value.field == "method"
    assert str(refused.value) == "this scene's motion is a closed form in time: there is no integrator to control"
    report = model().simulate(model.parameters.defaults(), {}, t_end_s=1.0, frame_rate_hz=10.0)
    assert isinstance(report, SimulationReport) and report.method == "closed-form" and len(report.t_s) == 11


def test_no_caller_asks_which_kind_of_model_it_has():
    found = [
        f"{path.relative_to(APP.parent)}:{number}: {line.strip()}"
        for path in sorted(APP.rglob("*.py"))
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1)
        if KIND_TEST.search(line)
    ]
    assert not found, "use the model contract (app/physics/core/model.py) instead:\n" + "\n".join(found)
