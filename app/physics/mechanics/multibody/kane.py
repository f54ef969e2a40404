"""Kane's equations of a :class:`~.parts.MultibodySystem` with dependent speeds, solved numerically at run time.

With every speed u = q̇ (independent and dependent together), each body's
partial velocities are the columns of ∂v/∂u and ∂ω/∂u (its own components), and

    M(q) u̇ = f(q, u) + Aᵀ λ,    A(q) u̇ = b(q, u)

where M = Σ m VᵀV + WᵀIW, f = Σ Vᵀ(m g − m a_u) − Wᵀ(I α_u + ω × Iω) (a_u, α_u:
the accelerations with u̇ = 0; applied loads add V_Pᵀ F, Wᵀ τ and a spring's
−k (q − rest)), A u = 0 the velocity constraints and b = −Ȧu
their rate. Kane's equations with dependent speeds are these projected on the
independent speeds (Cᵀ M C u̇_i = Cᵀ(f − M Ċ u_i), C spanning A's null space);
the multipliers λ are the constraint forces they never show. Nothing is inverted
symbolically: the generated code assembles the (n + m) square system and solves
it by LU at each call, so the equations stay the size of the kinematics.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy

from app.physics.mechanics.multibody.kinematics import Kinematics, component_rate, cross, kinematics
from app.physics.mechanics.multibody.parts import Force, JointSpring, MultibodySystem


@dataclass(frozen=True)
class ConstrainedEquations:
    """M u̇ = f + Aᵀλ, A u̇ = b, the configuration constraints g(q) = 0, and the energies (J).

    A's rows: the configuration constraints' rates first (∂g/∂q, as u = q̇), then the nonholonomic rows."""

    system: MultibodySystem
    mass_matrix: sympy.Matrix
    forcing: sympy.Matrix
    constraint_matrix: sympy.Matrix
    constraint_rate: sympy.Matrix
    configuration_constraints: sympy.Matrix
    kinetic_energy: sympy.Expr
    potential_energy: sympy.Expr
    #: The kinetic energy's rotational part, ½ Σ ω·I_G ω (J); the rest is ½ Σ m v_G².
    rotational_kinetic_energy: sympy.Expr = sympy.Integer(0)
    #: The generalized forces of the applied loads that no potential energy accounts for (forces, couples, dampers),
    #: already in ``forcing``: Lagrange's route adds them to what it finds from T and V.
    applied_forcing: sympy.Matrix | None = None


def equations(system: MultibodySystem, frames: Kinematics | None = None) -> ConstrainedEquations:
    """The system's constrained equations of motion (Kane's, in the unreduced form above)."""
    frames = frames or kinematics(system)
    q, u = system.q, system.u
    n = len(q)
    mass_matrix = sympy.zeros(n, n)
    forcing = sympy.zeros(n, 1)
    kinetic = sympy.Integer(0)
    rotational = sympy.Integer(0)
    potential = sympy.Integer(0)
    for body in system.bodies:
        frame = frames.frames[body.name]
        omega = frame.angular_velocity
        velocity = frames.mass_centre_velocity(system, body.name)
        V, W = frames.mass_centre_partials(system, body.name), frame.angular_velocity_partials
        # Accelerations with u̇ = 0, own components, built joint by joint as the velocities are (no time derivative).
        acceleration_u = frames.mass_centre_acceleration(system, body.name)
        angular_acceleration_u = frame.angular_acceleration
        weight = -body.mass * system.gravity * frame.up
        spin_momentum = body.inertia * omega
        mass_matrix += body.mass * V.T * V + W.T * body.inertia * W
        forcing += V.T * (weight - body.mass * acceleration_u) - W.T * (
            body.inertia * angular_acceleration_u + cross(omega, spin_momentum)
        )
        kinetic += (body.mass * (velocity.T * velocity)[0] + (omega.T * spin_momentum)[0]) / 2
        rotational += (omega.T * spin_momentum)[0] / 2
        potential += body.mass * system.gravity * (frame.height + (frame.up.T * body.mass_centre)[0])
    applied, spring_forcing, spring_energy = applied_loads(system, frames)
    forcing += applied + spring_forcing
    potential += spring_energy
    configuration = sympy.Matrix(list(frames.configuration_constraints))
    # The velocity rows, holonomic first: ġ = (∂g/∂q) q̇ with q̇ = u, then the rolling rows.
    holonomic_rates = list(configuration.jacobian(q) * sympy.Matrix(u)) if configuration.shape[0] else []
    constraints = sympy.Matrix(holonomic_rates + list(frames.velocity_constraints))
    if len(frames.configuration_constraints) != len(system.dependent_coordinates):
        raise ValueError(
            f"{system.id}: {len(frames.configuration_constraints)} configuration constraints, but "
            f"{len(system.dependent_coordinates)} dependent coordinates named"
        )
    if constraints.shape[0] != len(system.dependent_speeds):
        raise ValueError(
            f"{system.id}: {constraints.shape[0]} velocity constraints, but {len(system.dependent_speeds)} dependent "
            "speeds named"
        )
    if constraints.shape[0]:
        A = constraints.jacobian(u)
        rate = -component_rate(constraints, q, u)
    else:
        A, rate = sympy.zeros(0, n), sympy.zeros(0, 1)
    return ConstrainedEquations(
        system,
        mass_matrix,
        forcing,
        A,
        rate,
        configuration,
        kinetic,
        potential,
        rotational,
        applied,
    )


def applied_loads(system: MultibodySystem, frames: Kinematics) -> tuple[sympy.Matrix, sympy.Matrix, sympy.Expr]:
    """The loads' generalized forces: those no potential accounts for (a force F at P: V_Pᵀ F; a couple τ: Wᵀ τ; a
    damper: −c q̇), the springs' −k (q − rest), and the springs' potential energy ½ k (q − rest)² (J)."""
    n = len(system.coordinates)
    applied, springs = sympy.zeros(n, 1), sympy.zeros(n, 1)
    energy = sympy.Integer(0)
    for load in system.loads:
        if isinstance(load, JointSpring):
            i = system.index(load.coordinate)
            stretch = system.q[i] - load.rest
            springs[i] -= load.stiffness * stretch
            applied[i] -= load.damping * system.u[i]
            energy += load.stiffness * stretch**2 / 2
            continue
        own = load.vector if load.follower else frames.rotation_to_ground(load.body).T * load.vector
        if isinstance(load, Force):
            applied += frames.point_velocity_partials(load.body, load.point).T * own
        else:
            applied += frames.frames[load.body].angular_velocity_partials.T * own
    return applied, springs, energy


def lagrange_form(derived: ConstrainedEquations) -> ConstrainedEquations:
    """The same system by Lagrange's equations with multipliers, from the energies alone:
    ∂²T/∂q̇² q̈ = ∂T/∂q − ∂V/∂q − (∂²T/∂q̇∂q) q̇ + Aᵀλ. An independent route to M and f (no partial velocities, no
    transport theorem): where both are right they agree to rounding."""
    system = derived.system
    q, u = system.q, system.u
    T, V = derived.kinetic_energy, derived.potential_energy
    momentum = sympy.Matrix([T]).jacobian(u).T
    mass_matrix = momentum.jacobian(u)
    forcing = sympy.Matrix([T - V]).jacobian(q).T - momentum.jacobian(q) * sympy.Matrix(u)
    if derived.applied_forcing is not None:
        forcing += derived.applied_forcing
    return ConstrainedEquations(
        system,
        mass_matrix,
        forcing,
        derived.constraint_matrix,
        derived.constraint_rate,
        derived.configuration_constraints,
        T,
        V,
        derived.rotational_kinetic_energy,
        derived.applied_forcing,
    )
