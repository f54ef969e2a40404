"""Worked example ``helix-cylindrical-spherical`` (section 2.3): one helix described in cylindrical and in spherical
coordinates.

Frame: the fixed frame XYZ, +Z up; lengths in m, angles in rad, time in s. The path is the ``helix`` of
:mod:`~app.physics.systems.ch02.coordinate_paths` (the curvilinear-coordinates scene): radius a, climb angle β,
azimuth turning at the constant rate ω from θ = 0 at t = 0::

    R = a,   θ = ω t,   z = c θ,   c = a tan β (m per rad).

Cylindrical (R, θ, z) components follow at once. Spherical (r, φ, θ), φ measured down from +Z, need the chain
rule: r = √(a² + z²), φ = atan2(a, z), and with ż = c ω, z̈ = 0::

    ṙ = z ż / r,  r̈ = a² ż² / r³,  φ̇ = −a ż / r²,  φ̈ = 2 a z ż² / r⁴.

The check is a second and third method: both descriptions, put back on XYZ with their unit vectors, must give the
velocity and acceleration found by differentiating x = a cos ωt, y = a sin ωt, z = c ω t directly.

Refused (ParameterError naming ``path_angle_deg``): β = 90°, where tan β is infinite: a helix cannot climb
vertically and still go round.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch02.coordinate_paths import PARAMETERS as SCENE_PARAMETERS

#: Steepest climb angle (deg) the helix takes: at 90° it would be a vertical line with tan β infinite.
MAX_CLIMB_DEG = 89.0


def _check(values: Mapping[str, Any]) -> None:
    beta = values["path_angle_deg"]
    if beta > MAX_CLIMB_DEG:
        raise ParameterError(
            "path_angle_deg",
            f"a helix climbing at β = {beta:g}° would rise tan β = {math.tan(math.radians(beta)):.3g} m per metre "
            f"travelled round (infinitely at 90°): keep β at or below {MAX_CLIMB_DEG:g}°",
        )


INPUTS = ParameterSet(
    (
        SCENE_PARAMETERS.by_name["size_m"],
        SCENE_PARAMETERS.by_name["azimuth_rate_rad_s"],
        SCENE_PARAMETERS.by_name["path_angle_deg"],
        Parameter("t_s", "s", 2.0, 0.0, 60.0, "Instant at which the components are wanted", "t", step=0.1),
    ),
    check=_check,
)


@dataclass(frozen=True)
class HelixInstant:
    """The helix at one instant: cylindrical and spherical coordinates, rates and components (SI)."""

    theta_rad: float
    z_m: float
    z_dot_m_s: float
    cylindrical_velocity: np.ndarray  # (v_R, v_θ, v_z)
    cylindrical_acceleration: np.ndarray  # (a_R, a_θ, a_z)
    r_m: float
    phi_rad: float
    r_dot_m_s: float
    r_ddot_m_s2: float
    phi_dot_rad_s: float
    phi_ddot_rad_s2: float
    spherical_velocity: np.ndarray  # (v_r, v_φ, v_θ)
    spherical_acceleration: np.ndarray  # (a_r, a_φ, a_θ)
    cylindrical_axes: np.ndarray  # rows e_R, e_θ, e_z on XYZ
    spherical_axes: np.ndarray  # rows e_r, e_φ, e_θ on XYZ


def helix_at(a: float, omega: float, beta_deg: float, t: float) -> HelixInstant:
    """Both descriptions of the helix R = a, θ = ω t, z = a tan β θ at time ``t`` (closed forms)."""
    c = a * math.tan(math.radians(beta_deg))
    theta = omega * t
    z, z_dot = c * theta, c * omega
    cyl_v = np.array([0.0, a * omega, z_dot])
    cyl_a = np.array([-a * omega**2, 0.0, 0.0])
    r = math.hypot(a, z)
    phi = math.atan2(a, z)
    r_dot = z * z_dot / r
    r_ddot = a**2 * z_dot**2 / r**3
    phi_dot = -a * z_dot / r**2
    phi_ddot = 2.0 * a * z * z_dot**2 / r**4
    sp, cp = math.sin(phi), math.cos(phi)
    sph_v = np.array([r_dot, r * phi_dot, r * sp * omega])
    sph_a = np.array(
        [
            r_ddot - r * phi_dot**2 - r * sp**2 * omega**2,
            r * phi_ddot + 2.0 * r_dot * phi_dot - r * sp * cp * omega**2,
            2.0 * r_dot * omega * sp + 2.0 * r * phi_dot * omega * cp,  # θ̈ = 0
        ]
    )
    ct, st = math.cos(theta), math.sin(theta)
    e_R, e_theta, e_z = np.array([ct, st, 0.0]), np.array([-st, ct, 0.0]), np.array([0.0, 0.0, 1.0])
    e_r = np.array([sp * ct, sp * st, cp])
    e_phi = np.array([cp * ct, cp * st, -sp])
    return HelixInstant(
        theta,
        z,
        z_dot,
        cyl_v,
        cyl_a,
        r,
        phi,
        r_dot,
        r_ddot,
        phi_dot,
        phi_ddot,
        sph_v,
        sph_a,
        np.stack([e_R, e_theta, e_z]),
        np.stack([e_r, e_phi, e_theta]),
    )


def solve(inputs: Mapping[str, Any]) -> Solution:
    _check(inputs)
    a, omega, beta, t = inputs["size_m"], inputs["azimuth_rate_rad_s"], inputs["path_angle_deg"], inputs["t_s"]
    h = helix_at(a, omega, beta, t)
    speed = float(np.linalg.norm(h.cylindrical_velocity))
    a_size = a * omega**2
    ct, st = math.cos(h.theta_rad), math.sin(h.theta_rad)
    v_xyz = np.array([-a * omega * st, a * omega * ct, h.z_dot_m_s])
    a_xyz = np.array([-a * omega**2 * ct, -a * omega**2 * st, 0.0])
    v_cyl_xyz = h.cylindrical_velocity @ h.cylindrical_axes
    a_cyl_xyz = h.cylindrical_acceleration @ h.cylindrical_axes
    v_sph_xyz = h.spherical_velocity @ h.spherical_axes
    a_sph_xyz = h.spherical_acceleration @ h.spherical_axes
    v_units = {"v_R": "m/s", "v_theta": "m/s", "v_z": "m/s", "a_R": "m/s²", "a_theta": "m/s²", "a_z": "m/s²"}
    s_units = {"v_r": "m/s", "v_phi": "m/s", "v_theta": "m/s", "a_r": "m/s²", "a_phi": "m/s²", "a_theta": "m/s²"}
    steps = (
        Step(
            "Cylindrical coordinates and their rates",
            r"R = a,\quad \theta = \omega t,\quad z = c\,\theta,\ c = a\tan\beta;\qquad \dot R = \ddot R = 0,\quad "
            r"\dot\theta = \omega,\ \ddot\theta = 0,\quad \dot z = c\,\omega,\ \ddot z = 0",
            {"R": a, "theta": h.theta_rad, "z": h.z_m, "theta_dot": omega, "z_dot": h.z_dot_m_s},
            {"R": "m", "theta": "rad", "z": "m", "theta_dot": "rad/s", "z_dot": "m/s"},
        ),
        Step(
            "Cylindrical components: only the turning of e_R and e_θ adds a term",
            r"\bar v = \dot R\,\bar e_R + R\dot\theta\,\bar e_\theta + \dot z\,\bar e_z,\quad "
            r"\bar a = (\ddot R - R\dot\theta^2)\,\bar e_R + (R\ddot\theta + 2\dot R\dot\theta)\,\bar e_\theta "
            r"+ \ddot z\,\bar e_z",
            {
                "v_R": float(h.cylindrical_velocity[0]),
                "v_theta": float(h.cylindrical_velocity[1]),
                "v_z": float(h.cylindrical_velocity[2]),
                "a_R": float(h.cylindrical_acceleration[0]),
                "a_theta": float(h.cylindrical_acceleration[1]),
                "a_z": float(h.cylindrical_acceleration[2]),
            },
            v_units,
        ),
        Step(
            "Spherical coordinates (φ from +Z) and their rates, by the chain rule",
            r"r = \sqrt{a^2 + z^2},\ \ \varphi = \operatorname{atan2}(a, z);\quad \dot r = \frac{z\dot z}{r},\ \ "
            r"\ddot r = \frac{a^2\dot z^2}{r^3},\ \ \dot\varphi = -\frac{a\dot z}{r^2},\ \ "
            r"\ddot\varphi = \frac{2az\dot z^2}{r^4}",
            {
                "r": h.r_m,
                "phi": h.phi_rad,
                "r_dot": h.r_dot_m_s,
                "r_ddot": h.r_ddot_m_s2,
                "phi_dot": h.phi_dot_rad_s,
                "phi_ddot": h.phi_ddot_rad_s2,
            },
            {"r": "m", "phi": "rad", "r_dot": "m/s", "r_ddot": "m/s²", "phi_dot": "rad/s", "phi_ddot": "rad/s²"},
            scales={"r_dot": speed, "phi_ddot": omega**2},
        ),
        Step(
            "Spherical components",
            r"\bar v = \dot r\,\bar e_r + r\dot\varphi\,\bar e_\varphi + r\sin\varphi\,\dot\theta\,\bar e_\theta,\quad "
            r"a_r = \ddot r - r\dot\varphi^2 - r\sin^2\!\varphi\,\dot\theta^2,\quad "
            r"a_\varphi = r\ddot\varphi + 2\dot r\dot\varphi - r\sin\varphi\cos\varphi\,\dot\theta^2,\quad "
            r"a_\theta = r\sin\varphi\,\ddot\theta + 2\dot r\dot\theta\sin\varphi + 2r\dot\varphi\dot\theta\cos\varphi",
            {
                "v_r": float(h.spherical_velocity[0]),
                "v_phi": float(h.spherical_velocity[1]),
                "v_theta": float(h.spherical_velocity[2]),
                "a_r": float(h.spherical_acceleration[0]),
                "a_phi": float(h.spherical_acceleration[1]),
                "a_theta": float(h.spherical_acceleration[2]),
            },
            s_units,
            scales={
                "v_r": speed,
                "v_phi": speed,
                "v_theta": speed,
                "a_r": a_size,
                "a_phi": a_size,
                "a_theta": a_size,
            },
        ),
        Step(
            "Check: both descriptions give the Cartesian v and a",
            r"\bar v = \frac{d}{dt}(a\cos\omega t,\ a\sin\omega t,\ c\,\omega t),\quad "
            r"\bar a = (-a\omega^2\cos\omega t,\ -a\omega^2\sin\omega t,\ 0)",
            {
                "v (Cartesian)": v_xyz,
                "v (cylindrical)": v_cyl_xyz,
                "v (spherical)": v_sph_xyz,
                "a (Cartesian)": a_xyz,
                "a (cylindrical)": a_cyl_xyz,
                "a (spherical)": a_sph_xyz,
            },
            {
                "v (Cartesian)": "m/s",
                "v (cylindrical)": "m/s",
                "v (spherical)": "m/s",
                "a (Cartesian)": "m/s²",
                "a (cylindrical)": "m/s²",
                "a (spherical)": "m/s²",
            },
        ),
    )
    outputs = {
        "cylindrical_velocity_m_s": h.cylindrical_velocity,
        "cylindrical_acceleration_m_s2": h.cylindrical_acceleration,
        "r_m": h.r_m,
        "phi_rad": h.phi_rad,
        "theta_rad": h.theta_rad,
        "spherical_velocity_m_s": h.spherical_velocity,
        "spherical_acceleration_m_s2": h.spherical_acceleration,
        "speed_m_s": speed,
        "velocity_m_s": v_xyz,
        "acceleration_m_s2": a_xyz,
    }
    return Solution(
        outputs=outputs,
        steps=steps,
        output_scales={
            "spherical_velocity_m_s": speed,
            "spherical_acceleration_m_s2": a_size,
            "cylindrical_velocity_m_s": speed,
            "cylindrical_acceleration_m_s2": a_size,
        },
    )


EXAMPLE = WorkedExample(
    id="helix-cylindrical-spherical",
    title="A crate on a spiral conveyor: one helix in cylindrical and in spherical coordinates",
    chapter=2,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "cylindrical_velocity_m_s": "m/s",
        "cylindrical_acceleration_m_s2": "m/s²",
        "r_m": "m",
        "phi_rad": "rad",
        "theta_rad": "rad",
        "spherical_velocity_m_s": "m/s",
        "spherical_acceleration_m_s2": "m/s²",
        "speed_m_s": "m/s",
        "velocity_m_s": "m/s",
        "acceleration_m_s2": "m/s²",
    },
    section="2.3",
    story=ExampleStory(
        situation=(
            "A spiral conveyor lifts crates round a vertical column. A crate rides on the helical track at the "
            "radius $a = 1$ m, climbing at $\\beta = 15°$ above the horizontal, while it turns about the column at "
            "the steady rate $\\dot\\theta = 1$ rad/s. It passes the height $z = 0$ at $\\theta = 0$ when "
            "$t = 0$; the origin is on the column's axis at that height. We look at it at $t = 2$ s."
        ),
        wanted=(
            "The crate's velocity and acceleration components on the cylindrical unit vectors "
            "$(\\bar e_R, \\bar e_\\theta, \\bar e_z)$ and on the spherical ones "
            "$(\\bar e_r, \\bar e_\\varphi, \\bar e_\\theta)$, with the spherical coordinates and their rates, "
            "so that the two descriptions can be compared side by side."
        ),
        approach=(
            "The track is built around an axis, so cylindrical coordinates fit it: $R$ and $\\dot\\theta$ are "
            "constant and $z$ grows steadily, leaving one term, $-R\\dot\\theta^2$, in the acceleration. We "
            "then describe the same motion from the origin in spherical coordinates, as a sensor at the "
            "origin would see it: now $r$ and $\\varphi$ both change, their rates need the chain rule, and "
            "all six components are nonzero. The spherical route costs several times the work and hides "
            "the simple physics; it is here to show that the coordinates are a choice, while the vectors are "
            "not."
        ),
        check=(
            "Velocity and acceleration are vectors; only their components depend on the description. So each "
            "set of components, multiplied by its own unit vectors at the crate, must rebuild the same "
            "$\\bar v$ and $\\bar a$ on $XYZ$ as differentiating $x = a\\cos\\omega t$, "
            "$y = a\\sin\\omega t$, $z = c\\,\\omega t$ directly. The last step shows the three versions of "
            "each vector side by side: they agree to round-off."
        ),
        what_if=(
            "Set the scene's **unit vectors** control to *spherical* and move **β** from 15° up to 50°. At "
            "$t = 2$ s the crate is then 2.38 m up instead of 0.54 m, so seen from the origin $\\varphi$ has "
            "closed from 62° to 23° off the vertical, and the spherical acceleration turns from "
            "$a_r = -0.88$, $a_\\varphi = -0.47$ m/s² to $a_r = -0.39$, $a_\\varphi = -0.92$ m/s². The "
            "cylindrical acceleration stays $-R\\dot\\theta^2 = -1$ m/s² along $\\bar e_R$ whatever β is. In "
            "the scene, the red chain of components changes shape but still ends at the tip of the same arrow."
        ),
    ),
)
