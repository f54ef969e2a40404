"""Benchmark results for the Solver lab page: ``work_precision.json`` and one SVG diagram per scene.

``dynlab bench`` writes both into ``Settings.bench_dir`` (``docs/bench`` unless
``DYNLAB_BENCH_DIR`` says otherwise); :mod:`app.course.bench_reports` reads them,
on each request, so a new benchmark run shows up without restarting the server.
"""

from __future__ import annotations

from fastapi import APIRouter, HTTPException
from fastapi.responses import FileResponse

from app.api.deps import SettingsDep
from app.api.schemas.bench import WorkPrecisionReport
from app.api.schemas.errors import error_responses
from app.course.bench_reports import HOW_TO_MEASURE, SCENE_ID_PATTERN, diagram_path, missing_message, results_path

router = APIRouter(tags=["bench"])

_SVG_HEADERS = {
    "Cache-Control": "no-cache",
    "X-Content-Type-Options": "nosniff",
    # The diagrams are plain drawings: no scripts, no external loads, even when opened directly.
    "Content-Security-Policy": "default-src 'none'; style-src 'unsafe-inline'",
}


@router.get(
    "/api/bench/work-precision",
    response_class=FileResponse,
    responses={
        200: {"model": WorkPrecisionReport, "description": "work_precision.json as `dynlab bench` wrote it"},
        **error_responses(not_found="`dynlab bench` has not been run: there is no work_precision.json"),
    },
)
def work_precision(settings: SettingsDep) -> FileResponse:
    """The latest benchmark results as written by ``dynlab bench`` (404 until it has run)."""
    path = results_path(settings)
    if not path.is_file():
        raise HTTPException(status_code=404, detail=missing_message(settings))
    return FileResponse(path, media_type="application/json", headers={"Cache-Control": "no-cache"})


@router.get("/bench/{scene_id}.svg", include_in_schema=False)
def work_precision_diagram(scene_id: str, settings: SettingsDep) -> FileResponse:
    """One scene's work-precision diagram; only names matching ``[a-z0-9-]{1,64}`` are served."""
    path = diagram_path(settings, scene_id)
    if path is None:
        detail = (
            f"no work-precision diagram for scene {scene_id!r}; {HOW_TO_MEASURE}"
            if SCENE_ID_PATTERN.fullmatch(scene_id)
            else "no such diagram"
        )
        raise HTTPException(status_code=404, detail=detail)
    return FileResponse(path, media_type="image/svg+xml", headers=_SVG_HEADERS)
