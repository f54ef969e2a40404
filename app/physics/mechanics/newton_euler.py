"""Newton–Euler equations, body by body, with the constraint reactions as unknowns.

Each particle gives m a = ΣF (three rows, N components); each rigid body also
gives I_G α + ω × I_G ω = ΣM_G (three more, written in N components). The
forces are gravity, springs, applied forces and the declared reactions: each
:class:`~app.physics.mechanics.description.Reaction` contributes unknown
magnitudes along its force and moment directions, on one body and (reversed)
on the other. Accelerations are linear in u̇, so the rows are one linear system
in (u̇, reaction magnitudes), square when the reactions are declared fully.
"""

from __future__ import annotations

import sympy

from app.physics.mechanics.algebra import linear_parts, tidy
from app.physics.mechanics.derivation import (
    Derivation,
    FormulationUnavailable,
    Solve,
    Step,
    latex_printer,
    linear_equations_latex,
)
from app.physics.mechanics.description import Reaction, SystemDescription
from app.physics.mechanics.kinematics import body_motions, inertia_torque_body, speed_motion, spring_force_on_b
from app.physics.mechanics.speeds import recipe_through_speeds


def reaction_symbols(system: SystemDescription) -> list[tuple[sympy.Symbol, Reaction, str, int]]:
    """(magnitude symbol, reaction, "force" | "moment", index) for every unknown reaction component."""
    found = []
    for reaction in system.reactions:
        for k in range(len(reaction.forces)):
            found.append((sympy.Symbol(f"R_{reaction.name}_{k + 1}", real=True), reaction, "force", k))
        for k in range(len(reaction.moments)):
            found.append((sympy.Symbol(f"C_{reaction.name}_{k + 1}", real=True), reaction, "moment", k))
    return found


def derive_newton_euler(system: SystemDescription) -> Derivation:
    if not system.reactions:
        raise FormulationUnavailable(
            "Newton–Euler needs the constraint reactions declared body by body, and this system has none"
        )
    if system.kinetic_energy is not None or system.extra_potential != 0:
        raise FormulationUnavailable(
            "Newton–Euler needs forces, and this system gives part of its physics only as an energy"
        )
    names = dict(system.latex_names)
    motion = speed_motion(system)
    unknown_reactions = reaction_symbols(system)
    for symbol, reaction, kind, k in unknown_reactions:
        names[symbol] = f"{'R' if kind == 'force' else 'C'}_{{\\mathrm{{{reaction.name}}},{k + 1}}}"
    latex = latex_printer(names)
    positions = {p.name: p.position for p in system.particles} | {b.name: b.mass_centre for b in system.bodies}
    masses = {p.name: p.mass for p in system.particles} | {b.name: b.mass for b in system.bodies}
    # Forces (N) at points (m) and pure moments (N·m) on each body, by name.
    forces: dict[str, list[tuple[sympy.Matrix, sympy.Matrix]]] = {name: [] for name in positions}
    moments: dict[str, list[sympy.Matrix]] = {name: [] for name in positions}

    def add_force(on: str | None, point: sympy.Matrix, force: sympy.Matrix) -> None:
        if on is None:
            return
        if on not in forces:
            raise ValueError(f"{system.id}: a force acts on {on!r}, which is no particle or body")
        forces[on].append((point, force))

    if system.gravity is not None:
        for name, position in positions.items():
            add_force(name, position, masses[name] * system.gravity)
    for spring in system.springs:
        force_b = spring_force_on_b(spring)
        add_force(spring.on_b, spring.end_b, force_b)
        add_force(spring.on_a, spring.end_a, -force_b)
    for applied in system.forces:
        add_force(applied.on or None, applied.point, applied.force)
    for symbol, reaction, kind, k in unknown_reactions:
        if kind == "force":
            add_force(reaction.on, reaction.point, symbol * reaction.forces[k])
            add_force(reaction.against, reaction.point, -symbol * reaction.forces[k])
        else:
            moments[reaction.on].append(symbol * reaction.moments[k])
            if reaction.against is not None:
                moments[reaction.against].append(-symbol * reaction.moments[k])
    rows: list[sympy.Expr] = []
    steps: list[Step] = []
    for item in body_motions(system, motion):
        acceleration = motion.derivative(item.velocity)
        resultant = sum((f for _, f in forces[item.name]), sympy.zeros(3, 1))
        linear = item.mass * acceleration - resultant
        rows += list(linear)
        steps.append(
            Step(
                f"{item.name}: m a = ΣF",
                f"{latex(item.mass)}\\,{latex(tidy(acceleration).T)}^T = {latex(resultant.T)}^T",
            )
        )
        if item.angular_velocity is not None:
            centre = positions[item.name]
            moment = sum(((p - centre).cross(f) for p, f in forces[item.name]), sympy.zeros(3, 1))
            moment += sum(moments[item.name], sympy.zeros(3, 1))
            rotational = item.rotation * inertia_torque_body(item, motion) - moment
            rows += list(rotational)
            steps.append(Step(f"{item.name}: I α + ω × I ω = ΣM_G (N components)", f"{latex(moment.T)}^T"))
    unknowns = [*system.ud, *(s for s, *_ in unknown_reactions)]
    if len(rows) != len(unknowns):
        raise ValueError(
            f"{system.id}: Newton–Euler has {len(rows)} equations for {len(unknowns)} unknowns; declare the "
            "reactions fully"
        )
    A, b = linear_parts(rows, unknowns)
    equations = linear_equations_latex(A, unknowns, b, latex, tidy=tidy, tidy_left=True)
    return Derivation(
        system_id=system.id,
        formulation="newton-euler",
        variables="q, u, reactions",
        mass_matrix=A,
        forcing=b,
        equations_latex=equations,
        steps=tuple(steps),
        recipe=recipe_through_speeds(system, Solve(A, b, tuple(unknowns))),
        latex_names=names,
    )
