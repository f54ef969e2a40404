"""Answers of chapter 9's exercises: Hamilton's principle and Ritz series, generalized momenta with Hamilton's and
Routh's equations, and quasi-velocities with Gibbs–Appell and Kane.

Conventions follow the lessons of chapter 9: a cantilever's position ξ = x/L from the clamp, the spherical
pendulum's θ from the downward vertical with the azimuth φ about the upward vertical, the rolling disk's heading ψ,
lean θ and spin φ with R_NB = Rz(ψ) Rx(θ) Ry(φ) (body y the disk's axis).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import scipy.linalg
import sympy

from app.physics.systems.ch09.spherical_pendulum_model import turning_angles_rad
from app.practice.exercise import PartAnswer

# ---- 9.1 Hamilton's principle -------------------------------------------------------------------------------------

#: The two-term monomial Ritz series w = L (q₁ ξ² + q₂ ξ³) of a cantilever:
#: M_ij = ∫ φ_i φ_j dξ, K_ij = ∫ φ_i'' φ_j'' dξ.
TWO_TERM_MASS = np.array([[1 / 5, 1 / 6], [1 / 6, 1 / 7]])
TWO_TERM_STIFFNESS = np.array([[4.0, 6.0], [6.0, 12.0]])
#: The static tip-load shape ψ(ξ) = ξ²(3 − ξ)/2: ∫ ψ''² dξ = 3 and ∫ ψ² dξ = 33/140.
STATIC_SHAPE_CURVATURE = 3.0
STATIC_SHAPE_MASS = 33.0 / 140.0


def two_term_ritz_cantilever(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A uniform cantilever (L, EI, ρA) by the Ritz series with ξ² alone and with ξ² and ξ³: the one-term frequency,
    both two-term frequencies (rad/s), and on which side of the exact frequencies Ritz values lie."""
    length, rigidity, density = given["length_m"], given["rigidity_n_m2"], given["mass_per_length_kg_m"]
    scale = math.sqrt(rigidity / (density * length**4))
    one_term = math.sqrt(TWO_TERM_STIFFNESS[0, 0] / TWO_TERM_MASS[0, 0]) * scale
    factors = np.sqrt(scipy.linalg.eigh(TWO_TERM_STIFFNESS, TWO_TERM_MASS, eigvals_only=True))
    omega1, omega2 = (float(f) * scale for f in factors)
    diagonal = math.sqrt(TWO_TERM_STIFFNESS[1, 1] / TWO_TERM_MASS[1, 1]) * scale
    hz = 1.0 / (2.0 * math.pi)
    return {
        "one-term": PartAnswer(
            one_term,
            rf"K_{{11}} = 4,\ M_{{11}} = \tfrac15:\ \omega = \sqrt{{20}}\sqrt{{\frac{{EI}}{{\rho A L^4}}}}"
            rf" = \sqrt{{20}}\times {scale:.4g} = {one_term:.4g}\ \mathrm{{rad/s}}",
            {"hertz": one_term * hz},
        ),
        "omega1": PartAnswer(
            omega1,
            r"K = \begin{bmatrix}4 & 6\\ 6 & 12\end{bmatrix},\ M = \begin{bmatrix}\tfrac15 & \tfrac16\\ \tfrac16 &"
            r" \tfrac17\end{bmatrix},\ \det(K - \lambda^2 M) = 0:\ "
            rf"\lambda_1 = {factors[0]:.5g},\ \omega_1 = {omega1:.4g}\ \mathrm{{rad/s}}",
            {"one-term": one_term, "hertz": omega1 * hz},
        ),
        "omega2": PartAnswer(
            omega2,
            rf"\lambda_2 = {factors[1]:.5g},\ \omega_2 = \lambda_2\sqrt{{\frac{{EI}}{{\rho A L^4}}}} = {omega2:.4g}"
            r"\ \mathrm{rad/s}",
            {"diagonal-only": diagonal, "hertz": omega2 * hz},
        ),
        "bound": PartAnswer(
            "above",
            r"\text{a Ritz series is the true system with extra constraints: } \omega_n^{\text{Ritz}} \ge \omega_n",
            {"below": "below"},
        ),
    }


def tip_mass_static_shape(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A uniform cantilever (L, EI, ρA) carrying a point mass M at its tip, by one Ritz term whose shape is the
    static tip-load deflection ψ = ξ²(3 − ξ)/2 with q the tip deflection: the stiffness, the equivalent mass at the
    tip and the frequency."""
    length, rigidity = given["length_m"], given["rigidity_n_m2"]
    density, tip = given["mass_per_length_kg_m"], given["tip_mass_kg"]
    beam = density * length
    stiffness = STATIC_SHAPE_CURVATURE * rigidity / length**3
    mass = STATIC_SHAPE_MASS * beam + tip
    omega = math.sqrt(stiffness / mass)
    return {
        "stiffness": PartAnswer(
            stiffness,
            r"V = \tfrac12 \frac{EI}{L^3}\,q^2\!\int_0^1 \psi''^2\,d\xi,\ \psi'' = 3(1 - \xi),"
            r"\ \int_0^1 9(1-\xi)^2 d\xi"
            rf" = 3:\ k = \frac{{3EI}}{{L^3}} = {stiffness:.4g}\ \mathrm{{N/m}}",
            {"no-chain-rule": STATIC_SHAPE_CURVATURE * rigidity * length},
        ),
        "mass": PartAnswer(
            mass,
            r"T = \tfrac12\dot q^2\left(\rho A L\!\int_0^1\psi^2 d\xi + M\right),"
            r"\ \int_0^1 \psi^2 d\xi = \tfrac{33}{140}:"
            rf"\ m_{{\mathrm{{eq}}}} = \tfrac{{33}}{{140}}\,{beam:.4g} + {tip:.4g} = {mass:.4g}\ \mathrm{{kg}}",
            {"no-beam-mass": tip, "whole-beam": beam + tip},
        ),
        "omega": PartAnswer(
            omega,
            rf"\omega = \sqrt{{k/m_{{\mathrm{{eq}}}}}} = {omega:.4g}\ \mathrm{{rad/s}}",
            {"no-beam-mass": math.sqrt(stiffness / tip), "hertz": omega / (2.0 * math.pi)},
        ),
    }


a_sym, m_sym, g_sym, tau_sym = sympy.symbols("a m g tau", real=True)


def toss_action(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A ball tossed straight up that returns to the hand after τ, height x up from the hand: the action of the trial
    path x = a sin(πt/τ) as a function of a, the a that makes it stationary, the action there, and the true path's
    action −m g² τ³/24."""
    m, tau, g = given["mass_kg"], given["flight_time_s"], given["g_m_s2"]
    pi = sympy.pi
    action = m_sym * pi**2 * a_sym**2 / (4 * tau_sym) - 2 * m_sym * g_sym * tau_sym * a_sym / pi
    best = 4.0 * g * tau**2 / math.pi**3
    trial = -4.0 * m * g**2 * tau**3 / math.pi**4
    no_half_best = 2.0 * g * tau**2 / math.pi**3
    true = -m * g**2 * tau**3 / 24.0
    return {
        "action": PartAnswer(
            action,
            r"S(a) = \int_0^\tau\left(\tfrac12 m\dot x^2 - m g x\right)dt"
            r" = \frac{m\pi^2 a^2}{2\tau^2}\cdot\frac{\tau}{2} - m g a\,\frac{2\tau}{\pi}"
            r" = \frac{\pi^2 m a^2}{4\tau} - \frac{2 m g \tau a}{\pi}",
            {
                "potential-sign": m_sym * pi**2 * a_sym**2 / (4 * tau_sym) + 2 * m_sym * g_sym * tau_sym * a_sym / pi,
                "cos-squared": m_sym * pi**2 * a_sym**2 / (2 * tau_sym) - 2 * m_sym * g_sym * tau_sym * a_sym / pi,
            },
        ),
        "amplitude": PartAnswer(
            best,
            rf"\frac{{dS}}{{da}} = \frac{{\pi^2 m a}}{{2\tau}} - \frac{{2 m g\tau}}{{\pi}} = 0:\ a^* ="
            rf" \frac{{4 g\tau^2}}{{\pi^3}} = {best:.4g}\ \mathrm{{m}}",
            {"true-peak": g * tau**2 / 8.0, "cos-squared": no_half_best},
        ),
        "trial-action": PartAnswer(
            trial,
            rf"S(a^*) = -\frac{{4 m g^2\tau^3}}{{\pi^4}} = {trial:.4g}\ \mathrm{{J\,s}}",
            {"cos-squared": -2.0 * m * g**2 * tau**3 / math.pi**4},
        ),
        "true-action": PartAnswer(
            true,
            r"x = \tfrac12 g t(\tau - t):\ \int_0^\tau \tfrac12 m g^2(\tfrac\tau2 - t)^2 dt"
            r" - \int_0^\tau \tfrac12 m g^2 t(\tau - t)\,dt"
            rf" = \frac{{m g^2\tau^3}}{{24}} - \frac{{m g^2\tau^3}}{{12}} = {true:.4g}\ \mathrm{{J\,s}}",
            {"potential-sign": m * g**2 * tau**3 / 8.0},
        ),
    }


# ---- 9.2 Generalized momentum principles --------------------------------------------------------------------------

theta_sym, beta_sym, l_sym = sympy.symbols("theta beta l", real=True)


def spherical_pendulum_routh(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A spherical pendulum released at θ0 from the downward vertical with θ̇0 = 0 and azimuth rate φ̇0: its
    conserved β = m l² sin²θ0 φ̇0, Routh's effective potential, which way θ first moves, and the other turning
    angle (V_eff = E)."""
    m, length, g = given["mass_kg"], given["length_m"], given["g_m_s2"]
    theta0 = math.radians(given["theta_0_deg"])
    phi_rate = math.radians(given["phi_rate_0_deg_s"])
    cone_rate = math.sqrt(g / (length * math.cos(theta0)))
    if abs(phi_rate / cone_rate - 1.0) < 0.15:
        raise ValueError("too near the steady cone: the two turning angles nearly meet")
    beta = m * length**2 * math.sin(theta0) ** 2 * phi_rate
    params = {"mass_kg": m, "length_m": length, "g_m_s2": g}
    low, high = turning_angles_rad(params, np.array([theta0, 0.0, 0.0, phi_rate]))
    other = high if phi_rate > cone_rate else low
    other_deg = math.degrees(other)
    direction = "outward" if phi_rate > cone_rate else "inward"
    veff = beta_sym**2 / (2 * m_sym * l_sym**2 * sympy.sin(theta_sym) ** 2) - m_sym * g_sym * l_sym * sympy.cos(
        theta_sym
    )
    return {
        "beta": PartAnswer(
            beta,
            rf"\beta = \frac{{\partial L}}{{\partial\dot\phi}} = m l^2\sin^2\theta_0\,\dot\phi_0 = {beta:.4g}"
            r"\ \mathrm{kg\,m^2/s}",
            {
                "degrees": beta * 180.0 / math.pi,
                "sine-not-squared": m * length**2 * math.sin(theta0) * phi_rate,
            },
        ),
        "veff": PartAnswer(
            veff,
            r"R = L - \beta\dot\phi,\ \dot\phi = \frac{\beta}{m l^2\sin^2\theta}:\ R = \tfrac12 m l^2\dot\theta^2"
            r" - \left(\frac{\beta^2}{2 m l^2\sin^2\theta} - m g l\cos\theta\right)",
            {
                "substituted-in-lagrangian": -(beta_sym**2) / (2 * m_sym * l_sym**2 * sympy.sin(theta_sym) ** 2)
                - m_sym * g_sym * l_sym * sympy.cos(theta_sym),
                "gravity-sign": beta_sym**2 / (2 * m_sym * l_sym**2 * sympy.sin(theta_sym) ** 2)
                + m_sym * g_sym * l_sym * sympy.cos(theta_sym),
            },
        ),
        "direction": PartAnswer(
            direction,
            rf"\sqrt{{g/(l\cos\theta_0)}} = {cone_rate:.4g}\ \mathrm{{rad/s}}"
            + (r" < " if direction == "outward" else r" > ")
            + rf"\dot\phi_0 = {phi_rate:.4g}\ \mathrm{{rad/s}}",
            {"reversed": "inward" if direction == "outward" else "outward"},
        ),
        "other-angle": PartAnswer(
            other_deg,
            rf"V_{{\mathrm{{eff}}}}(\theta) = E = V_{{\mathrm{{eff}}}}(\theta_0):\ \theta = {other_deg:.4g}^\circ",
            {"start-angle": given["theta_0_deg"]},
        ),
    }


p_sym, big_r, omega_sym = sympy.symbols("p R Omega", real=True)


def bead_jacobi_integral(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A bead on a hoop driven at a constant Ω about its vertical diameter, released at θ0 from the bottom at rest
    relative to the hoop: its Hamiltonian (the Jacobi integral, not T + V), h at release, θ̇ as it passes the bottom,
    and which quantity is conserved."""
    radius, spin, g, m = given["hoop_radius_m"], given["hoop_speed_rad_s"], given["g_m_s2"], given["bead_mass_kg"]
    theta0 = math.radians(given["theta_0_deg"])
    c, s = math.cos(theta0), math.sin(theta0)
    h = -0.5 * m * radius**2 * spin**2 * s**2 - m * g * radius * c
    energy = 0.5 * m * radius**2 * spin**2 * s**2 - m * g * radius * c
    gravity_share = 2.0 * g / radius * (1.0 - c)
    rate_squared = gravity_share - spin**2 * s**2
    if rate_squared < 0.2 * gravity_share:
        raise ValueError("the bead would barely reach the bottom, or not at all")
    rate = math.sqrt(rate_squared)
    hamiltonian = (
        p_sym**2 / (2 * m_sym * big_r**2)
        - m_sym * big_r**2 * omega_sym**2 * sympy.sin(theta_sym) ** 2 / 2
        - m_sym * g_sym * big_r * sympy.cos(theta_sym)
    )
    return {
        "hamiltonian": PartAnswer(
            hamiltonian,
            r"p = \frac{\partial L}{\partial\dot\theta} = m R^2\dot\theta,\ H = p\dot\theta - L"
            r" = \frac{p^2}{2 m R^2} - \tfrac12 m R^2\Omega^2\sin^2\theta - m g R\cos\theta",
            {
                "energy-sign": hamiltonian + m_sym * big_r**2 * omega_sym**2 * sympy.sin(theta_sym) ** 2,
                "linear-momentum": hamiltonian + p_sym**2 / (2 * m_sym) - p_sym**2 / (2 * m_sym * big_r**2),
            },
        ),
        "jacobi": PartAnswer(
            h,
            rf"h = -\tfrac12 m R^2\Omega^2\sin^2\theta_0 - m g R\cos\theta_0 = {h:.4g}\ \mathrm{{J}}",
            {"energy": energy},
        ),
        "bottom-rate": PartAnswer(
            rate,
            r"\tfrac12 m R^2\dot\theta_b^2 - m g R = h:\ \dot\theta_b^2 = \frac{2g}{R}(1 - \cos\theta_0)"
            rf" - \Omega^2\sin^2\theta_0,\ |\dot\theta_b| = {rate:.4g}\ \mathrm{{rad/s}}",
            {
                "energy-conserved": math.sqrt(gravity_share + spin**2 * s**2),
                "plain-pendulum": math.sqrt(gravity_share),
            },
        ),
        "conserved": PartAnswer(
            "h-only",
            r"\partial L/\partial t = 0 \Rightarrow h\ \text{constant};\ T + V\ \text{changes by the motor's work}",
            {"both": "both"},
        ),
    }


r_sym, rd_sym, m1_sym, m2_sym = sympy.symbols("r rd m1 m2", real=True)


def puck_and_hanging_weight(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A puck (m1) on a smooth table tied by a string through a hole to a hanging weight (m2), started at r0 with
    ṙ = 0 and φ̇0: β = m1 r0² φ̇0, Routh's function for r, the radius of the steady circle at this β and the
    frequency of small radial oscillations about it."""
    m1, m2, r0, phi_rate, g = (
        given["puck_mass_kg"],
        given["hanging_mass_kg"],
        given["radius_0_m"],
        given["phi_rate_0_rad_s"],
        given["g_m_s2"],
    )
    beta = m1 * r0**2 * phi_rate
    steady = (beta**2 / (m1 * m2 * g)) ** (1.0 / 3.0)
    frequency = math.sqrt(3.0 * m2 * g / ((m1 + m2) * steady))
    routhian = (m1_sym + m2_sym) * rd_sym**2 / 2 - beta_sym**2 / (2 * m1_sym * r_sym**2) - m2_sym * g_sym * r_sym
    return {
        "beta": PartAnswer(
            beta,
            rf"\beta = \frac{{\partial L}}{{\partial\dot\phi}} = m_1 r_0^2\dot\phi_0 = {beta:.4g}"
            r"\ \mathrm{kg\,m^2/s}",
            {"both-masses": (m1 + m2) * r0**2 * phi_rate},
        ),
        "routhian": PartAnswer(
            routhian,
            r"L = \tfrac12(m_1 + m_2)\dot r^2 + \tfrac12 m_1 r^2\dot\phi^2 - m_2 g r,\ R = L - \beta\dot\phi"
            r" = \tfrac12(m_1 + m_2)\dot r^2 - \frac{\beta^2}{2 m_1 r^2} - m_2 g r",
            {
                "substituted-in-lagrangian": routhian + beta_sym**2 / (m1_sym * r_sym**2),
                "no-hanging-inertia": routhian - m2_sym * rd_sym**2 / 2,
            },
        ),
        "radius": PartAnswer(
            steady,
            rf"\frac{{\beta^2}}{{m_1 r_s^3}} = m_2 g:\ r_s = \left(\frac{{\beta^2}}{{m_1 m_2 g}}\right)^{{1/3}}"
            rf" = {steady:.4g}\ \mathrm{{m}}",
            {"fixed-spin-rate": m2 * g / (m1 * phi_rate**2)},
        ),
        "frequency": PartAnswer(
            frequency,
            r"V_{\mathrm{eff}}''(r_s) = \frac{3\beta^2}{m_1 r_s^4} = \frac{3 m_2 g}{r_s}:\ "
            rf"\omega_r = \sqrt{{\frac{{3 m_2 g}}{{(m_1 + m_2)\,r_s}}}} = {frequency:.4g}\ \mathrm{{rad/s}}",
            {
                "no-hanging-inertia": math.sqrt(3.0 * m2 * g / (m1 * steady)),
                "second-derivative": math.sqrt(m2 * g / ((m1 + m2) * steady)),
            },
        ),
    }


# ---- 9.3 Quasi-coordinates ----------------------------------------------------------------------------------------


def kane_wheel_on_incline(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A wheel (m, r, radius of gyration k about its axle) rolling without slip down a slope β, with the generalized
    speed u the centre's speed down the slope (x down the slope, y out of the slope, z = x × y): the partial angular
    velocity, the generalized active force, the coefficient of u̇ in the generalized inertia force, and u̇."""
    m, r, k, g = given["mass_kg"], given["radius_m"], given["gyration_m"], given["g_m_s2"]
    slope = math.radians(given["slope_deg"])
    active = m * g * math.sin(slope)
    effective = m * (1.0 + k**2 / r**2)
    acceleration = active / effective
    friction = m * g * math.sin(slope) * k**2 / (r**2 + k**2)
    return {
        "partial-omega": PartAnswer(
            (0.0, 0.0, -1.0 / r),
            r"\mathbf v_P = \mathbf v_G + \boldsymbol\omega\times(-r\,\mathbf j) = (u + r\omega_z)\,\mathbf i = 0:\ "
            rf"\boldsymbol\omega = -\frac{{u}}{{r}}\mathbf k,\ \boldsymbol\omega^{{(1)}} = -\frac1r\mathbf k"
            rf" = (0,\ 0,\ {-1.0 / r:.4g})\ \mathrm{{m^{{-1}}}}",
            {"sign": (0.0, 0.0, 1.0 / r), "radius-for-inverse": (0.0, 0.0, -r)},
        ),
        "active": PartAnswer(
            active,
            r"F_1 = m g(\sin\beta\,\mathbf i - \cos\beta\,\mathbf j)\cdot\mathbf i + (\mathbf N + \mathbf f)\cdot"
            rf"\mathbf v_P^{{(1)}} = m g\sin\beta + 0 = {active:.4g}\ \mathrm{{N}}",
            {"cosine": m * g * math.cos(slope), "friction-at-centre": active - friction},
        ),
        "inertia": PartAnswer(
            effective,
            r"F_1^* = -m\dot u\,\mathbf i\cdot\mathbf i - I_G\dot{\boldsymbol\omega}\cdot\boldsymbol\omega^{(1)}"
            rf" = -\left(m + \frac{{m k^2}}{{r^2}}\right)\dot u:\ m + \frac{{m k^2}}{{r^2}} = {effective:.4g}"
            r"\ \mathrm{kg}",
            {"no-rotation": m, "contact-inertia": m * (1.0 + (k**2 + r**2) / r**2)},
        ),
        "acceleration": PartAnswer(
            acceleration,
            rf"F_1 + F_1^* = 0:\ \dot u = \frac{{g\sin\beta}}{{1 + k^2/r^2}} = {acceleration:.4g}\ \mathrm{{m/s^2}}",
            {"sliding": g * math.sin(slope)},
        ),
    }


u1d_sym, u2_sym, u3_sym, i1_sym, i2_sym, i3_sym = sympy.symbols("u1d u2 u3 I1 I2 I3", real=True)


def gibbs_appell_body(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A rigid body with principal moments (I1, I2, I3) about G, body angular velocity ω = (u1, u2, u3) and a torque
    M1 about body x, with the speeds u_i the body components of ω: the vector ω × Iω whose components multiply u̇_i in
    the Gibbs function, ∂S/∂u̇1, and ω̇ from ∂S/∂u̇_i = M_i."""
    moments = np.array([given["i1_kg_m2"], given["i2_kg_m2"], given["i3_kg_m2"]])
    if max(moments) >= sum(moments) - max(moments):
        raise ValueError("no body has these principal moments (triangle inequality)")
    omega = np.array([given["u1_rad_s"], given["u2_rad_s"], given["u3_rad_s"]])
    torque = np.array([given["torque_n_m"], 0.0, 0.0])
    gyro = np.cross(omega, moments * omega)
    alpha = (torque - gyro) / moments
    derivative = i1_sym * u1d_sym + (i3_sym - i2_sym) * u2_sym * u3_sym

    def vector(v: np.ndarray) -> tuple[float, ...]:
        return tuple(float(c) for c in v)

    return {
        "gyroscopic": PartAnswer(
            vector(gyro),
            r"\boldsymbol\omega\times I\boldsymbol\omega = \big((I_3 - I_2)u_2u_3,\ (I_1 - I_3)u_3u_1,\ "
            rf"(I_2 - I_1)u_1u_2\big) = ({gyro[0]:.4g},\ {gyro[1]:.4g},\ {gyro[2]:.4g})\ \mathrm{{N\,m}}",
            {"order-swapped": vector(-gyro)},
        ),
        "derivative": PartAnswer(
            derivative,
            r"S = \tfrac12\sum_i I_i\dot u_i^2 + \dot{\mathbf u}\cdot(\boldsymbol\omega\times I\boldsymbol\omega)"
            r" + \dots:\ \frac{\partial S}{\partial\dot u_1} = I_1\dot u_1 + (I_3 - I_2)u_2u_3",
            {
                "gyro-sign": i1_sym * u1d_sym + (i2_sym - i3_sym) * u2_sym * u3_sym,
                "no-gyroscopic": i1_sym * u1d_sym,
            },
        ),
        "alpha": PartAnswer(
            vector(alpha),
            r"\dot u_i = \frac{M_i - (\boldsymbol\omega\times I\boldsymbol\omega)_i}{I_i}:\ "
            rf"\dot{{\boldsymbol\omega}} = ({alpha[0]:.4g},\ {alpha[1]:.4g},\ {alpha[2]:.4g})\ \mathrm{{rad/s^2}}",
            {"no-gyroscopic": vector(torque / moments), "gyro-sign": vector((torque + gyro) / moments)},
        ),
    }


def rolling_disk_partials(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The thin disk rolling without slip (m, r), leaning θ: in the heading frame (e1 along the heading, e3 up,
    e2 = e3 × e1) the partial velocities of its centre for u_ψ and u_θ, gravity's generalized active force for u_θ,
    and which forces enter Kane's generalized active forces."""
    m, r, g = given["mass_kg"], given["radius_m"], given["g_m_s2"]
    lean = math.radians(given["lean_0_deg"])
    c, s = math.cos(lean), math.sin(lean)
    active = m * g * r * s
    return {
        "v-psi": PartAnswer(
            (r * s, 0.0, 0.0),
            r"\mathbf r_{G/P} = r(-\sin\theta\,\mathbf e_2 + \cos\theta\,\mathbf e_3),\ \mathbf v_G = \boldsymbol\omega"
            r"\times\mathbf r_{G/P},\ \frac{\partial\mathbf v_G}{\partial u_\psi} = \mathbf e_3\times\mathbf r_{G/P}"
            rf" = r\sin\theta\,\mathbf e_1 = ({r * s:.4g},\ 0,\ 0)\ \mathrm{{m}}",
            {"cosine-lever": (r * c, 0.0, 0.0), "sign": (-r * s, 0.0, 0.0)},
        ),
        "v-theta": PartAnswer(
            (0.0, -r * c, -r * s),
            r"\frac{\partial\mathbf v_G}{\partial u_\theta} = \mathbf e_1\times\mathbf r_{G/P}"
            r" = -r(\cos\theta\,\mathbf e_2"
            rf" + \sin\theta\,\mathbf e_3) = (0,\ {-r * c:.4g},\ {-r * s:.4g})\ \mathrm{{m}}",
            {"sign": (0.0, r * c, r * s), "sine-cosine-swapped": (0.0, -r * s, -r * c)},
        ),
        "active": PartAnswer(
            active,
            rf"F_\theta = (-m g\,\mathbf e_3)\cdot\mathbf v_G^{{(\theta)}} = m g r\sin\theta = {active:.4g}"
            r"\ \mathrm{N\,m}",
            {"cosine": m * g * r * c, "sign": -active},
        ),
        "forces": PartAnswer(
            "gravity",
            r"\mathbf v_P^{(r)} = 0\ \text{for the contact point: the floor's forces drop out}",
            {"normal-too": "gravity-normal"},
        ),
    }
