"""The integrator interface: a small object that advances a system frame by frame.

The base class does the bookkeeping (the method's facts come from its
:class:`~app.physics.solvers.spec.MethodSpec`, and the system is checked
against what the method supports); subclasses implement one method each.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass

import numpy as np

from app.physics.solvers.kernels import Backend
from app.physics.solvers.spec import MethodSpec
from app.physics.solvers.status import NON_FINITE, OK, STATUS_NAMES
from app.physics.solvers.system import OdeSystem


@dataclass(frozen=True)
class EventRecord:
    """An event that happened: time ``t_s`` (s), which event function, and the state there (before any reset)."""

    t_s: float
    index: int
    state: np.ndarray


@dataclass(frozen=True)
class FramesOutcome:
    """What one call to :meth:`Integrator.run_frames` did."""

    frames_done: int
    steps: int
    rhs_evals: int
    #: A name from :data:`app.physics.solvers.status.STATUS_NAMES`.
    status: str = "ok"
    #: Time (s) of a terminal event, if one stopped the run.
    t_event_s: float | None = None
    #: Every event located during the call, in order.
    events: tuple[EventRecord, ...] = ()


class Integrator(ABC):
    """Advances ``y`` through frames of equal length.

    ``name``, ``label`` and ``order`` come from the method's spec (``name`` is
    the identifier used by the API and the controls).
    """

    spec: MethodSpec

    @property
    def name(self) -> str:
        return self.spec.name

    @property
    def label(self) -> str:
        return self.spec.label

    @property
    def order(self) -> int:
        return self.spec.order

    @property
    def adaptive(self) -> bool:
        return self.spec.adaptive

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
        """Advance ``y`` in place by ``n_frames`` frames, storing each frame's end state in ``y_frames`` (n_frames,
        n)."""
        self.spec.check_system(system)
        return self._run_frames(system, t0_s, y, frame_dt_s, n_frames, y_frames, backend=backend)

    @abstractmethod
    def _run_frames(self, system, t0_s, y, frame_dt_s, n_frames, y_frames, *, backend) -> FramesOutcome:
        """:meth:`run_frames` for a system already checked against the spec."""

    @abstractmethod
    def describe(self, frame_dt_s: float) -> str:
        """One line for a student: method, and step or tolerance, with units."""


class FixedStepIntegrator(Integrator):
    """An integrator taking ``steps_per_frame`` equal steps per frame."""

    def __init__(self, *, steps_per_frame: int) -> None:
        if not isinstance(steps_per_frame, int) or steps_per_frame < 1:
            raise ValueError(f"steps_per_frame must be a whole number ≥ 1 (got {steps_per_frame!r})")
        self.steps_per_frame = steps_per_frame

    @property
    def evals_per_step(self) -> int:
        return self.spec.evals_per_step

    def describe(self, frame_dt_s: float) -> str:
        h_ms = 1e3 * frame_dt_s / self.steps_per_frame
        return (
            f"{self.label}, {self.steps_per_frame} step{'' if self.steps_per_frame == 1 else 's'}/frame (h = "
            f"{h_ms:.3g} ms)"
        )

    def outcome(self, frames_done: int, n_frames: int, *, evals_per_run: int = 0) -> FramesOutcome:
        """Counters of a run that completed ``frames_done`` of ``n_frames`` (fewer: the state stopped being finite).

        ``evals_per_run``: evaluations made once per call on top of ``evals_per_step`` per step.
        """
        steps = int(frames_done) * self.steps_per_frame
        return FramesOutcome(
            frames_done=int(frames_done),
            steps=steps,
            rhs_evals=steps * self.spec.evals_per_step + evals_per_run,
            status=STATUS_NAMES[OK if frames_done == n_frames else NON_FINITE],
        )
