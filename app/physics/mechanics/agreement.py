"""Do the formulations agree? Numerically at random states, and symbolically where sympy can prove it.

Numerical: every available formulation's state derivative (q̇, q̈) at the same
states, compared with Lagrange's (or the first available one) as
|ẏ_f − ẏ_ref| / |ẏ_ref|. Symbolic: each formulation's recipe is replayed on
symbols (its solves done exactly) to give q̈_f(q, q̇, t), and
M_ref q̈_f − f_ref is simplified; zero is a proof that the two sets of
equations are the same. Proofs can be slow, so callers bound them in time.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import sympy

from app.physics.mechanics.derivation import Assign, Derivation, Recipe
from app.physics.mechanics.description import SystemDescription
from app.physics.mechanics.engine import DERIVERS, available_formulations, derived


def reference_formulation(system: SystemDescription) -> str:
    """Lagrange where it applies, else the first available formulation."""
    available = [f for f, reason in available_formulations(system).items() if not reason]
    return "lagrange" if "lagrange" in available else available[0]


def random_states(system: SystemDescription, rng: np.random.Generator, count: int) -> np.ndarray:
    """(count, 2n) states: coordinates in the system's ``state_ranges`` (default ±π rad, ±1 m), rates in ±3 /s."""
    columns = []
    for c in system.coordinates:
        low, high = system.state_ranges.get(c.name, (-np.pi, np.pi) if c.unit == "rad" else (-1.0, 1.0))
        columns.append(rng.uniform(low, high, count))
    columns += [rng.uniform(-3.0, 3.0, count) for _ in system.coordinates]
    return np.column_stack(columns)


def formulation_agreement(
    system: SystemDescription, params: Mapping[str, float], states: np.ndarray, *, t_s: float = 0.37
) -> dict[str, float]:
    """Per available formulation, the largest relative difference from the reference over ``states`` (N, 2n)."""
    p = np.array(system.parameter_array(params))
    reference = derived(system, reference_formulation(system))
    expected = [reference.state_derivative(t_s, y, p) for y in states]
    worst: dict[str, float] = {}
    for formulation, reason in available_formulations(system).items():
        if reason:
            continue
        result = derived(system, formulation)
        worst[formulation] = max(
            float(np.linalg.norm(result.state_derivative(t_s, y, p) - e) / np.linalg.norm(e))
            for y, e in zip(states, expected)
        )
    return worst


def symbolic_state_derivative(recipe: Recipe) -> list[sympy.Expr]:
    """The recipe's outputs as expressions of (q, q̇, t, parameters): assignments substituted, solves done exactly."""
    values: dict[sympy.Symbol, sympy.Expr] = {}
    for stage in recipe.stages:
        if isinstance(stage, Assign):
            for target, value in zip(stage.targets, stage.values):
                values[target] = sympy.sympify(value).xreplace(values)
        else:
            solution = stage.matrix.xreplace(values).LUsolve(stage.rhs.xreplace(values))
            values.update(zip(stage.targets, solution))
    return [sympy.sympify(e).xreplace(values) for e in recipe.outputs]


def proves_same_equations(system: SystemDescription, formulation: str) -> bool:
    """Whether sympy shows M q̈_f(q, q̇) = f (the reference's M and f) identically; False if it cannot tell.

    Runs sympy; may take long: bound it (a test or the benchmark runs it in a bounded process).
    """
    reference: Derivation = DERIVERS[reference_formulation(system)](system)
    candidate: Derivation = DERIVERS[formulation](system)
    n = len(system.coordinates)
    outputs = symbolic_state_derivative(candidate.recipe)
    reference_outputs = symbolic_state_derivative(reference.recipe)
    for rate, expected_rate in zip(outputs[:n], reference_outputs[:n]):
        if sympy.simplify(rate - expected_rate) != 0:
            return False
    if reference.formulation == "lagrange":
        residual = reference.mass_matrix * sympy.Matrix(outputs[n:]) - reference.forcing
        return all(sympy.simplify(sympy.together(r)) == 0 for r in residual)
    return all(sympy.simplify(a - b) == 0 for a, b in zip(outputs[n:], reference_outputs[n:]))
