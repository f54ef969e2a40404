"""Integrated models and the simulation report the API and the scenes share.

An :class:`IntegratedModel` says what to integrate (its compiled system and
initial state), how fast it moves (for the automatic step), what a student
reads off it (named series) and what it conserves (named invariants with the
scale their drift is measured against). :func:`simulate_model` runs one with
the integration controls and reports series, invariants and counters.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Mapping
from typing import Any, ClassVar

import numpy as np

from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.core.report import MAX_ADAPTIVE_STEPS, MAX_FIXED_STEP_WORK, SimulationReport, frame_times
from app.physics.solvers.base import FixedStepIntegrator
from app.physics.solvers.controls import integration_parameters, integrator_from_controls
from app.physics.solvers.dormand_prince import DormandPrince
from app.physics.solvers.solve import failure_message, simulate
from app.physics.solvers.system import OdeSystem

__all__ = ["IntegratedModel", "SimulationReport", "check_request_bounds", "simulate_model"]


class IntegratedModel(ABC):
    """A model whose motion is found by numerical integration."""

    #: Physical parameters (names are API contracts).
    parameters: ClassVar[ParameterSet]
    #: Methods a student may pick, and the one ``auto`` means.
    methods: ClassVar[tuple[str, ...]]
    default_method: ClassVar[str]
    #: Unit of each series, by name.
    series_units: ClassVar[Mapping[str, str]]
    invariant_units: ClassVar[Mapping[str, str]]

    @classmethod
    def controls(cls) -> tuple[Parameter, ...]:
        return integration_parameters(cls.methods, default_method=cls.default_method)

    @abstractmethod
    def system(self, params: Mapping[str, Any]) -> OdeSystem: ...

    @abstractmethod
    def initial_state(self, params: Mapping[str, Any]) -> np.ndarray: ...

    @abstractmethod
    def fastest_rate_rad_s(self, params: Mapping[str, Any], state: np.ndarray) -> float: ...

    @abstractmethod
    def series(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> dict[str, np.ndarray]: ...

    @abstractmethod
    def invariants(self, params: Mapping[str, Any], states: np.ndarray) -> dict[str, np.ndarray]: ...

    @abstractmethod
    def invariant_scales(self, params: Mapping[str, Any], state: np.ndarray) -> dict[str, float]:
        """Positive scale per invariant: drift is reported as |I(t) − I(0)| / scale."""

    def integrator(self, params: Mapping[str, Any], controls: Mapping[str, Any], frame_dt_s: float):
        y0 = self.initial_state(params)
        return integrator_from_controls(
            controls, default_method=self.default_method,
            fastest_rate_rad_s=self.fastest_rate_rad_s(params, y0), frame_dt_s=frame_dt_s,
        )

    def describable(self, params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
        """(N,) bool: whether the model can describe each of ``states`` (N, n); by default, every component finite.

        A model whose state has more structure (a unit quaternion) refuses states
        that are finite but have lost it, as a run that blew up leaves them.
        """
        return np.all(np.isfinite(states), axis=1)

    def relative_drift(self, params: Mapping[str, Any], states: np.ndarray) -> dict[str, np.ndarray]:
        """Per invariant, |I(t) − I(0)| / scale along ``states`` (dimensionless)."""
        scales = self.invariant_scales(params, states[0])
        values = self.invariants(params, states)
        return {name: np.abs(v - v[0]) / scales[name] for name, v in values.items()}


def check_request_bounds(integrator, *, t_end_s: float, frame_rate_hz: float) -> None:
    """Raise ParameterError naming the limit a request exceeds (before any work is done)."""
    frames = len(frame_times(t_end_s=t_end_s, frame_rate_hz=frame_rate_hz)) - 1
    if isinstance(integrator, FixedStepIntegrator):
        substeps = integrator.spec.substeps_per_step
        work = frames * integrator.steps_per_frame * substeps
        if work > MAX_FIXED_STEP_WORK:
            raise ParameterError(
                "steps_per_frame",
                f"{frames} frames × {integrator.steps_per_frame} steps/frame × {substeps} sub-steps = {work} exceeds "
                f"the limit of {MAX_FIXED_STEP_WORK} (shorten t_end or use fewer steps per frame)",
            )
    elif isinstance(integrator, DormandPrince):
        integrator.max_steps = MAX_ADAPTIVE_STEPS


def simulate_model(
    model: IntegratedModel,
    params: Mapping[str, Any],
    controls: Mapping[str, Any],
    *,
    t_end_s: float,
    frame_rate_hz: float,
    request_limits: bool = True,
) -> SimulationReport:
    """Integrate ``model`` for ``t_end_s`` and sample it at ``frame_rate_hz`` (t = 0 included).

    ``request_limits`` applies the per-request bounds (:func:`check_request_bounds`);
    tests and benchmarks that need longer or denser runs switch it off.
    """
    if request_limits:
        frame_times(t_end_s=t_end_s, frame_rate_hz=frame_rate_hz)  # span and rate checked before anything divides by them
    frame_dt = 1.0 / frame_rate_hz
    integrator = model.integrator(params, controls, frame_dt)
    if request_limits:
        check_request_bounds(integrator, t_end_s=t_end_s, frame_rate_hz=frame_rate_hz)
    result = simulate(model.system(params), integrator, model.initial_state(params), t_end_s=t_end_s, frame_rate_hz=frame_rate_hz)
    describable = model.describable(params, result.states)
    if not describable.all():  # blew up while staying finite (e.g. an overflowed norm zeroed the quaternion)
        frames = max(int(np.argmin(describable)), 1)
        t_stop = float(result.t_s[frames - 1])
        result = result.truncated(frames, status="non_finite", message=failure_message("non_finite", t_stop, integrator, frame_dt))
    with np.errstate(over="ignore", invalid="ignore"):
        drift = model.relative_drift(params, result.states)
    max_drift = max((float(d.max()) for d in drift.values()), default=0.0)
    return SimulationReport(
        t_s=result.t_s,
        series=model.series(params, result.t_s, result.states),
        invariants=model.invariants(params, result.states),
        method=result.method,
        description=result.description,
        steps=result.steps,
        rhs_evals=result.rhs_evals,
        cpu_s=result.cpu_s,
        max_invariant_drift=max_drift,
        status=result.status,
        message=result.message,
    )
