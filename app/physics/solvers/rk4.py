"""Classical fixed-step Runge–Kutta, order 4, with a projection after each step."""

from __future__ import annotations

import math

import numpy as np
from numba import types

from app.physics.solvers.base import FixedStepIntegrator, FramesOutcome
from app.physics.solvers.kernels import MATRIX, PROJECT_TYPE, RHS_TYPE, VECTOR, kernel, no_projection

#: Status codes shared by the fixed-step kernels.
STATUS_OK = 0
STATUS_NON_FINITE = 1


@kernel(types.int64(RHS_TYPE, PROJECT_TYPE, types.float64, VECTOR, types.float64, types.int64, types.int64, VECTOR, MATRIX, MATRIX))
def rk4_frames(rhs, project, t0, y, h, steps_per_frame, n_frames, p, y_frames, work):
    """Advance ``y`` (in place) ``n_frames`` frames of ``steps_per_frame`` RK4 steps of ``h`` s.

    Writes the state after frame ``i`` to ``y_frames[i]`` (shape (n_frames, n)).
    ``work`` is scratch of shape (5, n). Returns the number of frames completed;
    fewer than ``n_frames`` means the state stopped being finite, and ``y`` then
    holds the last finite state.
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

    name = "rk4"
    label = "RK4 + projection"
    order = 4
    evals_per_step = 4

    def run_frames(self, system, t0_s, y, frame_dt_s, n_frames, y_frames, *, backend="numba"):
        project = system.project or no_projection
        h = frame_dt_s / self.steps_per_frame
        done = rk4_frames.get(backend)(
            system.rhs.get(backend), project.get(backend), float(t0_s), y, h,
            self.steps_per_frame, int(n_frames), system.parameters, y_frames, rk4_work(y.shape[0]),
        )
        steps = done * self.steps_per_frame
        return FramesOutcome(
            frames_done=int(done), steps=steps, rhs_evals=4 * steps,
            status="ok" if done == n_frames else "non_finite",
        )
