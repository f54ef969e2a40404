"""Base for scenes whose motion is integrated live, a frame at a time.

It owns the :class:`~app.physics.solvers.LiveRun`, the integration
controls (method, steps per frame, tolerance), the blow-up pause and the live
readout the lesson page polls: time, method and step, the accuracy target with
the error estimated for the step in use, the error against the model's reference
solution where it has one (phase error, not only drift), invariant drift (with a
short history for a plot) and the physics cost per frame.

A restart never waits for the step choice's pilot: it starts at once with the
cached choice, or else the fixed step rule ("estimating…" in the panel), and the
pilot runs in the worker's background queue (:mod:`.background_pilots`); its
choice replaces the running integrator at the next frame boundary, from the
state reached.
"""

from __future__ import annotations

import time
from collections import deque
from collections.abc import Mapping
from dataclasses import replace
from typing import Any, ClassVar

import numpy as np

from app.physics.solvers import LiveRun
from app.physics.solvers.base import Integrator
from app.physics.solvers.controls import CONTROL_NAMES
from app.physics.solvers.integrated_model import IntegratedModel
from app.physics.solvers.solve import remedy
from app.physics.solvers.step_choice import ESTIMATING, PILOT_FAILED, StepChoice
from app.physics.solvers.step_policy import choose_integrator
from app.physics.solvers.system import OdeSystem
from app.scenes.kit.background_pilots import PILOTS
from app.scenes.kit.scene import FRAME_DT_S, Scene, motion_numbers

DRIFT_HISTORY_FRAMES = 300  # 10 s of history at 30 Hz
#: Invariants are evaluated every 6th frame (5 Hz): enough for the drift plot and the runaway check, and a
#: sixth of their cost per frame (with a class of 100 that cost is paid 3000 times a second).
DRIFT_SAMPLE_EVERY = 6
#: The error against a reference solution is evaluated every 30th frame (1 Hz): a readout line, not a plot, and an
#: exact solution (the heavy top's quadrature: about 0.3 ms a time) would otherwise cost more than the frame's physics.
REFERENCE_SAMPLE_EVERY = 30
#: Physics CPU (s) a live scene's automatic step may cost per frame (every viewer of a class pays it 30 times a
#: second): about the costliest default of the fixed step rule before the targets (the slider-crank DAE's 0.84 ms),
#: so a target never makes a scene dearer than that; beyond it the accuracy is lowered and the panel says so.
LIVE_PHYSICS_BUDGET_S = 1e-3
#: An invariant off by more than this fraction of its scale means the step is far
#: too large: the motion on screen would be fiction, so the scene pauses.
RUNAWAY_DRIFT = 0.2


def live_integrator(
    model: IntegratedModel,
    params: Mapping[str, Any],
    controls: Mapping[str, Any],
    frame_dt_s: float,
    *,
    run_pilots: bool = True,
) -> tuple[Integrator, StepChoice | None]:
    """The integrator a live scene runs for ``params`` and ``controls`` at ``frame_dt_s`` (s of simulated time a
    frame), and the step choice behind it: the choice within a live frame's physics budget
    (:data:`LIVE_PHYSICS_BUDGET_S`). The one place a live scene's integration is chosen: its restart (without pilots),
    its background pilot, and the pages that state what the scene runs (the Solver lab) all ask here."""
    return choose_integrator(
        model, params, controls, frame_dt_s, run_pilots=run_pilots, max_frame_cpu_s=LIVE_PHYSICS_BUDGET_S
    )


class IntegratedScene(Scene):
    """A scene driven by an :class:`IntegratedModel`; subclasses draw :attr:`run`'s state."""

    model: ClassVar[type[IntegratedModel]]
    #: The model instance the running integration was built from (a constrained model's algorithm choice included).
    run_model: IntegratedModel
    animated = True

    def physical_params(self) -> dict[str, Any]:
        """The model's parameters only (no scene or integration controls)."""
        return {name: self.params[name] for name in self.model.parameters.by_name}

    def integration_controls(self) -> dict[str, Any]:
        """Method, steps per frame and tolerance."""
        return {k: v for k, v in self.params.items() if k in CONTROL_NAMES}

    @classmethod
    def frame_dt_for(cls, params: Mapping[str, Any]) -> float:
        """Simulated seconds per displayed frame for the scene's values ``params`` (a scene showing time faster than
        real time scales it)."""
        return FRAME_DT_S

    @property
    def frame_dt_s(self) -> float:
        """Simulated seconds per displayed frame (:meth:`frame_dt_for` the scene's values)."""
        return self.frame_dt_for(self.params)

    @classmethod
    def live_default(cls, values: Mapping[str, Any] | None = None) -> tuple[Integrator, StepChoice | None, float]:
        """``(integrator, step choice, frame_dt_s)`` a page's scene runs for ``values`` (omitted: the defaults) once its
        step choice's pilot has answered, which this runs (or reuses): what the scene's live panel shows."""
        params = cls.parameters.validate(dict(values or {}))
        physical = {name: params[name] for name in cls.model.parameters.by_name}
        controls = {k: v for k, v in params.items() if k in CONTROL_NAMES}
        frame_dt = cls.frame_dt_for(params)
        integrator, choice = live_integrator(cls.model(), physical, controls, frame_dt)
        return integrator, choice, frame_dt

    def new_run(self, system: OdeSystem, integrator: Integrator, y0: np.ndarray) -> LiveRun:
        """The live run :meth:`step_physics` advances by :data:`FRAME_DT_S` a frame, stopping where the model's
        assumptions stop holding (:meth:`~app.physics.solvers.integrated_model.IntegratedModel.model_limit`)."""
        return LiveRun(system, integrator, y0, limit=self.model_limit())

    def model_limit(self):
        """The running model's :meth:`model_limit` for the current parameters, or None for a model that has none."""
        model = getattr(self, "run_model", None) or self.model()
        if type(model).model_limit is IntegratedModel.model_limit:
            return None
        params = self.physical_params()
        return lambda t_s, states: model.model_limit(params, t_s, states)

    def describe(self, integrator: Integrator) -> str:
        """The integration in words for the readout ("RK4, 12 steps/frame")."""
        return integrator.describe(self.frame_dt_s)

    def restart(self) -> None:
        """(Re)start the integration from the current parameters' initial state, without waiting for a pilot."""
        model = self.model()
        params = self.physical_params()
        controls = self.integration_controls()
        frame_dt = self.frame_dt_s
        integrator, self.accuracy = live_integrator(model, params, controls, frame_dt, run_pilots=False)
        self.run_model = model
        self.run = self.new_run(model.system(params), integrator, model.initial_state(params))
        self.description = self.describe(integrator)
        self._generation = getattr(self, "_generation", 0) + 1
        self._applied = 0
        self._measured: tuple[int, tuple[Integrator, StepChoice | None] | None] | None = None
        if self.accuracy is not None and self.accuracy.status == ESTIMATING:
            generation = self._generation
            PILOTS.submit(
                id(self),
                lambda: live_integrator(self.model(), params, controls, frame_dt),
                lambda chosen: setattr(self, "_measured", (generation, chosen)),
            )
        self._scales = model.invariant_scales(params, self.run.y)
        self._invariants0 = {k: float(v[0]) for k, v in model.invariants(params, self.run.y[None, :]).items()}
        self._drift_t: deque[float] = deque(maxlen=DRIFT_HISTORY_FRAMES // DRIFT_SAMPLE_EVERY)
        self._drift_max: deque[float] = deque(maxlen=DRIFT_HISTORY_FRAMES // DRIFT_SAMPLE_EVERY)
        self._frames = 0
        self._physics_s = 0.0
        self.status = ""
        self._reference_error: float | None = None
        self._reference_error_max = 0.0
        limit = model.model_limit(params, np.array([self.run.t_s]), self.run.y[None, :])
        if limit is not None:  # the start itself is outside the model (a floor that would have to pull): shown, not run
            self.run.status, self.run.message = limit.status, limit.message
            self.status = limit.message

    def step_physics(self) -> bool:
        """Advance one frame of simulated time; on blow-up pause with the reason."""
        # Wall time, not time.thread_time(): under load that clock's system call cost more than a whole frame's
        # physics (measured: a fifth of a scene worker's CPU). Most frames only copy a precomputed state; the
        # compiled batch that fills them runs every few frames and may wait for the GIL after it, which this counts.
        self._take_measured_choice()
        start = time.perf_counter()
        running = self.run.advance(FRAME_DT_S)
        self._physics_s += time.perf_counter() - start
        self._frames += 1
        if not running:  # a blow-up, or the model's own edge (lift-off, a singular mass matrix…) in its words
            event = self.run.stop_event
            stopped = self.run_model.stop_message(self.physical_params(), event) if event is not None else ""
            self.status = stopped or self.run.message
            return False
        if self._frames % REFERENCE_SAMPLE_EVERY == 0:
            self._sample_reference_error()
        if self._frames % DRIFT_SAMPLE_EVERY == 0:
            drift = self.current_drift()
            worst = max(drift, key=drift.__getitem__, default=None)
            self._drift_t.append(self.run.t_s)
            self._drift_max.append(drift[worst] if worst else 0.0)
            if worst is not None and drift[worst] > RUNAWAY_DRIFT:
                self.run.status = "runaway"
                self.status = (
                    f"Paused at t = {self.run.t_s:.2f} s: {worst.replace('_', ' ')} has drifted by "
                    f"{100 * drift[worst]:.0f}% of its scale with {self.description}, so the motion shown is no longer "
                    f"the physics. {remedy(self.run.system)}."
                )
                return False
        return True

    def _take_measured_choice(self) -> None:
        """At a frame boundary: switch to the pilot's choice for the current parameters, if it has arrived."""
        measured = self._measured  # written once per restart by the pilot thread; read, never cleared, here
        if measured is None or measured[0] != self._generation or self._applied == self._generation:
            return  # nothing yet, or a pilot for parameters since changed, or already applied
        self._applied = self._generation
        chosen = measured[1]
        if chosen is None:
            assert self.accuracy is not None
            self.accuracy = replace(
                self.accuracy,
                status=PILOT_FAILED,
                note="the pilot failed, so the error of the fixed step rule is unknown",
            )
            return
        integrator, self.accuracy = chosen
        old = self.run
        self.run = self.new_run(old.system, integrator, old.y)
        self.run.t_s, self.run.steps = old.t_s, old.steps
        self.description = self.describe(integrator)

    # -- motion ------------------------------------------------------------------------------------------------
    def step_motion(self, dt_s: float) -> bool:
        """One frame of :attr:`frame_dt_s` simulated time (``dt_s`` is the host's frame), without drawing."""
        return self.step_physics()

    def restart_motion(self) -> None:
        """Back to the initial state: :meth:`update` restarts the integration and draws it."""
        self.update()

    def motion_state(self) -> dict[str, Any]:
        """``{"t_s": simulated time (s), "y": the model's state vector}`` (a trail starts again after resume_from)."""
        return {"t_s": float(self.run.t_s), "y": [float(v) for v in self.run.y]}

    def resume_from(self, motion: Mapping[str, Any]) -> None:
        """Continue the integration from ``motion`` (:meth:`motion_state` of an instance with the same parameters),
        with the integrator running now; a pause (blow-up) is lifted. ValueError ("motion: …") if it does not fit."""
        t_s = motion_numbers(motion, ("t_s",))["t_s"]
        try:
            y = np.array(motion["y"], dtype=float)
        except (KeyError, TypeError, ValueError):
            raise ValueError("motion: needs t_s (s) and y (the state vector)") from None
        if y.shape != self.run.y.shape or not np.all(np.isfinite(y)):
            raise ValueError(f"motion: y must be {self.run.y.size} finite numbers")
        old = self.run
        self.run = self.new_run(old.system, old.integrator, y)
        self.run.t_s, self.run.steps = t_s, old.steps
        self.status = ""
        self.clear_trails()

    def motion_cost_s(self) -> float | None:
        """The physics of one frame (s), the mean over the frames this run has advanced; None before the first."""
        return self._physics_s / self._frames if self._frames else None

    def step_without_drawing(self, t_s: float) -> None:
        """Step whole frames to the one nearest ``t_s`` (simulated s), keeping the step choice the run started with:
        a pilot's choice arriving meanwhile applies at the next live frame, so the result does not depend on when."""
        frames = round(t_s / self.frame_dt_s)
        applied = self._applied
        self._applied = self._generation  # read by _take_measured_choice as "already applied"
        try:
            for _ in range(frames):
                if not self.step_motion(FRAME_DT_S) or not self.pace():
                    break
        finally:
            if self._applied == self._generation:
                self._applied = applied

    def close(self) -> None:
        PILOTS.cancel(id(self))
        super().close()

    def _sample_reference_error(self) -> None:
        """The error of the current state against the model's reference at this time (target's unit), if it has one."""
        model = self.run_model
        if not model.reference_error_series:
            return
        error = model.reference_error(self.physical_params(), np.array([self.run.t_s]), self.run.y[None, :])
        if error is not None and np.isfinite(error[0]):
            self._reference_error = float(error[0])
            self._reference_error_max = max(self._reference_error_max, self._reference_error)

    def accuracy_readout(self) -> dict[str, Any]:
        """Target, estimated error and setting ("target 1e-06 rad over 60 s · estimated 3e-07 rad · 12 steps/frame"),
        and the error against the reference so far; empty for a model that states no target."""
        out: dict[str, Any] = {}
        if self.accuracy is not None:
            fields = self.accuracy.as_dict() | {"status": self.accuracy.status, "note": self.accuracy.note}
            out["accuracy"] = {k: None if isinstance(v, float) and not np.isfinite(v) else v for k, v in fields.items()}
        model = self.run_model
        if self._reference_error is not None:
            unit = model.accuracy_target.unit if model.accuracy_target is not None else ""
            out["reference_error"] = {
                "name": model.reference_error_series,
                "reference": model.reference_name,
                "unit": unit,
                "value": self._reference_error,
                "max_so_far": self._reference_error_max,
            }
        return out

    def current_invariants(self) -> dict[str, float]:
        values = self.run_model.invariants(self.physical_params(), self.run.y[None, :])
        return {k: float(v[0]) for k, v in values.items()}

    def current_drift(self) -> dict[str, float]:
        now = self.current_invariants()
        return {k: abs(now[k] - self._invariants0[k]) / self._scales[k] for k in now}

    def live_readout(self) -> dict[str, Any]:
        """Numbers for the lesson page: time, method, invariants and their drift, cost."""
        model = self.run_model
        now = self.current_invariants()
        drift = self.current_drift()
        return {
            "t_s": self.run.t_s,
            "method": self.run.integrator.name,
            "description": self.description,
            "running": self.run.running,
            "status": self.status,
            "physics_us_per_frame": 1e6 * self._physics_s / max(self._frames, 1),
            "invariants": {
                name: {
                    "value": now[name],
                    "initial": self._invariants0[name],
                    "unit": model.invariant_units.get(name, ""),
                    "relative_drift": drift[name],
                }
                for name in now
            },
            "drift_history": {"t_s": list(self._drift_t), "max_relative_drift": list(self._drift_max)},
            **self.accuracy_readout(),
        }

    def frame_physics_cost_s(self, frames: int = 300) -> float:
        """Mean physics cost of one frame (s) over ``frames`` frames, measured off-screen."""
        probe = LiveRun(self.run.system, self.run.integrator, self.run.y.copy())
        probe.advance(FRAME_DT_S)
        start = time.perf_counter()
        for _ in range(frames):
            probe.advance(FRAME_DT_S)
        return (time.perf_counter() - start) / frames
