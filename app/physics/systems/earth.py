"""The rotating Earth as a reference frame: constants and the local frame at a latitude.

Frame used by every Earth scene: the **local frame** at a point on the ground at
latitude λ, with x east, y north and z up (along the plumb line, so +Z is up as
everywhere in Dynamics Lab). The Earth turns at Ω about its polar axis, which in
local components is ``Ω (0, cos λ, sin λ)``: it points north and, in the
northern hemisphere, upwards.

Seen from this frame a body of mass m obeys ``m a = F + m g − 2 m Ω × v``: the
gravitational pull and the centrifugal term ``−Ω × (Ω × r)`` of the Earth's
rotation are measured together as the weight ``m g`` along the plumb line, so
only the Coriolis term ``−2 Ω × v`` remains to be written. (That centrifugal
term relative to a point of a laboratory is ``Ω² × size``, about 5e-9 m/s² per
metre: negligible beside g.)
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.core.parameters import Parameter

#: The Earth's rotation rate relative to the stars (one sidereal day, 86164.1 s), rad/s.
EARTH_RATE_RAD_S = 7.292115e-5
#: Standard gravity (m/s²): weight per unit mass along the plumb line, centrifugal part included.
STANDARD_GRAVITY_M_S2 = 9.80665
SECONDS_PER_HOUR = 3600.0


def latitude_parameter(default_deg: float) -> Parameter:
    """The ``latitude_deg`` control shared by the Earth scenes (north positive)."""
    return Parameter(
        "latitude_deg",
        "deg",
        default_deg,
        -90.0,
        90.0,
        "Latitude of the laboratory: positive north of the equator, negative south",
        "latitude λ",
        step=0.05,
    )


def earth_rate_local(latitude_deg: float, rate_rad_s: float = EARTH_RATE_RAD_S) -> np.ndarray:
    """The Earth's angular velocity in the local frame (east, north, up), rad/s, shape (3,)."""
    lam = math.radians(latitude_deg)
    return np.array([0.0, rate_rad_s * math.cos(lam), rate_rad_s * math.sin(lam)])


def vertical_earth_rate_rad_s(latitude_deg: float, rate_rad_s: float = EARTH_RATE_RAD_S) -> float:
    """``Ω sin λ`` (rad/s): the part of the Earth's rotation about the local vertical.

    Positive north of the equator, where the ground turns counterclockwise as
    seen from above, so a freely swinging plane turns clockwise relative to it.
    """
    return rate_rad_s * math.sin(math.radians(latitude_deg))


def coriolis_acceleration(omega_local: np.ndarray, velocity: np.ndarray) -> np.ndarray:
    """``−2 Ω × v`` (m/s², local frame) for velocities ``v`` (m/s, shape (..., 3)) relative to the ground."""
    return -2.0 * np.cross(np.asarray(omega_local, dtype=float), np.asarray(velocity, dtype=float))


def bearing_deg_from_east_north(east: np.ndarray | float, north: np.ndarray | float) -> np.ndarray | float:
    """Compass bearing of a horizontal direction (deg clockwise from north, in [0, 360))."""
    return np.mod(np.degrees(np.arctan2(east, north)), 360.0)


def direction_from_bearing(bearing_deg: float) -> np.ndarray:
    """Unit horizontal vector (east, north, up) for a compass bearing in degrees clockwise from north."""
    b = math.radians(bearing_deg)
    return np.array([math.sin(b), math.cos(b), 0.0])
