"""Integrated models: the :class:`~app.physics.core.model.Model` contract for motion found by stepping.

An :class:`IntegratedModel` says what to integrate (its compiled system and
initial state), how fast it moves (the automatic step's starting guess), what a
student reads off it (named series), what it conserves (named invariants with
the scale their drift is measured against) and, where it states one, the error
its default must meet (:mod:`.step_choice`) and the reference it is checked
against. Its :meth:`~IntegratedModel.simulate` runs it with the integrator the
step policy (:mod:`.step_policy`) takes for the controls and reports series,
invariants, counters and the accuracy reached.
"""

from __future__ import annotations

import math
import time
from abc import abstractmethod
from collections.abc import Hashable, Mapping
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from app.physics.core.energy import EnergyParts, energy_budget
from app.physics.core.model import Model
from app.physics.core.parameters import Parameter, ParameterError
from app.physics.core.report import (
    MAX_ADAPTIVE_STEPS,
    MAX_FIXED_STEP_WORK,
    SimulationReport,
    frame_times,
)
from app.physics.solvers.base import EventRecord, FixedStepIntegrator
from app.physics.solvers.controls import integration_parameters
from app.physics.solvers.dormand_prince import DormandPrince
from app.physics.solvers.solve import failure_message, simulate
from app.physics.solvers.step_choice import EXACT_FALLBACK, REDUCED_ACCURACY, TARGET_MISSED, AccuracyTarget, StepChoice
from app.physics.solvers.step_policy import choose_integrator
from app.physics.solvers.system import OdeSystem

__all__ = ["IntegratedModel", "ModelLimit", "SimulationReport", "check_request_bounds"]


@dataclass(frozen=True)
class ModelLimit:
    """Where a motion leaves what its model describes: the frames kept, the answer's status and the student's
    message."""

    #: How many leading frames the model still describes (at least 1: the start is always kept, and shown).
    frames: int
    #: ``stats.status`` (a word such as ``lift_off``; never "ok").
    status: str
    #: What a student reads, with the time and the quantity that broke the model, in units.
    message: str

    def __post_init__(self) -> None:
        if self.frames < 1 or self.status in ("", "ok"):
            raise ValueError(
                f"a model limit keeps at least one frame and names a status other than ok (got {self.frames}, "
                f"{self.status!r})"
            )


class IntegratedModel(Model):
    """A model whose motion is found by numerical integration."""

    integrated = True
    how_computed = "integrates its model"
    #: Methods a student may pick; ``auto`` means the cheapest of them at the accuracy target
    #: (``default_method`` when the model states no target, and in the method menu's text).
    methods: ClassVar[tuple[str, ...]]
    default_method: ClassVar[str]
    #: The error the automatic choice must meet, measured by :meth:`solution_error`; None: the
    #: fixed ratio h·ω_max ≤ the method's ``step_ratio`` (a model that states no target).
    accuracy_target: ClassVar[AccuracyTarget | None] = None
    #: Methods ``auto`` chooses among at the target (None: all of :attr:`methods`); a model whose simulate answer
    #: names its method in a contract keeps ``auto`` to that one and only chooses its step.
    auto_methods: ClassVar[tuple[str, ...] | None] = None
    #: State components the default :meth:`solution_error` compares (None: all); the motion's own
    #: coordinates and rates, not bookkeeping slots (counters, modes, accumulated work).
    accuracy_components: ClassVar[tuple[int, ...] | None] = None
    #: Name of the series reporting the error against :meth:`reference_states` (e.g. ``attitude_error_rad``),
    #: and what that reference is; empty for a model without one.
    reference_error_series: ClassVar[str] = ""
    reference_name: ClassVar[str] = ""

    @classmethod
    def controls(cls) -> tuple[Parameter, ...]:
        return integration_parameters(
            cls.methods, default_method=cls.default_method, target=cls.accuracy_target, auto_methods=cls.auto_methods
        )

    def integration_controls(self, params: Mapping[str, Any], controls: Mapping[str, Any]) -> Mapping[str, Any]:
        """The integrator's controls (``method``, ``steps_per_frame``, ``rtol``) in ``controls``: the step policy
        asks this first, and a model with controls of its own (a constrained model's DAE algorithm) takes them here."""
        return controls

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

    def energy_parts(
        self, params: Mapping[str, Any], states: np.ndarray, *, t_s: np.ndarray | None = None
    ) -> EnergyParts | None:
        """The model's energies (J) along ``states`` (N, n) at ``t_s`` (N,; None: the energies do not depend on t);
        None for a model that states none."""
        return None

    def energy_budget(
        self, params: Mapping[str, Any], states: np.ndarray, *, t_s: np.ndarray | None = None
    ) -> dict[str, np.ndarray] | None:
        """Named energies (J, arrays (N,)) along ``states`` (N, n): ``translational_kinetic_J`` and
        ``rotational_kinetic_J`` (or ``kinetic_J``), ``potential_J``, ``total_J`` and ``dissipated_J`` (energy removed
        since t = 0, drive work counted; see :mod:`app.physics.core.energy`). None for a model without energies."""
        states = np.atleast_2d(np.asarray(states, dtype=float))
        parts = self.energy_parts(params, states, t_s=t_s)
        if parts is None:
            return None
        start = self.energy_parts(params, self.initial_state(params)[None, :], t_s=None if t_s is None else np.zeros(1))
        assert start is not None
        return energy_budget(parts, start)

    def energy_note(self, params: Mapping[str, Any]) -> str | None:
        """What the energy budget leaves out or assumes, in words (a drive whose work is not tracked, a reduced
        model's missing energy); None when it is complete."""
        return None

    def solution_error(self, params: Mapping[str, Any], states: np.ndarray, reference: np.ndarray) -> np.ndarray:
        """(N,) error of ``states`` (N, n) against ``reference`` (N, n) in :attr:`accuracy_target`'s unit.

        By default the largest difference of the :attr:`accuracy_components` relative to the largest of them in the
        reference state (dimensionless).
        """
        states, reference = np.asarray(states, dtype=float), np.asarray(reference, dtype=float)
        if self.accuracy_components is not None:
            states, reference = states[:, self.accuracy_components], reference[:, self.accuracy_components]
        scale = np.maximum(np.max(np.abs(reference), axis=1), 1e-300)
        return np.max(np.abs(states - reference), axis=1) / scale

    def reference_states(self, params: Mapping[str, Any], t_s: np.ndarray) -> np.ndarray | None:
        """States (N, n) of an exact (or independent, tight) solution at times ``t_s`` (N,), or None if there is
        none."""
        return None

    def starting_rate_rad_s(self, params: Mapping[str, Any]) -> float:
        """The fastest rate (rad/s) at the initial state: the fixed step rule's, and the pilots' first step."""
        return self.fastest_rate_rad_s(params, self.initial_state(params))

    def pilot_key(self, params: Mapping[str, Any]) -> Hashable:
        """Key under which the step choice's pilot is cached: the model and its parameter values."""
        values = tuple(
            sorted(
                (k, tuple(np.ravel(v).tolist()) if isinstance(v, (list, tuple, np.ndarray)) else v)
                for k, v in params.items()
            )
        )
        return (type(self).__module__, type(self).__qualname__, values)

    def describable(self, params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
        """(N,) bool: whether the model can describe each of ``states`` (N, n); by default, every component finite.

        A model whose state has more structure (a unit quaternion) refuses states
        that are finite but have lost it, as a run that blew up leaves them.
        """
        return np.all(np.isfinite(states), axis=1)

    def model_limit(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> ModelLimit | None:
        """Where along the frames ``states`` (N, n) at ``t_s`` (N,) the model's own assumptions stop holding (a disk
        whose floor would have to pull, a mass matrix gone singular), or None while they hold. The simulate answer
        and the live scene both stop there with the limit's status and message."""
        return None

    def stop_message(self, params: Mapping[str, Any], event: EventRecord) -> str:
        """Why a terminal ``event`` stopped the run, in words for the answer's ``message`` ("": the generic text)."""
        return ""

    def relative_drift(self, params: Mapping[str, Any], states: np.ndarray) -> dict[str, np.ndarray]:
        """Per invariant, |I(t) − I(0)| / scale along ``states`` (dimensionless)."""
        scales = self.invariant_scales(params, states[0])
        values = self.invariants(params, states)
        return {name: np.abs(v - v[0]) / scales[name] for name, v in values.items()}

    def reference_error(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> np.ndarray | None:
        """(N,) error of ``states`` against the reference at ``t_s`` (target's unit), or None without a reference."""
        if not self.reference_error_series:
            return None
        try:
            reference = self.reference_states(params, t_s)
        except ValueError:  # a motion the reference cannot represent
            return None
        if reference is None:
            return None
        return np.asarray(self.solution_error(params, states, reference), dtype=float)

    def simulate(
        self,
        params: Mapping[str, Any],
        controls: Mapping[str, Any],
        *,
        t_end_s: float,
        frame_rate_hz: float,
        request_limits: bool = True,
    ) -> SimulationReport:
        """Integrate for ``t_end_s`` and sample at ``frame_rate_hz`` (t = 0 included).

        ``request_limits`` applies the per-request bounds (:func:`check_request_bounds`). Automatic
        steps meet the model's accuracy target over ``t_end_s``; where that would
        exceed the bounds, the model's exact solution answers if it has one
        (status :data:`~.step_choice.EXACT_FALLBACK`), else the most work allowed
        runs with its estimated error stated (status :data:`~.step_choice.REDUCED_ACCURACY`).
        Explicit steps over the bounds are refused, naming the limit.
        """
        if request_limits:
            frame_times(
                t_end_s=t_end_s, frame_rate_hz=frame_rate_hz
            )  # span and rate checked before anything divides by them
        run = _integrate(
            self, params, controls, t_end_s=t_end_s, frame_rate_hz=frame_rate_hz, request_limits=request_limits
        )
        if isinstance(run, SimulationReport):
            return run
        integrator, choice, result = run
        limit = self.model_limit(params, result.t_s, result.states)
        if (
            limit is not None
            and limit.frames > 1
            and choice is not None
            and _automatic(controls)
            and limit.frames < len(result.t_s)
        ):
            # The automatic step was chosen over the whole span, its pilots run through where the model broke (which can
            # look like chaos, or need a far smaller step): choose again over the span the model describes.
            again = _integrate(
                self,
                params,
                controls,
                t_end_s=float(result.t_s[limit.frames - 1]),
                frame_rate_hz=frame_rate_hz,
                request_limits=request_limits,
            )
            if not isinstance(again, SimulationReport) and len(again[2].t_s) == limit.frames:
                integrator, choice, result = again
                limit = self.model_limit(params, result.t_s, result.states) or limit
        if limit is not None:
            result = result.truncated(min(limit.frames, len(result.t_s)), status=limit.status, message=limit.message)
        status, message = result.status, result.message
        if status == "event" and result.events:
            message = self.stop_message(params, result.events[-1]) or message
        if choice is not None and choice.status in (REDUCED_ACCURACY, TARGET_MISSED):
            note = f"{choice.note[0].upper()}{choice.note[1:]}."
            status, message = (choice.status, note) if status == "ok" else (status, f"{message} {note}")
        return _report(
            self,
            params,
            result.t_s,
            result.states,
            choice=choice,
            method=result.method,
            description=result.description,
            steps=result.steps,
            rhs_evals=result.rhs_evals,
            cpu_s=result.cpu_s,
            status=status,
            message=message,
        )


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


def _automatic(controls: Mapping[str, Any]) -> bool:
    """Whether the controls leave the step to the automatic choice (no steps per frame set by hand)."""
    return int(controls.get("steps_per_frame", 0) or 0) == 0


def _integrate(model: IntegratedModel, params, controls, *, t_end_s: float, frame_rate_hz: float, request_limits: bool):
    """``(integrator, choice, result)`` of the run over ``t_end_s``, its blow-up cut off; or the exact fallback's
    report."""
    frame_dt = 1.0 / frame_rate_hz
    integrator, choice = choose_integrator(
        model,
        params,
        controls,
        frame_dt,
        horizon_s=t_end_s,
        max_fixed_work=MAX_FIXED_STEP_WORK if request_limits else None,
        max_adaptive_steps=MAX_ADAPTIVE_STEPS if request_limits else math.inf,
    )
    if choice is not None and choice.status == REDUCED_ACCURACY:
        exact = _exact_report(model, params, t_end_s=t_end_s, frame_rate_hz=frame_rate_hz, choice=choice)
        if exact is not None:
            return exact
    if request_limits:
        check_request_bounds(integrator, t_end_s=t_end_s, frame_rate_hz=frame_rate_hz)
    system = model.system(params)
    result = simulate(system, integrator, model.initial_state(params), t_end_s=t_end_s, frame_rate_hz=frame_rate_hz)
    describable = model.describable(params, result.states)
    if not describable.all():  # blew up while staying finite (e.g. an overflowed norm zeroed the quaternion)
        frames = max(int(np.argmin(describable)), 1)
        t_stop = float(result.t_s[frames - 1])
        result = result.truncated(
            frames,
            status="non_finite",
            message=failure_message("non_finite", t_stop, integrator, frame_dt, system=system),
        )
    return integrator, choice, result


def _report(
    model: IntegratedModel, params, t_s: np.ndarray, states: np.ndarray, *, choice: StepChoice | None, **stats
) -> SimulationReport:
    """Series, invariants, drift and the accuracy of ``states`` (N, n) at ``t_s`` (N,)."""
    with np.errstate(over="ignore", invalid="ignore"):
        drift = model.relative_drift(params, states)
    max_drift = max((float(d.max()) for d in drift.values()), default=0.0)
    series = model.series(params, t_s, states)
    reference_error = model.reference_error(params, t_s, states)
    if reference_error is not None:
        series[model.reference_error_series] = reference_error
    accuracy = choice.as_dict() if choice is not None else {}
    if reference_error is not None:
        accuracy["max_reference_error"] = (
            float(np.max(reference_error)) if np.all(np.isfinite(reference_error)) else None
        )
        accuracy["reference"] = model.reference_name
    return SimulationReport(
        t_s=t_s,
        series=series,
        invariants=model.invariants(params, states),
        max_invariant_drift=max_drift,
        accuracy=accuracy or None,
        **stats,
    )


def _exact_report(
    model: IntegratedModel, params, *, t_end_s: float, frame_rate_hz: float, choice: StepChoice
) -> SimulationReport | None:
    """The model's exact solution at the frame times, when it has one (else None)."""
    start = time.thread_time()
    try:  # (a ParameterError is a ValueError: a span beyond the request limits has no exact answer here either)
        t_s = frame_times(t_end_s=t_end_s, frame_rate_hz=frame_rate_hz)
        states = model.reference_states(params, t_s)
    except ValueError:
        return None
    cpu_s = time.thread_time() - start
    if states is None or not np.all(np.isfinite(states)):
        return None
    message = (
        f"The automatic step for {choice.method} would exceed the request limit (it would run at "
        f"~{choice.target.format(choice.estimated_error)} instead of {choice.target.format(choice.target.error)}), "
        f"so the exact solution answers instead: {model.reference_name}."
    )
    exact_choice = StepChoice(
        "exact",
        None,
        None,
        choice.target,
        choice.horizon_s,
        choice.frame_dt_s,
        0.0,
        0.0,
    )
    return _report(
        model,
        params,
        t_s,
        states,
        choice=exact_choice,
        method="exact",
        description=model.reference_name,
        steps=0,
        rhs_evals=0,
        cpu_s=cpu_s,
        status=EXACT_FALLBACK,
        message=message,
    )
