"""A thin disk rolling without slip in redundant coordinates: the no-slip rows are nonholonomic multiplier rows.

Frame N: z up, floor z = 0 (the conventions of :mod:`app.physics.systems.ch09.rolling_disk`).
Coordinates ``q = (x, y, ψ, θ, φ)`` (m, m, rad, rad, rad): the contact point
(x, y), the heading ψ, the lean θ from the vertical and the spin φ, with
R_NB = Rz(ψ) Rx(θ) Ry(φ) (the disk's axis is body y). Touching the floor is
holonomic and built into the coordinates: the centre is at
(x + r sψ sθ, y − r cψ sθ, r cθ). Rolling without slip is not: the material
contact point's horizontal velocity

    A(q) q̇ = (ẋ − r cψ φ̇,  ẏ − r sψ φ̇) = 0        (m/s)

involves rates only and cannot be integrated to a relation among the
coordinates (the disk can reach any (x, y, ψ, φ) by rolling and turning), so
all five coordinates are kept and the two rows carry multipliers λ (N): the
floor's horizontal friction force on the disk. Lagrange's equations of the
unconstrained disk on the floor (kinetic energy of the centre plus the spin
about it, V = m g r cos θ) give the mass matrix and the forces below, derived
once with sympy (``tests/physics/systems/ch08`` re-derives them and compares):
with transverse moment a = m r²/4, axial moment c = m r²/2 about the centre,

    M = [[m, 0, m r sθ cψ, m r cθ sψ, 0],
         [0, m, m r sθ sψ, −m r cθ cψ, 0],
         [·, ·, a c²θ + (c + m r²) s²θ, 0, c sθ],
         [·, ·, 0, a + m r², 0],
         [·, ·, c sθ, 0, c]]       (symmetric)

and f collects gravity's m g r sθ on the lean and the velocity terms. The floor's
reaction does no work (the contact point does not move), so T + V is conserved.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.constrained.system import ConstrainedSystem
from app.physics.core.energy import EnergyParts
from app.physics.solvers.kernels import DYNAMICS_SIGNATURE, MULTIPLIER_CONSTRAINTS_SIGNATURE, kernel

#: Names of q (and, with "_rate", of v = q̇); the state of a run is (q, v).
COORDINATE_NAMES = ("x", "y", "heading", "lean", "spin")
X, Y, HEADING, LEAN, SPIN = range(5)
#: Indices of the parameter array p: mass (kg), radius (m), gravitational acceleration (m/s²).
MASS, RADIUS, GRAVITY = range(3)


@kernel(DYNAMICS_SIGNATURE)
def rolling_disk_dynamics(t, q, v, p, M_out, f_out):
    """M (5, 5) (kg, kg·m, kg·m²) and f (5,) (N, N·m) of the uniform thin disk touching the floor (no rolling rows)."""
    m, r, g = p[0], p[1], p[2]
    transverse, axial = 0.25 * m * r * r, 0.5 * m * r * r
    s_psi, c_psi = math.sin(q[2]), math.cos(q[2])
    s_th, c_th = math.sin(q[3]), math.cos(q[3])
    heading_rate, lean_rate, spin_rate = v[2], v[3], v[4]
    for i in range(5):
        for j in range(5):
            M_out[i, j] = 0.0
    M_out[0, 0] = m
    M_out[1, 1] = m
    M_out[0, 2] = M_out[2, 0] = m * r * s_th * c_psi
    M_out[0, 3] = M_out[3, 0] = m * r * c_th * s_psi
    M_out[1, 2] = M_out[2, 1] = m * r * s_th * s_psi
    M_out[1, 3] = M_out[3, 1] = -m * r * c_th * c_psi
    M_out[2, 2] = transverse * c_th * c_th + (axial + m * r * r) * s_th * s_th
    M_out[2, 4] = M_out[4, 2] = axial * s_th
    M_out[3, 3] = transverse + m * r * r
    M_out[4, 4] = axial
    squares = heading_rate * heading_rate + lean_rate * lean_rate
    cross = 2.0 * heading_rate * lean_rate * c_th
    f_out[0] = m * r * (s_psi * s_th * squares - c_psi * cross)
    f_out[1] = -m * r * (c_psi * s_th * squares + s_psi * cross)
    f_out[2] = lean_rate * c_th * (2.0 * (transverse - axial - m * r * r) * s_th * heading_rate - axial * spin_rate)
    f_out[3] = (
        (axial + m * r * r - transverse) * s_th * c_th * heading_rate * heading_rate
        + axial * c_th * spin_rate * heading_rate
        + m * g * r * s_th
    )
    f_out[4] = -axial * c_th * heading_rate * lean_rate


@kernel(MULTIPLIER_CONSTRAINTS_SIGNATURE)
def rolling_disk_constraints(q, v, p, g_out, C_out, c_out):
    """No holonomic rows; A (2, 5) with A v the contact point's horizontal velocity (m/s), and c = −Ȧ v (m/s²)."""
    r = p[1]
    s_psi, c_psi = math.sin(q[2]), math.cos(q[2])
    for i in range(2):
        for j in range(5):
            C_out[i, j] = 0.0
    C_out[0, 0] = 1.0
    C_out[0, 4] = -r * c_psi
    C_out[1, 1] = 1.0
    C_out[1, 4] = -r * s_psi
    turn_and_spin = r * v[2] * v[4]
    c_out[0] = -turn_and_spin * s_psi
    c_out[1] = turn_and_spin * c_psi


def parameter_array(params: Mapping[str, Any]) -> np.ndarray:
    """p = (mass_kg, radius_m, g_m_s2) as the kernels read it."""
    return np.array([float(params["mass_kg"]), float(params["radius_m"]), float(params["g_m_s2"])])


def rolling_disk_system(params: Mapping[str, Any]) -> ConstrainedSystem:
    """The disk as the DAE algorithms see it: 5 coordinates, 0 holonomic and 2 nonholonomic rows (3 degrees of freedom).

    Coordinate partitioning keeps the angles (ψ, θ, φ) independent: the rows solve for ẋ, ẏ.
    """
    return ConstrainedSystem(
        dynamics=rolling_disk_dynamics,
        constraints=rolling_disk_constraints,
        parameters=parameter_array(params),
        coordinate_names=COORDINATE_NAMES,
        n_holonomic=0,
        n_nonholonomic=2,
        independent=(HEADING, LEAN, SPIN),
    )


def rolling_state(
    *,
    radius_m: float,
    heading_rad: float,
    lean_rad: float,
    heading_rate_rad_s: float,
    lean_rate_rad_s: float,
    spin_rate_rad_s: float,
) -> np.ndarray:
    """A consistent state (q, v) (10,) at the origin: the contact point moves along the heading at r φ̇ (A v = 0
    exactly)."""
    return np.array(
        [
            0.0,
            0.0,
            heading_rad,
            lean_rad,
            0.0,
            radius_m * spin_rate_rad_s * math.cos(heading_rad),
            radius_m * spin_rate_rad_s * math.sin(heading_rad),
            heading_rate_rad_s,
            lean_rate_rad_s,
            spin_rate_rad_s,
        ]
    )


def energy_J(params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
    """T + V (J) along ``states`` (N, 10) = (q, v); V = m g z_centre = m g r cos θ."""
    return energy_parts(params, states).total_J


def energy_parts(params: Mapping[str, Any], states: np.ndarray) -> EnergyParts:
    """½ m v_G², ½ ω·I_G ω and m g r cos θ (J) along ``states`` (N, 10) = (q, v)."""
    states = np.atleast_2d(states)
    m, r, g = parameter_array(params)
    q, v = states[:, :5], states[:, 5:]
    heading, lean = q[:, HEADING], q[:, LEAN]
    x_rate, y_rate, heading_rate, lean_rate, spin_rate = v.T
    s_psi, c_psi, s_th, c_th = np.sin(heading), np.cos(heading), np.sin(lean), np.cos(lean)
    centre_velocity = np.stack(
        [
            x_rate + r * (c_psi * s_th * heading_rate + s_psi * c_th * lean_rate),
            y_rate + r * (s_psi * s_th * heading_rate - c_psi * c_th * lean_rate),
            -r * s_th * lean_rate,
        ],
        axis=1,
    )
    transverse, axial = 0.25 * m * r * r, 0.5 * m * r * r
    # Body rates in the lean frame Rz(ψ) Rx(θ) (the disk is symmetric about its axis): (θ̇, φ̇ + ψ̇ sθ, ψ̇ cθ).
    rotation = transverse * (lean_rate**2 + (heading_rate * c_th) ** 2) + axial * (spin_rate + heading_rate * s_th) ** 2
    return EnergyParts(
        m * g * r * c_th,
        translational_kinetic_J=0.5 * m * np.sum(centre_velocity**2, axis=1),
        rotational_kinetic_J=0.5 * rotation,
    )


def contact_velocity_m_s(params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
    """A(q) v (N, 2) (m/s): the material contact point's horizontal velocity along ``states`` (N, 10); zero when
    rolling."""
    states = np.atleast_2d(states)
    r = float(params["radius_m"])
    heading, spin_rate = states[:, HEADING], states[:, 5 + SPIN]
    return np.stack(
        [states[:, 5] - r * np.cos(heading) * spin_rate, states[:, 6] - r * np.sin(heading) * spin_rate], axis=1
    )
