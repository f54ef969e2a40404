"""``GET /api/bench/work-precision``: the committed benchmark report, served as the file ``dynlab bench`` wrote."""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict, JsonValue


class WorkPrecisionReport(BaseModel):
    """When and where the sweep ran, one entry per benchmarked scene (methods, points, ratios) and the live scenes'
    costs."""

    model_config = ConfigDict(extra="allow")
    created: str
    machine: dict[str, JsonValue]
    scenes: list[dict[str, JsonValue]]
    live_scenes: list[dict[str, JsonValue]] = []
