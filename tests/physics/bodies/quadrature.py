"""Mass properties from the definitions, by Gauss–Legendre quadrature over each primitive's volume, area or line.

Independent of :mod:`app.physics.bodies.inertia`'s closed forms: each shape is
parametrised in its natural coordinates (spherical, cylindrical, Cartesian) with
its Jacobian, and ``m``, ``∫ r dm`` and ``I = ∫ (|r|² 1 − r rᵀ) dm`` are summed
over tensor-product Gauss–Legendre nodes. With 24 nodes per coordinate every
integrand here (polynomials in ρ, z and trigonometric polynomials in the
angles) is integrated to rounding (relative 1e-13 or better).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

NODES = 24


def _gauss(low: float, high: float, n: int = NODES) -> tuple[np.ndarray, np.ndarray]:
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.5 * (high - low) * x + 0.5 * (high + low), 0.5 * (high - low) * w


def _grid(*axes: tuple[np.ndarray, np.ndarray]) -> tuple[list[np.ndarray], np.ndarray]:
    coords = np.meshgrid(*[a[0] for a in axes], indexing="ij")
    weights = np.ones_like(coords[0])
    for i, (_, w) in enumerate(axes):
        shape = [1] * len(axes)
        shape[i] = len(w)
        weights = weights * w.reshape(shape)
    return [c.ravel() for c in coords], weights.ravel()


def _cylindrical(rho_low: float, rho_high: Callable[[np.ndarray], np.ndarray] | float, z_low: float, z_high: float) -> tuple[np.ndarray, np.ndarray]:
    """Points and measure weights over a solid of revolution about z (ρ from rho_low to rho_high(z))."""
    (u, phi, z), w = _grid(_gauss(0.0, 1.0), _gauss(0.0, 2 * math.pi), _gauss(z_low, z_high))
    top = rho_high(z) if callable(rho_high) else np.full_like(z, rho_high)
    rho = rho_low + u * (top - rho_low)
    points = np.column_stack([rho * np.cos(phi), rho * np.sin(phi), z])
    return points, w * rho * (top - rho_low)


def sample(shape: str, **d: float) -> tuple[np.ndarray, np.ndarray]:
    """Quadrature points (N, 3) in the shape's own axes and their measure weights (m³, m² or m) for unit density."""
    if shape in ("sphere", "spherical-shell"):
        r = d["radius_m"]
        if shape == "sphere":
            (rr, th, ph), w = _grid(_gauss(0.0, r), _gauss(0.0, math.pi), _gauss(0.0, 2 * math.pi))
            w = w * rr**2 * np.sin(th)
        else:
            (th, ph), w = _grid(_gauss(0.0, math.pi), _gauss(0.0, 2 * math.pi))
            rr = np.full_like(th, r)
            w = w * r**2 * np.sin(th)
        return np.column_stack([rr * np.sin(th) * np.cos(ph), rr * np.sin(th) * np.sin(ph), rr * np.cos(th)]), w
    if shape == "cylinder":
        return _cylindrical(0.0, d["radius_m"], -d["length_m"] / 2, d["length_m"] / 2)
    if shape == "tube":
        return _cylindrical(d["inner_radius_m"], d["radius_m"], -d["length_m"] / 2, d["length_m"] / 2)
    if shape == "cone":
        r, h = d["radius_m"], d["height_m"]
        return _cylindrical(0.0, lambda z: r * (0.75 * h - z) / h, -h / 4, 0.75 * h)
    if shape == "box":
        a, b, c = d["length_m"], d["width_m"], d["height_m"]
        (x, y, z), w = _grid(_gauss(-a / 2, a / 2), _gauss(-b / 2, b / 2), _gauss(-c / 2, c / 2))
        return np.column_stack([x, y, z]), w
    if shape == "plate":
        a, b = d["length_m"], d["width_m"]
        (x, y), w = _grid(_gauss(-a / 2, a / 2), _gauss(-b / 2, b / 2))
        return np.column_stack([x, y, np.zeros_like(x)]), w
    if shape == "disk":
        (rho, phi), w = _grid(_gauss(0.0, d["radius_m"]), _gauss(0.0, 2 * math.pi))
        return np.column_stack([rho * np.cos(phi), rho * np.sin(phi), np.zeros_like(rho)]), w * rho
    if shape == "rod":
        z, w = _gauss(-d["length_m"] / 2, d["length_m"] / 2)
        return np.column_stack([np.zeros_like(z), np.zeros_like(z), z]), w
    raise KeyError(shape)


def mass_properties(points_m: np.ndarray, mass_weights_kg: np.ndarray) -> tuple[float, np.ndarray, np.ndarray]:
    """Mass (kg), centre of mass (m) and the tensor about the frame's origin (kg·m²) from weighted points."""
    m = float(np.sum(mass_weights_kg))
    centre = points_m.T @ mass_weights_kg / m
    r2 = np.sum(points_m**2, axis=1)
    tensor = np.eye(3) * float(r2 @ mass_weights_kg) - (points_m * mass_weights_kg[:, None]).T @ points_m
    return m, centre, tensor
