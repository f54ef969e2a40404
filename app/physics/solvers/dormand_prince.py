"""Dormand–Prince 5(4): adaptive steps, dense output and event location.

The pair and its quartic continuous extension are the ones of Dormand & Prince
(1980) and Shampine (1986), as used by scipy's ``RK45``; the step-size
controller is the classical one (safety 0.9, growth clipped to [0.2, 10]) on
the RMS norm of the local error scaled by ``atol + rtol·|y|``.
Events: after every accepted step each event function is checked at the
step's ends; a sign change is located on the dense output by the Illinois
method to about 1e-13 of the step, which keeps the event time as accurate as
the solution itself. The earliest event that acts either stops the run
(terminal) or applies its reset map, after which the step restarts from the
reset state (the rest of the step, computed from the old state, is dropped).
"""

from __future__ import annotations

import math

import numpy as np
from numba import types
from numba.extending import register_jitable

from app.physics.solvers.base import EventRecord, FramesOutcome, Integrator
from app.physics.solvers.constraints import project_onto_constraints
from app.physics.solvers.kernels import (
    CONSTRAINT_TYPE,
    EVENTS_TYPE,
    INDEX_VECTOR,
    MATRIX,
    PROJECT_TYPE,
    RESET_TYPE,
    RHS_TYPE,
    VECTOR,
    kernel,
    no_constraint,
    no_events,
    no_projection,
    no_reset,
)
from app.physics.solvers.spec import MethodSpec, Supports
from app.physics.solvers.status import EVENT, NON_FINITE, OK, STEP_TOO_SMALL, TOO_MANY_STEPS, status_name
from app.physics.solvers.system import EVENT_RECORD, EVENT_STOP

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

# Indices into the ``stats`` array.
STAT_ACCEPTED, STAT_REJECTED, STAT_RHS_EVALS, STAT_T_FINAL, STAT_T_EVENT, STAT_OUTPUTS, STAT_EVENTS = range(7)
N_STATS = 7
#: Events recorded per call at most (later ones are counted, not stored).
MAX_EVENT_RECORDS = 10_000


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


@register_jitable
def _locate_event(events, index, a, b, ga, gb, t, y, K, h, p, state, g_values):
    """θ in (a, b] where event ``index`` crosses zero (``ga``, ``gb`` its values at θ = a, b),
    by the Illinois method on the step's dense output."""
    side = 0
    for _ in range(100):
        c = (a * gb - b * ga) / (gb - ga)
        if not (c > a and c < b):
            c = 0.5 * (a + b)
        dense_state(c, y, K, h, state)
        events(t + c * h, state, p, g_values)
        gc = g_values[index]
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
    return b


@register_jitable
def _crosses(g_before, g_after, direction):
    """Whether an event function going from ``g_before`` to ``g_after`` crosses zero in ``direction``."""
    crossed = (g_before < 0.0 and g_after >= 0.0) or (g_before > 0.0 and g_after <= 0.0)
    return crossed and (direction == 0 or (direction > 0) == (g_after > g_before))


@register_jitable
def _record_event(event_log, stats, t, index, state):
    """Append ``[t, index, state…]`` to ``event_log`` if there is room; count it either way."""
    count = int(stats[STAT_EVENTS])
    if count < event_log.shape[0]:
        event_log[count, 0] = t
        event_log[count, 1] = index
        for i in range(state.shape[0]):
            event_log[count, 2 + i] = state[i]
    stats[STAT_EVENTS] = count + 1


@kernel(
    types.int64(
        RHS_TYPE,
        PROJECT_TYPE,
        EVENTS_TYPE,
        RESET_TYPE,
        CONSTRAINT_TYPE,
        types.float64,
        VECTOR,
        VECTOR,
        types.float64,
        types.float64,
        types.float64,
        types.float64,
        types.int64,
        VECTOR,
        MATRIX,
        MATRIX,
        VECTOR,
        INDEX_VECTOR,
        INDEX_VECTOR,
        MATRIX,
        MATRIX,
        types.boolean,
        types.int64,
        types.int64,
    )
)
def dopri5_solve(
    rhs,
    project,
    events,
    reset,
    constraint,
    t0,
    y,
    t_out,
    rtol,
    atol,
    h_init,
    h_max,
    max_steps,
    p,
    y_out,
    work,
    stats,
    directions,
    actions,
    event_work,
    event_log,
    has_projection,
    n_positions,
    n_constraints,
):
    """Integrate from ``t0`` to ``t_out[-1]``, writing ``y(t_out[j])`` into ``y_out[j]``.

    ``y`` is advanced in place; no step is longer than ``h_max`` (s). ``work`` is scratch of shape (10, n); ``stats``
    (length ``N_STATS``) receives the counters (see the ``STAT_*`` indices).
    Events: ``directions`` and ``actions`` (``EVENT_RECORD``/``STOP``/``RESET``)
    have one entry per event function (length 0: no events); ``event_work`` is
    scratch (5, m); each located event is logged as a row ``[t, index, y…]`` of
    ``event_log`` (capacity, 2 + n). A terminal event leaves ``y`` at the event.
    With ``n_constraints > 0`` accepted steps end on the constraint manifold.
    Returns a status code from :mod:`app.physics.solvers.status`.
    """
    n = y.shape[0]
    m = directions.shape[0]
    K = work[0:7]
    y_new = work[7]
    stage = work[8]
    scratch = work[9]
    g_old = event_work[0]
    g_new = event_work[1]
    g_probe = event_work[2]
    theta_cross = event_work[3]
    g_mid = event_work[4]
    t_end = t_out[t_out.shape[0] - 1]
    for k in range(N_STATS):
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
    if m > 0:
        events(t, y, p, g_old)
    next_out = 0
    while next_out < t_out.shape[0] and t_out[next_out] <= t0:
        for i in range(n):
            y_out[next_out, i] = y[i]
        next_out += 1
    accepted = 0
    rejected = 0
    status = OK
    while t < t_end:
        if accepted + rejected >= max_steps:
            status = TOO_MANY_STEPS
            break
        if h < 16.0 * 2.220446049250313e-16 * max(abs(t), 1.0):
            status = STEP_TOO_SMALL
            break
        if h > h_max:
            h = h_max
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
                status = NON_FINITE
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
        # The earliest event that acts (stops or resets) inside the step, at θ = theta_event.
        theta_event = 2.0
        acting = -1
        if m > 0:
            # Each event function is checked at the step's middle as well as its ends, so an
            # excursion that leaves and re-crosses within one long step (a ball's whole flight
            # after a bounce, where the parabola lets the step grow) is still seen.
            dense_state(0.5, y, K, h, scratch)
            events(t + 0.5 * h, scratch, p, g_mid)
            events(t_step_end, y_new, p, g_new)
            for i in range(m):
                theta_cross[i] = 2.0
                if _crosses(g_old[i], g_mid[i], directions[i]):
                    theta_cross[i] = _locate_event(
                        events, i, 0.0, 0.5, g_old[i], g_mid[i], t, y, K, h, p, scratch, g_probe
                    )
                elif _crosses(g_mid[i], g_new[i], directions[i]):
                    theta_cross[i] = _locate_event(
                        events, i, 0.5, 1.0, g_mid[i], g_new[i], t, y, K, h, p, scratch, g_probe
                    )
                if theta_cross[i] <= 1.0:
                    if actions[i] != EVENT_RECORD and theta_cross[i] < theta_event:
                        theta_event = theta_cross[i]
                        acting = i
            for i in range(m):
                if actions[i] == EVENT_RECORD and theta_cross[i] <= min(theta_event, 1.0):
                    dense_state(theta_cross[i], y, K, h, scratch)
                    _record_event(event_log, stats, t + theta_cross[i] * h, i, scratch)
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
            # The interpolant leaves the manifold by its own error: a frame is projected as a step's end is.
            if has_projection:
                project(y_out[next_out], p)
            if n_constraints > 0:
                project_onto_constraints(constraint, y_out[next_out], p, n_positions, n_constraints)
            next_out += 1
        if acting >= 0:
            dense_state(theta_event, y, K, h, scratch)
            t = t + theta_event * h
            for i in range(n):
                y[i] = scratch[i]
            _record_event(event_log, stats, t, acting, y)
            if actions[acting] == EVENT_STOP:
                stats[STAT_T_EVENT] = t
                status = EVENT
                break
            # Reset map, then restart the step from the reset state.
            reset(t, y, p, acting)
            if has_projection:
                project(y, p)
            if n_constraints > 0:
                project_onto_constraints(constraint, y, p, n_positions, n_constraints)
            rhs(t, y, p, K[0])
            n_eval += 1
            events(t, y, p, g_old)
            # The state is on the acting event's surface: the sign of its g there is round-off noise.
            g_old[acting] = 0.0
            continue
        if m > 0:
            for i in range(m):
                g_old[i] = g_new[i]
        t = t_step_end
        corrected = has_projection or n_constraints > 0
        if has_projection:
            project(y_new, p)
        if n_constraints > 0:
            project_onto_constraints(constraint, y_new, p, n_positions, n_constraints)
        for i in range(n):
            y[i] = y_new[i]
        if corrected:
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


class DormandPrince(Integrator):
    """Adaptive Dormand–Prince 5(4) with dense output at the frame times."""

    def __init__(self, *, rtol: float = 1e-8, atol: float | None = None, max_steps: int = 2_000_000) -> None:
        if not (math.isfinite(rtol) and 1e-14 <= rtol <= 1e-2):
            raise ValueError(f"rtol must lie between 1e-14 and 1e-2 (got {rtol!r})")
        self.spec = DOPRI5_SPEC
        self.rtol = float(rtol)
        self.atol = float(atol) if atol is not None else 1e-3 * self.rtol
        self.max_steps = int(max_steps)

    def describe(self, frame_dt_s: float) -> str:
        return f"{self.label}, rtol = {self.rtol:.0e}"

    def _run_frames(self, system, t0_s, y, frame_dt_s, n_frames, y_frames, *, backend="numba"):
        t_out = t0_s + frame_dt_s * np.arange(1, n_frames + 1, dtype=float)
        return self.solve(system, t0_s, y, t_out, y_frames, backend=backend)

    def solve(self, system, t0_s, y, t_out, y_out, *, backend="numba", events: bool = True) -> FramesOutcome:
        """Integrate to ``t_out[-1]`` writing ``y(t_out)`` into ``y_out`` (len(t_out), n).

        The system's events act (stop, reset or are recorded) unless ``events=False``.
        """
        self.spec.check_system(system)
        n = y.shape[0]
        stats = np.zeros(N_STATS)
        project = system.project or no_projection
        event_set = system.events if events else None
        if event_set is not None:
            event_functions, reset = event_set.functions, event_set.reset or no_reset
            directions, actions = event_set.direction_array(), event_set.action_array()
        else:
            event_functions, reset = no_events, no_reset
            directions = actions = np.zeros(0, dtype=np.int64)
        constraints = system.constraints if system.constraints is not None and system.constraints.project else None
        event_log = np.empty((MAX_EVENT_RECORDS if event_set is not None else 0, 2 + n))
        status = dopri5_solve.get(backend)(
            system.rhs.get(backend),
            project.get(backend),
            event_functions.get(backend),
            reset.get(backend),
            (constraints.function if constraints is not None else no_constraint).get(backend),
            float(t0_s),
            y,
            np.ascontiguousarray(t_out, dtype=float),
            self.rtol,
            self.atol,
            0.0,
            event_set.max_step_s if event_set is not None else math.inf,
            self.max_steps,
            system.parameters,
            y_out,
            dopri5_work(n),
            stats,
            directions,
            actions,
            np.empty((5, directions.shape[0])),
            event_log,
            system.project is not None,
            constraints.n_positions if constraints is not None else 0,
            constraints.n_constraints if constraints is not None else 0,
        )
        recorded = min(int(stats[STAT_EVENTS]), event_log.shape[0])
        return FramesOutcome(
            frames_done=int(stats[STAT_OUTPUTS]),
            steps=int(stats[STAT_ACCEPTED] + stats[STAT_REJECTED]),
            rhs_evals=int(stats[STAT_RHS_EVALS]),
            status=status_name(status),
            t_event_s=float(stats[STAT_T_EVENT]) if status == EVENT else None,
            events=tuple(EventRecord(float(row[0]), int(row[1]), row[2:].copy()) for row in event_log[:recorded]),
        )


DOPRI5_SPEC = MethodSpec(
    name="dopri5",
    label="Dormand–Prince 5(4), adaptive",
    short_label="Dormand–Prince 5(4)",
    description="Dormand–Prince 5(4): adaptive steps to a relative tolerance, dense output",
    order=ORDER,
    # Six new stages per attempted step (FSAL); one more after a projection or a reset.
    evals_per_step=6,
    substeps_per_step=1,
    adaptive=True,
    geometric=False,
    step_ratio=None,
    supports=Supports(events=True, reset_maps=True, projection=True, constraints=True),
    needs_torque=False,
    factory=DormandPrince,
)
