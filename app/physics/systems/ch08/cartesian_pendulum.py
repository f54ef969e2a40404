"""The planar pendulum in Cartesian coordinates: the classic index-3 test problem of the DAE algorithms.

Frame: the pendulum's plane, x horizontal, y up, the pivot at the origin; the bob
(mass m, kg) at ``q = (x, y)`` (m) on a massless rod of length L (m), gravity g (m/s²)
along −y. Coordinates q (2,), rates v = (ẋ, ẏ) (2,), one holonomic constraint

    g(q) = (L² − x² − y²) / 2 = 0      (m²),   C = ∂g/∂q = (−x, −y),   c = −Ċ v = ẋ² + ẏ²,

so ``M v̇ = f + Cᵀλ`` reads ``m ẍ = −λ x``, ``m ÿ = −m g − λ y``: the rod pulls the bob
with the force −λ (x, y). The multiplier λ (N/m) is the constraint force per unit length,
positive when the rod pulls the bob toward the pivot (tension T = λ L, N).
Parameter array ``p = (m, L, g)``.

The angle from the downward vertical θ (x = L sin θ, y = −L cos θ) obeys the simple
pendulum's θ̈ = −(g/L) sin θ, whose libration has the closed form
sin(θ/2) = k sn(ω t + u₀ | k²), ω = √(g/L) (:func:`exact_states`).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.special import ellipj, ellipk, ellipkinc

from app.physics.constrained.system import ConstrainedSystem
from app.physics.solvers.kernels import DYNAMICS_SIGNATURE, MULTIPLIER_CONSTRAINTS_SIGNATURE, kernel

MASS, LENGTH, GRAVITY = range(3)


@kernel(DYNAMICS_SIGNATURE)
def pendulum_dynamics(t, q, v, p, M_out, f_out):
    """M = m I (kg), f = (0, −m g) (N)."""
    M_out[0, 0] = p[MASS]
    M_out[0, 1] = 0.0
    M_out[1, 0] = 0.0
    M_out[1, 1] = p[MASS]
    f_out[0] = 0.0
    f_out[1] = -p[MASS] * p[GRAVITY]


@kernel(MULTIPLIER_CONSTRAINTS_SIGNATURE)
def pendulum_constraint(q, v, p, g_out, C_out, c_out):
    """g = (L² − x² − y²)/2 (m²), C = (−x, −y) (m), c = ẋ² + ẏ² (m²/s²)."""
    g_out[0] = 0.5 * (p[LENGTH] * p[LENGTH] - q[0] * q[0] - q[1] * q[1])
    C_out[0, 0] = -q[0]
    C_out[0, 1] = -q[1]
    c_out[0] = v[0] * v[0] + v[1] * v[1]


def pendulum_system(mass_kg: float, length_m: float, g_m_s2: float) -> ConstrainedSystem:
    """The Cartesian pendulum as a :class:`ConstrainedSystem` (coordinates x, y; one holonomic row)."""
    return ConstrainedSystem(
        dynamics=pendulum_dynamics,
        constraints=pendulum_constraint,
        parameters=np.array([mass_kg, length_m, g_m_s2], dtype=float),
        coordinate_names=("x", "y"),
        n_holonomic=1,
    )


def angle_and_rate(length_m: float, states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """θ (rad, from the downward vertical) and θ̇ (rad/s) of ``(x, y, ẋ, ẏ)`` rows (N, 4)."""
    states = np.atleast_2d(states)
    x, y, vx, vy = states.T
    return np.arctan2(x, -y), (x * vy - y * vx) / (length_m * length_m)


def cartesian_states(length_m: float, theta_rad: np.ndarray, theta_rate_rad_s: np.ndarray) -> np.ndarray:
    """``(x, y, ẋ, ẏ)`` rows (N, 4) of the angle θ (rad) and rate θ̇ (rad/s) arrays (N,)."""
    s, c = np.sin(theta_rad), np.cos(theta_rad)
    return np.stack(
        [length_m * s, -length_m * c, length_m * c * theta_rate_rad_s, length_m * s * theta_rate_rad_s], axis=-1
    )


def exact_states(length_m: float, g_m_s2: float, state0: np.ndarray, t_s: np.ndarray) -> np.ndarray:
    """The exact motion ``(x, y, ẋ, ẏ)`` (N, 4) at times ``t_s`` (N,) s from a consistent start ``state0`` (4,).

    Libration only: ValueError when the bob goes over the top (k ≥ 1) or g = 0.
    With k = √(sin²(θ₀/2) + θ̇₀²/(4ω²)): sin(θ/2) = k sn(u), cos(θ/2) = dn(u), θ̇ = 2kω cn(u),
    u = ω t + u₀ and sn(u₀) = sin(θ₀/2)/k with cn(u₀) of the sign of θ̇₀.
    """
    if not g_m_s2 > 0.0:
        raise ValueError("g_m_s2: the closed form needs gravity (g > 0)")
    omega = math.sqrt(g_m_s2 / length_m)
    theta0, rate0 = (float(a[0]) for a in angle_and_rate(length_m, np.asarray(state0, dtype=float)[None, :]))
    k = math.sqrt(math.sin(0.5 * theta0) ** 2 + (rate0 / (2.0 * omega)) ** 2)
    if k >= 1.0:
        raise ValueError("the bob goes over the top (k ≥ 1): the libration closed form does not apply")
    t = np.asarray(t_s, dtype=float)
    if k == 0.0:
        return cartesian_states(length_m, np.zeros_like(t), np.zeros_like(t))
    m = k * k
    phase = math.asin(min(max(math.sin(0.5 * theta0) / k, -1.0), 1.0))
    u0 = float(ellipkinc(phase, m))
    if rate0 < 0.0:
        u0 = 2.0 * float(ellipk(m)) - u0
    sn, cn, dn, _ = ellipj(omega * t + u0, m)
    theta = 2.0 * np.arctan2(k * sn, dn)
    return cartesian_states(length_m, theta, 2.0 * k * omega * cn)
