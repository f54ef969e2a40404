"""A derivation as data: its equations, its steps, and the recipe that evaluates it.

Every formulation answers the same numerical question — the state derivative
(q̇, q̈) at a state (q, q̇) and time t — through its own variables: Lagrange's
through q̈ directly, Hamilton's through the momenta p, Routh's through the
ignorable momenta β, Kane's and Gibbs–Appell's through the speeds u and u̇,
Newton–Euler's through u̇ and the reaction magnitudes. The :class:`Recipe`
spells that path out as stages of assignments and linear solves over sympy
expressions, so one code generator turns any of them into a function.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

import sympy

from app.physics.mechanics.shown import print_latex

#: The formulations, in the order the page shows them (ids are API contracts).
FORMULATIONS = ("newton-euler", "lagrange", "hamilton", "routh", "gibbs-appell", "kane")
FORMULATION_TITLES = {
    "newton-euler": "Newton–Euler",
    "lagrange": "Lagrange",
    "hamilton": "Hamilton",
    "routh": "Routh",
    "gibbs-appell": "Gibbs–Appell",
    "kane": "Kane",
}


def latex_printer(names: dict) -> Callable[[sympy.Expr | sympy.Matrix], str]:
    """LaTeX of an expression with the page's symbol names (θ₁, θ̇₁ …); inside :func:`~.shown.shown_forms` (the
    engine's derivations) a token for it, filled in with its simplified form once the derivation is done."""
    return lambda expr: print_latex(expr, names)


def linear_equations_latex(
    matrix: sympy.Matrix,
    unknowns: Sequence[sympy.Symbol],
    forcing: sympy.Matrix,
    latex: Callable[[sympy.Expr], str],
    *,
    tidy: Callable[[sympy.Expr], sympy.Expr] = lambda e: e,
    tidy_left: bool = False,
) -> tuple[str, ...]:
    """One LaTeX equation per row of matrix · unknowns = forcing: the right side passed through ``tidy``,
    the left (the unknowns' coefficients, kept as written) only with ``tidy_left``."""
    column = sympy.Matrix(list(unknowns))
    left = tidy if tidy_left else (lambda e: e)
    return tuple(latex(sympy.Eq(left((matrix[j, :] * column)[0]), tidy(forcing[j]))) for j in range(matrix.shape[0]))


class FormulationUnavailable(ValueError):
    """This formulation does not apply to this system (the message says why)."""


@dataclass(frozen=True)
class Step:
    """One step a student follows: a title and the LaTeX it shows."""

    title: str
    latex: str

    def as_dict(self) -> dict[str, str]:
        return {"title": self.title, "latex": self.latex}


@dataclass(frozen=True)
class Assign:
    """``targets[i] = values[i]``, in order (values may use earlier targets)."""

    targets: tuple[sympy.Symbol, ...]
    values: tuple[sympy.Expr, ...]


@dataclass(frozen=True)
class Solve:
    """Solve ``matrix · targets = rhs`` (a small dense system) for ``targets``."""

    matrix: sympy.Matrix
    rhs: sympy.Matrix
    targets: tuple[sympy.Symbol, ...]


@dataclass(frozen=True)
class Recipe:
    """From (t, q, q̇, parameters) to the state derivative (q̇, q̈), stage by stage."""

    stages: tuple[Assign | Solve, ...]
    outputs: tuple[sympy.Expr, ...]


@dataclass(frozen=True)
class Derivation:
    """The equations of motion of one system by one formulation.

    ``mass_matrix`` and ``forcing`` are the formulation's own: M·(its
    accelerations) = forcing, in the variables it names in ``variables``
    (for Newton–Euler the unknowns include the reaction magnitudes).
    """

    system_id: str
    formulation: str
    variables: str
    mass_matrix: sympy.Matrix
    forcing: sympy.Matrix
    equations_latex: tuple[str, ...]
    steps: tuple[Step, ...]
    recipe: Recipe
    latex_names: dict = field(default_factory=dict, compare=False, repr=False)

    def latex(self, expr: sympy.Expr | sympy.Matrix) -> str:
        return latex_printer(self.latex_names)(expr)
