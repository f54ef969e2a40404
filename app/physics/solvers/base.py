"""The integrator interface: a small object that advances a system frame by frame."""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from app.physics.solvers.kernels import Backend
from app.physics.solvers.system import OdeSystem


@dataclass(frozen=True)
class FramesOutcome:
    """What one call to :meth:`Integrator.run_frames` did."""

    frames_done: int
    steps: int
    rhs_evals: int
    #: "ok", "non_finite", "event", "step_too_small" or "too_many_steps".
    status: str = "ok"
    #: Time (s) of a terminal event, if one stopped the run.
    t_event_s: float | None = None


class Integrator(ABC):
    """Advances ``y`` through frames of equal length; subclasses implement one method each.

    ``name`` is the identifier used by the API and the controls; ``order`` is the
    global order of accuracy the tests measure.
    """

    name: ClassVar[str]
    label: ClassVar[str]
    order: ClassVar[int]
    adaptive: ClassVar[bool] = False

    @abstractmethod
    def run_frames(
        self,
        system: OdeSystem,
        t0_s: float,
        y: np.ndarray,
        frame_dt_s: float,
        n_frames: int,
        y_frames: np.ndarray,
        *,
        backend: Backend = "numba",
    ) -> FramesOutcome:
        """Advance ``y`` in place by ``n_frames`` frames, storing each frame's end state."""

    @abstractmethod
    def describe(self, frame_dt_s: float) -> str:
        """One line for a student: method, and step or tolerance, with units."""


class FixedStepIntegrator(Integrator):
    """An integrator taking ``steps_per_frame`` equal steps per frame."""

    #: Right-hand-side (or force) evaluations per step.
    evals_per_step: ClassVar[int]

    def __init__(self, *, steps_per_frame: int) -> None:
        if not isinstance(steps_per_frame, int) or steps_per_frame < 1:
            raise ValueError(f"steps_per_frame must be a whole number ≥ 1 (got {steps_per_frame!r})")
        self.steps_per_frame = steps_per_frame

    def describe(self, frame_dt_s: float) -> str:
        h_ms = 1e3 * frame_dt_s / self.steps_per_frame
        return f"{self.label}, {self.steps_per_frame} step{'' if self.steps_per_frame == 1 else 's'}/frame (h = {h_ms:.3g} ms)"
