"""A small dense linear solve for generated right-hand sides (n ≤ about 12), compiled and plain."""

from __future__ import annotations

import numba
import numpy as np


def solve_small_python(A: np.ndarray, b: np.ndarray) -> bool:
    """Solve A x = b in place (x overwrites b; A is destroyed) by Gaussian elimination with partial pivoting.

    Returns False, leaving b undefined, if a pivot is below 1e-13 times the
    largest entry of A: the matrix is singular to working precision.
    """
    n = b.shape[0]
    scale = 0.0
    for i in range(n):
        for j in range(n):
            scale = max(scale, abs(A[i, j]))
    if not scale > 0.0:
        return False
    for k in range(n):
        pivot = k
        for i in range(k + 1, n):
            if abs(A[i, k]) > abs(A[pivot, k]):
                pivot = i
        if not abs(A[pivot, k]) > 1e-13 * scale:
            return False
        if pivot != k:
            for j in range(n):
                A[k, j], A[pivot, j] = A[pivot, j], A[k, j]
            b[k], b[pivot] = b[pivot], b[k]
        for i in range(k + 1, n):
            factor = A[i, k] / A[k, k]
            for j in range(k, n):
                A[i, j] -= factor * A[k, j]
            b[i] -= factor * b[k]
    for k in range(n - 1, -1, -1):
        total = b[k]
        for j in range(k + 1, n):
            total -= A[k, j] * b[j]
        b[k] = total / A[k, k]
    return True


solve_small = numba.njit(cache=True, nogil=True, error_model="numpy")(solve_small_python)
