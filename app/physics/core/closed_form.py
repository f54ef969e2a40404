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

import math
import time
from abc import ABC, abstractmethod
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from app.physics.core.parameters import ParameterError, ParameterSet


@dataclass(frozen=True)
class Event:
    """Something the student should know happened at ``t_s`` (s): ``kind`` is a short tag."""

    t_s: float
    kind: str
    message: str

    def as_dict(self) -> dict[str, Any]:
        return {"t_s": self.t_s, "kind": self.kind, "message": self.message}


@dataclass
class ClosedFormSolution:
    """Series and invariants at the requested times, plus any events in the span."""

    series: dict[str, np.ndarray]
    invariants: dict[str, np.ndarray] = field(default_factory=dict)
    events: list[Event] = field(default_factory=list)


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


#: The same request bounds as an integrated run (frames only: there are no steps).
MAX_T_END_S = 600.0
FRAME_RATE_RANGE_HZ = (1.0, 240.0)
MAX_FRAMES = 36_000


def frame_times(*, t_end_s: float, frame_rate_hz: float) -> np.ndarray:
    """Frame grid 0, 1/rate, … ≤ t_end (s); raises ParameterError naming a bound it breaks."""
    if not (math.isfinite(t_end_s) and 0.0 < t_end_s <= MAX_T_END_S):
        raise ParameterError("t_end", f"must be a finite time in (0, {MAX_T_END_S:g}] s (got {t_end_s!r})")
    low, high = FRAME_RATE_RANGE_HZ
    if not (math.isfinite(frame_rate_hz) and low <= frame_rate_hz <= high):
        raise ParameterError("frame_rate", f"must lie in [{low:g}, {high:g}] Hz (got {frame_rate_hz!r})")
    frames = round(t_end_s * frame_rate_hz)
    if frames > MAX_FRAMES:
        raise ParameterError("t_end", f"t_end × frame_rate = {frames} frames exceeds the limit of {MAX_FRAMES} frames")
    return np.arange(frames + 1) / frame_rate_hz


def evaluate_model(model: ClosedFormModel, params: Mapping[str, Any], *, t_end_s: float, frame_rate_hz: float) -> dict[str, Any]:
    """The simulate report for a closed-form model (same shape as an integrated one)."""
    t_s = frame_times(t_end_s=t_end_s, frame_rate_hz=frame_rate_hz)
    start = time.process_time()
    solution = model.evaluate(params, t_s)
    cpu_s = time.process_time() - start
    scales = model.invariant_scales(params, solution.invariants)
    drift = [float(np.max(np.abs(v - v[0])) / scales[k]) for k, v in solution.invariants.items()]
    finite = all(np.all(np.isfinite(v)) for v in (*solution.series.values(), *solution.invariants.values()))
    return {
        "t": t_s.tolist(),
        "series": {k: _json_values(v) for k, v in solution.series.items()},
        "invariants": {k: _json_values(v) for k, v in solution.invariants.items()},
        "events": [event.as_dict() for event in solution.events],
        "stats": {
            "method": "closed-form",
            "description": model.description,
            "steps": 0,
            "rhs_evals": 0,
            "cpu_s": cpu_s,
            "max_invariant_drift": max(drift, default=0.0),
            "status": "ok" if finite else "undefined",
            "message": "" if finite else "the formula is undefined at some frames (see events)",
        },
    }


def _json_values(values: np.ndarray) -> list[float | None]:
    """A float array as a JSON list, with non-finite entries (undefined instants) as null."""
    array = np.asarray(values, dtype=float)
    return [float(v) if math.isfinite(v) else None for v in array.tolist()]
