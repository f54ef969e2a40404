"""Constraints pictured in configuration space: scleronomic, rheonomic and nonholonomic.

Three systems, each with closed-form motion (no integrator):

* **Scleronomic** — a bead on a fixed ellipse ``g(x, y) = x²/a² + y²/b² − 1 = 0`` (planar, m).
  The configuration space is the plane (x, y); the constraint is the curve g = 0. The bead runs
  round it at a steady parameter rate ω: ``r = (a cos φ, b sin φ)``, φ = φ₀ + ω t.
  Both the actual velocity and every virtual displacement are tangent to the curve.
* **Rheonomic** — a bead on a circular hoop of radius R whose centre slides along x as
  ``x_c(t) = A sin Ωt``: ``g(x, y, t) = ((x − x_c)² + y²)/R² − 1 = 0``. The bead turns round the
  centre at the rate ω: ``r = (x_c + R cos φ, R sin φ)``. A virtual displacement (time frozen) is
  tangent to the circle *as it is at t*; the actual displacement ``dr = ṙ dt`` also carries the
  hoop's own motion, so ``∇g·dr = −∂g/∂t dt ≠ 0``.
* **Nonholonomic** — a knife edge on the plane, configuration ``q = (x, y, ψ)`` (m, m, rad),
  constraint ``ẋ sin ψ − ẏ cos ψ = 0`` (no sideways slip). Admissible velocities span the
  plane of the fields ``drive = (cos ψ, sin ψ, 0)`` (per m) and ``turn = (0, 0, 1)`` (per rad).
  Their Lie bracket ``[drive, turn] = (sin ψ, −cos ψ, 0)`` leaves that plane (Frobenius: not
  integrable), so the manoeuvre drive s, turn α, reverse s, turn back α ends displaced
  sideways by exactly ``s sin α`` — to leading order ``s α`` times the bracket's component
  along the constraint covector, which is 1.

Dimensionless constraint functions g (the ellipse's and the hoop's): ∇g is in 1/m, ∂g/∂t in 1/s.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from app.physics.core.parameters import ParameterError


def _positive(field: str, value: float, unit: str) -> None:
    if not (math.isfinite(value) and value > 0.0):
        raise ParameterError(field, f"must be a positive, finite length in {unit} (got {value!r})")


def _finite(field: str, value: float) -> None:
    if not math.isfinite(value):
        raise ParameterError(field, f"must be finite (got {value!r})")


@dataclass(frozen=True)
class HolonomicSnapshot:
    """One instant of a bead on a curve g(r, t) = 0 (planar; every vector (2,), m or m/s).

    ``virtual_displacement`` is a unit tangent of the curve frozen at t (m per m of δs);
    ``gradient`` is ∇g (1/m); ``time_rate`` is ∂g/∂t (1/s); ``constraint_value`` is g.
    """

    position: np.ndarray
    velocity: np.ndarray
    virtual_displacement: np.ndarray
    gradient: np.ndarray
    time_rate: float
    constraint_value: float

    @property
    def virtual_variation(self) -> float:
        """∇g·δr for the unit δr (1/m · m): zero for an admissible virtual displacement."""
        return float(self.gradient @ self.virtual_displacement)

    @property
    def gradient_along_velocity(self) -> float:
        """∇g·ṙ (1/s): zero only when the constraint does not move."""
        return float(self.gradient @ self.velocity)

    @property
    def actual_variation(self) -> float:
        """∇g·ṙ + ∂g/∂t = dg/dt along the motion (1/s): zero for every admissible actual motion."""
        return self.gradient_along_velocity + self.time_rate

    @property
    def angle_between_deg(self) -> float:
        """Angle (deg) between the actual velocity and the virtual displacement, 0 to 180 (0 at rest)."""
        speed = float(np.linalg.norm(self.velocity))
        if speed == 0.0:
            return 0.0
        cosine = float(self.velocity @ self.virtual_displacement) / speed
        return math.degrees(math.acos(min(1.0, max(-1.0, cosine))))


@dataclass(frozen=True)
class FixedEllipse:
    """Scleronomic: a bead on the fixed ellipse with semi-axes a along x and b along y (m), parameter rate ω (rad/s)."""

    semi_axis_a_m: float
    semi_axis_b_m: float
    rate_rad_s: float

    def __post_init__(self) -> None:
        _positive("semi_axis_a_m", self.semi_axis_a_m, "m")
        _positive("semi_axis_b_m", self.semi_axis_b_m, "m")
        _finite("bead_rate_rad_s", self.rate_rad_s)

    def curve(self, angles_rad: np.ndarray) -> np.ndarray:
        """Points (N, 2) (m) of the ellipse at parameters φ (rad, (N,))."""
        angles_rad = np.asarray(angles_rad, dtype=float)
        return np.stack([self.semi_axis_a_m * np.cos(angles_rad), self.semi_axis_b_m * np.sin(angles_rad)], axis=-1)

    def constraint(self, position: np.ndarray) -> float:
        """g = x²/a² + y²/b² − 1 (dimensionless) at ``position`` (2,) (m)."""
        return float((position[0] / self.semi_axis_a_m) ** 2 + (position[1] / self.semi_axis_b_m) ** 2 - 1.0)

    def gradient(self, position: np.ndarray) -> np.ndarray:
        """∇g = (2x/a², 2y/b²) (1/m, (2,))."""
        return np.array([2.0 * position[0] / self.semi_axis_a_m**2, 2.0 * position[1] / self.semi_axis_b_m**2])

    def snapshot(self, t_s: float, *, phase_rad: float = 0.0) -> HolonomicSnapshot:
        """The bead at time t (s), starting at parameter φ₀ = ``phase_rad``."""
        a, b, rate = self.semi_axis_a_m, self.semi_axis_b_m, self.rate_rad_s
        phi = phase_rad + rate * t_s
        c, s = math.cos(phi), math.sin(phi)
        position = np.array([a * c, b * s])
        tangent = np.array([-a * s, b * c])
        return HolonomicSnapshot(
            position=position,
            velocity=rate * tangent,
            virtual_displacement=tangent / float(np.linalg.norm(tangent)),
            gradient=self.gradient(position),
            time_rate=0.0,
            constraint_value=self.constraint(position),
        )


@dataclass(frozen=True)
class SlidingHoop:
    """Rheonomic: a bead on a hoop of radius R (m) whose centre moves as x_c = A sin Ωt (A in m, Ω in rad/s);
    the bead turns about the centre at ω (rad/s)."""

    radius_m: float
    amplitude_m: float
    centre_rate_rad_s: float
    rate_rad_s: float

    def __post_init__(self) -> None:
        _positive("hoop_radius_m", self.radius_m, "m")
        _finite("hoop_amplitude_m", self.amplitude_m)
        _finite("hoop_rate_rad_s", self.centre_rate_rad_s)
        _finite("bead_rate_rad_s", self.rate_rad_s)

    def centre(self, t_s: float) -> np.ndarray:
        """The hoop's centre (2,) (m) at t (s)."""
        return np.array([self.amplitude_m * math.sin(self.centre_rate_rad_s * t_s), 0.0])

    def centre_velocity(self, t_s: float) -> np.ndarray:
        """ẋ_c (2,) (m/s) at t (s)."""
        return np.array([self.amplitude_m * self.centre_rate_rad_s * math.cos(self.centre_rate_rad_s * t_s), 0.0])

    def curve(self, angles_rad: np.ndarray, t_s: float) -> np.ndarray:
        """Points (N, 2) (m) of the hoop as it is at t (s), at angles φ (rad, (N,)) about its centre."""
        angles_rad = np.asarray(angles_rad, dtype=float)
        return self.centre(t_s) + self.radius_m * np.stack([np.cos(angles_rad), np.sin(angles_rad)], axis=-1)

    def constraint(self, position: np.ndarray, t_s: float) -> float:
        """g = ((x − x_c)² + y²)/R² − 1 (dimensionless)."""
        offset = position - self.centre(t_s)
        return float(offset @ offset / self.radius_m**2 - 1.0)

    def gradient(self, position: np.ndarray, t_s: float) -> np.ndarray:
        """∇g = 2 (r − r_c)/R² (1/m, (2,)), at frozen t."""
        return 2.0 * (position - self.centre(t_s)) / self.radius_m**2

    def time_rate(self, position: np.ndarray, t_s: float) -> float:
        """∂g/∂t = −2 (r − r_c)·ṙ_c / R² (1/s): how fast g changes at a fixed point as the hoop moves."""
        return float(-2.0 * (position - self.centre(t_s)) @ self.centre_velocity(t_s) / self.radius_m**2)

    def snapshot(self, t_s: float, *, phase_rad: float = 0.0) -> HolonomicSnapshot:
        """The bead at t (s), at angle φ = φ₀ + ω t about the centre (φ₀ = ``phase_rad``)."""
        phi = phase_rad + self.rate_rad_s * t_s
        radial = np.array([math.cos(phi), math.sin(phi)])
        tangent = np.array([-radial[1], radial[0]])
        position = self.centre(t_s) + self.radius_m * radial
        return HolonomicSnapshot(
            position=position,
            velocity=self.centre_velocity(t_s) + self.radius_m * self.rate_rad_s * tangent,
            virtual_displacement=tangent,
            gradient=self.gradient(position, t_s),
            time_rate=self.time_rate(position, t_s),
            constraint_value=self.constraint(position, t_s),
        )


# --- The knife edge: a nonholonomic constraint ---------------------------------------------------------------


def knife_edge_covector(q: np.ndarray) -> np.ndarray:
    """The constraint's row a(q) (3,) in ``a·q̇ = ẋ sin ψ − ẏ cos ψ = 0``, for q = (x, y, ψ) (m, m, rad)."""
    return np.array([math.sin(q[2]), -math.cos(q[2]), 0.0])


def drive_field(q: np.ndarray) -> np.ndarray:
    """Rolling forward: q̇ per unit speed (3,) = (cos ψ, sin ψ, 0)."""
    return np.array([math.cos(q[2]), math.sin(q[2]), 0.0])


def turn_field(q: np.ndarray) -> np.ndarray:
    """Pivoting on the spot: q̇ per unit turn rate (3,) = (0, 0, 1)."""
    return np.array([0.0, 0.0, 1.0])


def lie_bracket(
    first: Callable[[np.ndarray], np.ndarray],
    second: Callable[[np.ndarray], np.ndarray],
    q: np.ndarray,
    *,
    step: float = 1e-6,
) -> np.ndarray:
    """[f, g](q) = (∂g/∂q) f − (∂f/∂q) g (n,), the Jacobians by central differences of ``step`` in each coordinate.

    Generic in the fields: it knows nothing of the knife edge, so it checks the closed form
    :func:`drive_turn_bracket`. Error O(step²) times the fields' third derivatives.
    """
    q = np.asarray(q, dtype=float)
    n = q.size

    def jacobian(field: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
        columns = []
        for index in range(n):
            shift = np.zeros(n)
            shift[index] = step
            columns.append((field(q + shift) - field(q - shift)) / (2.0 * step))
        return np.stack(columns, axis=-1)

    return jacobian(second) @ first(q) - jacobian(first) @ second(q)


def drive_turn_bracket(q: np.ndarray) -> np.ndarray:
    """[drive, turn](q) = (sin ψ, −cos ψ, 0) (3,): a sideways step, to the right of the heading."""
    return np.array([math.sin(q[2]), -math.cos(q[2]), 0.0])


def bracket_leaves_the_plane(q: np.ndarray) -> float:
    """a·[drive, turn] at q: nonzero means the admissible plane is not involutive (Frobenius), so no surface
    f(x, y, ψ) = 0 has it as tangent plane and the constraint cannot be integrated. It is 1 everywhere."""
    return float(knife_edge_covector(q) @ drive_turn_bracket(q))


#: The manoeuvre's four legs: (drive speed factor, turn rate factor) per unit leg time.
MANOEUVRE_LEGS = ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))


@dataclass(frozen=True)
class ParallelParking:
    """Drive s (m), turn α (rad), reverse s, turn back α: four legs, each one unit of leg time long."""

    drive_distance_m: float
    turn_angle_rad: float

    def __post_init__(self) -> None:
        _positive("drive_distance_m", self.drive_distance_m, "m")
        _finite("turn_angle_deg", self.turn_angle_rad)

    def leg_velocity(self, leg: int, q: np.ndarray) -> np.ndarray:
        """q̇ (3,) on leg 0–3 at q (m, m, rad per unit leg time): s·drive, α·turn, −s·drive, −α·turn."""
        drive, turn = MANOEUVRE_LEGS[leg]
        return drive * self.drive_distance_m * drive_field(q) + turn * self.turn_angle_rad * turn_field(q)

    def configuration(self, start: np.ndarray, progress: float) -> tuple[np.ndarray, np.ndarray]:
        """(q, q̇) (3,) after ``progress`` legs (0–4, unit leg time each) from ``start`` = (x, y, ψ).

        Exact: q̇ is constant along each leg (ψ does not change while driving, x and y not while turning).
        """
        if not 0.0 <= progress <= 4.0:
            raise ValueError(f"progress must lie in [0, 4] legs (got {progress!r})")
        leg = min(int(progress), 3)
        q = np.asarray(start, dtype=float).copy()
        for done in range(leg):
            q = q + self.leg_velocity(done, q)
        velocity = self.leg_velocity(leg, q)
        return q + (progress - leg) * velocity, velocity

    def net_displacement(self, heading_rad: float) -> np.ndarray:
        """End minus start (3,) (m, m, rad) of one manoeuvre begun at heading ψ₀: s (cos ψ₀ − cos(ψ₀+α), sin ψ₀ −
        sin(ψ₀+α), 0)."""
        s, alpha = self.drive_distance_m, self.turn_angle_rad
        return s * np.array(
            [
                math.cos(heading_rad) - math.cos(heading_rad + alpha),
                math.sin(heading_rad) - math.sin(heading_rad + alpha),
                0.0,
            ]
        )

    @property
    def sideways_drift_m(self) -> float:
        """Exact net step along the bracket direction (to the right of the heading): s sin α (m)."""
        return self.drive_distance_m * math.sin(self.turn_angle_rad)

    @property
    def forward_drift_m(self) -> float:
        """Exact net step along the heading: s (1 − cos α) (m)."""
        return self.drive_distance_m * (1.0 - math.cos(self.turn_angle_rad))

    def leading_order_displacement(self, heading_rad: float) -> np.ndarray:
        """s α [drive, turn](q₀) (3,): the net motion to second order; with s = L ε and α = ε it is ε² L [drive,
        turn]."""
        return self.drive_distance_m * self.turn_angle_rad * drive_turn_bracket(np.array([0.0, 0.0, heading_rad]))
