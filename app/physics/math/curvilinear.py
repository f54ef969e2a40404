"""Cylindrical and spherical coordinates of a moving particle: unit vectors and components.

Fixed frame XYZ, +Z up; lengths in m, angles in rad, time in s.

Cylindrical (R, θ, z): R ≥ 0 is the distance from the Z axis, θ the azimuth
measured from +X toward +Y about +Z. Unit vectors (a right-handed triad)::

    e_R = (cos θ, sin θ, 0),  e_θ = (−sin θ, cos θ, 0),  e_z = (0, 0, 1)
    v = Ṙ e_R + R θ̇ e_θ + ż e_z
    a = (R̈ − R θ̇²) e_R + (R θ̈ + 2 Ṙ θ̇) e_θ + z̈ e_z

Spherical (r, φ, θ): r ≥ 0 is the distance from the origin, φ ∈ [0, π] the
polar angle measured down from +Z, and θ the same azimuth as above (so e_θ is
the same vector in both systems). Unit vectors (right-handed in the order
e_r, e_φ, e_θ)::

    e_r = (sin φ cos θ, sin φ sin θ, cos φ),  e_φ = (cos φ cos θ, cos φ sin θ, −sin φ)
    v = ṙ e_r + r φ̇ e_φ + r sin φ θ̇ e_θ
    a = (r̈ − r φ̇² − r sin²φ θ̇²) e_r + (r φ̈ + 2 ṙ φ̇ − r sin φ cos φ θ̇²) e_φ
        + (r sin φ θ̈ + 2 ṙ θ̇ sin φ + 2 r φ̇ θ̇ cos φ) e_θ

The coordinates and their first two rates are found from the Cartesian
position, velocity and acceleration (e.g. Ṙ = (x ẋ + y ẏ)/R), and the
components are then formed with the formulas above, so that a test can check
the formulas by rebuilding the Cartesian v and a from them.

Where a coordinate is singular the quantities that depend on it are NaN:
on the Z axis (R = 0) θ, e_R, e_θ and the spherical e_φ are undefined, and at
the origin (r = 0) every spherical direction is.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Distances below this fraction of the length scale count as zero (on the axis, at the origin).
AXIS_TOLERANCE = 1e-9


@dataclass(frozen=True)
class CurvilinearKinematics:
    """Coordinates, rates, unit vectors and components at N instants.

    ``coordinates``, ``rates``, ``second_rates``: (N, 3) in the system's order
    ((R, θ, z) or (r, φ, θ)); ``unit_vectors``: (N, 3, 3), row k the k-th unit
    vector on XYZ; ``velocity``/``acceleration``: (N, 3) components on those
    unit vectors (m/s, m/s²). ``names`` name the three coordinates.
    """

    names: tuple[str, str, str]
    coordinates: np.ndarray
    rates: np.ndarray
    second_rates: np.ndarray
    unit_vectors: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray


def _axis_rates(p: np.ndarray, v: np.ndarray, a: np.ndarray, defined: np.ndarray):
    """R, Ṙ, R̈, θ, θ̇, θ̈ from Cartesian p, v, a (NaN where ``defined`` is False)."""
    x, y = p[:, 0], p[:, 1]
    vx, vy = v[:, 0], v[:, 1]
    ax, ay = a[:, 0], a[:, 1]
    with np.errstate(all="ignore"):
        R = np.hypot(x, y)
        R_safe = np.where(defined, R, np.nan)
        R_dot = (x * vx + y * vy) / R_safe
        theta = np.where(defined, np.arctan2(y, x), np.nan)
        theta_dot = (x * vy - y * vx) / R_safe**2
        R_ddot = (vx**2 + vy**2 + x * ax + y * ay) / R_safe - R_dot**2 / R_safe
        theta_ddot = (x * ay - y * ax) / R_safe**2 - 2.0 * R_dot * theta_dot / R_safe
    return R, R_dot, R_ddot, theta, theta_dot, theta_ddot


def cylindrical(
    position_m: np.ndarray, velocity_m_s: np.ndarray, acceleration_m_s2: np.ndarray, *, length_scale_m: float
) -> CurvilinearKinematics:
    """Cylindrical (R, θ, z) description of a motion given on XYZ (arrays (N, 3))."""
    p, v, a = (np.atleast_2d(np.asarray(arr, dtype=float)) for arr in (position_m, velocity_m_s, acceleration_m_s2))
    off_axis = np.hypot(p[:, 0], p[:, 1]) > AXIS_TOLERANCE * length_scale_m
    R, R_dot, R_ddot, theta, theta_dot, theta_ddot = _axis_rates(p, v, a, off_axis)
    c, s = np.cos(theta), np.sin(theta)
    zeros, ones = np.zeros_like(R), np.ones_like(R)
    e_R = np.stack([c, s, zeros], axis=1)
    e_theta = np.stack([-s, c, zeros], axis=1)
    e_R[~off_axis] = e_theta[~off_axis] = np.nan
    e_z = np.stack([zeros, zeros, ones], axis=1)
    velocity = np.stack([R_dot, R * theta_dot, v[:, 2]], axis=1)
    acceleration = np.stack([R_ddot - R * theta_dot**2, R * theta_ddot + 2.0 * R_dot * theta_dot, a[:, 2]], axis=1)
    return CurvilinearKinematics(
        names=("R", "theta", "z"),
        coordinates=np.stack([R, theta, p[:, 2]], axis=1),
        rates=np.stack([R_dot, theta_dot, v[:, 2]], axis=1),
        second_rates=np.stack([R_ddot, theta_ddot, a[:, 2]], axis=1),
        unit_vectors=np.stack([e_R, e_theta, e_z], axis=1),
        velocity=velocity,
        acceleration=acceleration,
    )


def spherical(
    position_m: np.ndarray, velocity_m_s: np.ndarray, acceleration_m_s2: np.ndarray, *, length_scale_m: float
) -> CurvilinearKinematics:
    """Spherical (r, φ, θ) description (φ polar from +Z, θ azimuth) of a motion given on XYZ."""
    p, v, a = (np.atleast_2d(np.asarray(arr, dtype=float)) for arr in (position_m, velocity_m_s, acceleration_m_s2))
    tolerance = AXIS_TOLERANCE * length_scale_m
    r = np.linalg.norm(p, axis=1)
    off_origin = r > tolerance
    off_axis = np.hypot(p[:, 0], p[:, 1]) > tolerance
    R, R_dot, R_ddot, theta, theta_dot, theta_ddot = _axis_rates(p, v, a, off_axis)
    z, z_dot, z_ddot = p[:, 2], v[:, 2], a[:, 2]
    with np.errstate(all="ignore"):
        r_safe = np.where(off_origin, r, np.nan)
        r_dot = np.einsum("ij,ij->i", p, v) / r_safe
        r_ddot = (np.einsum("ij,ij->i", v, v) + np.einsum("ij,ij->i", p, a)) / r_safe - r_dot**2 / r_safe
        phi = np.where(off_origin, np.arctan2(R, z), np.nan)
        # φ = atan2(R, z): φ̇ = (z Ṙ − R ż)/r², φ̈ = (z R̈ − R z̈)/r² − 2 ṙ φ̇ / r (needs Ṙ, so off the axis).
        phi_dot = (z * R_dot - R * z_dot) / r_safe**2
        phi_ddot = (z * R_ddot - R * z_ddot) / r_safe**2 - 2.0 * r_dot * phi_dot / r_safe
    sp, cp, st, ct = np.sin(phi), np.cos(phi), np.sin(theta), np.cos(theta)
    # e_r is defined on the axis too (it is ±Z there); only the origin leaves it undefined.
    e_r = np.where(off_origin[:, None], p / r_safe[:, None], np.nan)
    e_phi = np.stack([cp * ct, cp * st, -sp], axis=1)
    e_theta = np.stack([-st, ct, np.zeros_like(st)], axis=1)
    e_phi[~off_axis] = e_theta[~off_axis] = np.nan
    velocity = np.stack([r_dot, r * phi_dot, r * sp * theta_dot], axis=1)
    acceleration = np.stack(
        [
            r_ddot - r * phi_dot**2 - r * sp**2 * theta_dot**2,
            r * phi_ddot + 2.0 * r_dot * phi_dot - r * sp * cp * theta_dot**2,
            r * sp * theta_ddot + 2.0 * r_dot * theta_dot * sp + 2.0 * r * phi_dot * theta_dot * cp,
        ],
        axis=1,
    )
    return CurvilinearKinematics(
        names=("r", "phi", "theta"),
        coordinates=np.stack([r, phi, theta], axis=1),
        rates=np.stack([r_dot, phi_dot, theta_dot], axis=1),
        second_rates=np.stack([r_ddot, phi_ddot, theta_ddot], axis=1),
        unit_vectors=np.stack([e_r, e_phi, e_theta], axis=1),
        velocity=velocity,
        acceleration=acceleration,
    )


def unwrapped_azimuth(angle_rad: np.ndarray) -> np.ndarray:
    """An azimuth (rad) made continuous across ±π, left as it is where it is undefined (NaN on the axis)."""
    finite = np.isfinite(angle_rad)
    out = angle_rad.copy()
    out[finite] = np.unwrap(angle_rad[finite])
    return out


def curvilinear_series(
    position_m: np.ndarray, velocity_m_s: np.ndarray, acceleration_m_s2: np.ndarray, *, length_scale_m: float
) -> dict[str, np.ndarray]:
    """A path's cylindrical and spherical description as simulate series, by the names the scenes use:
    R, theta (unwrapped), v_R, v_theta, v_z, a_R, a_theta, a_z and r, phi, v_r, v_phi, a_r, a_phi (m, rad, m/s,
    m/s²)."""
    cyl = cylindrical(position_m, velocity_m_s, acceleration_m_s2, length_scale_m=length_scale_m)
    sph = spherical(position_m, velocity_m_s, acceleration_m_s2, length_scale_m=length_scale_m)
    return {
        "R": cyl.coordinates[:, 0],
        "theta": unwrapped_azimuth(cyl.coordinates[:, 1]),
        "v_R": cyl.velocity[:, 0],
        "v_theta": cyl.velocity[:, 1],
        "v_z": cyl.velocity[:, 2],
        "a_R": cyl.acceleration[:, 0],
        "a_theta": cyl.acceleration[:, 1],
        "a_z": cyl.acceleration[:, 2],
        "r": sph.coordinates[:, 0],
        "phi": sph.coordinates[:, 1],
        "v_r": sph.velocity[:, 0],
        "v_phi": sph.velocity[:, 1],
        "a_r": sph.acceleration[:, 0],
        "a_phi": sph.acceleration[:, 1],
    }
