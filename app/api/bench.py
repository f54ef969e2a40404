"""Benchmark results for the Solver lab page: ``work_precision.json`` and one SVG diagram per scene.

``dynlab bench`` writes both into ``Settings.bench_dir`` (``docs/bench`` unless
``DYNLAB_BENCH_DIR`` says otherwise). The files are read on each request, so a
new benchmark run shows up without restarting the server.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from fastapi import APIRouter, HTTPException
from fastapi.responses import FileResponse

from app.api.deps import SettingsDep
from app.api.schemas.bench import WorkPrecisionReport
from app.api.schemas.errors import error_responses
from app.bench.report_file import read_report_file
from app.settings import Settings

router = APIRouter(tags=["bench"])

RESULTS_FILE = "work_precision.json"
#: Scene ids that may name a diagram file; anything else (dots, slashes, capitals, or a name longer than
#: any scene id and than a file name may be) is refused.
SCENE_ID_PATTERN = re.compile(r"[a-z0-9-]{1,64}")
HOW_TO_MEASURE = "run `uv run --group bench dynlab bench` to measure the integrators and write it"
_SVG_HEADERS = {
    "Cache-Control": "no-cache",
    "X-Content-Type-Options": "nosniff",
    # The diagrams are plain drawings: no scripts, no external loads, even when opened directly.
    "Content-Security-Policy": "default-src 'none'; style-src 'unsafe-inline'",
}


class BenchResultsError(Exception):
    """work_precision.json exists but cannot be used."""


def results_path(settings: Settings) -> Path:
    return Path(settings.bench_dir) / RESULTS_FILE


def missing_message(settings: Settings) -> str:
    return f"No benchmark results: `{_shown(results_path(settings))}` does not exist; {HOW_TO_MEASURE}."


def _shown(path: Path) -> str:
    """The path as a reader should see it: relative to the project when it lies inside it."""
    root = Path(__file__).resolve().parents[2]
    try:
        return str(path.resolve().relative_to(root))
    except ValueError:
        return str(path)


def load_results(settings: Settings) -> dict[str, Any] | None:
    """The parsed results, ``None`` if the file is missing; ``BenchResultsError`` if it is unreadable."""
    path = results_path(settings)
    try:
        return read_report_file(path, list_key="scenes", shown_as=f"`{_shown(path)}`")
    except ValueError as exc:
        raise BenchResultsError(str(exc)) from None


def diagram_path(settings: Settings, scene_id: str) -> Path | None:
    """The SVG for a scene, or ``None`` if the id is not a safe file name or the file is missing."""
    if not isinstance(scene_id, str) or not SCENE_ID_PATTERN.fullmatch(scene_id):
        return None
    path = Path(settings.bench_dir) / f"{scene_id}.svg"
    return path if path.is_file() else None


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
