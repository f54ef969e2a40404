from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, HTTPException, Path

from app.api.deps import SceneHostDep
from app.api.errors import unprocessable
from app.api.schemas.errors import error_responses
from app.api.schemas.readout import LiveAnswer
from app.api.schemas.scenes import SceneSummary, SessionParamsAnswer, SessionParamsRequest
from app.api.schemas.simulation import SimulateRequest, SimulationAnswer
from app.physics.core.closed_form import ClosedFormModel, evaluate_model
from app.physics.core.parameters import ParameterError, ParameterSet
from app.physics.solvers.integrated_model import simulate_model
from app.scenes.host.host import SESSION_ID_PATTERN, UnknownSceneError
from app.scenes.kit import Scene

router = APIRouter(prefix="/api/scenes", tags=["scenes"])

SessionId = Annotated[str, Path(pattern=SESSION_ID_PATTERN, description="One page's session: 8–64 letters, digits, '-' or '_'")]
_UNKNOWN_SCENE = "No scene has this id"


def _scene_class(host: SceneHostDep, scene_id: str) -> type[Scene]:
    """The scene's class, or a 404 naming the id."""
    try:
        return host.scene_class(scene_id)
    except UnknownSceneError:
        raise HTTPException(status_code=404, detail=f"no scene {scene_id!r}") from None


@router.get("", response_model=list[SceneSummary], response_model_exclude_unset=True)
def list_scenes(host: SceneHostDep) -> list[dict[str, Any]]:
    """Every scene's id, title, chapter and parameter schema."""
    return [cls.schema() for cls in host.scenes.values()]


@router.put(
    "/{scene_id}/sessions/{session_id}",
    response_model=SessionParamsAnswer,
    responses=error_responses(
        not_found=_UNKNOWN_SCENE,
        unprocessable="A parameter is unknown, not finite or out of range, or the session id is malformed; nothing changed",
    ),
)
def set_session_params(scene_id: str, session_id: SessionId, request: SessionParamsRequest, host: SceneHostDep) -> dict[str, Any]:
    """Set the parameters of one page's scene; every viewer of that session redraws.

    Bad input gets a 422 naming the field and changes nothing.
    """
    _scene_class(host, scene_id)
    try:
        params = host.set_params(scene_id, session_id, request.params)
    except ParameterError as exc:  # the request's field is `params`: name it, and the path inside it
        raise unprocessable(["body", "params", *exc.path], str(exc)) from None
    return {"scene_id": scene_id, "session_id": session_id, "params": params, "viewers": host.viewer_count(session_id)}


@router.post(
    "/{scene_id}/simulate",
    response_model=SimulationAnswer,
    response_model_exclude_unset=True,
    responses=error_responses(
        not_found=_UNKNOWN_SCENE,
        unprocessable="The scene has no motion in time, a parameter or control is bad, or the request is over a limit; `loc` names it",
    ),
)
def simulate_scene(scene_id: str, request: SimulateRequest, host: SceneHostDep) -> dict[str, Any]:
    """Integrate a scene's model off-screen and return the frame-sampled solution.

    Returns ``t`` (s), ``series`` and ``invariants`` by name, and ``stats``
    (``method``, ``steps``, ``rhs_evals``, ``cpu_s``, ``max_invariant_drift`` plus
    ``status``/``message`` when the integration had to stop). Bad input or a
    request over the limits gets a 422 naming the field and the limit.
    """
    model_cls = _scene_class(host, scene_id).model
    if model_cls is None:
        raise unprocessable(["path", "scene_id"], f"scene {scene_id!r} has no motion in time: nothing to simulate")
    try:
        params = model_cls.parameters.validate(request.params)
    except ParameterError as exc:
        raise unprocessable(["body", "params", *exc.path], str(exc)) from None
    except ValueError as exc:  # a combination of values that cannot exist together
        raise unprocessable(["body", "params"], str(exc)) from None
    if issubclass(model_cls, ClosedFormModel):
        out = _closed_form_report(model_cls, params, request)
    else:
        raw_controls = {k: v for k, v in (("method", request.method), ("steps_per_frame", request.steps_per_frame), ("rtol", request.rtol)) if v is not None}
        try:
            controls = ParameterSet(model_cls.controls()).validate(raw_controls)
            out = simulate_model(model_cls(), params, controls, t_end_s=request.t_end, frame_rate_hz=request.frame_rate).as_dict()
        except ParameterError as exc:
            raise unprocessable(["body", exc.field], str(exc)) from None
    out["params"] = params
    out["units"] = {"t": "s", **model_cls.series_units, **{f"invariants.{k}": v for k, v in model_cls.invariant_units.items()}}
    return out


def _closed_form_report(model_cls: type[ClosedFormModel], params: dict[str, Any], request: SimulateRequest) -> dict[str, Any]:
    for name in ("method", "steps_per_frame", "rtol"):
        if getattr(request, name) not in (None, "auto", "closed-form", 0):
            raise unprocessable(["body", name], "this scene's motion is a closed form in time: there is no integrator to control")
    try:
        return evaluate_model(model_cls(), params, t_end_s=request.t_end, frame_rate_hz=request.frame_rate)
    except ParameterError as exc:
        raise unprocessable(["body", exc.field], str(exc)) from None
    except ValueError as exc:  # the formula has no solution for these values (e.g. a linkage that cannot assemble)
        raise unprocessable(["body", "params"], str(exc)) from None


@router.get(
    "/{scene_id}/sessions/{session_id}/live",
    response_model=LiveAnswer,
    response_model_exclude_unset=True,
    responses=error_responses(
        not_found="No scene has this id, or no viewer of it is connected in this session yet",
        unprocessable="The session id is malformed",
    ),
)
def live_readout(scene_id: str, session_id: SessionId, host: SceneHostDep) -> dict[str, Any]:
    """The running scene's live numbers: time, method and step, invariants and their drift, cost per frame."""
    _scene_class(host, scene_id)
    readout = host.live_readout(scene_id, session_id)
    if readout is None:
        raise HTTPException(status_code=404, detail=f"no live {scene_id!r} viewer in session {session_id!r} yet")
    return {"scene_id": scene_id, "viewers": host.viewer_count(session_id), **readout}
