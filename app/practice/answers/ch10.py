"""Answers of chapter 10's exercises: torque-free motion, the heavy top, and gyroscopic instruments.

Conventions follow the lessons of chapter 10: 3-1-3 Euler angles (precession φ about the fixed Z, nutation θ, spin ψ
about the symmetry axis k), ω_z the body component of ω along k (not ψ̇), moments of a top about its pivot.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import sympy
from scipy.special import ellipk

from app.physics.bodies import inertia
from app.physics.systems.ch10 import free_gyroscope, gyrocompass, rate_gyro
from app.physics.systems.ch10.torque_free_axisymmetric import AxisymmetricFreeMotion
from app.practice.exercise import PartAnswer

#: The Earth's rotation rate (rad/s), one turn per sidereal day, as the gyrocompass lesson uses.
EARTH_RATE_RAD_S = gyrocompass.EARTH_RATE_RAD_S

AXES = ("x", "y", "z")


# ---- 10.1 Free motion ---------------------------------------------------------------------------------------------


def canister_precession(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A tossed canister (prolate, I_a < I_t about G), spin ω_z about its axis, the axis θ from H_G: |H_G|, the
    precession rate φ̇ of the axis round H_G and the spin rate ψ̇ relative to the line of nodes."""
    i_t, i_a, spin, theta_deg = given["i_transverse"], given["i_axial"], given["spin_rad_s"], given["nutation_deg"]
    motion = AxisymmetricFreeMotion(
        I_transverse_kg_m2=i_t, I_axial_kg_m2=i_a, spin_rad_s=spin, nutation_rad=math.radians(theta_deg)
    )
    h = motion.angular_momentum_kg_m2_s
    phi_dot = motion.precession_rate_rad_s
    psi_dot = motion.spin_rate_rad_s
    return {
        "h": PartAnswer(
            h,
            rf"H_G \cos\theta = I_a\omega_z \Rightarrow H_G = \frac{{I_a\omega_z}}{{\cos\theta}} = {h:.4g}"
            r"\ \mathrm{kg\,m^2/s}",
            {"spin-only": i_a * spin},
        ),
        "precession": PartAnswer(
            phi_dot,
            rf"\dot\phi = \frac{{H_G}}{{I_t}} = \frac{{I_a\omega_z}}{{I_t\cos\theta}} = {phi_dot:.4g}"
            r"\ \mathrm{rad/s}",
            {"axial-moment": h / i_a, "no-cos": i_a * spin / i_t},
        ),
        "spin": PartAnswer(
            psi_dot,
            rf"\dot\psi = \omega_z - \dot\phi\cos\theta = \frac{{I_t - I_a}}{{I_t}}\,\omega_z = {psi_dot:.4g}"
            r"\ \mathrm{rad/s}",
            {"omega-z": spin, "body-frame-rate": motion.body_frame_precession_rate_rad_s},
        ),
    }


def tossed_cylinder(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A uniform solid cylinder (radius r, length L) tossed with spin ω_z about its axis, the axis θ from H_G: the
    sense of precession, the body cone's half-angle β, the space cone's γ, and ω in XYZ (Z along H_G) at the instant
    the line of nodes is along X, when k = (0, −sin θ, cos θ)."""
    r, length, spin, theta_deg = given["radius_m"], given["length_m"], given["spin_rad_s"], given["nutation_deg"]
    tensor = inertia.solid_cylinder(1.0, r, length)  # the mass cancels from every answer
    i_t, i_a = float(tensor[0, 0]), float(tensor[2, 2])
    ratio = i_a / i_t
    if abs(ratio - 1.0) < 0.1:
        raise ValueError("too nearly a sphere: the cones are too thin to tell apart")
    theta = math.radians(theta_deg)
    motion = AxisymmetricFreeMotion(I_transverse_kg_m2=i_t, I_axial_kg_m2=i_a, spin_rad_s=spin, nutation_rad=theta)
    beta = math.degrees(motion.body_cone_half_angle_rad)
    gamma = math.degrees(motion.space_cone_half_angle_rad)
    if gamma < 2.0:
        raise ValueError("the space cone is too thin: its angle is a small difference of two larger ones")
    phi_dot, psi_dot = motion.precession_rate_rad_s, motion.spin_rate_rad_s
    k = np.array([0.0, -math.sin(theta), math.cos(theta)])
    vertical = np.array([0.0, 0.0, 1.0])
    omega = phi_dot * vertical + psi_dot * k
    with_spin = phi_dot * vertical + spin * k
    sense = "direct" if ratio < 1.0 else "retrograde"
    return {
        "sense": PartAnswer(
            sense,
            rf"I_a/I_t = \frac{{6r^2}}{{3r^2 + L^2}} = {ratio:.4g}"
            + (r" < 1:\ \text{prolate, direct}" if ratio < 1.0 else r" > 1:\ \text{oblate, retrograde}"),
            {"shape-backwards": "retrograde" if sense == "direct" else "direct"},
        ),
        "beta": PartAnswer(
            beta,
            rf"\tan\beta = \frac{{I_a}}{{I_t}}\tan\theta = {ratio * math.tan(theta):.4g},\ \beta = {beta:.4g}^\circ",
            {"ratio-inverted": math.degrees(math.atan(math.tan(theta) / ratio))},
        ),
        "gamma": PartAnswer(
            gamma,
            rf"\gamma = |\theta - \beta| = {gamma:.4g}^\circ",
            {"cones-added": theta_deg + beta, "gamma-is-theta": theta_deg},
        ),
        "omega": PartAnswer(
            tuple(float(c) for c in omega),
            rf"\boldsymbol\omega = \dot\phi\,\mathbf K + \dot\psi\,\mathbf k,\ \dot\phi = {phi_dot:.4g},"
            rf"\ \dot\psi = {psi_dot:.4g}\ \mathrm{{rad/s}}:\ ({omega[0]:.4g},\ {omega[1]:.4g},\ {omega[2]:.4g})"
            r"\ \mathrm{rad/s}",
            {"omega-z-for-psi-dot": tuple(float(c) for c in with_spin)},
        ),
    }


def tumbling_box(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A uniform box (sides a, b, c along x, y, z) spun at Ω about the axis where a steady spin is unstable: which
    axis, the growth rate s of a small wobble, and the time for the growing wobble to multiply by 100."""
    m, a, b, c, spin = given["mass_kg"], given["length_m"], given["width_m"], given["height_m"], given["spin_rad_s"]
    moments = np.diag(inertia.box(m, a, b, c))
    order = np.argsort(moments)
    low, mid, high = (float(moments[i]) for i in order)
    if mid / low < 1.1 or high / mid < 1.1:
        raise ValueError("two moments too close: the unstable axis would be ambiguous and the growth slow")
    product = (mid - low) * (high - mid) / (low * high)
    rate = spin * math.sqrt(product)
    time = math.log(100.0) / rate
    moments_text = r",\ ".join(rf"I_{AXES[i]} = {moments[i]:.4g}" for i in range(3))
    return {
        "axis": PartAnswer(
            AXES[order[1]],
            rf"{moments_text}\ \mathrm{{kg\,m^2}}:\ \text{{the intermediate moment is about }} {AXES[order[1]]}",
            {"largest-axis": AXES[order[2]], "smallest-axis": AXES[order[0]]},
        ),
        "rate": PartAnswer(
            rate,
            r"s = \Omega\sqrt{\frac{(I_{\mathrm{mid}} - I_{\min})(I_{\max} - I_{\mathrm{mid}})}{I_{\min} I_{\max}}}"
            rf" = {rate:.4g}\ \mathrm{{s^{{-1}}}}",
            {"no-root": spin * product},
        ),
        "time": PartAnswer(
            time,
            rf"e^{{s t}} = 100 \Rightarrow t = \frac{{\ln 100}}{{s}} = {time:.4g}\ \mathrm{{s}}",
            {"log-ten": 2.0 / rate},
        ),
    }


# ---- 10.2 Spinning top --------------------------------------------------------------------------------------------


def _top(given: Mapping[str, float]) -> tuple[float, float, float, float]:
    """(I_t about the pivot, I_a, m g l, ω_z) of a top given by its numbers; ValueError if no body has them."""
    m, l, g = given["mass_kg"], given["cg_distance_m"], given["g_m_s2"]
    i_t, i_a = given["i_transverse_pivot"], given["i_axial"]
    centroidal = i_t - m * l**2
    if centroidal <= 0.0 or i_a > 2.0 * centroidal:
        raise ValueError("no real top has these moments (parallel-axis share or triangle inequality)")
    return i_t, i_a, m * g * l, given["spin_rad_s"]


def steady_precession(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A top spinning at ω_z with its axis steady at θ from the upward vertical: gravity's moment about the pivot,
    the gyroscopic estimate of the precession rate, and the exact slow steady rate, the smaller root of
    I_t cos θ φ̇² − I_a ω_z φ̇ + m g l = 0."""
    i_t, i_a, mgl, spin = _top(given)
    theta = math.radians(given["theta0_deg"])
    h = i_a * spin
    discriminant_ratio = 4.0 * i_t * mgl * math.cos(theta) / h**2
    if not 0.12 <= discriminant_ratio <= 0.95:
        raise ValueError("the spin is so fast that the estimate is exact, or too slow for steady precession")
    root = math.sqrt(1.0 - discriminant_ratio)
    slow = 2.0 * mgl / (h * (1.0 + root))  # the smaller root, written without cancellation
    fast = h * (1.0 + root) / (2.0 * i_t * math.cos(theta))
    moment = mgl * math.sin(theta)
    estimate = mgl / h
    return {
        "moment": PartAnswer(
            moment,
            rf"|\mathbf M_O| = |l\,\mathbf k \times (-m g\,\mathbf K)| = m g l \sin\theta = {moment:.4g}"
            r"\ \mathrm{N\,m}",
            {"cos-lever": mgl * math.cos(theta)},
        ),
        "estimate": PartAnswer(
            estimate,
            rf"\dot\phi \approx \frac{{|\mathbf M_O|}}{{H\sin\theta}} = \frac{{m g l}}{{I_a\omega_z}} = {estimate:.4g}"
            r"\ \mathrm{rad/s}",
            {"kept-sine": moment / h, "transverse-moment": mgl / (i_t * spin)},
        ),
        "exact": PartAnswer(
            slow,
            r"I_t\cos\theta\,\dot\phi^2 - I_a\omega_z\dot\phi + m g l = 0,\ "
            rf"\dot\phi = \frac{{I_a\omega_z - \sqrt{{I_a^2\omega_z^2 - 4 I_t m g l\cos\theta}}}}{{2 I_t\cos\theta}}"
            rf" = {slow:.4g}\ \mathrm{{rad/s}}",
            {"fast-root": fast, "estimate": estimate},
        ),
    }


def sleeping_top(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A thin disk (m, r) on a light stem, its centre l above the pivot, spinning upright at ω_z: I_t about the
    pivot, the sleeping threshold as a formula and as a number, and whether this top sleeps."""
    m, r, l, g, spin = given["mass_kg"], given["radius_m"], given["cg_distance_m"], given["g_m_s2"], given["spin_rad_s"]
    disk = inertia.thin_disk(m, r)
    about_pivot = inertia.parallel_axis(disk, m, np.array([0.0, 0.0, l]))
    i_t, i_a = float(about_pivot[0, 0]), float(about_pivot[2, 2])
    critical = math.sqrt(4.0 * m * g * l * i_t) / i_a
    if abs(spin / critical - 1.0) < 0.05:
        raise ValueError("the spin is too near the threshold to call")
    Ia, It, ms, gs, ls = sympy.symbols("Ia It m g l", real=True)
    formula = 2 * sympy.sqrt(ms * gs * ls * It) / Ia
    centroidal_t = float(disk[0, 0])
    sleeps = "sleeps" if spin > critical else "falls"
    return {
        "it": PartAnswer(
            i_t,
            rf"I_t = \tfrac14 m r^2 + m l^2 = {i_t:.4g}\ \mathrm{{kg\,m^2}}",
            {"no-parallel-axis": centroidal_t, "axial-for-transverse": float(disk[2, 2]) + m * l**2},
        ),
        "formula": PartAnswer(
            formula,
            r"\omega_z^2 > \frac{4 m g l I_t}{I_a^2} \Rightarrow \omega_{\mathrm{cr}} = \frac{2\sqrt{m g l I_t}}{I_a}",
            {"no-four": formula / 2, "moments-swapped": 2 * sympy.sqrt(ms * gs * ls * Ia) / It},
        ),
        "critical": PartAnswer(
            critical,
            rf"\omega_{{\mathrm{{cr}}}} = \frac{{2\sqrt{{m g l I_t}}}}{{I_a}} = {critical:.4g}\ \mathrm{{rad/s}}",
            {"centroidal-it": math.sqrt(4.0 * m * g * l * centroidal_t) / i_a, "no-four": critical / 2.0},
        ),
        "sleeps": PartAnswer(
            sleeps,
            rf"\omega_z = {spin:.4g}\ \mathrm{{rad/s}}"
            + (r" > " if spin > critical else r" < ")
            + rf"\omega_{{\mathrm{{cr}}}} = {critical:.4g}\ \mathrm{{rad/s}}",
            {"backwards": "falls" if sleeps == "sleeps" else "sleeps"},
        ),
    }


def top_released_at_rest(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A top released at tilt θ0 with spin ω_z and no precession or nutation rate: the vertical angular momentum
    H_Z, the largest tilt θ_max (the other root of f(u) in [−1, u0]) and the precession rate φ̇ there."""
    i_t, i_a, mgl, spin = _top(given)
    theta0 = math.radians(given["theta0_deg"])
    u0 = math.cos(theta0)
    h = i_a * spin
    h_z = h * u0
    # u̇² = f(u) = (u0 − u)[β(1 − u²) − c²(u0 − u)], β = 2mgl/I_t, c = I_a ω_z / I_t: the other root of the bracket
    # below u0, the quadratic's smaller root, written as (product of roots) / (larger root) for precision.
    beta, c2 = 2.0 * mgl / i_t, (h / i_t) ** 2
    discriminant = (c2 - 2.0 * beta * u0) ** 2 + 4.0 * beta**2 * (1.0 - u0**2)
    u_low = 2.0 * (c2 * u0 - beta) / (c2 + math.sqrt(discriminant))
    if not -1.0 < u_low < u0:
        raise ValueError("no turning point below the start")
    theta_max = math.degrees(math.acos(u_low))
    sin_max = math.sqrt(1.0 - u_low**2)
    phi_dot = h * (u0 - u_low) / (i_t * sin_max**2)
    estimate = math.degrees(theta0 + 2.0 * mgl * i_t * math.sin(theta0) / h**2)
    if theta_max > 100.0:
        raise ValueError("the top falls nearly over: not a top any more")
    return {
        "hz": PartAnswer(
            h_z,
            rf"H_Z = I_a\omega_z\cos\theta_0 = {h_z:.4g}\ \mathrm{{kg\,m^2/s}}",
            {"no-cos": h},
        ),
        "theta-max": PartAnswer(
            theta_max,
            r"\dot u^2 = (u_0 - u)\left[\beta(1 - u^2) - c^2(u_0 - u)\right],\ "
            rf"\beta = \frac{{2mgl}}{{I_t}} = {beta:.4g},\ c = \frac{{I_a\omega_z}}{{I_t}} = {math.sqrt(c2):.4g}:\ "
            rf"u = {u_low:.5g},\ \theta_{{\max}} = {theta_max:.4g}^\circ",
            {"fast-top-estimate": estimate, "start-angle": math.degrees(theta0)},
        ),
        "phi-dot": PartAnswer(
            phi_dot,
            rf"\dot\phi = \frac{{H_Z - I_a\omega_z\cos\theta_{{\max}}}}{{I_t\sin^2\theta_{{\max}}}} = {phi_dot:.4g}"
            r"\ \mathrm{rad/s}",
            {"sine-not-squared": h * (u0 - u_low) / (i_t * sin_max)},
        ),
    }


# ---- 10.3 Gyroscopes for inertial guidance ------------------------------------------------------------------------


def _gyrocompass_params(given: Mapping[str, float]) -> dict[str, float]:
    return {
        "latitude_deg": given["latitude_deg"],
        "spin_rad_s": given["spin_rad_s"],
        "rotor_axial_inertia_kg_m2": given["rotor_inertia_kg_m2"],
        "vertical_inertia_kg_m2": given["vertical_inertia_kg_m2"],
        "damping_N_m_s_rad": 0.0,
        "alpha0_deg": given["alpha0_deg"],
        "alpha_rate0_rad_s": 0.0,
        "earth_rate_rad_s": EARTH_RATE_RAD_S,
    }


def gyrocompass_swing(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A gyrocompass at latitude λ released from rest α0 east of north: K = I_a ω_s Ω cos λ, the small-swing period
    and the period of this swing, 4 K(m)/ω_n with m = sin²(α0/2)."""
    params = _gyrocompass_params(given)
    k = gyrocompass.restoring_moment_N_m(params)
    small = gyrocompass.small_angle_period_s(params)
    amplitude = math.radians(given["alpha0_deg"])
    period = gyrocompass.large_amplitude_period_s(params, amplitude)
    h = gyrocompass.spin_momentum_N_m_s(params)
    latitude = math.radians(given["latitude_deg"])
    m = math.sin(amplitude / 2) ** 2
    return {
        "moment": PartAnswer(
            k,
            rf"K = I_a\omega_s\,\Omega\cos\lambda = {k:.4g}\ \mathrm{{N\,m}}",
            {"sine-latitude": h * EARTH_RATE_RAD_S * math.sin(latitude), "whole-earth-rate": h * EARTH_RATE_RAD_S},
        ),
        "small-period": PartAnswer(
            small,
            rf"T_0 = 2\pi\sqrt{{I_t/K}} = {small:.4g}\ \mathrm{{s}}",
            {"no-two-pi": small / (2.0 * math.pi)},
        ),
        "period": PartAnswer(
            period,
            rf"T = \frac{{4}}{{\omega_n}} K(m),\ m = \sin^2\frac{{\alpha_0}}{{2}} = {m:.4g},"
            rf"\ K(m) = {float(ellipk(m)):.5g}:\ T = {period:.4g}\ \mathrm{{s}}",
            {"small-angle": small},
        ),
    }


def _rate_gyro_params(given: Mapping[str, float]) -> dict[str, float | str]:
    return {
        "rotor_axial_inertia_kg_m2": given["rotor_inertia_kg_m2"],
        "spin_rad_s": given["spin_rad_s"],
        "gimbal_inertia_kg_m2": given["gimbal_inertia_kg_m2"],
        "stiffness_N_m_rad": given["stiffness_nm_rad"],
        "damping_N_m_s_rad": given["damping_nms_rad"],
        "input_kind": "step",
        "input_rate_rad_s": given["input_rate_rad_s"],
        "input_frequency_rad_s": 5.0,
    }


def rate_gyro_step(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A rate gyro whose case starts turning at a constant Ω0: the steady deflection H Ω0 / k, the damping ratio and
    the first (largest) deflection, β_ss (1 + e^(−πζ/√(1−ζ²)))."""
    params = _rate_gyro_params(given)
    steady = rate_gyro.steady_gain_s(params) * given["input_rate_rad_s"]
    zeta = rate_gyro.damping_ratio(params)
    if zeta >= 0.7:
        raise ValueError("too heavily damped for a clear overshoot")
    overshoot = math.exp(-math.pi * zeta / math.sqrt(1.0 - zeta**2))
    peak = steady * (1.0 + overshoot)
    if peak > rate_gyro.SMALL_ANGLE_LIMIT_RAD:
        raise ValueError("the gimbal would swing beyond the small-angle model")
    return {
        "steady": PartAnswer(
            math.degrees(steady),
            rf"\beta_{{ss}} = \frac{{I_a\omega_s\,\Omega_0}}{{k}} = {steady:.4g}\ \mathrm{{rad}}"
            rf" = {math.degrees(steady):.4g}^\circ",
            {"radian-number": steady},
        ),
        "zeta": PartAnswer(
            zeta,
            rf"\zeta = \frac{{c}}{{2\sqrt{{k I_g}}}} = {zeta:.4g}",
            {"no-two": 2.0 * zeta},
        ),
        "peak": PartAnswer(
            math.degrees(peak),
            rf"\beta_{{\max}} = \beta_{{ss}}\left(1 + e^{{-\pi\zeta/\sqrt{{1-\zeta^2}}}}\right)"
            rf" = {math.degrees(steady):.4g}^\circ \times {1.0 + overshoot:.4g} = {math.degrees(peak):.4g}^\circ",
            {"steady-value": math.degrees(steady), "undamped-peak": 2.0 * math.degrees(steady)},
        ),
    }


def free_gyro_readout(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A free gyroscope on a vehicle turning at a constant body rate (p, 0, r); at t = 0 the outer gimbal angle is 0
    and the inner one ε, so the spin axis is (0, cos ε, sin ε). The spin axis in vehicle components at time t, and
    the two gimbal angles then."""
    p, r, t = given["roll_rate_rad_s"], given["yaw_rate_rad_s"], given["time_s"]
    params = {
        "vehicle_rate_rad_s": [p, 0.0, r],
        "spin_rad_s": 1000.0,
        "rotor_inertia_kg_m2": 1e-3,
        "inner_gimbal0_deg": given["elevation_deg"],
        "outer_gimbal0_deg": 0.0,
    }
    motion = free_gyroscope.gimbal_motion(params, t)
    axis = motion.spin_axis_vehicle[0]
    inner, outer = math.degrees(float(motion.inner_rad[0])), math.degrees(float(motion.outer_rad[0]))
    if abs(inner) > 75.0:
        raise ValueError("too near gimbal lock")
    if min(abs(inner), abs(outer)) < 1.5:
        raise ValueError("a gimbal angle too near zero to be checked to a relative tolerance")
    # The mistake: the spin axis turned with the vehicle instead of against it.
    rate = math.hypot(p, r)
    n = np.array([p, 0.0, r]) / rate
    s_n = free_gyroscope.spin_axis_inertial(params)
    angle = rate * t
    turned = s_n * math.cos(angle) + np.cross(n, s_n) * math.sin(angle) + n * float(n @ s_n) * (1 - math.cos(angle))
    return {
        "axis": PartAnswer(
            tuple(float(c) for c in axis),
            r"\{s\}_B = [R_{NB}]^{\mathsf T}\{s\}_N,\ [R_{NB}] = \mathrm{Rot}(\hat n,\ |\boldsymbol\omega_B| t),"
            rf"\ |\boldsymbol\omega_B| t = {angle:.4g}\ \mathrm{{rad}}:"
            rf"\ ({axis[0]:.4g},\ {axis[1]:.4g},\ {axis[2]:.4g})",
            {"turned-with-vehicle": tuple(float(c) for c in turned)},
        ),
        "inner": PartAnswer(
            inner,
            rf"\phi_i = \arcsin s_{{Bz}} = {inner:.4g}^\circ",
            {"radian-number": math.radians(inner), "turned-with-vehicle": math.degrees(math.asin(float(turned[2])))},
        ),
        "outer": PartAnswer(
            outer,
            rf"\phi_o = \operatorname{{atan2}}(-s_{{Bx}},\ s_{{By}}) = {outer:.4g}^\circ",
            {"sign-convention": -outer},
        ),
    }
