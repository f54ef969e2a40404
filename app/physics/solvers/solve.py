"""Where a model, an integrator and a step choice meet.

:func:`simulate` runs a system over a time span and samples it once per frame;
:class:`LiveRun` advances a scene's system a frame at a time. Both stop at the
first non-finite state and say so in words instead of returning NaN.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from app.physics.solvers.base import EventRecord, FixedStepIntegrator, Integrator
from app.physics.solvers.kernels import Backend
from app.physics.solvers.registry import (  # noqa: F401 - re-exported: the names other modules import from here
    MAX_STEPS_PER_FRAME,
    METHODS,
    STEP_RATIO,
    automatic_steps_per_frame,
    make_integrator,
)
from app.physics.solvers.status import FAILURE_TEXT, SUCCESSFUL
from app.physics.solvers.system import OdeSystem


def failure_message(status: str, t_s: float, integrator: Integrator, frame_dt_s: float, *, system: OdeSystem) -> str:
    """A sentence a student can act on (naming only remedies ``system`` allows: :func:`remedy`)."""
    what = FAILURE_TEXT.get(status, status)
    if status == "event":  # the model's own stop (a landing, a lift-off), not a numerical failure: nothing to loosen
        return f"Stopped at t = {t_s:.3f} s: {what}."
    advice = "Loosen the tolerance or check the parameters." if integrator.spec.adaptive else f"{remedy(system)}."
    return f"Stopped at t = {t_s:.3f} s: {what} with {integrator.describe(frame_dt_s)}. {advice}"


def remedy(system: OdeSystem) -> str:
    """ "Use more steps per frame", adding a geometric method only where one applies to ``system`` (a rigid body
    about a fixed point, :attr:`OdeSystem.torque`): a model without one is never told to use it."""
    geometric = [name for name, spec in METHODS.items() if spec.needs_torque]
    if system.torque is None or not geometric:
        return "Use more steps per frame"
    return f"Use more steps per frame, or a splitting method ({', '.join(geometric)})"


@dataclass
class SimulationResult:
    """Frame-sampled solution with counters; ``status`` is "ok", "event" or a failure."""

    t_s: np.ndarray
    states: np.ndarray
    status: str
    message: str
    method: str
    description: str
    steps: int
    rhs_evals: int
    cpu_s: float
    t_event_s: float | None = None
    #: Events located during the run, in order (see :class:`EventRecord`).
    events: tuple[EventRecord, ...] = ()

    @property
    def ok(self) -> bool:
        return self.status in SUCCESSFUL

    def truncated(self, frames: int, *, status: str, message: str) -> SimulationResult:
        """The first ``frames`` frames only (``frames`` ≥ 1), ended with ``status`` and ``message``."""
        return replace(self, t_s=self.t_s[:frames], states=self.states[:frames], status=status, message=message)


def simulate(
    system: OdeSystem,
    integrator: Integrator,
    y0: np.ndarray,
    *,
    t_end_s: float,
    frame_rate_hz: float,
    backend: Backend = "numba",
) -> SimulationResult:
    """Integrate from t = 0 to ``t_end_s``, sampling ``y`` at every frame (t = 0 included).

    ``cpu_s`` is the CPU time of the integration alone, in its own thread (the other threads of a scene worker or a
    test process do not count).
    """
    frame_dt = 1.0 / frame_rate_hz
    n_frames = max(int(round(t_end_s * frame_rate_hz)), 1)
    y = np.array(y0, dtype=float)
    # Rows past a failure are cut off below, so they need no filling.
    states = np.empty((n_frames + 1, y.shape[0]))
    states[0] = y
    start = time.thread_time()
    outcome = integrator.run_frames(system, 0.0, y, frame_dt, n_frames, states[1:], backend=backend)
    cpu_s = time.thread_time() - start
    done = outcome.frames_done
    t = frame_dt * np.arange(done + 1)
    message = ""
    if outcome.status not in SUCCESSFUL:
        message = failure_message(outcome.status, float(t[-1]), integrator, frame_dt, system=system)
    return SimulationResult(
        t_s=t,
        states=states[: done + 1],
        status=outcome.status,
        message=message,
        method=integrator.name,
        description=integrator.describe(frame_dt),
        steps=outcome.steps,
        rhs_evals=outcome.rhs_evals,
        cpu_s=cpu_s,
        t_event_s=outcome.t_event_s,
        events=outcome.events,
    )


#: About the most integration steps one :class:`LiveRun` batch takes (one kernel call inside a scene worker's
#: frame loop): 2,048 RK4 steps of the double pendulum take about 1.5 ms. A run of more steps per frame than this
#: computes one frame per batch.
STEPS_PER_BATCH = 2048


@dataclass
class LiveRun:
    """A system advanced frame by frame for a live scene (never yields a non-finite state).

    Frames are computed up to ``batch_frames`` at a time and handed out one per
    call: a call from Python into a compiled kernel costs far more than a few
    steps of a small model, so batching keeps the physics cost per displayed
    frame to a few microseconds. A batch holds at most about
    :data:`STEPS_PER_BATCH` steps (at least one frame), judged from the steps per
    frame of the batch before (a fixed-step integrator's own count for the first;
    an adaptive one starts with one frame): one costly session's batch must not
    hold a scene worker's frame loop for more than a few milliseconds (15 frames
    of 4,096 RK4 steps of the double pendulum took 45 ms, a frame and a half for
    every student on that worker). The batch sizes follow from the step counts
    alone, so the same start gives the same motion. A failure inside a batch
    surfaces when playback reaches it.

    ``limit`` (optional) is the model's own edge (:meth:`IntegratedModel.model_limit
    <app.physics.solvers.integrated_model.IntegratedModel.model_limit>`, its parameters bound): called once per batch
    with the times (N,) and states (N, n) from the current frame on, it returns None or ``(frames, status, message)``
    for the leading frames it still describes; playback then stops after them with that status and message, as the
    simulate answer does.
    """

    system: OdeSystem
    integrator: Integrator
    y: np.ndarray
    t_s: float = 0.0
    status: str = "ok"
    message: str = ""
    #: The terminal event that stopped the run (status "event"), once playback has reached it.
    stop_event: EventRecord | None = None
    steps: int = 0
    batch_frames: int = 15
    limit: Callable[[np.ndarray, np.ndarray], Any] | None = None
    _buffer: np.ndarray = field(init=False, repr=False)
    _ready: int = field(init=False, default=0, repr=False)
    _next: int = field(init=False, default=0, repr=False)
    _pending_status: str = field(init=False, default="ok", repr=False)
    _pending_message: str = field(init=False, default="", repr=False)
    _pending_event: EventRecord | None = field(init=False, default=None, repr=False)
    _frame_dt_s: float = field(init=False, default=0.0, repr=False)
    _next_batch: int = field(init=False, default=1, repr=False)

    def __post_init__(self) -> None:
        self.y = np.array(self.y, dtype=float)
        self._buffer = np.empty((self.batch_frames, self.y.shape[0]))
        if isinstance(self.integrator, FixedStepIntegrator):
            self._next_batch = self._frames_within_budget(self.integrator.steps_per_frame)

    def _frames_within_budget(self, steps_per_frame: float) -> int:
        """Frames of ``steps_per_frame`` steps that fit in :data:`STEPS_PER_BATCH`: between 1 and ``batch_frames``."""
        return max(1, min(self.batch_frames, int(STEPS_PER_BATCH // max(steps_per_frame, 1.0))))

    @property
    def running(self) -> bool:
        return self.status == "ok"

    def _refill(self, frame_dt_s: float) -> None:
        trial = self.y.copy()
        batch = self._next_batch
        outcome = self.integrator.run_frames(self.system, self.t_s, trial, frame_dt_s, batch, self._buffer[:batch])
        self.steps += outcome.steps
        done = outcome.frames_done
        if done:
            self._next_batch = self._frames_within_budget(outcome.steps / done)
        finite = np.all(np.isfinite(self._buffer[:done]), axis=1)
        if not finite.all():
            done = int(np.argmin(finite))
        self._ready, self._next = done, 0
        self._frame_dt_s = frame_dt_s
        self._pending_status = (
            "ok"
            if done == batch and outcome.status == "ok"
            else (outcome.status if outcome.status != "ok" else "non_finite")
        )
        self._pending_message = ""
        self._pending_event = outcome.events[-1] if outcome.status == "event" and outcome.events else None
        if self.limit is not None and done > 0:
            times = self.t_s + frame_dt_s * np.arange(done + 1)
            reached = self.limit(times, np.vstack([self.y[None, :], self._buffer[:done]]))
            if reached is not None and reached.frames - 1 < done:
                self._ready = reached.frames - 1
                self._pending_status, self._pending_message = reached.status, reached.message

    def advance(self, frame_dt_s: float) -> bool:
        """Advance one frame; on failure keep the last good state, pause and explain. Returns running."""
        if not self.running:
            return False
        if frame_dt_s != self._frame_dt_s:
            # A new frame length: frames (and any failure) precomputed with the old one no longer apply.
            self._ready = self._next = 0
            self._pending_status = "ok"
        if self._next >= self._ready:
            if self._pending_status != "ok":
                return self._fail(frame_dt_s)  # playback has reached the failure found in the last batch
            self._refill(frame_dt_s)
            if self._ready == 0:
                return self._fail(frame_dt_s)
        self.y = self._buffer[self._next].copy()
        self._next += 1
        self.t_s += frame_dt_s
        return True

    def _fail(self, frame_dt_s: float) -> bool:
        self.status = self._pending_status if self._pending_status != "ok" else "non_finite"
        self.stop_event = self._pending_event if self.status == "event" else None
        self.message = self._pending_message or failure_message(
            self.status, self.t_s, self.integrator, frame_dt_s, system=self.system
        )
        return False
