from __future__ import annotations

import contextlib
import math
from typing import Annotated, Any

from fastapi import APIRouter, Header, HTTPException, Path, Query
from fastapi.responses import JSONResponse, Response

from app.api.access import KEY_HEADER as SESSION_KEY_HEADER
from app.api.access import SESSION_KEY_PATTERN, Refused
from app.api.deps import ClientDep, ExploreStartDep, SceneHostDep, SessionsDep
from app.api.errors import unprocessable
from app.api.examples import ScriptParams, python_file
from app.api.limits import SIMULATIONS, TOO_MANY_RESPONSE
from app.api.schemas.errors import ErrorDetail, error_responses
from app.api.schemas.graph import GraphAnswer
from app.api.schemas.readout import LiveAnswer
from app.api.schemas.scenes import (
    PlaybackAnswer,
    PlaybackRequest,
    SceneSummary,
    SessionParamsAnswer,
    SessionParamsRequest,
)
from app.api.schemas.simulation import SimulateRequest, SimulationAnswer
from app.course.scripts import scene_script, script_file_name, script_values
from app.physics.core.parameters import ParameterError
from app.physics.solvers.controls import CONTROL_NAMES
from app.scenes.host.fair_share import is_long_request
from app.scenes.host.graph import DEFAULT_MAX_POINTS, MAX_POINTS_RANGE, graph_csv
from app.scenes.host.host import SESSION_ID_PATTERN, UnknownSceneError
from app.scenes.host.interface import HostBusy
from app.scenes.host.recorder import DEFAULT_RECORDING_S, RECORDING_SECONDS_RANGE
from app.scenes.kit import Scene

router = APIRouter(prefix="/api/scenes", tags=["scenes"])

SessionId = Annotated[
    str, Path(pattern=SESSION_ID_PATTERN, description="One page's session: 8–64 letters, digits, '-' or '_'")
]
SessionKey = Annotated[
    str | None,
    Header(
        alias=SESSION_KEY_HEADER,
        pattern=SESSION_KEY_PATTERN.pattern,
        description="The page's secret for its session: 16–128 letters, digits, '-' or '_'",
    ),
]
_UNKNOWN_SCENE = "No scene has this id"
#: What the session doors answer besides 404/422 (:mod:`app.api.access`).
_RETRY_AFTER = {"Retry-After": {"description": "Seconds to wait before retrying", "schema": {"type": "integer"}}}
_SESSION_DOOR: dict[int | str, dict[str, Any]] = {
    403: {
        "model": ErrorDetail,
        "description": (
            "The session belongs to another page (its X-Session-Key is missing or wrong), or it is a classroom "
            "room's shared scene (changed only by its instructor); nothing changed"
        ),
    },
    503: {
        "model": ErrorDetail,
        "description": "The session's scene worker is busy or restarting; Retry-After says when to try again",
        "headers": _RETRY_AFTER,
    },
}
_TOO_MANY_SESSIONS: dict[int | str, dict[str, Any]] = {
    429: {
        "model": ErrorDetail,
        "description": "Too many new scenes from this device; Retry-After says when to try again",
        "headers": _RETRY_AFTER,
    }
}


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


@router.get(
    "/{scene_id}/sessions/{session_id}",
    response_model=SessionParamsAnswer,
    responses=error_responses(
        not_found="No scene has this id, or the session shows none (or another scene)",
        unprocessable="The session id is malformed",
    ),
)
def session_params(scene_id: str, session_id: SessionId, host: SceneHostDep, sessions: SessionsDep) -> dict[str, Any]:
    """The session's parameters now and how many viewers are connected to it."""
    _scene_class(host, scene_id)
    sessions.reopen_kept(session_id)  # kept from the server's last run: its scene comes back first
    params = host.session_params(session_id) if host.session_scene(session_id) == scene_id else None
    if params is None:
        raise HTTPException(status_code=404, detail=f"session {session_id!r} shows no {scene_id!r} scene")
    return {"scene_id": scene_id, "session_id": session_id, "params": params, "viewers": host.viewer_count(session_id)}


@router.put(
    "/{scene_id}/sessions/{session_id}",
    response_model=SessionParamsAnswer,
    responses={
        **error_responses(
            not_found=_UNKNOWN_SCENE,
            unprocessable=(
                "A parameter is unknown, not finite or out of range, "
                "or the session id or key is malformed; nothing changed"
            ),
        ),
        **_SESSION_DOOR,
        **_TOO_MANY_SESSIONS,
    },
)
def set_session_params(
    scene_id: str,
    session_id: SessionId,
    request: SessionParamsRequest,
    host: SceneHostDep,
    sessions: SessionsDep,
    client: ClientDep,
    explore_start: ExploreStartDep,
    session_key: SessionKey = None,
) -> dict[str, Any]:
    """Set the parameters of one page's scene; every viewer of that session redraws.

    The first change makes the session (a page's own scene); the first that carries an ``X-Session-Key`` claims
    it for that key: later changes without it are refused with 403. A classroom room's shared scene
    (``room-…``) is refused with 403: only its instructor changes it, through the room. Bad input gets a 422
    naming the field and changes nothing.
    """
    cls = _scene_class(host, scene_id)
    sessions.check_change(session_id, session_key, client=client)
    try:  # a student exploring starts from the room's parameters and motion, or a 422 says why not
        start = explore_start(request.from_room, scene_id) if request.from_room else None
    except ValueError as exc:
        raise unprocessable(["body", "from_room"], str(exc)) from None
    raw = {**start["params"], **request.params} if start else request.params
    typed = any(p.kind == "text" for p in cls.parameters.parameters)  # validating compiles what the student typed
    try:
        with sessions.heavy_change(client=client) if typed else contextlib.nullcontext():
            params = host.set_params(scene_id, session_id, raw)
    except ParameterError as exc:  # the request's field is `params`: name it, and the path inside it
        raise unprocessable(["body", "params", *exc.path], str(exc)) from None
    except ValueError as exc:  # values that cannot exist together (a linkage that cannot assemble, …)
        raise unprocessable(["body", "params"], str(exc)) from None
    sessions.changed(session_id, scene_id, session_key, client=client, params=params)
    if start and start["motion"] is not None and params == start["params"]:
        host.resume_from(session_id, start["motion"])  # same parameters: continue the room's motion, not restart it
    return {"scene_id": scene_id, "session_id": session_id, "params": params, "viewers": host.viewer_count(session_id)}


@router.put(
    "/{scene_id}/sessions/{session_id}/playback",
    response_model=PlaybackAnswer,
    response_model_exclude_unset=True,
    responses={
        **error_responses(
            not_found=_UNKNOWN_SCENE,
            unprocessable=(
                "A field is out of range, the session has no scene yet, seek_s is outside the kept motion, or the "
                "request would compute longer than one request may; nothing changed"
            ),
        ),
        **_SESSION_DOOR,
    },
)
def set_session_playback(
    scene_id: str,
    session_id: SessionId,
    request: PlaybackRequest,
    host: SceneHostDep,
    sessions: SessionsDep,
    client: ClientDep,
    session_key: SessionKey = None,
) -> dict[str, Any]:
    """Play, pause, step, scrub, restart or change the speed of one page's scene (the page's time controls);
    ``go_to_s`` restores the motion at a simulated time (a share link). Owned sessions need their X-Session-Key;
    a classroom room's shared scene is refused (403)."""
    _scene_class(host, scene_id)
    try:
        sessions.check_change(session_id, session_key, client=client, creating=False)
    except Refused as exc:
        if exc.status != 404:
            raise
        raise unprocessable(
            ["path", "session_id"], f"session {session_id!r} has no scene yet: set its parameters first"
        ) from None
    sessions.reopen_kept(session_id)  # kept from the server's last run: its scene comes back first
    if host.session_scene(session_id) != scene_id:
        raise unprocessable(
            ["path", "session_id"], f"session {session_id!r} shows no {scene_id!r} scene: set its parameters first"
        )
    if is_long_request(step=request.step, go_to_s=request.go_to_s):
        sessions.check_long_request(client=client)
    try:
        answer = host.set_playback(session_id, **request.model_dump(exclude_none=True))
    except ValueError as exc:
        field = str(exc).split(":", 1)[0]
        raise unprocessable(
            ["body", field if field in PlaybackRequest.model_fields else "session_id"], str(exc)
        ) from None
    sessions.touched(session_id)
    return answer


@router.get(
    "/{scene_id}/sessions/{session_id}/playback",
    response_model=PlaybackAnswer,
    response_model_exclude_unset=True,
    responses=error_responses(
        not_found="No scene has this id, or the session has none yet", unprocessable="The session id is malformed"
    ),
)
def session_playback(scene_id: str, session_id: SessionId, host: SceneHostDep, sessions: SessionsDep) -> dict[str, Any]:
    """The session's play state, simulated time, the motion kept for scrubbing, the first viewer's camera (for a share
    link) and how many viewers are connected (a page waits for its viewer before asking for live numbers)."""
    _scene_class(host, scene_id)
    sessions.reopen_kept(session_id)  # kept from the server's last run: its scene comes back first
    answer = host.playback(session_id)
    if answer is None:
        raise HTTPException(status_code=404, detail=f"session {session_id!r} has no scene yet")
    return answer


@router.post(
    "/{scene_id}/simulate",
    response_model=SimulationAnswer,
    response_model_exclude_unset=True,
    responses={
        **error_responses(
            not_found=_UNKNOWN_SCENE,
            unprocessable=(
                "The scene has no motion in time, a parameter or control "
                "is bad, or the request is over a limit; `loc` names it"
            ),
        ),
        **TOO_MANY_RESPONSE,
    },
)
def simulate_scene(scene_id: str, request: SimulateRequest, host: SceneHostDep) -> JSONResponse:
    """Integrate a scene's model off-screen and return the frame-sampled solution.

    Returns ``t`` (s), ``series`` and ``invariants`` by name, and ``stats``
    (``method``, ``steps``, ``rhs_evals``, ``cpu_s``, ``max_invariant_drift`` plus
    ``status``/``message`` when the integration had to stop, e.g. ``non_finite``
    with the finite part of the run). Bad input or a request over the limits gets
    a 422 naming the field and the limit; while the process's simulations are all
    busy and their queue is full, a 429 with ``Retry-After``.
    """
    model_cls = _scene_class(host, scene_id).model
    if model_cls is None:
        raise unprocessable(["path", "scene_id"], f"scene {scene_id!r} has no motion in time: nothing to simulate")
    with SIMULATIONS.slot("simulate"):  # the heavy part: at most a few at once, or a 429
        try:
            params = model_cls.parameters.validate(request.params)
        except ParameterError as exc:
            raise unprocessable(["body", "params", *exc.path], str(exc)) from None
        except ValueError as exc:  # a combination of values that cannot exist together
            raise unprocessable(["body", "params"], str(exc)) from None
        raw_controls = {name: value for name in CONTROL_NAMES if (value := getattr(request, name)) is not None}
        try:
            controls = model_cls.validate_controls(raw_controls)
            report = model_cls().simulate(params, controls, t_end_s=request.t_end, frame_rate_hz=request.frame_rate)
        except (
            ParameterError
        ) as exc:  # a control, a request field (t_end, frame_rate), a parameter failing over this span
            where = ["body", "params", *exc.path] if exc.field in params else ["body", exc.field]
            raise unprocessable(where, str(exc)) from None
        except ValueError as exc:  # no motion for these values (e.g. a linkage that cannot assemble)
            raise unprocessable(["body", "params"], str(exc)) from None
        out = report.as_dict()
        out["params"] = params
        invariant_units = {
            k: v for k, v in model_cls.invariant_units.items() if k in out["invariants"]
        }  # e.g. |L| only without gravity
        out["units"] = {
            "t": "s",
            **model_cls.series_units,
            **{f"invariants.{k}": v for k, v in invariant_units.items()},
        }
        # Encoded here, inside the slot, as FastAPI would after it: the encoding is half the answer's memory.
        return JSONResponse(SimulationAnswer.model_validate(out).model_dump(mode="json", exclude_unset=True))


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


@router.get("/{scene_id}/sessions/{session_id}/recording.html", include_in_schema=False)
def session_recording(
    scene_id: str,
    session_id: SessionId,
    host: SceneHostDep,
    sessions: SessionsDep,
    client: ClientDep,
    seconds: Annotated[
        float, Query(ge=RECORDING_SECONDS_RANGE[0], le=RECORDING_SECONDS_RANGE[1], description="Length (s)")
    ] = DEFAULT_RECORDING_S,
) -> Response:
    """The last ``seconds`` (1–60) of what the session's viewer showed, as one HTML file that plays offline in any
    browser (viser's client and the recording inside it); a still of the scene when it has no kept motion.

    404 for an unknown scene or a session without this scene; 422 for bad ``seconds``, a file over the size
    limit or more computing than one request may take; 429 with Retry-After for a device's second recording at
    once or more than 2 then 1 per 30 s; 503 with Retry-After while another recording is being made in the same
    worker; 500 with the reason when the recording fails.
    """
    _scene_class(host, scene_id)
    try:
        with sessions.recording(client=client):
            page = host.recording_html(scene_id, session_id, seconds=seconds)
    except ValueError as exc:
        raise unprocessable(["query", "seconds"], str(exc)) from None
    except HostBusy:  # the worker's recorder is making another recording, or the worker is not answering: 503
        raise
    except RuntimeError as exc:  # RecordingError in-process; a worker's arrives as "scene worker failed: …"
        raise HTTPException(status_code=500, detail=f"the recording could not be made: {exc}") from None
    if page is None:
        raise HTTPException(status_code=404, detail=f"session {session_id!r} has no {scene_id!r} scene yet")
    return Response(
        page,
        media_type="text/html; charset=utf-8",
        headers={"Content-Disposition": f'attachment; filename="{scene_id}-recording.html"'},
    )


@router.get("/{scene_id}/script.py", include_in_schema=False)
def scene_script_file(scene_id: str, host: SceneHostDep, params: ScriptParams = None) -> Response:
    """A Python script reproducing the scene's numbers for ``params`` with the project's own package ("Open as Python").

    ``params`` are the scene's parameters (the page's controls); a bad one gets a 422
    naming the field (``loc`` ``["query", "params", name]``) and no script.
    """
    cls = _scene_class(host, scene_id)
    try:
        params_checked = script_values(cls.parameters, params)
    except ParameterError as exc:
        raise unprocessable(["query", *exc.path], str(exc)) from None
    return python_file(scene_script(cls, params_checked), script_file_name(scene_id))


_GRAPH_UNPROCESSABLE = "since_s is not a number or is +∞, max_points is outside 10–2000, or the session id is malformed"


def _session_graph(
    host: SceneHostDep, scene_id: str, session_id: str, *, since_s: float | None, max_points: int
) -> dict[str, Any]:
    """The host's graph of the session's kept motion, or a 404 / 422 naming why not."""
    _scene_class(host, scene_id)
    try:
        answer = host.graph(session_id, since_s=-math.inf if since_s is None else since_s, max_points=max_points)
    except ValueError as exc:
        field = str(exc).split(":", 1)[0]
        raise unprocessable(["query", field], str(exc)) from None
    if answer is None or answer["scene_id"] != scene_id:
        raise HTTPException(status_code=404, detail=f"session {session_id!r} shows no {scene_id!r} scene")
    return answer


@router.get(
    "/{scene_id}/sessions/{session_id}/graph",
    response_model=GraphAnswer,
    responses=error_responses(
        not_found="No scene has this id, or the session shows none (or another scene)",
        unprocessable=_GRAPH_UNPROCESSABLE,
    ),
)
def session_graph(
    scene_id: str,
    session_id: SessionId,
    host: SceneHostDep,
    since_s: Annotated[
        float | None, Query(description="Only frames later than this simulated time (s); none: all the kept motion")
    ] = None,
    max_points: Annotated[
        int,
        Query(
            ge=MAX_POINTS_RANGE[0],
            le=MAX_POINTS_RANGE[1],
            description="Most frames in the answer (evenly thinned, the latest kept)",
        ),
    ] = DEFAULT_MAX_POINTS,
) -> dict[str, Any]:
    """Graphs of the session's kept motion (the scrubber's last 60 s): every series, invariant and energy part
    against simulated time, evaluated on the kept states, and the energy bars at the latest frame. A scene that is
    not integrated answers with no quantities and a note saying why."""
    return _session_graph(host, scene_id, session_id, since_s=since_s, max_points=max_points)


@router.get("/{scene_id}/sessions/{session_id}/graph.csv", include_in_schema=False)
def session_graph_csv(scene_id: str, session_id: SessionId, host: SceneHostDep) -> Response:
    """The session's kept motion as CSV (every quantity of :func:`session_graph`, every kept frame), as a download."""
    answer = _session_graph(host, scene_id, session_id, since_s=None, max_points=MAX_POINTS_RANGE[1])
    return Response(
        graph_csv(answer),
        media_type="text/csv",
        headers={"Content-Disposition": f'attachment; filename="{scene_id}-graph.csv"'},
    )
