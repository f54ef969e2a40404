"""Along a run: the constraint residuals and the multipliers (what the plots and the series show).

``states`` (N, 2n) are ``(q, v)`` rows of a :class:`~.system.ConstrainedSystem`.
The position residual is max |g_i(q)| over the holonomic rows (in the rows' unit,
e.g. m² for ``g = (L² − x² − y²)/2``); the velocity residual max |(C v)_i| over all
rows (that unit per second). The multipliers are those of the index-1 equations
``[M Cᵀ; C 0]`` with ``C v̇ = −Ċ v`` at each state, signed as in :mod:`.system`
(``M v̇ = f + Cᵀλ``) — the constraint forces the
state itself calls for, whatever stabilisation the algorithm added.
Non-finite rows give NaN.
"""

from __future__ import annotations

import numpy as np
from numba import types

from app.physics.constrained.system import ConstrainedSystem
from app.physics.solvers.constraints import constrained_acceleration, kkt_inputs_finite
from app.physics.solvers.kernels import DYNAMICS_TYPE, MATRIX, MULTIPLIER_CONSTRAINTS_TYPE, VECTOR, kernel


@kernel(types.void(MULTIPLIER_CONSTRAINTS_TYPE, MATRIX, VECTOR, types.int64, types.int64, MATRIX))
def residuals_along(constraints, states, p, n_holonomic, n_constraints, out):
    """``out[k] = (max |g|, max |C v|)`` for each row of ``states`` (N, 2n); ``out`` (N, 2)."""
    n = states.shape[1] // 2
    g = np.empty(n_holonomic)
    C = np.empty((n_constraints, n))
    c = np.empty(n_constraints)
    for row in range(states.shape[0]):
        state = states[row]
        if not np.all(np.isfinite(state)):
            out[row, 0] = np.nan
            out[row, 1] = np.nan
            continue
        q = state[:n].copy()
        v = state[n : 2 * n].copy()
        constraints(q, v, p, g, C, c)
        position = 0.0
        for i in range(n_holonomic):
            position = max(position, abs(g[i]))
        velocity = 0.0
        for i in range(n_constraints):
            acc = 0.0
            for k in range(n):
                acc += C[i, k] * v[k]
            velocity = max(velocity, abs(acc))
        out[row, 0] = position
        out[row, 1] = velocity


@kernel(
    types.void(DYNAMICS_TYPE, MULTIPLIER_CONSTRAINTS_TYPE, VECTOR, MATRIX, VECTOR, types.int64, types.int64, MATRIX)
)
def multipliers_along(dynamics, constraints, t_s, states, p, n_holonomic, n_constraints, out):
    """``out[k]`` = λ (m,) of the index-1 equations at ``states[k]`` (N, 2n) and time ``t_s[k]`` (s); ``out`` (N, m)."""
    n = states.shape[1] // 2
    mass = np.empty((n, n))
    forces = np.empty(n)
    g = np.empty(n_holonomic)
    C = np.empty((n_constraints, n))
    c = np.empty(n_constraints)
    acceleration = np.empty(n)
    for row in range(states.shape[0]):
        state = states[row]
        if not np.all(np.isfinite(state)):
            for i in range(n_constraints):
                out[row, i] = np.nan
            continue
        q = state[:n].copy()
        v = state[n : 2 * n].copy()
        dynamics(t_s[row], q, v, p, mass, forces)
        constraints(q, v, p, g, C, c)
        if not kkt_inputs_finite(mass, C, forces, c):
            for i in range(n_constraints):
                out[row, i] = np.nan
            continue
        solved = constrained_acceleration(mass, C, forces, c, acceleration)
        for i in range(n_constraints):
            out[row, i] = -solved[i]  # the helper's unknown is −λ: M v̇ + Cᵀ(−λ) = f


def constraint_residuals(system: ConstrainedSystem, states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(max |g| (N,), max |C v| (N,)) along ``states`` (N, 2n), compiled."""
    states = np.ascontiguousarray(np.atleast_2d(states), dtype=float)
    out = np.empty((states.shape[0], 2))
    residuals_along.compiled(
        system.constraints.compiled, states, system.parameters, system.n_holonomic, system.n_constraints, out
    )
    return out[:, 0], out[:, 1]


def multipliers(system: ConstrainedSystem, t_s: np.ndarray, states: np.ndarray) -> np.ndarray:
    """λ (N, m) along ``states`` (N, 2n) at times ``t_s`` (N,) s, compiled; the unit is each row's (see
    :mod:`.system`)."""
    states = np.ascontiguousarray(np.atleast_2d(states), dtype=float)
    times = np.array(np.broadcast_to(np.asarray(t_s, dtype=float), states.shape[:1]), dtype=float)
    out = np.empty((states.shape[0], system.n_constraints))
    multipliers_along.compiled(
        system.dynamics.compiled,
        system.constraints.compiled,
        times,
        states,
        system.parameters,
        system.n_holonomic,
        system.n_constraints,
        out,
    )
    return out
