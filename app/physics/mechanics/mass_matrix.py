"""The mass matrix M = ∂²T/∂q̇² of a system known by its kinetic energy, evaluated numerically at many states at once.

For a Lagrangian a student types, T(t, q, q̇, p) is all there is: Lagrange's equations solve M q̈ = … for the
accelerations, so they hold only where M is positive definite. This module finds M from T as a numpy function
(``kinetic(t (N,), q (n, N), q̇ (n, N), p)`` in J, e.g. :func:`~app.physics.mechanics.model.energy_functions`'s),
says when it is not positive definite at a state, and where a motion between two states passes through a
configuration where it is singular (a polar radius through r = 0), which no integrator can step across honestly.

Entry (i, j) of M is the central difference along q̇_j of ∂T/∂q̇_i, itself a complex step
(Im T(q̇ + iη e_i) / η, exact to rounding for an analytic T): for a T quadratic in the rates, ∂T/∂q̇_i is linear in
them and the difference is exact whatever its step; otherwise it is second order in the step. No symbolic work is
done here, so the scene's process never differentiates what was typed.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

#: Complex step for the inner derivative ∂T/∂q̇_i (exact to rounding: no subtraction).
_COMPLEX_STEP = 1e-20
#: Relative real step for the outer derivative along q̇_j (times max(1, |q̇_j|)).
_RATE_STEP = 1e-3
#: M counts as singular at a state where its smallest eigenvalue is below this fraction of its largest: the threshold
#: at which the generated right-hand side's solve calls a matrix singular to working precision.
SINGULAR_RATIO = 1e-13
#: A motion has met a singular M where the inertia in some direction (or det M) has fallen below this fraction of the
#: start's (:func:`relative_inertia`): a condition number grown 10¹⁰-fold, where no step size is honest any more.
SINGULAR_FALL = 1e-10
#: Points per segment between two frames at which M is found.
SEGMENT_SAMPLES = 9

Kinetic = Callable[[np.ndarray, np.ndarray, np.ndarray, np.ndarray], np.ndarray]


def mass_matrices(kinetic: Kinetic, t_s: np.ndarray, q: np.ndarray, qd: np.ndarray, p: np.ndarray) -> np.ndarray:
    """M = ∂²T/∂q̇² (N, n, n) at N states: times ``t_s`` (N,) s, coordinates ``q`` and rates ``qd`` (n, N), parameters
    ``p``.

    Entries are in T's units over the rates' squared (kg·m², kg, …); a non-finite T gives non-finite entries.
    """
    q, qd = np.asarray(q, dtype=float), np.asarray(qd, dtype=float)
    n, count = qd.shape
    t = np.broadcast_to(np.asarray(t_s, dtype=float), (count,))
    steps = _RATE_STEP * np.maximum(1.0, np.abs(qd))  # (n, N)
    # Every (i, j, ±) variant of the rates at once, in one call of T: (n, 2 n² N) columns, ordered (i, j, sign, state).
    kicks = np.zeros((n, n, n, 2, 1), dtype=complex)
    for i in range(n):
        kicks[i, i] = 1j * _COMPLEX_STEP  # inner: component i of variant i gets q̇_i + iη
    rates = np.broadcast_to(qd.astype(complex)[:, None, None, None, :], (n, n, n, 2, count)).copy()
    for j in range(n):
        rates[j, :, j, 0] += steps[j]  # outer: q̇_j ± h_j
        rates[j, :, j, 1] -= steps[j]
    rates = rates + kicks  # axes (component, i, j, sign, state)
    variants = 2 * n * n
    with np.errstate(all="ignore"):
        values = kinetic(
            np.tile(t, variants), np.tile(q.astype(complex), variants), rates.reshape(n, variants * count), p
        )
    values = np.broadcast_to(np.asarray(values), (variants * count,)).reshape(n, n, 2, count)
    derivative = np.imag(values) / _COMPLEX_STEP  # ∂T/∂q̇_i at q̇ ± h_j e_j: (i, j, sign, state)
    out = np.moveaxis((derivative[:, :, 0] - derivative[:, :, 1]) / (2.0 * steps[None, :, :]), -1, 0)  # (N, i, j)
    return 0.5 * (out + np.swapaxes(out, 1, 2))  # symmetric by definition; the two differences agree to rounding


def relative_inertia(matrices: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """The smallest eigenvalue λ of M v = λ M₀ v (N,) for symmetric ``matrices`` M (N, n, n) against a positive definite
    ``reference`` M₀ (n, n), such as the start's: how far the inertia in the weakest direction has fallen since then
    (1 where nothing changed, 0 where M is singular, negative where it is not positive definite, NaN where not finite).
    Unlike M's own condition number it does not depend on the units of the coordinates (kg against kg·m²)."""
    return _relative(matrices, reference)[0]


def _relative(matrices: np.ndarray, reference: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(smallest eigenvalue, product of the eigenvalues = det M / det M₀) of M v = λ M₀ v, each (N,); NaN where M is not
    finite. The product is smooth where the smallest eigenvalue is not (min(1, r²) for a polar particle: r² for
    both)."""
    matrices = np.asarray(matrices, dtype=float)
    finite = np.all(np.isfinite(matrices), axis=(1, 2))
    smallest, product = np.full(len(matrices), np.nan), np.full(len(matrices), np.nan)
    if finite.any():
        inverse = np.linalg.inv(np.linalg.cholesky(np.asarray(reference, dtype=float)))
        eigenvalues = np.linalg.eigvalsh(inverse @ matrices[finite] @ inverse.T)
        smallest[finite], product[finite] = eigenvalues[:, 0], np.prod(eigenvalues, axis=1)
    return smallest, product


def not_positive_definite(matrix: np.ndarray, rate_names: Sequence[str]) -> tuple[str, str]:
    """``(kind, why)`` for a mass matrix (n, n) that is not positive definite: ``kind`` is "negative" (an eigenvalue
    below
    zero: no mass can have that kinetic energy), "singular" (one at zero, to :data:`SINGULAR_RATIO` of the largest) or
    "not_finite"; ``why`` says so in words, naming the rate its eigenvector points along most. ``("", "")`` if it is."""
    matrix = np.asarray(matrix, dtype=float)
    if not np.all(np.isfinite(matrix)):
        return "not_finite", "∂²T/∂q̇² is not finite there"
    eigenvalues, vectors = np.linalg.eigh(matrix)
    largest = float(np.max(np.abs(eigenvalues)))
    lowest = float(eigenvalues[0])
    along = rate_names[int(np.argmax(np.abs(vectors[:, 0])))]
    if lowest < 0.0 and abs(lowest) > SINGULAR_RATIO * largest:
        return "negative", (
            f"∂²T/∂q̇² has the negative eigenvalue {lowest:.4g} (mostly along {along}): moving that way would have "
            "negative kinetic energy, which no mass can have"
        )
    if largest == 0.0 or lowest <= SINGULAR_RATIO * largest:
        return "singular", (
            f"∂²T/∂q̇² is singular (smallest eigenvalue {lowest:.3g}, largest {largest:.3g}; mostly along {along}): "
            "that rate carries no kinetic energy, so its acceleration cannot be found"
        )
    return "", ""


@dataclass(frozen=True)
class SingularCrossing:
    """Where a motion between two frames meets a singular mass matrix: the frame it left, and the closest approach."""

    #: Index of the last frame before the crossing.
    frame: int
    #: Coordinates (n,) at the closest approach, on the straight segment between the two frames.
    q: np.ndarray
    #: The lower of :func:`relative_inertia` at the samples and the estimated least det M / det M₀ (≤
    #: :data:`SINGULAR_FALL`;
    #: the estimate may dip a little below 0 where M only touches singularity).
    inertia: float
    #: Whether M is not positive definite at a sampled point (a negative eigenvalue, not only a vanishing one).
    indefinite: bool
    #: Index of the rate the eigenvector of the smallest eigenvalue points along most.
    rate_index: int


def first_singular_crossing(
    kinetic: Kinetic, t_s: np.ndarray, states: np.ndarray, p: np.ndarray, *, reference: np.ndarray
) -> SingularCrossing | None:
    """The first pair of consecutive frames (``states`` (N, 2n) = (q, q̇) at ``t_s`` (N,)) between which M becomes
    singular.

    ``reference`` is M at the start (n, n), positive definite. Along the straight segment between two frames' states
    (q, q̇ and t linear in s ∈ [0, 1]) M is found at :data:`SEGMENT_SAMPLES` points. The motion has met a singular M
    where the smallest eigenvalue against the start's (:func:`relative_inertia`) is at most :data:`SINGULAR_FALL` at a
    sample (negative: M stopped being positive definite), where M is not finite, or where det M / det M₀ dips to that
    between samples: a parabola through the lowest sample of the determinant and its neighbours estimates its lowest
    value. Where M touches singularity the determinant is quadratic in s (r² where a polar radius passes through r = 0,
    however far the frames jump across it), so the estimate is zero there to rounding, while a path that keeps its
    distance keeps it positive. None if it never does. A single state is checked alone.
    """
    states = np.atleast_2d(np.asarray(states, dtype=float))
    count, width = states.shape
    n = width // 2
    t_s = np.atleast_1d(np.asarray(t_s, dtype=float))
    if count == 0:
        return None
    samples = np.linspace(0.0, 1.0, SEGMENT_SAMPLES) if count > 1 else np.zeros(1)
    start, end = (states[:-1], states[1:]) if count > 1 else (states, states)
    t_start, t_end = (t_s[:-1], t_s[1:]) if count > 1 else (t_s, t_s)
    points = start[:, None, :] + samples[None, :, None] * (end - start)[:, None, :]  # (pairs, K, 2n)
    times = t_start[:, None] + samples[None, :] * (t_end - t_start)[:, None]
    flat = points.reshape(-1, width)
    matrices = mass_matrices(kinetic, times.ravel(), flat[:, :n].T, flat[:, n:].T, p)
    smallest, product = (values.reshape(len(start), len(samples)) for values in _relative(matrices, reference))
    lowest = np.where(
        np.isnan(smallest).any(axis=1), -np.inf, np.min(np.where(np.isnan(smallest), np.inf, smallest), axis=1)
    )
    estimate, at = _parabola_minima(samples, product)
    met = (lowest <= SINGULAR_FALL) | (estimate <= SINGULAR_FALL)
    if not met.any():
        return None
    frame = int(np.argmax(met))
    row = smallest[frame]
    below = np.flatnonzero(~(row > SINGULAR_FALL))
    where = float(at[frame])
    if len(below) and below[0] > 0 and np.isfinite(row[below[0]]):  # sampled through it: where the samples reach zero
        j = below[0]
        where = float(samples[j - 1] + (samples[j] - samples[j - 1]) * row[j - 1] / (row[j - 1] - row[j]))
    closest = start[frame] + where * (end[frame] - start[frame])
    time = t_start[frame] + where * (t_end[frame] - t_start[frame])
    matrix = mass_matrices(kinetic, np.array([time]), closest[:n, None], closest[n:, None], p)[0]
    rate_index = int(np.argmax(np.abs(np.linalg.eigh(matrix)[1][:, 0]))) if np.all(np.isfinite(matrix)) else 0
    return SingularCrossing(
        frame=frame,
        q=closest[:n].copy(),
        inertia=float(min(lowest[frame], estimate[frame])),
        indefinite=bool(lowest[frame] < 0.0),
        rate_index=rate_index,
    )


def _parabola_minima(s: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per row of ``values`` (P, K) at equally spaced ``s`` (K,): the lowest value (P,) of the parabola through the
    row's
    lowest sample and its two neighbours (the first or last three at an end), its vertex kept inside them, and where it
    is (P,); the lowest sample itself where the parabola opens downwards; −inf where a value is not finite."""
    count, width = values.shape
    rows = np.arange(count)
    finite = np.all(np.isfinite(values), axis=1)
    k = np.argmin(np.where(np.isfinite(values), values, np.inf), axis=1)
    lowest, where = values[rows, k].astype(float), s[k].astype(float)
    if width >= 3:
        centre = np.clip(k, 1, width - 2)
        h = float(s[1] - s[0])
        v0, v1, v2 = values[rows, centre - 1], values[rows, centre], values[rows, centre + 1]
        with np.errstate(invalid="ignore", over="ignore"):
            curvature = (v2 - 2.0 * v1 + v0) / (2.0 * h * h)
            slope = (v2 - v0) / (2.0 * h)
            opens_up = finite & (curvature > 0.0)
            offset = np.clip(-slope / (2.0 * np.where(opens_up, curvature, 1.0)), -h, h)
            vertex = v1 + slope * offset + curvature * offset * offset
        better = opens_up & (vertex < lowest)
        lowest, where = np.where(better, vertex, lowest), np.where(better, s[centre] + offset, where)
    lowest[~finite] = -np.inf
    return lowest, where
