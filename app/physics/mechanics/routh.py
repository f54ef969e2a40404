"""Routh's method: ignorable coordinates removed through their conserved momenta.

For ignorable (cyclic) coordinates q_C — absent from L, with no generalized
force — the momenta β = ∂L/∂q̇_C are constants. The Routhian
R(q_K, q̇_K, β, t) = L − β·q̇_C, with q̇_C solved from β, is a Lagrangian for the
remaining coordinates q_K alone; the ignorable rates follow from q̇_C = −∂R/∂β.
The recipe forms β from the state, solves Routh's equations for q̈_K, and gets
q̇_C and q̈_C from −∂R/∂β and its time derivative (β constant).
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
    linear_equations_latex,
)
from app.physics.mechanics.description import SystemDescription
from app.physics.mechanics.kinematics import Motion, coordinate_motion, generalized_forces, jacobian_of
from app.physics.mechanics.lagrange import lagrangian


def routhian(system: SystemDescription) -> tuple[sympy.Expr, list[sympy.Symbol], list[sympy.Expr], list[sympy.Expr]]:
    """(R, β symbols, β as functions of (q, q̇), q̇_C in terms of (q_K, q̇_K, β))."""
    if not system.ignorable:
        raise FormulationUnavailable("Routh's method needs an ignorable coordinate, and this system has none")
    if not system.holonomic:
        raise FormulationUnavailable("Routh's method is written here for holonomic systems")
    cyclic = [c for c in system.coordinates if c.name in system.ignorable]
    T, V = lagrangian(system)
    L = T - V
    for c in cyclic:
        if L.has(c.symbol):
            raise FormulationUnavailable(f"{c.name} appears in the Lagrangian, so it is not ignorable")
    Q = generalized_forces(system, coordinate_motion(system), system.qd)
    for c, Q_j in zip(system.coordinates, Q):
        if c.name in system.ignorable and Q_j != 0:
            raise FormulationUnavailable(f"a force does work through {c.name}, so its momentum is not conserved")
    beta = [sympy.Symbol(f"beta_{c.name}", real=True) for c in cyclic]
    beta_of_state = [sympy.diff(L, c.rate) for c in cyclic]
    cyclic_rates = [c.rate for c in cyclic]
    A = sympy.Matrix(beta_of_state).jacobian(cyclic_rates)
    rest = sympy.Matrix(beta_of_state) - A * sympy.Matrix(cyclic_rates)
    solved, _ = solve_exactly(A, sympy.Matrix(beta) - rest)
    to_beta = dict(zip(cyclic_rates, solved))
    R = L.xreplace(to_beta) - sum(b * r for b, r in zip(beta, solved))
    return R, beta, beta_of_state, solved


def derive_routh(system: SystemDescription) -> Derivation:
    R, beta, beta_of_state, _ = routhian(system)
    names = dict(system.latex_names)
    kept = [c for c in system.coordinates if c.name not in system.ignorable]
    cyclic = [c for c in system.coordinates if c.name in system.ignorable]
    for c, b in zip(cyclic, beta):
        names[b] = f"\\beta_{{{c.latex}}}"
    latex = latex_printer(names)
    q_K, qd_K, qdd_K = [c.symbol for c in kept], [c.rate for c in kept], [c.acceleration for c in kept]
    motion = Motion(q_K, qd_K, qd_K, qdd_K)  # β is constant
    Q_all = dict(zip(system.q, generalized_forces(system, coordinate_motion(system), system.qd)))
    equations_zero = [motion.derivative(sympy.diff(R, r)) - sympy.diff(R, q) - Q_all[q] for q, r in zip(q_K, qd_K)]
    M = jacobian_of(equations_zero, qdd_K)
    forcing = -sympy.Matrix(equations_zero).xreplace({a: 0 for a in qdd_K})
    cyclic_rates = [-sympy.diff(R, b) for b in beta]
    cyclic_accelerations = [motion.derivative(e) for e in cyclic_rates]
    qd_c = [sympy.Symbol(f"{c.name}_dR", real=True) for c in cyclic]
    qdd_c = [sympy.Symbol(f"{c.name}_ddR", real=True) for c in cyclic]
    recipe = Recipe(
        stages=(
            Assign(tuple(beta), tuple(beta_of_state)),
            Solve(M, forcing, tuple(qdd_K)),
            Assign((*qd_c, *qdd_c), (*cyclic_rates, *cyclic_accelerations)),
        ),
        outputs=tuple(
            [c.rate if c in kept else qd_c[cyclic.index(c)] for c in system.coordinates]
            + [c.acceleration if c in kept else qdd_c[cyclic.index(c)] for c in system.coordinates]
        ),
    )
    steps = [
        *(
            Step(
                f"Conserved momentum of the ignorable {c.name}",
                f"{names[b]} = \\frac{{\\partial L}}{{\\partial {names[c.rate]}}} = {latex(tidy(e))}",
            )
            for c, b, e in zip(cyclic, beta, beta_of_state)
        ),
        Step("Routhian", f"R = L - \\sum \\beta \\dot q_C = {latex(R)}"),
        *(
            Step(
                f"Ignorable rate {c.name}",
                f"{names[c.rate]} = -\\frac{{\\partial R}}{{\\partial {names[b]}}} = {latex(e)}",
            )
            for c, b, e in zip(cyclic, beta, cyclic_rates)
        ),
    ]
    equations = linear_equations_latex(M, qdd_K, forcing, latex) + tuple(
        f"{names[c.rate]} = {latex(e)}" for c, e in zip(cyclic, cyclic_rates)
    )
    return Derivation(
        system_id=system.id,
        formulation="routh",
        variables="q_K, q̇_K, β",
        mass_matrix=M,
        forcing=forcing,
        equations_latex=equations,
        steps=tuple(steps),
        recipe=recipe,
        latex_names=names,
    )
