"""Symbolic algebra the formulations share: tidying, linear parts, small exact solves."""

from __future__ import annotations

from collections.abc import Sequence

import sympy


def tidy(expr: sympy.Expr | sympy.Matrix) -> sympy.Expr | sympy.Matrix:
    """A cheap tidy-up for display and code size: expand, then gather trigonometric squares.

    Meant for polynomial-like expressions (energies, matrix entries); a large
    rational expression is better tidied piece by piece (see :func:`solve_exactly`).
    """
    if isinstance(expr, sympy.MatrixBase):
        return expr.applyfunc(tidy)
    return sympy.trigsimp(sympy.expand(expr))


def linear_parts(
    expressions: Sequence[sympy.Expr], unknowns: Sequence[sympy.Symbol]
) -> tuple[sympy.Matrix, sympy.Matrix]:
    """(A, b) with expressions = A·unknowns − b (the expressions must be linear in the unknowns)."""
    A = sympy.Matrix(list(expressions)).jacobian(list(unknowns))
    b = -sympy.Matrix(list(expressions)).xreplace({x: 0 for x in unknowns})
    return A, b


def solve_exactly(matrix: sympy.Matrix, rhs: sympy.Matrix) -> tuple[list[sympy.Expr], sympy.Expr]:
    """(x, det) with matrix·x = rhs, as adj(matrix)·rhs / det, each piece tidied on its own.

    Raises ZeroDivisionError if the determinant is identically zero.
    """
    determinant = tidy(matrix.det())
    if determinant == 0:
        raise ZeroDivisionError("the matrix is singular")
    adjugate = tidy(matrix.adjugate())
    return [sympy.expand(e) / determinant for e in adjugate * rhs], determinant
