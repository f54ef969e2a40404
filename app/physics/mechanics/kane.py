"""Kane's equations, F_r + F*_r = 0, from partial velocities.

For each speed u_r: the partial velocities ∂v/∂u_r of every mass centre and
point a force acts at, and the partial angular velocities ∂ω/∂u_r. The
generalized active forces F_r = Σ F·∂v/∂u_r take gravity, springs and applied
forces as forces (not through a potential, unlike Gibbs–Appell), and the
generalized inertia forces are F*_r = −Σ m a·∂v/∂u_r − Σ ∂ω/∂u_r·(I α + ω × I ω).
Constraint forces that do no work never enter.
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
from app.physics.mechanics.description import SystemDescription
from app.physics.mechanics.kinematics import body_motions, inertia_torque_body, speed_motion, spring_force_on_b
from app.physics.mechanics.speeds import conservative_share, recipe_through_speeds


def derive_kane(system: SystemDescription) -> Derivation:
    if system.kinetic_energy is not None:
        raise FormulationUnavailable("Kane's equations need the particles and bodies, not only an energy expression")
    names = system.latex_names
    latex = latex_printer(names)
    motion = speed_motion(system)
    u, ud = system.u, system.ud
    items = body_motions(system, motion)
    # Forces at points: gravity at mass centres, springs at both ends, applied forces.
    point_forces: list[tuple[sympy.Matrix, sympy.Matrix]] = []
    if system.gravity is not None:
        point_forces += [(p.position, p.mass * system.gravity) for p in system.particles]
        point_forces += [(b.mass_centre, b.mass * system.gravity) for b in system.bodies]
    for spring in system.springs:
        force_b = spring_force_on_b(spring)
        point_forces += [(spring.end_b, force_b), (spring.end_a, -force_b)]
    point_forces += [(f.point, f.force) for f in system.forces]
    point_velocities = [motion.derivative(point) for point, _ in point_forces]
    active = [
        sum(
            ((force.T * velocity.diff(u_r))[0] for (_, force), velocity in zip(point_forces, point_velocities)),
            sympy.Integer(0),
        )
        for u_r in u
    ]
    active = [a + c for a, c in zip(active, conservative_share(system, system.extra_potential))]
    inertia = []
    for u_r in u:
        total = sympy.Integer(0)
        for item in items:
            acceleration = motion.derivative(item.velocity)
            total -= item.mass * (acceleration.T * item.velocity.diff(u_r))[0]
            if item.angular_velocity is not None:
                total -= (item.angular_velocity.diff(u_r).T * inertia_torque_body(item, motion))[0]
        inertia.append(total)
    A, b = linear_parts([a + s for a, s in zip(active, inertia)], ud)
    M, forcing = -A, -b
    steps = []
    for item in items:
        for u_r, speed in zip(u, system.speed_list):
            steps.append(
                Step(
                    f"Partial velocity of {item.name} for {speed.name}",
                    f"\\frac{{\\partial \\mathbf v_{{{item.name}}}}}{{\\partial {names[u_r]}}} = "
                    f"{latex(tidy(item.velocity.diff(u_r)).T)}",
                )
            )
            if item.angular_velocity is not None:
                steps.append(
                    Step(
                        f"Partial angular velocity of {item.name} for {speed.name}",
                        f"\\frac{{\\partial \\boldsymbol\\omega_{{{item.name}}}}}{{\\partial {names[u_r]}}} = "
                        f"{latex(tidy(item.angular_velocity.diff(u_r)).T)}",
                    )
                )
    for speed, F_r, Fs_r in zip(system.speed_list, active, inertia):
        steps.append(Step(f"Generalized active force for {speed.name}", f"F_{{{speed.latex}}} = {latex(tidy(F_r))}"))
        steps.append(
            Step(f"Generalized inertia force for {speed.name}", f"F^*_{{{speed.latex}}} = {latex(tidy(Fs_r))}")
        )
    equations = linear_equations_latex(M, ud, forcing, latex, tidy=tidy)
    return Derivation(
        system_id=system.id,
        formulation="kane",
        variables="q, u",
        mass_matrix=M,
        forcing=forcing,
        equations_latex=equations,
        steps=tuple(steps),
        recipe=recipe_through_speeds(system, Solve(M, forcing, tuple(ud))),
        latex_names=names,
    )
