"""Answers of chapter 6's exercises: Newton–Euler for one body and for systems of bodies, planar motion, and the
momentum and energy principles (impulses, work, rigid-body collisions)."""

from __future__ import annotations

import math
from collections.abc import Mapping

import sympy

from app.practice.exercise import PartAnswer

theta, theta0, Omega, L, g, P, m, d = sympy.symbols("theta theta0 Omega L g P m d", real=True)


# -- 6.1 Fundamental equations ------------------------------------------------------------------------------------


def rotor_bearing_loads(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A thin disk (m, r) on a shaft between bearings A and B a span L apart, at a from A; its centre of mass e off
    the axis, its axis skewed β from the shaft; constant ω, gravity left out. The force that keeps G on its circle,
    the couple the skew needs, and the rotating force at A (the two parts are at right angles in the rotor frame)."""
    mass, r, e = given["mass_kg"], given["radius_m"], given["eccentricity_m"]
    beta, w = math.radians(given["skew_deg"]), given["speed_rad_s"]
    span, a = given["span_m"], given["position_m"]
    static = mass * e * w**2
    axial, diametral = 0.5 * mass * r**2, 0.25 * mass * r**2
    couple = (axial - diametral) * w**2 * math.sin(beta) * math.cos(beta)
    share_a = (span - a) / span * static
    force_a = math.hypot(share_a, couple / span)
    return {
        "static": PartAnswer(
            static,
            rf"m e \omega^2 = {static:.4g}\ \mathrm{{N}}",
            {"disk-radius": mass * r * w**2},
        ),
        "couple": PartAnswer(
            couple,
            r"C = (I_a - I_d)\,\omega^2 \sin\beta\cos\beta = \tfrac14 m r^2 \omega^2 \sin\beta\cos\beta"
            rf" = {couple:.4g}\ \mathrm{{N\,m}}",
            {"axial-only": axial * w**2 * math.sin(beta) * math.cos(beta)},
        ),
        "bearing-a": PartAnswer(
            force_a,
            rf"R_A = \sqrt{{\left(\tfrac{{L-a}}{{L}}\,m e\omega^2\right)^2 + (C/L)^2}}"
            rf" = \sqrt{{{share_a:.4g}^2 + {couple / span:.4g}^2}} = {force_a:.4g}\ \mathrm{{N}}",
            {
                "static-only": share_a,
                "magnitudes-added": share_a + couple / span,
                "shares-swapped": math.hypot(a / span * static, couple / span),
            },
        ),
    }


def hinged_bar_on_shaft(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A slender bar (m, L) hinged at its upper end O to a vertical shaft turning at constant Ω, the hinge axis
    horizontal and normal to the plane of shaft and bar; θ from the downward vertical. Euler about O (principal
    axes of the bar at O, axial moment zero) gives (m L²/3) θ̈ = (m L²/3) Ω² sin θ cos θ − m g (L/2) sin θ."""
    mass, length, spin, gravity = given["mass_kg"], given["length_m"], given["spin_rad_s"], given["g_m_s2"]
    equation = (Omega**2 * sympy.cos(theta) - 3 * g / (2 * L)) * sympy.sin(theta)
    ratio = 3 * gravity / (2 * length * spin**2)
    lumped = 2 * gravity / (length * spin**2)
    if ratio >= 1.0 or lumped >= 1.0:
        raise ValueError("the shaft turns too slowly for the bar to stand off the shaft")
    steady = math.acos(ratio)
    horizontal = mass * (length / 2) * math.sin(steady) * spin**2
    weight = mass * gravity
    hinge = math.hypot(horizontal, weight)
    return {
        "equation": PartAnswer(
            equation,
            r"\tfrac13 m L^2 \ddot\theta = \tfrac13 m L^2 \Omega^2 \sin\theta\cos\theta - m g \tfrac{L}{2}\sin\theta"
            r"\ \Rightarrow\ \ddot\theta = \left(\Omega^2\cos\theta - \tfrac{3g}{2L}\right)\sin\theta",
            {
                "point-mass": (Omega**2 * sympy.cos(theta) - 2 * g / L) * sympy.sin(theta),
                "no-spin-term": -3 * g / (2 * L) * sympy.sin(theta),
            },
        ),
        "steady": PartAnswer(
            math.degrees(steady),
            rf"\cos\theta_s = \frac{{3g}}{{2L\Omega^2}} = {ratio:.4g},\ \theta_s = {math.degrees(steady):.4g}^\circ",
            {"point-mass": math.degrees(math.acos(lumped)), "radian-number": steady},
        ),
        "hinge": PartAnswer(
            hinge,
            rf"\sqrt{{\left(m \tfrac{{L}}{{2}}\sin\theta_s\,\Omega^2\right)^2 + (m g)^2}}"
            rf" = \sqrt{{{horizontal:.4g}^2 + {weight:.4g}^2}} = {hinge:.4g}\ \mathrm{{N}}",
            {
                "weight-only": weight,
                "end-radius": math.hypot(2 * horizontal, weight),
            },
        ),
    }


def plate_about_diagonal(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A thin rectangular plate (m, sides a along x and b along y) spun at constant ω about its diagonal through
    G, bearings a span L apart with G midway. Plate axes xyz at G are principal: H_G = (I_xx ω_x, I_yy ω_y, 0) with
    I_xx = m b²/12, I_yy = m a²/12; the bearings supply ω × H_G, a couple of two forces L apart."""
    mass, a, b, w, span = given["mass_kg"], given["side_a_m"], given["side_b_m"], given["speed_rad_s"], given["span_m"]
    if abs(a - b) < 0.1:
        raise ValueError("a nearly square plate needs almost no couple")
    diagonal = math.hypot(a, b)
    if span <= diagonal:
        raise ValueError("the bearings must lie outside the plate")
    ixx, iyy = mass * b**2 / 12, mass * a**2 / 12
    omega = (w * a / diagonal, w * b / diagonal, 0.0)
    h = (ixx * omega[0], iyy * omega[1], 0.0)
    moment = abs(omega[0] * h[1] - omega[1] * h[0])
    force = moment / span
    along = (ixx * a**2 + iyy * b**2) / diagonal**2 * w
    return {
        "h": PartAnswer(
            h,
            r"\boldsymbol\omega = \tfrac{\omega}{\sqrt{a^2+b^2}}(a,\ b,\ 0),\ "
            r"\mathbf H_G = \left(\tfrac{m b^2}{12}\omega_x,\ \tfrac{m a^2}{12}\omega_y,\ 0\right)"
            rf" = ({h[0]:.4g},\ {h[1]:.4g},\ 0)\ \mathrm{{kg\,m^2/s}}",
            {
                "h-along-shaft": (along * a / diagonal, along * b / diagonal, 0.0),
                "moments-swapped": (iyy * omega[0], ixx * omega[1], 0.0),
            },
        ),
        "moment": PartAnswer(
            moment,
            r"|\dot{\mathbf H}_G| = |\boldsymbol\omega\times\mathbf H_G| = \frac{m\omega^2 a b\,|a^2-b^2|}{12(a^2+b^2)}"
            rf" = {moment:.4g}\ \mathrm{{N\,m}}",
            {"no-moment": 0.0},
        ),
        "force": PartAnswer(
            force,
            rf"F = |\dot{{\mathbf H}}_G| / L = {force:.4g}\ \mathrm{{N}}",
            {"half-span": 2 * force, "moment-not-force": moment},
        ),
    }


# -- 6.2 Planar motion --------------------------------------------------------------------------------------------


def ladder_at_release(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A uniform ladder (m, L) on a smooth wall and floor, released from rest at θ0 from the floor (θ̇ = 0 at the
    start). With x_G = (L/2) cos θ, z_G = (L/2) sin θ and Newton–Euler: θ̈ = −(3g/2L) cos θ0,
    N_A = m ẍ_G = (3/4) m g sin θ0 cos θ0, N_B = m g + m z̈_G = m g (1 − (3/4) cos² θ0); it leaves the wall where
    sin θ = (2/3) sin θ0."""
    length, mass, angle0, gravity = (
        given["length_m"],
        given["mass_kg"],
        math.radians(given["angle0_deg"]),
        given["g_m_s2"],
    )
    alpha = -3 * gravity / (2 * length) * math.cos(angle0)
    wall = mass * -(length / 2) * math.sin(angle0) * alpha
    floor = mass * gravity + mass * (length / 2) * math.cos(angle0) * alpha
    leave = math.asin(2 / 3 * math.sin(angle0))
    return {
        "alpha": PartAnswer(
            alpha,
            rf"\ddot\theta = -\frac{{3g}}{{2L}}\cos\theta_0 = {alpha:.4g}\ \mathrm{{rad/s^2}}",
            {"sign": -alpha, "inertia-about-g": -6 * gravity / length * math.cos(angle0)},
        ),
        "wall": PartAnswer(
            wall,
            r"N_A = m\ddot x_G = -m\tfrac{L}{2}\sin\theta_0\,\ddot\theta = \tfrac34 m g\sin\theta_0\cos\theta_0"
            rf" = {wall:.4g}\ \mathrm{{N}}",
            {"acceleration-sign": -wall},
        ),
        "floor": PartAnswer(
            floor,
            r"N_B = m g + m\ddot z_G = m g\left(1 - \tfrac34\cos^2\theta_0\right)" rf" = {floor:.4g}\ \mathrm{{N}}",
            {"static-floor": mass * gravity},
        ),
        "leave": PartAnswer(
            math.degrees(leave),
            rf"\sin\theta = \tfrac23\sin\theta_0,\ \theta = {math.degrees(leave):.4g}^\circ",
            {"radian-number": leave},
        ),
    }


def spool_pulled(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A spool (m, rim radius R, hub radius r, radius of gyration k about G) on a level floor, rolling without
    slipping; a cord from the underside of the hub pulled with force P at φ above the horizontal. The cord's line
    passes R cos φ − r from the contact point C, so about C: P (R cos φ − r) = m (k² + R²) a / R. Friction F (along
    the pull's horizontal direction) from m a = P cos φ + F; the floor's normal force N = m g − P sin φ."""
    mass, rim, hub, gyration = given["mass_kg"], given["rim_m"], given["hub_m"], given["gyration_m"]
    pull, phi, gravity = given["pull_n"], math.radians(given["angle_deg"]), given["g_m_s2"]
    arm = rim * math.cos(phi) - hub
    if abs(arm) < 0.05 * rim:
        raise ValueError("the cord's line passes too near the contact point")
    normal = mass * gravity - pull * math.sin(phi)
    if normal < 0.2 * mass * gravity:
        raise ValueError("the pull nearly lifts the spool")
    accel = pull * arm * rim / (mass * (gyration**2 + rim**2))
    friction = mass * accel - pull * math.cos(phi)
    mu = abs(friction) / normal
    return {
        "direction": PartAnswer(
            "toward" if arm > 0 else "away",
            rf"R\cos\varphi - r = {arm:.4g}\ \mathrm{{m}}"
            + (r" > 0:\ \text{it rolls toward the pull}" if arm > 0 else r" < 0:\ \text{it rolls away from the pull}"),
        ),
        "accel": PartAnswer(
            accel,
            r"P(R\cos\varphi - r) = m(k^2 + R^2)\,\frac{a}{R}\ \Rightarrow\ a = \frac{P R (R\cos\varphi - r)}"
            rf"{{m(k^2+R^2)}} = {accel:.4g}\ \mathrm{{m/s^2}}",
            {
                "no-parallel-axis": pull * arm * rim / (mass * gyration**2),
                "pulled-at-centre": pull * math.cos(phi) * rim**2 / (mass * (gyration**2 + rim**2)),
            },
        ),
        "friction": PartAnswer(
            friction,
            rf"F = m a - P\cos\varphi = {friction:.4g}\ \mathrm{{N}}",
            {"friction-sign": -friction},
        ),
        "mu": PartAnswer(
            mu,
            rf"N = m g - P\sin\varphi = {normal:.4g}\ \mathrm{{N}},\ \mu_{{\min}} = |F|/N = {mu:.4g}",
            {"normal-is-weight": abs(friction) / (mass * gravity)},
        ),
    }


def bar_support_cut(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A horizontal uniform bar (m, L) on a pin at O, a distance s from end A, and a cord at the far end B; the cord
    is cut. Just after, ω = 0: about O, (m L²/12 + m b²) α = m g b with b = L/2 − s; a_G = α b; the pin force
    R = m g − m a_G (up); end B falls at α (L − s)."""
    mass, length, s, gravity = given["mass_kg"], given["length_m"], given["pin_m"], given["g_m_s2"]
    b = length / 2 - s
    if b < 0.05 * length:
        raise ValueError("the pin is too near the centre")
    inertia_g = mass * length**2 / 12
    alpha = mass * gravity * b / (inertia_g + mass * b**2)
    pin = mass * gravity - mass * alpha * b
    end = alpha * (length - s)
    return {
        "alpha": PartAnswer(
            alpha,
            rf"\alpha = \frac{{m g b}}{{\tfrac1{{12}} m L^2 + m b^2}},"
            rf"\ b = \tfrac{{L}}{{2}} - s = {b:.4g}\ \mathrm{{m}},\ \alpha = {alpha:.4g}\ \mathrm{{rad/s^2}}",
            {"no-parallel-axis": mass * gravity * b / inertia_g, "point-mass": gravity / b},
        ),
        "pin": PartAnswer(
            pin,
            rf"R = m g - m\,\alpha b = {pin:.4g}\ \mathrm{{N}}",
            {"before-cut": mass * gravity * (1 - b / (length - s)), "weight": mass * gravity},
        ),
        "end": PartAnswer(
            end,
            rf"a_B = \alpha\,(L - s) = {end:.4g}\ \mathrm{{m/s^2}}",
            {"centre-acceleration": alpha * b, "free-fall": gravity},
        ),
    }


# -- 6.3 Newton–Euler equations for a system ----------------------------------------------------------------------


def slider_crank_dead_centre(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The in-line slider-crank (crank r, rod l, uniform slender links m_c, m_r, slider m_s) at the outer dead
    centre θ = 0, crank held at constant ω. ẍ = −r ω² (1 + r/l), φ̈ = 0, a_G2 = −r ω² (1 + r/2l) along x. The rod
    is horizontal and φ̈ = 0, so the pins share its weight equally: A = (m_s ẍ + m_r a_G2, m_r g/2); the motor
    holds gravity's moment only, τ = g r (m_c + m_r)/2."""
    r, rod, w, gravity = given["crank_m"], given["rod_m"], given["speed_rad_s"], given["g_m_s2"]
    m_c, m_r, m_s = given["crank_mass_kg"], given["rod_mass_kg"], given["slider_mass_kg"]
    slider = -r * w**2 * (1 + r / rod)
    rod_centre = -r * w**2 * (1 + r / (2 * rod))
    pin = (m_s * slider + m_r * rod_centre, m_r * gravity / 2, 0.0)
    torque = gravity * r * (m_c + m_r) / 2
    return {
        "slider-acc": PartAnswer(
            slider,
            rf"\ddot x = -r\omega^2\left(1 + \tfrac{{r}}{{l}}\right) = {slider:.4g}\ \mathrm{{m/s^2}}",
            {"crank-only": -r * w**2},
        ),
        "pin-a": PartAnswer(
            pin,
            r"\mathbf A = \mathbf B + m_r\mathbf a_{G_2} - m_r\mathbf g,\ B_x = m_s\ddot x,"
            r"\ A_y = -B_y = \tfrac12 m_r g"
            rf" \Rightarrow \mathbf A = ({pin[0]:.4g},\ {pin[1]:.4g},\ 0)\ \mathrm{{N}}",
            {
                "rod-massless": (m_s * slider, 0.0, 0.0),
                "rod-weight-whole": (pin[0], m_r * gravity, 0.0),
            },
        ),
        "torque": PartAnswer(
            torque,
            rf"\tau = m_c g\tfrac{{r}}{{2}} + \tfrac12 m_r g\,r = {torque:.4g}\ \mathrm{{N\,m}}",
            {"whole-rod-weight": gravity * r * (m_c / 2 + m_r), "crank-only": gravity * r * m_c / 2},
        ),
    }


def block_pulley_hanging(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A block m1 on a level table (kinetic friction μ) tied by a cord over a pulley (uniform disk M, radius R,
    frictionless axle) to a hanging block m2; the cord does not slip on the pulley. Per body: m1 a = T1 − μ m1 g,
    m2 a = m2 g − T2, (M R²/2) (a/R) = (T2 − T1) R, so a = (m2 − μ m1) g / (m1 + m2 + M/2)."""
    m1, m2, pulley, mu, gravity = (
        given["table_kg"],
        given["hanging_kg"],
        given["pulley_kg"],
        given["mu"],
        given["g_m_s2"],
    )
    drive = (m2 - mu * m1) * gravity
    if drive < 0.1 * m2 * gravity:
        raise ValueError("friction (nearly) holds the blocks")
    accel = drive / (m1 + m2 + pulley / 2)
    hanging = m2 * (gravity - accel)
    table = m1 * (accel + mu * gravity)
    return {
        "accel": PartAnswer(
            accel,
            rf"a = \frac{{(m_2 - \mu m_1) g}}{{m_1 + m_2 + M/2}} = {accel:.4g}\ \mathrm{{m/s^2}}",
            {
                "massless-pulley": drive / (m1 + m2),
                "pulley-as-hoop": drive / (m1 + m2 + pulley),
                "no-friction": m2 * gravity / (m1 + m2 + pulley / 2),
            },
        ),
        "hanging": PartAnswer(
            hanging,
            rf"T_2 = m_2 (g - a) = {hanging:.4g}\ \mathrm{{N}}",
            {"static": m2 * gravity},
        ),
        "table": PartAnswer(
            table,
            rf"T_1 = m_1 (a + \mu g) = {table:.4g}\ \mathrm{{N}}",
            {"equal-tensions": hanging},
        ),
    }


def cart_pendulum(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A cart (M) pushed by a constant horizontal force F on a smooth level track; a uniform bar (m, L) hangs from a
    pin on the cart. In the steady motion every body has acceleration a = F/(M + m); the bar translates, so the
    moment about its G vanishes and the pin force m(a, g) lies along the bar: tan θ = a/g."""
    cart, mass, force, gravity = given["cart_kg"], given["bar_kg"], given["force_n"], given["g_m_s2"]
    accel = force / (cart + mass)
    angle = math.atan2(accel, gravity)
    pin = mass * math.hypot(accel, gravity)
    return {
        "accel": PartAnswer(
            accel,
            rf"a = \frac{{F}}{{M + m}} = {accel:.4g}\ \mathrm{{m/s^2}}",
            {"cart-only": force / cart},
        ),
        "angle": PartAnswer(
            math.degrees(angle),
            rf"\tan\theta = a/g = {accel / gravity:.4g},\ \theta = {math.degrees(angle):.4g}^\circ",
            {"radian-number": angle, "cart-only": math.degrees(math.atan2(force / cart, gravity))},
        ),
        "pin": PartAnswer(
            pin,
            rf"|\mathbf R| = m\sqrt{{a^2 + g^2}} = {pin:.4g}\ \mathrm{{N}}",
            {"weight-only": mass * gravity, "horizontal-only": mass * accel},
        ),
    }


# -- 6.4 Momentum and energy principles ---------------------------------------------------------------------------


def struck_bar(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A uniform bar (m, L) at rest on smooth ice, struck by a horizontal impulse P normal to it at a distance d
    from its centre. Linear impulse–momentum: v_G = P/m; angular about G: (m L²/12) ω = P d. The far end moves at
    v_G − ω L/2 = (P/m)(1 − 6 d/L) (positive along P); it stays still when struck at d = L/6 from the centre."""
    mass, length, impulse, offset = given["mass_kg"], given["length_m"], given["impulse_ns"], given["offset_m"]
    if offset > 0.4 * length:
        raise ValueError("strike the bar within its length")
    inertia = mass * length**2 / 12
    v_centre = impulse / mass
    spin = impulse * offset / inertia
    far_end = P / m * (1 - 6 * d / L)
    return {
        "vg": PartAnswer(
            v_centre,
            rf"m v_G = P\ \Rightarrow\ v_G = {v_centre:.4g}\ \mathrm{{m/s}}",
            {"struck-point": v_centre + spin * offset},
        ),
        "omega": PartAnswer(
            spin,
            rf"\tfrac1{{12}} m L^2\,\omega = P d\ \Rightarrow\ \omega = {spin:.4g}\ \mathrm{{rad/s}}",
            {
                "inertia-about-end": impulse * offset / (mass * length**2 / 3),
                "lever-to-end": impulse * (length / 2) / inertia,
            },
        ),
        "far-end": PartAnswer(
            far_end,
            r"v_{\text{end}} = v_G - \omega\tfrac{L}{2} = \frac{P}{m} - \frac{12 P d}{m L^2}\,\frac{L}{2}"
            r" = \frac{P}{m}\left(1 - \frac{6 d}{L}\right)",
            {"rotation-sign": P / m * (1 + 6 * d / L), "translation-only": P / m},
        ),
        "percussion": PartAnswer(
            length / 6,
            rf"1 - \frac{{6 d}}{{L}} = 0\ \Rightarrow\ d = \frac{{L}}{{6}} = {length / 6:.4g}\ \mathrm{{m}}",
            {"from-far-end": 2 * length / 3},
        ),
    }


def disk_collision(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """Disk 1 (m1, r1) slides at v along +x into disk 2 (m2, r2) at rest, neither spinning; the line of centres is
    at β from +x, n = (cos β, sin β), t = k × n. Contact velocity v_n = −v cos β, v_t = v sin β;
    W_nn = 1/m1 + 1/m2, W_tt = W_nn + 2/m1 + 2/m2 (uniform disks). P_n = (1 + e)(−v_n)/W_nn; friction stops the
    slip if μ P_n ≥ |v_t|/W_tt, otherwise P_t = −μ P_n. Disk 2's spin after: ω2 = −r2 P_t / (½ m2 r2²). Energy
    lost: −½ Pᵀ(v_before + v_after) with v_after = v_before + W P."""
    m1, m2, r2 = given["m1_kg"], given["m2_kg"], given["r2_m"]
    speed, beta, e, mu = given["speed_m_s"], math.radians(given["beta_deg"]), given["restitution"], given["mu"]
    vn, vt = -speed * math.cos(beta), speed * math.sin(beta)
    w_nn = 1 / m1 + 1 / m2
    w_tt = w_nn + 2 / m1 + 2 / m2
    pn = (1 + e) * -vn / w_nn
    stick = abs(vt) / w_tt
    stuck = mu * pn >= stick
    if abs(mu * pn - stick) < 0.05 * stick:
        raise ValueError("too near the edge between sliding and sticking")
    pt = -math.copysign(stick if stuck else mu * pn, vt)
    spin2 = -r2 * pt / (0.5 * m2 * r2**2)
    vn_after, vt_after = vn + w_nn * pn, vt + w_tt * pt
    loss = -0.5 * (pn * (vn + vn_after) + pt * (vt + vt_after))
    normal_loss = 0.5 * (1 - e**2) * vn**2 / w_nn
    return {
        "pn": PartAnswer(
            pn,
            rf"P_n = \frac{{(1+e)\,v\cos\beta}}{{1/m_1 + 1/m_2}} = {pn:.4g}\ \mathrm{{N\,s}}",
            {
                "plastic": -vn / w_nn,
                "fixed-disk": (1 + e) * -vn * m2,
                "no-cosine": (1 + e) * speed / w_nn,
            },
        ),
        "slip": PartAnswer(
            "stuck" if stuck else "slid",
            rf"\mu P_n = {mu * pn:.4g}\ \mathrm{{N\,s}}"
            + (r"\ \ge\ " if stuck else r"\ <\ ")
            + rf"|v_t|/W_{{tt}} = {stick:.4g}\ \mathrm{{N\,s}}",
        ),
        "spin2": PartAnswer(
            spin2,
            rf"P_t = {pt:.4g}\ \mathrm{{N\,s}},\ \omega_2' = -\frac{{r_2 P_t}}{{\tfrac12 m_2 r_2^2}}"
            rf" = {spin2:.4g}\ \mathrm{{rad/s}}",
            {"hoop-inertia": spin2 / 2},
        ),
        "loss": PartAnswer(
            loss,
            r"\Delta T = -\tfrac12\left[P_n (v_n + v_n') + P_t (v_t + v_t')\right]" rf" = {loss:.4g}\ \mathrm{{J}}",
            {"normal-only": normal_loss},
        ),
    }


def pendulum_energy(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A uniform bar (m, L) pivoted at one end O, released from rest at θ0 from the downward vertical. Work–energy
    with T = ½ (m L²/3) ω² and V = −m g (L/2) cos θ: ω² = (3 g/L)(cos θ − cos θ0). At the bottom the pivot force is
    m g + m (L/2) ω² (G moves on a circle of radius L/2; the tangential acceleration is zero there)."""
    mass, length, angle0, gravity = (
        given["mass_kg"],
        given["length_m"],
        math.radians(given["angle0_deg"]),
        given["g_m_s2"],
    )
    squared = 3 * g / L * (sympy.cos(theta) - sympy.cos(theta0))
    drop = 1 - math.cos(angle0)
    spin = math.sqrt(3 * gravity / length * drop)
    pivot = mass * gravity + mass * (length / 2) * spin**2
    return {
        "omega-squared": PartAnswer(
            squared,
            r"\tfrac12\cdot\tfrac13 m L^2\,\omega^2 = m g\tfrac{L}{2}(\cos\theta - \cos\theta_0)"
            r"\ \Rightarrow\ \omega^2 = \frac{3g}{L}(\cos\theta - \cos\theta_0)",
            {
                "point-mass": 4 * g / L * (sympy.cos(theta) - sympy.cos(theta0)),
                "rotation-about-g": 12 * g / L * (sympy.cos(theta) - sympy.cos(theta0)),
            },
        ),
        "omega": PartAnswer(
            spin,
            rf"\omega = \sqrt{{\tfrac{{3g}}{{L}}(1 - \cos\theta_0)}} = {spin:.4g}\ \mathrm{{rad/s}}",
            {"point-mass": math.sqrt(4 * gravity / length * drop)},
        ),
        "pivot": PartAnswer(
            pivot,
            rf"R = m g + m\tfrac{{L}}{{2}}\omega^2 = {pivot:.4g}\ \mathrm{{N}}",
            {"weight-only": mass * gravity, "radius-l": mass * gravity + mass * length * spin**2},
        ),
    }
