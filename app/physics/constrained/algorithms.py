"""The DAE algorithms: how ``M v̇ = f + Cᵀλ, g(q) = 0, A v = 0`` becomes an ODE an integrator can advance.

Every algorithm integrates the state ``y = (q, v)`` (2n,) with the index-1 equations

    [M Cᵀ; C 0] [v̇; −λ] = [f; γ]      (λ the multipliers with the sign of :mod:`.system`)

solved each right-hand side call by :func:`~app.physics.solvers.constraints.constrained_acceleration`,
and differs in ``γ`` and in what happens after each step:

* ``uncorrected`` — ``γ = c = −Ċ v`` (index reduction only): the residuals ``g`` and
  ``C v`` are not fed back, so round-off and truncation make them drift, ``C v`` about
  linearly and ``g`` about quadratically in time for a steady error source;
* ``baumgarte`` — ``γ = c − 2α C v − β² g`` (``g`` taken as 0 on nonholonomic rows), so a
  holonomic residual ``e`` obeys ``ë + 2α ė + β² e = 0`` and a nonholonomic one
  ``ė + 2α e = 0`` (α, β in 1/s). α = β: critical damping at rate α. α = β = 0 is
  ``uncorrected``; gains with ``h·α`` or ``h·β`` of order one or more make the step unstable;
* ``projection`` — ``uncorrected``, then after every step the positions are moved
  onto ``g = 0`` by Gauss–Newton (minimum Euclidean change) and the velocities onto
  ``C v = 0`` (all rows, minimum Euclidean change);
* ``partitioning`` — only the independent coordinates and rates carry information:
  every right-hand side call and every step end first solves the dependent ones
  (:mod:`.partitioning`). The partition is re-chosen when it becomes ill-conditioned
  (counted in the parameter array, see :func:`repartition_count`).

The algorithm and its settings ride at the end of the parameter array ``p``
(``SETTINGS + n`` slots after the system's own parameters, which the system's
kernels read from the front): code, α (1/s), β (1/s), re-partition count, partition.
So the right-hand side and projection kernels are compiled once per system
(a tiny C callback wrapping the shared, disk-cached kernels below), not per request.
The shared kernels are C callbacks themselves: a system's wrapper calls them through
their address, so none of their code is linked into, and optimised again with, each
wrapper (that cost 2.3–3 s per system; now 0.1–0.25 s, see :func:`algorithm_kernels`).
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numba
import numpy as np
from numba import types

from app.physics.constrained.partitioning import REPARTITION_GAIN, choose_partition, dependent_gain, solve_dependent
from app.physics.constrained.system import ConstrainedSystem
from app.physics.solvers.constraints import (
    MAX_PROJECTION_ITERATIONS,
    baumgarte_target,
    constrained_acceleration,
    kkt_inputs_finite,
    minimum_norm_correction,
)
from app.physics.solvers.kernels import (
    DYNAMICS_TYPE,
    MULTIPLIER_CONSTRAINTS_TYPE,
    PROJECT_SIGNATURE,
    RHS_SIGNATURE,
    VECTOR,
    Kernel,
)
from app.physics.solvers.system import OdeSystem

UNCORRECTED, BAUMGARTE, PROJECTION, PARTITIONING = 0, 1, 2, 3
#: Slots before the partition in the parameter array's tail: code, α, β, re-partition count.
SETTINGS = 4
_CODE, _ALPHA, _BETA, _REPARTITIONS = range(SETTINGS)


@dataclass(frozen=True)
class Algorithm:
    """One DAE algorithm: its API name, its code in the kernels and the words a student reads."""

    name: str
    code: int
    label: str
    description: str


ALGORITHMS: dict[str, Algorithm] = {
    a.name: a
    for a in (
        Algorithm(
            "uncorrected",
            UNCORRECTED,
            "uncorrected index reduction",
            "C v̇ = −Ċ v only: the constraint residuals are never fed back and drift",
        ),
        Algorithm(
            "baumgarte",
            BAUMGARTE,
            "Baumgarte stabilisation",
            "C v̇ = −Ċ v − 2α C v − β² g: the residual is a damped oscillator driven back to zero",
        ),
        Algorithm(
            "projection",
            PROJECTION,
            "coordinate projection",
            "index reduction, then positions and velocities projected back onto the constraints after every step",
        ),
        Algorithm(
            "partitioning",
            PARTITIONING,
            "coordinate partitioning",
            "independent coordinates integrated; dependent ones solved by Newton on g(q) = 0 and from C v = 0",
        ),
    )
}


def _shared_kernel(signature: Any) -> Callable[[Callable[..., Any]], Kernel]:
    """Decorator: compile ``fn`` for ``signature`` as a disk-cached C callback (a first-class function value) with its
    twin.

    :func:`~app.physics.solvers.kernels.kernel` makes an ordinary ``njit`` function of a
    signature that is not a model function's; a caller compiled later would then link
    that function's whole code into its own module and optimise it again. Called
    through its address instead, it is compiled once and loaded from the disk cache.
    """

    def wrap(fn: Callable[..., Any]) -> Kernel:
        compiled = numba.cfunc(  # type: ignore[call-arg]  # numba's stub omits cfunc's nopython option
            signature, cache=True, nopython=True, error_model="numpy"
        )(fn)
        return Kernel(compiled=compiled, python=fn)

    return wrap


@_shared_kernel(
    types.void(
        DYNAMICS_TYPE,
        MULTIPLIER_CONSTRAINTS_TYPE,
        types.float64,
        VECTOR,
        VECTOR,
        VECTOR,
        types.int64,
        types.int64,
        types.int64,
    )
)
def constrained_rhs(dynamics, constraints, t, y, p, dydt, n, n_holonomic, n_constraints):
    """``dydt = (v, v̇)`` (2n,) of the algorithm named in ``p``'s tail, at time ``t`` (s) and state ``y = (q, v)``
    (2n,)."""
    base = p.shape[0] - SETTINGS - n
    code = int(p[base + _CODE])
    state = y
    if code == PARTITIONING:
        state = y.copy()
        if not solve_dependent(constraints, state, p, p[base + SETTINGS :], n, n_holonomic, n_constraints):
            for i in range(2 * n):
                dydt[i] = np.nan
            return
    q = state[:n]
    v = state[n : 2 * n]
    mass = np.empty((n, n))
    forces = np.empty(n)
    g = np.empty(n_holonomic)
    C = np.empty((n_constraints, n))
    c = np.empty(n_constraints)
    dynamics(t, q, v, p, mass, forces)
    constraints(q, v, p, g, C, c)
    gamma = c.copy()
    if code == BAUMGARTE:
        residual = np.zeros(n_constraints)
        rate = np.zeros(n_constraints)
        for i in range(n_constraints):
            if i < n_holonomic:
                residual[i] = g[i]
            acc = 0.0
            for k in range(n):
                acc += C[i, k] * v[k]
            rate[i] = acc
        baumgarte_target(-c, residual, rate, p[base + _ALPHA], p[base + _BETA], gamma)
    if not kkt_inputs_finite(mass, C, forces, gamma):  # blown up: the integrator stops at the first non-finite state
        for i in range(2 * n):
            dydt[i] = np.nan
        return
    for i in range(n):
        dydt[i] = v[i]
    constrained_acceleration(mass, C, forces, gamma, dydt[n : 2 * n])


@_shared_kernel(types.void(MULTIPLIER_CONSTRAINTS_TYPE, VECTOR, VECTOR, types.int64, types.int64, types.int64))
def constrained_project(constraints, y, p, n, n_holonomic, n_constraints):
    """After a step: projection (positions onto ``g = 0``, then ``C v = 0``) or partitioning (dependent from
    independent)."""
    base = p.shape[0] - SETTINGS - n
    code = int(p[base + _CODE])
    if code == PROJECTION:
        q = y[:n]
        v = y[n : 2 * n]
        g = np.empty(n_holonomic)
        C = np.empty((n_constraints, n))
        c = np.empty(n_constraints)
        if n_holonomic > 0:
            for _ in range(MAX_PROJECTION_ITERATIONS):
                constraints(q, v, p, g, C, c)
                largest_step = minimum_norm_correction(C[:n_holonomic], g, q)
                largest_q = 0.0
                for k in range(n):
                    largest_q = max(largest_q, abs(q[k]))
                if largest_step <= 4.0 * 2.220446049250313e-16 * max(largest_q, 1e-300):
                    break
        constraints(q, v, p, g, C, c)
        rate = np.empty(n_constraints)
        for i in range(n_constraints):
            acc = 0.0
            for k in range(n):
                acc += C[i, k] * v[k]
            rate[i] = acc
        minimum_norm_correction(C, rate, v)
    elif code == PARTITIONING:
        partition = p[base + SETTINGS :]
        if not solve_dependent(constraints, y, p, partition, n, n_holonomic, n_constraints):
            for i in range(2 * n):
                y[i] = np.nan
            return
        g = np.empty(n_holonomic)
        C = np.empty((n_constraints, n))
        c = np.empty(n_constraints)
        constraints(y[:n], y[n : 2 * n], p, g, C, c)
        if dependent_gain(C, partition) > REPARTITION_GAIN:
            fresh = partition.copy()
            if choose_partition(C, fresh):
                changed = False
                for j in range(n_constraints):
                    changed = changed or fresh[j] != partition[j]
                if changed:
                    for j in range(n):
                        partition[j] = fresh[j]
                    p[base + _REPARTITIONS] += 1.0


@dataclass(frozen=True)
class AlgorithmKernels:
    """A system's right-hand side and after-step kernels (C callbacks with Python twins)."""

    rhs: Kernel
    project: Kernel


@functools.lru_cache(maxsize=64)
def algorithm_kernels(
    dynamics: Kernel, constraints: Kernel, n: int, n_holonomic: int, n_constraints: int
) -> AlgorithmKernels:
    """The RHS_SIGNATURE / PROJECT_SIGNATURE callbacks of one system class (compiled once per process).

    They close over the system's two kernels; numba cannot cache such closures on disk,
    but the work they call (:func:`constrained_rhs`, :func:`constrained_project`) is
    cached and called through its address, so only the two few-line wrappers are
    compiled here: 0.1–0.25 s per system in a fresh process with a warm disk cache
    (measured on 2 loaded cores; it was 2.3–3 s with the callees linked in).
    """
    rhs_kernel, project_kernel = constrained_rhs.compiled, constrained_project.compiled
    dynamics_c, constraints_c = dynamics.compiled, constraints.compiled

    def rhs(t, y, p, dydt):
        rhs_kernel(dynamics_c, constraints_c, t, y, p, dydt, n, n_holonomic, n_constraints)

    def project(y, p):
        project_kernel(constraints_c, y, p, n, n_holonomic, n_constraints)

    def rhs_python(t, y, p, dydt):
        constrained_rhs.python(dynamics.python, constraints.python, t, y, p, dydt, n, n_holonomic, n_constraints)

    def project_python(y, p):
        constrained_project.python(constraints.python, y, p, n, n_holonomic, n_constraints)

    rhs_python.__name__ = rhs.__name__ = f"constrained_rhs_{dynamics.name}"
    project_python.__name__ = project.__name__ = f"constrained_project_{constraints.name}"
    return AlgorithmKernels(
        rhs=Kernel(
            compiled=numba.cfunc(  # type: ignore[call-arg]  # numba's stub omits cfunc's nopython option
                RHS_SIGNATURE, nopython=True, error_model="numpy"
            )(rhs),
            python=rhs_python,
        ),
        project=Kernel(
            compiled=numba.cfunc(  # type: ignore[call-arg]  # numba's stub omits cfunc's nopython option
                PROJECT_SIGNATURE, nopython=True, error_model="numpy"
            )(project),
            python=project_python,
        ),
    )


def algorithm_parameters(
    system: ConstrainedSystem,
    algorithm: str,
    *,
    alpha_1_s: float = 0.0,
    beta_1_s: float = 0.0,
    q: np.ndarray | None = None,
) -> np.ndarray:
    """The system's parameters followed by the algorithm's settings (see the module docstring).

    ``q`` (n,) is where partitioning chooses its first partition (``system.independent``
    if given, else by pivoting on ``C(q)``); it is required for ``partitioning``
    without ``system.independent``.
    """
    if algorithm not in ALGORITHMS:
        raise ValueError(f"method: unknown DAE algorithm {algorithm!r}; use one of {', '.join(ALGORITHMS)}")
    for name, gain in (("baumgarte_alpha_1_s", alpha_1_s), ("baumgarte_beta_1_s", beta_1_s)):
        if not (np.isfinite(gain) and gain >= 0.0):
            raise ValueError(f"{name}: a Baumgarte gain must be a finite rate ≥ 0 in 1/s (got {gain!r})")
    n = system.n_coordinates
    partition = np.arange(n, dtype=float)
    if algorithm == "partitioning":
        partition = initial_partition(system, q)
    settings = np.array([ALGORITHMS[algorithm].code, alpha_1_s, beta_1_s, 0.0])
    return np.concatenate([np.asarray(system.parameters, dtype=float), settings, partition])


def initial_partition(system: ConstrainedSystem, q: np.ndarray | None) -> np.ndarray:
    """(n,) dependent coordinates (row order) then independent ones, as floats (see :mod:`.partitioning`)."""
    n, m = system.n_coordinates, system.n_constraints
    if system.independent is not None:
        dependent = [k for k in range(n) if k not in system.independent]
        return np.array([*dependent, *sorted(system.independent)], dtype=float)
    if q is None:
        raise ValueError("method partitioning: give the state q where the independent coordinates are chosen")
    _, jacobian, _ = system.constraint_terms(q, np.zeros(n))
    partition = np.empty(n)
    if not choose_partition(jacobian, partition):
        raise ValueError(
            f"method partitioning: the {m} constraint rows are "
            "dependent at this state; no coordinates can be solved for"
        )
    return partition


def repartition_count(parameters: np.ndarray, n: int) -> int:
    """How many times partitioning re-chose its dependent coordinates during the runs that used ``parameters``."""
    return int(parameters[len(parameters) - SETTINGS - n + _REPARTITIONS])


def current_partition(parameters: np.ndarray, n: int, n_constraints: int) -> tuple[tuple[int, ...], tuple[int, ...]]:
    """(dependent, independent) coordinate indices partitioning is using now."""
    partition = parameters[len(parameters) - n :].astype(int)
    return tuple(int(k) for k in partition[:n_constraints]), tuple(int(k) for k in partition[n_constraints:])


def algorithm_system(
    system: ConstrainedSystem,
    algorithm: str,
    *,
    alpha_1_s: float = 0.0,
    beta_1_s: float = 0.0,
    q: np.ndarray | None = None,
) -> OdeSystem:
    """An :class:`OdeSystem` on ``y = (q, v)`` (2n,) that advances ``system`` by ``algorithm``.

    Every integrator that supports a ``project`` hook (rk4, dopri5) can run it;
    ``parameters`` is a fresh array (partitioning writes its re-choices into it).
    """
    kernels = algorithm_kernels(
        system.dynamics, system.constraints, system.n_coordinates, system.n_holonomic, system.n_constraints
    )
    names = system.coordinate_names
    needs_step_end = ALGORITHMS[algorithm].code in (PROJECTION, PARTITIONING) if algorithm in ALGORITHMS else False
    return OdeSystem(
        rhs=kernels.rhs,
        parameters=algorithm_parameters(system, algorithm, alpha_1_s=alpha_1_s, beta_1_s=beta_1_s, q=q),
        state_names=(*names, *(f"{name}_rate" for name in names)),
        project=kernels.project if needs_step_end else None,
    )
