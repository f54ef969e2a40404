"""Dormand–Prince 5(4): adaptive steps, dense output and event location.

The pair and its quartic continuous extension are the ones of Dormand & Prince
(1980) and Shampine (1986), as used by scipy's ``RK45``; the step-size
controller is the classical one (safety 0.9, growth clipped to [0.2, 10]) on
the RMS norm of the local error scaled by ``atol + rtol·|y|``.
Events: after every accepted step the event function is checked at the step's
ends; a sign change is located on the dense output by the Illinois method to
about 1e-13 of the step, which keeps the event time as accurate as the
solution itself.
"""

from __future__ import annotations

import math

import numpy as np
from numba import types
from numba.extending import register_jitable

from app.physics.solvers.base import FramesOutcome, Integrator
from app.physics.solvers.kernels import EVENT_TYPE, MATRIX, PROJECT_TYPE, RHS_TYPE, VECTOR, kernel, no_event, no_projection

C = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0])
A = np.array(
    [
        [0.0, 0.0, 0.0, 0.0, 0.0],
        [1 / 5, 0.0, 0.0, 0.0, 0.0],
        [3 / 40, 9 / 40, 0.0, 0.0, 0.0],
        [44 / 45, -56 / 15, 32 / 9, 0.0, 0.0],
        [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0],
        [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656],
    ]
)
B = np.array([35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84])
#: Difference between the 5th- and 4th-order weights (7 stages, FSAL).
E = np.array([-71 / 57600, 0.0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40])
#: Dense output: y(t + θh) = y + h Σ_j K_j (P_j0 θ + P_j1 θ² + P_j2 θ³ + P_j3 θ⁴).
P = np.array(
    [
        [1.0, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
        [0.0, 0.0, 0.0, 0.0],
        [0.0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799],
        [0.0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
        [0.0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632],
        [0.0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
        [0.0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423],
    ]
)
ORDER = 5
ERROR_ORDER = 4

STATUS_FINISHED = 0
STATUS_NON_FINITE = 1
STATUS_EVENT = 2
STATUS_STEP_TOO_SMALL = 3
STATUS_TOO_MANY_STEPS = 4

# Indices into the ``stats`` array.
STAT_ACCEPTED, STAT_REJECTED, STAT_RHS_EVALS, STAT_T_FINAL, STAT_T_EVENT, STAT_OUTPUTS = range(6)


@register_jitable
def dense_state(theta, y, K, h, out):
    """``out = y(t + θh)`` from the accepted step's stages ``K`` (7, n)."""
    t1 = theta
    t2 = t1 * theta
    t3 = t2 * theta
    t4 = t3 * theta
    for i in range(y.shape[0]):
        acc = 0.0
        for j in range(7):
            acc += K[j, i] * (P[j, 0] * t1 + P[j, 1] * t2 + P[j, 2] * t3 + P[j, 3] * t4)
        out[i] = y[i] + h * acc


@kernel(
    types.int64(
        RHS_TYPE, PROJECT_TYPE, EVENT_TYPE, types.float64, VECTOR, VECTOR, types.float64, types.float64,
        types.float64, types.int64, VECTOR, MATRIX, MATRIX, VECTOR, types.int64, types.boolean, types.boolean,
    )
)
def dopri5_solve(
    rhs, project, event, t0, y, t_out, rtol, atol, h_init, max_steps, p, y_out, work, stats,
    event_direction, event_terminal, has_projection,
):
    """Integrate from ``t0`` to ``t_out[-1]``, writing ``y(t_out[j])`` into ``y_out[j]``.

    ``y`` is advanced in place. ``work`` is scratch of shape (10, n); ``stats``
    receives the counters (see the ``STAT_*`` indices). With ``event_terminal``
    the run stops at the first sign change of ``event`` in ``event_direction``
    (+1 rising, −1 falling, 0 either); ``y`` then holds the state at the event.
    Returns a ``STATUS_*`` code.
    """
    n = y.shape[0]
    K = work[0:7]
    y_new = work[7]
    stage = work[8]
    scratch = work[9]
    t_end = t_out[t_out.shape[0] - 1]
    for k in range(6):
        stats[k] = 0.0
    stats[STAT_T_EVENT] = math.nan
    n_eval = 0
    t = t0
    rhs(t, y, p, K[0])
    n_eval += 1
    # Initial step (Hairer, Nørsett & Wanner, II.4) unless one is given.
    h = h_init
    if h <= 0.0:
        d0 = 0.0
        d1 = 0.0
        for i in range(n):
            sc = atol + rtol * abs(y[i])
            d0 += (y[i] / sc) ** 2
            d1 += (K[0, i] / sc) ** 2
        d0 = math.sqrt(d0 / n)
        d1 = math.sqrt(d1 / n)
        h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
        h0 = min(h0, t_end - t0)
        for i in range(n):
            stage[i] = y[i] + h0 * K[0, i]
        rhs(t + h0, stage, p, K[1])
        n_eval += 1
        d2 = 0.0
        for i in range(n):
            sc = atol + rtol * abs(y[i])
            d2 += ((K[1, i] - K[0, i]) / sc) ** 2
        d2 = math.sqrt(d2 / n) / h0
        if max(d1, d2) <= 1e-15:
            h1 = max(1e-6, h0 * 1e-3)
        else:
            h1 = (0.01 / max(d1, d2)) ** (1.0 / ORDER)
        h = min(100.0 * h0, h1)
    g_old = event(t, y, p)
    next_out = 0
    while next_out < t_out.shape[0] and t_out[next_out] <= t0:
        for i in range(n):
            y_out[next_out, i] = y[i]
        next_out += 1
    accepted = 0
    rejected = 0
    status = STATUS_FINISHED
    while t < t_end:
        if accepted + rejected >= max_steps:
            status = STATUS_TOO_MANY_STEPS
            break
        if h < 16.0 * 2.220446049250313e-16 * max(abs(t), 1.0):
            status = STATUS_STEP_TOO_SMALL
            break
        last = False
        if t + h >= t_end:
            h = t_end - t
            last = True
        for s in range(1, 6):
            for i in range(n):
                acc = 0.0
                for j in range(s):
                    acc += A[s, j] * K[j, i]
                stage[i] = y[i] + h * acc
            rhs(t + C[s] * h, stage, p, K[s])
        for i in range(n):
            acc = 0.0
            for j in range(6):
                acc += B[j] * K[j, i]
            y_new[i] = y[i] + h * acc
        rhs(t + h, y_new, p, K[6])
        n_eval += 6
        err = 0.0
        finite = True
        for i in range(n):
            e = 0.0
            for j in range(7):
                e += E[j] * K[j, i]
            sc = atol + rtol * max(abs(y[i]), abs(y_new[i]))
            err += (h * e / sc) ** 2
            if not math.isfinite(y_new[i]):
                finite = False
        err = math.sqrt(err / n)
        if not finite or not math.isfinite(err):
            if h < 1e-300:
                status = STATUS_NON_FINITE
                break
            h *= 0.2
            rejected += 1
            continue
        if err > 1.0:
            h *= max(0.2, 0.9 * err ** (-1.0 / (ERROR_ORDER + 1)))
            rejected += 1
            continue
        # Accepted step [t, t + h].
        accepted += 1
        t_step_end = t_end if last else t + h
        theta_event = 2.0
        if event_terminal:
            g_new = event(t_step_end, y_new, p)
            crossed = (g_old < 0.0 and g_new >= 0.0) or (g_old > 0.0 and g_new <= 0.0)
            if crossed and (event_direction == 0 or (event_direction > 0) == (g_new > g_old)):
                # Illinois iteration on θ in [0, 1] using the dense output.
                a = 0.0
                b = 1.0
                ga = g_old
                gb = g_new
                side = 0
                for _ in range(100):
                    c = (a * gb - b * ga) / (gb - ga)
                    if not (c > a and c < b):
                        c = 0.5 * (a + b)
                    dense_state(c, y, K, h, scratch)
                    gc = event(t + c * h, scratch, p)
                    if (gc < 0.0) == (ga < 0.0) and gc != 0.0:
                        a = c
                        ga = gc
                        if side == -1:
                            gb *= 0.5
                        side = -1
                    else:
                        b = c
                        gb = gc
                        if side == 1:
                            ga *= 0.5
                        side = 1
                    if gc == 0.0 or (b - a) * h <= 1e-13 * max(h, abs(t) * 1e-3):
                        break
                theta_event = b
            g_old = g_new
        # Dense output at requested times inside the step (and before an event).
        while next_out < t_out.shape[0] and t_out[next_out] <= t_step_end:
            theta = (t_out[next_out] - t) / h
            if theta > theta_event:
                break
            if t_out[next_out] == t_step_end:
                for i in range(n):
                    y_out[next_out, i] = y_new[i]
            else:
                dense_state(theta, y, K, h, scratch)
                for i in range(n):
                    y_out[next_out, i] = scratch[i]
            next_out += 1
        if theta_event <= 1.0:
            dense_state(theta_event, y, K, h, scratch)
            t = t + theta_event * h
            for i in range(n):
                y[i] = scratch[i]
            stats[STAT_T_EVENT] = t
            status = STATUS_EVENT
            break
        t = t_step_end
        if has_projection:
            project(y_new, p)
        for i in range(n):
            y[i] = y_new[i]
        if has_projection:
            rhs(t, y, p, K[0])
            n_eval += 1
        else:
            for i in range(n):
                K[0, i] = K[6, i]
        if err == 0.0:
            factor = 10.0
        else:
            factor = min(10.0, 0.9 * err ** (-1.0 / (ERROR_ORDER + 1)))
        h *= factor
    stats[STAT_ACCEPTED] = accepted
    stats[STAT_REJECTED] = rejected
    stats[STAT_RHS_EVALS] = n_eval
    stats[STAT_T_FINAL] = t
    stats[STAT_OUTPUTS] = next_out
    return status


def dopri5_work(n_state: int) -> np.ndarray:
    """Scratch array for :func:`dopri5_solve`."""
    return np.empty((10, n_state))


_STATUS_NAMES = {
    STATUS_FINISHED: "ok",
    STATUS_NON_FINITE: "non_finite",
    STATUS_EVENT: "event",
    STATUS_STEP_TOO_SMALL: "step_too_small",
    STATUS_TOO_MANY_STEPS: "too_many_steps",
}


class DormandPrince(Integrator):
    """Adaptive Dormand–Prince 5(4) with dense output at the frame times."""

    name = "dopri5"
    label = "Dormand–Prince 5(4), adaptive"
    order = 5
    adaptive = True

    def __init__(self, *, rtol: float = 1e-8, atol: float | None = None, max_steps: int = 2_000_000) -> None:
        if not (math.isfinite(rtol) and 1e-14 <= rtol <= 1e-2):
            raise ValueError(f"rtol must lie between 1e-14 and 1e-2 (got {rtol!r})")
        self.rtol = float(rtol)
        self.atol = float(atol) if atol is not None else 1e-3 * self.rtol
        self.max_steps = int(max_steps)

    def describe(self, frame_dt_s: float) -> str:
        return f"{self.label}, rtol = {self.rtol:.0e}"

    def run_frames(self, system, t0_s, y, frame_dt_s, n_frames, y_frames, *, backend="numba"):
        t_out = t0_s + frame_dt_s * np.arange(1, n_frames + 1, dtype=float)
        return self.solve(system, t0_s, y, t_out, y_frames, backend=backend)

    def solve(self, system, t0_s, y, t_out, y_out, *, backend="numba", terminal_event: bool = False) -> FramesOutcome:
        """Integrate to ``t_out[-1]`` writing ``y(t_out)``; optionally stop at the system's event."""
        stats = np.zeros(6)
        project = system.project or no_projection
        event = system.event or no_event
        status = dopri5_solve.get(backend)(
            system.rhs.get(backend), project.get(backend), event.get(backend), float(t0_s), y,
            np.ascontiguousarray(t_out, dtype=float), self.rtol, self.atol, 0.0, self.max_steps,
            system.parameters, y_out, dopri5_work(y.shape[0]), stats, int(system.event_direction),
            bool(terminal_event and system.event is not None), system.project is not None,
        )
        return FramesOutcome(
            frames_done=int(stats[STAT_OUTPUTS]),
            steps=int(stats[STAT_ACCEPTED] + stats[STAT_REJECTED]),
            rhs_evals=int(stats[STAT_RHS_EVALS]),
            status=_STATUS_NAMES[int(status)],
            t_event_s=float(stats[STAT_T_EVENT]) if status == STATUS_EVENT else None,
        )
