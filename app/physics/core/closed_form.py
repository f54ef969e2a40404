"""Models whose motion is a closed form in time: evaluated, never integrated.

A :class:`ClosedFormModel` states its parameters, the unit of each series and
invariant, and evaluates all of them at any array of times. The simulate API
samples it on the same frame grid as an integrated model and returns the same
report shape (``t``, ``series``, ``invariants``, ``stats``), with ``stats.method``
``"closed-form"`` and zero steps. Singular instants the formula passes through
(a linkage's toggle position, say) are reported as :class:`Event`\\ s rather
than crossed silently.
"""

from __future__ import annotations

import time
from abc import ABC, abstractmethod
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from app.physics.core.parameters import ParameterSet
from app.physics.core.report import Event, SimulationReport, frame_times

__all__ = ["OUTSIDE_MODEL", "ClosedFormModel", "ClosedFormSolution", "Event", "evaluate_model", "frame_times"]

#: ``stats.status`` of a result that is finite but outside the model's assumptions (``message`` says which).
OUTSIDE_MODEL = "outside_model"


@dataclass
class ClosedFormSolution:
    """Series and invariants at the requested times, plus any events in the span.

    ``warning`` (empty when none) says in words where the result leaves the model's
    assumptions (e.g. a small-angle model driven to large angles); the report's
    status is then ``outside_model`` and its message the warning.
    """

    series: dict[str, np.ndarray]
    invariants: dict[str, np.ndarray] = field(default_factory=dict)
    events: list[Event] = field(default_factory=list)
    warning: str = ""


class ClosedFormModel(ABC):
    """A model evaluated from a formula at any time (no integration)."""

    #: Physical parameters (names are API contracts).
    parameters: ClassVar[ParameterSet]
    #: Unit of each series / invariant, by name.
    series_units: ClassVar[Mapping[str, str]]
    invariant_units: ClassVar[Mapping[str, str]] = {}
    #: What the formula is, for the report (e.g. "Jacobi elliptic functions").
    description: ClassVar[str]

    @abstractmethod
    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        """Series and invariants at times ``t_s`` (s, 1-D array starting at 0)."""

    def invariant_scales(self, params: Mapping[str, Any], invariants: Mapping[str, np.ndarray]) -> dict[str, float]:
        """Scale per invariant for the drift report (default: its initial magnitude, at least 1e-300)."""
        return {name: max(abs(float(values[0])), 1e-300) for name, values in invariants.items()}


def evaluate_model(model: ClosedFormModel, params: Mapping[str, Any], *, t_end_s: float, frame_rate_hz: float) -> dict[str, Any]:
    """The simulate report for a closed-form model (same shape as an integrated one)."""
    t_s = frame_times(t_end_s=t_end_s, frame_rate_hz=frame_rate_hz)
    start = time.process_time()
    solution = model.evaluate(params, t_s)
    cpu_s = time.process_time() - start
    scales = model.invariant_scales(params, solution.invariants)
    drift = [float(np.max(np.abs(v - v[0])) / scales[k]) for k, v in solution.invariants.items()]
    finite = all(np.all(np.isfinite(v)) for v in (*solution.series.values(), *solution.invariants.values()))
    return SimulationReport(
        t_s=t_s,
        series=solution.series,
        invariants=solution.invariants,
        events=list(solution.events),
        method="closed-form",
        description=model.description,
        steps=0,
        rhs_evals=0,
        cpu_s=cpu_s,
        max_invariant_drift=max(drift, default=0.0),
        status="undefined" if not finite else OUTSIDE_MODEL if solution.warning else "ok",
        message=" ".join(m for m in ("" if finite else "the formula is undefined at some frames (see events)", solution.warning) if m),
    ).as_dict()
