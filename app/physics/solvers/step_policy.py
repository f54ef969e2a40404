"""The step policy: which integrator, at which step, answers an integrated model's controls.

The model is the problem (what to integrate, its error measure and accuracy
target, the methods it allows); the integrators are the solvers; this module is
the controller that joins them, as diffrax keeps the step-size controller apart
from the solver and the term. With explicit controls it builds the integrator
asked for (and, where the model states a target, estimates its error); with
automatic steps it runs (or reuses) the pilots of :mod:`.step_choice` and takes
the cheapest setting meeting the target within a request's or a live frame's
limits.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import replace
from typing import TYPE_CHECKING, Any, TypedDict, cast

from app.physics.solvers.base import FixedStepIntegrator, Integrator
from app.physics.solvers.controls import AUTO, integrator_from_controls
from app.physics.solvers.registry import METHODS, make_integrator
from app.physics.solvers.step_choice import (
    REDUCED_ACCURACY,
    TARGET_MISSED,
    AccuracyTarget,
    PilotPending,
    StepChoice,
    choose,
    error_model,
    usable_methods,
)

if TYPE_CHECKING:
    from app.physics.solvers.dormand_prince import DormandPrince
    from app.physics.solvers.integrated_model import IntegratedModel

__all__ = ["choose_integrator"]


class _Setting(TypedDict):
    """A method's setting as :class:`StepChoice` takes it: steps per frame (fixed step) or ``rtol`` (adaptive)."""

    steps_per_frame: int | None
    rtol: float | None


def choose_integrator(
    model: IntegratedModel,
    params: Mapping[str, Any],
    controls: Mapping[str, Any],
    frame_dt_s: float,
    *,
    horizon_s: float | None = None,
    max_fixed_work: int | None = None,
    max_adaptive_steps: float = math.inf,
    run_pilots: bool = True,
    max_frame_cpu_s: float = math.inf,
) -> tuple[Integrator, StepChoice | None]:
    """The integrator ``model``'s ``controls`` ask for, and the step choice behind it (None without an accuracy target).

    The model first takes the controls that are its own (:meth:`IntegratedModel.integration_controls`: a constrained
    model's DAE algorithm). With automatic steps (``steps_per_frame`` 0) and a target, each candidate
    method (``auto``: every usable method of the model's ``methods``) gets the fewest
    steps meeting the target over ``horizon_s`` (default: the target's), and
    ``auto`` takes the cheapest. ``max_fixed_work`` (sub-steps over the
    horizon) and ``max_adaptive_steps`` are a request's limits: a choice
    that would exceed them is capped, its lowered accuracy stated, as is one over a
    live scene's physics budget per frame ``max_frame_cpu_s`` (s).

    ``run_pilots=False`` (a live restart, which must not wait): where a pilot
    is not cached yet, the fixed-ratio integrator with a choice of status
    :data:`~.step_choice.ESTIMATING`; the same call with pilots (in the
    background) then gives the measured one.
    """
    controls = model.integration_controls(params, controls)
    target = model.accuracy_target
    steps = int(controls.get("steps_per_frame", 0) or 0)
    method = controls.get("method", AUTO)
    y0 = model.initial_state(params)
    rate = model.starting_rate_rad_s(params)
    explicit_adaptive = method != AUTO and method in model.methods and _is_adaptive(method)
    if (
        method == AUTO
        and _is_adaptive(model.default_method)
        and controls.get("rtol") not in (None, _default_rtol(model))
    ):
        explicit_adaptive = True  # a tolerance set by hand for a model whose default method is adaptive
    ratio_rule = integrator_from_controls(
        controls, default_method=model.default_method, fastest_rate_rad_s=rate, frame_dt_s=frame_dt_s
    )
    if target is None:
        return ratio_rule, None
    horizon = target.horizon_s if horizon_s is None else horizon_s
    try:
        if steps > 0 or explicit_adaptive:
            return ratio_rule, _estimate_for(model, params, ratio_rule, frame_dt_s, horizon, run_pilot=run_pilots)
        chosen = choose(
            model.system(params),
            y0,
            (model.auto_methods or model.methods) if method == AUTO else (method,),
            target=target,
            frame_dt_s=frame_dt_s,
            horizon_s=horizon,
            fastest_rate_rad_s=rate,
            error=lambda a, b: model.solution_error(params, a, b),
            cache_key=model.pilot_key(params),
            max_fixed_work=max_fixed_work,
            max_adaptive_steps=max_adaptive_steps,
            run_pilots=run_pilots,
            max_frame_cpu_s=max_frame_cpu_s,
        )
    except PilotPending:
        fixed = isinstance(ratio_rule, FixedStepIntegrator)
        return ratio_rule, StepChoice.pending(
            ratio_rule.name,
            cast(FixedStepIntegrator, ratio_rule).steps_per_frame if fixed else None,
            None if fixed else cast("DormandPrince", ratio_rule).rtol,
            target,
            horizon_s=horizon,
            frame_dt_s=frame_dt_s,
        )
    if chosen is None:  # no pilot finished: every run blew up or ran out of steps
        return _unmeasured(model, controls, target, rate, frame_dt_s, horizon, max_fixed_work)
    integrator = make_integrator(chosen.method, steps_per_frame=chosen.steps_per_frame, rtol=chosen.rtol)
    return integrator, chosen


def _unmeasured(
    model: IntegratedModel,
    controls: Mapping[str, Any],
    target: AccuracyTarget,
    rate: float,
    frame_dt_s: float,
    horizon_s: float,
    max_fixed_work: int | None,
) -> tuple[Integrator, StepChoice]:
    """No pilot finished (a motion too stiff or too fast for every method): the fixed ratio, capped by the
    request limit, with the error stated as unknown; the run itself then says where it stopped."""
    integrator = integrator_from_controls(
        controls, default_method=model.default_method, fastest_rate_rad_s=rate, frame_dt_s=frame_dt_s
    )
    note = (
        "no pilot run of any method finished (the motion is too stiff "
        "or too fast for the steps tried), so the error is unknown"
    )
    if isinstance(integrator, FixedStepIntegrator) and max_fixed_work is not None:
        cap = max(
            int(max_fixed_work // max(math.ceil(horizon_s / frame_dt_s) * integrator.spec.substeps_per_step, 1)), 1
        )
        if integrator.steps_per_frame > cap:
            integrator = make_integrator(integrator.name, steps_per_frame=cap)
            note += f"; {cap} steps/frame is the most the request limit of {max_fixed_work} sub-steps allows"
    setting = (
        dict(steps_per_frame=integrator.steps_per_frame, rtol=None)
        if isinstance(integrator, FixedStepIntegrator)
        else dict(steps_per_frame=None, rtol=cast("DormandPrince", integrator).rtol)
    )
    return integrator, StepChoice(
        integrator.name,
        target=target,
        horizon_s=horizon_s,
        frame_dt_s=frame_dt_s,
        estimated_error=math.nan,
        cost_s=math.nan,
        status=REDUCED_ACCURACY,
        note=note,
        **setting,
    )


def _estimate_for(
    model: IntegratedModel,
    params: Mapping[str, Any],
    integrator: Integrator,
    frame_dt_s: float,
    horizon: float,
    *,
    run_pilot: bool,
) -> StepChoice | None:
    """The estimated error of a setting the student chose (from the same cached pilot as the automatic choice)."""
    target = model.accuracy_target
    assert target is not None
    spec = integrator.spec
    system = model.system(params)
    if not usable_methods(system, (spec.name,)):
        return None
    y0 = model.initial_state(params)
    start = spec.automatic_steps_per_frame(model.starting_rate_rad_s(params), frame_dt_s) if not spec.adaptive else 1
    errors = error_model(
        system,
        y0,
        spec,
        target=target,
        start_steps=start,
        frame_dt_s=frame_dt_s,
        error=lambda a, b: model.solution_error(params, a, b),
        cache_key=model.pilot_key(params),
        run_pilot=run_pilot,
        horizon_s=horizon,
    )
    if errors is None:
        return None
    if spec.adaptive:
        rtol = cast("DormandPrince", integrator).rtol
        setting = _Setting(steps_per_frame=None, rtol=rtol)
        error = errors.error_adaptive(rtol, horizon)
    else:
        steps_per_frame = cast(FixedStepIntegrator, integrator).steps_per_frame
        setting = _Setting(steps_per_frame=steps_per_frame, rtol=None)
        error = errors.error_fixed(frame_dt_s / steps_per_frame, horizon)
    chosen = StepChoice(
        spec.name,
        target=target,
        horizon_s=horizon,
        frame_dt_s=frame_dt_s,
        estimated_error=error,
        cost_s=math.nan,
        **setting,
    )
    if chosen.meets_target:
        return chosen
    note = (
        f"the chosen setting misses the target of {target.format(target.error)} over {horizon:g} s: estimated "
        f"{target.format(error)} (automatic steps meet it)"
    )
    return replace(chosen, status=TARGET_MISSED, note=note)


def _default_rtol(model: IntegratedModel) -> float | None:
    """The ``rtol`` control's default value (what validated controls carry when no one set it)."""
    return next((cast(float, c.default) for c in model.controls() if c.name == "rtol"), None)


def _is_adaptive(method: str) -> bool:
    spec = METHODS.get(method)
    return spec is not None and spec.adaptive
