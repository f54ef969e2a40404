"""A tiny nonholonomic test system: the knife edge (skate) on a level plane, no forces.

Coordinates q = (x, y, φ) (m, m, rad): contact point = centre of mass, heading φ.
One nonholonomic row, no sideways slip: A v = −sin φ ẋ + cos φ ẏ = 0 (m/s), so
c = −Ȧ v = φ̇ (cos φ ẋ + sin φ ẏ). M = diag(m, m, I). Free motion: φ̇ = ω and the
forward speed u stay constant and the contact draws a circle of radius u/ω:
x = x₀ + (u/ω)(sin φ − sin φ₀), y = y₀ − (u/ω)(cos φ − cos φ₀), φ = φ₀ + ω t.
Parameter array p = (m, I).
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.constrained.system import ConstrainedSystem
from app.physics.solvers.kernels import DYNAMICS_SIGNATURE, MULTIPLIER_CONSTRAINTS_SIGNATURE, kernel


@kernel(DYNAMICS_SIGNATURE)
def knife_edge_dynamics(t, q, v, p, M_out, f_out):
    for i in range(3):
        for j in range(3):
            M_out[i, j] = 0.0
        f_out[i] = 0.0
    M_out[0, 0] = p[0]
    M_out[1, 1] = p[0]
    M_out[2, 2] = p[1]


@kernel(MULTIPLIER_CONSTRAINTS_SIGNATURE)
def knife_edge_constraint(q, v, p, g_out, C_out, c_out):
    s, c = math.sin(q[2]), math.cos(q[2])
    C_out[0, 0] = -s
    C_out[0, 1] = c
    C_out[0, 2] = 0.0
    c_out[0] = v[2] * (c * v[0] + s * v[1])


def knife_edge(mass_kg: float = 2.0, inertia_kg_m2: float = 0.3) -> ConstrainedSystem:
    return ConstrainedSystem(
        dynamics=knife_edge_dynamics, constraints=knife_edge_constraint, parameters=np.array([mass_kg, inertia_kg_m2]),
        coordinate_names=("x", "y", "phi"), n_holonomic=0, n_nonholonomic=1,
    )  # fmt: skip


def knife_edge_exact(speed_m_s: float, rate_rad_s: float, phi0_rad: float, t_s: np.ndarray) -> np.ndarray:
    """(N, 6) exact (x, y, φ, ẋ, ẏ, φ̇) from the origin with forward speed u and turn rate ω."""
    phi = phi0_rad + rate_rad_s * t_s
    radius = speed_m_s / rate_rad_s
    x = radius * (np.sin(phi) - math.sin(phi0_rad))
    y = -radius * (np.cos(phi) - math.cos(phi0_rad))
    return np.stack([x, y, phi, speed_m_s * np.cos(phi), speed_m_s * np.sin(phi), np.full_like(phi, rate_rad_s)], axis=1)
