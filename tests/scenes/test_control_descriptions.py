"""What each integrated scene's controls say ``auto`` and 0 steps per frame do is what the code does (issue 24, Found 12).

The cartesian pendulum's ``integrator`` said "auto = rk4" while auto picked dopri5; the heavy top's steps per frame still
gave the old h·ω rule; a blow-up message offered a splitting method to models that have none. For every integrated
scene the descriptions are read back and the automatic choice made at its defaults (with pilot runs, as a simulate
request makes it): the method chosen is one the description names, the step is the kind it describes, and a model is
only ever told to use a method it offers.
"""

from __future__ import annotations

import math

import pytest

from app.physics.constrained.model import ConstrainedModel
from app.physics.solvers.controls import AUTO, CONTROL_NAMES
from app.physics.solvers.integrated_model import IntegratedModel
from app.physics.solvers.registry import METHODS
from app.physics.solvers.solve import remedy
from app.physics.solvers.step_choice import REDUCED_ACCURACY
from app.physics.solvers.step_policy import choose_integrator
from app.scenes import SCENES

FRAME_DT_S = 1.0 / 60.0
INTEGRATED = sorted(sid for sid, scene in SCENES.items() if isinstance(getattr(scene, "model", None), type) and issubclass(scene.model, IntegratedModel))


def _defaults(scene_id: str):
    scene = SCENES[scene_id]
    model = scene.model()
    values = scene.parameters.validate({})
    params = {name: values[name] for name in model.parameters.by_name}
    controls = {name: values[name] for name in CONTROL_NAMES if name in values}
    descriptions = {p.name: p.description for p in scene.parameters.parameters}
    return model, params, controls, descriptions


def test_every_integrated_scene_is_checked():
    """Every scene the catalogue calls integrated has an integrated model, so each is in the list below (19 today)."""
    assert INTEGRATED == sorted(sid for sid, scene in SCENES.items() if scene.schema().get("integrated"))
    assert {"heavy-top", "cartesian-pendulum", "typed-lagrangian", "bouncing-bar"} <= set(INTEGRATED)


@pytest.mark.parametrize("scene_id", INTEGRATED)
def test_auto_picks_what_the_description_names(scene_id):
    model, params, controls, descriptions = _defaults(scene_id)
    method_control = "integrator" if isinstance(model, ConstrainedModel) else "method"
    described = descriptions[method_control]
    integrator, choice = choose_integrator(model, params, {**controls, method_control: AUTO, "steps_per_frame": 0}, FRAME_DT_S)
    target = model.accuracy_target
    if target is None:
        assert f"({AUTO} = {model.default_method})" in described
        assert integrator.name == model.default_method
        assert "h·ω_max" in descriptions["steps_per_frame"]
        return
    candidates = model.auto_methods or model.methods
    named = f"{AUTO} = {candidates[0]})" if len(candidates) == 1 else f"{AUTO} = whichever of {', '.join(candidates)} meets"
    assert named in described, described
    assert integrator.name in candidates, (integrator.name, candidates)
    assert f"meet the accuracy target of {target.format(target.error)}" in descriptions["steps_per_frame"]
    assert "h·ω_max ≤" not in descriptions["steps_per_frame"]  # the old rule, which a target replaced
    assert choice is not None and choice.method == integrator.name
    assert choice.meets_target or choice.status == REDUCED_ACCURACY or math.isnan(choice.estimated_error), choice


@pytest.mark.parametrize("scene_id", [sid for sid in INTEGRATED if issubclass(SCENES[sid].model, ConstrainedModel)])
def test_a_constrained_scenes_auto_algorithm_is_the_one_it_names(scene_id):
    model, params, controls, descriptions = _defaults(scene_id)
    assert f"({AUTO} = {model.default_algorithm})" in descriptions["method"]
    choose_integrator(model, params, {**controls, "method": AUTO}, FRAME_DT_S)
    assert model.algorithm() == model.default_algorithm


@pytest.mark.parametrize("scene_id", INTEGRATED)
def test_a_blow_up_only_suggests_methods_the_scene_offers(scene_id):
    model, params, _, _ = _defaults(scene_id)
    advice = remedy(model.system(params))
    offered = set(model.methods)
    for name, spec in METHODS.items():
        if name in advice:
            assert name in offered, (scene_id, advice)
    assert ("splitting" in advice) == any(METHODS[m].needs_torque for m in offered), (scene_id, advice)
