"""Hamilton's canonical equations, q̇ = ∂H/∂p, ṗ = −∂H/∂q + Q, with H(q, p, t) = p·q̇ − L.

The momenta p = ∂L/∂q̇ = M(q, t) q̇ + b(q, t) are linear in the rates, so the
Legendre transformation is exact: q̇ = M⁻¹(p − b), solved symbolically. To
answer in the common state (q, q̇) the recipe forms p from q̇, takes Hamilton's
q̇ and ṗ, and converts ṗ back to q̈ through ṗ = M q̈ + (∂p/∂q) q̇ + ∂p/∂t.
"""

from __future__ import annotations

import sympy

from app.physics.mechanics.algebra import solve_exactly, tidy
from app.physics.mechanics.derivation import (
    Assign,
    Derivation,
    FormulationUnavailable,
    Recipe,
    Solve,
    Step,
    latex_printer,
)
from app.physics.mechanics.description import TIME, SystemDescription
from app.physics.mechanics.kinematics import coordinate_motion, generalized_forces, jacobian_of
from app.physics.mechanics.lagrange import lagrangian


def momentum_symbols(system: SystemDescription) -> list[sympy.Symbol]:
    return [sympy.Symbol(f"p_{c.name}", real=True) for c in system.coordinates]


def legendre_rates(
    L: sympy.Expr, rates: list[sympy.Symbol], momenta: list[sympy.Symbol]
) -> tuple[sympy.Matrix, sympy.Matrix, list[sympy.Expr]]:
    """(M, b, q̇(p)): ∂L/∂q̇ = M q̇ + b, and the rates solved for the given momenta (adjugate over determinant).

    Raises FormulationUnavailable if L is not quadratic in the rates or M is singular.
    """
    momentum = sympy.Matrix([sympy.diff(L, r) for r in rates])
    M = momentum.jacobian(rates)
    if any(M.diff(r) != sympy.zeros(*M.shape) for r in rates):
        raise FormulationUnavailable(
            "the Lagrangian is not quadratic in the rates, so the Legendre transformation is not linear"
        )
    b = momentum.xreplace({r: 0 for r in rates})
    try:
        solved, _ = solve_exactly(M, sympy.Matrix(momenta) - b)
    except ZeroDivisionError:
        raise FormulationUnavailable(
            "the mass matrix is singular, so the rates cannot be written in terms of the momenta"
        ) from None
    return M, b, solved


def hamiltonian(L: sympy.Expr, rates: list[sympy.Symbol], M: sympy.Matrix, rates_of_p: list[sympy.Expr]) -> sympy.Expr:
    """H(q, p, t) = ½ q̇ᵀ M q̇ − T₀ + V with q̇ = q̇(p): for L = ½ q̇ᵀ M q̇ + b·q̇ + T₀ − V, this is p·q̇ − L."""
    at_rest = L.xreplace({r: 0 for r in rates})  # T₀ − V
    qd = sympy.Matrix(rates_of_p)
    return sympy.Rational(1, 2) * (qd.T * M * qd)[0] - at_rest


def derive_hamilton(system: SystemDescription) -> Derivation:
    if not system.holonomic:
        raise FormulationUnavailable(
            "Hamilton's equations need independent generalized coordinates (the rolling constraints are nonholonomic)"
        )
    names = dict(system.latex_names)
    P = momentum_symbols(system)
    for c, p in zip(system.coordinates, P):
        names[p] = f"p_{{{c.latex}}}"
    latex = latex_printer(names)
    q, qd, qdd = system.q, system.qd, system.qdd
    T, V = lagrangian(system)
    L = T - V
    M, b, rates_of_p = legendre_rates(L, qd, P)
    to_p = dict(zip(qd, rates_of_p))
    H = hamiltonian(L, qd, M, rates_of_p)
    Q = [e.xreplace(to_p) for e in generalized_forces(system, coordinate_motion(system), qd)]
    qd_hamilton = [sympy.diff(H, p) for p in P]
    pd_hamilton = [-sympy.diff(H, q_j) + Q_j for q_j, Q_j in zip(q, Q)]
    # Back to q̈: ṗ = M q̈ + (∂p/∂q) q̇ + ∂p/∂t, with p(q, q̇, t) = M q̇ + b.
    p_of_rates = M * sympy.Matrix(qd) + b
    rest = jacobian_of(p_of_rates, q) * sympy.Matrix(qd) + p_of_rates.diff(TIME)
    qd_h = [sympy.Symbol(f"{c.name}_dH", real=True) for c in system.coordinates]
    pd_h = [sympy.Symbol(f"p_{c.name}_d", real=True) for c in system.coordinates]
    rest_at_h = rest.xreplace(dict(zip(qd, qd_h)))
    recipe = Recipe(
        stages=(
            Assign(tuple(P), tuple(p_of_rates)),
            Assign((*qd_h, *pd_h), (*qd_hamilton, *pd_hamilton)),
            Solve(M, sympy.Matrix(pd_h) - rest_at_h, tuple(qdd)),
        ),
        outputs=(*qd_h, *qdd),
    )
    steps = [
        Step("Lagrangian", f"L = T - V = {latex(L)}"),
        *(
            Step(
                f"Momentum conjugate to {c.name}",
                f"{names[p]} = \\frac{{\\partial L}}{{\\partial {names[r]}}} = {latex(tidy(e))}",
            )
            for c, p, r, e in zip(system.coordinates, P, qd, p_of_rates)
        ),
        *(
            Step(f"Rate of {c.name} in terms of the momenta", f"{names[r]} = {latex(e)}")
            for c, r, e in zip(system.coordinates, qd, rates_of_p)
        ),
        Step("Hamiltonian", f"H = \\sum_j p_j \\dot q_j - L = {latex(H)}"),
    ]
    equations = []
    for c, p, q_j, r, e_q, e_p in zip(system.coordinates, P, q, qd, qd_hamilton, pd_hamilton):
        equations.append(f"{names[r]} = \\frac{{\\partial H}}{{\\partial {names[p]}}} = {latex(e_q)}")
        equations.append(
            f"\\dot{{p}}_{{{c.latex}}} = -\\frac{{\\partial H}}{{\\partial {names[q_j]}}} + Q_{{{c.latex}}} = "
            f"{latex(e_p)}"
        )
    n = len(q)
    pd_symbols = sympy.Matrix(pd_h)
    return Derivation(
        system_id=system.id,
        formulation="hamilton",
        variables="q, p",
        mass_matrix=sympy.eye(2 * n),
        forcing=sympy.Matrix([*qd_hamilton, *pd_hamilton]),
        equations_latex=tuple(equations),
        steps=tuple(steps),
        recipe=recipe,
        latex_names={**names, **{s: f"\\dot{{p}}_{{{c.latex}}}" for s, c in zip(pd_symbols, system.coordinates)}},
    )
