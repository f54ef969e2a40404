"""A body dropped (or thrown) on the rotating Earth: exact flight and the eastward deflection.

Frame: the local frame of :mod:`app.physics.systems.earth` (x east, y north, z up),
origin on the ground at the foot of the plumb line through the release point,
which is at height h. In that frame, with a uniform g along the plumb line,

``r̈ = −g Z − 2 Ω × ṙ``,

a linear equation with constant coefficients, solved **exactly**: the velocity
turns about Ω at the rate −2|Ω| while gravity adds to it, so with
``K = [Ω̂]×`` and ``c = −2|Ω|``

* ``v(t) = R(t) v₀ + S₁(t) g``, ``r(t) = r₀ + S₁(t) v₀ + S₂(t) g``,
* ``R = I + sin(ct) K + (1 − cos ct) K²``,
* ``S₁ = ∫R = t I + (1 − cos ct)/c K + (t − sin(ct)/c) K²``,
* ``S₂ = ∫S₁ = ½t² I + (t − sin(ct)/c)/c K + (½t² − (1 − cos ct)/c²) K²``,

where the small differences are evaluated by series so that the second-order
(southward) part, a millionth of the height, keeps full relative accuracy.

Expanding in powers of Ω instead (:func:`series_position`) gives the familiar
results for a drop from rest, with ``t = √(2h/g)``: the body lands
``⅓ Ω g t³ cos λ`` east of the plumb line, and (second order)
``⅙ Ω² g t⁴ sin λ cos λ`` towards the equator.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.optimize import brentq

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution, Event
from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.systems.earth import EARTH_RATE_RAD_S, STANDARD_GRAVITY_M_S2, earth_rate_local, latitude_parameter

PARAMETERS = ParameterSet(
    (
        Parameter(
            "height_m",
            "m",
            100.0,
            1.0,
            2000.0,
            "Height h of the release point above the ground (top of the tower)",
            "drop height h",
            scale="log",
        ),
        latitude_parameter(45.0),
        Parameter(
            "launch_velocity_m_s",
            "m/s",
            [0.0, 0.0, 0.0],
            -100.0,
            100.0,
            "Velocity relative to the ground at release, components (east, north, up); zero for a drop from rest",
            "launch velocity (E, N, up)",
            kind="vector",
        ),
        Parameter(
            "g_m_s2",
            "m/s²",
            STANDARD_GRAVITY_M_S2,
            1.0,
            30.0,
            "Gravitational acceleration along the plumb line",
            "g",
            step=0.001,
        ),
    ),
)


# -- small-argument-safe pieces of the exact solution ------------------------------------
def _one_minus_cos(x: np.ndarray) -> np.ndarray:
    return 2.0 * np.sin(0.5 * x) ** 2


def _x_minus_sin(x: np.ndarray) -> np.ndarray:
    """x − sin x, accurate for small x (series below |x| = 0.1)."""
    x = np.asarray(x, dtype=float)
    x2 = x * x
    series = x * x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0)))
    return np.where(np.abs(x) < 0.1, series, x - np.sin(x))


def _half_x2_minus_one_minus_cos(x: np.ndarray) -> np.ndarray:
    """x²/2 − (1 − cos x), accurate for small x (series below |x| = 0.1)."""
    x = np.asarray(x, dtype=float)
    x2 = x * x
    series = x2 * x2 / 24.0 * (1.0 - x2 / 30.0 * (1.0 - x2 / 56.0 * (1.0 - x2 / 90.0)))
    return np.where(np.abs(x) < 0.1, series, 0.5 * x2 - _one_minus_cos(x))


def exact_state(
    t_s: np.ndarray, *, r0_m: np.ndarray, v0_m_s: np.ndarray, omega_local: np.ndarray, g_m_s2: float
) -> tuple[np.ndarray, np.ndarray]:
    """Exact position (m) and velocity (m/s), local frame, shape (N, 3) each, of ``r̈ = −g Z − 2 Ω × ṙ``."""
    t = np.atleast_1d(np.asarray(t_s, dtype=float))[:, None]
    r0 = np.asarray(r0_m, dtype=float)
    v0 = np.asarray(v0_m_s, dtype=float)
    gravity = np.array([0.0, 0.0, -g_m_s2])
    rate = float(np.linalg.norm(omega_local))
    if rate == 0.0:
        return r0 + v0 * t + 0.5 * gravity * t * t, v0 + gravity * t
    axis = np.asarray(omega_local, dtype=float) / rate
    c = -2.0 * rate
    x = c * t

    def K(v):
        return np.cross(axis, v)

    def K2(v):
        return np.cross(axis, np.cross(axis, v))

    # R v = v + sin(x) K v + (1 − cos x) K² v, and the integrals S1, S2 term by term.
    def R(v):
        return v + np.sin(x) * K(v) + _one_minus_cos(x) * K2(v)

    def S1(v):
        return t * v + (_one_minus_cos(x) / c) * K(v) + (_x_minus_sin(x) / c) * K2(v)

    def S2(v):
        return (
            0.5 * t * t * v + (_x_minus_sin(x) / (c * c)) * K(v) + (_half_x2_minus_one_minus_cos(x) / (c * c)) * K2(v)
        )

    position = r0 + S1(v0) + S2(gravity)
    velocity = R(v0) + S1(gravity)
    return position, velocity


def series_position(
    t_s: np.ndarray, *, r0_m: np.ndarray, v0_m_s: np.ndarray, omega_local: np.ndarray, g_m_s2: float, order: int
) -> np.ndarray:
    """Position (m, local frame, (N, 3)) expanded in powers of Ω up to ``order`` (0, 1 or 2).

    ``r = r₀ + u t − ½ g t² Z``
    ``  − (Ω × u) t² + ⅓ g t³ (Ω × Z)``                      (first order)
    ``  + ⅔ t³ Ω × (Ω × u) − ⅙ g t⁴ Ω × (Ω × Z)``           (second order)
    """
    if order not in (0, 1, 2):
        raise ValueError(f"order must be 0, 1 or 2 (got {order!r})")
    t = np.atleast_1d(np.asarray(t_s, dtype=float))[:, None]
    u = np.asarray(v0_m_s, dtype=float)
    omega = np.asarray(omega_local, dtype=float)
    up = np.array([0.0, 0.0, 1.0])
    r = np.asarray(r0_m, dtype=float) + u * t - 0.5 * g_m_s2 * t * t * up
    if order >= 1:
        r = r - np.cross(omega, u) * t**2 + (g_m_s2 / 3.0) * np.cross(omega, up) * t**3
    if order >= 2:
        r = (
            r
            + (2.0 / 3.0) * np.cross(omega, np.cross(omega, u)) * t**3
            - (g_m_s2 / 6.0) * np.cross(omega, np.cross(omega, up)) * t**4
        )
    return r


@dataclass(frozen=True)
class Flight:
    """One flight from release to the ground, under the exact rotating-frame equations."""

    r0_m: np.ndarray
    v0_m_s: np.ndarray
    omega_local: np.ndarray
    g_m_s2: float

    @classmethod
    def from_params(cls, params: Mapping[str, Any], *, earth_rate_rad_s: float = EARTH_RATE_RAD_S) -> Flight:
        return cls(
            r0_m=np.array([0.0, 0.0, params["height_m"]]),
            v0_m_s=np.asarray(params["launch_velocity_m_s"], dtype=float),
            omega_local=earth_rate_local(params["latitude_deg"], earth_rate_rad_s),
            g_m_s2=params["g_m_s2"],
        )

    def state(self, t_s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Exact position (m) and velocity (m/s), local frame, each (N, 3)."""
        return exact_state(t_s, r0_m=self.r0_m, v0_m_s=self.v0_m_s, omega_local=self.omega_local, g_m_s2=self.g_m_s2)

    def position_without_rotation(self, t_s: np.ndarray) -> np.ndarray:
        """Where the body would be (m, (N, 3)) if the Earth did not turn: ``r₀ + u t − ½ g t² Z``."""
        return self.series(t_s, order=0)

    def series(self, t_s: np.ndarray, *, order: int) -> np.ndarray:
        return series_position(
            t_s, r0_m=self.r0_m, v0_m_s=self.v0_m_s, omega_local=self.omega_local, g_m_s2=self.g_m_s2, order=order
        )

    def fall_time_without_rotation_s(self) -> float:
        """Positive root of ``h + u_z t − ½ g t² = 0`` (s)."""
        h, uz, g = float(self.r0_m[2]), float(self.v0_m_s[2]), self.g_m_s2
        return (uz + math.sqrt(uz * uz + 2.0 * g * h)) / g

    def landing_time_s(self, *, order: int | None = None) -> float:
        """Time (s) the body reaches the ground: exact (``order=None``) or for the series of that order."""

        def height(t: float) -> float:
            if order is None:
                return float(self.state(np.array([t]))[0][0, 2])
            return float(self.series(np.array([t]), order=order)[0, 2])

        t0 = self.fall_time_without_rotation_s()
        low, high = 0.5 * t0, 1.5 * t0
        while height(high) > 0.0:  # the rotation delays the landing by far less than this
            high *= 1.5
        while low > 0.0 and height(low) < 0.0:
            low *= 0.5
        return brentq(height, low, high, xtol=1e-15 * t0, rtol=4 * np.finfo(float).eps, maxiter=200)

    def landing_point(self, *, order: int | None = None) -> np.ndarray:
        """Landing point (m, local frame, (3,)): exact or from the series of that order."""
        t = self.landing_time_s(order=order)
        if order is None:
            return self.state(np.array([t]))[0][0]
        return self.series(np.array([t]), order=order)[0]

    def deflection(self, *, order: int | None = None) -> np.ndarray:
        """Landing point minus the landing point without the Earth's rotation (m, (east, north, up))."""
        return self.landing_point(order=order) - self.landing_point(order=0)


def drop_east_deflection_first_order_m(
    *, height_m: float, latitude_deg: float, g_m_s2: float, earth_rate_rad_s: float = EARTH_RATE_RAD_S
) -> float:
    """The textbook ``⅓ Ω g t³ cos λ`` with ``t = √(2h/g)`` (m east), for a drop from rest."""
    t = math.sqrt(2.0 * height_m / g_m_s2)
    return earth_rate_rad_s * g_m_s2 * t**3 * math.cos(math.radians(latitude_deg)) / 3.0


def drop_south_deflection_second_order_m(
    *, height_m: float, latitude_deg: float, g_m_s2: float, earth_rate_rad_s: float = EARTH_RATE_RAD_S
) -> float:
    """``⅙ Ω² g t⁴ sin λ cos λ`` with ``t = √(2h/g)`` (m south), for a drop from rest (uniform g)."""
    t = math.sqrt(2.0 * height_m / g_m_s2)
    lam = math.radians(latitude_deg)
    return earth_rate_rad_s**2 * g_m_s2 * t**4 * math.sin(lam) * math.cos(lam) / 6.0


class EastwardDeflection(ClosedFormModel):
    """Position and deflection of the dropped or thrown body until it lands (then it stays there)."""

    parameters = PARAMETERS
    description = "exact solution of the linear rotating-frame equations r̈ = −g Z − 2 Ω × ṙ (Rodrigues form)"
    series_units = {"east": "m", "north": "m", "up": "m", "east_deflection": "m", "south_deflection": "m"}
    invariant_units = {"jacobi_integral": "J/kg"}

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        """Series at ``t_s``; from the landing instant on, every series holds its value at landing."""
        flight = Flight.from_params(params)
        t_land = flight.landing_time_s()
        t = np.minimum(np.asarray(t_s, dtype=float), t_land)
        position, velocity = flight.state(t)
        deviation = position - flight.position_without_rotation(t)
        events = []
        if float(np.max(t_s)) >= t_land:
            deflection = flight.deflection()
            events.append(
                Event(
                    t_land,
                    "landed",
                    f"lands {1000 * deflection[0]:.3f} mm east and {-1000 * deflection[1]:.3f} mm south of where it "
                    f"would land if the Earth did not turn; the series hold their landing values from here on",
                )
            )
        return ClosedFormSolution(
            series={
                "east": position[:, 0],
                "north": position[:, 1],
                "up": position[:, 2],
                "east_deflection": deviation[:, 0],
                "south_deflection": -deviation[:, 1],
            },
            invariants={"jacobi_integral": 0.5 * np.sum(velocity**2, axis=-1) + flight.g_m_s2 * position[:, 2]},
            events=events,
        )
