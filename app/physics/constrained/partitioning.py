"""Coordinate partitioning: which coordinates are dependent, and solving for them from the independent ones.

The ``m`` velocity rows ``C`` (m, n) of a :class:`~.system.ConstrainedSystem`
split the coordinates into ``m`` dependent ones ``d`` and ``n − m`` independent
ones ``i``: with ``C_d`` (m, m) invertible, ``C v = 0`` gives
``v_d = −C_d⁻¹ C_i v_i``. Positions: the first ``m_h`` dependent coordinates
(chosen on the holonomic rows) are found from ``g(q) = 0`` by Newton's method
with the others held; a system with nonholonomic rows keeps its other positions
integrated (those rows have no position form), only its velocities partition.

A partition is stored as ``n`` integers (as floats in the parameter array):
the dependent coordinates in row order, then the independent ones ascending.
Everything here is ``register_jitable``: callable from numba kernels and from Python.
"""

from __future__ import annotations

import numpy as np
from numba.extending import register_jitable

from app.physics.mechanics.linear import solve_small as solve_in_place

#: Newton iterations for the dependent positions at most (quadratic convergence: 2–3 near the manifold).
MAX_NEWTON_ITERATIONS = 12
#: Re-choose the partition when a dependent rate responds to an independent one with a gain above this
#: (max |C_d⁻¹ C_i|): the dependent block is becoming singular (e.g. the pendulum's x near the bottom when
#: x is dependent). A fresh choice by column pivoting has gains ≤ 1 for one constraint.
REPARTITION_GAIN = 2.0
_EPS = 2.220446049250313e-16


@register_jitable
def solve_small(A, b, x):
    """Solve ``A x = b`` (A (k, k), b (k,)) into ``x`` (k,), leaving ``A`` and ``b`` unchanged; False if singular.

    The engine's compiled elimination (:func:`app.physics.mechanics.linear.solve_small`) on copies:
    no exception, so it is safe inside a C callback.
    """
    work = A.copy()
    for i in range(b.shape[0]):
        x[i] = b[i]
    return solve_in_place(work, x)


@register_jitable
def choose_partition(C, partition):
    """Pick the dependent coordinates from ``C`` (m, n) by elimination with column pivoting, row by row.

    Row ``i`` (holonomic rows first) takes the not yet chosen column with the largest
    entry after the earlier rows are eliminated, so the first ``m_h`` dependent
    coordinates make the holonomic block invertible. Writes ``partition`` (n,):
    dependent in row order, then independent ascending. False if ``C`` is rank deficient.
    """
    m, n = C.shape
    W = C.copy()
    taken = np.zeros(n, dtype=np.bool_)
    scale = 0.0
    for i in range(m):
        for j in range(n):
            scale = max(scale, abs(C[i, j]))
    if not scale > 0.0:
        return False
    for i in range(m):
        best = -1
        for j in range(n):
            if not taken[j] and (best < 0 or abs(W[i, j]) > abs(W[i, best])):
                best = j
        if not abs(W[i, best]) > 1e3 * _EPS * scale:
            return False
        taken[best] = True
        partition[i] = best
        for r in range(i + 1, m):
            factor = W[r, best] / W[i, best]
            for j in range(n):
                W[r, j] -= factor * W[i, j]
    slot = m
    for j in range(n):
        if not taken[j]:
            partition[slot] = j
            slot += 1
    return True


@register_jitable
def dependent_gain(C, partition):
    """max |C_d⁻¹ C_i| (dimensionless): how strongly the dependent rates follow the independent ones; inf if C_d is
    singular."""
    m, n = C.shape
    block = np.empty((m, m))
    for i in range(m):
        for j in range(m):
            block[i, j] = C[i, int(partition[j])]
    column = np.empty(m)
    solution = np.empty(m)
    gain = 0.0
    for k in range(m, n):
        for i in range(m):
            column[i] = C[i, int(partition[k])]
        if not solve_small(block, column, solution):
            return np.inf
        for i in range(m):
            gain = max(gain, abs(solution[i]))
    return gain


@register_jitable
def solve_dependent(constraints, y, p, partition, n, n_holonomic, n_constraints):
    """Make ``y = (q, v)`` (2n,) consistent in place, keeping the independent coordinates and rates.

    Newton on ``g(q) = 0`` for the first ``n_holonomic`` dependent positions, then
    ``C_d v_d = −C_i v_i`` for all dependent rates. ``constraints`` is the system's
    ``constraints(q, v, p, g, C, c)`` kernel. Returns False if Newton does not
    converge or the dependent block is singular (``y`` is then unusable).
    """
    q = y[:n]
    v = y[n : 2 * n]
    g = np.empty(n_holonomic)
    C = np.empty((n_constraints, n))
    c = np.empty(n_constraints)
    if n_holonomic > 0:
        block = np.empty((n_holonomic, n_holonomic))
        delta = np.empty(n_holonomic)
        converged = False
        for _ in range(MAX_NEWTON_ITERATIONS):
            constraints(q, v, p, g, C, c)
            for i in range(n_holonomic):
                for j in range(n_holonomic):
                    block[i, j] = C[i, int(partition[j])]
            if not solve_small(block, g, delta):
                return False
            largest_step = 0.0
            largest_q = 0.0
            for j in range(n_holonomic):
                k = int(partition[j])
                q[k] -= delta[j]
                largest_step = max(largest_step, abs(delta[j]))
            for k in range(n):
                largest_q = max(largest_q, abs(q[k]))
            if largest_step <= 4.0 * _EPS * max(largest_q, 1e-300):
                converged = True
                break
        if not converged:
            return False
    constraints(q, v, p, g, C, c)
    block = np.empty((n_constraints, n_constraints))
    rhs = np.empty(n_constraints)
    rates = np.empty(n_constraints)
    for i in range(n_constraints):
        acc = 0.0
        for j in range(n_constraints):
            block[i, j] = C[i, int(partition[j])]
        for j in range(n_constraints, n):
            k = int(partition[j])
            acc -= C[i, k] * v[k]
        rhs[i] = acc
    if not solve_small(block, rhs, rates):
        return False
    for j in range(n_constraints):
        v[int(partition[j])] = rates[j]
    return True
