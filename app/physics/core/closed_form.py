"""Models whose motion is a closed form in time: evaluated, never integrated.

A :class:`ClosedFormModel` keeps the :class:`~app.physics.core.model.Model`
contract by evaluating its series and invariants at any array of times: its
:meth:`~ClosedFormModel.simulate` samples them on the same frame grid as an
integrated model and returns the same report shape (``t``, ``series``,
``invariants``, ``stats``), with ``stats.method`` ``"closed-form"`` and zero steps.
Singular instants the formula passes through (a linkage's toggle position, say)
are reported as :class:`Event`\\ s rather than crossed silently. It has no
controls: a request that sets an integrator's is refused.
"""

from __future__ import annotations

import time
from abc import abstractmethod
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from app.physics.core.model import Model
from app.physics.core.parameters import ParameterError
from app.physics.core.report import Event, SimulationReport, frame_times

__all__ = ["OUTSIDE_MODEL", "ClosedFormModel", "ClosedFormSolution", "Event", "frame_times"]

#: ``stats.status`` of a result that is finite but outside the model's assumptions (``message`` says which).
OUTSIDE_MODEL = "outside_model"
#: Control values that ask for nothing (what a page or a script sends for an integrator left alone).
_NO_CONTROL = (None, "auto", "closed-form", 0)


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


class ClosedFormModel(Model):
    """A model evaluated from a formula at any time (no integration)."""

    #: What the formula is, for the report (e.g. "Jacobi elliptic functions").
    description: ClassVar[str]
    how_computed = "evaluates its model's formula (no integration)"

    @abstractmethod
    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        """Series and invariants at times ``t_s`` (s, 1-D array starting at 0)."""

    def invariant_scales(self, params: Mapping[str, Any], invariants: Mapping[str, np.ndarray]) -> dict[str, float]:
        """Scale per invariant for the drift report (default: its initial magnitude, at least 1e-300)."""
        return {name: max(abs(float(values[0])), 1e-300) for name, values in invariants.items()}

    @classmethod
    def validate_controls(cls, controls: Mapping[str, Any]) -> dict[str, Any]:
        """No controls: ParameterError naming the first control set to anything but "leave it" (auto, 0)."""
        for name, value in controls.items():
            if value not in _NO_CONTROL:  # (the label starts the text a student reads: the reason, then the refusal)
                reason = "this scene's motion is a closed form in time"
                raise ParameterError(name, "there is no integrator to control", label=reason)
        return {}

    def simulate(
        self,
        params: Mapping[str, Any],
        controls: Mapping[str, Any],
        *,
        t_end_s: float,
        frame_rate_hz: float,
        request_limits: bool = True,
    ) -> SimulationReport:
        """The formula at the frame times (the span and frame bounds always apply: the frames are a formula's only
        cost, so ``request_limits`` changes nothing)."""
        t_s = frame_times(t_end_s=t_end_s, frame_rate_hz=frame_rate_hz)
        start = time.thread_time()
        solution = self.evaluate(params, t_s)
        cpu_s = time.thread_time() - start
        scales = self.invariant_scales(params, solution.invariants)
        drift = [float(np.max(np.abs(v - v[0])) / scales[k]) for k, v in solution.invariants.items()]
        finite = all(np.all(np.isfinite(v)) for v in (*solution.series.values(), *solution.invariants.values()))
        undefined = "" if finite else "the formula is undefined at some frames (see events)"
        return SimulationReport(
            t_s=t_s,
            series=solution.series,
            invariants=solution.invariants,
            events=list(solution.events),
            method="closed-form",
            description=self.description,
            steps=0,
            rhs_evals=0,
            cpu_s=cpu_s,
            max_invariant_drift=max(drift, default=0.0),
            status="undefined" if not finite else OUTSIDE_MODEL if solution.warning else "ok",
            message=" ".join(m for m in (undefined, solution.warning) if m),
        )
