"""Lagrange's equations, d/dt(∂L/∂q̇_j) − ∂L/∂q_j = Q_j, through ``sympy.physics.mechanics.LagrangesMethod``.

L = T − V is built from the description (T from the particles' and bodies'
velocities, V from gravity, springs and any extra term); Q_j are the applied
non-conservative forces' generalized forces Σ F·∂v/∂q̇_j. sympy forms the mass
matrix and forcing (M q̈ = f); the steps a student follows are formed here.
"""

from __future__ import annotations

import sympy
from sympy.physics.mechanics import LagrangesMethod, dynamicsymbols

from app.physics.mechanics.algebra import tidy
from app.physics.mechanics.derivation import (
    Derivation,
    FormulationUnavailable,
    Recipe,
    Solve,
    Step,
    latex_printer,
    linear_equations_latex,
)
from app.physics.mechanics.description import TIME, SystemDescription
from app.physics.mechanics.kinematics import coordinate_motion, generalized_forces, kinetic_energy, potential_energy


def lagrangian(system: SystemDescription) -> tuple[sympy.Expr, sympy.Expr]:
    """(T, V) in (q, q̇, t), J."""
    return kinetic_energy(system, coordinate_motion(system)), potential_energy(system)


def _lagranges_method(system: SystemDescription, lagrangian_expr: sympy.Expr) -> tuple[sympy.Matrix, sympy.Matrix]:
    """sympy's mass matrix and forcing for L (conservative part), back in plain symbols."""
    t = dynamicsymbols._t
    functions = [dynamicsymbols(c.name) for c in system.coordinates]
    forward = {TIME: t}
    for c, f in zip(system.coordinates, functions):
        forward[c.symbol] = f
        forward[c.rate] = f.diff(t)
    method = LagrangesMethod(lagrangian_expr.xreplace(forward), functions)
    method.form_lagranges_equations()
    back = {t: TIME}
    for c, f in zip(system.coordinates, functions):
        back[f.diff(t, 2)] = c.acceleration
        back[f.diff(t)] = c.rate
        back[f] = c.symbol
    return method.mass_matrix.xreplace(back), method.forcing.xreplace(back)


def derive_lagrange(system: SystemDescription) -> Derivation:
    if not system.holonomic:
        raise FormulationUnavailable(
            "Lagrange's equations in this form need as many independent coordinates as degrees of freedom; the rolling "
            "constraints restrict velocities only, so they need multipliers (chapter 8)"
        )
    names = system.latex_names
    latex = latex_printer(names)
    motion = coordinate_motion(system)
    T, V = lagrangian(system)
    L = T - V
    Q = generalized_forces(system, motion, system.qd)
    mass_matrix, conservative_forcing = _lagranges_method(system, L)
    forcing = conservative_forcing + sympy.Matrix(Q)
    steps = [Step("Kinetic energy", f"T = {latex(T)}"), Step("Potential energy", f"V = {latex(V)}")]
    for c, q_j, qd_j, Q_j in zip(system.coordinates, system.q, system.qd, Q):
        momentum = sympy.diff(L, qd_j)
        steps.append(
            Step(
                f"Coordinate {c.name}: ∂L/∂q̇",
                f"\\frac{{\\partial L}}{{\\partial {names[qd_j]}}} = {latex(tidy(momentum))}",
            )
        )
        steps.append(
            Step(
                f"Coordinate {c.name}: d/dt of it",
                f"\\frac{{d}}{{dt}}\\frac{{\\partial L}}{{\\partial {names[qd_j]}}} = "
                f"{latex(tidy(motion.derivative(momentum)))}",
            )
        )
        steps.append(
            Step(
                f"Coordinate {c.name}: ∂L/∂q",
                f"\\frac{{\\partial L}}{{\\partial {names[q_j]}}} = {latex(tidy(sympy.diff(L, q_j)))}",
            )
        )
        steps.append(Step(f"Coordinate {c.name}: generalized force", f"Q_{{{names[q_j]}}} = {latex(Q_j)}"))
    equations = linear_equations_latex(mass_matrix, system.qdd, forcing, latex, tidy=tidy)
    return Derivation(
        system_id=system.id,
        formulation="lagrange",
        variables="q, q̇",
        mass_matrix=mass_matrix,
        forcing=forcing,
        equations_latex=equations,
        steps=tuple(steps),
        recipe=Recipe(stages=(Solve(mass_matrix, forcing, tuple(system.qdd)),), outputs=(*system.qd, *system.qdd)),
        latex_names=names,
    )
