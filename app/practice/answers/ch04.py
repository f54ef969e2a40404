"""Answers of chapter 4's exercises: the two general equations for points of a rigid body, Eulerian angles and their
rates, loop closure of linkages (four-bar, offset slider-crank, cardan joint), and rolling without slip.

Conventions are the lessons': fixed frames have Z (or y, in the plane) up, angles are counterclockwise positive, the
Eulerian angles are the 3-1-3 sequence (precession φ about Z, nutation θ about the line of nodes, spin ψ about the
body's axis) and the nutation frame x′y′z′ is the frame after the first two turns. Where the project has a model of
the system (the disk on the turntable, the Eulerian-angle kinematics, the four-bar, the slider-crank, the cardan
joint), the answer function calls it; the tests check every answer by another route.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import sympy

from app.physics.math.rotations import angle_rate_matrix_body
from app.physics.systems.ch04.cardan_joint import CardanJoint
from app.physics.systems.ch04.eulerian_angles import EulerianAngleMotion
from app.physics.systems.ch04.four_bar import FourBar
from app.physics.systems.ch04.rigid_body_points import DiskOnTurntable
from app.physics.systems.ch04.slider_crank import SliderCrank
from app.practice.exercise import PartAnswer

#: Symbols of the expression parts (real, as the checker's are).
v, L, R, theta, thetad, phid, psid, r, l, e, omega = sympy.symbols(
    "v L R theta thetad phid psid r l e omega", real=True
)
beta_s, phi_s = sympy.symbols("beta phi", real=True)


def _vec(vector: np.ndarray) -> tuple[float, float, float]:
    return (float(vector[0]), float(vector[1]), float(vector[2]))


def _tex(vector: np.ndarray | tuple[float, ...], digits: int = 4) -> str:
    """Components as the working shows them; rounding noise (below 1e-12 of the largest) is shown as 0."""
    values = np.asarray(vector, dtype=float)
    values = np.where(np.abs(values) < 1e-12 * np.max(np.abs(values), initial=0.0), 0.0, values) + 0.0
    return r"\left(" + r",\ ".join(f"{float(c):.{digits}g}" for c in values) + r"\right)"


def _z_cross(vector: np.ndarray) -> np.ndarray:
    """k × (x, y, 0) = (−y, x, 0) for a plane vector written with three components."""
    return np.array([-vector[1], vector[0], 0.0])


# -- 4.1 general equations ---------------------------------------------------------------------------------------


def disk_on_turntable_point(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The rigid-body-points scene at t = 0: the disk's ω and α on XYZ, and v_B and a_B for B on the rim at angle γ.
    The project's model applies v_B = v_A + ω × r_B/A and a_B = a_A + α × r_B/A + ω × (ω × r_B/A) twice."""
    disk = DiskOnTurntable.from_params(
        {
            "turntable_rate_rad_s": given["turntable_rate_rad_s"],
            "turntable_acceleration_rad_s2": given["turntable_accel_rad_s2"],
            "spin_rate_rad_s": given["spin_rate_rad_s"],
            "spin_acceleration_rad_s2": given["spin_accel_rad_s2"],
            "shaft_elevation_deg": given["elevation_deg"],
            "shaft_length_m": given["shaft_m"],
            "disk_radius_m": given["radius_m"],
            "point_angle_deg": given["point_deg"],
            "point_radius_fraction": 1.0,
        }
    )
    k = disk.at(np.array([0.0]))
    w1, w2 = given["turntable_rate_rad_s"], given["spin_rate_rad_s"]
    beta = math.radians(given["elevation_deg"])
    n = np.array([math.cos(beta), 0.0, math.sin(beta)])
    K = np.array([0.0, 0.0, 1.0])
    w_vec, a_vec = k.angular_velocity[0], k.angular_acceleration[0]
    offset = k.point_from_center[0]
    v_a, v_b = k.center_velocity[0], k.point_velocity[0]
    a_a, a_b = k.center_acceleration[0], k.point_acceleration[0]
    fixed_axis = a_vec - w1 * w2 * np.cross(K, n)
    tangential, centripetal = k.tangential_acceleration[0], k.centripetal_acceleration[0]
    if np.linalg.norm(v_b) < 0.05 or np.linalg.norm(v_a) < 0.05 * np.linalg.norm(v_b):
        raise ValueError("keep v_B clear of zero and the carried part v_A clear of the total")
    return {
        "omega": PartAnswer(
            _vec(w_vec),
            rf"\bar\omega = \omega_1\bar K + \omega_2\bar n = {_tex(w_vec)}\ \mathrm{{rad/s}}",
            {"spin-only": _vec(w2 * n), "turntable-only": _vec(w1 * K)},
        ),
        "alpha": PartAnswer(
            _vec(a_vec),
            r"\bar\alpha = \dot\omega_1\bar K + \dot\omega_2\bar n + \omega_1\omega_2\,\bar K\times\bar n,\ "
            rf"\bar K\times\bar n = (0, \cos\beta, 0):\ \bar\alpha = {_tex(a_vec)}\ \mathrm{{rad/s^2}}",
            {"axis-fixed": _vec(fixed_axis)},
        ),
        "velocity": PartAnswer(
            _vec(v_b),
            rf"\bar r_{{B/A}} = {_tex(offset)}\ \mathrm{{m}},\ \bar v_A = \omega_1\bar K\times L\bar n = {_tex(v_a)},\ "
            rf"\bar v_B = \bar v_A + \bar\omega\times\bar r_{{B/A}} = {_tex(v_b)}\ \mathrm{{m/s}}",
            {"no-carry": _vec(v_b - v_a), "cross-order": _vec(v_a - np.cross(w_vec, offset))},
        ),
        "accel": PartAnswer(
            _vec(a_b),
            rf"\bar a_A = {_tex(a_a)},\ \bar\alpha\times\bar r_{{B/A}} = {_tex(tangential)},\ "
            rf"\bar\omega\times(\bar\omega\times\bar r_{{B/A}}) = {_tex(centripetal)};\ "
            rf"\bar a_B = {_tex(a_b)}\ \mathrm{{m/s^2}}",
            {
                "axis-fixed": _vec(a_b - np.cross(a_vec - fixed_axis, offset)),
                "no-centripetal": _vec(a_b - centripetal),
            },
        ),
    }


def ladder_sliding_ends(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A ladder of length L, top B on a smooth wall (x = 0), foot A on the floor pulled away from the wall at v_A
    with acceleration a_A; θ between ladder and floor. From v_B = v_A + ω k × r_B/A with v_B along the wall:
    ω = v/(L sin θ), v_B = −v cot θ; from a_B = a_A + α k × r − ω² r: α = (a + ω² L cos θ)/(L sin θ)."""
    length, angle = given["length_m"], math.radians(given["angle_deg"])
    speed, accel = given["foot_speed_m_s"], given["foot_accel_m_s2"]
    s, c = math.sin(angle), math.cos(angle)
    w = speed / (length * s)
    vb = -w * length * c
    alpha = (accel + w**2 * length * c) / (length * s)
    ab = -alpha * length * c - w**2 * length * s
    alpha_plain = accel / (length * s)
    alpha_flipped = (accel - w**2 * length * c) / (length * s)
    return {
        "omega": PartAnswer(
            v / (L * sympy.sin(theta)),
            r"\bar v_B = v\,\bar i + \omega\bar k\times L(-\cos\theta, \sin\theta) = (v - \omega L\sin\theta,\ "
            r"-\omega L\cos\theta);\ v_{Bx} = 0\ \Rightarrow\ \omega = \frac{v}{L\sin\theta}",
            {"sin-cos": v / (L * sympy.cos(theta)), "foot-radius": v / L},
        ),
        "vb": PartAnswer(
            vb,
            rf"v_B = -\omega L\cos\theta = -v\cot\theta = {vb:.4g}\ \mathrm{{m/s}}",
            {"tan-not-cot": -speed * s / c, "sign": -vb},
        ),
        "alpha": PartAnswer(
            alpha,
            rf"\omega = {w:.4g}\ \mathrm{{rad/s}};\ a_{{Bx}} = a - \alpha L\sin\theta + \omega^2 L\cos\theta = 0"
            rf"\ \Rightarrow\ \alpha = \frac{{a + \omega^2 L\cos\theta}}{{L\sin\theta}} = {alpha:.4g}\ "
            r"\mathrm{rad/s^2}",
            {"no-centripetal": alpha_plain},
        ),
        "ab": PartAnswer(
            ab,
            rf"a_B = -\alpha L\cos\theta - \omega^2 L\sin\theta = {ab:.4g}\ \mathrm{{m/s^2}}",
            {
                "no-centripetal": -alpha_plain * length * c,
                "centripetal-sign": -alpha_flipped * length * c + w**2 * length * s,
            },
        ),
    }


def drone_rotor_hub(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A drone's centre G flies at v_G = (v, 0, 0) and climbs with a_G = (0, 0, a); the body turns at ω and
    α (on XYZ); the hub B is at r_B/G = d (cos χ, sin χ, 0). v_B and a_B by the general equations; reversing ω
    flips ω × r but leaves ω × (ω × r) as it is."""
    w_vec = np.array([given["p_rad_s"], given["q_rad_s"], given["r_rad_s"]])
    a_vec = np.array([given["alpha_x_rad_s2"], given["alpha_y_rad_s2"], given["alpha_z_rad_s2"]])
    chi = math.radians(given["arm_deg"])
    offset = given["arm_m"] * np.array([math.cos(chi), math.sin(chi), 0.0])
    v_g = np.array([given["speed_m_s"], 0.0, 0.0])
    a_g = np.array([0.0, 0.0, given["climb_accel_m_s2"]])
    turning = np.cross(w_vec, offset)
    v_b = v_g + turning
    tangential = np.cross(a_vec, offset)
    centripetal = np.cross(w_vec, np.cross(w_vec, offset))
    a_b = a_g + tangential + centripetal
    return {
        "velocity": PartAnswer(
            _vec(v_b),
            rf"\bar r_{{B/G}} = {_tex(offset)}\ \mathrm{{m}},\ \bar\omega\times\bar r_{{B/G}} = {_tex(turning)},\ "
            rf"\bar v_B = \bar v_G + \bar\omega\times\bar r_{{B/G}} = {_tex(v_b)}\ \mathrm{{m/s}}",
            {"cross-order": _vec(v_g - turning), "no-carry": _vec(turning)},
        ),
        "accel": PartAnswer(
            _vec(a_b),
            rf"\bar\alpha\times\bar r = {_tex(tangential)},\ \bar\omega\times(\bar\omega\times\bar r) = "
            rf"{_tex(centripetal)},\ \bar a_B = \bar a_G + \bar\alpha\times\bar r + \bar\omega\times(\bar\omega\times"
            rf"\bar r) = {_tex(a_b)}\ \mathrm{{m/s^2}}",
            {
                "no-centripetal": _vec(a_g + tangential),
                "no-alpha": _vec(a_g + centripetal),
                "centripetal-sign": _vec(a_g + tangential - centripetal),
            },
        ),
        "reverse": PartAnswer(
            "velocity-only",
            r"\bar\omega\to-\bar\omega:\ \bar\omega\times\bar r\to-\bar\omega\times\bar r,\ "
            r"(-\bar\omega)\times((-\bar\omega)\times\bar r) = \bar\omega\times(\bar\omega\times\bar r)",
            {"both": "both", "neither": "neither"},
        ),
    }


# -- 4.2 Eulerian angles -----------------------------------------------------------------------------------------


def _euler_motion(given: Mapping[str, float], **fixed: float) -> EulerianAngleMotion:
    params = {
        "precession_deg": 0.0,
        "nutation_deg": given["nutation_deg"],
        "spin_deg": 0.0,
        "precession_rate_rad_s": given["precession_rate_rad_s"],
        "nutation_rate_rad_s": 0.0,
        "spin_rate_rad_s": given["spin_rate_rad_s"],
        "precession_acceleration_rad_s2": 0.0,
        "nutation_acceleration_rad_s2": 0.0,
        "spin_acceleration_rad_s2": 0.0,
    }
    params.update({k: v for k, v in given.items() if k in params})
    params.update(fixed)
    return EulerianAngleMotion.from_params(params)


def top_nutation_frame(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """Constant φ̇, θ̇, ψ̇: ω and α on the nutation frame (from the project's Eulerian-angle model), with
    α_y′ = θ̇ (φ̇ cos θ − ψ̇) as a formula."""
    tilt = math.radians(given["nutation_deg"])
    pd, td, sd = given["precession_rate_rad_s"], given["nutation_rate_rad_s"], given["spin_rate_rad_s"]
    state = _euler_motion(given).at(np.array([0.0]))
    w_vec, a_vec = state.angular_velocity_nutation[0], state.angular_acceleration_nutation[0]
    s, c = math.sin(tilt), math.cos(tilt)
    return {
        "omega": PartAnswer(
            _vec(w_vec),
            r"\bar\omega = \dot\theta\,\bar i' + \dot\phi\sin\theta\,\bar j' + (\dot\phi\cos\theta + \dot\psi)\,\bar k'"
            rf" = {_tex(w_vec)}\ \mathrm{{rad/s}}",
            {"spin-only-z": (td, pd * s, sd), "sin-cos": (td, pd * c, pd * s + sd)},
        ),
        "alpha-y": PartAnswer(
            thetad * (phid * sympy.cos(theta) - psid),
            r"\bar\alpha = \frac{d}{dt}(\omega_{x'}, \omega_{y'}, \omega_{z'}) + \bar\Omega'\times\bar\omega,\ "
            r"\bar\Omega' = (\dot\theta, \dot\phi\sin\theta, \dot\phi\cos\theta):\ "
            r"\alpha_{y'} = \dot\phi\dot\theta\cos\theta - \dot\psi\dot\theta",
            {"components-only": thetad * phid * sympy.cos(theta), "transport-only": -thetad * psid},
        ),
        "alpha": PartAnswer(
            _vec(a_vec),
            r"\bar\alpha = (\dot\phi\dot\psi\sin\theta,\ \dot\theta(\dot\phi\cos\theta - \dot\psi),\ "
            rf"-\dot\phi\dot\theta\sin\theta) = {_tex(a_vec)}\ \mathrm{{rad/s^2}}",
            {
                "steady-precession": (pd * sd * s, 0.0, 0.0),
                "components-only": (0.0, pd * td * c, -pd * td * s),
            },
        ),
    }


def gyro_rotor_rim_point(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A rotor whose axis is tilted a steady θ from Z and precesses at φ̇ (speeding up at φ̈) while it spins at a
    steady ψ̇; its centre is L from the fixed point O along the axis. The highest point P of its rim, R from the
    centre along j′: α and a_P on x′y′z′, and |v_P|."""
    tilt = math.radians(given["nutation_deg"])
    pd, pdd, sd = given["precession_rate_rad_s"], given["precession_accel_rad_s2"], given["spin_rate_rad_s"]
    length, radius = given["arm_m"], given["radius_m"]
    state = _euler_motion(given, precession_acceleration_rad_s2=pdd).at(np.array([0.0]))
    w_vec, a_vec = state.angular_velocity_nutation[0], state.angular_acceleration_nutation[0]
    s, c = math.sin(tilt), math.cos(tilt)
    point = np.array([0.0, radius, length])
    velocity = np.cross(w_vec, point)
    speed = float(np.linalg.norm(velocity))
    if speed < 0.1 * sd * radius:
        raise ValueError("keep the rim point's speed clear of zero")
    centripetal = np.cross(w_vec, np.cross(w_vec, point))
    accel = np.cross(a_vec, point) + centripetal
    steady = np.array([pd * sd * s, 0.0, 0.0])
    spin_only = np.cross(np.array([0.0, 0.0, sd]), point)
    return {
        "alpha": PartAnswer(
            _vec(a_vec),
            r"\bar\alpha = \frac{d}{dt}(0, \dot\phi\sin\theta, \dot\phi\cos\theta + \dot\psi) + \bar\Omega'\times"
            r"\bar\omega = (\dot\phi\dot\psi\sin\theta,\ \ddot\phi\sin\theta,\ \ddot\phi\cos\theta)"
            rf" = {_tex(a_vec)}\ \mathrm{{rad/s^2}}",
            {"steady-alpha": _vec(steady), "no-gyroscopic": (0.0, pdd * s, pdd * c)},
        ),
        "speed": PartAnswer(
            speed,
            rf"\bar\omega = {_tex(w_vec)},\ \bar r_{{P/O}} = (0, R, L),\ \bar v_P = \bar\omega\times\bar r_{{P/O}}"
            rf" = {_tex(velocity)},\ |\bar v_P| = {speed:.4g}\ \mathrm{{m/s}}",
            {"spin-only": float(np.linalg.norm(spin_only))},
        ),
        "accel": PartAnswer(
            _vec(accel),
            rf"\bar a_P = \bar\alpha\times\bar r + \bar\omega\times(\bar\omega\times\bar r) = {_tex(accel)}\ "
            r"\mathrm{m/s^2}",
            {"no-alpha": _vec(centripetal)},
        ),
    }


def rates_near_upright(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """Body-axis gyros read ω = (ω_x, ω_y, ω_z) on a body whose nutation is θ and spin ψ. Back to the rates:
    φ̇ = (ω_x sin ψ + ω_y cos ψ)/sin θ, ψ̇ = ω_z − φ̇ cos θ; a bias δ on ω_x moves φ̇ by δ sin ψ / sin θ."""
    tilt, spin = math.radians(given["nutation_deg"]), math.radians(given["spin_deg"])
    w_body = np.array([given["wx_rad_s"], given["wy_rad_s"], given["wz_rad_s"]])
    bias = given["bias_rad_s"]
    J = angle_rate_matrix_body(np.array([0.0, tilt, spin]), "3-1-3")
    rates = np.linalg.solve(J, w_body)
    shifted = np.linalg.solve(J, w_body + np.array([bias, 0.0, 0.0]))
    precession, spin_rate = float(rates[0]), float(rates[2])
    change = abs(float(shifted[0] - rates[0]))
    if abs(precession) < 0.1 or abs(math.sin(spin)) < 0.3:
        raise ValueError("keep the precession rate and the bias's effect clear of zero")
    numerator = given["wx_rad_s"] * math.sin(spin) + given["wy_rad_s"] * math.cos(spin)
    swapped = (given["wx_rad_s"] * math.cos(spin) - given["wy_rad_s"] * math.sin(spin)) / math.sin(tilt)
    return {
        "precession": PartAnswer(
            precession,
            rf"\dot\phi = \frac{{\omega_x\sin\psi + \omega_y\cos\psi}}{{\sin\theta}} = \frac{{{numerator:.4g}}}"
            rf"{{{math.sin(tilt):.4g}}} = {precession:.4g}\ \mathrm{{rad/s}}",
            {"no-sine": numerator, "swap-trig": swapped},
        ),
        "spin": PartAnswer(
            spin_rate,
            rf"\dot\psi = \omega_z - \dot\phi\cos\theta = {spin_rate:.4g}\ \mathrm{{rad/s}}",
            {"gyro-is-spin": given["wz_rad_s"], "sign": given["wz_rad_s"] + precession * math.cos(tilt)},
        ),
        "bias": PartAnswer(
            change,
            rf"\Delta\dot\phi = \frac{{\delta\,|\sin\psi|}}{{\sin\theta}} = {change:.4g}\ \mathrm{{rad/s}}",
            {"no-sine": bias * abs(math.sin(spin))},
        ),
        "fails": PartAnswer(
            "upright",
            r"\dot\phi = (\ldots)/\sin\theta:\ \sin\theta = 0\ \text{at}\ \theta = 0^\circ, 180^\circ",
            {"ninety": "ninety"},
        ),
    }


# -- 4.3 interconnections and linkages ---------------------------------------------------------------------------


def _four_bar(given: Mapping[str, float]) -> tuple[FourBar, float, dict[str, float]]:
    """The linkage, its crank angle (rad) and its open and crossed rocker angles; ValueError near a toggle."""
    linkage = FourBar(given["ground_m"], given["crank_m"], given["coupler_m"], given["rocker_m"])
    if linkage.grashof().name != "crank-rocker":
        raise ValueError("the exercise is about a crank-rocker")
    angle = math.radians(given["crank_deg"])
    mu = math.degrees(float(linkage.transmission_angle(np.array([angle]))[0]))
    if not 30.0 <= mu <= 150.0:
        raise ValueError("keep the linkage away from its toggle positions (transmission angle 30°–150°)")
    both = linkage.assemblies(np.array([angle]))
    return linkage, angle, {name: float(pos.rocker_angle[0]) for name, pos in both.items()}


def four_bar_rates(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """Open assembly at crank angle θ₂, crank turning at ω₂: θ₄ (deg), ω₃, ω₄ from the differentiated loop (the
    project's four-bar model) and v_B = ω₄ k × c e^{iθ₄}."""
    linkage, t2, rockers = _four_bar(given)
    pos = linkage.positions(np.array([t2]), "open")
    t3, t4 = float(pos.coupler_angle[0]), float(pos.rocker_angle[0])
    w2 = given["crank_speed_rad_s"]
    w3_arr, w4_arr, _ = linkage.rates(np.array([t2]), np.array([t3]), np.array([t4]), np.array([w2]))
    w3, w4 = float(w3_arr[0]), float(w4_arr[0])
    a, c = linkage.crank_m, linkage.rocker_m
    rocker_vec = c * np.array([math.cos(t4), math.sin(t4), 0.0])
    v_b = w4 * _z_cross(rocker_vec)
    v_a = w2 * a * np.array([-math.sin(t2), math.cos(t2), 0.0])
    translating = a * w2 * math.cos(t2 - t4) / c
    if min(abs(w3), abs(w4)) < 0.02 * abs(w2):
        raise ValueError("keep both rates clear of zero")
    theta4 = math.degrees(t4)
    return {
        "rocker-angle": PartAnswer(
            theta4,
            rf"s = |O_4 - A| = {math.hypot(given['ground_m'] - a * math.cos(t2), a * math.sin(t2)):.4g}\ \mathrm{{m}};"
            rf"\ B\ \text{{on both circles, left of}}\ A\to O_4:\ \theta_3 = {math.degrees(t3):.4g}^\circ,\ "
            rf"\theta_4 = {theta4:.4g}^\circ",
            {"crossed": math.degrees(rockers["crossed"]), "radian-number": t4},
        ),
        "omega3": PartAnswer(
            w3,
            r"\begin{bmatrix} -b\sin\theta_3 & c\sin\theta_4 \\ b\cos\theta_3 & -c\cos\theta_4 \end{bmatrix}"
            r"\begin{bmatrix}\omega_3\\ \omega_4\end{bmatrix} = \begin{bmatrix} a\omega_2\sin\theta_2 \\ "
            rf"-a\omega_2\cos\theta_2\end{{bmatrix}}:\ \omega_3 = {w3:.4g}\ \mathrm{{rad/s}}",
            {"sign": -w3},
        ),
        "omega4": PartAnswer(
            w4,
            rf"\omega_4 = {w4:.4g}\ \mathrm{{rad/s}}",
            {"coupler-translates": translating},
        ),
        "velocity-b": PartAnswer(
            _vec(v_b),
            rf"\bar v_B = \omega_4\bar k\times c(\cos\theta_4, \sin\theta_4) = {_tex(v_b)}\ \mathrm{{m/s}}",
            {"coupler-translates": _vec(v_a)},
        ),
    }


def four_bar_accelerations(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """Open assembly at θ₂ with the crank at ω₂ and speeding up at α₂: α₃, α₄ from the twice-differentiated loop
    (the project's four-bar model) and a_B = α₄ k × r_B/O₄ − ω₄² r_B/O₄."""
    linkage, t2, _ = _four_bar(given)
    pos = linkage.positions(np.array([t2]), "open")
    t3, t4 = float(pos.coupler_angle[0]), float(pos.rocker_angle[0])
    w2, al2 = given["crank_speed_rad_s"], given["crank_accel_rad_s2"]
    arr = np.array
    w3_arr, w4_arr, _ = linkage.rates(arr([t2]), arr([t3]), arr([t4]), arr([w2]))
    w3, w4 = float(w3_arr[0]), float(w4_arr[0])
    al3_arr, al4_arr = linkage.accelerations(arr([t2]), arr([t3]), arr([t4]), arr([w2]), w3_arr, w4_arr, arr([al2]))
    al3, al4 = float(al3_arr[0]), float(al4_arr[0])
    # Dropping every ω² term: the same linear system with α₂ in place of ω₂ (the velocity solve, redone).
    plain3_arr, plain4_arr, _ = linkage.rates(arr([t2]), arr([t3]), arr([t4]), arr([al2]))
    steady3_arr, steady4_arr = linkage.accelerations(
        arr([t2]), arr([t3]), arr([t4]), arr([w2]), w3_arr, w4_arr, arr([0.0])
    )
    c = linkage.rocker_m
    rocker_vec = c * np.array([math.cos(t4), math.sin(t4), 0.0])
    a_b = al4 * _z_cross(rocker_vec) - w4**2 * rocker_vec
    if min(abs(al3), abs(al4)) < 0.05:
        raise ValueError("keep the angular accelerations clear of zero")
    return {
        "alpha3": PartAnswer(
            al3,
            rf"\theta_3 = {math.degrees(t3):.4g}^\circ,\ \theta_4 = {math.degrees(t4):.4g}^\circ,\ "
            rf"\omega_3 = {w3:.4g},\ \omega_4 = {w4:.4g}\ \mathrm{{rad/s}};\ "
            r"\begin{bmatrix} -b\sin\theta_3 & c\sin\theta_4 \\ b\cos\theta_3 & -c\cos\theta_4 \end{bmatrix}"
            r"\begin{bmatrix}\alpha_3\\ \alpha_4\end{bmatrix} = \begin{bmatrix} a\alpha_2\sin\theta_2 + "
            r"a\omega_2^2\cos\theta_2 + b\omega_3^2\cos\theta_3 - c\omega_4^2\cos\theta_4 \\ -a\alpha_2\cos\theta_2 + "
            r"a\omega_2^2\sin\theta_2 + b\omega_3^2\sin\theta_3 - c\omega_4^2\sin\theta_4 \end{bmatrix}:\ "
            rf"\alpha_3 = {al3:.4g}\ \mathrm{{rad/s^2}}",
            {"no-centripetal": float(plain3_arr[0]), "crank-steady": float(steady3_arr[0])},
        ),
        "alpha4": PartAnswer(
            al4,
            rf"\alpha_4 = {al4:.4g}\ \mathrm{{rad/s^2}}",
            {"no-centripetal": float(plain4_arr[0]), "crank-steady": float(steady4_arr[0])},
        ),
        "accel-b": PartAnswer(
            _vec(a_b),
            r"\bar a_B = \alpha_4\bar k\times\bar r_{B/O_4} - \omega_4^2\,\bar r_{B/O_4},\ \bar r_{B/O_4} = "
            rf"{_tex(rocker_vec)}\ \mathrm{{m}}:\ \bar a_B = {_tex(a_b)}\ \mathrm{{m/s^2}}",
            {
                "no-centripetal": _vec(float(plain4_arr[0]) * _z_cross(rocker_vec)),
            },
        ),
    }


def offset_slider_crank(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """Offset slider-crank (guide y = e) at crank angle θ, crank at constant ω: rod angle φ (deg), φ̇ as a formula,
    ẋ and ẍ from the project's slider-crank model."""
    crank, rod, offset = given["crank_m"], given["rod_m"], given["offset_m"]
    t, w = math.radians(given["crank_deg"]), given["crank_speed_rad_s"]
    mech = SliderCrank(crank, rod, offset)
    arr = np.array
    x_arr, phi_arr = mech.positions(arr([t]))
    phi = float(phi_arr[0])
    xd_arr, phid_arr = mech.rates(arr([t]), phi_arr, arr([w]))
    xdd_arr, _ = mech.accelerations(arr([t]), phi_arr, arr([w]), phid_arr, arr([0.0]))
    xd, pd, xdd = float(xd_arr[0]), float(phid_arr[0]), float(xdd_arr[0])
    if abs(xd) < 0.02 * crank * abs(w) or abs(xdd) < 0.02 * crank * w**2:
        raise ValueError("keep the slider's velocity and acceleration clear of zero")
    # ẍ with the rod's centripetal term l φ̇² dropped: the same two equations without it.
    ph_s, ph_c = math.sin(phi), math.cos(phi)
    phidd_plain = crank * w**2 * math.sin(t) / (rod * ph_c)
    xdd_plain = -crank * w**2 * math.cos(t) - rod * ph_s * phidd_plain
    no_offset = math.degrees(math.asin(-crank * math.sin(t) / rod))
    return {
        "rod-angle": PartAnswer(
            math.degrees(phi),
            rf"\sin\phi = \frac{{e - r\sin\theta}}{{l}} = {math.sin(phi):.4g},\ \phi = {math.degrees(phi):.4g}^\circ",
            {"no-offset": no_offset, "radian-number": phi},
        ),
        "rod-rate": PartAnswer(
            -r * omega * sympy.cos(theta) / sympy.sqrt(l**2 - (e - r * sympy.sin(theta)) ** 2),
            r"r\sin\theta + l\sin\phi = e\ \Rightarrow\ r\omega\cos\theta + l\cos\phi\,\dot\phi = 0,\ "
            r"\dot\phi = -\frac{r\omega\cos\theta}{\sqrt{l^2 - (e - r\sin\theta)^2}}",
            {
                "no-offset": -r * omega * sympy.cos(theta) / sympy.sqrt(l**2 - r**2 * sympy.sin(theta) ** 2),
                "over-l": -r * omega * sympy.cos(theta) / l,
            },
        ),
        "slider-vel": PartAnswer(
            xd,
            rf"\dot\phi = {pd:.4g}\ \mathrm{{rad/s}},\ \dot x = -r\omega\sin\theta - l\dot\phi\sin\phi = {xd:.4g}\ "
            r"\mathrm{m/s}",
            {"crank-only": -crank * w * math.sin(t)},
        ),
        "slider-acc": PartAnswer(
            xdd,
            r"\ddot\phi = \frac{r\omega^2\sin\theta + l\dot\phi^2\sin\phi}{l\cos\phi},\ "
            r"\ddot x = -r\omega^2\cos\theta - l\ddot\phi\sin\phi - l\dot\phi^2\cos\phi"
            rf" = {xdd:.4g}\ \mathrm{{m/s^2}}",
            {"no-rod-centripetal": xdd_plain},
        ),
    }


# -- 4.4 rolling -------------------------------------------------------------------------------------------------


def wheel_rim_points(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A wheel (radius R) rolling to +x on level ground, centre at v speeding up at a; ω = −v/R, α = −a/R about
    +z. The rim point P at angle β round from the contact point (forward), r_P/G = R (sin β, −cos β):
    v_P = v_G + ω × r, a_P = a_G + α × r − ω² r; the contact point's acceleration is v²/R towards the centre."""
    radius, speed, accel = given["radius_m"], given["speed_m_s"], given["accel_m_s2"]
    beta = math.radians(given["point_deg"])
    w, al = -speed / radius, -accel / radius
    offset = radius * np.array([math.sin(beta), -math.cos(beta), 0.0])
    v_g, a_g = np.array([speed, 0.0, 0.0]), np.array([accel, 0.0, 0.0])
    v_p = v_g + w * _z_cross(offset)
    tangential = al * _z_cross(offset)
    centripetal = -(w**2) * offset
    a_p = a_g + tangential + centripetal
    return {
        "velocity": PartAnswer(
            _vec(v_p),
            rf"\omega = -v/R = {w:.4g}\ \mathrm{{rad/s}},\ \bar r_{{P/G}} = {_tex(offset)}\ \mathrm{{m}},\ "
            rf"\bar v_P = v\,\bar i + \omega\bar k\times\bar r_{{P/G}} = {_tex(v_p)}\ \mathrm{{m/s}}",
            {"spin-sign": _vec(v_g - w * _z_cross(offset))},
        ),
        "accel": PartAnswer(
            _vec(a_p),
            rf"\alpha = -a/R = {al:.4g}\ \mathrm{{rad/s^2}},\ \bar a_P = a\,\bar i + \alpha\bar k\times\bar r - "
            rf"\omega^2\bar r = {_tex(a_g)} + {_tex(tangential)} + {_tex(centripetal)} = {_tex(a_p)}\ "
            r"\mathrm{m/s^2}",
            {"no-centripetal": _vec(a_g + tangential), "no-alpha": _vec(a_g + centripetal)},
        ),
        "contact": PartAnswer(
            "up",
            r"\beta = 0:\ \bar a_C = a\,\bar i + \alpha\bar k\times(0, -R) - \omega^2(0, -R) = (a - a,\ v^2/R)"
            rf" = (0,\ {speed**2 / radius:.4g})\ \mathrm{{m/s^2}}",
            {"zero": "zero", "forward": "forward"},
        ),
    }


def leaning_disk_circle(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The rolling scene's disk: rim R tilted θ inwards, contact point on a circle of radius ρ at speed v.
    σ̇ = −v/R, ω = (v/ρ) K + σ̇ n on (ê_r, ê_ψ, K), v_G = v − R (v/ρ) sin θ, and O′ at height (R − ρ sin θ)/cos θ."""
    radius, tilt, path, speed = (
        given["radius_m"],
        math.radians(given["tilt_deg"]),
        given["path_m"],
        given["speed_m_s"],
    )
    s, c = math.sin(tilt), math.cos(tilt)
    turn, spin = speed / path, -speed / radius
    w_vec = np.array([spin * c, 0.0, turn + spin * s])
    v_g = speed - radius * turn * s
    height = (radius - path * s) / c
    if abs(height) < 0.03:
        raise ValueError("keep O' clear of the ground")
    return {
        "spin": PartAnswer(
            spin,
            r"\bar v_C = (v + R\dot\sigma)\,\bar e_\psi = \bar 0\ \Rightarrow\ \dot\sigma = -v/R"
            rf" = {spin:.4g}\ \mathrm{{rad/s}}",
            {"path-radius": -speed / path, "sign": -spin},
        ),
        "omega": PartAnswer(
            _vec(w_vec),
            r"\bar\omega = \frac{v}{\rho}\bar K + \dot\sigma(\cos\theta\,\bar e_r + \sin\theta\,\bar K)"
            rf" = {_tex(w_vec)}\ \mathrm{{rad/s}}",
            {"no-turn": (spin * c, 0.0, spin * s)},
        ),
        "centre-speed": PartAnswer(
            v_g,
            rf"v_G = v - R\,\frac{{v}}{{\rho}}\sin\theta = {v_g:.4g}\ \mathrm{{m/s}}",
            {"contact-speed": speed},
        ),
        "axis-height": PartAnswer(
            height,
            rf"z_{{O'}} = \frac{{R - \rho\sin\theta}}{{\cos\theta}} = {height:.4g}\ \mathrm{{m}}",
            {"no-cos": radius - path * s, "centre-height": radius * c},
        ),
    }


def cone_rolling_apex(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A cone (base radius R, half-angle θ) rolling on its side about its apex at O, the rim's contact point at
    speed v: ω = −(v cos θ / R) ê_r along the contact line, the top of the base rim at 2 v cos² θ, and
    |α| = (v/ρ)|ω| = v² sin θ cos θ / R² (ω is carried round K at v/ρ, ρ = R / sin θ)."""
    radius, half, speed = given["radius_m"], math.radians(given["half_angle_deg"]), given["speed_m_s"]
    s, c = math.sin(half), math.cos(half)
    slant = radius / s
    size = speed * c / radius
    spin = -speed / radius
    w_vec = np.array([-size, 0.0, 0.0])
    top = 2 * speed * c**2
    alpha_size = (speed / slant) * size
    return {
        "omega-size": PartAnswer(
            v * sympy.cos(theta) / R,
            r"\bar\omega = \frac{v}{\rho}\bar K - \frac{v}{R}(\cos\theta\,\bar e_r + \sin\theta\,\bar K),\ "
            r"\rho = \frac{R}{\sin\theta}:\ |\bar\omega| = \frac{v\cos\theta}{R}",
            {"spin-only": v / R, "sin-cos": v * sympy.sin(theta) / R},
        ),
        "omega": PartAnswer(
            _vec(w_vec),
            rf"\bar\omega = -\frac{{v\cos\theta}}{{R}}\,\bar e_r = {_tex(w_vec)}\ \mathrm{{rad/s}}",
            {"no-turn": (spin * c, 0.0, spin * s)},
        ),
        "top-speed": PartAnswer(
            top,
            r"\bar v_P = \bar\omega\times\bar r_{P/C},\ \bar r_{P/C} = 2R(\cos\theta\,\bar K - \sin\theta\,\bar e_r):\ "
            rf"|\bar v_P| = 2v\cos^2\theta = {top:.4g}\ \mathrm{{m/s}}",
            {"flat-wheel": 2 * speed},
        ),
        "alpha": PartAnswer(
            alpha_size,
            rf"\bar\alpha = \frac{{v}}{{\rho}}\bar K\times\bar\omega,\ |\bar\alpha| = \frac{{v}}{{\rho}}\cdot"
            rf"\frac{{v\cos\theta}}{{R}} = {alpha_size:.4g}\ \mathrm{{rad/s^2}}",
            {"steady-zero": 0.0},
        ),
    }


def cardan_output(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A cardan joint with shafts β apart, input at φ₁ turning steadily at ω₁: the output angle from
    tan φ₂ = tan φ₁ / cos β (the project's joint model, quadrant kept), the speed ratio as a formula, ω₂, and
    α₂ = ω₁² d(ω₂/ω₁)/dφ₁."""
    beta, phi1, w1 = (
        math.radians(given["shaft_angle_deg"]),
        math.radians(given["input_deg"]),
        given["input_speed_rad_s"],
    )
    joint = CardanJoint(beta)
    at = np.array([phi1])
    phi2 = float(joint.output_angle(at)[0])
    ratio = float(joint.speed_ratio(at)[0])
    slope = float(joint.speed_ratio_slope(at)[0])
    w2, a2 = ratio * w1, slope * w1**2
    inverted = math.atan2(math.sin(phi1) * math.cos(beta), math.cos(phi1))
    sb, cb = sympy.sin(beta_s), sympy.cos(beta_s)
    return {
        "out-angle": PartAnswer(
            math.degrees(phi2),
            rf"\tan\varphi_2 = \frac{{\tan\varphi_1}}{{\cos\beta}} = {math.tan(phi1) / math.cos(beta):.4g},\ "
            rf"\varphi_2 = {math.degrees(phi2):.4g}^\circ\ \text{{(the quadrant of }}\varphi_1\text{{)}}",
            {"inverted": math.degrees(inverted), "radian-number": phi2},
        ),
        "ratio": PartAnswer(
            cb / (1 - sb**2 * sympy.cos(phi_s) ** 2),
            r"\sec^2\varphi_2\,\omega_2 = \frac{\sec^2\varphi_1\,\omega_1}{\cos\beta},\ "
            r"\sec^2\varphi_2 = 1 + \frac{\tan^2\varphi_1}{\cos^2\beta}\ \Rightarrow\ "
            r"\frac{\omega_2}{\omega_1} = \frac{\cos\beta}{1 - \sin^2\beta\cos^2\varphi_1}",
            {
                "phase": cb / (1 - sb**2 * sympy.sin(phi_s) ** 2),
                "inverted": (1 - sb**2 * sympy.cos(phi_s) ** 2) / cb,
            },
        ),
        "out-speed": PartAnswer(
            w2,
            rf"\omega_2 = \frac{{\cos\beta}}{{1 - \sin^2\beta\cos^2\varphi_1}}\,\omega_1 = {ratio:.4g}\times{w1:.4g}"
            rf" = {w2:.4g}\ \mathrm{{rad/s}}",
            {"same-speed": w1},
        ),
        "out-accel": PartAnswer(
            a2,
            r"\alpha_2 = \omega_1^2\,\frac{d}{d\varphi_1}\frac{\omega_2}{\omega_1} = -\omega_1^2\,"
            r"\frac{\cos\beta\sin^2\beta\sin 2\varphi_1}{(1 - \sin^2\beta\cos^2\varphi_1)^2}"
            rf" = {a2:.4g}\ \mathrm{{rad/s^2}}",
            {"steady-zero": 0.0},
        ),
    }
