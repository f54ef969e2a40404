"""The unbalanced rotor: bearing reactions of a disk on a shaft turning at constant speed (Newton–Euler).

Frames (m, +Z up). World: the shaft runs along +X from bearing A (the origin)
to bearing B at ``X = L``; gravity ``g`` points along −Z, across the shaft.
Rotor frame xyz turns with the shaft: x = X along the shaft, y through the
disk's centre of mass G (the eccentricity ``e`` lies along +y), z = x × y. It
is turned by the spin angle ``φ = ω t`` about X, so at ``φ = 0`` rotor y is
world +Y and G is level with the shaft.

The disk (thin, uniform, mass m, radius r) has its centre G at ``(a, e, 0)``
in the rotor frame and its normal tilted by the skew β about the rotor's y
axis: ``n = (cos β, 0, sin β)``. Its inertia about G comes from
:func:`~app.physics.bodies.inertia.thin_disk` rotated onto those axes.

Newton–Euler for each part k of the rotor (the disk, and the correction
masses when fitted), at constant ω so every ``a_k`` and ``dH_Gk/dt = ω × H_Gk``
are fixed in the rotor frame:

    ΣF = Σ m_k a_k,      ΣM_A = Σ (dH_Gk/dt + r_k × m_k a_k).

The external loads are the two transverse bearing reactions R_A, R_B (forces
of the bearings on the shaft), the weight and the drive torque T about the
shaft. Moments about A give ``T = M_A·X̂`` and ``R_B = M_A × X̂ / L``; the
forces then give ``R_A``. The massless shaft carries no inertia.

Balancing: a rotor is balanced when its first moment of mass about the shaft
``S = Σ m_k (y_k, z_k)`` and its products of inertia about A with the shaft
``P = (I_xy, I_xz)`` (``I_xy = ∫ x y dm``) both vanish. Two point masses at
radius ρ in planes x₁, x₂ do it: with ``U_i = m_i ρ (cos θ_i, sin θ_i)``,
``U₁ + U₂ = −S`` and ``x₁ U₁ + x₂ U₂ = −P``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np

from app.physics.bodies.inertia import parallel_axis, rotate_tensor, thin_disk
from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet

ImbalanceClass = Literal["static", "dynamic", "both", "balanced"]
#: A first moment or product of inertia below this fraction of the disk's own scale (m r, m r²) counts as zero.
BALANCED_BELOW = 1e-12
#: The correction planes must be at least this fraction of the bearing span apart.
MIN_PLANE_SEPARATION = 0.02
AXIS_X = np.array([1.0, 0.0, 0.0])


@dataclass(frozen=True)
class RotorPart:
    """One rigid part of the rotor: mass (kg), centre of mass in the rotor frame (m, shape (3,)),
    inertia about its own centre of mass in rotor-frame components (kg·m², shape (3, 3))."""

    mass_kg: float
    centre_m: np.ndarray
    inertia_cm_kg_m2: np.ndarray


@dataclass(frozen=True)
class DiskOnShaft:
    """A thin uniform disk on a shaft between bearings A and B (see the module docstring for the frames)."""

    disk_mass_kg: float
    disk_radius_m: float
    eccentricity_m: float
    skew_rad: float
    bearing_span_m: float
    disk_position_m: float

    def __post_init__(self) -> None:
        values = (
            self.disk_mass_kg,
            self.disk_radius_m,
            self.eccentricity_m,
            self.skew_rad,
            self.bearing_span_m,
            self.disk_position_m,
        )
        if not all(math.isfinite(v) for v in values):
            raise ValueError("the rotor's mass, sizes and angles must be finite numbers")
        if not (self.disk_mass_kg > 0.0 and self.disk_radius_m > 0.0 and self.bearing_span_m > 0.0):
            raise ValueError("the disk's mass and radius and the bearing span must be positive")
        if not 0.0 <= self.disk_position_m <= self.bearing_span_m:
            raise ParameterError(
                "disk_position_m",
                f"the disk ({self.disk_position_m:g} m from A) must sit between the bearings (0 to "
                f"{self.bearing_span_m:g} m)",
            )
        if not 0.0 <= self.eccentricity_m < self.disk_radius_m:
            raise ParameterError(
                "eccentricity_m",
                f"the eccentricity ({self.eccentricity_m:g} m) must be less than the disk's radius "
                f"({self.disk_radius_m:g} m)",
            )

    @property
    def normal(self) -> np.ndarray:
        """The disk's unit normal in the rotor frame: the shaft axis x tilted by the skew towards z."""
        return np.array([math.cos(self.skew_rad), 0.0, math.sin(self.skew_rad)])

    @property
    def disk_axes(self) -> np.ndarray:
        """(3, 3) rotation whose columns are the disk's own x, y, z (z its normal) in the rotor frame."""
        c, s = math.cos(self.skew_rad), math.sin(self.skew_rad)
        return np.array([[s, 0.0, c], [0.0, 1.0, 0.0], [-c, 0.0, s]])  # x = y × n, y = rotor y, z = n

    def part(self) -> RotorPart:
        """The disk as a rotor part: G at ``(a, e, 0)``, thin-disk inertia turned onto the tilted axes."""
        inertia = rotate_tensor(thin_disk(self.disk_mass_kg, self.disk_radius_m), self.disk_axes)
        return RotorPart(self.disk_mass_kg, np.array([self.disk_position_m, self.eccentricity_m, 0.0]), inertia)


def first_moment_kg_m(parts: tuple[RotorPart, ...]) -> np.ndarray:
    """Static imbalance ``S = Σ m_k (y_k, z_k)`` (kg·m, shape (2,), rotor y and z)."""
    return sum((p.mass_kg * p.centre_m[1:] for p in parts), np.zeros(2))


def products_about_bearing_A_kg_m2(parts: tuple[RotorPart, ...]) -> np.ndarray:
    """Couple imbalance ``P = (I_xy, I_xz)`` about bearing A (kg·m², shape (2,)), ``I_xy = ∫ x y dm``."""
    total = sum((parallel_axis(p.inertia_cm_kg_m2, p.mass_kg, p.centre_m) for p in parts), np.zeros((3, 3)))
    return -total[0, 1:]  # the tensor holds −I_xy, −I_xz


@dataclass(frozen=True)
class TwoPlaneCorrection:
    """Point masses (kg, shape (2,)) at angles (rad from rotor +y towards +z, in [0, 2π)) and radius ρ (m)
    in the planes ``x₁, x₂`` (m from A) that balance the rotor."""

    masses_kg: np.ndarray
    angles_rad: np.ndarray
    planes_m: tuple[float, float]
    radius_m: float

    def parts(self) -> tuple[RotorPart, ...]:
        """The correction masses as rotor parts (points: no inertia about their own centre)."""
        return tuple(
            RotorPart(
                float(m), np.array([x, self.radius_m * math.cos(th), self.radius_m * math.sin(th)]), np.zeros((3, 3))
            )
            for m, th, x in zip(self.masses_kg, self.angles_rad, self.planes_m, strict=True)
        )


def two_plane_correction(
    parts: tuple[RotorPart, ...], *, planes_m: tuple[float, float], radius_m: float
) -> TwoPlaneCorrection:
    """Solve ``U₁ + U₂ = −S`` and ``x₁ U₁ + x₂ U₂ = −P`` for the two correction masses (see the module docstring)."""
    x1, x2 = planes_m
    if not (radius_m > 0.0 and x1 != x2):
        raise ValueError("two-plane balancing needs a positive radius and two different planes")
    S, P = first_moment_kg_m(parts), products_about_bearing_A_kg_m2(parts)
    U1 = (P - x2 * S) / (x2 - x1)
    U2 = (x1 * S - P) / (x2 - x1)
    U = np.array([U1, U2])
    masses = np.hypot(U[:, 0], U[:, 1]) / radius_m
    angles = np.mod(np.arctan2(U[:, 1], U[:, 0]), 2.0 * math.pi)
    return TwoPlaneCorrection(masses, angles, (float(x1), float(x2)), float(radius_m))


def couple_imbalance_kg_m2(parts: tuple[RotorPart, ...]) -> np.ndarray:
    """Products of inertia with the shaft ``(I_xy, I_xz)`` about the shaft point level with the centre of mass
    (kg·m², shape (2,)): what is left of ``P`` once the static imbalance ``S`` is taken out (``P − x̄ S``)."""
    total_mass = sum(p.mass_kg for p in parts)
    centre_x = sum(p.mass_kg * p.centre_m[0] for p in parts) / total_mass
    return products_about_bearing_A_kg_m2(parts) - centre_x * first_moment_kg_m(parts)


def imbalance_class(parts: tuple[RotorPart, ...], *, mass_kg: float, radius_m: float) -> ImbalanceClass:
    """Which imbalance the parts have: ``static`` (G off the shaft, the shaft a principal axis at G), ``dynamic``
    (G on the shaft, products of inertia with it at G), ``both``, or ``balanced``; judged against ``m r`` and
    ``m r²``."""
    static = float(np.hypot(*first_moment_kg_m(parts))) > BALANCED_BELOW * mass_kg * radius_m
    dynamic = float(np.hypot(*couple_imbalance_kg_m2(parts))) > BALANCED_BELOW * mass_kg * radius_m**2
    return "both" if static and dynamic else "static" if static else "dynamic" if dynamic else "balanced"


@dataclass(frozen=True)
class RotorLoads:
    """At N spin angles φ (rad): bearing reactions on the shaft R_A, R_B (N, world, shape (N, 3)),
    their rotating (speed) parts (N, world, (N, 3)) and the drive torque about +X (N·m, shape (N,))."""

    spin_angle: np.ndarray
    bearing_A_N: np.ndarray
    bearing_B_N: np.ndarray
    bearing_A_rotating_N: np.ndarray
    bearing_B_rotating_N: np.ndarray
    driving_torque_Nm: np.ndarray

    @property
    def bearing_A_force_N(self) -> np.ndarray:
        return np.linalg.norm(self.bearing_A_N, axis=-1)

    @property
    def bearing_B_force_N(self) -> np.ndarray:
        return np.linalg.norm(self.bearing_B_N, axis=-1)


@dataclass(frozen=True)
class UnbalancedRotor:
    """The rotor turning at constant speed ω (rad/s) under gravity g (m/s², along −Z), optionally balanced."""

    disk: DiskOnShaft
    shaft_speed_rad_s: float
    g_m_s2: float
    correction: TwoPlaneCorrection
    balanced: bool

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> UnbalancedRotor:
        disk = DiskOnShaft(
            params["disk_mass_kg"],
            params["disk_radius_m"],
            params["eccentricity_m"],
            math.radians(params["skew_deg"]),
            params["bearing_span_m"],
            params["disk_position_m"],
        )
        span = disk.bearing_span_m
        planes = (params["correction_plane_1_m"], params["correction_plane_2_m"])
        for name, x in zip(("correction_plane_1_m", "correction_plane_2_m"), planes, strict=True):
            if not 0.0 <= x <= span:
                raise ParameterError(
                    name, f"the correction plane ({x:g} m from A) must lie between the bearings (0 to {span:g} m)"
                )
        if abs(planes[1] - planes[0]) < MIN_PLANE_SEPARATION * span:
            raise ParameterError(
                "correction_plane_2_m",
                f"the two correction planes must be at least {MIN_PLANE_SEPARATION * span:g} m apart (2% of the "
                "bearing span)",
            )
        correction = two_plane_correction((disk.part(),), planes_m=planes, radius_m=params["correction_radius_m"])
        return cls(disk, params["shaft_speed_rad_s"], params["g_m_s2"], correction, params["balanced"] == "on")

    @property
    def parts(self) -> tuple[RotorPart, ...]:
        """The disk, and the two correction masses when fitted."""
        return (self.disk.part(), *self.correction.parts()) if self.balanced else (self.disk.part(),)

    @property
    def imbalance(self) -> ImbalanceClass:
        return imbalance_class(self.parts, mass_kg=self.disk.disk_mass_kg, radius_m=self.disk.disk_radius_m)

    def inertial_loads_rotor(self) -> tuple[np.ndarray, np.ndarray]:
        """``(Σ m_k a_k (N), Σ dH_Gk/dt + r_k × m_k a_k about A (N·m))`` in the rotor frame; constant at constant ω."""
        omega = self.shaft_speed_rad_s * AXIS_X
        force, moment = np.zeros(3), np.zeros(3)
        for part in self.parts:
            acceleration = np.cross(omega, np.cross(omega, part.centre_m))
            force += part.mass_kg * acceleration
            moment += np.cross(omega, part.inertia_cm_kg_m2 @ omega) + np.cross(
                part.centre_m, part.mass_kg * acceleration
            )
        return force, moment

    def steady_loads(self) -> SteadyLoads:
        """The load pattern: everything that is fixed in the rotor frame, computed once."""
        force_rotor, moment_rotor = self.inertial_loads_rotor()
        parts = self.parts
        b_rotating = np.cross(moment_rotor, AXIS_X) / self.disk.bearing_span_m
        return SteadyLoads(
            shaft_speed_rad_s=self.shaft_speed_rad_s,
            g_m_s2=self.g_m_s2,
            bearing_span_m=self.disk.bearing_span_m,
            mass_kg=sum(p.mass_kg for p in parts),
            mass_moment_kg_m=sum((p.mass_kg * p.centre_m for p in parts), np.zeros(3)),
            bearing_A_rotating_rotor_N=force_rotor - b_rotating,
            bearing_B_rotating_rotor_N=b_rotating,
        )

    def at(self, t_s: np.ndarray) -> RotorLoads:
        return self.steady_loads().at(t_s)


def harmonic_coefficients(vector_rotor: np.ndarray) -> np.ndarray:
    """(3, 3) matrix K with world components ``K @ (1, cos φ, sin φ)`` of a rotor-frame vector (shape (3,)) at spin
    φ."""
    x, y, z = vector_rotor
    return np.array([[x, 0.0, 0.0], [0.0, y, -z], [0.0, z, y]])


@dataclass(frozen=True)
class SteadyLoads:
    """What stays fixed while the rotor turns at constant speed: the rotating reactions in the rotor frame
    (N, shape (3,)), the total mass (kg) and its moment ``Σ m_k r_k`` (kg·m, rotor frame), speed, gravity, span.

    Every load is then ``K @ (1, cos φ, sin φ)`` with constant coefficients, so a frame costs one product.
    """

    shaft_speed_rad_s: float
    g_m_s2: float
    bearing_span_m: float
    mass_kg: float
    mass_moment_kg_m: np.ndarray
    bearing_A_rotating_rotor_N: np.ndarray
    bearing_B_rotating_rotor_N: np.ndarray
    #: K (13, 3), rows A, B rotating; A, B total; T: set on construction from the fields above.
    _coefficients: np.ndarray = field(init=False, repr=False, compare=False)

    @property
    def weight_shares_N(self) -> tuple[float, float]:
        """Upward weight shares at A and B (N): moments about A give ``M g x̄ / L`` at B, the rest of ``M g`` at A."""
        at_B = self.g_m_s2 * float(self.mass_moment_kg_m[0]) / self.bearing_span_m
        return self.mass_kg * self.g_m_s2 - at_B, at_B

    @property
    def driving_torque_amplitude_Nm(self) -> float:
        """Largest drive torque over a turn (N·m): ``g |Σ m_k (y_k, z_k)|``, gravity's moment about the shaft."""
        return self.g_m_s2 * float(np.hypot(*self.mass_moment_kg_m[1:]))

    def __post_init__(self) -> None:
        g, (_, first_y, first_z) = self.g_m_s2, self.mass_moment_kg_m
        share_A, share_B = (np.array([0.0, 0.0, share]) for share in self.weight_shares_N)
        # Gravity's moment about A is (Σ m_k r_k) × (0, 0, −g); its X component −g·(Σ m_k r_k)_Y is what
        # the drive must cancel: T = g (Σ m_k r_k)_Y = g (first_y cos φ − first_z sin φ).
        torque = np.array([[0.0, g * first_y, -g * first_z]])
        rotating_A = harmonic_coefficients(self.bearing_A_rotating_rotor_N)
        rotating_B = harmonic_coefficients(self.bearing_B_rotating_rotor_N)
        with_weight = np.column_stack([np.concatenate([share_A, share_B]), np.zeros((6, 2))])
        rows = np.vstack([rotating_A, rotating_B, np.vstack([rotating_A, rotating_B]) + with_weight, torque])
        object.__setattr__(self, "_coefficients", rows)  # (13, 3): A, B rotating; A, B total; T

    def at(self, t_s: np.ndarray) -> RotorLoads:
        """Reactions and drive torque at times ``t_s`` (s, shape (N,)), spin angle ``φ = ω t``."""
        return self.at_spin_angle(self.shaft_speed_rad_s * np.atleast_1d(np.asarray(t_s, dtype=float)))

    def at_spin_angle(self, spin_angle_rad: np.ndarray) -> RotorLoads:
        """Reactions and drive torque with the rotor turned by ``φ`` (rad, shape (N,)) from its start."""
        phi = np.atleast_1d(np.asarray(spin_angle_rad, dtype=float))
        values = self._coefficients @ np.stack([np.ones_like(phi), np.cos(phi), np.sin(phi)])
        return RotorLoads(phi, values[6:9].T, values[9:12].T, values[0:3].T, values[3:6].T, values[12])


def _check(params: Mapping[str, Any]) -> None:
    UnbalancedRotor.from_params(params)


PARAMETERS = ParameterSet(
    (
        Parameter(
            "shaft_speed_rad_s",
            "rad/s",
            100.0,
            -500.0,
            500.0,
            "Constant shaft speed ω about +X (A to B)",
            "ω",
            step=1.0,
        ),
        Parameter("disk_mass_kg", "kg", 10.0, 0.01, 1000.0, "Mass m of the thin uniform disk", "disk mass m", step=0.1),
        Parameter("disk_radius_m", "m", 0.2, 0.01, 2.0, "Radius r of the disk", "disk radius r", step=0.01),
        Parameter(
            "eccentricity_m",
            "m",
            0.001,
            0.0,
            0.5,
            "Distance e of the disk's centre of mass from the shaft axis",
            "eccentricity e",
            step=0.0005,
        ),
        Parameter(
            "skew_deg",
            "deg",
            2.0,
            -45.0,
            45.0,
            "Skew β: angle between the disk's axis and the shaft",
            "skew β",
            step=0.1,
        ),
        Parameter(
            "bearing_span_m", "m", 0.6, 0.05, 5.0, "Distance L between bearings A and B", "bearing span L", step=0.01
        ),
        Parameter(
            "disk_position_m",
            "m",
            0.2,
            0.0,
            5.0,
            "Distance a of the disk from bearing A along the shaft",
            "disk position a",
            step=0.01,
        ),
        Parameter(
            "g_m_s2",
            "m/s²",
            9.81,
            0.0,
            30.0,
            "Gravity g across the shaft (along −Z); 0 for none",
            "gravity g",
            step=0.01,
        ),
        Parameter(
            "correction_plane_1_m",
            "m",
            0.05,
            0.0,
            5.0,
            "Position x₁ of the first correction plane from A",
            "plane 1 x₁",
            step=0.01,
        ),
        Parameter(
            "correction_plane_2_m",
            "m",
            0.55,
            0.0,
            5.0,
            "Position x₂ of the second correction plane from A",
            "plane 2 x₂",
            step=0.01,
        ),
        Parameter(
            "correction_radius_m",
            "m",
            0.15,
            0.01,
            2.0,
            "Radius ρ at which the correction masses are fixed",
            "correction radius ρ",
            step=0.01,
        ),
        Parameter(
            "balanced",
            "",
            "off",
            kind="choice",
            choices=("off", "on"),
            label="correction masses",
            description="Fit the two correction masses that balance the rotor",
        ),
    ),
    check=_check,
)


class UnbalancedRotorModel(ClosedFormModel):
    """A disk on a shaft at constant speed: bearing reactions and drive torque by Newton–Euler, in closed form."""

    parameters = PARAMETERS
    series_units = {"spin_angle": "rad", "bearing_A_force_N": "N", "bearing_B_force_N": "N", "driving_torque_Nm": "N·m"}
    description = (
        "Newton–Euler for a rigid rotor at constant speed: the inertial loads are fixed in the rotor "
        "frame (closed form)"
    )

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        loads = UnbalancedRotor.from_params(params).at(t_s)
        return ClosedFormSolution(
            {
                "spin_angle": loads.spin_angle,
                "bearing_A_force_N": loads.bearing_A_force_N,
                "bearing_B_force_N": loads.bearing_B_force_N,
                "driving_torque_Nm": loads.driving_torque_Nm,
            }
        )
