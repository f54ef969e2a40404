"""What the speed-based formulations (Kane, Gibbs–Appell, Newton–Euler) share.

Their unknowns are the speed derivatives u̇; the common answer is (q̇, q̈), so
the recipe first recovers u from the state's q̇ (for a holonomic system u = q̇
and nothing is done), solves the formulation's linear system, and then forms
q̇ = q̇(q, u, t) and q̈ = d/dt q̇(q, u, t).
"""

from __future__ import annotations

import sympy

from app.physics.mechanics.derivation import Assign, Recipe, Solve
from app.physics.mechanics.description import SystemDescription
from app.physics.mechanics.kinematics import speed_motion


def recipe_through_speeds(system: SystemDescription, solve: Solve) -> Recipe:
    """Stages: u from q̇ (nonholonomic only), the formulation's solve, then (q̇, q̈) from (u, u̇)."""
    motion = speed_motion(system)
    rates = system.rates_in_speeds
    accelerations = [motion.derivative(r) for r in rates]
    stages: list[Assign | Solve] = []
    if not system.holonomic:
        assert system.speeds_from_rates is not None  # a description with speeds names them (checked on construction)
        stages.append(Assign(tuple(system.u), tuple(system.speeds_from_rates)))
    stages.append(solve)
    if system.holonomic:
        return Recipe(tuple(stages), (*system.qd, *system.qdd))
    qd_out = [sympy.Symbol(f"{c.name}_dS", real=True) for c in system.coordinates]
    qdd_out = [sympy.Symbol(f"{c.name}_ddS", real=True) for c in system.coordinates]
    stages.append(Assign((*qd_out, *qdd_out), (*rates, *accelerations)))
    return Recipe(tuple(stages), (*qd_out, *qdd_out))


def conservative_share(system: SystemDescription, potential: sympy.Expr) -> list[sympy.Expr]:
    """−Σ_i ∂V/∂q_i · ∂q̇_i/∂u_r for each speed u_r (N or N·m)."""
    rates = system.rates_in_speeds
    return [
        -sum(sympy.diff(potential, q_i) * sympy.diff(rate_i, u_r) for q_i, rate_i in zip(system.q, rates))
        for u_r in system.u
    ]
