"""Holonomic constraints ``g(q) = 0``: projection onto them, and the multipliers that hold them.

Both work from the residual ``g`` (m,) and Jacobian ``G = ∂g/∂q`` (m, n_q)
of a :class:`~app.physics.solvers.system.Constraints` kernel:

* :func:`project_onto_constraints` — after a step, Gauss–Newton corrections of
  minimum norm (each one :func:`minimum_norm_correction`), ``q ← q − Gᵀ (G Gᵀ)⁻¹ g(q)``, until ``g`` is at round-off,
  then
  ``v ← v − Gᵀ (G Gᵀ)⁻¹ G v`` so that ``ġ = G v = 0``;
* :func:`constrained_acceleration` — inside a right-hand side, solve
  ``[M Gᵀ; G 0] [a; λ] = [f; γ]`` for the accelerations ``a`` and multipliers ``λ``,
  with ``γ = −Ġ v − 2α ġ − β² g`` from :func:`baumgarte_target` (α = β = 0: plain
  index reduction, whose residual drifts; α, β > 0 (1/s): Baumgarte stabilisation).

Both are ``register_jitable``: callable from numba kernels and from plain Python.
"""

from __future__ import annotations

import numpy as np
from numba.extending import register_jitable

#: Gauss–Newton iterations at most; the corrections converge quadratically, so 2–3 suffice near the manifold.
MAX_PROJECTION_ITERATIONS = 8


@register_jitable
def _gram_solve(G, rhs):
    """``(G Gᵀ)⁻¹ rhs`` for G (m, n) of full row rank and rhs (m,)."""
    m = G.shape[0]
    gram = np.empty((m, m))
    for i in range(m):
        for j in range(m):
            acc = 0.0
            for k in range(G.shape[1]):
                acc += G[i, k] * G[j, k]
            gram[i, j] = acc
    return np.linalg.solve(gram, rhs)


@register_jitable
def minimum_norm_correction(G, residual, x):
    """``x ← x − Gᵀ (G Gᵀ)⁻¹ residual`` in place: the smallest change of ``x`` (n,) with ``G Δx = −residual``.

    ``G`` (m, n) of full row rank, ``residual`` (m,). Returns the largest |Δx| component.
    Used for positions (residual ``g``, Gauss–Newton) and for velocities (residual ``G v``,
    holonomic and nonholonomic rows alike: ``C v = 0`` is linear in ``v``).
    """
    multiplier = _gram_solve(G, residual)
    largest_step = 0.0
    for k in range(x.shape[0]):
        step = 0.0
        for i in range(G.shape[0]):
            step += G[i, k] * multiplier[i]
        x[k] -= step
        largest_step = max(largest_step, abs(step))
    return largest_step


@register_jitable
def project_onto_constraints(constraint, y, p, n_positions, n_constraints):
    """Move ``y`` in place onto ``g(q) = 0`` and ``G v = 0`` (q = y[:n_q], v = y[n_q:2 n_q])."""
    g = np.empty(n_constraints)
    G = np.empty((n_constraints, n_positions))
    q = y[:n_positions]
    for _ in range(MAX_PROJECTION_ITERATIONS):
        constraint(y, p, g, G)
        largest_step = minimum_norm_correction(G, g, q)
        largest_q = 0.0
        for k in range(n_positions):
            largest_q = max(largest_q, abs(y[k]))
        if largest_step <= 4.0 * 2.220446049250313e-16 * max(largest_q, 1e-300):
            break
    constraint(y, p, g, G)
    normal_velocity = np.empty(n_constraints)
    for i in range(n_constraints):
        acc = 0.0
        for k in range(n_positions):
            acc += G[i, k] * y[n_positions + k]
        normal_velocity[i] = acc
    minimum_norm_correction(G, normal_velocity, y[n_positions : 2 * n_positions])


@register_jitable
def baumgarte_target(gdot_v, g, gdot, alpha, beta, out):
    """``out = −Ġ v − 2α ġ − β² g`` (m,): the constraint acceleration to impose (α, β in 1/s)."""
    for i in range(g.shape[0]):
        out[i] = -gdot_v[i] - 2.0 * alpha * gdot[i] - beta * beta * g[i]


@register_jitable
def constrained_acceleration(M, G, f, gamma, a_out):
    """Solve ``[M Gᵀ; G 0] [a; λ] = [f; γ]``; writes ``a`` (n,) and returns ``λ`` (m,).

    ``M`` (n, n) mass matrix, ``G`` (m, n) constraint Jacobian, ``f`` (n,)
    applied forces, ``γ`` (m,) the imposed constraint acceleration ``G a``.
    """
    n = M.shape[0]
    m = G.shape[0]
    kkt = np.zeros((n + m, n + m))
    rhs = np.empty(n + m)
    for i in range(n):
        for j in range(n):
            kkt[i, j] = M[i, j]
        for j in range(m):
            kkt[i, n + j] = G[j, i]
            kkt[n + j, i] = G[j, i]
        rhs[i] = f[i]
    for j in range(m):
        rhs[n + j] = gamma[j]
    solution = np.linalg.solve(kkt, rhs)
    for i in range(n):
        a_out[i] = solution[i]
    return solution[n:]


@register_jitable
def kkt_inputs_finite(M, G, f, gamma):
    """Whether ``M`` (n, n), ``G`` (m, n), ``f`` (n,) and ``γ`` (m,) are all finite.

    Check before :func:`constrained_acceleration` where a state may have blown up:
    the solve raises on non-finite input, which a C callback cannot pass on.
    """
    return np.all(np.isfinite(M)) and np.all(np.isfinite(G)) and np.all(np.isfinite(f)) and np.all(np.isfinite(gamma))
