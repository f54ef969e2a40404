"""Torque-free axisymmetric rigid body: steady precession about the fixed angular momentum, in closed form.

Frames and units. World frame ``XYZ`` (+Z up) with the angular momentum ``L``
about the centre of mass along +Z (it is fixed: no torque acts). Body axes
``xyz`` are principal axes through the centre of mass with ``z`` along the
symmetry axis: moments ``(I_t, I_t, I_a)`` in kg·m². The attitude is the 3-1-3
sequence ``R_world_body = Rz(φ) Rx(θ) Rz(ψ)`` (see :mod:`app.physics.math.rotations`),
angles in rad, rates in rad/s.

Derivation. With ``L = L K`` the body components of ``L`` are
``L (sin θ sin ψ, sin θ cos ψ, cos θ)``, and ``L_body = (I_t ω1, I_t ω2, I_a ω3)``:

* ``ω3 = L cos θ / I_a``, so ``L = I_a ω3 / cos θ`` (hence the exclusion of θ = 90°);
* Euler's third equation with ``I_1 = I_2`` gives ``ω3`` constant, so ``θ`` is
  constant (``θ̇ = 0``);
* the 3-1-3 rate relations with ``θ̇ = 0`` give ``ω1 = φ̇ sin θ sin ψ`` and
  ``ω2 = φ̇ sin θ cos ψ``; matching ``ω1 = L sin θ sin ψ / I_t`` gives
  ``φ̇ = L / I_t = I_a ω3 / (I_t cos θ)``;
* ``ω3 = φ̇ cos θ + ψ̇`` gives ``ψ̇ = ω3 − I_a ω3 / I_t = (I_t − I_a) ω3 / I_t``.

So ``φ = φ̇ t`` and ``ψ = ψ̇ t`` grow linearly (both start at 0) and the angular
velocity is ``ω = φ̇ K + ψ̇ k``: it lies in the plane of ``L`` and the symmetry
axis ``k``. The *body cone* (half-angle β about ``k``, fixed in the body) rolls
without slipping on the *space cone* (half-angle γ about ``K``, fixed in space)
along their common line, ω. ``tan β = (I_a / I_t) tan θ``. A prolate body
(``I_a < I_t``) has β < θ, γ = θ − β, ψ̇ > 0: *direct* precession, the body
cone rolls on the outside of the space cone. An oblate body (``I_a > I_t``) has
β > θ, γ = β − θ, ψ̇ < 0: *retrograde* precession, the space cone sits inside
the body cone. Seen from the body, ω circles ``k`` at ``λ = −ψ̇ = (I_a − I_t) ω3 / I_t``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet

#: Largest nutation accepted: L = I_a ω3 / cos θ grows without bound as θ → 90°.
MAX_NUTATION_DEG = 89.0

PrecessionSense = Literal["direct", "retrograde", "none"]


@dataclass(frozen=True)
class AxisymmetricFreeMotion:
    """The steady free motion of an axisymmetric body with ``L`` along world +Z.

    ``I_transverse_kg_m2`` and ``I_axial_kg_m2`` are principal moments about the
    centre of mass, ``spin_rad_s`` is ω3 (the body-axis component of ω along the
    symmetry axis, > 0), ``nutation_rad`` the constant angle θ between the
    symmetry axis and ``L`` (0 ≤ θ < π/2). Construct it from validated inputs
    (:func:`motion_from_params`); the constructor re-checks them.
    """

    I_transverse_kg_m2: float
    I_axial_kg_m2: float
    spin_rad_s: float
    nutation_rad: float

    def __post_init__(self) -> None:
        check_inputs(
            I_transverse=self.I_transverse_kg_m2,
            I_axial=self.I_axial_kg_m2,
            spin_rad_s=self.spin_rad_s,
            nutation_deg=math.degrees(self.nutation_rad),
        )

    # -- constant rates and magnitudes -----------------------------------------------------
    @property
    def inertia_ratio(self) -> float:
        """``I_a / I_t`` (dimensionless, in (0, 2]): below 1 prolate, above 1 oblate."""
        return self.I_axial_kg_m2 / self.I_transverse_kg_m2

    @property
    def angular_momentum_kg_m2_s(self) -> float:
        """|L| = I_a ω3 / cos θ (kg·m²/s), along world +Z."""
        return self.I_axial_kg_m2 * self.spin_rad_s / math.cos(self.nutation_rad)

    @property
    def precession_rate_rad_s(self) -> float:
        """φ̇ = |L| / I_t (rad/s): the symmetry axis circles L at this rate."""
        return self.angular_momentum_kg_m2_s / self.I_transverse_kg_m2

    @property
    def spin_rate_rad_s(self) -> float:
        """ψ̇ = (I_t − I_a) ω3 / I_t (rad/s): the body turns about its axis relative to the line of nodes."""
        return (self.I_transverse_kg_m2 - self.I_axial_kg_m2) * self.spin_rad_s / self.I_transverse_kg_m2

    @property
    def body_frame_precession_rate_rad_s(self) -> float:
        """λ = (I_a − I_t) ω3 / I_t (rad/s): the rate at which ω circles the symmetry axis, seen from the body."""
        return (self.I_axial_kg_m2 - self.I_transverse_kg_m2) * self.spin_rad_s / self.I_transverse_kg_m2

    @property
    def angular_speed_rad_s(self) -> float:
        """|ω| = √(ω⊥² + ω3²) (rad/s), with the transverse part ω⊥ = φ̇ sin θ."""
        return math.hypot(self.precession_rate_rad_s * math.sin(self.nutation_rad), self.spin_rad_s)

    @property
    def energy_J(self) -> float:
        """Kinetic energy T = ½ (I_t ω⊥² + I_a ω3²) (J), with ω⊥ = φ̇ sin θ."""
        transverse = self.precession_rate_rad_s * math.sin(self.nutation_rad)
        return 0.5 * (self.I_transverse_kg_m2 * transverse**2 + self.I_axial_kg_m2 * self.spin_rad_s**2)

    @property
    def body_cone_half_angle_rad(self) -> float:
        """β, the angle between ω and the symmetry axis (rad): tan β = (I_a / I_t) tan θ."""
        theta = self.nutation_rad
        return math.atan2(self.I_axial_kg_m2 * math.sin(theta), self.I_transverse_kg_m2 * math.cos(theta))

    @property
    def space_cone_half_angle_rad(self) -> float:
        """γ, the angle between ω and L (rad), from ω = φ̇ K + ψ̇ k without forming θ − β.

        The component of ω along K is φ̇ + ψ̇ cos θ (positive for every real body), the
        component across it |ψ̇| sin θ; so a nearly spherical body gets a tiny γ to full
        relative precision.
        """
        theta = self.nutation_rad
        along = self.precession_rate_rad_s + self.spin_rate_rad_s * math.cos(theta)
        return math.atan2(abs(self.spin_rate_rad_s) * math.sin(theta), along)

    @property
    def sense(self) -> PrecessionSense:
        """``"direct"`` when φ̇ and ψ̇ have the same sign (prolate), ``"retrograde"`` when opposite (oblate).

        ``"none"`` when ψ̇ = 0 (I_a = I_t): ω lies along L and the body simply turns about it.
        """
        if self.I_axial_kg_m2 < self.I_transverse_kg_m2:
            return "direct"
        if self.I_axial_kg_m2 > self.I_transverse_kg_m2:
            return "retrograde"
        return "none"

    @property
    def precession_period_s(self) -> float:
        """Time for the symmetry axis to go once round L (s)."""
        return 2.0 * math.pi / self.precession_rate_rad_s

    # -- time histories ---------------------------------------------------------------------
    def euler_angles_313(self, t_s: np.ndarray | float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(φ, θ, ψ)`` in rad at times ``t_s`` (s); φ = ψ = 0 at t = 0, not wrapped."""
        t = np.asarray(t_s, dtype=float)
        return self.precession_rate_rad_s * t, np.full_like(t, self.nutation_rad), self.spin_rate_rad_s * t

    def nodal_and_body_quaternions(
        self, t_s: float
    ) -> tuple[tuple[float, float, float, float], tuple[float, float, float, float]]:
        """``q_world_nodal`` = Rz(φ) and ``q_nodal_body`` = Rx(θ) Rz(ψ) (``wxyz``) at time ``t_s`` (s).

        Their product is ``q_world_body``. The nodal frame carries ω and the symmetry
        axis (both constant on it), so a scene moves two nodes per frame. Scalar and
        cheap (a few µs): the live scene calls it every frame.
        """
        half_phi = 0.5 * math.remainder(self.precession_rate_rad_s * t_s, 4.0 * math.pi)
        half_psi = 0.5 * math.remainder(self.spin_rate_rad_s * t_s, 4.0 * math.pi)
        ct, st = math.cos(0.5 * self.nutation_rad), math.sin(0.5 * self.nutation_rad)
        cp, sp = math.cos(half_psi), math.sin(half_psi)
        return (math.cos(half_phi), 0.0, 0.0, math.sin(half_phi)), (ct * cp, st * cp, -st * sp, ct * sp)

    def symmetry_axis_nodal(self) -> np.ndarray:
        """The symmetry axis k (unit, shape (3,)) on the nodal frame ``Rz(φ)`` (x along the line of nodes).

        Constant: in that frame k = (0, −sin θ, cos θ).
        """
        return np.array([0.0, -math.sin(self.nutation_rad), math.cos(self.nutation_rad)])

    def angular_velocity_nodal_rad_s(self) -> np.ndarray:
        """ω = φ̇ K + ψ̇ k (rad/s, shape (3,)) on the nodal frame ``Rz(φ)``: constant there."""
        return (
            self.precession_rate_rad_s * np.array([0.0, 0.0, 1.0]) + self.spin_rate_rad_s * self.symmetry_axis_nodal()
        )

    def angular_velocity_body_rad_s(self, t_s: np.ndarray | float) -> np.ndarray:
        """ω on body axes (rad/s, shape (..., 3)) at times ``t_s``: ω⊥ turns about k at λ = −ψ̇."""
        _, theta, psi = self.euler_angles_313(t_s)
        transverse = self.precession_rate_rad_s * np.sin(theta)
        return np.stack(
            [transverse * np.sin(psi), transverse * np.cos(psi), np.full_like(psi, self.spin_rad_s)], axis=-1
        )


def spheroid_aspect_ratio(inertia_ratio: float) -> float:
    """Semi-axis along the symmetry axis over the transverse semi-axis of the uniform solid spheroid with
    ``I_a / I_t = inertia_ratio``.

    For semi-axes ``a`` (axial) and ``b``: ``I_a = (2/5) m b²`` and ``I_t = (1/5) m (a² + b²)``,
    so ``I_a / I_t = 2 b² / (a² + b²)`` and ``a / b = √(2 / ratio − 1)``: 2 for a rugby ball
    (ratio 0.4), 1 for a sphere, 0 for the flat-disc limit (ratio 2).
    """
    if not 0.0 < inertia_ratio <= 2.0 * (1.0 + 1e-12):
        raise ValueError(f"inertia ratio I_a/I_t must lie in (0, 2] (got {inertia_ratio!r})")
    return math.sqrt(max(2.0 / inertia_ratio - 1.0, 0.0))


def check_inputs(*, I_transverse: float, I_axial: float, spin_rad_s: float, nutation_deg: float) -> None:
    """Raise :class:`ParameterError` (naming the input) for values no torque-free axisymmetric body can have."""
    for name, value in (("I_transverse", I_transverse), ("I_axial", I_axial)):
        if not (math.isfinite(value) and value > 0.0):
            raise ParameterError(
                name, f"must be a finite positive moment of inertia about the centre of mass in kg·m² (got {value!r})"
            )
    if I_axial > 2.0 * I_transverse * (1.0 + 1e-12):
        raise ParameterError(
            "I_axial",
            f"must not exceed twice I_t (2 × {I_transverse:g} = {2.0 * I_transverse:g} kg·m²): for any real body "
            "I_a ≤ 2 I_t (triangle inequality of the moments), and a flat disc is the limit",
        )
    if not math.isfinite(spin_rad_s) or spin_rad_s == 0.0:
        raise ParameterError(
            "spin_rad_s",
            "must not be zero: with no spin about the symmetry axis and the axis less than 90° from L, "
            "L = I_a·ω₃/cos θ is zero, the body is at rest, and the precession and cones are undefined",
        )
    if spin_rad_s < 0.0:
        raise ParameterError(
            "spin_rad_s",
            "must be positive: the symmetry axis is taken to point the way the body spins about it, which keeps it "
            "within 90° of L (for the opposite spin, turn the axis round)",
        )
    if not (math.isfinite(nutation_deg) and 0.0 <= nutation_deg <= MAX_NUTATION_DEG):
        raise ParameterError(
            "nutation_deg",
            f"must lie between 0° and {MAX_NUTATION_DEG:g}°: at 90° the axis is perpendicular to L and L = "
            "I_a·ω₃/cos θ is undefined",
        )


def _check(values: Mapping[str, Any]) -> None:
    check_inputs(
        I_transverse=values["I_transverse"],
        I_axial=values["I_axial"],
        spin_rad_s=values["spin_rad_s"],
        nutation_deg=values["nutation_deg"],
    )


PARAMETERS = ParameterSet(
    (
        Parameter(
            "I_transverse",
            "kg·m²",
            1.0,
            1e-6,
            1e6,
            "Moment of inertia about a transverse axis through the centre of mass",
            "I_t",
            scale="log",
        ),
        Parameter(
            "I_axial",
            "kg·m²",
            0.4,
            1e-6,
            1e6,
            "Moment of inertia about the symmetry axis (at most 2 I_t)",
            "I_a",
            scale="log",
        ),
        Parameter(
            "spin_rad_s",
            "rad/s",
            3.0,
            -1000.0,
            1000.0,
            "Spin ω3: angular velocity component along the symmetry axis (positive)",
            "ω₃",
            step=0.05,
        ),
        Parameter(
            "nutation_deg",
            "deg",
            25.0,
            0.0,
            MAX_NUTATION_DEG,
            "Nutation θ: constant angle between the symmetry axis and L",
            "θ",
            step=0.5,
        ),
    ),
    check=_check,
)


def motion_from_params(params: Mapping[str, Any]) -> AxisymmetricFreeMotion:
    """The motion for validated parameters (names as in :data:`PARAMETERS`)."""
    return AxisymmetricFreeMotion(
        I_transverse_kg_m2=float(params["I_transverse"]),
        I_axial_kg_m2=float(params["I_axial"]),
        spin_rad_s=float(params["spin_rad_s"]),
        nutation_rad=math.radians(float(params["nutation_deg"])),
    )


class TorqueFreeAxisymmetric(ClosedFormModel):
    """Steady precession of a torque-free axisymmetric body (no integration)."""

    parameters = PARAMETERS
    series_units = {"theta": "rad", "phi": "rad", "psi": "rad"}
    invariant_units = {"energy": "J", "angular_momentum": "kg·m²/s"}
    description = "steady precession: θ constant, φ = φ̇ t and ψ = ψ̇ t (3-1-3 angles, L along +Z)"

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        motion = motion_from_params(params)
        phi, theta, psi = motion.euler_angles_313(t_s)
        return ClosedFormSolution(
            series={"theta": theta, "phi": phi, "psi": psi},
            invariants=invariants_from_state(motion, t_s),
        )


def invariants_from_state(motion: AxisymmetricFreeMotion, t_s: np.ndarray) -> dict[str, np.ndarray]:
    """Energy (J) and |L| (kg·m²/s) recomputed at each time from the body-axis ω of the closed form.

    They are constant to round-off if the formulas for φ̇, ψ̇ and θ are mutually
    consistent; the simulate report's drift figure shows that they are.
    """
    omega = motion.angular_velocity_body_rad_s(t_s)
    inertia = np.array([motion.I_transverse_kg_m2, motion.I_transverse_kg_m2, motion.I_axial_kg_m2])
    momentum = omega * inertia
    return {
        "energy": 0.5 * np.einsum("...i,...i->...", omega, momentum),
        "angular_momentum": np.linalg.norm(momentum, axis=-1),
    }
