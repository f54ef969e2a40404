"""The Gibbs–Appell equations, ∂S/∂u̇_r = Π_r, from the Gibbs function (the "energy of acceleration").

S = Σ ½ m a·a over particles and mass centres, plus ½ αᵀ I α + αᵀ(ω × I ω)
for each body (terms free of the accelerations u̇ dropped: they vanish in
∂S/∂u̇). Π_r are the generalized forces for the speeds: the applied forces'
Σ F·∂v/∂u_r and the potential's −Σ ∂V/∂q_i ∂q̇_i/∂u_r (gravity and springs
enter through V here, as forces in Kane's form).
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
from app.physics.mechanics.kinematics import body_motions, generalized_forces, potential_energy, speed_motion
from app.physics.mechanics.speeds import conservative_share, recipe_through_speeds


def gibbs_function(system: SystemDescription) -> sympy.Expr:
    """S in (q, u, u̇, t), kg·m²/s⁴."""
    motion = speed_motion(system)
    S = sympy.Integer(0)
    for item in body_motions(system, motion):
        acceleration = motion.derivative(item.velocity)
        S += sympy.Rational(1, 2) * item.mass * (acceleration.T * acceleration)[0]
        if item.angular_velocity is not None:
            omega, I = item.angular_velocity, item.inertia
            alpha = motion.derivative(omega)
            S += sympy.Rational(1, 2) * (alpha.T * I * alpha)[0] + (alpha.T * omega.cross(I * omega))[0]
    return S


def derive_gibbs_appell(system: SystemDescription) -> Derivation:
    if system.kinetic_energy is not None:
        raise FormulationUnavailable(
            "the Gibbs function needs the particles' and bodies' accelerations, not only an energy expression"
        )
    names = system.latex_names
    latex = latex_printer(names)
    motion = speed_motion(system)
    u, ud = system.u, system.ud
    S = gibbs_function(system)
    forces = generalized_forces(system, motion, u)
    V = potential_energy(system)
    generalized = [F + C for F, C in zip(forces, conservative_share(system, V))]
    dS = [sympy.diff(S, a) for a in ud]
    M, forcing = linear_parts([d - g for d, g in zip(dS, generalized)], ud)
    steps = [Step("Potential energy", f"V = {latex(V)}")]
    steps += [
        Step(f"∂S/∂u̇ for {speed.name}", f"\\frac{{\\partial S}}{{\\partial {names[a]}}} = {latex(tidy(d))}")
        for speed, a, d in zip(system.speed_list, ud, dS)
    ]
    steps += [
        Step(f"Generalized force for {speed.name}", f"\\Pi_{{{speed.latex}}} = {latex(tidy(g))}")
        for speed, g in zip(system.speed_list, generalized)
    ]
    equations = linear_equations_latex(M, ud, forcing, latex, tidy=tidy)
    return Derivation(
        system_id=system.id,
        formulation="gibbs-appell",
        variables="q, u",
        mass_matrix=M,
        forcing=forcing,
        equations_latex=equations,
        steps=tuple(steps),
        recipe=recipe_through_speeds(system, Solve(M, forcing, tuple(ud))),
        latex_names=names,
    )
