"""Classical fixed-step Runge–Kutta, order 4, with projections after each step.

After every step the model's ``project`` hook runs (unit quaternion, say) and,
if the system declares projected :class:`~app.physics.solvers.system.Constraints`,
the state is moved back onto ``g(q) = 0``, ``G v = 0``.
"""

from __future__ import annotations

import math

import numpy as np
from numba import types

from app.physics.solvers.base import FixedStepIntegrator
from app.physics.solvers.constraints import project_onto_constraints
from app.physics.solvers.kernels import (
    CONSTRAINT_TYPE,
    MATRIX,
    PROJECT_TYPE,
    RHS_TYPE,
    VECTOR,
    kernel,
    no_constraint,
    no_projection,
)
from app.physics.solvers.spec import MethodSpec, Supports


@kernel(
    types.int64(
        RHS_TYPE,
        PROJECT_TYPE,
        CONSTRAINT_TYPE,
        types.float64,
        VECTOR,
        types.float64,
        types.int64,
        types.int64,
        VECTOR,
        MATRIX,
        MATRIX,
        types.int64,
        types.int64,
    )
)
def rk4_frames(
    rhs, project, constraint, t0, y, h, steps_per_frame, n_frames, p, y_frames, work, n_positions, n_constraints
):
    """Advance ``y`` (in place) ``n_frames`` frames of ``steps_per_frame`` RK4 steps of ``h`` s.

    Writes the state after frame ``i`` to ``y_frames[i]`` (shape (n_frames, n)).
    ``work`` is scratch of shape (5, n). With ``n_constraints > 0`` each step
    ends with :func:`project_onto_constraints` on ``y[:n_positions]`` and the
    velocities after them. Returns the number of frames completed; fewer than
    ``n_frames`` means the state stopped being finite, and ``y`` then holds the
    last finite state.
    """
    n = y.shape[0]
    k1 = work[0]
    k2 = work[1]
    k3 = work[2]
    k4 = work[3]
    stage = work[4]
    half = 0.5 * h
    sixth = h / 6.0
    for frame in range(n_frames):
        for step in range(steps_per_frame):
            t = t0 + h * (frame * steps_per_frame + step)
            rhs(t, y, p, k1)
            for i in range(n):
                stage[i] = y[i] + half * k1[i]
            rhs(t + half, stage, p, k2)
            for i in range(n):
                stage[i] = y[i] + half * k2[i]
            rhs(t + half, stage, p, k3)
            for i in range(n):
                stage[i] = y[i] + h * k3[i]
            rhs(t + h, stage, p, k4)
            finite = True
            for i in range(n):
                stage[i] = y[i] + sixth * (k1[i] + 2.0 * (k2[i] + k3[i]) + k4[i])
                if not math.isfinite(stage[i]):
                    finite = False
            if not finite:
                return frame
            project(stage, p)
            if n_constraints > 0:
                project_onto_constraints(constraint, stage, p, n_positions, n_constraints)
            for i in range(n):
                y[i] = stage[i]
        for i in range(n):
            y_frames[frame, i] = y[i]
    return n_frames


def rk4_work(n_state: int) -> np.ndarray:
    """Scratch array for :func:`rk4_frames`."""
    return np.empty((5, n_state))


class RK4(FixedStepIntegrator):
    """Classical Runge–Kutta of order 4, projecting onto the model's constraints after each step."""

    def __init__(self, *, steps_per_frame: int) -> None:
        super().__init__(steps_per_frame=steps_per_frame)
        self.spec = RK4_SPEC

    def _run_frames(self, system, t0_s, y, frame_dt_s, n_frames, y_frames, *, backend="numba"):
        project = system.project or no_projection
        constraints = system.constraints
        projected = constraints is not None and constraints.project
        h = frame_dt_s / self.steps_per_frame
        done = rk4_frames.get(backend)(
            system.rhs.get(backend),
            project.get(backend),
            (constraints.function if projected else no_constraint).get(backend),
            float(t0_s),
            y,
            h,
            self.steps_per_frame,
            int(n_frames),
            system.parameters,
            y_frames,
            rk4_work(y.shape[0]),
            constraints.n_positions if projected else 0,
            constraints.n_constraints if projected else 0,
        )
        return self.outcome(done, n_frames)


RK4_SPEC = MethodSpec(
    name="rk4",
    label="RK4",
    short_label="RK4",
    description=(
        "Classical Runge–Kutta 4; after each step the model's own "
        "projection, if it has one (a quaternion back to unit length)"
    ),
    order=4,
    evals_per_step=4,
    substeps_per_step=1,
    adaptive=False,
    geometric=False,
    # The classical rule h·ω ≲ 0.1.
    step_ratio=0.1,
    supports=Supports(projection=True, constraints=True),
    needs_torque=False,
    factory=RK4,
)
