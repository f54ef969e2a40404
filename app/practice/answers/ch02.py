"""Answers of chapter 2's exercises: path variables (tangential and normal components, curvature, the binormal) and
rectangular Cartesian components of velocity and acceleration."""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import sympy

from app.physics.systems.ch02.cartesian_components import Projectile, SineSlot
from app.physics.systems.ch02.rotating_arm import RotatingArm
from app.practice.exercise import PartAnswer

#: Largest acceleration (m/s²) a car's tyres can give on a dry road (about 0.9 g): a braking-on-a-bend variant that
#: needs more is not a car on a road, and is drawn again.
TYRE_GRIP_M_S2 = 9.0


def _vec(v: np.ndarray) -> tuple[float, float, float]:
    return (float(v[0]), float(v[1]), float(v[2]))


def _latex_vec(v: np.ndarray, unit: str) -> str:
    components = rf"({v[0]:.4g},\ {v[1]:.4g},\ {v[2]:.4g})"
    return components + rf"\ \mathrm{{{unit}}}" if unit else components


def _clean(v: np.ndarray) -> np.ndarray:
    """``v`` with the components that are round-off of an exact zero (below 1e-12 of its size) set to 0."""
    return np.where(np.abs(v) < 1e-12 * float(np.linalg.norm(v)), 0.0, v)


def braking_on_bend(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A car on a circular bend of radius ρ at speed v (given in km/h), slowing at a rate |v̇|: a_n = v²/ρ,
    |a| = √(a_t² + a_n²), and the angle between a and v (more than 90°, since the car slows)."""
    v_kmh, rho, slowing = given["speed_kmh"], given["radius_m"], given["slowing_m_s2"]
    v = v_kmh / 3.6
    a_t, a_n = -slowing, v**2 / rho
    total = math.hypot(a_t, a_n)
    if total > TYRE_GRIP_M_S2:
        raise ValueError("more acceleration than a car's tyres can give")
    angle = math.degrees(math.atan2(a_n, a_t))
    return {
        "normal": PartAnswer(
            a_n,
            rf"v = {v_kmh:g}/3.6 = {v:.4g}\ \mathrm{{m/s}},\ a_n = \frac{{v^2}}{{\rho}} = {a_n:.4g}\ \mathrm{{m/s^2}}",
            {"kmh-not-converted": v_kmh**2 / rho, "v-over-rho": v / rho},
        ),
        "total": PartAnswer(
            total,
            rf"|\bar a| = \sqrt{{a_t^2 + a_n^2}} = {total:.4g}\ \mathrm{{m/s^2}}",
            {"added": slowing + a_n},
        ),
        "angle": PartAnswer(
            angle,
            rf"a_t = {a_t:.4g}\ \mathrm{{m/s^2}} < 0,\ \cos\phi = \frac{{a_t}}{{|\bar a|}},\ \phi = {angle:.4g}^\circ",
            {"braking-sign": 180.0 - angle, "radian-number": math.radians(angle)},
        ),
    }


a_s, c_s = sympy.symbols("a c", real=True)


def helix_frenet(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A particle on the helix x = a cos φ, y = a sin φ, z = c φ (c = pitch/2π), φ increasing, at constant speed v:
    κ(a, c), the radius of curvature, a_n at speed v, and the binormal at φ = 0 (the point (a, 0, 0))."""
    a, pitch, v = given["radius_m"], given["pitch_m"], given["speed_m_s"]
    c = pitch / (2 * math.pi)
    rho = (a**2 + c**2) / a
    a_n = v**2 / rho
    binormal = np.array([0.0, -c, a]) / math.hypot(a, c)
    return {
        "kappa": PartAnswer(
            a_s / (a_s**2 + c_s**2),
            r"\kappa = \frac{|\bar r'\times\bar r''|}{|\bar r'|^3} = \frac{a\sqrt{a^2+c^2}}{(a^2+c^2)^{3/2}}"
            r" = \frac{a}{a^2+c^2}",
            {"circle": 1 / a_s, "torsion": c_s / (a_s**2 + c_s**2)},
        ),
        "rho": PartAnswer(
            rho,
            rf"c = \frac{{p}}{{2\pi}} = {c:.4g}\ \mathrm{{m}},"
            rf"\ \rho = \frac{{a^2 + c^2}}{{a}} = {rho:.4g}\ \mathrm{{m}}",
            {"helix-radius": a, "pitch-per-turn": (a**2 + pitch**2) / a},
        ),
        "normal": PartAnswer(
            a_n, rf"a_n = \frac{{v^2}}{{\rho}} = {a_n:.4g}\ \mathrm{{m/s^2}}", {"helix-radius": v**2 / a}
        ),
        "binormal": PartAnswer(
            _vec(binormal),
            r"\bar e_b = \frac{\bar r'\times\bar r''}{|\bar r'\times\bar r''|} = \frac{(0,\ -c,\ a)}{\sqrt{a^2+c^2}} = "
            + _latex_vec(binormal, ""),
            {"order": _vec(-binormal)},
        ),
    }


def projectile_path_variables(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A ball thrown at v₀, α above level ground, no air; at time t₁ in flight: the tangential and normal components
    of a = −g K, and the radius of curvature of the path there."""
    v0, alpha, t1, g = given["speed_m_s"], math.radians(given["angle_deg"]), given["time_s"], given["g_m_s2"]
    vx, vz = v0 * math.cos(alpha), v0 * math.sin(alpha) - g * t1
    if t1 >= 2 * v0 * math.sin(alpha) / g:
        raise ValueError("the ball has landed by then")
    v = math.hypot(vx, vz)
    if abs(vz) < 0.25 * v:
        raise ValueError("too near the top of the path, where the tangential part vanishes")
    a_t = -g * vz / v
    a_n = g * vx / v
    rho = v**2 / a_n
    return {
        "tangential": PartAnswer(
            a_t,
            rf"\bar v = ({vx:.4g},\ {vz:.4g})\ \mathrm{{m/s}},\ a_t = \bar a\cdot\bar e_t = \frac{{-g\,v_z}}{{v}}"
            rf" = {a_t:.4g}\ \mathrm{{m/s^2}}",
            {"whole-g": math.copysign(g, a_t), "sign": -a_t},
        ),
        "normal": PartAnswer(
            a_n,
            rf"a_n = \sqrt{{g^2 - a_t^2}} = \frac{{g\,v_x}}{{v}} = {a_n:.4g}\ \mathrm{{m/s^2}}",
            {"sin-cos": g * abs(vz) / v},
        ),
        "rho": PartAnswer(
            rho,
            rf"\rho = \frac{{v^2}}{{a_n}} = {rho:.4g}\ \mathrm{{m}}",
            {"whole-g": v**2 / g},
        ),
    }


def pin_in_sine_slot(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A pin driven at constant ẋ = u along the slot y = h sin(πx/L) (plane z = 0), at the instant it is at x:
    its velocity on XYZ, ÿ there, and the largest |a| over the slot (at a crest). Uses the scene's SineSlot model."""
    h, half, u, x = given["amplitude_m"], given["half_wavelength_m"], given["drive_speed_m_s"], given["x_m"]
    slot = SineSlot(h, half, u)
    state = slot.at(x / u)
    velocity, y_accel = state.velocity_m_s[0], float(state.acceleration_m_s2[0, 1])
    k = math.pi / half
    peak = h * k**2 * u**2
    return {
        "velocity": PartAnswer(
            _vec(velocity),
            r"\dot y = h\frac{\pi}{L}\cos\frac{\pi x}{L}\,\dot x,\ \bar v = " + _latex_vec(velocity, "m/s"),
            {"no-chain-rule": (u, h * k * math.cos(k * x), 0.0)},
        ),
        "yddot": PartAnswer(
            y_accel,
            rf"\ddot y = -h\left(\frac{{\pi}}{{L}}\right)^2\sin\frac{{\pi x}}{{L}}\,\dot x^2 = {y_accel:.4g}"
            r"\ \mathrm{m/s^2}",
            {"sign": -y_accel, "one-drive-factor": y_accel / u},
        ),
        "peak": PartAnswer(
            peak,
            rf"|\bar a|_{{\max}} = h\left(\frac{{\pi}}{{L}}\right)^2\dot x^2 = {peak:.4g}\ \mathrm{{m/s^2}}",
            {"k-not-squared": h * k * u**2},
        ),
    }


def projectile_heading(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A ball launched from the origin at v₀, elevation α, heading ψ (from +X toward +Y), gravity −g K, level
    ground: the time to the top, the landing point and the landing velocity on XYZ, and a at the top."""
    v0, g = given["speed_m_s"], given["g_m_s2"]
    alpha, psi = math.radians(given["elevation_deg"]), math.radians(given["heading_deg"])
    ball = Projectile(v0, alpha, psi, g)
    flight = ball.run_s
    landing = ball.at(flight)
    # Exactly on the ground, and no round-off left where a heading of ±90° makes a component 0.
    position, velocity = _clean(landing.position_m[0] * np.array([1.0, 1.0, 0.0])), _clean(landing.velocity_m_s[0])
    top = v0 * math.sin(alpha) / g
    reach = float(np.hypot(position[0], position[1]))
    return {
        "top-time": PartAnswer(
            top,
            rf"\dot z = v_0\sin\alpha - g t = 0\ \Rightarrow\ t = {top:.4g}\ \mathrm{{s}}",
            {"full-flight": flight},
        ),
        "landing": PartAnswer(
            _vec(position),
            rf"t_f = \frac{{2 v_0\sin\alpha}}{{g}} = {flight:.4g}\ \mathrm{{s}},\ "
            r"\bar r = v_0\cos\alpha\,t_f(\cos\psi,\ \sin\psi,\ 0) = " + _latex_vec(position, "m"),
            {
                "heading-swapped": (position[1], position[0], 0.0),
                "top-time": (position[0] / 2, position[1] / 2, 0.0),
            },
        ),
        "landing-velocity": PartAnswer(
            _vec(velocity),
            r"\bar v = (v_0\cos\alpha\cos\psi,\ v_0\cos\alpha\sin\psi,\ v_0\sin\alpha - g t_f) = "
            + _latex_vec(velocity, "m/s"),
            {"z-not-reversed": (float(velocity[0]), float(velocity[1]), -float(velocity[2]))},
        ),
        "top-acceleration": PartAnswer(
            "down-g",
            rf"\bar a = \ddot z\,\bar K = -g\,\bar K\ \text{{at every instant (range {reach:.4g} m)}}",
            {"zero": "zero", "along-velocity": "horizontal"},
        ),
    }


amp_s, omega_s, time_s = sympy.symbols("A omega t", real=True)


def elliptic_lift(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A point moving as x = A cos ωt, y = B sin ωt, z = C t² on XYZ: ẍ(t), the acceleration at t₁, the speed at
    t₁."""
    big_a, big_b, omega, lift, t1 = (
        given["a_m"],
        given["b_m"],
        given["omega_rad_s"],
        given["lift_m_s2"],
        given["time_s"],
    )
    wt = omega * t1
    velocity = np.array([-big_a * omega * math.sin(wt), big_b * omega * math.cos(wt), 2 * lift * t1])
    accel = np.array([-big_a * omega**2 * math.cos(wt), -big_b * omega**2 * math.sin(wt), 2 * lift])
    speed = float(np.linalg.norm(velocity))
    return {
        "xddot": PartAnswer(
            -amp_s * omega_s**2 * sympy.cos(omega_s * time_s),
            r"\dot x = -A\omega\sin\omega t,\ \ddot x = -A\omega^2\cos\omega t",
            {
                "sign": amp_s * omega_s**2 * sympy.cos(omega_s * time_s),
                "no-chain-factor": -amp_s * sympy.cos(omega_s * time_s),
            },
        ),
        "acceleration": PartAnswer(
            _vec(accel),
            r"\bar a = (-A\omega^2\cos\omega t_1,\ -B\omega^2\sin\omega t_1,\ 2C) = " + _latex_vec(accel, "m/s^2"),
            {
                "z-half": _vec(accel - np.array([0.0, 0.0, lift])),
                "omega-once": _vec(np.array([accel[0] / omega, accel[1] / omega, accel[2]])),
            },
        ),
        "speed": PartAnswer(
            speed,
            r"\bar v = (-A\omega\sin\omega t_1,\ B\omega\cos\omega t_1,\ 2 C t_1),\ "
            rf"v = |\bar v| = {speed:.4g}\ \mathrm{{m/s}}",
            {"sum-of-components": float(np.sum(np.abs(velocity)))},
        ),
    }


# -- 2.3 curvilinear coordinates ---------------------------------------------------------------------------------

big_r_s, phi_s, phid_s, spin_s = sympy.symbols("R phi phid Omega", real=True)
rdot_s, thetad_s, speed_s, track_s = sympy.symbols("Rdot thetad v b", real=True)


def conical_spiral_components(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The curvilinear-coordinates scene's conical spiral: R = a(1 + θ/2π), θ = θ̇ t, z = R cot β (cone of half-angle
    β about Z, vertex at O). At the instant t: v and a on (e_R, e_θ, e_z), and the speed."""
    a, rate, beta, t = given["size_m"], given["azimuth_rate_rad_s"], math.radians(given["cone_deg"]), given["time_s"]
    theta = rate * t
    radius = a * (1 + theta / (2 * math.pi))
    r_dot = a * rate / (2 * math.pi)
    cot = 1 / math.tan(beta)
    velocity = np.array([r_dot, radius * rate, r_dot * cot])
    accel = np.array([-radius * rate**2, 2 * r_dot * rate, 0.0])
    speed = float(np.linalg.norm(velocity))
    return {
        "velocity": PartAnswer(
            _vec(velocity),
            rf"R = a\left(1 + \frac{{\theta}}{{2\pi}}\right) = {radius:.4g}\ \mathrm{{m}},\ "
            rf"\dot R = \frac{{a\dot\theta}}{{2\pi}} = {r_dot:.4g}\ \mathrm{{m/s}},\ "
            r"\bar v = (\dot R,\ R\dot\theta,\ \dot R\cot\beta) = " + _latex_vec(velocity, "m/s"),
            {"no-climb": (velocity[0], velocity[1], 0.0), "no-rdot": (0.0, velocity[1], 0.0)},
        ),
        "acceleration": PartAnswer(
            _vec(accel),
            r"\ddot R = \ddot\theta = \ddot z = 0,\ \bar a = (-R\dot\theta^2,\ 2\dot R\dot\theta,\ 0) = "
            + _latex_vec(accel, "m/s^2"),
            {
                "no-coriolis": (accel[0], 0.0, 0.0),
                "half-coriolis": (accel[0], r_dot * rate, 0.0),
            },
        ),
        "speed": PartAnswer(
            speed,
            rf"v = \sqrt{{v_R^2 + v_\theta^2 + v_z^2}} = {speed:.4g}\ \mathrm{{m/s}}",
            {"no-climb": math.hypot(velocity[0], velocity[1])},
        ),
    }


def bead_on_hoop_spherical(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A bead on a hoop of radius R spinning at a constant Ω about the vertical diameter (Z), hoop centre at O; the
    bead at polar angle φ from +Z with rates φ̇, φ̈. Spherical (r, φ, θ) with r = R, θ̇ = Ω: a_θ in symbols, a on
    (e_r, e_φ, e_θ), and the push m|a_θ| the hoop gives square to its own plane."""
    radius, spin, mass = given["hoop_radius_m"], given["hoop_rate_rad_s"], given["mass_kg"]
    phi, phi_dot, phi_ddot = math.radians(given["polar_deg"]), given["phi_rate_rad_s"], given["phi_accel_rad_s2"]
    s, c = math.sin(phi), math.cos(phi)
    accel = np.array(
        [
            -radius * phi_dot**2 - radius * s**2 * spin**2,
            radius * phi_ddot - radius * s * c * spin**2,
            2 * radius * phi_dot * spin * c,
        ]
    )
    push = mass * abs(float(accel[2]))
    return {
        "a-theta": PartAnswer(
            2 * big_r_s * phid_s * spin_s * sympy.cos(phi_s),
            r"a_\theta = r\sin\varphi\,\ddot\theta + 2\dot r\dot\theta\sin\varphi + 2r\dot\varphi\dot\theta\cos\varphi"
            r" = 2R\dot\varphi\,\Omega\cos\varphi",
            {
                "half": big_r_s * phid_s * spin_s * sympy.cos(phi_s),
                "sin-cos": 2 * big_r_s * phid_s * spin_s * sympy.sin(phi_s),
            },
        ),
        "acceleration": PartAnswer(
            _vec(accel),
            r"\bar a = \left(-R\dot\varphi^2 - R\sin^2\varphi\,\Omega^2,\ R\ddot\varphi - R\sin\varphi\cos\varphi\,"
            r"\Omega^2,\ 2R\dot\varphi\,\Omega\cos\varphi\right) = " + _latex_vec(accel, "m/s^2"),
            {
                "no-coriolis": (accel[0], accel[1], 0.0),
                "no-hoop-spin": (-radius * phi_dot**2, radius * phi_ddot, 0.0),
            },
        ),
        "push": PartAnswer(
            push,
            rf"N_\theta = m\,|a_\theta| = {mass:.4g} \times {abs(accel[2]):.4g} = {push:.4g}\ \mathrm{{N}}",
            {"half": push / 2},
        ),
    }


def straight_line_polar(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A car at constant speed v along the line y = d (in +X), tracked from O in polar coordinates (R, θ from +X),
    at the instant it is at x: Ṙ, θ̇, θ̈ in symbols (from a_θ = 0) and R̈ (from a_R = 0)."""
    v, d, x = given["speed_m_s"], given["offset_m"], given["x_m"]
    if x == 0.0:
        raise ValueError("abeam of the radar the range does not change: no Ṙ to ask for")
    radius = math.hypot(x, d)
    r_dot = v * x / radius
    theta_dot = -v * d / radius**2
    r_ddot = radius * theta_dot**2
    return {
        "rdot": PartAnswer(
            r_dot,
            rf"R = \sqrt{{x^2 + d^2}} = {radius:.4g}\ \mathrm{{m}},\ \dot R = \bar v\cdot\bar e_R = \frac{{v x}}{{R}}"
            rf" = {r_dot:.4g}\ \mathrm{{m/s}}",
            {"whole-speed": v},
        ),
        "thetadot": PartAnswer(
            theta_dot,
            r"R\dot\theta = \bar v\cdot\bar e_\theta = -\frac{v d}{R},\ \dot\theta = -\frac{v d}{R^2}"
            rf" = {theta_dot:.4g}\ \mathrm{{rad/s}}",
            {"sign": -theta_dot, "whole-speed": -v / radius},
        ),
        "thetaddot": PartAnswer(
            -2 * rdot_s * thetad_s / big_r_s,
            r"\bar a = \bar 0:\ R\ddot\theta + 2\dot R\dot\theta = 0\ \Rightarrow\ "
            r"\ddot\theta = -\frac{2\dot R\dot\theta}{R}",
            {"zero": sympy.Integer(0), "half": -rdot_s * thetad_s / big_r_s},
        ),
        "rddot": PartAnswer(
            r_ddot,
            rf"\ddot R - R\dot\theta^2 = 0\ \Rightarrow\ \ddot R = R\dot\theta^2 = {r_ddot:.4g}\ \mathrm{{m/s^2}}",
            {"zero": 0.0},
        ),
    }


# -- 2.4 mixed kinematical descriptions --------------------------------------------------------------------------


def collar_path_variables(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The rotating-arm scene at the instant t: the arm at θ = Ω t + ½ α t², the collar at r = r₀ + b sin(ω_c t).
    a on the arm's (e_r, e_θ, e_z), then the path variables v, a_t = v·a/v and a_n = |v × a|/v."""
    arm = RotatingArm(
        given["arm_rate_rad_s"],
        given["arm_accel_rad_s2"],
        given["collar_mean_m"],
        given["collar_amplitude_m"],
        given["collar_frequency_rad_s"],
    )
    state = arm.at(given["time_s"])
    r, r_dot, r_ddot = float(state.r_m[0]), float(state.r_dot_m_s[0]), float(state.r_ddot_m_s2[0])
    th_dot, th_ddot = float(state.theta_dot_rad_s[0]), float(state.theta_ddot_rad_s2[0])
    velocity = np.array([r_dot, r * th_dot, 0.0])
    accel = np.array([r_ddot - r * th_dot**2, r * th_ddot + 2 * r_dot * th_dot, 0.0])
    speed = float(np.linalg.norm(velocity))
    size = float(np.linalg.norm(accel))
    a_t = float(velocity @ accel) / speed
    a_n = abs(float(np.cross(velocity, accel)[2])) / speed
    if min(abs(a_t), a_n) < 0.25 * size or speed < 0.1:
        raise ValueError("keep both path components a fair share of |a| (and the collar moving)")
    return {
        "acceleration": PartAnswer(
            _vec(accel),
            rf"r = {r:.4g}\ \mathrm{{m}},\ \dot r = {r_dot:.4g}\ \mathrm{{m/s}},\ \ddot r = {r_ddot:.4g}\ "
            rf"\mathrm{{m/s^2}},\ \dot\theta = {th_dot:.4g}\ \mathrm{{rad/s}},\ "
            r"\bar a = (\ddot r - r\dot\theta^2,\ r\ddot\theta + 2\dot r\dot\theta,\ 0) = "
            + _latex_vec(accel, "m/s^2"),
            {
                "no-coriolis": (accel[0], r * th_ddot, 0.0),
                "no-centripetal": (r_ddot, accel[1], 0.0),
            },
        ),
        "speed": PartAnswer(
            speed,
            rf"\bar v = (\dot r,\ r\dot\theta,\ 0) = {_latex_vec(velocity, 'm/s')},\ v = {speed:.4g}\ \mathrm{{m/s}}",
            {"along-arm-only": abs(r_dot)},
        ),
        "tangential": PartAnswer(
            a_t,
            rf"a_t = \frac{{\bar v\cdot\bar a}}{{v}} = {a_t:.4g}\ \mathrm{{m/s^2}}",
            {"rddot": r_ddot},
        ),
        "normal": PartAnswer(
            a_n,
            rf"a_n = \frac{{|\bar v\times\bar a|}}{{v}} = \sqrt{{|\bar a|^2 - a_t^2}} = {a_n:.4g}\ \mathrm{{m/s^2}}",
            {"whole-a": size},
        ),
    }


def bead_down_helix(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A bead released from rest on a frictionless helical wire (radius R, climb angle γ, z = R tan γ θ), after it
    has dropped h: v = √(2gh), v̇ = g sin γ. θ̇ (negative: it runs down, clockwise seen from above), a on
    (e_R, e_θ, e_z) and the wire's radius of curvature R / cos²γ."""
    radius, gamma, drop, g = given["radius_m"], math.radians(given["climb_deg"]), given["drop_m"], given["g_m_s2"]
    v = math.sqrt(2 * g * drop)
    v_dot = g * math.sin(gamma)
    c, s = math.cos(gamma), math.sin(gamma)
    theta_dot = -v * c / radius
    accel = np.array([-((v * c) ** 2) / radius, -v_dot * c, -v_dot * s])
    rho = radius / c**2
    return {
        "theta-rate": PartAnswer(
            theta_dot,
            rf"v = \sqrt{{2gh}} = {v:.4g}\ \mathrm{{m/s}},\ v_\theta = R\dot\theta = -v\cos\gamma,\ "
            rf"\dot\theta = {theta_dot:.4g}\ \mathrm{{rad/s}}",
            {"no-climb": -v / radius, "sign": -theta_dot},
        ),
        "acceleration": PartAnswer(
            _vec(accel),
            r"\bar a = \dot v\,\bar e_t + \frac{v^2}{\rho}\bar e_n,\ \bar e_t = (0, -\cos\gamma, -\sin\gamma),\ "
            r"\bar e_n = -\bar e_R,\ \dot v = g\sin\gamma:\ \bar a = \left(-\frac{v^2\cos^2\gamma}{R},\ "
            r"-g\sin\gamma\cos\gamma,\ -g\sin^2\gamma\right) = " + _latex_vec(accel, "m/s^2"),
            {
                "radial-whole-speed": (-(v**2) / radius, accel[1], accel[2]),
                "no-normal": (0.0, accel[1], accel[2]),
            },
        ),
        "rho": PartAnswer(
            rho,
            rf"\rho = \frac{{v^2}}{{a_n}} = \frac{{R}}{{\cos^2\gamma}} = {rho:.4g}\ \mathrm{{m}}",
            {"helix-radius": radius},
        ),
    }


def car_seen_from_rim(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A car at constant speed v on a circular track of radius b, watched from a point O on the track: polar
    coordinates about O with θ from the diameter through O, R = 2b cos θ, θ̇ = v/(2b). Ṙ, a_R and a_θ at θ."""
    v, b, theta = given["speed_m_s"], given["track_radius_m"], math.radians(given["bearing_deg"])
    theta_dot = v / (2 * b)
    radius = 2 * b * math.cos(theta)
    r_dot = -2 * b * math.sin(theta) * theta_dot
    r_ddot = -2 * b * math.cos(theta) * theta_dot**2
    a_r = r_ddot - radius * theta_dot**2
    a_theta = 2 * r_dot * theta_dot
    return {
        "thetadot": PartAnswer(
            speed_s / (2 * track_s),
            r"R = 2b\cos\theta,\ \dot R = -2b\sin\theta\,\dot\theta,\ v^2 = \dot R^2 + (R\dot\theta)^2 = "
            r"4b^2\dot\theta^2\ \Rightarrow\ \dot\theta = \frac{v}{2b}",
            {"centre-rate": speed_s / track_s},
        ),
        "rdot": PartAnswer(
            r_dot,
            rf"\dot R = -2b\sin\theta\,\dot\theta = -v\sin\theta = {r_dot:.4g}\ \mathrm{{m/s}}",
            {"zero": 0.0, "sign": -r_dot},
        ),
        "a-radial": PartAnswer(
            a_r,
            rf"\ddot R = -2b\cos\theta\,\dot\theta^2 = {r_ddot:.4g},\ a_R = \ddot R - R\dot\theta^2 = "
            rf"-\frac{{v^2}}{{b}}\cos\theta = {a_r:.4g}\ \mathrm{{m/s^2}}",
            {"no-rddot": -radius * theta_dot**2, "whole": -(v**2) / b},
        ),
        "a-transverse": PartAnswer(
            a_theta,
            rf"a_\theta = R\ddot\theta + 2\dot R\dot\theta = 0 + 2\dot R\dot\theta = -\frac{{v^2}}{{b}}\sin\theta"
            rf" = {a_theta:.4g}\ \mathrm{{m/s^2}}",
            {"no-coriolis": 0.0},
        ),
    }
