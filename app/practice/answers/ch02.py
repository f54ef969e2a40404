"""Answers of chapter 2's exercises: path variables (tangential and normal components, curvature, the binormal) and
rectangular Cartesian components of velocity and acceleration."""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import sympy

from app.physics.systems.ch02.cartesian_components import Projectile, SineSlot
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
