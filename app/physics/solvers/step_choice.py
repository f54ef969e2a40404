"""Steps chosen to meet a stated error over a horizon at least cost, from a measured error constant.

A method of order ``p`` has a global error ``E(h, T) ≈ C h^p g(T)``. A *pilot*
integrates the model twice over a short span, with ``n`` and ``2n`` steps per
frame; the difference of the two runs divided by ``1 − 2^−p`` estimates the
error of the ``n``-step run (Richardson), measured by the model's own error
measure (an angle in rad, or a relative error) at every frame. The pilot covers
the horizon asked for (at least :data:`PILOT_SPAN_S` of it, more as
:data:`PILOT_WORK` allows, all within :data:`PILOT_CPU_S`), so the growth of the
error is measured, not assumed; its running largest value is kept (the *error
curve*). While the curve is small (below :data:`LINEAR_LIMIT`, where the error is
still proportional to ``h^p``) it is used as measured. If it grows faster than
``t⁴`` there, the motion is chaotic: beyond that point it is extended as the
exponential it is (rate fitted on the curve), and where no setting within the
limits meets the target over the horizon the choice states the shorter horizon,
within the measured curve, over which it does (the predictability horizon).
Otherwise the growth ``g(T) = (T / T_pilot)^γ`` beyond the measured part assumes:

* geometric methods: ``γ = 1`` (their energy error stays bounded, so what grows
  is the phase error, linearly in time);
* other methods: at least ``γ = 2`` (a quadratic error driven by a linear
  energy drift: a pilot shorter than the horizon cannot rule it out, and a
  measured ``γ = 1`` extrapolated from a few seconds to a minute undershot a
  constrained linkage's error tenfold), the measured one where larger, up to 4;
  and a pilot cut shorter than :data:`PILOT_SPAN_S` by its CPU budget is not
  extrapolated at all: the target is stated over the span it measured.

From that constant the fewest steps per frame (or the loosest ``rtol`` for an
adaptive method, ``E ∝ rtol^(p/(p+1))``) meeting half the target over the
horizon is chosen (half: a margin for the estimate's own error), and among the
methods a model allows the cheapest at the target, by the CPU time per step
measured in the pilot. Pilot results are cached per (model, parameters,
method) and bounded in work (:data:`PILOT_WORK`) and in CPU time
(:data:`PILOT_CPU_S`, which shortens a costly model's span). A caller that must not wait
for a pilot (a live scene's restart) asks with ``run_pilots=False``: a cache
miss then raises :class:`PilotPending` instead of measuring, and the caller
runs the pilot elsewhere.
"""

from __future__ import annotations

import math
import threading
import time
from collections import Counter, OrderedDict
from collections.abc import Callable, Hashable, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, TypedDict, cast

import numpy as np

from app.physics.solvers.registry import METHODS
from app.physics.solvers.solve import simulate
from app.physics.solvers.spec import MAX_STEPS_PER_FRAME, MethodSpec
from app.physics.solvers.system import OdeSystem

if TYPE_CHECKING:
    from app.physics.solvers.dormand_prince import DormandPrince

#: Horizon (s) over which a live scene's default meets its target: what a student watches.
DEFAULT_HORIZON_S = 60.0
#: Span (s) of simulated time a pilot covers whatever PILOT_WORK says (CPU allowing); a shorter one is not
#: extrapolated beyond itself.
PILOT_SPAN_S = 10.0
#: Largest error (in the target's unit) up to which a pilot's error is taken to scale with h^p: beyond it the
#: difference of two runs no longer measures the error of one (a chaotic motion's runs have parted).
LINEAR_LIMIT = 1e-3
#: Points kept of a pilot's error curve.
CURVE_POINTS = 200
#: Growth of the error over the second half of its measured curve beyond which the motion is called chaotic (2⁴).
CHAOTIC_GROWTH = 16.0
#: Shortest pilot span, in frames (a shorter one cannot show growth).
PILOT_MIN_FRAMES = 20
#: Most sub-steps (frames × steps/frame × sub-steps/step) one pilot pair may take, both runs together.
PILOT_WORK = 150_000
#: Pilot pairs tried per method (each re-pilots at the step the last one asked for).
MAX_PILOTS = 4
#: CPU time (s) one method's pilots may take in all: a short calibration run measures the cost per frame and a
#: costly system (a constrained one, say) gets a shorter span, extrapolated by the growth law beyond it.
PILOT_CPU_S = 1.0
#: CPU time a pilot's calibration measures at least (s), unless that would take a quarter of its budget.
CALIBRATION_CPU_S = 0.02
#: The choice aims at this fraction of the target (margin for the estimate's own error).
SAFETY = 0.5
#: Tolerance range an adaptive choice may use, and the tolerance its pilot starts from. Never looser than the
#: fixed rule's 1e-8: events are located, and invariants such as an energy budget kept, only to the tolerance,
#: which the state error at frame times does not see (a belt's energy budget drifted 2e-8 at rtol 1e-3).
RTOL_RANGE = (1e-12, 1e-8)
PILOT_RTOL = RTOL_RANGE[1]
#: The adaptive pilot's reference run is this much tighter (its own error then ~1/300 of the loose run's, corrected
#: for).
PILOT_RTOL_REFERENCE_FACTOR = 1e-3
#: Most steps an adaptive pilot run may take (a stiff model stops it here instead of running for seconds).
PILOT_ADAPTIVE_STEPS = 50_000
#: Largest angle error that means anything: beyond it the phase is lost and the estimate is capped there.
PHASE_LOST_RAD = math.pi
#: Largest relative error that means anything (the error is as large as the state itself).
STATE_LOST = 1.0

#: ``stats.status`` of a request run at a lower accuracy than its target, to stay within the request limits.
REDUCED_ACCURACY = "reduced_accuracy"
#: ``stats.status`` of a request answered by the model's exact solution instead of the integration it asked for.
EXACT_FALLBACK = "exact_fallback"
#: ``stats.status`` (and the live panel's) of a run whose explicitly chosen setting misses the model's target by
#: estimate.
TARGET_MISSED = "target_missed"
#: Status of a live choice whose pilot is still running: the fixed-ratio step runs meanwhile, its error not yet known.
ESTIMATING = "estimating"
#: Status of a live choice whose pilot raised: the fixed-ratio step keeps running, its error unknown.
PILOT_FAILED = "pilot_failed"


class PilotPending(Exception):
    """A pilot that is not cached was needed by a caller that asked not to run one (``run_pilots=False``)."""


#: Error of ``states`` (N, n) against ``reference`` (N, n), per frame (N,), in the target's unit.
ErrorMeasure = Callable[[np.ndarray, np.ndarray], np.ndarray]


@dataclass(frozen=True)
class AccuracyTarget:
    """An error a model's default integration must meet over ``horizon_s`` (s).

    ``unit`` is ``"rad"`` for an angle error or ``""`` for a relative one;
    ``measure`` names what is compared (e.g. "attitude angle").
    """

    error: float
    unit: str
    measure: str
    horizon_s: float = DEFAULT_HORIZON_S

    def __post_init__(self) -> None:
        if not (math.isfinite(self.error) and self.error > 0.0):
            raise ValueError(f"the target error must be a finite number > 0 (got {self.error!r})")
        if not (math.isfinite(self.horizon_s) and self.horizon_s > 0.0):
            raise ValueError(f"the target horizon must be a finite time > 0 s (got {self.horizon_s!r})")

    def format(self, value: float) -> str:
        """``value`` with the unit ("3e-07 rad", "3e-07 relative"; "unknown" for NaN)."""
        if not math.isfinite(value):
            return "unknown"
        if self.unit == "rad" and value >= PHASE_LOST_RAD:
            return "π rad or more (the phase is lost)"
        if not self.unit and value >= STATE_LOST:
            return "100% or more (the state is lost)"
        return f"{value:.1g} {self.unit or 'relative'}"


@dataclass(frozen=True)
class ErrorModel:
    """What a pilot measured for one method: ``E(h, T) = E_pilot(T) (h/h_pilot)^order``, with ``E_pilot(T)``
    its error curve over the measured span and the growth law beyond (:meth:`pilot_error_over`).

    For an adaptive method ``h_pilot_s`` is 0 and the error scales with the
    tolerance instead: ``E = E_pilot(T) (rtol/rtol_pilot)^(order/(order+1))``.
    """

    method: str
    order: int
    adaptive: bool
    h_pilot_s: float
    rtol_pilot: float
    #: Largest estimated error of the pilot run over the pilot span, in the target's unit.
    error_pilot: float
    span_s: float
    growth_exponent: float
    #: Measured CPU time (s) per step of the pilot's finer run.
    cpu_per_step_s: float
    #: Steps per simulated second of the adaptive pilot at ``rtol_pilot`` (0 for fixed-step methods).
    steps_per_s_pilot: float = 0.0
    #: CPU time (s) this pilot took, calibration included.
    pilot_cpu_s: float = 0.0
    #: The error curve: times (s) and the running largest error up to each, while below :data:`LINEAR_LIMIT`.
    curve_t_s: tuple[float, ...] = ()
    curve_error: tuple[float, ...] = ()
    #: e-folding rate (1/s) of a chaotic motion's error, fitted on the curve (0: not chaotic).
    chaotic_rate_1_s: float = 0.0

    def growth(self, horizon_s: float) -> float:
        return (horizon_s / self.span_s) ** self.growth_exponent

    def pilot_error_over(self, horizon_s: float) -> float:
        """Largest error of the pilot's own setting over [0, ``horizon_s``] (target's unit).

        Measured along the curve; beyond it extended exponentially (chaotic) or by ``(T/T_end)^γ``.
        """
        if not self.curve_t_s:
            return self.error_pilot * self.growth(horizon_s)
        end_s, end_error = self.curve_t_s[-1], self.curve_error[-1]
        if horizon_s <= end_s:
            return float(np.interp(horizon_s, self.curve_t_s, self.curve_error))
        if self.chaotic_rate_1_s > 0.0:
            return end_error * math.exp(min(self.chaotic_rate_1_s * (horizon_s - end_s), 700.0))
        return end_error * (horizon_s / max(end_s, 1e-300)) ** self.growth_exponent

    def fixed_factor(self, h_s: float) -> float:
        return (h_s / self.h_pilot_s) ** self.order

    def adaptive_factor(self, rtol: float) -> float:
        return (rtol / self.rtol_pilot) ** (self.order / (self.order + 1))

    def error_fixed(self, h_s: float, horizon_s: float) -> float:
        return self.pilot_error_over(horizon_s) * self.fixed_factor(h_s)

    def error_adaptive(self, rtol: float, horizon_s: float) -> float:
        return self.pilot_error_over(horizon_s) * self.adaptive_factor(rtol)

    def predictable_horizon_s(self, factor: float, error: float, horizon_s: float) -> float:
        """Longest T ≤ ``horizon_s`` over which a setting ``factor`` times the pilot's keeps within ``error`` (s)."""
        if self.pilot_error_over(horizon_s) * factor <= error:
            return horizon_s
        low, high = 0.0, horizon_s
        for _ in range(60):
            mid = 0.5 * (low + high)
            low, high = (mid, high) if self.pilot_error_over(mid) * factor <= error else (low, mid)
        return low

    def adaptive_steps(self, rtol: float, horizon_s: float) -> float:
        """Steps over ``horizon_s`` at ``rtol`` (step count ∝ rtol^(−1/(order+1)))."""
        return self.steps_per_s_pilot * horizon_s * (self.rtol_pilot / rtol) ** (1.0 / (self.order + 1))


@dataclass(frozen=True)
class StepChoice:
    """The automatic setting of one method for one model, with its estimated error and cost."""

    method: str
    #: Steps per frame (fixed-step methods) or ``None``.
    steps_per_frame: int | None
    #: Relative tolerance (adaptive methods) or ``None``.
    rtol: float | None
    target: AccuracyTarget
    horizon_s: float
    frame_dt_s: float
    #: Estimated error over ``horizon_s`` in the target's unit.
    estimated_error: float
    #: Estimated CPU time (s) over ``horizon_s`` (for comparing methods).
    cost_s: float
    #: "ok"; :data:`REDUCED_ACCURACY` when a limit (or chaos, or a short pilot) kept the choice from meeting the
    #: target over ``horizon_s`` asked for; :data:`ESTIMATING` / :data:`PILOT_FAILED` for a live scene's pending choice.
    status: str = "ok"
    #: Why the accuracy or the horizon was lowered (empty when the target is met).
    note: str = ""

    @property
    def meets_target(self) -> bool:
        return self.estimated_error <= self.target.error

    @classmethod
    def pending(
        cls,
        method: str,
        steps_per_frame: int | None,
        rtol: float | None,
        target: AccuracyTarget,
        *,
        horizon_s: float,
        frame_dt_s: float,
    ) -> StepChoice:
        """A setting running while its pilot is measured elsewhere (status :data:`ESTIMATING`, error unknown)."""
        return cls(
            method,
            steps_per_frame,
            rtol,
            target,
            horizon_s,
            frame_dt_s,
            math.nan,
            math.nan,
            ESTIMATING,
            "the fixed step rule runs until the pilot has measured the error",
        )

    def setting_text(self) -> str:
        if self.steps_per_frame is None and self.rtol is None:
            return "exact solution"
        if self.steps_per_frame is not None:
            return f"{self.steps_per_frame} step{'' if self.steps_per_frame == 1 else 's'}/frame"
        return f"rtol {self.rtol:.1g}"

    def text(self) -> str:
        """One line for the live panel: "target 1e-06 rad over 60 s · estimated 3e-07 rad · 12 steps/frame"."""
        estimate = (
            "estimating…" if self.status == ESTIMATING else f"estimated {self.target.format(self.estimated_error)}"
        )
        return (
            f"target {self.target.format(self.target.error)} over {self.horizon_s:g} s · {estimate} · "
            f"{self.setting_text()}"
        )

    def as_dict(self) -> dict:
        """The keys the live readout and a simulate answer's stats carry."""
        return {
            "target_error": self.target.error,
            "error_unit": self.target.unit,
            "error_measure": self.target.measure,
            "error_horizon_s": self.horizon_s,
            "estimated_error": self.estimated_error,
            "accuracy": self.text(),
        }


# ---- the pilot ---------------------------------------------------------------------------------


def _pilot_frames(spec: MethodSpec, steps_per_frame: int, frame_dt_s: float, span_s: float = PILOT_SPAN_S) -> int:
    """Frames of a pilot pair (n and 2n steps per frame) within :data:`PILOT_WORK`, at most ``span_s``."""
    per_frame = 3 * steps_per_frame * spec.substeps_per_step
    frames = min(int(round(span_s / frame_dt_s)), PILOT_WORK // max(per_frame, 1))
    return max(frames, PILOT_MIN_FRAMES)


def _error_curve(errors: np.ndarray, frame_dt_s: float) -> tuple[tuple[float, ...], tuple[float, ...], float]:
    """(times, running largest error) while below :data:`LINEAR_LIMIT`, and the chaotic e-folding rate (1/s, or 0).

    Chaotic: over the second half of the measured part the error grew more than :data:`CHAOTIC_GROWTH` times
    (faster than t⁴: neither a phase error, ∝ t, nor one driven by an energy drift, ∝ t²).
    """
    running = np.maximum.accumulate(np.asarray(errors, dtype=float))
    linear = int(np.searchsorted(running, LINEAR_LIMIT, side="right"))  # frames [0, linear) are below the limit
    linear = max(linear, 2)
    t = np.arange(linear) * frame_dt_s
    kept = np.unique(np.linspace(0, linear - 1, min(linear, CURVE_POINTS)).astype(int))
    rate = 0.0
    half, end = float(running[(linear - 1) // 2]), float(running[linear - 1])
    if half > 0.0 and end > CHAOTIC_GROWTH * half:
        rate = math.log(end / half) / (t[-1] - t[(linear - 1) // 2])
    return tuple(t[kept].tolist()), tuple(running[kept].tolist()), rate


def _growth_exponent(errors: np.ndarray, *, geometric: bool) -> float:
    """Growth exponent γ of the running largest error beyond the pilot: 1 for geometric methods, else at least 2
    (a linear energy drift's; the measured one where faster, up to 4 — faster is chaotic, see :func:`_error_curve`)."""
    if geometric:
        return 1.0
    running = np.maximum.accumulate(errors)
    half, last = float(running[len(running) // 2]), float(running[-1])
    if not (half > 0.0 and last > 0.0):
        return 2.0
    return float(min(max(math.log(last / half) / math.log(2.0), 2.0), 4.0))


def _run(
    system: OdeSystem,
    spec: MethodSpec,
    y0: np.ndarray,
    frames: int,
    frame_dt_s: float,
    *,
    max_steps: int = PILOT_ADAPTIVE_STEPS,
    **setting,
):
    """One pilot run: (result, CPU s, usable). Usable: finite, and complete, or ended at a terminal event (the
    model's own end of the motion), or (adaptive) out of its ``max_steps`` after :data:`PILOT_MIN_FRAMES` frames."""
    integrator = spec.factory(**setting)
    if spec.adaptive:
        cast("DormandPrince", integrator).max_steps = max(int(max_steps), 1)
    start = time.thread_time()
    result = simulate(system, integrator, y0, t_end_s=frames * frame_dt_s, frame_rate_hz=1.0 / frame_dt_s)
    cpu = time.thread_time() - start
    complete = result.status == "ok" and len(result.t_s) == frames + 1
    partial = result.status == "too_many_steps" and len(result.t_s) > PILOT_MIN_FRAMES
    finished = (complete or partial or result.status == "event") and bool(np.all(np.isfinite(result.states)))
    return result, cpu, finished


def _affordable_frames(
    system: OdeSystem,
    spec: MethodSpec,
    y0: np.ndarray,
    frames: int,
    frame_dt_s: float,
    *,
    runs_cost: float,
    cpu_budget_s: float,
    **setting,
) -> tuple[int, float]:
    """(frames ≤ ``frames`` the pilot runs can afford within ``cpu_budget_s``, CPU s of the calibration measuring that).

    ``runs_cost``: the pilot pair's cost in units of one run at ``setting``. A one-frame run first takes the costs
    paid once per process (compiling or loading the model's kernels, numba's dispatch): counted in the calibration's
    CPU, not in its cost per frame (in a fresh test process they made the Foucault pendulum's pilot afford 9.3 s of
    its 60 s, and its target was stated over that span only).
    """
    once = _run(system, spec, y0, 1, frame_dt_s, **setting)[1]
    # A cheap model's first frames take a fraction of a millisecond, where one page fault or collection would decide
    # the estimate: the calibration runs longer (four times the frames each time) until it has measured enough, or
    # has spent a quarter of the budget itself (the one-frame run's once-only costs do not cut it short: a kernel
    # loaded on a loaded machine once left a 20-frame calibration's noise to decide the Foucault pendulum's span).
    calibration_frames, calibrating = PILOT_MIN_FRAMES, 0.0
    while True:
        calibration, cpu, _ = _run(system, spec, y0, calibration_frames, frame_dt_s, **setting)
        calibrating += cpu
        if cpu >= CALIBRATION_CPU_S or calibration_frames >= frames or calibrating >= cpu_budget_s / 4:
            break
        calibration_frames = min(4 * calibration_frames, frames)
    spent = once + calibrating
    per_frame = cpu / max(len(calibration.t_s) - 1, 1)
    if per_frame <= 0.0:
        return frames, spent
    return max(PILOT_MIN_FRAMES, min(frames, int(cpu_budget_s / (runs_cost * per_frame)))), spent


def _common_errors(error: ErrorMeasure, a, b) -> np.ndarray:
    """The error measure over the frames both runs reached (a run may end early at a terminal event)."""
    frames = min(len(a.t_s), len(b.t_s))
    return np.asarray(error(a.states[:frames], b.states[:frames]), dtype=float)


def _measured_growth(errors: np.ndarray, frame_dt_s: float, spec: MethodSpec, *runs) -> dict:
    """The :class:`ErrorModel` fields a pilot pair's per-frame ``errors`` give: span, largest error, growth, curve.

    Runs that both ended at a terminal event covered the whole motion: the error does not grow after it (γ = 0).
    """
    curve_t, curve_error, rate = _error_curve(errors, frame_dt_s)
    ended = all(run.status == "event" for run in runs)
    return dict(
        span_s=max(len(errors) - 1, 1) * frame_dt_s,
        error_pilot=float(errors.max()),
        growth_exponent=0.0 if ended else _growth_exponent(errors, geometric=spec.geometric),
        curve_t_s=curve_t,
        curve_error=curve_error,
        chaotic_rate_1_s=0.0 if ended else rate,
    )


def pilot_fixed(
    system: OdeSystem,
    y0: np.ndarray,
    spec: MethodSpec,
    steps_per_frame: int,
    frame_dt_s: float,
    error: ErrorMeasure,
    *,
    span_s: float = PILOT_SPAN_S,
    cpu_budget_s: float = PILOT_CPU_S,
) -> ErrorModel | None:
    """Richardson pilot of a fixed-step method at ``steps_per_frame`` over ``span_s`` (bounded in work and in CPU
    time; None: a run did not finish)."""
    # PILOT_WORK bounds the span beyond PILOT_SPAN_S; up to that (or the horizon) only the CPU budget does.
    wanted = max(
        _pilot_frames(spec, steps_per_frame, frame_dt_s, span_s), int(round(min(span_s, PILOT_SPAN_S) / frame_dt_s))
    )
    frames, calibration_cpu = _affordable_frames(
        system,
        spec,
        y0,
        wanted,
        frame_dt_s,
        runs_cost=3.0,
        cpu_budget_s=cpu_budget_s,
        steps_per_frame=steps_per_frame,
    )
    coarse, cpu_coarse, ok_coarse = _run(system, spec, y0, frames, frame_dt_s, steps_per_frame=steps_per_frame)
    fine, cpu_fine, ok_fine = _run(system, spec, y0, frames, frame_dt_s, steps_per_frame=2 * steps_per_frame)
    if not (ok_coarse and ok_fine):
        return None
    errors = _common_errors(error, coarse, fine) / (1.0 - 2.0 ** (-spec.order))
    if not np.all(np.isfinite(errors)):
        return None
    return ErrorModel(
        method=spec.name,
        order=spec.order,
        adaptive=False,
        h_pilot_s=frame_dt_s / steps_per_frame,
        rtol_pilot=0.0,
        cpu_per_step_s=cpu_fine / max(fine.steps, 1),
        pilot_cpu_s=calibration_cpu + cpu_coarse + cpu_fine,
        **_measured_growth(errors, frame_dt_s, spec, coarse, fine),
    )


def pilot_adaptive(
    system: OdeSystem,
    y0: np.ndarray,
    spec: MethodSpec,
    frame_dt_s: float,
    error: ErrorMeasure,
    *,
    span_s: float = PILOT_SPAN_S,
    rtol: float = PILOT_RTOL,
    cpu_budget_s: float = PILOT_CPU_S,
) -> ErrorModel | None:
    """Pilot of an adaptive method over ``span_s``: the run at ``rtol`` against one 10³ times tighter
    (at most down to the tightest tolerance offered, the difference then corrected as Richardson's is).

    A run out of steps (:data:`PILOT_ADAPTIVE_STEPS`) over a span longer than :data:`PILOT_SPAN_S` is retried over that.
    """
    tighter = max(rtol * PILOT_RTOL_REFERENCE_FACTOR, RTOL_RANGE[0] / 10.0)
    frames = max(int(round(span_s / frame_dt_s)), PILOT_MIN_FRAMES)
    # Steps within the CPU budget, from a calibration run's cost per step: the tighter run takes about
    # (rtol/tighter)^(1/(p+1)) times the steps of the loose one; a run out of steps gives a shorter span.
    calibration, calibration_cpu, _ = _run(system, spec, y0, PILOT_MIN_FRAMES, frame_dt_s, rtol=rtol)
    cpu_per_step = calibration_cpu / max(calibration.steps, 1)
    affordable = cpu_budget_s / max(cpu_per_step, 1e-9)
    ratio = (rtol / tighter) ** (1.0 / (spec.order + 1))
    loose, cpu, ok_loose = _run(
        system, spec, y0, frames, frame_dt_s, rtol=rtol, max_steps=min(PILOT_ADAPTIVE_STEPS, affordable / (1.0 + ratio))
    )
    tight, cpu_tight, ok_tight = _run(
        system,
        spec,
        y0,
        len(loose.t_s) - 1 if loose.status == "too_many_steps" else frames,
        frame_dt_s,
        rtol=tighter,
        max_steps=min(PILOT_ADAPTIVE_STEPS, affordable * ratio / (1.0 + ratio)),
    )
    if not (ok_loose and ok_tight and min(len(loose.t_s), len(tight.t_s)) >= 2):
        return None
    errors = _common_errors(error, loose, tight) / (1.0 - (tighter / rtol) ** (spec.order / (spec.order + 1)))
    if not np.all(np.isfinite(errors)):
        return None
    growth = _measured_growth(errors, frame_dt_s, spec, loose, tight)
    return ErrorModel(
        method=spec.name,
        order=spec.order,
        adaptive=True,
        h_pilot_s=0.0,
        rtol_pilot=rtol,
        cpu_per_step_s=cpu / max(loose.steps, 1),
        steps_per_s_pilot=loose.steps / ((len(loose.t_s) - 1) * frame_dt_s),
        pilot_cpu_s=calibration_cpu + cpu + cpu_tight,
        **growth,
    )


# ---- the choice ----------------------------------------------------------------------------------


def _tolerance_scaled(rtol: float, ratio: float, exponent: float) -> float:
    """``rtol · ratio**exponent`` within :data:`RTOL_RANGE`. A pilot's error can be near the smallest float (over a
    span of 1e-292 s), and the power then overflows before the range would clamp it: the range's end instead."""
    if math.isnan(ratio):
        return RTOL_RANGE[0]
    try:
        scaled = rtol * ratio**exponent
    except OverflowError:
        return RTOL_RANGE[1] if ratio > 1.0 else RTOL_RANGE[0]
    return min(max(scaled, RTOL_RANGE[0]), RTOL_RANGE[1])


def _fixed_steps_needed(model: ErrorModel, goal: float, horizon_s: float, frame_dt_s: float) -> int:
    """Fewest steps per frame whose estimated error over ``horizon_s`` is at most ``goal`` (at least 1)."""
    base = model.pilot_error_over(horizon_s)
    if base <= 0.0:
        return 1
    h_needed = model.h_pilot_s * (goal / base) ** (1.0 / model.order)
    return max(1, math.ceil(frame_dt_s / h_needed - 1e-9))


def _fixed_error_model(
    system: OdeSystem,
    y0: np.ndarray,
    spec: MethodSpec,
    *,
    target: AccuracyTarget,
    horizon_s: float,
    start_steps: int,
    frame_dt_s: float,
    error: ErrorMeasure,
) -> ErrorModel | None:
    """The error model from the pilot whose step is closest to what the target needs (re-piloted when shrinking
    steps)."""
    n = max(1, min(start_steps, MAX_STEPS_PER_FRAME))
    trusted: ErrorModel | None = None
    spent = 0.0
    for _ in range(MAX_PILOTS):
        if spent >= PILOT_CPU_S:
            return trusted
        model = pilot_fixed(system, y0, spec, n, frame_dt_s, error, span_s=horizon_s, cpu_budget_s=PILOT_CPU_S - spent)
        if model is None:  # unstable at this step: smaller steps
            if n >= MAX_STEPS_PER_FRAME:
                return trusted
            n = min(4 * n, MAX_STEPS_PER_FRAME)
            continue
        trusted = model
        spent += model.pilot_cpu_s
        needed = _fixed_steps_needed(model, SAFETY * target.error, horizon_s, frame_dt_s)
        if needed >= n or n == 1:
            return model  # smaller steps than the pilot's: extrapolating inside the asymptotic range
        if needed * 2 > n:
            return model  # close enough: a re-pilot would change little
        n = needed  # a larger step than measured: measure there before trusting it
    return trusted


def _adaptive_error_model(
    system: OdeSystem,
    y0: np.ndarray,
    spec: MethodSpec,
    *,
    target: AccuracyTarget,
    horizon_s: float,
    frame_dt_s: float,
    error: ErrorMeasure,
) -> ErrorModel | None:
    """The error model from the pilot at the tolerance closest to what the target needs (re-piloted there).

    An adaptive method's error is a power of the tolerance only roughly (a maximum step, or event location,
    can keep it flat over decades), so the choice is measured at the tolerance it settles on, within 10×.
    """
    rtol = PILOT_RTOL
    trusted: ErrorModel | None = None
    spent = 0.0
    for _ in range(MAX_PILOTS):
        if spent >= PILOT_CPU_S:
            return trusted
        model = pilot_adaptive(
            system, y0, spec, frame_dt_s, error, span_s=horizon_s, rtol=rtol, cpu_budget_s=PILOT_CPU_S - spent
        )
        if model is None:
            return trusted
        trusted = model
        spent += model.pilot_cpu_s
        base = model.pilot_error_over(horizon_s)
        if base <= 0.0:
            return model
        needed = _tolerance_scaled(rtol, SAFETY * target.error / base, (spec.order + 1) / spec.order)
        if abs(math.log10(needed / rtol)) <= 1.0 or (
            needed > rtol and base <= SAFETY * target.error and rtol >= RTOL_RANGE[1]
        ):
            return model
        rtol = needed
    return trusted


class _PilotCache:
    """Error models by (model key, method), least recently used dropped first; safe across scene threads."""

    def __init__(self, size: int = 512) -> None:
        self._items: OrderedDict[Hashable, ErrorModel | None] = OrderedDict()
        self._size = size
        self._lock = threading.Lock()
        self.pilots_run = 0
        #: Pilots run, by the name of the thread that ran them (a live scene's must never be the frame loop's).
        self.pilots_by_thread: Counter[str] = Counter()

    def get(
        self, key: Hashable, compute: Callable[[], ErrorModel | None], *, run_pilot: bool = True
    ) -> ErrorModel | None:
        """The cached value of ``key``, else ``compute()`` cached (``run_pilot=False``: :class:`PilotPending`
        instead)."""
        with self._lock:
            if key in self._items:
                self._items.move_to_end(key)
                return self._items[key]
        if not run_pilot:
            raise PilotPending(key)
        value = compute()
        with self._lock:
            self.pilots_run += 1
            self.pilots_by_thread[threading.current_thread().name] += 1
            self._items[key] = value
            while len(self._items) > self._size:
                self._items.popitem(last=False)
        return value

    def clear(self) -> None:
        with self._lock:
            self._items.clear()
            self.pilots_run = 0
            self.pilots_by_thread.clear()


PILOT_CACHE = _PilotCache()


def error_model(
    system: OdeSystem,
    y0: np.ndarray,
    spec: MethodSpec,
    *,
    target: AccuracyTarget,
    start_steps: int,
    frame_dt_s: float,
    error: ErrorMeasure,
    cache_key: Hashable | None = None,
    run_pilot: bool = True,
    horizon_s: float | None = None,
) -> ErrorModel | None:
    """The method's measured error model for this system over ``horizon_s`` (default: the target's), cached under
    ``cache_key`` when given.

    ``run_pilot=False``: only a cached model; :class:`PilotPending` when it would have to be measured.
    """
    horizon = target.horizon_s if horizon_s is None else horizon_s

    def compute() -> ErrorModel | None:
        if spec.adaptive:
            return _adaptive_error_model(
                system, y0, spec, target=target, horizon_s=horizon, frame_dt_s=frame_dt_s, error=error
            )
        return _fixed_error_model(
            system,
            y0,
            spec,
            target=target,
            horizon_s=horizon,
            start_steps=start_steps,
            frame_dt_s=frame_dt_s,
            error=error,
        )

    if cache_key is None:
        if not run_pilot:
            raise PilotPending(spec.name)
        return compute()
    return PILOT_CACHE.get((cache_key, spec.name, target, horizon), compute, run_pilot=run_pilot)


class _Limits(TypedDict):
    """The limits :func:`choice_from_model` passes on (to itself over a shorter horizon, and to :func:`_setting`)."""

    max_steps_per_frame: int
    max_adaptive_steps: float
    limit_text: str
    max_frame_cpu_s: float


def choice_from_model(
    model: ErrorModel,
    target: AccuracyTarget,
    *,
    horizon_s: float,
    frame_dt_s: float,
    max_steps_per_frame: int = MAX_STEPS_PER_FRAME,
    max_adaptive_steps: float = math.inf,
    limit_text: str = "",
    max_frame_cpu_s: float = math.inf,
) -> StepChoice:
    """The cheapest setting meeting ``target`` over ``horizon_s``, or the most accurate the limits allow (stated).

    ``max_frame_cpu_s``: a live scene's physics budget per frame (s of CPU, from the pilot's cost per step).

    A chaotic motion that no setting within the limits follows to the target over ``horizon_s`` gets the target
    stated over its predictability horizon instead (the choice's ``horizon_s``, the reason in its note): the
    part of the pilot's error curve measured before the runs parted, never an extrapolation of the exponential.
    """
    limits = _Limits(
        max_steps_per_frame=max_steps_per_frame,
        max_adaptive_steps=max_adaptive_steps,
        limit_text=limit_text,
        max_frame_cpu_s=max_frame_cpu_s,
    )
    trusted_s = _extrapolation_limit_s(model)
    if horizon_s > trusted_s:
        stated = min(_two_figures_down(trusted_s), trusted_s)
        choice = choice_from_model(model, target, horizon_s=stated, frame_dt_s=frame_dt_s, **limits)
        note = (
            f"the target is stated over {stated:g} s, not the {horizon_s:g} s asked for: the pilot could measure "
            f"{model.span_s:.3g} s of this motion within its budget, too short to extrapolate this method's error from"
        )
        return replace(choice, status=REDUCED_ACCURACY, note=f"{choice.note}; {note}" if choice.note else note)
    steps, rtol, factor, cost, setting, limit = _setting(model, target, horizon_s, frame_dt_s, **limits)
    estimated = _capped(model.pilot_error_over(horizon_s) * factor, target)
    if estimated <= target.error:
        return StepChoice(model.method, steps, rtol, target, horizon_s, frame_dt_s, estimated, cost)
    if model.chaotic_rate_1_s > 0.0 and model.curve_t_s:
        measured_s = min(horizon_s, model.curve_t_s[-1])
        steps, rtol, factor, cost, setting, _ = _setting(model, target, measured_s, frame_dt_s, **limits)
        predictable = _two_figures_down(model.predictable_horizon_s(factor, SAFETY * target.error, measured_s))
        if predictable > 0.0:
            note = (
                f"exponential error growth (×e every {1.0 / model.chaotic_rate_1_s:.2g} s, measured by the pilot: a "
                f"chaotic motion, or one that keeps speeding up), so the target is stated over {predictable:g} s, the "
                f"predictability horizon at these parameters, not over the {horizon_s:g} s asked for"
            )
            return StepChoice(
                model.method,
                steps,
                rtol,
                target,
                predictable,
                frame_dt_s,
                model.pilot_error_over(predictable) * factor,
                cost,
                REDUCED_ACCURACY,
                note,
            )
    note = f"accuracy lowered to ~{target.format(estimated)} with {setting} to stay within {limit}"
    return StepChoice(model.method, steps, rtol, target, horizon_s, frame_dt_s, estimated, cost, REDUCED_ACCURACY, note)


def _budget_text(max_frame_cpu_s: float) -> str:
    return f"a live scene's physics budget of {1e3 * max_frame_cpu_s:g} ms per frame (each viewer of the class pays it)"


def _extrapolation_limit_s(model: ErrorModel) -> float:
    """Longest horizon (s) the model's estimate may be trusted over: any for a geometric method (linear phase error),
    a motion the pilot saw end, or a pilot span of at least :data:`PILOT_SPAN_S`; else (a costly model's pilot cut
    short by :data:`PILOT_CPU_S`) the span measured: a growth law fitted on 2–4 s undershot the error of chapter 8's
    linkages 4× to 30× at 60 s (their errors grow as t³ to t⁴ there)."""
    if model.growth_exponent <= 1.0 or model.span_s >= PILOT_SPAN_S - 1e-9:
        return math.inf
    return model.span_s


def _setting(
    model: ErrorModel,
    target: AccuracyTarget,
    horizon_s: float,
    frame_dt_s: float,
    *,
    max_steps_per_frame: int,
    max_adaptive_steps: float,
    limit_text: str,
    max_frame_cpu_s: float,
) -> tuple[int | None, float | None, float, float, str, str]:
    """(steps/frame, rtol, error factor on the pilot's, cost over ``horizon_s`` (s), the setting and the limit in words)
    of the cheapest setting meeting half the target over ``horizon_s``, capped by the limits."""
    goal = SAFETY * target.error
    base = model.pilot_error_over(horizon_s)
    if model.adaptive:
        exponent = model.order / (model.order + 1)
        rtol = _tolerance_scaled(model.rtol_pilot, goal / base, 1.0 / exponent) if base > 0 else RTOL_RANGE[1]
        rtol = float(f"{rtol:.1g}")  # a tolerance a student can read (rounded down or up by less than 2×)
        limit = f"rtol {RTOL_RANGE[0]:g}, the tightest tolerance offered"
        if model.adaptive_steps(rtol, horizon_s) > max_adaptive_steps:
            steps_over = model.adaptive_steps(model.rtol_pilot, horizon_s) / max_adaptive_steps
            rtol = _tolerance_scaled(model.rtol_pilot, steps_over, model.order + 1)
            limit = limit_text or "the step limit"
        steps_in_budget = max_frame_cpu_s / max(model.cpu_per_step_s, 1e-12)
        if model.adaptive_steps(rtol, frame_dt_s) > steps_in_budget:
            steps_over = model.adaptive_steps(model.rtol_pilot, frame_dt_s) / steps_in_budget
            rtol = float(f"{_tolerance_scaled(model.rtol_pilot, steps_over, model.order + 1):.1g}")
            limit = _budget_text(max_frame_cpu_s)
        cost = model.adaptive_steps(rtol, horizon_s) * model.cpu_per_step_s
        return None, rtol, model.adaptive_factor(rtol), cost, f"rtol {rtol:.1g}", limit
    needed = _fixed_steps_needed(model, goal, horizon_s, frame_dt_s)
    in_budget = int(min(max_frame_cpu_s / max(model.cpu_per_step_s, 1e-12), MAX_STEPS_PER_FRAME))
    steps = max(min(needed, max_steps_per_frame, in_budget), 1)
    limit = limit_text or f"the limit of {max_steps_per_frame} steps/frame"
    if in_budget < min(needed, max_steps_per_frame):
        limit = _budget_text(max_frame_cpu_s)
    limit = f"{limit} (the target needs {needed})"
    cost = steps * (horizon_s / frame_dt_s) * model.cpu_per_step_s
    return steps, None, model.fixed_factor(frame_dt_s / steps), cost, f"{steps} steps/frame", limit


def _two_figures_down(value: float) -> float:
    """``value`` > 0 rounded down to two significant figures (0 stays 0)."""
    if value <= 0.0:
        return 0.0
    unit = 10.0 ** (math.floor(math.log10(value)) - 1)
    return math.floor(value / unit + 1e-9) * unit


def _capped(error: float, target: AccuracyTarget) -> float:
    """An error beyond :data:`PHASE_LOST_RAD` (angle) or :data:`STATE_LOST` (relative) only says all is lost: report it
    as that."""
    return min(error, PHASE_LOST_RAD if target.unit == "rad" else STATE_LOST)


def cheapest(choices: Sequence[StepChoice]) -> StepChoice:
    """Least cost among the choices meeting their target; if none does, the longest horizon stated, then the smallest
    error."""
    if not choices:
        raise ValueError("no method to choose from")
    meeting = [c for c in choices if c.meets_target and c.status == "ok"]
    if meeting:
        return min(meeting, key=lambda c: c.cost_s)
    return min(
        choices, key=lambda c: (-c.horizon_s, c.estimated_error)
    )  # the longest horizon stated, then the smallest error


def usable_methods(system: OdeSystem, methods: Sequence[str]) -> list[MethodSpec]:
    """The specs of ``methods`` that can integrate ``system`` (the others' checks refuse it)."""
    usable = []
    for name in methods:
        spec = METHODS.get(name)
        if spec is None:
            continue
        try:
            spec.check_system(system)
        except ValueError:
            continue
        usable.append(spec)
    return usable


def choose(
    system: OdeSystem,
    y0: np.ndarray,
    methods: Sequence[str],
    *,
    target: AccuracyTarget,
    frame_dt_s: float,
    horizon_s: float,
    fastest_rate_rad_s: float,
    error: ErrorMeasure,
    cache_key: Hashable | None = None,
    max_fixed_work: int | None = None,
    max_adaptive_steps: float = math.inf,
    run_pilots: bool = True,
    max_frame_cpu_s: float = math.inf,
) -> StepChoice | None:
    """The cheapest of ``methods`` (those that can integrate ``system``) meeting ``target`` over ``horizon_s``.

    Fixed-step pilots start from the method's ``step_ratio`` rule at ``fastest_rate_rad_s``.
    ``max_fixed_work`` (frames × steps × sub-steps over the horizon) and
    ``max_adaptive_steps`` cap the choice (its lowered accuracy stated), as does a live
    scene's ``max_frame_cpu_s`` (physics CPU per frame). None when
    no pilot run of any method finished. ``run_pilots=False``: :class:`PilotPending`
    unless every method's pilot is cached.
    """
    choices = []
    frames = math.ceil(horizon_s / frame_dt_s - 1e-9)
    for spec in usable_methods(system, methods):
        start = 1 if spec.adaptive else spec.automatic_steps_per_frame(fastest_rate_rad_s, frame_dt_s)
        model = error_model(
            system,
            y0,
            spec,
            target=target,
            start_steps=start,
            frame_dt_s=frame_dt_s,
            error=error,
            cache_key=cache_key,
            horizon_s=horizon_s,
            run_pilot=run_pilots,
        )
        if model is None:
            continue
        cap, limit_text = MAX_STEPS_PER_FRAME, ""
        if max_fixed_work is not None and not spec.adaptive:
            cap = min(cap, max(int(max_fixed_work // max(frames * spec.substeps_per_step, 1)), 1))
            limit_text = f"the request limit of {max_fixed_work} sub-steps"
        elif math.isfinite(max_adaptive_steps) and spec.adaptive:
            limit_text = f"the request limit of {int(max_adaptive_steps)} adaptive steps"
        choices.append(
            choice_from_model(
                model,
                target,
                horizon_s=horizon_s,
                frame_dt_s=frame_dt_s,
                max_steps_per_frame=cap,
                max_adaptive_steps=max_adaptive_steps,
                limit_text=limit_text,
                max_frame_cpu_s=max_frame_cpu_s,
            )
        )
    return cheapest(choices) if choices else None
