"""Linear motion about a reference motion (an equilibrium or a steady motion), its eigenvalues, its stability bounds.

The linear model's state is a chosen set of coordinates and speeds (a bicycle's
lean and steer and their rates); every other coordinate and speed follows the
reference, and the dependent ones are solved from the constraints at each
perturbed state, so the model stays on the constraint manifold. The Jacobian is
taken from the generated equations by central differences, extrapolated
(Richardson) to remove the step's leading error: about 1e-12 relative on the
bicycle's eigenvalues.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from app.physics.mechanics.multibody.compiled import CompiledSystem
from app.physics.mechanics.multibody.parts import ReferenceMotion

#: Central-difference step (rad, m, rad/s, m/s) before extrapolation.
STEP = 1e-4


def state_matrix(model: CompiledSystem, params: Mapping[str, float], reference: ReferenceMotion) -> np.ndarray:
    """The linear model's A in ẋ = A x (x: the reference's states, perturbations from it)."""
    system = model.system
    p = model.parameter_array(params)
    q0, u0 = reference.state(params)
    coordinates = [system.index(name) for name in reference.coordinates]
    speeds = [system.index(name) for name in reference.speeds]
    k = len(coordinates) + len(speeds)

    def rates(x: np.ndarray) -> np.ndarray:
        q, u = q0.copy(), u0.copy()
        q[coordinates] += x[: len(coordinates)]
        u[speeds] += x[len(coordinates) :]
        q, u = model.assemble(q, u, p)
        return np.concatenate([u[coordinates], model.accelerations(q, u, p)[speeds]])

    def central(column: int, h: float) -> np.ndarray:
        e = np.zeros(k)
        e[column] = h
        return (rates(e) - rates(-e)) / (2 * h)

    A = np.empty((k, k))
    for column in range(k):
        A[:, column] = (4 * central(column, STEP / 2) - central(column, STEP)) / 3
    return A


def eigenvalues(A: np.ndarray) -> np.ndarray:
    """Sorted by real part, then imaginary part."""
    values = np.linalg.eigvals(A)
    return values[np.lexsort((values.imag, values.real))]


@dataclass(frozen=True)
class Crossing:
    """Where the largest real part of the eigenvalues crosses zero as a parameter grows: ``value`` (the parameter's
    unit), ``becomes`` "stable" or "unstable", and whether the eigenvalue crossing is part of an oscillating pair."""

    value: float
    becomes: str
    oscillating: bool


def stability_crossings(
    spectrum: Callable[[float], np.ndarray], low: float, high: float, *, samples: int = 101, tolerance: float = 1e-12
) -> list[Crossing]:
    """Every crossing of max Re λ through zero on [low, high], found on ``samples`` points, then to ``tolerance``
    (Brent's method)."""

    def growth(value: float) -> float:
        return float(np.max(spectrum(value).real))

    grid = np.linspace(low, high, samples)
    signs = [growth(v) for v in grid]
    found = []
    for a, b, ga, gb in zip(grid[:-1], grid[1:], signs[:-1], signs[1:]):
        if (ga < 0) == (gb < 0):
            continue
        root = float(brentq(growth, a, b, xtol=tolerance, rtol=4 * np.finfo(float).eps))
        # Which eigenvalue crosses: the one with the largest real part just on the unstable side.
        side = root + (1e-6 if gb > 0 else -1e-6)
        values = spectrum(side)
        crossing = values[np.argmax(values.real)]
        found.append(Crossing(root, "unstable" if gb > 0 else "stable", bool(abs(crossing.imag) > 1e-9)))
    return found


@dataclass(frozen=True)
class Sweep:
    """The eigenvalues (points, k) at each value of one parameter, and where stability changes."""

    parameter: str
    values: np.ndarray
    eigenvalues: np.ndarray
    crossings: list[Crossing]


def sweep(
    model: CompiledSystem,
    params: Mapping[str, float],
    reference: ReferenceMotion,
    *,
    parameter: str,
    low: float,
    high: float,
    points: int,
) -> Sweep:
    """The linear model's eigenvalues as ``parameter`` runs from ``low`` to ``high`` (``points`` values), and the
    values where the largest real part crosses zero (to 1e-12, :func:`stability_crossings`)."""
    base = dict(params)

    def spectrum(value: float) -> np.ndarray:
        return eigenvalues(state_matrix(model, {**base, parameter: value}, reference))

    values = np.linspace(low, high, points)
    return Sweep(
        parameter,
        values,
        np.array([spectrum(v) for v in values]),
        stability_crossings(spectrum, low, high, samples=points),
    )
