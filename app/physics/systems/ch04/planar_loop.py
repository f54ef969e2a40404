"""Pieces every planar loop-closure solution needs.

Differentiating a planar vector loop once gives two scalar equations linear in
the two unknown rates; differentiating again gives the same matrix with a new
right side for the accelerations. :func:`solve_2x2` solves such systems for
arrays of configurations at once (Cramer's rule) and says where the matrix is
singular, which for a linkage is a toggle or change point. :func:`continuous_angle`
turns an angle known only modulo 2π into the branch nearest a reference, so
plotted angles do not jump by 2π.
"""

from __future__ import annotations

import numpy as np

TWO_PI = 2.0 * np.pi


def solve_2x2(
    m11: np.ndarray | float,
    m12: np.ndarray | float,
    m21: np.ndarray | float,
    m22: np.ndarray | float,
    r1: np.ndarray | float,
    r2: np.ndarray | float,
    *,
    singular_below: np.ndarray | float,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Solve ``[[m11, m12], [m21, m22]] x = [r1, r2]`` elementwise.

    All arguments broadcast together. Where ``|det| <= singular_below`` the
    system is treated as singular: both unknowns are NaN and the returned mask
    is True there. Returns ``(x1, x2, singular)``.
    """
    det = m11 * m22 - m12 * m21
    singular = np.abs(det) <= singular_below
    safe = np.where(singular, 1.0, det)
    x1 = np.where(singular, np.nan, (r1 * m22 - m12 * r2) / safe)
    x2 = np.where(singular, np.nan, (m11 * r2 - r1 * m21) / safe)
    return x1, x2, np.broadcast_to(singular, x1.shape)


def wrap_angle(angle_rad: np.ndarray) -> np.ndarray:
    """Angle (rad) wrapped into [-π, π)."""
    return (np.asarray(angle_rad, dtype=float) + np.pi) % TWO_PI - np.pi


def continuous_angle(wrapped_rad: np.ndarray, reference_rad: np.ndarray) -> np.ndarray:
    """``wrapped + 2πk`` with the integer k that lands nearest ``reference`` (rad).

    Exact whenever the reference is within π of the true continuous angle.
    """
    wrapped = np.asarray(wrapped_rad, dtype=float)
    return wrapped + TWO_PI * np.round((np.asarray(reference_rad, dtype=float) - wrapped) / TWO_PI)
