"""A worked solution as data: outputs, the named steps that produced them, and plots.

The same object feeds the API (JSON), the lesson's step-by-step panel (LaTeX) and
the tests (numbers), so a derivation is written once.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from app.physics.core.parameters import ParameterSet


def _plain(value: Any) -> Any:
    """Convert numpy scalars/arrays (nested) into JSON-ready Python values."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, Mapping):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


@dataclass(frozen=True)
class Step:
    """One step of a worked solution: a title, the formula in LaTeX, and its numbers.

    ``values`` maps a symbol (as the lesson prints it) to a number or an
    ``[x, y, z]`` vector in SI units; ``units`` gives each symbol's unit.
    """

    title: str
    latex: str
    values: Mapping[str, Any] = field(default_factory=dict)
    units: Mapping[str, str] = field(default_factory=dict)

    def as_dict(self) -> dict[str, Any]:
        return {"title": self.title, "latex": self.latex, "values": _plain(self.values), "units": dict(self.units)}


@dataclass(frozen=True)
class PlotSeries:
    name: str
    x: np.ndarray
    y: np.ndarray


@dataclass(frozen=True)
class Plot:
    """A 2D plot the lesson page draws (axes carry units in their labels)."""

    title: str
    x_label: str
    y_label: str
    series: tuple[PlotSeries, ...]
    log_x: bool = False
    log_y: bool = False

    def as_dict(self) -> dict[str, Any]:
        return {
            "title": self.title,
            "x_label": self.x_label,
            "y_label": self.y_label,
            "log_x": self.log_x,
            "log_y": self.log_y,
            "series": [{"name": s.name, "x": _plain(s.x), "y": _plain(s.y)} for s in self.series],
        }


@dataclass(frozen=True)
class Solution:
    outputs: Mapping[str, Any]
    steps: tuple[Step, ...]
    plots: tuple[Plot, ...] = ()

    def as_dict(self) -> dict[str, Any]:
        return {
            "outputs": _plain(self.outputs),
            "steps": [s.as_dict() for s in self.steps],
            "plots": [p.as_dict() for p in self.plots],
        }


@dataclass(frozen=True)
class WorkedExample:
    """A worked example: its inputs and the function that solves it.

    ``solve`` takes validated inputs (SI; angles in degrees where the name ends in
    ``_deg``) and returns a :class:`Solution`; it raises ``ValueError`` for inputs
    that are in range but physically impossible together.
    """

    id: str
    title: str
    chapter: int
    inputs: ParameterSet
    solve: Callable[[Mapping[str, Any]], Solution]
    output_units: Mapping[str, str] = field(default_factory=dict)

    def schema(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "title": self.title,
            "chapter": self.chapter,
            "inputs": self.inputs.schema(),
            "output_units": dict(self.output_units),
        }
