"""``/api/examples``: worked examples, their inputs and their solutions."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, Field, JsonValue

from app.api.schemas.parameters import ParameterSpec, ParameterValue


class ExampleStoryText(BaseModel):
    situation: str
    wanted: str
    approach: str = Field(description="Why this frame, coordinates and method; what the alternatives would cost")
    check: str = Field(description="The conservation law, limiting case or second method the Check step computes")
    what_if: str = Field(description="One input to move, and what to look for in the scene")


class ExampleSummary(BaseModel):
    """A worked example: its inputs (name, unit, default, range) and the unit of each output."""

    id: str
    title: str
    chapter: int
    section: str = Field(description="The course section it belongs to (empty: not placed yet)")
    inputs: list[ParameterSpec]
    output_units: dict[str, str]
    story: ExampleStoryText | None = Field(
        description="The words around the steps (Markdown with $…$ LaTeX): situation, wanted, approach, check, what_if"
    )


class SolveRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    inputs: dict[str, Any] = Field(default_factory=dict, description="Inputs by name; omitted ones take their defaults")


class SolutionStep(BaseModel):
    """One step of the worked solution: the LaTeX shown and the values (with units) it produced."""

    title: str
    latex: str
    values: dict[str, JsonValue]
    units: dict[str, str]


class PlotLine(BaseModel):
    name: str
    x: list[float | None]
    y: list[float | None]


class SolutionPlot(BaseModel):
    """A 2D plot; the axis labels carry the units."""

    title: str
    x_label: str
    y_label: str
    log_x: bool
    log_y: bool
    series: list[PlotLine]


class SolveAnswer(BaseModel):
    """The solution: ``outputs`` (SI; vectors as ``[x, y, z]``), ``steps``, ``plots`` and the validated ``inputs``."""

    outputs: dict[str, JsonValue]
    steps: list[SolutionStep]
    plots: list[SolutionPlot]
    inputs: dict[str, ParameterValue]
