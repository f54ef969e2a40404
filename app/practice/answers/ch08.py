"""Answers of chapter 8's exercises: Lagrange's equations with constrained coordinates and multipliers, and the
computational side of constraints (drift and its correction, consistent starts) and Coulomb friction."""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import sympy

from app.practice.exercise import PartAnswer

m1, m2, g, theta1, theta2 = sympy.symbols("m1 m2 g theta1 theta2", real=True)
m, beta = sympy.symbols("m beta", real=True)

#: Where RK4's stability region meets the negative real axis: the real root of 1 + z/2 + z²/6 + z³/24 = 0, i.e.
#: |1 + z + z²/2 + z³/6 + z⁴/24| = 1 (about −2.785).
RK4_REAL_LIMIT = float(min(root.real for root in np.roots([1 / 24, 1 / 6, 1 / 2, 1.0]) if abs(root.imag) < 1e-12))


def _vector(values: np.ndarray) -> tuple[float, float, float]:
    return (float(values[0]), float(values[1]), float(values[2]))


# -- 8.1 Lagrange's equations, constrained case ---------------------------------------------------------------------


def double_pendulum_release(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """Two bobs on light rods (pivot at the origin, y up), Cartesian coordinates (x₁, y₁, x₂, y₂) with the rods as
    g₁ = ½(L₁² − |r₁|²) and g₂ = ½(L₂² − |r₂ − r₁|²); released from rest at θ₁, θ₂ from the downward vertical. The
    lower rod's tension as an expression, its multiplier λ₂ (N/m) and the upper rod's tension λ₁L₁ (N)."""
    mass1, mass2, length1, length2 = given["mass1_kg"], given["mass2_kg"], given["length1_m"], given["length2_m"]
    angle1, angle2, gravity = math.radians(given["theta1_deg"]), math.radians(given["theta2_deg"]), given["g_m_s2"]
    delta = angle2 - angle1
    if abs(delta) > math.radians(75.0):
        raise ValueError("the lower rod would be nearly square to the upper one: its tension is nearly zero")
    tension2 = mass1 * mass2 * gravity * math.cos(angle1) * math.cos(delta) / (mass1 + mass2 * math.sin(delta) ** 2)
    tension1 = mass1 * gravity * math.cos(angle1) + tension2 * math.cos(delta)
    static2 = mass2 * gravity * math.cos(angle2)
    expression = (
        m1 * m2 * g * sympy.cos(theta1) * sympy.cos(theta2 - theta1) / (m1 + m2 * sympy.sin(theta2 - theta1) ** 2)
    )
    return {
        "tension2": PartAnswer(
            expression,
            r"\text{at rest } \ddot{\mathbf r}_1\cdot\mathbf e_1 = 0,\ (\ddot{\mathbf r}_2 - \ddot{\mathbf r}_1)\cdot"
            r"\mathbf e_2 = 0 \Rightarrow T_2 = \frac{m_1 m_2 g\cos\theta_1\cos(\theta_2 - \theta_1)}"
            r"{m_1 + m_2\sin^2(\theta_2 - \theta_1)}",
            {"static": m2 * g * sympy.cos(theta2)},
        ),
        "lambda2": PartAnswer(
            tension2 / length2,
            rf"\lambda_2 = T_2 / L_2 = {tension2:.4g}\ \mathrm{{N}} / {length2:g}\ \mathrm{{m}}"
            rf" = {tension2 / length2:.4g}\ \mathrm{{N/m}}",
            {"times-length": tension2 * length2, "static": static2 / length2},
        ),
        "tension1": PartAnswer(
            tension1,
            r"T_1 = m_1 g\cos\theta_1 + T_2\cos(\theta_2 - \theta_1)"
            rf" = {tension1:.4g}\ \mathrm{{N}}\quad(\lambda_1 = T_1/L_1 = {tension1 / length1:.4g}\ \mathrm{{N/m}})",
            {
                "no-lower-rod": mass1 * gravity * math.cos(angle1),
                "static-lower": mass1 * gravity * math.cos(angle1) + static2 * math.cos(delta),
            },
        ),
    }


def rolling_cylinder_multiplier(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A uniform solid cylinder rolling down an incline β with x down the slope and φ its turn, held by the rolling
    constraint x − r φ = 0 with multiplier λ (the friction force along +x): λ as an expression, ẍ, the least μ_s,
    and whether λ does work."""
    angle, gravity = math.radians(given["incline_deg"]), given["g_m_s2"]
    accel = 2.0 / 3.0 * gravity * math.sin(angle)
    mu = math.tan(angle) / 3.0
    return {
        "lambda": PartAnswer(
            -m * g * sympy.sin(beta) / 3,
            r"m\ddot x = m g\sin\beta + \lambda,\ \tfrac12 m r^2\ddot\phi = -r\lambda,\ \ddot x = r\ddot\phi"
            r"\ \Rightarrow\ \lambda = -\tfrac13 m g\sin\beta",
            {"sign": m * g * sympy.sin(beta) / 3, "hoop": -m * g * sympy.sin(beta) / 2},
        ),
        "accel": PartAnswer(
            accel,
            rf"\ddot x = g\sin\beta + \lambda/m = \tfrac23 g\sin\beta = {accel:.4g}\ \mathrm{{m/s^2}}",
            {"no-constraint": gravity * math.sin(angle), "hoop": 0.5 * gravity * math.sin(angle)},
        ),
        "mu": PartAnswer(
            mu,
            rf"\mu_s \ge \frac{{|\lambda|}}{{N}} = \frac{{\tfrac13 m g\sin\beta}}{{m g\cos\beta}}"
            rf" = \tfrac13\tan\beta = {mu:.4g}",
            {"weight-not-normal": math.sin(angle) / 3.0},
        ),
        "work": PartAnswer(
            "none",
            r"\text{power } \lambda\,(\dot x - r\dot\phi) = 0",
            {"work-by-distance": "negative"},
        ),
    }


def slider_crank_start(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The slider-crank (crank r from O at the origin, rod l, slider on y = 0 beyond the crank, y up) at crank angle θ
    turning at ω: the rod's angle φ₂ (from A to B) and rate, the velocity of the rod's centre, and T of the crank and
    rod (uniform slender bars) and slider (a particle) from the absolute coordinates."""
    r, l, theta, omega = given["crank_m"], given["rod_m"], math.radians(given["crank_angle_deg"]), given["omega_rad_s"]
    crank_mass, rod_mass, slider_mass = given["crank_mass_kg"], given["rod_mass_kg"], given["slider_mass_kg"]
    if abs(math.cos(theta)) < 0.15:
        raise ValueError("near θ = 90° the rod's rate is nearly zero, too small to ask for")
    phi = math.asin(-r * math.sin(theta) / l)
    phi_rate = -r * omega * math.cos(theta) / (l * math.cos(phi))
    v_a = r * omega * np.array([-math.sin(theta), math.cos(theta), 0.0])
    v_g2 = v_a + phi_rate * 0.5 * l * np.array([-math.sin(phi), math.cos(phi), 0.0])
    v_b = float(v_a[0] - phi_rate * l * math.sin(phi))
    crank = 0.5 * (crank_mass * r**2 / 3) * omega**2
    rod_translation = 0.5 * rod_mass * float(v_g2 @ v_g2)
    rod_rotation = 0.5 * (rod_mass * l**2 / 12) * phi_rate**2
    slider = 0.5 * slider_mass * v_b**2
    energy = crank + rod_translation + rod_rotation + slider
    crank_about_g = 0.5 * (crank_mass * r**2 / 12) * omega**2
    return {
        "phi": PartAnswer(
            math.degrees(phi),
            rf"l\sin\phi_2 = -r\sin\theta \Rightarrow \phi_2 = {math.degrees(phi):.4g}^\circ",
            {"radian-number": phi, "sign": -math.degrees(phi)},
        ),
        "phi-rate": PartAnswer(
            phi_rate,
            r"\dot y_B = r\omega\cos\theta + l\dot\phi_2\cos\phi_2 = 0 \Rightarrow \dot\phi_2 = "
            rf"-\frac{{r\omega\cos\theta}}{{l\cos\phi_2}} = {phi_rate:.4g}\ \mathrm{{rad/s}}",
            {"sign": -phi_rate},
        ),
        "vg2": PartAnswer(
            _vector(v_g2),
            r"\dot{\mathbf r}_{G_2} = \mathbf v_A + \dot\phi_2\,\mathbf k\times\tfrac l2\mathbf e(\phi_2)"
            rf" = ({v_g2[0]:.4g},\ {v_g2[1]:.4g},\ 0)\ \mathrm{{m/s}}",
            {"end-a": _vector(v_a)},
        ),
        "energy": PartAnswer(
            energy,
            r"T = \tfrac12\sum_i\left(m_i\dot x_{G_i}^2 + m_i\dot y_{G_i}^2 + I_{G_i}\dot\phi_i^2\right)"
            rf" = {energy:.4g}\ \mathrm{{J}}",
            {
                "no-rotation": energy - rod_rotation - 0.5 * (crank_mass * r**2 / 12) * omega**2,
                "crank-about-g": energy - crank + crank_about_g,
            },
        ),
    }


# -- 8.2 Computational methods ------------------------------------------------------------------------------------


def baumgarte_critical(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """Baumgarte's correction with α = β (critical damping): a position residual e₀ (mm) with ė(0) = 0 decays as
    e₀(1 + αt)e^(−αt); RK4 keeps those error dynamics stable while h α ≤ 2.785; with α = 0 the error oscillates."""
    alpha, e0, t = given["alpha_1_s"], given["residual0_mm"], given["time_s"]
    if alpha * t > 6.0:
        raise ValueError("the residual would have died out to nothing worth asking about")
    residual = e0 * (1.0 + alpha * t) * math.exp(-alpha * t)
    step = -RK4_REAL_LIMIT / alpha
    return {
        "residual": PartAnswer(
            residual,
            rf"e(t) = e_0\,(1 + \alpha t)\,e^{{-\alpha t}} = {residual:.4g}\ \mathrm{{mm}}",
            {
                "no-linear-term": e0 * math.exp(-alpha * t),
                "rate-two-alpha": e0 * (1.0 + 2.0 * alpha * t) * math.exp(-2.0 * alpha * t),
            },
        ),
        "step": PartAnswer(
            step,
            rf"h\,\alpha \le {-RK4_REAL_LIMIT:.4f} \Rightarrow h_{{\max}} = {step:.4g}\ \mathrm{{s}}",
            {"euler-limit": 2.0 / alpha, "rate-two-alpha": -RK4_REAL_LIMIT / (2.0 * alpha)},
        ),
        "undamped": PartAnswer(
            "oscillates",
            r"\alpha = 0:\ \ddot e + \beta^2 e = 0,\ e = e_0\cos\beta t",
            {"uncorrected": "grows"},
        ),
    }


def pendulum_consistent_start(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The Cartesian pendulum (pivot at the origin, y up, rod L): the requested start moved the least distance onto
    the circle (along the ray from the pivot), its velocity stripped of the part along the rod, and the rod's tension
    there (m v²/L − m g y/L)."""
    mass, length, gravity = given["mass_kg"], given["length_m"], given["g_m_s2"]
    requested = np.array([given["x0_m"], given["y0_m"], 0.0])
    velocity0 = np.array([given["vx0_m_s"], given["vy0_m_s"], 0.0])
    distance = float(np.linalg.norm(requested))
    if not 0.3 * length <= distance <= 3.0 * length:
        raise ValueError("the requested start is too near the pivot, or too far from the circle, to be a fair request")
    direction = requested / distance
    position = length * direction
    velocity = velocity0 - float(velocity0 @ direction) * direction
    if float(np.linalg.norm(velocity)) < 0.1:
        raise ValueError("the requested velocity is nearly along the rod: almost nothing of it is left")
    one_step = requested * (1.0 + (length**2 - distance**2) / (2.0 * distance**2))
    speed2 = float(velocity @ velocity)
    tension = mass * speed2 / length - mass * gravity * float(position[1]) / length
    return {
        "position": PartAnswer(
            _vector(position),
            rf"\mathbf r = L\,\frac{{\mathbf r_0}}{{|\mathbf r_0|}} = ({position[0]:.4g},\ {position[1]:.4g},\ 0)"
            r"\ \mathrm{m}",
            {"one-step": _vector(one_step)},
        ),
        "velocity": PartAnswer(
            _vector(velocity),
            r"\mathbf v = \mathbf v_0 - (\mathbf v_0\cdot\mathbf n)\,\mathbf n"
            rf" = ({velocity[0]:.4g},\ {velocity[1]:.4g},\ 0)\ \mathrm{{m/s}}"
            r"\quad(\mathbf n = \mathbf r / L)",
            {"kept-radial": _vector(velocity0 - velocity), "unchanged": _vector(velocity0)},
        ),
        "tension": PartAnswer(
            tension,
            rf"T = \lambda L = \frac{{m v^2}}{{L}} - \frac{{m g y}}{{L}} = {tension:.4g}\ \mathrm{{N}}",
            {
                "no-gravity": mass * speed2 / length,
                "requested-speed": mass * float(velocity0 @ velocity0) / length
                - mass * gravity * float(position[1]) / length,
            },
        ),
    }


def belt_stick_slip(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The block on the moving belt (spring k to a post, N = m g) in its stick–slip limit cycle: where sticking
    ends, how long it sticks and slips, and the heat friction makes in one cycle."""
    mass, k, speed = given["mass_kg"], given["stiffness_n_m"], given["belt_speed_m_s"]
    mu_s, mu_k, gravity = given["mu_static"], given["mu_kinetic"], given["g_m_s2"]
    if mu_k >= mu_s:
        raise ValueError("the kinetic coefficient must be below the static one for a stick–slip cycle")
    normal = mass * gravity
    omega = math.sqrt(k / mass)
    d = (mu_s - mu_k) * normal / k
    x_break = mu_s * normal / k
    stick = 2.0 * d / speed
    slip = (math.pi + 2.0 * math.atan(speed / (omega * d))) / omega
    heat = mu_k * normal * (speed * slip + 2.0 * d)
    return {
        "break": PartAnswer(
            x_break,
            rf"k x = \mu_s N \Rightarrow x = \mu_s m g / k = {x_break:.4g}\ \mathrm{{m}}",
            {"kinetic": mu_k * normal / k},
        ),
        "stick": PartAnswer(
            stick,
            r"\text{stick from } (2\mu_k - \mu_s)N/k \text{ to } \mu_s N/k:\ T_{\text{stick}} = \frac{2d}{v_b}"
            rf" = {stick:.4g}\ \mathrm{{s}}",
            {"from-centre": d / speed},
        ),
        "slip": PartAnswer(
            slip,
            r"T_{\text{slip}} = \frac{\pi + 2\arctan\!\big(v_b/(\omega d)\big)}{\omega}"
            rf" = {slip:.4g}\ \mathrm{{s}}",
            {"half-period": math.pi / omega},
        ),
        "heat": PartAnswer(
            heat,
            r"E = \mu_k N\int|v_{\text{rel}}|\,dt = \mu_k N\,(v_b T_{\text{slip}} + 2d)"
            rf" = {heat:.4g}\ \mathrm{{J}}",
            {"belt-distance": mu_k * normal * speed * slip},
        ),
    }
