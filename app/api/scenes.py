from __future__ import annotations

from typing import Any

from fastapi import APIRouter, HTTPException
from pydantic import BaseModel, ConfigDict, Field

from app.api.deps import SceneHostDep
from app.physics.core.closed_form import ClosedFormModel, evaluate_model
from app.physics.core.parameters import ParameterError, ParameterSet
from app.physics.solvers.integrated_model import simulate_model
from app.scenes.host.host import UnknownSceneError

router = APIRouter(prefix="/api/scenes", tags=["scenes"])


class SessionParamsRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    params: dict[str, Any] = Field(default_factory=dict, description="Parameters to change; others keep their values")


@router.get("")
def list_scenes(host: SceneHostDep) -> list[dict[str, Any]]:
    """Every scene's id, title, chapter and parameter schema."""
    return [cls.schema() for cls in host.scenes.values()]


@router.put("/{scene_id}/sessions/{session_id}")
def set_session_params(scene_id: str, session_id: str, request: SessionParamsRequest, host: SceneHostDep) -> dict[str, Any]:
    """Set the parameters of one page's scene; every viewer of that session redraws.

    Bad input gets a 422 naming the field and changes nothing.
    """
    try:
        params = host.set_params(scene_id, session_id, request.params)
    except UnknownSceneError:
        raise HTTPException(status_code=404, detail=f"no scene {scene_id!r}") from None
    return {"scene_id": scene_id, "session_id": session_id, "params": params, "viewers": host.viewer_count(session_id)}


class SimulateRequest(BaseModel):
    """Body of ``POST /api/scenes/{scene_id}/simulate``."""

    model_config = ConfigDict(extra="forbid")
    params: dict[str, Any] = Field(default_factory=dict, description="Physical parameters; omitted ones take their defaults")
    t_end: float = Field(description="Simulated time span (s), at most 600 s")
    frame_rate: float = Field(60.0, description="Samples per second of simulated time (Hz), 1–240")
    method: str | None = Field(None, description="Integrator: 'auto' or one the scene lists; default auto")
    steps_per_frame: int | None = Field(None, description="Fixed steps per frame (0 or omitted: automatic)")
    rtol: float | None = Field(None, description="Relative tolerance of the adaptive method")


@router.post("/{scene_id}/simulate")
def simulate_scene(scene_id: str, request: SimulateRequest, host: SceneHostDep) -> dict[str, Any]:
    """Integrate a scene's model off-screen and return the frame-sampled solution.

    Returns ``t`` (s), ``series`` and ``invariants`` by name, and ``stats``
    (``method``, ``steps``, ``rhs_evals``, ``cpu_s``, ``max_invariant_drift`` plus
    ``status``/``message`` when the integration had to stop). Bad input or a
    request over the limits gets a 422 naming the field and the limit.
    """
    try:
        cls = host.scene_class(scene_id)
    except UnknownSceneError:
        raise HTTPException(status_code=404, detail=f"no scene {scene_id!r}") from None
    model_cls = getattr(cls, "model", None)
    if model_cls is None:
        raise HTTPException(
            status_code=422,
            detail=[{"loc": ["path", "scene_id"], "msg": f"scene {scene_id!r} has no motion in time: nothing to simulate", "type": "value_error"}],
        )
    try:
        params = model_cls.parameters.validate(request.params)
    except ParameterError as exc:
        raise _unprocessable(["body", "params", exc.field], str(exc)) from None
    except ValueError as exc:  # a combination of values that cannot exist together
        raise _unprocessable(["body", "params"], str(exc)) from None
    if issubclass(model_cls, ClosedFormModel):
        return _closed_form_report(model_cls, params, request)
    raw_controls = {k: v for k, v in (("method", request.method), ("steps_per_frame", request.steps_per_frame), ("rtol", request.rtol)) if v is not None}
    try:
        controls = ParameterSet(model_cls.controls()).validate(raw_controls)
        report = simulate_model(model_cls(), params, controls, t_end_s=request.t_end, frame_rate_hz=request.frame_rate)
    except ParameterError as exc:
        raise _unprocessable(["body", exc.field], str(exc)) from None
    out = report.as_dict()
    out["params"] = params
    out["units"] = {"t": "s", **model_cls.series_units, **{f"invariants.{k}": v for k, v in model_cls.invariant_units.items()}}
    return out


def _closed_form_report(model_cls: type[ClosedFormModel], params: dict[str, Any], request: SimulateRequest) -> dict[str, Any]:
    for name in ("method", "steps_per_frame", "rtol"):
        if getattr(request, name) not in (None, "auto", "closed-form", 0):
            raise _unprocessable(["body", name], "this scene's motion is a closed form in time: there is no integrator to control")
    try:
        out = evaluate_model(model_cls(), params, t_end_s=request.t_end, frame_rate_hz=request.frame_rate)
    except ParameterError as exc:
        raise _unprocessable(["body", exc.field], str(exc)) from None
    except ValueError as exc:  # the formula has no solution for these values (e.g. a linkage that cannot assemble)
        raise _unprocessable(["body", "params"], str(exc)) from None
    out["params"] = params
    out["units"] = {"t": "s", **model_cls.series_units, **{f"invariants.{k}": v for k, v in model_cls.invariant_units.items()}}
    return out


@router.get("/{scene_id}/sessions/{session_id}/live")
def live_readout(scene_id: str, session_id: str, host: SceneHostDep) -> dict[str, Any]:
    """The running scene's live numbers: time, method and step, invariants and their drift, cost per frame."""
    try:
        host.scene_class(scene_id)
    except UnknownSceneError:
        raise HTTPException(status_code=404, detail=f"no scene {scene_id!r}") from None
    readout = host.live_readout(scene_id, session_id)
    if readout is not None:
        return {"scene_id": scene_id, "viewers": host.viewer_count(session_id), **readout}
    raise HTTPException(status_code=404, detail=f"no live {scene_id!r} viewer in session {session_id!r} yet")


def _unprocessable(loc: list[str], message: str) -> HTTPException:
    return HTTPException(status_code=422, detail=[{"loc": loc, "msg": message, "type": "value_error"}])
