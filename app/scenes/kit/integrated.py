"""Base for scenes whose motion is integrated live, a frame at a time.

It owns the :class:`~app.physics.solvers.LiveRun`, the integration
controls (method, steps per frame, tolerance), the blow-up pause and the live
readout the lesson page polls: time, method and step, invariant drift (with a
short history for a plot) and the physics cost per frame.
"""

from __future__ import annotations

import time
from collections import deque
from typing import Any, ClassVar

from app.physics.solvers import LiveRun
from app.physics.solvers.controls import CONTROL_NAMES
from app.physics.solvers.integrated_model import IntegratedModel
from app.scenes.kit.scene import Scene

#: Simulated seconds per displayed frame (the host draws at 30 Hz).
FRAME_DT_S = 1.0 / 30.0
DRIFT_HISTORY_FRAMES = 300  # 10 s of history at 30 Hz
#: Invariants are evaluated every 6th frame (5 Hz): enough for the drift plot and the runaway check, and a
#: sixth of their cost per frame (with a class of 100 that cost is paid 3000 times a second).
DRIFT_SAMPLE_EVERY = 6
#: An invariant off by more than this fraction of its scale means the step is far
#: too large: the motion on screen would be fiction, so the scene pauses.
RUNAWAY_DRIFT = 0.2


class IntegratedScene(Scene):
    """A scene driven by an :class:`IntegratedModel`; subclasses draw :attr:`run`'s state."""

    model: ClassVar[type[IntegratedModel]]
    animated = True

    def physical_params(self) -> dict[str, Any]:
        """The model's parameters only (no scene or integration controls)."""
        return {name: self.params[name] for name in self.model.parameters.by_name}

    def integration_controls(self) -> dict[str, Any]:
        """Method, steps per frame and tolerance."""
        return {k: v for k, v in self.params.items() if k in CONTROL_NAMES}

    def restart(self) -> None:
        """(Re)start the integration from the current parameters' initial state."""
        model = self.model()
        params = self.physical_params()
        integrator = model.integrator(params, self.integration_controls(), FRAME_DT_S)
        self._model_instance = model
        self.run = LiveRun(model.system(params), integrator, model.initial_state(params))
        self.description = integrator.describe(FRAME_DT_S)
        self._scales = model.invariant_scales(params, self.run.y)
        self._invariants0 = {k: float(v[0]) for k, v in model.invariants(params, self.run.y[None, :]).items()}
        self._drift_t: deque[float] = deque(maxlen=DRIFT_HISTORY_FRAMES // DRIFT_SAMPLE_EVERY)
        self._drift_max: deque[float] = deque(maxlen=DRIFT_HISTORY_FRAMES // DRIFT_SAMPLE_EVERY)
        self._frames = 0
        self._physics_s = 0.0
        self.status = ""

    def step_physics(self) -> bool:
        """Advance one frame of simulated time; on blow-up pause with the reason."""
        # Wall time, not time.thread_time(): under load that clock's system call cost more than a whole frame's
        # physics (measured: a fifth of a scene worker's CPU). Most frames only copy a precomputed state; the
        # compiled batch that fills them runs every few frames and may wait for the GIL after it, which this counts.
        start = time.perf_counter()
        running = self.run.advance(FRAME_DT_S)
        self._physics_s += time.perf_counter() - start
        self._frames += 1
        if not running:
            self.status = self.run.message
            return False
        if self._frames % DRIFT_SAMPLE_EVERY == 0:
            drift = self.current_drift()
            worst = max(drift, key=drift.get, default=None)
            self._drift_t.append(self.run.t_s)
            self._drift_max.append(drift[worst] if worst else 0.0)
            if worst is not None and drift[worst] > RUNAWAY_DRIFT:
                self.run.status = "runaway"
                self.status = (
                    f"Paused at t = {self.run.t_s:.2f} s: {worst.replace('_', ' ')} has drifted by "
                    f"{100 * drift[worst]:.0f}% of its scale with {self.description}, so the motion shown is no longer "
                    f"the physics. Use more steps per frame or the splitting method."
                )
                return False
        return True

    def current_invariants(self) -> dict[str, float]:
        values = self._model_instance.invariants(self.physical_params(), self.run.y[None, :])
        return {k: float(v[0]) for k, v in values.items()}

    def current_drift(self) -> dict[str, float]:
        now = self.current_invariants()
        return {k: abs(now[k] - self._invariants0[k]) / self._scales[k] for k in now}

    def live_readout(self) -> dict[str, Any]:
        """Numbers for the lesson page: time, method, invariants and their drift, cost."""
        model = self._model_instance
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
                name: {"value": now[name], "initial": self._invariants0[name], "unit": model.invariant_units.get(name, ""), "relative_drift": drift[name]}
                for name in now
            },
            "drift_history": {"t_s": list(self._drift_t), "max_relative_drift": list(self._drift_max)},
        }

    def frame_physics_cost_s(self, frames: int = 300) -> float:
        """Mean physics cost of one frame (s) over ``frames`` frames, measured off-screen."""
        probe = LiveRun(self.run.system, self.run.integrator, self.run.y.copy())
        probe.advance(FRAME_DT_S)
        start = time.perf_counter()
        for _ in range(frames):
            probe.advance(FRAME_DT_S)
        return (time.perf_counter() - start) / frames

