"""A simulate request's bounds and its answer, shared by closed-form and integrated models.

:func:`frame_times` and the ``MAX_*`` bounds say what one request may ask for
(so none holds a core for more than about a second); :class:`SimulationReport`
is what ``POST /api/scenes/{id}/simulate`` returns, whichever way the motion
was found.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.parameters import ParameterError

#: Longest time span (s) and the frame-rate range (Hz) of one request.
MAX_T_END_S = 600.0
FRAME_RATE_RANGE_HZ = (1.0, 240.0)
#: Most frames one request may sample.
MAX_FRAMES = 36_000
#: Fixed-step work of one integrated request: frames × steps per frame × sub-steps per step.
MAX_FIXED_STEP_WORK = 4_000_000
#: Steps an adaptive integration may take in one request.
MAX_ADAPTIVE_STEPS = 1_000_000


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


@dataclass(frozen=True)
class Event:
    """Something the student should know happened at ``t_s`` (s): ``kind`` is a short tag."""

    t_s: float
    kind: str
    message: str

    def as_dict(self) -> dict[str, Any]:
        return {"t_s": self.t_s, "kind": self.kind, "message": self.message}


@dataclass
class SimulationReport:
    """What ``POST /api/scenes/{id}/simulate`` returns (see :meth:`as_dict`).

    ``t_s`` (N,) frame times (s); ``series`` and ``invariants`` map names to
    arrays (N,) in their declared units. The remaining fields are the ``stats``.
    ``events`` is reported by closed-form models (possibly empty) and left
    ``None`` by integrated ones, whose answer has no ``events`` key.
    Models in constrained coordinates (chapter 8) add ``integrator`` (``method`` is
    then the DAE algorithm) and ``initial_conditions``: the coordinates and rates
    the start had to change to satisfy the constraints (``name``, ``requested``,
    ``consistent``, ``change``, ``unit``; empty when none). Both stay out of ``stats`` when ``None``.
    """

    t_s: np.ndarray
    series: dict[str, np.ndarray]
    invariants: dict[str, np.ndarray]
    method: str
    description: str
    steps: int
    rhs_evals: int
    cpu_s: float
    max_invariant_drift: float
    status: str
    message: str
    events: list[Event] | None = None
    #: Accuracy keys added to ``stats`` for an integrated model with a stated target (target, estimate,
    #: error against a reference; see :meth:`app.physics.solvers.step_choice.StepChoice.as_dict`).
    accuracy: dict[str, Any] | None = None
    integrator: str | None = None
    initial_conditions: list[dict[str, Any]] | None = None

    def as_dict(self) -> dict[str, Any]:
        """The JSON answer; a non-finite value (an undefined instant of a formula) becomes null."""
        out: dict[str, Any] = {
            "t": self.t_s.tolist(),
            "series": {k: json_values(v) for k, v in self.series.items()},
            "invariants": {k: json_values(v) for k, v in self.invariants.items()},
        }
        if self.events is not None:
            out["events"] = [event.as_dict() for event in self.events]
        out["stats"] = {
            "method": self.method,
            "description": self.description,
            "steps": self.steps,
            "rhs_evals": self.rhs_evals,
            "cpu_s": self.cpu_s,
            "max_invariant_drift": self.max_invariant_drift if math.isfinite(self.max_invariant_drift) else None,
            "status": self.status,
            "message": self.message,
        }
        if self.accuracy is not None:
            out["stats"].update(
                {k: (None if isinstance(v, float) and not math.isfinite(v) else v) for k, v in self.accuracy.items()}
            )
        if self.integrator is not None:
            out["stats"]["integrator"] = self.integrator
        if self.initial_conditions is not None:
            out["stats"]["initial_conditions"] = self.initial_conditions
        return out


def json_values(values: np.ndarray) -> list[float | None]:
    """A float array as a JSON list, with non-finite entries as null."""
    array = np.asarray(values, dtype=float)
    return [float(v) if math.isfinite(v) else None for v in array.tolist()]
