"""A particle on a chosen path described in cylindrical or spherical coordinates.

Frame: the fixed frame XYZ, +Z up; lengths in m, angles in rad, time t in s.
Every path turns about Z at a constant azimuth rate θ̇ = ω, θ = θ₀ + ω t, and
is set by a length a (m) and an angle β:

* ``helix``: R = a, z = a θ tan β (β: the climb angle; β = 0 is a circle, polar coordinates);
  two turns, θ from 0 to 4π.
* ``conical-spiral``: R = a (1 + θ/2π), z = R cot β: on the cone of half-angle β
  about Z with its vertex at the origin (so φ = β); R grows by a each turn; three
  turns from θ = 0. β = 90° lays it flat in z = 0 (polar coordinates).
* ``latitude-circle``: r = a, φ = β (the polar angle, measured from +Z): one turn.
* ``loxodrome``: on the sphere r = a, crossing every meridian at the bearing β
  from north: the latitude is λ = gd(θ cot β) (gd the Gudermannian: cos λ =
  sech(θ cot β), sin λ = tanh(θ cot β)), so φ = π/2 − λ; from latitude −80° to
  +80° (at most two turns each side of θ = 0, which is all of it once β is near
  90°, where the loxodrome is nearly the equator).

Only the Cartesian position is written here, as a sympy expression; its first
two time derivatives are exact (``sympy.diff``) and compiled once per path
(``lambdify`` with a, ω, β and θ₀ as arguments). The cylindrical and spherical
components are then found from the Cartesian motion by
:mod:`app.physics.math.curvilinear`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np
import sympy

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.math.curvilinear import CurvilinearKinematics, curvilinear_series, cylindrical, spherical

PATHS = ("helix", "conical-spiral", "latitude-circle", "loxodrome")
FRAMES = ("cylindrical", "spherical")
#: The loxodrome runs between these latitudes (rad): it never reaches a pole, where its speed would vanish.
LOXODROME_LATITUDE_RAD = math.radians(80.0)
#: The loxodrome's azimuth turns at most this far (rad) each side of θ = 0.
LOXODROME_MAX_AZIMUTH_RAD = 4.0 * math.pi
#: Smallest and largest β (deg) each path takes (beyond them the path is not a curve, or leaves every bound).
PATH_ANGLE_LIMITS_DEG = {
    "helix": (0.0, 60.0, "steeper, two turns would climb more than 20 times the radius; at 90° it is a vertical line"),
    "conical-spiral": (5.0, 90.0, "a cone of half-angle 0° closes onto the Z axis"),
    "latitude-circle": (0.0, 90.0, ""),
    "loxodrome": (10.0, 90.0, "a bearing near 0° runs up a meridian straight into the pole"),
}
_T, _A, _OMEGA, _BETA, _THETA0 = sympy.symbols("t a omega beta theta0", real=True)


def _position(path: str) -> tuple[sympy.Expr, sympy.Expr, sympy.Expr]:
    """x, y, z (m) of ``path`` in t, a, ω, β, θ₀."""
    theta = _THETA0 + _OMEGA * _T
    if path == "helix":
        return _A * sympy.cos(theta), _A * sympy.sin(theta), _A * theta * sympy.tan(_BETA)
    if path == "conical-spiral":
        radius = _A * (1 + theta / (2 * sympy.pi))
        return radius * sympy.cos(theta), radius * sympy.sin(theta), radius * sympy.cos(_BETA) / sympy.sin(_BETA)
    if path == "latitude-circle":
        return (
            _A * sympy.sin(_BETA) * sympy.cos(theta),
            _A * sympy.sin(_BETA) * sympy.sin(theta),
            _A * sympy.cos(_BETA),
        )
    u = theta * sympy.cos(_BETA) / sympy.sin(_BETA)
    cos_latitude, sin_latitude = 1 / sympy.cosh(u), sympy.tanh(u)
    return _A * cos_latitude * sympy.cos(theta), _A * cos_latitude * sympy.sin(theta), _A * sin_latitude


@lru_cache(maxsize=len(PATHS))
def _compiled(path: str) -> Callable[..., list]:
    """f(t, a, ω, β, θ₀) -> [x, y, z, ẋ, ẏ, ż, ẍ, ÿ, z̈] (numpy, vectorised in t)."""
    position = _position(path)
    velocity = [sympy.diff(expr, _T) for expr in position]
    acceleration = [sympy.diff(expr, _T) for expr in velocity]
    return sympy.lambdify(
        (_T, _A, _OMEGA, _BETA, _THETA0), [*position, *velocity, *acceleration], modules="numpy", cse=True
    )


@dataclass(frozen=True)
class CoordinatePath:
    """One path with its numbers: ``size_m`` a, ``azimuth_rate_rad_s`` ω, ``path_angle_rad`` β."""

    path: str
    size_m: float
    azimuth_rate_rad_s: float
    path_angle_rad: float

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> CoordinatePath:
        return cls(
            params["path"], params["size_m"], params["azimuth_rate_rad_s"], math.radians(params["path_angle_deg"])
        )

    @property
    def start_azimuth_rad(self) -> float:
        """θ₀ (rad): 0, except the loxodrome, which starts at its southern end."""
        if self.path != "loxodrome":
            return 0.0
        return -self.azimuth_span_rad / 2.0

    @property
    def azimuth_span_rad(self) -> float:
        """How far θ turns in one run (rad)."""
        if self.path == "helix":
            return 4.0 * math.pi
        if self.path == "conical-spiral":
            return 6.0 * math.pi
        if self.path == "latitude-circle":
            return 2.0 * math.pi
        # θ cot β = gd⁻¹(λ) = artanh(sin λ): the azimuth at which the loxodrome reaches latitude λ.
        half = math.tan(self.path_angle_rad) * math.atanh(math.sin(LOXODROME_LATITUDE_RAD))
        return 2.0 * min(half, LOXODROME_MAX_AZIMUTH_RAD)

    @property
    def run_s(self) -> float:
        """Duration (s) of one run along the path."""
        return self.azimuth_span_rad / self.azimuth_rate_rad_s

    def at(self, t_s: np.ndarray | float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Position (m), velocity (m/s), acceleration (m/s²) on XYZ at times ``t_s`` (s), each (N, 3)."""
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        values = _compiled(self.path)(
            t, self.size_m, self.azimuth_rate_rad_s, self.path_angle_rad, self.start_azimuth_rad
        )
        columns = np.stack([np.broadcast_to(np.asarray(v, dtype=float), t.shape) for v in values], axis=1)
        return columns[:, 0:3], columns[:, 3:6], columns[:, 6:9]

    @property
    def length_scale_m(self) -> float:
        """The path's size (m), for deciding when the particle is on the Z axis or at the origin."""
        return self.size_m

    def describe(
        self, frame: str, t_s: np.ndarray | float
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, CurvilinearKinematics]:
        """Cartesian position, velocity, acceleration and their ``frame`` ('cylindrical' or 'spherical') description."""
        position, velocity, acceleration = self.at(t_s)
        describe = cylindrical if frame == "cylindrical" else spherical
        return (
            position,
            velocity,
            acceleration,
            describe(position, velocity, acceleration, length_scale_m=self.length_scale_m),
        )


def _check(values: Mapping[str, Any]) -> None:
    low, high, why = PATH_ANGLE_LIMITS_DEG[values["path"]]
    beta = values["path_angle_deg"]
    if not low <= beta <= high:
        reason = f" ({why})" if why else ""
        raise ParameterError(
            "path_angle_deg", f"β must be from {low:g}° to {high:g}° for the {values['path']} (got {beta:g}°){reason}"
        )


PARAMETERS = ParameterSet(
    (
        Parameter(
            "path",
            "",
            "helix",
            kind="choice",
            choices=PATHS,
            label="path",
            description=(
                "The path: a helix, a spiral on a cone, a circle of latitude on a sphere, or a loxodrome "
                "(rhumb line) on a sphere"
            ),
        ),
        Parameter(
            "size_m",
            "m",
            1.0,
            0.1,
            3.0,
            "a: the helix's radius, the spiral's growth of R per turn (and its starting R), or the sphere's radius",
            "a",
            step=0.01,
        ),
        Parameter(
            "azimuth_rate_rad_s",
            "rad/s",
            1.0,
            0.1,
            3.0,
            "θ̇: the constant rate at which the azimuth θ turns about Z",
            "θ̇",
            step=0.05,
        ),
        Parameter(
            "path_angle_deg",
            "deg",
            15.0,
            0.0,
            90.0,
            "β: the helix's climb angle, the cone's half-angle, the circle's polar angle φ, or the loxodrome's "
            "bearing from north",
            "β",
            step=1,
        ),
    ),
    check=_check,
)


class ParticleOnCoordinatePath(ClosedFormModel):
    """A particle on a path given in cylindrical or spherical coordinates: both sets of components."""

    parameters = PARAMETERS
    series_units = {
        "x": "m",
        "y": "m",
        "z": "m",
        "speed": "m/s",
        "acceleration_magnitude": "m/s^2",
        "R": "m",
        "theta": "rad",
        "v_R": "m/s",
        "v_theta": "m/s",
        "v_z": "m/s",
        "a_R": "m/s^2",
        "a_theta": "m/s^2",
        "a_z": "m/s^2",
        "r": "m",
        "phi": "rad",
        "v_r": "m/s",
        "v_phi": "m/s",
        "a_r": "m/s^2",
        "a_phi": "m/s^2",
    }
    description = (
        "x, y, z of the path in closed form, differentiated exactly (sympy); cylindrical and spherical "
        "components from R = √(x²+y²), θ = atan2(y, x), r = |r|, φ = atan2(R, z) and their rates"
    )

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        path = CoordinatePath.from_params(params)
        position, velocity, acceleration = path.at(t_s)
        series = {
            "x": position[:, 0],
            "y": position[:, 1],
            "z": position[:, 2],
            "speed": np.linalg.norm(velocity, axis=1),
            "acceleration_magnitude": np.linalg.norm(acceleration, axis=1),
            **curvilinear_series(position, velocity, acceleration, length_scale_m=path.length_scale_m),
        }
        warning = ""
        if t_s[-1] > path.run_s:
            warning = (
                f"One run along the path lasts {path.run_s:.4g} s; after it the formulas go on past the path's end."
            )
        return ClosedFormSolution(series=series, warning=warning)
