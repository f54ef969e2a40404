"""Planar linkages in absolute coordinates: every link (x_G, y_G, φ), every joint its own constraint rows.

Frame (planar, m): x to the right, y up, gravity ``g`` along −y; angles (rad)
counterclockwise from +x. Body ``i`` has coordinates ``q[3i:3i+3] = (x_G, y_G, φ)``
of its centre of mass G and the direction of its axis. A point of the body is
named by its distance ``s`` (m) along that axis from G, so it sits at
``r(s) = (x_G + s cos φ, y_G + s sin φ)``.

The mass matrix is constant and diagonal, ``M = diag(m, m, I_G)`` per body; the
generalized forces are gravity ``(0, −m g, 0)`` per body plus a constant driving
torque τ (N·m, counterclockwise) on the driven body's φ. Four joint kinds give
the constraint rows (all holonomic), each with its multiplier's meaning in
``M v̇ = f + Cᵀλ``:

* ground pin — ``r_i(s_i) − P = 0`` (2 rows): λ is the ground's force on body i at the pin (N);
* pin — ``r_i(s_i) − r_j(s_j) = 0`` (2 rows): λ is body j's force on body i (N);
* guide — ``n·(r_i(s_i) − P) = 0`` with ``n = (−sin α, cos α)`` normal to a line
  through P at angle α (1 row): λ is the guide's force on body i along n (N);
* fixed angle — ``φ_i − α = 0`` (1 row): λ is the guide's moment on body i (N·m).

Differentiated twice, a point row reads ``C v̇ = c`` with ``c = −Ċ v``; for
the point at ``s`` on body i that is ``s φ̇² (cos φ, sin φ)`` (the point's
centripetal acceleration relative to G, moved to the right side).

:func:`linkage_dynamics` and :func:`linkage_constraints` are the two kernels of
:class:`~app.physics.constrained.system.ConstrainedSystem`; the linkage's bodies and
joints travel as data in the parameter array (:meth:`PlanarLinkage.kernel_parameters`),
so one pair of compiled kernels serves every mechanism. The slider-crank and the
four-bar are assembled from these pieces in :mod:`.slider_crank_dae` and
:mod:`.massive_four_bar`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba.extending import register_jitable

from app.physics.constrained.system import ConstrainedSystem
from app.physics.solvers.kernels import DYNAMICS_SIGNATURE, MULTIPLIER_CONSTRAINTS_SIGNATURE, kernel

GROUND_PIN, PIN, GUIDE, FIXED_ANGLE = 0, 1, 2, 3
JOINT_KINDS = ("ground pin", "pin", "guide", "fixed angle")
#: Constraint rows per joint kind.
JOINT_ROWS = (2, 2, 1, 1)
#: Floats per joint in the parameter array: kind, body i, s_i, body j, s_j, P_x, P_y, α.
JOINT_RECORD = 8
#: p = [g, τ, driven body, n_bodies, diag(M) (3 n_bodies), n_joints, joint records ...]
_HEADER = 4


@dataclass(frozen=True)
class RigidLink:
    """One moving body: its name, mass (kg), moment of inertia about G normal to the plane (kg·m²) and length (m)."""

    name: str
    mass_kg: float
    inertia_kg_m2: float
    length_m: float

    def __post_init__(self) -> None:
        if not (self.mass_kg > 0.0 and self.inertia_kg_m2 > 0.0 and self.length_m > 0.0):
            raise ValueError(f"the {self.name} needs a positive mass, inertia and length")

    @classmethod
    def slender_bar(cls, name: str, mass_kg: float, length_m: float) -> RigidLink:
        """A uniform slender bar: ``I_G = m l²/12``."""
        return cls(name, mass_kg, mass_kg * length_m**2 / 12.0, length_m)


@dataclass(frozen=True)
class Joint:
    """One joint (see the module docstring): ``kind`` one of :data:`JOINT_KINDS`; bodies by index, points by
    their distance along the body's axis from G (m); ``ground_m`` the fixed point P (m); ``angle_rad`` α."""

    name: str
    kind: str
    body: int
    at_m: float = 0.0
    other: int = -1
    other_at_m: float = 0.0
    ground_m: tuple[float, float] = (0.0, 0.0)
    angle_rad: float = 0.0

    @property
    def rows(self) -> int:
        return JOINT_ROWS[JOINT_KINDS.index(self.kind)]

    def record(self) -> list[float]:
        return [
            float(JOINT_KINDS.index(self.kind)),
            float(self.body),
            self.at_m,
            float(self.other),
            self.other_at_m,
            self.ground_m[0],
            self.ground_m[1],
            self.angle_rad,
        ]


def ground_pin(name: str, body: int, at_m: float, ground_m: tuple[float, float]) -> Joint:
    """Body ``body``'s point at ``at_m`` pinned to the fixed point ``ground_m``; λ = ground's force on the body (N)."""
    return Joint(name, "ground pin", body, at_m, ground_m=ground_m)


def pin(name: str, body: int, at_m: float, other: int, other_at_m: float) -> Joint:
    """Two bodies pinned at a common point; λ = the force of ``other`` on ``body`` (N)."""
    return Joint(name, "pin", body, at_m, other, other_at_m)


def guide(name: str, body: int, at_m: float, through_m: tuple[float, float], angle_rad: float) -> Joint:
    """Body's point kept on the fixed line through ``through_m`` at ``angle_rad``; λ = guide force along the normal
    (N)."""
    return Joint(name, "guide", body, at_m, ground_m=through_m, angle_rad=angle_rad)


def fixed_angle(name: str, body: int, angle_rad: float) -> Joint:
    """Body kept at the angle ``angle_rad``; λ = the moment holding it (N·m)."""
    return Joint(name, "fixed angle", body, angle_rad=angle_rad)


@register_jitable
def _add_point_row(q, v, body, s, sign, nx, ny, row, g_out, C_out, c_out):
    """Add ``sign · n·r_body(s)`` to holonomic row ``row`` with its Jacobian and ``c = −Ċ v`` parts."""
    k = 3 * body
    cos_phi, sin_phi = math.cos(q[k + 2]), math.sin(q[k + 2])
    rate = v[k + 2]
    g_out[row] += sign * (nx * (q[k] + s * cos_phi) + ny * (q[k + 1] + s * sin_phi))
    C_out[row, k] += sign * nx
    C_out[row, k + 1] += sign * ny
    C_out[row, k + 2] += sign * s * (ny * cos_phi - nx * sin_phi)
    c_out[row] += sign * s * rate * rate * (nx * cos_phi + ny * sin_phi)


@kernel(DYNAMICS_SIGNATURE)
def linkage_dynamics(t, q, v, p, M_out, f_out):
    """``M`` = diag(m, m, I_G) per body (kg, kg·m²); ``f`` = gravity (N) plus τ (N·m) on the driven body's φ."""
    gravity, torque, driven, n_bodies = p[0], p[1], int(p[2]), int(p[3])
    n = 3 * n_bodies
    for i in range(n):
        f_out[i] = 0.0
        for j in range(n):
            M_out[i, j] = 0.0
        M_out[i, i] = p[_HEADER + i]
    for b in range(n_bodies):
        f_out[3 * b + 1] = -p[_HEADER + 3 * b] * gravity
    f_out[3 * driven + 2] += torque


@kernel(MULTIPLIER_CONSTRAINTS_SIGNATURE)
def linkage_constraints(q, v, p, g_out, C_out, c_out):
    """Rows of every joint in order (module docstring): ``g`` (m), ``C`` (m, 3 n_bodies), ``c = −Ċ v`` (m/s²,
    rad/s²)."""
    n_bodies = int(p[3])
    start = _HEADER + 3 * n_bodies
    n_joints = int(p[start])
    for i in range(g_out.shape[0]):
        g_out[i] = 0.0
        c_out[i] = 0.0
        for j in range(C_out.shape[1]):
            C_out[i, j] = 0.0
    row = 0
    for joint in range(n_joints):
        r = start + 1 + JOINT_RECORD * joint
        kind, body, s, other, s_other = int(p[r]), int(p[r + 1]), p[r + 2], int(p[r + 3]), p[r + 4]
        px, py, angle = p[r + 5], p[r + 6], p[r + 7]
        if kind == GROUND_PIN or kind == PIN:
            for axis in range(2):
                nx, ny = 1.0 - axis, float(axis)
                _add_point_row(q, v, body, s, 1.0, nx, ny, row + axis, g_out, C_out, c_out)
                if kind == PIN:
                    _add_point_row(q, v, other, s_other, -1.0, nx, ny, row + axis, g_out, C_out, c_out)
                else:
                    g_out[row + axis] -= nx * px + ny * py
            row += 2
        elif kind == GUIDE:
            nx, ny = -math.sin(angle), math.cos(angle)
            _add_point_row(q, v, body, s, 1.0, nx, ny, row, g_out, C_out, c_out)
            g_out[row] -= nx * px + ny * py
            row += 1
        else:
            g_out[row] = q[3 * body + 2] - angle
            C_out[row, 3 * body + 2] = 1.0
            row += 1


@dataclass(frozen=True)
class PlanarLinkage:
    """Moving links, the joints between them and the ground, gravity (m/s², along −y) and the torque (N·m)
    on the driven link's φ (counterclockwise positive)."""

    links: tuple[RigidLink, ...]
    joints: tuple[Joint, ...]
    g_m_s2: float
    drive_torque_N_m: float
    driven: int = 0

    def __post_init__(self) -> None:
        n = len(self.links)
        for joint in self.joints:
            bodies = (joint.body, joint.other) if joint.kind == "pin" else (joint.body,)
            if any(not 0 <= b < n for b in bodies):
                raise ValueError(f"joint {joint.name} names a body outside 0…{n - 1}")
        if not 0 <= self.driven < n:
            raise ValueError(f"the driven link must be one of the {n} links")

    @property
    def coordinate_names(self) -> tuple[str, ...]:
        return tuple(f"{link.name}_{c}" for link in self.links for c in ("x_m", "y_m", "angle_rad"))

    @property
    def n_constraints(self) -> int:
        return sum(joint.rows for joint in self.joints)

    @property
    def mass_diagonal(self) -> np.ndarray:
        """diag(M) (3 n_bodies,): m, m, I_G per body (kg, kg, kg·m²)."""
        return np.array([value for link in self.links for value in (link.mass_kg, link.mass_kg, link.inertia_kg_m2)])

    def kernel_parameters(self) -> np.ndarray:
        """The flat array ``p`` both kernels read (layout in :data:`_HEADER`'s comment)."""
        header = [self.g_m_s2, self.drive_torque_N_m, float(self.driven), float(len(self.links))]
        records = [value for joint in self.joints for value in joint.record()]
        return np.array(header + list(self.mass_diagonal) + [float(len(self.joints))] + records)

    def system(self, *, independent: tuple[int, ...] | None = None) -> ConstrainedSystem:
        return ConstrainedSystem(
            dynamics=linkage_dynamics,
            constraints=linkage_constraints,
            parameters=self.kernel_parameters(),
            coordinate_names=self.coordinate_names,
            n_holonomic=self.n_constraints,
            independent=independent,
        )

    def multiplier_rows(self) -> dict[str, slice]:
        """Each joint's rows in ``λ`` (and in ``g``, ``C``), by joint name."""
        rows, start = {}, 0
        for joint in self.joints:
            rows[joint.name] = slice(start, start + joint.rows)
            start += joint.rows
        return rows

    def kinetic_energy_J(self, v: np.ndarray) -> np.ndarray:
        """T = ½ vᵀ M v (J) for rates ``v`` (..., 3 n_bodies)."""
        return 0.5 * np.sum(self.mass_diagonal * np.asarray(v) ** 2, axis=-1)

    def potential_energy_J(self, q: np.ndarray) -> np.ndarray:
        """V = g Σ m y_G (J), zero at y = 0, for coordinates ``q`` (..., 3 n_bodies)."""
        masses = np.array([link.mass_kg for link in self.links])
        return self.g_m_s2 * np.sum(masses * np.asarray(q)[..., 1::3], axis=-1)

    def torque_work_J(self, q: np.ndarray, q0: np.ndarray) -> np.ndarray:
        """W = τ (φ − φ₀) (J) of the constant torque on the driven link since ``q0``, for ``q`` (..., 3 n_bodies)."""
        k = 3 * self.driven + 2
        return self.drive_torque_N_m * (np.asarray(q)[..., k] - q0[k])

    def work_energy_residual_J(self, q: np.ndarray, v: np.ndarray, q0: np.ndarray, v0: np.ndarray) -> np.ndarray:
        """(T + V) − (T₀ + V₀) − W (J): zero along an exact motion."""
        energy = self.kinetic_energy_J(v) + self.potential_energy_J(q)
        energy0 = self.kinetic_energy_J(v0) + self.potential_energy_J(q0)
        return energy - energy0 - self.torque_work_J(q, q0)

    def one_dof_terms(
        self, velocity_coefficients: np.ndarray, acceleration_coefficients: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The one-degree-of-freedom equation's ``M(θ)`` (kg·m²), ``½M′(θ)`` (kg·m²) and ``V′(θ)`` (N·m), each (N,).

        From the kinematic coefficients of the absolute coordinates with respect to
        the driven angle θ, ``q′`` and ``q″`` (N, 3 n_bodies) (the rates and
        accelerations at θ̇ = 1, θ̈ = 0): ``T = ½ θ̇² q′ᵀ M q′`` gives
        ``M = q′ᵀ M q′`` and ``½ M′ = q′ᵀ M q″``; ``V′ = g Σ m y_G′``.
        Then ``M θ̈ + ½ M′ θ̇² = τ − V′``.
        """
        diagonal = self.mass_diagonal
        q1, q2 = np.atleast_2d(velocity_coefficients), np.atleast_2d(acceleration_coefficients)
        masses = np.array([link.mass_kg for link in self.links])
        return (
            np.sum(diagonal * q1 * q1, axis=-1),
            np.sum(diagonal * q1 * q2, axis=-1),
            self.g_m_s2 * np.sum(masses * q1[:, 1::3], axis=-1),
        )
