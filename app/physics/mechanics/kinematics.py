"""Velocities, accelerations and energies of a described system, as sympy expressions.

Two ways of writing a motion share this module:

* in coordinates and their rates (q, q̇, q̈, t): what Lagrange's, Hamilton's
  and Routh's equations use;
* in coordinates and generalized speeds (q, u, u̇, t), with q̇ = q̇(q, u, t):
  what Kane's and the Gibbs–Appell equations and Newton–Euler use.

For a holonomic system u = q̇ (the same symbols), so both coincide.
Angular velocities and accelerations are in body components (rad/s, rad/s²);
positions, velocities and accelerations in N components (m, m/s, m/s²).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import sympy

from app.physics.mechanics.algebra import tidy
from app.physics.mechanics.description import TIME, RigidBody, Spring, SystemDescription


def simple_rotation(axis: str, angle: sympy.Expr) -> sympy.Matrix:
    """R such that v_parent = R v_child for a rotation by ``angle`` (rad) about ``axis``."""
    c, s = sympy.cos(angle), sympy.sin(angle)
    if axis == "x":
        return sympy.Matrix([[1, 0, 0], [0, c, -s], [0, s, c]])
    if axis == "y":
        return sympy.Matrix([[c, 0, s], [0, 1, 0], [-s, 0, c]])
    if axis == "z":
        return sympy.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    raise ValueError(f"rotation axis must be 'x', 'y' or 'z' (got {axis!r})")


_UNIT = {"x": sympy.Matrix([1, 0, 0]), "y": sympy.Matrix([0, 1, 0]), "z": sympy.Matrix([0, 0, 1])}


def body_rotation(body: RigidBody) -> sympy.Matrix:
    """R_NB: body components → N components."""
    rotation = sympy.eye(3)
    for axis, angle in body.rotations:
        rotation = rotation * simple_rotation(axis, angle)
    return rotation


@dataclass(frozen=True)
class Motion:
    """How to differentiate in time: the position-level variables, their rates and the next derivatives.

    ``rates[i]`` is d(variables[i])/dt as an expression; ``velocity_variables``
    are the symbols whose own derivatives are ``accelerations``.
    """

    variables: Sequence[sympy.Symbol]
    rates: Sequence[sympy.Expr]
    velocity_variables: Sequence[sympy.Symbol]
    accelerations: Sequence[sympy.Symbol]

    def derivative(self, expr: sympy.Expr | sympy.Matrix) -> sympy.Expr | sympy.Matrix:
        """d/dt of an expression in (variables, velocity_variables, t)."""
        if isinstance(expr, sympy.MatrixBase):
            return expr.applyfunc(self.derivative)
        result = sympy.diff(expr, TIME)
        for variable, rate in zip(self.variables, self.rates):
            result += sympy.diff(expr, variable) * rate
        for velocity, acceleration in zip(self.velocity_variables, self.accelerations):
            result += sympy.diff(expr, velocity) * acceleration
        return result


def coordinate_motion(system: SystemDescription) -> Motion:
    """Differentiation in (q, q̇, q̈)."""
    return Motion(system.q, system.qd, system.qd, system.qdd)


def speed_motion(system: SystemDescription) -> Motion:
    """Differentiation in (q, u, u̇), with q̇ = q̇(q, u, t)."""
    return Motion(system.q, system.rates_in_speeds, system.u, system.ud)


def angular_velocity_body(body: RigidBody, motion: Motion) -> sympy.Matrix:
    """ω of the body in N, in body components: Σ_k (R_{k+1} ⋯ R_n)ᵀ e_k ȧ_k (rad/s)."""
    omega = sympy.zeros(3, 1)
    later = sympy.eye(3)
    for axis, angle in reversed(body.rotations):
        omega += later.T * _UNIT[axis] * motion.derivative(angle)
        later = simple_rotation(axis, angle) * later
    return omega


@dataclass(frozen=True)
class BodyMotion:
    """One particle or body's velocity (N) and, for a body, angular velocity (body components), in one Motion."""

    name: str
    mass: sympy.Expr
    velocity: sympy.Matrix
    angular_velocity: sympy.Matrix | None = None
    inertia: sympy.Matrix | None = None
    rotation: sympy.Matrix | None = None


def body_motions(system: SystemDescription, motion: Motion) -> list[BodyMotion]:
    """Velocities of every particle and body, written with ``motion``'s variables."""
    found = [BodyMotion(p.name, p.mass, motion.derivative(p.position)) for p in system.particles]
    for body in system.bodies:
        found.append(
            BodyMotion(
                body.name,
                body.mass,
                motion.derivative(body.mass_centre),
                tidy(angular_velocity_body(body, motion)),
                body.inertia,
                body_rotation(body),
            )
        )
    return found


def inertia_torque_body(item: BodyMotion, motion: Motion) -> sympy.Matrix:
    """I_G α + ω × I_G ω in body components (N·m): what a body's moment about its mass centre must supply."""
    omega, inertia = item.angular_velocity, item.inertia
    if omega is None or inertia is None:
        raise ValueError(f"{item.name} is a particle: it has no angular velocity or inertia")
    return inertia * motion.derivative(omega) + omega.cross(inertia * omega)


def kinetic_energy(system: SystemDescription, motion: Motion) -> sympy.Expr:
    """T (J): ½ m v·v for particles; ½ m v_G·v_G + ½ ωᵀ I_G ω for bodies."""
    if system.kinetic_energy is not None:
        return system.kinetic_energy
    energy = sympy.Integer(0)
    for item in body_motions(system, motion):
        energy += sympy.Rational(1, 2) * item.mass * (item.velocity.T * item.velocity)[0]
        if item.angular_velocity is not None:
            energy += sympy.Rational(1, 2) * (item.angular_velocity.T * item.inertia * item.angular_velocity)[0]
    return tidy(energy)


def potential_energy(system: SystemDescription, *, tidied: bool = True) -> sympy.Expr:
    """V (J): gravity −Σ m g·r, springs ½ k (stretch)², plus the extra term.

    ``tidied=False`` skips the symbolic tidy-up (for numerics on typed input, whose expansion is unbounded).
    """
    energy = system.extra_potential
    if system.gravity is not None:
        for p in system.particles:
            energy -= p.mass * (system.gravity.T * p.position)[0]
        for b in system.bodies:
            energy -= b.mass * (system.gravity.T * b.mass_centre)[0]
    for spring in system.springs:
        energy += sympy.Rational(1, 2) * spring.stiffness * spring_stretch(spring) ** 2
    return tidy(energy) if tidied else energy


def spring_stretch(spring: Spring) -> sympy.Expr:
    """The spring's stretch (m): signed along its axis, or length minus free length."""
    d = spring.end_b - spring.end_a
    if spring.axis is not None:
        return (spring.axis.T * d)[0] - spring.free_length
    return sympy.sqrt((d.T * d)[0]) - spring.free_length


def spring_force_on_b(spring: Spring) -> sympy.Matrix:
    """The spring's force on its end b (N, N components); its end a feels the opposite."""
    d = spring.end_b - spring.end_a
    direction = spring.axis if spring.axis is not None else d / sympy.sqrt((d.T * d)[0])
    return -spring.stiffness * spring_stretch(spring) * direction


def generalized_forces(
    system: SystemDescription, motion: Motion, velocities: Sequence[sympy.Symbol]
) -> list[sympy.Expr]:
    """Σ F·∂v/∂w for each of ``velocities`` (q̇ or u): the applied non-conservative forces' share (N or N·m)."""
    forces = []
    for w in velocities:
        total = sympy.Integer(0)
        for applied in system.forces:
            point_velocity = motion.derivative(applied.point)
            total += (applied.force.T * point_velocity.diff(w))[0]
        forces.append(total)
    return forces


def jacobian_of(expressions: Sequence[sympy.Expr], variables: Sequence[sympy.Symbol]) -> sympy.Matrix:
    return sympy.Matrix(list(expressions)).jacobian(list(variables))
