"""A rigid body turning about a fixed point, optionally under gravity (heavy top).

Frames: world +Z up, gravity ``−g Z``; body axes 1, 2, 3 are principal axes at
the fixed point, and the centre of mass lies on body +3 at ``cg_distance_m``.
State ``y = [q_w, q_x, q_y, q_z, ω1, ω2, ω3]``: ``q`` = ``q_world_body`` (wxyz)
and ``ω`` the body-frame angular velocity in rad/s.

Equations: ``q̇ = ½ q ⊗ (0, ω)`` and Euler's ``I ω̇ = (I ω) × ω + τ`` with the
gravity torque ``τ = l e3 × (−m g Z_body)``. A free (torque-free) body is the
case ``cg_distance_m = 0`` or ``mass_kg = 0``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from app.physics.bodies.inertia import centroidal_from_point, check_inertia_tensor, check_principal_inertia
from app.physics.math.rotations import rotation_matrix
from app.physics.solvers.kernels import PROJECT_SIGNATURE, RHS_SIGNATURE, TORQUE_SIGNATURE, kernel
from app.physics.solvers.system import OdeSystem

STATE_NAMES = ("q_w", "q_x", "q_y", "q_z", "omega1", "omega2", "omega3")


@dataclass(frozen=True)
class PivotedBody:
    """A rigid body turning about a fixed point (its pivot): principal moments about it (kg·m²), the gravity load."""

    inertia_pivot_kg_m2: tuple[float, float, float]
    mass_kg: float = 0.0
    cg_distance_m: float = 0.0
    g_m_s2: float = 9.807

    def __post_init__(self) -> None:
        for name in ("mass_kg", "cg_distance_m", "g_m_s2"):
            value = getattr(self, name)
            if not math.isfinite(value) or value < 0.0:
                raise ValueError(f"{name} must be a finite number ≥ 0 (got {value!r})")
        check_principal_inertia(self.inertia_pivot_kg_m2, about="the fixed point")
        # Parallel-axis theorem back to the centre of mass (on body 3): that body must exist too.
        if self.mass_kg * self.cg_distance_m > 0.0:
            inertia_cm = centroidal_from_point(
                np.diag(self.inertia_pivot_kg_m2), self.mass_kg, np.array([0.0, 0.0, self.cg_distance_m])
            )
            check_inertia_tensor(inertia_cm, about="the centre of mass")

    @property
    def gravity_moment_N_m(self) -> float:
        """``m g l``: the largest gravity torque about the pivot (N·m), when the body is horizontal."""
        return self.mass_kg * self.g_m_s2 * self.cg_distance_m

    @property
    def axisymmetric(self) -> bool:
        I1, I2, _ = self.inertia_pivot_kg_m2
        return I1 == I2

    def kernel_parameters(self) -> np.ndarray:
        """``p = [I1, I2, I3, m g l]`` for the kernels."""
        return np.array([*self.inertia_pivot_kg_m2, self.gravity_moment_N_m], dtype=float)

    def system(self) -> OdeSystem:
        return OdeSystem(
            rhs=rigid_body_rhs,
            parameters=self.kernel_parameters(),
            state_names=STATE_NAMES,
            project=normalise_quaternion,
            torque=gravity_torque,
        )

    # -- invariants ---------------------------------------------------------
    def energy_J(self, states: np.ndarray) -> np.ndarray:
        """Kinetic + gravitational energy (J, zero potential at the pivot height) of states (..., 7)."""
        states = np.asarray(states, dtype=float)
        inertia = np.asarray(self.inertia_pivot_kg_m2)
        kinetic = 0.5 * np.sum(inertia * states[..., 4:7] ** 2, axis=-1)
        q = states[..., 0:4] / np.linalg.norm(states[..., 0:4], axis=-1, keepdims=True)
        axis_z = 1.0 - 2.0 * (q[..., 1] ** 2 + q[..., 2] ** 2)  # world Z component of body 3
        return kinetic + self.gravity_moment_N_m * axis_z

    def angular_momentum_world(self, states: np.ndarray) -> np.ndarray:
        """Angular momentum about the fixed point (kg·m²/s, world frame), shape (..., 3)."""
        states = np.asarray(states, dtype=float)
        momentum_body = np.asarray(self.inertia_pivot_kg_m2) * states[..., 4:7]
        return np.einsum("...ij,...j->...i", rotation_matrix(states[..., 0:4]), momentum_body)

    def invariants(self, states: np.ndarray) -> dict[str, np.ndarray]:
        """The quantities this body conserves, evaluated on states (..., 7).

        Always: ``energy`` (J), ``angular_momentum_z`` (kg·m²/s; gravity has no
        moment about the vertical through the pivot) and ``quaternion_norm_error``
        (|q| − 1, zero for an exact attitude). Torque-free: ``angular_momentum``
        (|L|). Axisymmetric: ``spin`` (ω3, rad/s).
        """
        momentum = self.angular_momentum_world(states)
        out = {
            "energy": self.energy_J(states),
            "angular_momentum_z": momentum[..., 2],
            "quaternion_norm_error": np.linalg.norm(np.asarray(states)[..., 0:4], axis=-1) - 1.0,
        }
        if self.gravity_moment_N_m == 0.0:
            out["angular_momentum"] = np.linalg.norm(momentum, axis=-1)
        if self.axisymmetric:
            out["spin"] = np.asarray(states)[..., 6].copy()
        return out

    def fastest_rate_rad_s(self, state: np.ndarray) -> float:
        """Bound on how fast anything in the motion turns (rad/s), for choosing steps.

        Energy bounds the angular velocity for all time: ``½ I_min |ω|² ≤ E − V_min``.
        """
        energy = float(self.energy_J(state))
        kinetic_max = energy + self.gravity_moment_N_m
        rate = math.sqrt(max(2.0 * kinetic_max / min(self.inertia_pivot_kg_m2), 0.0))
        pendulum = math.sqrt(self.gravity_moment_N_m / max(self.inertia_pivot_kg_m2[:2]))
        return max(rate, pendulum)


@kernel(RHS_SIGNATURE)
def rigid_body_rhs(t, y, p, dydt):
    """``[q̇, ω̇]`` for a rigid body about a fixed point under gravity (see module docstring)."""
    w, x, yq, z = y[0], y[1], y[2], y[3]
    o1, o2, o3 = y[4], y[5], y[6]
    I1, I2, I3, mgl = p[0], p[1], p[2], p[3]
    dydt[0] = 0.5 * (-x * o1 - yq * o2 - z * o3)
    dydt[1] = 0.5 * (w * o1 + yq * o3 - z * o2)
    dydt[2] = 0.5 * (w * o2 - x * o3 + z * o1)
    dydt[3] = 0.5 * (w * o3 + x * o2 - yq * o1)
    # World Z in body components (third row of R), normalised by |q|².
    inv_norm2 = 1.0 / (w * w + x * x + yq * yq + z * z)
    zb1 = 2.0 * (x * z - w * yq) * inv_norm2
    zb2 = 2.0 * (yq * z + w * x) * inv_norm2
    dydt[4] = ((I2 - I3) * o2 * o3 + mgl * zb2) / I1
    dydt[5] = ((I3 - I1) * o3 * o1 - mgl * zb1) / I2
    dydt[6] = (I1 - I2) * o1 * o2 / I3


@kernel(TORQUE_SIGNATURE)
def gravity_torque(q, p, torque_body):
    """Gravity torque about the pivot in body components (N·m) for attitude ``q``."""
    w, x, y, z = q[0], q[1], q[2], q[3]
    mgl = p[3]
    torque_body[0] = mgl * 2.0 * (y * z + w * x)
    torque_body[1] = -mgl * 2.0 * (x * z - w * y)
    torque_body[2] = 0.0


@kernel(PROJECT_SIGNATURE)
def normalise_quaternion(y, p):
    """Project the attitude back onto |q| = 1."""
    norm = math.sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2] + y[3] * y[3])
    for i in range(4):
        y[i] /= norm
