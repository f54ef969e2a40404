"""Consistent initial conditions: the least change to a requested start that satisfies the constraints.

Given requested coordinates ``q₀`` (n,) and rates ``v₀`` (n,) of a
:class:`~.system.ConstrainedSystem`, find

* ``q`` minimising |q − q₀| (Euclidean, in the coordinates' own units) subject to
  ``g(q) = 0``, moving only the coordinates not listed in ``fixed_positions``:
  Newton's method on the Lagrange conditions ``(q − q₀) + Gᵀλ = 0, g(q) = 0`` over the
  free columns of ``G``, the constraints' curvature included (:func:`_consistent_positions`);
* then ``v`` minimising |v − v₀| subject to ``C(q) v = 0`` (holonomic and
  nonholonomic rows), moving only the rates not in ``fixed_velocities``: one
  minimum-norm correction (the condition is linear in ``v``).

A request that cannot be met is refused with a ValueError saying why: fixed
entries that leave fewer free coordinates than constraints, constraint rows that
are dependent on the free coordinates at the start (the pendulum's bob at its
pivot, where every direction is tangent), or an iteration that does not converge
(no nearby point satisfies ``g = 0``).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from app.physics.constrained.system import ConstrainedSystem
from app.physics.solvers.constraints import minimum_norm_correction

#: Newton iterations at most.
MAX_ITERATIONS = 50
#: Rows of the free Jacobian count as dependent below this singular-value ratio.
RANK_TOLERANCE = 1e-10


@dataclass(frozen=True)
class CoordinateChange:
    """One coordinate or rate the start had to change: ``name``, requested and consistent values, ``unit``."""

    name: str
    requested: float
    consistent: float
    unit: str

    @property
    def change(self) -> float:
        return self.consistent - self.requested

    def as_dict(self) -> dict[str, float | str]:
        return {
            "name": self.name,
            "requested": self.requested,
            "consistent": self.consistent,
            "change": self.change,
            "unit": self.unit,
        }

    def sentence(self) -> str:
        return f"{self.name} {self.requested:.6g} → {self.consistent:.6g} {self.unit}".rstrip()


@dataclass(frozen=True)
class ConsistentStart:
    """The consistent ``q`` (n,), ``v`` (n,), what changed, and the residuals left (max |g|, max |C v|)."""

    q: np.ndarray
    v: np.ndarray
    changes: tuple[CoordinateChange, ...]
    position_residual: float
    velocity_residual: float

    @property
    def state(self) -> np.ndarray:
        """``(q, v)`` (2n,)."""
        return np.concatenate([self.q, self.v])

    @property
    def changed(self) -> bool:
        return bool(self.changes)

    def summary(self) -> str:
        """One sentence for a student ("as requested" when nothing changed)."""
        if not self.changes:
            return "the start satisfies the constraints as requested"
        return "made consistent: " + "; ".join(change.sentence() for change in self.changes)


def consistent_initial_conditions(
    system: ConstrainedSystem,
    q0: Sequence[float] | np.ndarray,
    v0: Sequence[float] | np.ndarray,
    *,
    fixed_positions: Sequence[int] = (),
    fixed_velocities: Sequence[int] = (),
    names: Sequence[str] | None = None,
    units: Sequence[str] | None = None,
) -> ConsistentStart:
    """The least change to ``(q0, v0)`` that satisfies ``g(q) = 0`` and ``C(q) v = 0`` (see the module docstring).

    ``names``/``units`` (2n each: positions then rates) label the reported changes
    (default: the system's coordinate names and ``<name>_rate``, no unit). A change
    is reported when it exceeds 1e-12 of the value's size (at least 1e-12 absolute).
    """
    n = system.n_coordinates
    q_requested = _finite_vector("q0", q0, n)
    v_requested = _finite_vector("v0", v0, n)
    free_q = _free_columns("positions", fixed_positions, n)
    free_v = _free_columns("velocities", fixed_velocities, n)
    q = _consistent_positions(system, q_requested, free_q)
    _, jacobian, _ = system.constraint_terms(q, v_requested)
    v = v_requested.copy()
    if len(free_v) < system.n_constraints:
        raise ValueError(
            f"velocities: {system.n_constraints} velocity constraints but only {len(free_v)} free rates; "
            "free more of them (fewer fixed velocities)"
        )
    _check_rank("velocities", jacobian[:, free_v], system.n_constraints)
    free_rates = v[free_v]
    minimum_norm_correction(np.ascontiguousarray(jacobian[:, free_v]), jacobian @ v, free_rates)
    v[free_v] = free_rates
    g, jacobian, _ = system.constraint_terms(q, v)
    labels = (
        list(names)
        if names is not None
        else [*system.coordinate_names, *(f"{c}_rate" for c in system.coordinate_names)]
    )
    unit_labels = list(units) if units is not None else [""] * (2 * n)
    if len(labels) != 2 * n or len(unit_labels) != 2 * n:
        raise ValueError(f"names and units must have {2 * n} entries (positions then rates)")
    requested = np.concatenate([q_requested, v_requested])
    consistent = np.concatenate([q, v])
    changes = tuple(
        CoordinateChange(labels[k], float(requested[k]), float(consistent[k]), unit_labels[k])
        for k in range(2 * n)
        if abs(consistent[k] - requested[k]) > 1e-12 * max(1.0, abs(requested[k]))
    )
    return ConsistentStart(
        q=q,
        v=v,
        changes=changes,
        position_residual=float(np.max(np.abs(g), initial=0.0)),
        velocity_residual=float(np.max(np.abs(jacobian @ v), initial=0.0)),
    )


def _consistent_positions(system: ConstrainedSystem, q_requested: np.ndarray, free: np.ndarray) -> np.ndarray:
    """The point of ``g(q) = 0`` nearest ``q_requested``, moving the ``free`` coordinates only: Newton's method on the
    Lagrange conditions ``(q − q₀) + Gᵀλ = 0, g(q) = 0``, with the constraints' curvature ``∑ λᵢ ∂²gᵢ/∂q²`` taken
    from central differences of ``G``.

    Without the curvature term (Gauss–Newton: project ``q₀`` onto the constraints' tangent plane at ``q``) the
    iteration is unstable along the constraints once ``λ`` times their curvature exceeds 1: a pendulum's bob asked for
    more than twice the rod's length from the pivot (measured: its round-off grew fourfold a step at five lengths, and
    the start was refused)."""
    m_h = system.n_holonomic
    q = q_requested.copy()
    if m_h == 0:
        return q
    if len(free) < m_h:
        raise ValueError(
            f"positions: {m_h} position constraints but only {len(free)} "
            "free coordinates; free more of them (fewer fixed positions)"
        )
    zero_rates = np.zeros(system.n_coordinates)
    size = max(1.0, float(np.max(np.abs(q_requested))))
    k = len(free)

    def free_jacobian(at: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        g, jacobian, _ = system.constraint_terms(at, zero_rates)
        return g[:m_h], np.ascontiguousarray(jacobian[:m_h, free])

    multipliers = np.zeros(m_h)
    previous_step = np.inf
    for iteration in range(MAX_ITERATIONS):
        g, G = free_jacobian(q)
        if iteration == 0:
            _check_rank("positions", G, m_h)
        elif not _full_rank(G, m_h):
            break  # the iteration ran into a place where the free coordinates no longer move g: nothing reachable
        curvature = np.zeros((k, k))
        if iteration > 0 and np.any(multipliers):
            for column, j in enumerate(free):
                h = 1e-6 * max(1.0, abs(float(q[j])))
                ahead, behind = q.copy(), q.copy()
                ahead[j] += h
                behind[j] -= h
                curvature[:, column] = (free_jacobian(ahead)[1] - free_jacobian(behind)[1]).T @ multipliers / (2 * h)
        stationarity = (q[free] - q_requested[free]) + G.T @ multipliers
        kkt = np.block([[np.eye(k) + curvature, G.T], [G, np.zeros((m_h, m_h))]])
        try:
            change = np.linalg.solve(kkt, -np.concatenate([stationarity, g]))
        except np.linalg.LinAlgError:
            break
        step, multipliers = change[:k], multipliers + change[k:]
        q[free] += step
        if not np.all(np.isfinite(q)):
            break
        largest = float(np.max(np.abs(step)))
        # Converged: the step is at round-off (the stationarity residual is a difference of terms the size of the
        # distance moved), or has stopped shrinking there.
        if largest <= 1e-13 * size or (largest <= 1e-9 * size and largest >= 0.5 * previous_step):
            g, _ = free_jacobian(q)
            if float(np.max(np.abs(g))) <= 1e-10 * size * size:
                return q
            break
        previous_step = largest
    raise ValueError(
        f"positions: no consistent start near the requested one (Newton's method did not converge in {MAX_ITERATIONS} "
        "iterations): the fixed coordinates ask for a place the constraints cannot reach"
    )


def _full_rank(jacobian: np.ndarray, rows: int) -> bool:
    """Whether ``jacobian`` (rows, k) has ``rows`` independent rows (smallest singular value above the tolerance)."""
    if jacobian.shape[1] < rows or not np.all(np.isfinite(jacobian)):
        return False
    singular = np.linalg.svd(jacobian, compute_uv=False)
    return bool(singular[0] > 0.0 and singular[-1] > RANK_TOLERANCE * singular[0])


def _check_rank(what: str, jacobian: np.ndarray, rows: int) -> None:
    if not _full_rank(jacobian, rows):
        raise ValueError(
            f"{what}: the constraints do not fix the free {what} at this start (their rows are dependent there, "
            "e.g. a pendulum's bob at its pivot); choose another start"
        )


def _finite_vector(name: str, values: Sequence[float] | np.ndarray, n: int) -> np.ndarray:
    array = np.asarray(values, dtype=float).reshape(-1)
    if array.shape != (n,) or not np.all(np.isfinite(array)):
        raise ValueError(f"{name}: give {n} finite numbers (got {values!r})")
    return array


def _free_columns(what: str, fixed: Sequence[int], n: int) -> np.ndarray:
    fixed_set = {int(k) for k in fixed}
    if any(not 0 <= k < n for k in fixed_set):
        raise ValueError(f"fixed {what}: indices must lie in [0, {n}) (got {sorted(fixed_set)})")
    return np.array([k for k in range(n) if k not in fixed_set], dtype=int)
