"""Answers of chapter 7's exercises: Lagrange's equations for the systems of the derivation engine's catalogue."""

from __future__ import annotations

import math
from collections.abc import Mapping

import sympy
from scipy.special import ellipk

from app.practice.exercise import PartAnswer

theta, theta_rate, m, R, Omega, g = sympy.symbols("theta thetad m R Omega g", real=True)


def bead_on_hoop_lagrange(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The bead on a hoop spun at a prescribed Ω about its vertical diameter (θ from the bottom): T, V (up to a
    constant), the equation of motion solved for θ̈, and the steady angle off the bottom at the given numbers."""
    kinetic = m * R**2 * (theta_rate**2 + Omega**2 * sympy.sin(theta) ** 2) / 2
    potential = -m * g * R * sympy.cos(theta)
    acceleration = (Omega**2 * sympy.cos(theta) - g / R) * sympy.sin(theta)
    radius, spin, gravity = given["hoop_radius_m"], given["hoop_speed_rad_s"], given["g_m_s2"]
    ratio = gravity / (radius * spin**2)
    if ratio >= 1.0:
        raise ValueError("the hoop turns too slowly for a steady angle off the bottom")
    steady = math.degrees(math.acos(ratio))
    return {
        "kinetic": PartAnswer(
            kinetic,
            r"T = \tfrac12 m \left(R^2\dot\theta^2 + (R\sin\theta)^2\,\Omega^2\right)",
            {
                "no-hoop-spin": m * R**2 * theta_rate**2 / 2,
                "spin-radius-cos": m * R**2 * (theta_rate**2 + Omega**2 * sympy.cos(theta) ** 2) / 2,
            },
        ),
        "potential": PartAnswer(
            potential, r"V = -m g R \cos\theta \quad(\text{zero at the hoop's centre})", {"potential-sign": -potential}
        ),
        "equation": PartAnswer(
            acceleration,
            r"m R^2 \ddot\theta - m R^2 \Omega^2 \sin\theta\cos\theta + m g R \sin\theta = 0"
            r"\ \Rightarrow\ \ddot\theta = \left(\Omega^2\cos\theta - \tfrac{g}{R}\right)\sin\theta",
            {
                "no-centrifugal": -g / R * sympy.sin(theta),
                "gravity-sign": (Omega**2 * sympy.cos(theta) + g / R) * sympy.sin(theta),
            },
        ),
        "steady": PartAnswer(
            steady,
            rf"\cos\theta_s = \frac{{g}}{{R\,\Omega^2}} = {ratio:.4g},\ \theta_s = {steady:.4g}^\circ",
            {"steady-sine": math.degrees(math.asin(ratio))},
        ),
    }


# -- 7.1 Virtual work -----------------------------------------------------------------------------------------------


def toggle_press_hold(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The toggle press of lesson 7.1 with unequal bars: AB (a) pinned at A, BC (b) to a slider C on the line AC, AB
    at θ above AC; loads P at the knee B and weights W₁, W₂ at the bars' midpoints, all downward. Releasing C's hold
    leaves one degree of freedom θ: δr_B = a(−sin θ, cos θ) δθ, x_C′ = −a sin θ (1 + a cos θ/√(b² − a² sin²θ)), and
    δW = −(P + W₁/2 + W₂/2) a cos θ δθ − Q x_C′ δθ = 0 gives the hold Q (on C along −x)."""
    a, b, angle = given["bar_ab_m"], given["bar_bc_m"], math.radians(given["angle_deg"])
    load, w1, w2 = given["load_n"], given["weight_ab_n"], given["weight_bc_n"]
    if a * math.sin(angle) > 0.9 * b:
        raise ValueError("bar BC must reach the line AC well clear of the vertical")
    span = math.sqrt(b**2 - (a * math.sin(angle)) ** 2)
    knee = (-a * math.sin(angle), a * math.cos(angle), 0.0)
    slider = -a * math.sin(angle) * (1.0 + a * math.cos(angle) / span)
    lift = a * math.cos(angle)  # y_B′; the midpoints rise half as much (C stays on the line)

    def hold(weights_share: float) -> float:
        return -(load + weights_share) * lift / slider

    q = hold(0.5 * (w1 + w2))
    return {
        "knee": PartAnswer(
            knee,
            rf"\bar r_B = a(\cos\theta,\ \sin\theta)\ \Rightarrow\ \delta\bar r_B/\delta\theta = a(-\sin\theta,\ "
            rf"\cos\theta) = ({knee[0]:.4g},\ {knee[1]:.4g})\ \mathrm{{m}}",
            {"position-not-rate": (a * math.cos(angle), a * math.sin(angle), 0.0)},
        ),
        "slider": PartAnswer(
            slider,
            r"x_C = a\cos\theta + \sqrt{b^2 - a^2\sin^2\theta}\ \Rightarrow\ x_C' = -a\sin\theta\left(1 + "
            rf"\frac{{a\cos\theta}}{{\sqrt{{b^2 - a^2\sin^2\theta}}}}\right) = {slider:.4g}\ \mathrm{{m}}",
            {"bc-not-turning": -a * math.sin(angle)},
        ),
        "hold": PartAnswer(
            q,
            r"\delta W = \left[-\left(P + \tfrac12 W_1 + \tfrac12 W_2\right) a\cos\theta - Q\,x_C'\right]\delta\theta"
            rf" = 0\ \Rightarrow\ Q = {q:.4g}\ \mathrm{{N}}",
            {"weights-at-knee": hold(w1 + w2), "weights-left-out": hold(0.0)},
        ),
    }


def scissor_lift_force(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A scissor lift of n stages of crossed bars (length L, weight w each, two per stage) at angle θ to the
    horizontal, carrying a platform of weight W; a horizontal actuator force F pushes the bottom slider towards the
    fixed bottom pin. h = n L sin θ, x_slider = L cos θ; the bars' centres of stage i are at (i − ½) L sin θ.
    δW = F L sin θ δθ − W n L cos θ δθ − w n² L cos θ δθ = 0 ⇒ F = n (W + n w)/tan θ."""
    stages, length, angle = round(given["stages"]), given["bar_m"], math.radians(given["angle_deg"])
    platform, bar = given["platform_n"], given["bar_n"]
    rise = stages * length * math.cos(angle)
    force = stages * (platform + stages * bar) / math.tan(angle)
    return {
        "rise": PartAnswer(
            rise,
            rf"h = n L\sin\theta\ \Rightarrow\ \delta h/\delta\theta = n L\cos\theta = {rise:.4g}\ \mathrm{{m}}",
            {"one-stage": length * math.cos(angle)},
        ),
        "force": PartAnswer(
            force,
            r"F L\sin\theta - W n L\cos\theta - 2w L\cos\theta\sum_{i=1}^{n}\left(i - \tfrac12\right) = 0"
            rf"\ \Rightarrow\ F = \frac{{n(W + n w)}}{{\tan\theta}} = {force:.4g}\ \mathrm{{N}}",
            {
                "bars-left-out": stages * platform / math.tan(angle),
                "bars-rise-like-platform": stages * (platform + 2 * stages * bar) / math.tan(angle),
            },
        ),
    }


def _slider_crank_coefficients(r: float, l: float, angle: float) -> dict[str, float]:
    """First and second θ-derivatives of the slider-crank's positions (zero offset, O at the origin, the slider on
    +x): x_B = r cos θ + √(l² − r² sin²θ), the rod's angle φ with sin φ = −r sin θ / l, G₂ the rod's midpoint."""
    s, c = math.sin(angle), math.cos(angle)
    span = math.sqrt(l**2 - (r * s) ** 2)
    x1 = -r * s - r**2 * s * c / span
    x2 = -r * c - r**2 * (c**2 - s**2) / span - r**4 * s**2 * c**2 / span**3
    phi1 = -r * c / span
    phi2 = r * s / span - r**3 * s * c**2 / span**3
    return {
        "x1": x1,
        "x2": x2,
        "phi1": phi1,
        "phi2": phi2,
        "g2x1": 0.5 * (-r * s + x1),
        "g2x2": 0.5 * (-r * c + x2),
        "g2y1": 0.5 * r * c,
        "g2y2": -0.5 * r * s,
    }


def crank_drive_torque(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The slider-crank (crank r, uniform, m_c; rod l, uniform, m_r; slider m_s; zero offset; gravity −y) with its
    crank held at a constant ω, at crank angle θ. With constant ω every acceleration is r″ ω² and the rod's angular
    acceleration φ″ ω². Dynamic virtual work: τ = Σ m a·r′ + I_G₂ α_rod φ′ + Σ m g y′; the crank's centre has only a
    centripetal acceleration, normal to its δr, and no angular acceleration."""
    r, l, angle, omega = given["crank_m"], given["rod_m"], math.radians(given["angle_deg"]), given["speed_rad_s"]
    m_c, m_r, m_s, gravity = given["crank_kg"], given["rod_kg"], given["slider_kg"], given["g_m_s2"]
    k = _slider_crank_coefficients(r, l, angle)
    accel = k["x2"] * omega**2
    if abs(accel) < 0.1 * r * omega**2:
        raise ValueError("too near the slider's fastest point: its acceleration nearly vanishes")
    gravity_part = (m_c + m_r) * gravity * 0.5 * r * math.cos(angle)
    inertia_part = omega**2 * (
        m_r * (k["g2x2"] * k["g2x1"] + k["g2y2"] * k["g2y1"])
        + m_s * k["x2"] * k["x1"]
        + m_r * l**2 / 12 * k["phi2"] * k["phi1"]
    )
    torque = inertia_part + gravity_part
    if abs(torque) < 0.2 * (abs(inertia_part) + abs(gravity_part)):
        raise ValueError("inertia and weight nearly cancel: a torque too sensitive to rounding")
    return {
        "slider-rate": PartAnswer(
            k["x1"],
            r"x_B = r\cos\theta + \sqrt{l^2 - r^2\sin^2\theta}\ \Rightarrow\ x_B' = -r\sin\theta - "
            rf"\frac{{r^2\sin\theta\cos\theta}}{{\sqrt{{l^2 - r^2\sin^2\theta}}}} = {k['x1']:.4g}\ \mathrm{{m}}",
            {"rod-ignored": -r * math.sin(angle)},
        ),
        "slider-accel": PartAnswer(
            accel,
            rf"\ddot x_B = x_B''\,\omega^2 = {accel:.4g}\ \mathrm{{m/s^2}}\quad(\ddot\theta = 0)",
            {"rod-ignored": -r * omega**2 * math.cos(angle)},
        ),
        "torque": PartAnswer(
            torque,
            r"\tau = \sum_i m_i\bar a_i\cdot\bar r_i' + I_{G_2}\alpha_{AB}\,\phi' + \sum_i m_i g\,y_i'"
            rf" = {inertia_part:.4g} + {gravity_part:.4g} = {torque:.4g}\ \mathrm{{N\,m}}",
            {"statics-only": gravity_part, "inertia-sign": gravity_part - inertia_part},
        ),
    }


# -- 7.2 Generalized coordinates and kinematical constraints ----------------------------------------------------


def double_pendulum_coordinates(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The double pendulum (rods l₁, l₂; θ₁, θ₂ each from the downward vertical). Four Cartesian coordinates of the
    bobs less two rod-length constraints: two degrees of freedom. r₂ = l₁(sin θ₁, −cos θ₁) + l₂(sin θ₂, −cos θ₂);
    v₂² = l₁²θ̇₁² + l₂²θ̇₂² + 2 l₁ l₂ θ̇₁ θ̇₂ cos(θ₁ − θ₂)."""
    l1, l2 = given["upper_m"], given["lower_m"]
    t1, t2 = math.radians(given["theta1_deg"]), math.radians(given["theta2_deg"])
    w1, w2 = given["rate1_rad_s"], given["rate2_rad_s"]
    bob = (l1 * math.sin(t1) + l2 * math.sin(t2), -l1 * math.cos(t1) - l2 * math.cos(t2), 0.0)
    relative = (l1 * math.sin(t1) + l2 * math.sin(t1 + t2), -l1 * math.cos(t1) - l2 * math.cos(t1 + t2), 0.0)
    speed = math.sqrt((l1 * w1) ** 2 + (l2 * w2) ** 2 + 2 * l1 * l2 * w1 * w2 * math.cos(t1 - t2))
    return {
        "dof": PartAnswer(
            "two", r"4\ \text{coordinates} - 2\ \text{constraints} = 2", {"four": "four", "three": "three"}
        ),
        "bob": PartAnswer(
            bob,
            r"\bar r_2 = l_1(\sin\theta_1,\ -\cos\theta_1) + l_2(\sin\theta_2,\ -\cos\theta_2)"
            rf" = ({bob[0]:.4g},\ {bob[1]:.4g})\ \mathrm{{m}}",
            {"relative-angle": relative},
        ),
        "speed": PartAnswer(
            speed,
            r"v_2^2 = l_1^2\dot\theta_1^2 + l_2^2\dot\theta_2^2 + 2 l_1 l_2\dot\theta_1\dot\theta_2"
            rf"\cos(\theta_1 - \theta_2)\ \Rightarrow\ v_2 = {speed:.4g}\ \mathrm{{m/s}}",
            {"no-cross-term": math.hypot(l1 * w1, l2 * w2)},
        ),
    }


def _four_bar_branch(a: float, b: float, c: float, d: float, crank: float, sign: float) -> tuple[float, float]:
    """θ₃ and θ₄ (rad) of the four-bar O₂A (a), AB (b), O₄B (c), O₂O₄ = d along x, for the crank at θ₂: B is on the
    left of the directed line A→O₄ for sign = +1 (the open, upper assembly), on its right for sign = −1."""
    ax, ay = a * math.cos(crank), a * math.sin(crank)
    ex, ey = d - ax, -ay
    e = math.hypot(ex, ey)
    cos_gamma = (b**2 + e**2 - c**2) / (2 * b * e)
    if not -0.95 < cos_gamma < 0.95:
        raise ValueError("the linkage cannot be assembled, or is too near a toggle, at this crank angle")
    coupler = math.atan2(ey, ex) + sign * math.acos(cos_gamma)
    bx, by = ax + b * math.cos(coupler), ay + b * math.sin(coupler)
    return coupler, math.atan2(by, bx - d)


def _four_bar_rates(a: float, b: float, c: float, angles: tuple[float, float, float], crank_rate: float) -> float:
    """ω₄ from the loop's rate equation a ω₂ e⊥(θ₂) + b ω₃ e⊥(θ₃) − c ω₄ e⊥(θ₄) = 0 (Cramer's rule)."""
    t2, t3, t4 = angles
    return a * crank_rate * math.sin(t2 - t3) / (c * math.sin(t4 - t3))


def four_bar_constraints(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A four-bar linkage described by its three link angles θ₂, θ₃, θ₄ (from +x, counterclockwise) tied by the two
    scalar loop-closure equations: one degree of freedom. θ₄ of the assembly with B left of A→O₄, and ω₄ by
    differentiating the loop equations."""
    a, b, c, d = given["crank_m"], given["coupler_m"], given["rocker_m"], given["ground_m"]
    crank, rate = math.radians(given["crank_deg"]), given["crank_rate_rad_s"]
    t3, t4 = _four_bar_branch(a, b, c, d, crank, +1.0)
    x3, x4 = _four_bar_branch(a, b, c, d, crank, -1.0)
    if not 10.0 < abs(math.degrees(t4)) < 170.0:
        raise ValueError("the rocker lies too near the ground line for a clear angle")
    w4 = _four_bar_rates(a, b, c, (crank, t3, t4), rate)
    crossed_w4 = _four_bar_rates(a, b, c, (crank, x3, x4), rate)
    if abs(w4) < 0.05 * rate:
        raise ValueError("the rocker is nearly at rest: a rate too sensitive to rounding")
    return {
        "dof": PartAnswer("one", r"3\ \text{angles} - 2\ \text{loop equations} = 1", {"three": "three", "two": "two"}),
        "rocker": PartAnswer(
            math.degrees(t4),
            r"a\,\bar e(\theta_2) + b\,\bar e(\theta_3) - c\,\bar e(\theta_4) - d\,\bar\imath = 0"
            rf"\ \Rightarrow\ \theta_3 = {math.degrees(t3):.4g}^\circ,\ \theta_4 = {math.degrees(t4):.4g}^\circ",
            {"crossed": math.degrees(x4)},
        ),
        "rocker-rate": PartAnswer(
            w4,
            r"a\omega_2\bar e_\perp(\theta_2) + b\omega_3\bar e_\perp(\theta_3) - c\omega_4\bar e_\perp(\theta_4) = 0"
            rf"\ \Rightarrow\ \omega_4 = \frac{{a\,\omega_2\sin(\theta_2 - \theta_3)}}{{c\sin(\theta_4 - \theta_3)}}"
            rf" = {w4:.4g}\ \mathrm{{rad/s}}",
            {"crossed": crossed_w4},
        ),
    }


def spool_rolling_cord(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A spool (outer radius R) rolling without slip on a level floor; a cord wound on its hub (radius r) leaves the
    hub's bottom horizontally, forward. Coordinates x (centre), φ (turn, clockwise), s (cord end); constraints
    x − Rφ = const (rolling, holonomic) and s − x + rφ = const (the cord): one degree of freedom. The centre moving
    d turns the spool d/R and moves the cord's end d (1 − r/R)."""
    outer, hub, travel = given["outer_m"], given["hub_m"], given["travel_m"]
    turn = travel / outer
    cord = travel * (1 - hub / outer)
    return {
        "dof": PartAnswer(
            "one", r"3\ \text{coordinates} - 2\ \text{constraints} = 1", {"three": "three", "two": "two"}
        ),
        "kind": PartAnswer(
            "holonomic",
            r"\dot x - R\dot\varphi = 0\ \Rightarrow\ x - R\varphi = \text{const}",
            {"nonholonomic": "nonholonomic"},
        ),
        "turn": PartAnswer(
            math.degrees(turn),
            rf"\Delta\varphi = d/R = {turn:.4g}\ \mathrm{{rad}} = {math.degrees(turn):.4g}^\circ",
            {"radian-number": turn},
        ),
        "cord": PartAnswer(
            cord,
            rf"\Delta s = \Delta x - r\,\Delta\varphi = d\left(1 - \frac{{r}}{{R}}\right) = {cord:.4g}\ \mathrm{{m}}",
            {"cord-over-top": travel * (1 + hub / outer), "hub-rolls": travel * hub / outer},
        ),
    }


# -- 7.3 Virtual displacements --------------------------------------------------------------------------------------


def sliding_hoop_bead(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """Lesson 7.3's rheonomic hoop: centre x_c = A sin Ωt, radius R, the bead at φ = ωt about the centre.
    g = ((x − x_c)² + y²)/R² − 1: ∇g = 2(x − x_c, y)/R². The actual velocity is the hoop's (AΩ cos Ωt, 0) plus
    Rω(−sin φ, cos φ); a virtual displacement is along the frozen hoop's tangent (−sin φ, cos φ), so ∇g·δr = 0 while
    ∇g·ṙ = 2 cos φ ẋ_c / R = −∂g/∂t."""
    radius, amplitude = given["hoop_radius_m"], given["amplitude_m"]
    hoop_rate, bead_rate, time = given["hoop_rate_rad_s"], given["bead_rate_rad_s"], given["time_s"]
    phi = bead_rate * time
    centre_speed = amplitude * hoop_rate * math.cos(hoop_rate * time)
    along = radius * bead_rate
    if abs(centre_speed) < 0.1 * along or abs(math.cos(phi)) < 0.1:
        raise ValueError("the hoop's motion hardly shows at this instant")
    velocity = (centre_speed - along * math.sin(phi), along * math.cos(phi), 0.0)
    grad_dot = 2 * math.cos(phi) * centre_speed / radius
    tangent = (-math.sin(phi), math.cos(phi))
    speed = math.hypot(velocity[0], velocity[1])
    cosine = (velocity[0] * tangent[0] + velocity[1] * tangent[1]) / speed
    angle = math.acos(max(-1.0, min(1.0, cosine)))
    if math.degrees(angle) < 3.0:
        raise ValueError("the angle is too small to read")
    return {
        "velocity": PartAnswer(
            velocity,
            r"\dot{\bar r} = (A\Omega\cos\Omega t,\ 0) + R\omega(-\sin\varphi,\ \cos\varphi)"
            rf" = ({velocity[0]:.4g},\ {velocity[1]:.4g})\ \mathrm{{m/s}}",
            {"hoop-still": (-along * math.sin(phi), along * math.cos(phi), 0.0)},
        ),
        "grad-dot": PartAnswer(
            grad_dot,
            r"\nabla g\cdot\dot{\bar r} = \frac{2}{R^2}(x - x_c)\,\dot x_c = \frac{2\cos\varphi\,\dot x_c}{R}"
            rf" = {grad_dot:.4g}\ \mathrm{{1/s}}",
            {"virtual-zero": 0.0, "time-rate": -grad_dot},
        ),
        "angle": PartAnswer(
            math.degrees(angle),
            r"\cos\beta = \frac{\dot{\bar r}\cdot(-\sin\varphi,\ \cos\varphi)}{|\dot{\bar r}|}"
            rf"\ \Rightarrow\ \beta = {math.degrees(angle):.4g}^\circ",
            {"radian-number": angle},
        ),
    }


def ladder_instant_centre(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The sliding ladder AB (length L): foot A on the floor at (L cos θ, 0), top B on the wall at (0, L sin θ),
    θ from the floor; the corner is the origin. Analytically δy_B = L cos θ δθ. Kinematically the ladder turns by
    −δθ (clockwise as θ grows) about the point where the normals to δr_A (vertical through A) and δr_B (horizontal
    through B) meet, (L cos θ, L sin θ); a point P at distance d from A moves δr_P = (−(L − d) sin θ, d cos θ) δθ."""
    length, angle, d = given["length_m"], math.radians(given["angle_deg"]), given["point_m"]
    if d >= length:
        raise ValueError("P must lie on the ladder")
    s, c = math.sin(angle), math.cos(angle)
    top = length * c
    centre = (length * c, length * s, 0.0)
    point = (-(length - d) * s, d * c, 0.0)
    return {
        "top": PartAnswer(
            top,
            rf"y_B = L\sin\theta\ \Rightarrow\ \delta y_B/\delta\theta = L\cos\theta = {top:.4g}\ \mathrm{{m}}",
            {"sine": length * s},
        ),
        "centre": PartAnswer(
            centre,
            r"\delta\bar r_A \parallel \bar\imath,\ \delta\bar r_B \parallel \bar\jmath\ \Rightarrow\ "
            rf"\text{{IC}} = (L\cos\theta,\ L\sin\theta) = ({centre[0]:.4g},\ {centre[1]:.4g})\ \mathrm{{m}}",
            {"corner": (0.0, 0.0, 0.0)},
        ),
        "point": PartAnswer(
            point,
            r"\delta\bar r_P = -\delta\theta\,\bar k\times(\bar r_P - \bar r_{IC}) = (-(L - d)\sin\theta,\ d\cos\theta)"
            rf"\,\delta\theta = ({point[0]:.4g},\ {point[1]:.4g})\ \mathrm{{m}}\ \text{{per rad}}",
            {"foot-fixed": (d * s, d * c, 0.0)},
        ),
    }


def knife_edge_parking(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """Lesson 7.3's knife edge (ẋ sin ψ − ẏ cos ψ = 0) parallel-parked from heading ψ₀: drive s, turn α, reverse s,
    turn back α. Each leg is admissible; the net step is s(cos ψ₀ − cos(ψ₀ + α), sin ψ₀ − sin(ψ₀ + α)), whose part
    to the right of the heading is s sin α (exactly) and whose leading-order estimate is s α [drive, turn]."""
    s, alpha, heading = given["drive_m"], math.radians(given["turn_deg"]), math.radians(given["heading_deg"])
    step = (
        s * (math.cos(heading) - math.cos(heading + alpha)),
        s * (math.sin(heading) - math.sin(heading + alpha)),
        0.0,
    )
    bracket = (math.sin(heading), -math.cos(heading), 0.0)
    sideways = s * math.sin(alpha)
    return {
        "admissible": PartAnswer(
            "roll-and-turn",
            r"\delta x\sin\psi - \delta y\cos\psi = 0:\ \delta q = \delta s\,(\cos\psi,\ \sin\psi,\ 0) + "
            r"\delta\psi\,(0,\ 0,\ 1)",
            {"any": "any"},
        ),
        "step": PartAnswer(
            step,
            r"\Delta(x, y) = s\left(\cos\psi_0 - \cos(\psi_0 + \alpha),\ \sin\psi_0 - \sin(\psi_0 + \alpha)\right)"
            rf" = ({step[0]:.4g},\ {step[1]:.4g})\ \mathrm{{m}}",
            {"leading-order": tuple(s * alpha * b for b in bracket)},
        ),
        "sideways": PartAnswer(
            sideways,
            rf"\Delta_\perp = s\sin\alpha = {sideways:.4g}\ \mathrm{{m}}",
            {"small-angle": s * alpha, "forward-creep": s * (1 - math.cos(alpha))},
        ),
    }


# -- 7.4 Generalized forces -----------------------------------------------------------------------------------------


def cart_pendulum_forces(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """Lesson 7.4's pendulum on a sprung cart, every force counted through Q (no potential): the push F on the cart,
    a horizontal pull P on the bob, the spring −k x on the cart and the bob's weight. With the cart at (x, 0) and the
    bob at (x + l sin θ, −l cos θ): ∂r_bob/∂x = (1, 0), ∂r_bob/∂θ = l(cos θ, sin θ). Q_x = F + P − k x,
    Q_θ = P l cos θ − m g l sin θ. The rod's pulls on bob and cart cancel in every Q."""
    bob, length, stiffness = given["bob_kg"], given["length_m"], given["stiffness_n_m"]
    x, angle = given["x_m"], math.radians(given["theta_deg"])
    push, pull, gravity = given["push_n"], given["pull_n"], given["g_m_s2"]
    q_x = push + pull - stiffness * x
    q_theta = pull * length * math.cos(angle) - bob * gravity * length * math.sin(angle)
    if abs(q_x) < 0.1 * (push + pull) or abs(q_theta) < 0.1 * (pull + bob * gravity) * length:
        raise ValueError("the forces nearly balance: a generalized force too near zero to check")
    return {
        "qx": PartAnswer(
            q_x,
            rf"Q_x = F\cdot 1 + P\cdot 1 - k x = {q_x:.4g}\ \mathrm{{N}}",
            {"pull-left-out": push - stiffness * x, "spring-sign": push + pull + stiffness * x},
        ),
        "qtheta": PartAnswer(
            q_theta,
            r"Q_\theta = (P,\ -m g)\cdot l(\cos\theta,\ \sin\theta) = P l\cos\theta - m g l\sin\theta"
            rf" = {q_theta:.4g}\ \mathrm{{N\,m}}",
            {
                "sine-cosine": pull * length * math.sin(angle) - bob * gravity * length * math.cos(angle),
                "gravity-sign": pull * length * math.cos(angle) + bob * gravity * length * math.sin(angle),
            },
        ),
        "rod": PartAnswer(
            "zero",
            r"-T(\sin\theta, -\cos\theta)\cdot\tfrac{\partial\bar r_{bob}}{\partial x} + "
            r"T(\sin\theta, -\cos\theta)\cdot\tfrac{\partial\bar r_{cart}}{\partial x} = 0",
            {"bob-only": "minus-t-sin"},
        ),
    }


def double_pendulum_motor(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A double pendulum (rods l₁, l₂) with a motor at the elbow turning the lower rod by τ (and the upper rod by −τ)
    and a horizontal force F on the lower bob. Absolute angles θ₁, θ₂: Q₁ = F l₁ cos θ₁ − τ, Q₂ = F l₂ cos θ₂ + τ.
    With (θ₁, φ = θ₂ − θ₁) instead, the motor works τ δφ only: Q_θ₁ = F (l₁ cos θ₁ + l₂ cos θ₂)."""
    l1, l2, force, torque = given["upper_m"], given["lower_m"], given["force_n"], given["torque_n_m"]
    t1, t2 = math.radians(given["theta1_deg"]), math.radians(given["theta2_deg"])
    q1 = force * l1 * math.cos(t1) - torque
    q2 = force * l2 * math.cos(t2) + torque
    q1_relative = force * (l1 * math.cos(t1) + l2 * math.cos(t2))
    if abs(q1) < 0.1 * (abs(force * l1 * math.cos(t1)) + torque):
        raise ValueError("force and motor nearly cancel in Q1: too sensitive to rounding")
    return {
        "q1": PartAnswer(
            q1,
            rf"Q_1 = F\,l_1\cos\theta_1 - \tau = {q1:.4g}\ \mathrm{{N\,m}}",
            {"no-reaction": force * l1 * math.cos(t1)},
        ),
        "q2": PartAnswer(
            q2,
            rf"Q_2 = F\,l_2\cos\theta_2 + \tau = {q2:.4g}\ \mathrm{{N\,m}}",
            {"sine": force * l2 * math.sin(t2) + torque, "motor-left-out": force * l2 * math.cos(t2)},
        ),
        "q1-relative": PartAnswer(
            q1_relative,
            r"\delta W = F\,\delta x_2 + \tau\,\delta\varphi,\ x_2 = l_1\sin\theta_1 + l_2\sin(\theta_1 + \varphi)"
            r"\ \Rightarrow\ Q_{\theta_1} = F(l_1\cos\theta_1 + l_2\cos\theta_2)"
            rf" = {q1_relative:.4g}\ \mathrm{{N\,m}}",
            {"same-as-absolute": q1},
        ),
    }


theta_s, m_s, g_s, L_s, k_s, h_s, l0_s = sympy.symbols("theta m g L k h l0", real=True)


def spring_bar_potential(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A uniform bar (m, L) pinned at its top end O, θ from the downward vertical; a spring (k, natural length ℓ₀)
    from its lower end to an anchor a height h above O. The spring's length is d = √(L² + h² + 2hL cos θ):
    V = −½ m g L cos θ + ½ k (d − ℓ₀)², and Q_θ = −dV/dθ = −½ m g L sin θ + k (d − ℓ₀) h L sin θ / d."""
    spring_length = sympy.sqrt(L_s**2 + h_s**2 + 2 * h_s * L_s * sympy.cos(theta_s))
    potential = -m_s * g_s * L_s * sympy.cos(theta_s) / 2 + k_s * (spring_length - l0_s) ** 2 / 2
    mass, length, stiffness = given["mass_kg"], given["length_m"], given["stiffness_n_m"]
    height, natural, angle, gravity = (
        given["anchor_m"],
        given["natural_m"],
        math.radians(given["theta_deg"]),
        given["g_m_s2"],
    )
    d = math.sqrt(length**2 + height**2 + 2 * height * length * math.cos(angle))
    gravity_q = -0.5 * mass * gravity * length * math.sin(angle)
    spring_q = stiffness * (d - natural) * height * length * math.sin(angle) / d
    q = gravity_q + spring_q
    if abs(q) < 0.2 * (abs(gravity_q) + abs(spring_q)):
        raise ValueError("gravity and the spring nearly balance: Q too sensitive to rounding")
    return {
        "potential": PartAnswer(
            potential,
            r"V = -\tfrac12 m g L\cos\theta + \tfrac12 k\left(\sqrt{L^2 + h^2 + 2hL\cos\theta} - \ell_0\right)^2",
            {
                "gravity-sign": potential + m_s * g_s * L_s * sympy.cos(theta_s),
                "natural-length": -m_s * g_s * L_s * sympy.cos(theta_s) / 2 + k_s * spring_length**2 / 2,
            },
        ),
        "q": PartAnswer(
            q,
            r"Q_\theta = -\frac{dV}{d\theta} = -\tfrac12 m g L\sin\theta + k(d - \ell_0)\frac{hL\sin\theta}{d}"
            rf",\ d = {d:.4g}\ \mathrm{{m}}\ \Rightarrow\ Q_\theta = {q:.4g}\ \mathrm{{N\,m}}",
            {"sign": -q, "gravity-only": gravity_q},
        ),
    }


# -- 7.5 Lagrange's equations ---------------------------------------------------------------------------------------

x_rate, x_accel, M_s, l_s = sympy.symbols("xd xdd M l", real=True)
r_s, r_rate, k_m = sympy.symbols("r rd k", real=True)


def cart_pendulum_release(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """Lesson 7.5's pendulum on a sprung cart (no push): T = ½(M + m)ẋ² + m l cos θ ẋ θ̇ + ½ m l² θ̇²; the θ equation
    m l cos θ ẍ + m l² θ̈ + m g l sin θ = 0 gives θ̈ = −(ẍ cos θ + g sin θ)/l. Released from rest at x₀, θ₀ both
    equations with θ̇ = 0 give ẍ = (m g sin θ₀ cos θ₀ − k x₀)/(M + m sin²θ₀)."""
    kinetic = (
        (M_s + m) * x_rate**2 / 2 + m * l_s * sympy.cos(theta) * x_rate * theta_rate + m * l_s**2 * theta_rate**2 / 2
    )
    swing = -(x_accel * sympy.cos(theta) + g * sympy.sin(theta)) / l_s
    cart, bob, stiffness = given["cart_kg"], given["bob_kg"], given["stiffness_n_m"]
    x0, angle, gravity = given["x0_m"], math.radians(given["theta0_deg"]), given["g_m_s2"]
    numerator = bob * gravity * math.sin(angle) * math.cos(angle) - stiffness * x0
    accel = numerator / (cart + bob * math.sin(angle) ** 2)
    if abs(numerator) < 0.2 * (bob * gravity * math.sin(angle) * math.cos(angle) + stiffness * abs(x0)):
        raise ValueError("the spring and the swing nearly cancel: too sensitive to rounding")
    return {
        "kinetic": PartAnswer(
            kinetic,
            r"\bar v_{bob} = (\dot x + l\cos\theta\,\dot\theta,\ l\sin\theta\,\dot\theta)\ \Rightarrow\ "
            r"T = \tfrac12(M + m)\dot x^2 + m l\cos\theta\,\dot x\dot\theta + \tfrac12 m l^2\dot\theta^2",
            {
                "no-cross-term": (M_s + m) * x_rate**2 / 2 + m * l_s**2 * theta_rate**2 / 2,
                "bob-relative": M_s * x_rate**2 / 2 + m * l_s**2 * theta_rate**2 / 2,
            },
        ),
        "swing": PartAnswer(
            swing,
            r"m l\cos\theta\,\ddot x + m l^2\ddot\theta + m g l\sin\theta = 0\ \Rightarrow\ "
            r"\ddot\theta = -\frac{\ddot x\cos\theta + g\sin\theta}{l}",
            {
                "support-fixed": -g * sympy.sin(theta) / l_s,
                "cart-sign": (x_accel * sympy.cos(theta) - g * sympy.sin(theta)) / l_s,
            },
        ),
        "cart-accel": PartAnswer(
            accel,
            r"(M + m)\ddot x + m l\cos\theta_0\,\ddot\theta = -k x_0,\ \ m l\cos\theta_0\,\ddot x + m l^2\ddot\theta"
            r" = -m g l\sin\theta_0\ \Rightarrow\ \ddot x = \frac{m g\sin\theta_0\cos\theta_0 - k x_0}"
            rf"{{M + m\sin^2\theta_0}} = {accel:.4g}\ \mathrm{{m/s^2}}",
            {
                "pendulum-ignored": -stiffness * x0 / (cart + bob),
                "total-mass": numerator / (cart + bob),
            },
        ),
    }


def spring_pendulum(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A bob (m) on a spring (k, natural length ℓ₀) hung from a fixed pivot, swinging in a vertical plane: polar
    coordinates r, θ (from the downward vertical). T = ½ m (ṙ² + r² θ̇²), V = ½ k (r − ℓ₀)² − m g r cos θ;
    r̈ = r θ̇² − (k/m)(r − ℓ₀) + g cos θ and θ̈ = −(2 ṙ θ̇ + g sin θ)/r."""
    kinetic = m * (r_rate**2 + r_s**2 * theta_rate**2) / 2
    radial = r_s * theta_rate**2 - k_m / m * (r_s - l0_s) + g * sympy.cos(theta)
    swing = -(2 * r_rate * theta_rate + g * sympy.sin(theta)) / r_s
    radius, rate, angle, spin, gravity = (
        given["r_m"],
        given["r_rate_m_s"],
        math.radians(given["theta_deg"]),
        given["theta_rate_rad_s"],
        given["g_m_s2"],
    )
    angular = -(2 * rate * spin + gravity * math.sin(angle)) / radius
    return {
        "kinetic": PartAnswer(
            kinetic,
            r"\bar v = \dot r\,\bar e_r + r\dot\theta\,\bar e_\theta\ \Rightarrow\ "
            r"T = \tfrac12 m(\dot r^2 + r^2\dot\theta^2)",
            {"no-stretch-rate": m * r_s**2 * theta_rate**2 / 2},
        ),
        "radial": PartAnswer(
            radial,
            r"m\ddot r - m r\dot\theta^2 + k(r - \ell_0) - m g\cos\theta = 0",
            {"no-centripetal": -k_m / m * (r_s - l0_s) + g * sympy.cos(theta)},
        ),
        "swing": PartAnswer(
            swing,
            r"\frac{d}{dt}(m r^2\dot\theta) + m g r\sin\theta = 0\ \Rightarrow\ "
            r"\ddot\theta = -\frac{2\dot r\dot\theta + g\sin\theta}{r}",
            {
                "no-coriolis": -g * sympy.sin(theta) / r_s,
                "half-coriolis": -(r_rate * theta_rate + g * sympy.sin(theta)) / r_s,
            },
        ),
        "swing-now": PartAnswer(
            angular,
            rf"\ddot\theta = -\frac{{2\dot r\dot\theta + g\sin\theta}}{{r}} = {angular:.4g}\ \mathrm{{rad/s^2}}",
            {"no-coriolis": -gravity * math.sin(angle) / radius},
        ),
    }


# -- 7.6 Solution of the equations ----------------------------------------------------------------------------------


def hoop_stability(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """Lesson 7.6's bead on a hoop spun at a prescribed Ω: R θ̈ = sin θ (R Ω² cos θ − g). The critical spin is
    Ω_c = √(g/R). Below it the bottom is stable, δθ̈ = −(g/R − Ω²) δθ; above it the bottom is unstable and the
    equilibria cos θ* = g/(R Ω²) are stable with δθ̈ = −Ω² sin²θ* δθ."""
    radius, spin, gravity = given["hoop_radius_m"], given["hoop_speed_rad_s"], given["g_m_s2"]
    critical = math.sqrt(gravity / radius)
    ratio = spin**2 / critical**2
    if abs(ratio - 1.0) < 0.15:
        raise ValueError("too near the critical spin for a clear small oscillation")
    if ratio < 1.0:
        bottom = "stable"
        frequency = math.sqrt(gravity / radius - spin**2)
        how = rf"\Omega < \Omega_c:\ \omega_n = \sqrt{{g/R - \Omega^2}} = {frequency:.4g}\ \mathrm{{rad/s}}"
    else:
        bottom = "unstable"
        frequency = spin * math.sqrt(1.0 - (gravity / (radius * spin**2)) ** 2)
        how = (
            r"\Omega > \Omega_c:\ \cos\theta^* = \frac{g}{R\Omega^2},\ \omega_n = \Omega\sin\theta^*"
            rf" = {frequency:.4g}\ \mathrm{{rad/s}}"
        )
    return {
        "critical": PartAnswer(
            critical,
            rf"\Omega_c = \sqrt{{g/R}} = {critical:.4g}\ \mathrm{{rad/s}}",
            {"no-root": gravity / radius},
        ),
        "bottom": PartAnswer(
            bottom,
            r"\delta\ddot\theta = -\left(\frac{g}{R} - \Omega^2\right)\delta\theta"
            rf":\ \Omega/\Omega_c = {math.sqrt(ratio):.4g}",
            {"wrong-side": "unstable" if bottom == "stable" else "stable"},
        ),
        "frequency": PartAnswer(frequency, how, {"no-spin": critical}),
    }


def cart_pendulum_modes(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """Lesson 7.4/7.5's pendulum on a sprung cart linearised about x = 0, θ = 0: M q̈ + K q = 0 with
    M = [[M + m, m l], [m l, m l²]], K = diag(k, m g l). det(K − ω² M) = 0 is a quadratic in ω²:
    M m l² ω⁴ − (k m l² + (M + m) m g l) ω² + k m g l = 0. The slow mode's shape from the first row:
    θ/x = (k − ω₁²(M + m))/(ω₁² m l)."""
    cart, bob, length = given["cart_kg"], given["bob_kg"], given["length_m"]
    stiffness, gravity = given["stiffness_n_m"], given["g_m_s2"]
    a = cart * bob * length**2
    b = -(stiffness * bob * length**2 + (cart + bob) * bob * gravity * length)
    c = stiffness * bob * gravity * length
    root = math.sqrt(b**2 - 4 * a * c)
    slow_sq, fast_sq = (-b - root) / (2 * a), (-b + root) / (2 * a)
    slow, fast = math.sqrt(slow_sq), math.sqrt(fast_sq)
    shape = (stiffness - slow_sq * (cart + bob)) / (slow_sq * bob * length)
    return {
        "slow": PartAnswer(
            slow,
            r"M m l^2\omega^4 - \left(k m l^2 + (M + m) m g l\right)\omega^2 + k m g l = 0"
            rf"\ \Rightarrow\ \omega_1 = {slow:.4g}\ \mathrm{{rad/s}}",
            {"fixed-support": math.sqrt(gravity / length)},
        ),
        "fast": PartAnswer(
            fast,
            rf"\omega_2 = {fast:.4g}\ \mathrm{{rad/s}}",
            {"lumped-cart": math.sqrt(stiffness / (cart + bob))},
        ),
        "shape": PartAnswer(
            shape,
            r"\left(k - \omega_1^2(M + m)\right)x - \omega_1^2 m l\,\theta = 0\ \Rightarrow\ "
            rf"\theta/x = {shape:.4g}\ \mathrm{{rad/m}}",
            {"in-degrees": math.degrees(shape)},
        ),
    }


def bar_large_swing(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A uniform bar (L) pivoted at one end, released from rest at θ₀: θ̈ = −(3g/2L) sin θ. Small swings have
    period 2π√(2L/3g); the swing from θ₀ has period 4√(2L/3g) K(sin²(θ₀/2)) (K the complete elliptic integral of
    the first kind, parameter m = k²); energy gives the speed at the bottom, ω = √(3g(1 − cos θ₀)/L)."""
    length, angle, gravity = given["length_m"], math.radians(given["theta0_deg"]), given["g_m_s2"]
    rate = 3 * gravity / (2 * length)
    small = 2 * math.pi / math.sqrt(rate)
    period = 4 / math.sqrt(rate) * float(ellipk(math.sin(angle / 2) ** 2))
    speed = math.sqrt(2 * rate * (1 - math.cos(angle)))
    return {
        "small": PartAnswer(
            small,
            rf"\tfrac13 m L^2\ddot\theta = -\tfrac12 m g L\theta\ \Rightarrow\ T_0 = 2\pi\sqrt{{\frac{{2L}}{{3g}}}}"
            rf" = {small:.4g}\ \mathrm{{s}}",
            {"point-mass": 2 * math.pi * math.sqrt(length / gravity)},
        ),
        "period": PartAnswer(
            period,
            r"T = 4\sqrt{\frac{2L}{3g}}\,K\!\left(\sin^2\tfrac{\theta_0}{2}\right)"
            rf" = {period:.4g}\ \mathrm{{s}}",
            {"small-angle": small},
        ),
        "speed": PartAnswer(
            speed,
            r"\tfrac12\cdot\tfrac13 m L^2\omega^2 = m g\tfrac{L}{2}(1 - \cos\theta_0)\ \Rightarrow\ "
            rf"\omega = \sqrt{{\frac{{3g(1 - \cos\theta_0)}}{{L}}}} = {speed:.4g}\ \mathrm{{rad/s}}",
            {"point-mass": math.sqrt(2 * gravity * (1 - math.cos(angle)) / length)},
        ),
    }
