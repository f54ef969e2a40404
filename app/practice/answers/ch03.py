"""Answers of chapter 3's exercises: rotation matrices and sequences, rates seen from turning frames, angular
velocity and acceleration from angle rates, and the moving-frame formulas for velocity and acceleration.

Conventions are the app's (:mod:`app.physics.math.rotations`): the fixed frame XYZ has Z up, ``[R]`` takes body
components to fixed ones (its columns are the body axes on XYZ), and a sequence ``a1-a2-a3`` turns about body axes,
``[R] = R_a1(θ1) R_a2(θ2) R_a3(θ3)``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import sympy

from app.physics.math.rotations import (
    angle_rate_matrix_body,
    angular_acceleration_world,
    angular_velocity_body,
    angular_velocity_world,
    axis_angle_from_matrix,
    matrix_from_angles,
    matrix_from_axis_angle,
)
from app.physics.systems.ch03.finite_rotation import finite_rotation
from app.physics.systems.ch03.moving_frame import MovingFrameMotion
from app.physics.systems.ch03.vector_derivative import VectorMotion
from app.physics.systems.earth import EARTH_RATE_RAD_S
from app.practice.exercise import PartAnswer

#: Symbols of the expression parts (real, as the checker's are).
Omega, L, gamma, theta, thetad, phid, psid, omega, alpha, r, u = sympy.symbols(
    "Omega L gamma theta thetad phid psid omega alpha r u", real=True
)


def _vec(v: np.ndarray) -> tuple[float, float, float]:
    return (float(v[0]), float(v[1]), float(v[2]))


def _tex(v: np.ndarray | tuple[float, ...], digits: int = 4) -> str:
    """Components as the working shows them; rounding noise (below 1e-12 of the largest) is shown as 0."""
    values = np.asarray(v, dtype=float)
    values = np.where(np.abs(values) < 1e-12 * np.max(np.abs(values), initial=0.0), 0.0, values) + 0.0
    return r"\left(" + r",\ ".join(f"{float(c):.{digits}g}" for c in values) + r"\right)"


def _radians(*degrees: float) -> np.ndarray:
    return np.radians(np.array(degrees, dtype=float))


# -- 3.1 coordinate transformations ------------------------------------------------------------------------------


def aircraft_nose_and_wingtip(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """3-2-1 (yaw ψ, pitch θ, roll φ; Z up, x the nose, y the left wing): the nose's unit vector on XYZ (column 1
    of [R]) and the height of the left wingtip above the centre, b times the Z component of column 2."""
    yaw, pitch, roll = _radians(given["yaw_deg"], given["pitch_deg"], given["roll_deg"])
    b = given["half_span_m"]
    R = matrix_from_angles(np.array([yaw, pitch, roll]), "3-2-1")
    nose = R[:, 0]
    flipped = matrix_from_angles(np.array([yaw, -pitch, roll]), "3-2-1")[:, 0]
    height = b * float(R[2, 1])
    return {
        "nose": PartAnswer(
            _vec(nose),
            r"\{i\}_{XYZ} = [R]\{1,0,0\}^{\mathsf T} = (\cos\psi\cos\theta,\ \sin\psi\cos\theta,\ -\sin\theta)"
            rf" = {_tex(nose)}",
            {"pitch-sign": _vec(flipped), "row-not-column": _vec(R[0, :])},
        ),
        "tip": PartAnswer(
            height,
            r"\{j\}_{XYZ} = [R]\{0,1,0\}^{\mathsf T},\ Z_{\text{tip}} = b\,R_{32} = b\cos\theta\sin\phi"
            rf" = {height:.4g}\ \mathrm{{m}}",
            {"no-pitch": b * math.sin(roll), "roll-sign": -height},
        ),
    }


def satellite_single_turn(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """3-1-3 (φ, θ, ψ): the body z axis on XYZ (column 3 of [R]), the angle of the single equivalent turn
    (trace = 1 + 2 cos α) and its axis (from the skew part of [R])."""
    angles = _radians(given["precession_deg"], given["nutation_deg"], given["spin_deg"])
    R = matrix_from_angles(angles, "3-1-3")
    trace = float(np.trace(R))
    if abs(trace / 2) > 1.0:
        raise ValueError("the trace is outside ±2: the 'forgot the 1' mistake would have no angle")
    axis, angle_rad = axis_angle_from_matrix(R)
    angle = math.degrees(float(angle_rad))
    if not 20.0 < angle < 170.0:
        raise ValueError("keep the turn well away from 0° and 180°, where the axis is ill-defined by hand")
    return {
        "boresight": PartAnswer(
            _vec(R[:, 2]),
            r"\{k\}_{XYZ} = (\sin\phi\sin\theta,\ -\cos\phi\sin\theta,\ \cos\theta)" rf" = {_tex(R[:, 2])}",
            {"row-not-column": _vec(R[2, :])},
        ),
        "angle": PartAnswer(
            angle,
            rf"\operatorname{{tr}}[R] = {trace:.4g} = 1 + 2\cos\alpha,\ \alpha = {angle:.4g}^\circ",
            {
                "trace-no-one": math.degrees(math.acos(trace / 2)),
                "radian-number": math.radians(angle),
            },
        ),
        "axis": PartAnswer(
            _vec(axis),
            r"\{n\} = \frac{(R_{32} - R_{23},\ R_{13} - R_{31},\ R_{21} - R_{12})}{2\sin\alpha}" rf" = {_tex(axis)}",
            {"transpose-axis": _vec(-axis)},
        ),
    }


def angles_read_back(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """An attitude given by 3-2-1 angles, read back as 3-1-3 angles: θ = acos R33, φ = atan2(R13, −R23),
    ψ = atan2(R31, R32) (in degrees, φ and ψ in (−180°, 180°]); and which other triple is the same attitude."""
    yaw, pitch, roll = _radians(given["yaw_deg"], given["pitch_deg"], given["roll_deg"])
    R = matrix_from_angles(np.array([yaw, pitch, roll]), "3-2-1")
    nutation = math.degrees(math.acos(float(np.clip(R[2, 2], -1.0, 1.0))))
    precession = math.degrees(math.atan2(R[0, 2], -R[1, 2]))
    spin = math.degrees(math.atan2(R[2, 0], R[2, 1]))
    if nutation < 10.0 or not (5.0 < abs(precession) < 175.0 and 5.0 < abs(spin) < 175.0):
        raise ValueError("keep away from 3-1-3 gimbal lock, from zero angles and from the ±180° seam")
    return {
        "nutation": PartAnswer(
            nutation,
            rf"\cos\theta = R_{{33}} = \cos\theta_2\cos\theta_3 = {R[2, 2]:.4g},\ \theta = {nutation:.4g}^\circ",
            {
                "radian-number": math.radians(nutation),
                "tilts-added": abs(given["pitch_deg"]) + abs(given["roll_deg"]),
            },
        ),
        "precession": PartAnswer(
            precession,
            rf"\phi = \operatorname{{atan2}}(R_{{13}}, -R_{{23}}) = \operatorname{{atan2}}({R[0, 2]:.4g},"
            rf" {-R[1, 2]:.4g}) = {precession:.4g}^\circ",
            {"spin-formula": spin, "yaw-is-precession": given["yaw_deg"]},
        ),
        "spin": PartAnswer(
            spin,
            rf"\psi = \operatorname{{atan2}}(R_{{31}}, R_{{32}}) = \operatorname{{atan2}}({R[2, 0]:.4g},"
            rf" {R[2, 1]:.4g}) = {spin:.4g}^\circ",
            {"precession-formula": precession},
        ),
        "twin": PartAnswer(
            "flip",
            r"[R_3(\phi + \pi)][R_1(-\theta)][R_3(\psi + \pi)] = [R_3(\phi)][R_3(\pi)R_1(-\theta)R_3(\pi)][R_3(\psi)]"
            r" = [R_3(\phi)][R_1(\theta)][R_3(\psi)]",
            {"negate-middle": "negate"},
        ),
    }


# -- 3.3 time derivatives ----------------------------------------------------------------------------------------


def _vector_motion(given: Mapping[str, float]) -> VectorMotion:
    return VectorMotion.from_params(
        {
            "frame_rate_rad_s": given["frame_rate_rad_s"],
            "frame_axis_tilt_deg": given["tilt_deg"],
            "length_m": given["length_m"],
            "stretch_amplitude_m": given["stretch_m"],
            "stretch_frequency_hz": given["stretch_hz"],
            "relative_turn_rate_rad_s": given["turn_rate_rad_s"],
            "elevation_deg": given["elevation_deg"],
        }
    )


def stretching_vector_rates(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The vector-derivative scene's A at the instant t, on the turning frame's own axes xyz: the rate the rider
    sees, ω × A, and the magnitude of the fixed observer's rate (the sum)."""
    motion = _vector_motion(given)
    t = given["time_s"]
    rates = motion.rates(np.array([t]))
    R = motion.attitude(np.array([t]))[0]
    on_frame = {name: R.T @ value[0] for name, value in rates.terms_m_s.items()}  # xyz components
    vector = rates.vector_frame_m[0]
    relative, transport, fixed = on_frame["relative"], on_frame["transport"], on_frame["fixed"]
    w = 2 * math.pi * given["stretch_hz"]
    length = given["length_m"] + given["stretch_m"] * math.sin(w * t)
    length_rate = given["stretch_m"] * w * math.cos(w * t)
    direction = vector / length
    omega_vec = motion.omega_world_rad_s  # the same on xyz: the frame turns about this fixed line
    return {
        "relative": PartAnswer(
            _vec(relative),
            rf"L = {length:.4g}\ \mathrm{{m}},\ \dot L = {length_rate:.4g}\ \mathrm{{m/s}},\ "
            r"\left(\tfrac{d\bar A}{dt}\right)_{\text{rel}} = \dot L\,\bar u + L\dot\psi\cos e\,"
            rf"(-\sin\psi, \cos\psi, 0) = {_tex(relative)}\ \mathrm{{m/s}}",
            {
                "no-stretch": _vec(relative - length_rate * direction),
                "no-turn": _vec(length_rate * direction),
            },
        ),
        "transport": PartAnswer(
            _vec(transport),
            rf"\bar\omega = {_tex(omega_vec)}\ \mathrm{{rad/s}},\ \bar A = {_tex(vector)}\ \mathrm{{m}},\ "
            rf"\bar\omega\times\bar A = {_tex(transport)}\ \mathrm{{m/s}}",
            {"cross-order": _vec(-transport)},
        ),
        "fixed": PartAnswer(
            float(np.linalg.norm(fixed)),
            rf"\left|\left(\tfrac{{d\bar A}}{{dt}}\right)_{{\text{{rel}}}} + \bar\omega\times\bar A\right|"
            rf" = |{_tex(fixed)}| = {np.linalg.norm(fixed):.4g}\ \mathrm{{m/s}}",
            {
                "rel-only": float(np.linalg.norm(relative)),
                "magnitudes-added": float(np.linalg.norm(relative) + np.linalg.norm(transport)),
            },
        ),
    }


def telescope_on_turntable(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A tube at elevation θ (rising at θ̇) on a turntable turning at Ω about the vertical: the rate of the tube's
    unit vector u = (cos θ, 0, sin θ) on the turntable's axes, the speed of its far end, and |du/dt| in symbols."""
    spin, rise, elevation, length = (
        given["table_rate_rad_s"],
        given["rise_rate_rad_s"],
        math.radians(given["elevation_deg"]),
        given["tube_m"],
    )
    c, s = math.cos(elevation), math.sin(elevation)
    relative = np.array([-rise * s, 0.0, rise * c])
    transport = np.array([0.0, spin * c, 0.0])
    fixed = relative + transport
    rate = float(np.linalg.norm(fixed))
    magnitude = sympy.sqrt(thetad**2 + Omega**2 * sympy.cos(theta) ** 2)
    return {
        "rate": PartAnswer(
            _vec(fixed),
            r"\dot{\bar u} = \dot\theta(-\sin\theta, 0, \cos\theta) + \Omega\bar k\times\bar u"
            rf" = {_tex(relative)} + {_tex(transport)} = {_tex(fixed)}\ \mathrm{{1/s}}",
            {"no-transport": _vec(relative), "no-relative": _vec(transport)},
        ),
        "speed": PartAnswer(
            length * rate,
            rf"v = \ell\,|\dot{{\bar u}}| = {length:.4g} \times {rate:.4g} = {length * rate:.4g}\ \mathrm{{m/s}}",
            {"magnitudes-added": length * (abs(rise) + abs(spin) * c)},
        ),
        "magnitude": PartAnswer(
            magnitude,
            r"|\dot{\bar u}| = \sqrt{\dot\theta^2 + \Omega^2\cos^2\theta}",
            {
                "sin-cos": sympy.sqrt(thetad**2 + Omega**2 * sympy.sin(theta) ** 2),
                "no-transport": thetad,
            },
        ),
    }


def vector_fixed_in_frame(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A boom of length L fixed in a body spinning at Ω, at the elevation e above the plane square to the spin axis
    (so γ = 90° − e from it): |dA/dt| = Ω L sin γ in symbols, its value, and its direction (across ω and the boom)."""
    spin, length, elevation = given["spin_rate_rad_s"], given["boom_m"], math.radians(given["elevation_deg"])
    angle = math.pi / 2 - elevation
    speed = spin * length * math.sin(angle)
    return {
        "formula": PartAnswer(
            Omega * L * sympy.sin(gamma),
            r"\left|\tfrac{d\bar A}{dt}\right| = |\bar\omega\times\bar A| = \Omega L\sin\gamma",
            {"cos-angle": Omega * L * sympy.cos(gamma), "fixed-means-zero": sympy.Integer(0)},
        ),
        "speed": PartAnswer(
            speed,
            rf"\Omega L\sin\gamma = \Omega L\cos e = {spin:.4g} \times {length:.4g} \times \cos"
            rf" {given['elevation_deg']:.4g}^\circ = {speed:.4g}\ \mathrm{{m/s}}",
            {"no-sin": spin * length, "cos-angle": spin * length * abs(math.cos(angle))},
        ),
        "direction": PartAnswer(
            "across",
            r"\bar\omega\times\bar A \perp \bar\omega,\ \bar\omega\times\bar A \perp \bar A",
            {"toward-axis": "toward-axis", "along-boom": "along-boom"},
        ),
    }


# -- 3.4 angular velocity and acceleration -----------------------------------------------------------------------


def nutating_top_omega(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """3-1-3 angles and rates: ω on the body axes, |ω|, and ω's component on fixed Z."""
    angles = _radians(given["precession_deg"], given["nutation_deg"], given["spin_deg"])
    rates = np.array([given["precession_rate_rad_s"], given["nutation_rate_rad_s"], given["spin_rate_rad_s"]])
    body = angular_velocity_body(angles, rates, "3-1-3")
    world = angular_velocity_world(angles, rates, "3-1-3")
    if abs(world[2]) < 0.05 or abs(body[2]) < 0.05:
        raise ValueError("keep the Z components clear of zero")
    spin_only = body.copy()
    spin_only[2] = rates[2]
    return {
        "body": PartAnswer(
            _vec(body),
            r"\omega_x = \dot\phi\sin\theta\sin\psi + \dot\theta\cos\psi,\ "
            r"\omega_y = \dot\phi\sin\theta\cos\psi - \dot\theta\sin\psi,\ \omega_z = \dot\phi\cos\theta + \dot\psi"
            rf":\ {_tex(body)}\ \mathrm{{rad/s}}",
            {"rates-as-components": _vec(rates), "spin-only-z": _vec(spin_only)},
        ),
        "size": PartAnswer(
            float(np.linalg.norm(body)),
            rf"|\bar\omega| = \sqrt{{\omega_x^2 + \omega_y^2 + \omega_z^2}} = {np.linalg.norm(body):.4g}\ "
            r"\mathrm{rad/s}",
            {"rates-perpendicular": float(np.linalg.norm(rates))},
        ),
        "vertical": PartAnswer(
            float(world[2]),
            r"\omega_Z = \bar\omega\cdot\bar K = \dot\phi + \dot\psi\cos\theta" rf" = {world[2]:.4g}\ \mathrm{{rad/s}}",
            {"body-z": float(body[2])},
        ),
    }


def gyro_rates_to_angle_rates(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """3-2-1 (yaw θ1, pitch θ2, roll θ3): body rates (p, q, r) from gyros back to the yaw and roll rates,
    ``θ̇1 = (q sin θ3 + r cos θ3)/cos θ2``, ``θ̇3 = p + θ̇1 sin θ2``; and where that fails (θ2 = ±90°)."""
    pitch, roll = math.radians(given["pitch_deg"]), math.radians(given["roll_deg"])
    p, q, rr = given["p_rad_s"], given["q_rad_s"], given["r_rad_s"]
    J = angle_rate_matrix_body(np.array([0.0, pitch, roll]), "3-2-1")
    rates = np.linalg.solve(J, np.array([p, q, rr]))
    yaw_rate, roll_rate = float(rates[0]), float(rates[2])
    if min(abs(yaw_rate), abs(roll_rate)) < 0.05:
        raise ValueError("keep the rates clear of zero")
    numerator = q * math.sin(roll) + rr * math.cos(roll)
    return {
        "yaw-rate": PartAnswer(
            yaw_rate,
            r"q\sin\theta_3 + r\cos\theta_3 = \dot\theta_1\cos\theta_2\ \Rightarrow\ "
            rf"\dot\theta_1 = {numerator:.4g} / {math.cos(pitch):.4g} = {yaw_rate:.4g}\ \mathrm{{rad/s}}",
            {"gyro-is-rate": rr, "no-cos": numerator},
        ),
        "roll-rate": PartAnswer(
            roll_rate,
            rf"\dot\theta_3 = p + \dot\theta_1\sin\theta_2 = {roll_rate:.4g}\ \mathrm{{rad/s}}",
            {"gyro-is-rate": p, "sign": p - yaw_rate * math.sin(pitch)},
        ),
        "lock": PartAnswer(
            "p90",
            r"\det[J] \propto \cos\theta_2 = 0\ \text{at}\ \theta_2 = \pm 90^\circ",
            {"proper-lock": "p0"},
        ),
    }


def precessing_disk_alpha(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A disk spinning steadily at ψ̇ about its axis, tilted θ from Z and precessing steadily at φ̇: |α| in symbols,
    α on XYZ at precession angle φ (ψ̇φ̇ K × k, along the line of nodes) and |ω|."""
    phi, tilt = math.radians(given["precession_deg"]), math.radians(given["tilt_deg"])
    precession, spin = given["precession_rate_rad_s"], given["spin_rate_rad_s"]
    angles = np.array([phi, tilt, 0.0])
    rates = np.array([precession, 0.0, spin])
    alpha_world = angular_acceleration_world(angles, rates, np.zeros(3), "3-1-3")
    omega_world = angular_velocity_world(angles, rates, "3-1-3")
    size = float(np.linalg.norm(omega_world))
    return {
        "formula": PartAnswer(
            phid * psid * sympy.sin(theta),
            r"\bar\alpha = \dot\phi\,\bar K\times\dot\psi\,\bar k,\ |\bar\alpha| = \dot\phi\dot\psi\sin\theta",
            {"cos-angle": phid * psid * sympy.cos(theta)},
        ),
        "alpha": PartAnswer(
            _vec(alpha_world),
            r"\bar\alpha = \dot\phi\dot\psi\,\bar K\times\bar k = \dot\phi\dot\psi\sin\theta\,(\cos\phi, \sin\phi, 0)"
            rf" = {_tex(alpha_world)}\ \mathrm{{rad/s^2}}",
            {"cross-order": _vec(-alpha_world), "steady-means-zero": (0.0, 0.0, 0.0)},
        ),
        "omega": PartAnswer(
            size,
            rf"|\dot\phi\bar K + \dot\psi\bar k| = \sqrt{{\dot\phi^2 + \dot\psi^2 + 2\dot\phi\dot\psi\cos\theta}}"
            rf" = {size:.4g}\ \mathrm{{rad/s}}",
            {"rates-perpendicular": math.hypot(precession, spin)},
        ),
    }


# -- 3.5 velocity and acceleration with a moving reference frame -------------------------------------------------


def _table(given: Mapping[str, float], **fixed: float) -> MovingFrameMotion:
    params = {
        "spin_rate_rad_s": given["spin_rate_rad_s"],
        "spin_acceleration_rad_s2": given["spin_accel_rad_s2"],
        "tilt_deg": 0.0,
        "precession_rate_rad_s": 0.0,
        "groove_offset_m": given["offset_m"],
        "slider_amplitude_m": 0.0,
        "slider_frequency_hz": 0.0,
        "cart_amplitude_m": 0.0,
        "cart_frequency_hz": 0.0,
    }
    params.update({k: v for k, v in given.items() if k in params})
    params.update(fixed)
    return MovingFrameMotion.from_params(params)


def slider_in_offset_groove(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The moving-frame scene with a level table spinning up and the slider oscillating in a groove at y = d:
    v_P and a_P at the instant t, on the table's axes xyz."""
    motion = _table(given)
    t = given["time_s"]
    k = motion.kinematics(np.array([t]))
    R = motion.attitude(np.array([t]))[0]
    velocity = R.T @ k.velocity_m_s[0]
    terms = {name: R.T @ value[0] for name, value in k.terms_m_s2.items()}
    total = terms["total"]
    spin_now = given["spin_rate_rad_s"] + given["spin_accel_rad_s2"] * t
    r_body, v_rel, _ = motion.relative_body(np.array([t]))
    slow = v_rel[0] + np.cross([0.0, 0.0, given["spin_rate_rad_s"]], r_body[0])
    return {
        "velocity": PartAnswer(
            _vec(velocity),
            rf"\omega = \omega_0 + \alpha_0 t = {spin_now:.4g}\ \mathrm{{rad/s}},\ \bar r = {_tex(r_body[0])}\ "
            rf"\mathrm{{m}},\ \bar v_P = \omega\bar k\times\bar r + \bar v_{{\text{{rel}}}} = {_tex(velocity)}\ "
            r"\mathrm{m/s}",
            {"no-transport": _vec(v_rel[0]), "initial-rate": _vec(slow)},
        ),
        "acceleration": PartAnswer(
            _vec(total),
            r"\bar a_P = \bar\alpha\times\bar r + \bar\omega\times(\bar\omega\times\bar r) + 2\bar\omega\times"
            rf"\bar v_{{\text{{rel}}}} + \bar a_{{\text{{rel}}}} = {_tex(terms['angular'])} + "
            rf"{_tex(terms['centripetal'])} + {_tex(terms['coriolis'])} + {_tex(terms['relative'])} = "
            rf"{_tex(total)}\ \mathrm{{m/s^2}}",
            {
                "no-coriolis": _vec(total - terms["coriolis"]),
                "half-coriolis": _vec(total - terms["coriolis"] / 2),
                "no-angular": _vec(total - terms["angular"]),
            },
        ),
    }


def tilted_precessing_table(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """The moving-frame scene at t = 0 with the table tilted β about X, precessing at Ω_p about Z and spinning (and
    spinning up) about its axis k = (0, −sin β, cos β); a point P fixed at (0, d, 0) on the table: ω, α, |a_P|."""
    motion = _table(given, tilt_deg=given["tilt_deg"], precession_rate_rad_s=given["precession_rate_rad_s"])
    k = motion.kinematics(np.array([0.0]))
    omega_vec, alpha_vec = k.omega_rad_s[0], k.alpha_rad_s2[0]
    total = k.terms_m_s2["total"][0]
    axis = motion.spin_axis_world(np.array([0.0]))[0]
    spin_up = given["spin_accel_rad_s2"] * axis
    r_vec = k.position_m[0] - k.origin_m[0]
    fixed_axis = np.cross(spin_up, r_vec) + np.cross(omega_vec, np.cross(omega_vec, r_vec))
    return {
        "omega": PartAnswer(
            _vec(omega_vec),
            r"\bar k = (0, -\sin\beta, \cos\beta),\ \bar\omega = \Omega_p\bar K + \dot\theta\,\bar k"
            rf" = {_tex(omega_vec)}\ \mathrm{{rad/s}}",
            {
                "spin-only": _vec(given["spin_rate_rad_s"] * axis),
                "no-tilt": (0.0, 0.0, given["spin_rate_rad_s"] + given["precession_rate_rad_s"]),
            },
        ),
        "alpha": PartAnswer(
            _vec(alpha_vec),
            r"\bar\alpha = \ddot\theta\,\bar k + \dot\theta\,\Omega_p\,\bar K\times\bar k"
            rf" = {_tex(alpha_vec)}"
            r"\ \mathrm{rad/s^2}",
            {"axis-fixed": _vec(spin_up), "cross-order": _vec(spin_up - (alpha_vec - spin_up))},
        ),
        "accel": PartAnswer(
            float(np.linalg.norm(total)),
            rf"\bar r = (0, d\cos\beta, d\sin\beta) = {_tex(r_vec)}\ \mathrm{{m}},\ "
            rf"\bar a_P = \bar\alpha\times\bar r + \bar\omega\times(\bar\omega\times\bar r) = {_tex(total)},\ "
            rf"|\bar a_P| = {np.linalg.norm(total):.4g}\ \mathrm{{m/s^2}}",
            {"axis-fixed": float(np.linalg.norm(fixed_axis))},
        ),
    }


def collar_on_spinning_arm(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A collar sliding out along a horizontal arm that turns (and spins up) about a vertical axis: its
    acceleration across the arm, αr + 2ωu, the side force m(αr + 2ωu) and which face of the arm pushes."""
    m, spin, spin_up, radius, speed = (
        given["mass_kg"],
        given["arm_rate_rad_s"],
        given["arm_accel_rad_s2"],
        given["radius_m"],
        given["slide_speed_m_s"],
    )
    across = spin_up * radius + 2 * spin * speed
    force = m * across
    return {
        "transverse": PartAnswer(
            alpha * r + 2 * omega * u,
            r"\bar a_P\cdot\bar e_\theta = (\bar\alpha\times\bar r + 2\bar\omega\times\bar v_{\text{rel}})"
            r"\cdot\bar e_\theta = \alpha r + 2\omega u",
            {"no-coriolis": alpha * r, "half-coriolis": alpha * r + omega * u},
        ),
        "force": PartAnswer(
            force,
            rf"N = m(\alpha r + 2\omega u) = {m:.4g}\,({spin_up:.4g}\times{radius:.4g} + 2\times{spin:.4g}"
            rf"\times{speed:.4g}) = {force:.4g}\ \mathrm{{N}}",
            {"no-coriolis": m * spin_up * radius, "half-coriolis": m * (spin_up * radius + spin * speed)},
        ),
        "face": PartAnswer(
            "trailing",
            r"\alpha r + 2\omega u > 0:\ \text{the push is forward, in the sense of the arm's turning}",
            {"none": "none", "leading": "leading"},
        ),
    }


# -- 3.2 displacement: Euler's theorem and finite rotations ------------------------------------------------------

#: Symbols of the 3.2 and 3.6 expression parts (real, as the checker's are).
d_s, phi_s, a_s, b_s, g_s, t_s, lam_s = sympy.symbols("d phi a b g t lam", real=True)


def _skew(n: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -n[2], n[1]], [n[2], 0.0, -n[0]], [-n[1], n[0], 0.0]])


def rodrigues_lid(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A lid turned by φ about the fixed hinge line through O along n = (sin δ, 0, cos δ): where the point
    P = (x, y, 0) goes (Rodrigues), the chord 2 d sin(φ/2) in symbols (d: P's distance from the hinge line), and
    its value."""
    delta, angle = math.radians(given["hinge_tilt_deg"]), math.radians(given["turn_deg"])
    n = np.array([math.sin(delta), 0.0, math.cos(delta)])
    p = np.array([given["x_m"], given["y_m"], 0.0])
    R = matrix_from_axis_angle(n, angle)
    image = R @ p
    along = float(n @ p)
    d = float(np.linalg.norm(p - along * n))
    chord = float(np.linalg.norm(image - p))
    first_order = p + math.sin(angle) * _skew(n) @ p
    return {
        "image": PartAnswer(
            _vec(image),
            r"[R] = [I] + \sin\phi\,[\tilde n] + (1 - \cos\phi)[\tilde n]^2,\ "
            rf"\bar n = {_tex(n)},\ \{{r_P'\}} = [R]\{{r_P\}} = {_tex(image)}\ \mathrm{{m}}",
            {
                "sin-sign": _vec(matrix_from_axis_angle(n, -angle) @ p),
                "no-second-order": _vec(first_order),
            },
        ),
        "chord": PartAnswer(
            2 * d_s * sympy.sin(phi_s / 2),
            r"|\bar r_P' - \bar r_P| = 2d\sin\frac{\phi}{2}\ \text{(a chord of the circle of radius } d)",
            {"arc": d_s * phi_s, "sin-whole": d_s * sympy.sin(phi_s)},
        ),
        "distance": PartAnswer(
            chord,
            rf"\bar r_P\cdot\bar n = {along:.4g}\ \mathrm{{m}},\ d = \sqrt{{|\bar r_P|^2 - (\bar r_P\cdot\bar n)^2}}"
            rf" = {d:.4g}\ \mathrm{{m}},\ 2d\sin\frac{{\phi}}{{2}} = {chord:.4g}\ \mathrm{{m}}",
            {"radius-from-o": 2 * float(np.linalg.norm(p)) * math.sin(angle / 2), "arc": d * angle},
        ),
    }


def two_turns_order(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A = a about fixed X, B = b about fixed Y. 'A then B' is [R_Y(b)][R_X(a)]: cos φ = (cos a + cos b +
    cos a cos b − 1)/2 in symbols, φ, its axis, and the angle between the two orders' results. Uses the
    finite-rotation scene's model."""
    a, b = math.radians(given["a_deg"]), math.radians(given["b_deg"])
    model = finite_rotation(np.array([a, 0.0, 0.0]), "1-2-3", second_axis="Y", second_angle_rad=b)
    turn, other = model.a_then_b, model.b_then_a
    angle = math.degrees(turn.angle_rad)
    gap = math.degrees(model.order_gap_rad)
    trace = float(np.trace(turn.R_world_body))
    return {
        "cos-angle": PartAnswer(
            (sympy.cos(a_s) + sympy.cos(b_s) + sympy.cos(a_s) * sympy.cos(b_s) - 1) / 2,
            r"\operatorname{tr}([R_Y(b)][R_X(a)]) = \cos b + \cos a + \cos a\cos b = 1 + 2\cos\phi",
            {
                "angles-added": sympy.cos(a_s + b_s),
                "trace-no-one": (sympy.cos(a_s) + sympy.cos(b_s) + sympy.cos(a_s) * sympy.cos(b_s)) / 2,
            },
        ),
        "angle": PartAnswer(
            angle,
            rf"\operatorname{{tr}}[R] = {trace:.4g} = 1 + 2\cos\phi,\ \phi = {angle:.4g}^\circ",
            {"angles-added": given["a_deg"] + given["b_deg"], "radian-number": math.radians(angle)},
        ),
        "axis": PartAnswer(
            _vec(turn.axis_world),
            r"\{n\} = \frac{(R_{32} - R_{23},\ R_{13} - R_{31},\ R_{21} - R_{12})}{2\sin\phi}"
            rf" = {_tex(turn.axis_world)}",
            {"order-swapped": _vec(other.axis_world), "opposite": _vec(-turn.axis_world)},
        ),
        "gap": PartAnswer(
            gap,
            r"[R_{AB}][R_{BA}]^{\mathsf T}\ \text{is one turn, by}\ "
            rf"{gap:.4g}^\circ\ (\text{{both orders turn by }} {angle:.4g}^\circ\text{{, about different axes}})",
            {"commute": 0.0},
        ),
    }


#: The choice ids of a small gap turn's axis, by (axis index, sign).
GAP_AXES = {(0, 1): "x", (0, -1): "minus-x", (1, 1): "y", (1, -1): "minus-y", (2, 1): "z", (2, -1): "minus-z"}


def small_turns_commute(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A = a about fixed Y, B = b about fixed Z, both small: the exact angle of the turn between the two orders'
    results, the leading-order a·b in symbols, which axis that turn is about, and the gap with both angles doubled.
    Uses the finite-rotation scene's model."""
    a_deg, b_deg = given["a_deg"], given["b_deg"]

    def model(scale: float):
        return finite_rotation(
            np.radians([scale * a_deg, 0.0, 0.0]),
            "2-1-3",
            second_axis="Z",
            second_angle_rad=math.radians(scale * b_deg),
        )

    turns, doubled = model(1.0), model(2.0)
    gap = math.degrees(turns.order_gap_rad)
    gap_matrix = turns.a_then_b.R_world_body @ turns.b_then_a.R_world_body.T
    axis, _ = axis_angle_from_matrix(gap_matrix)
    index = int(np.argmax(np.abs(axis)))
    if abs(axis[index]) < 0.99:
        raise ValueError("the gap turn is not about a fixed axis")
    choice = GAP_AXES[(index, 1 if axis[index] > 0 else -1)]
    estimate = math.degrees(math.radians(a_deg) * math.radians(b_deg))
    gap2 = math.degrees(doubled.order_gap_rad)
    return {
        "gap": PartAnswer(
            gap,
            r"[R_{AB}] = [R_Z(b)][R_Y(a)],\ [R_{BA}] = [R_Y(a)][R_Z(b)],\ "
            rf"\operatorname{{tr}}([R_{{AB}}][R_{{BA}}]^{{\mathsf T}}) = 1 + 2\cos\gamma,\ \gamma = {gap:.4g}^\circ"
            rf"\ (a b = {estimate:.4g}^\circ)",
            {"commute": 0.0, "degree-product": a_deg * b_deg},
        ),
        "estimate": PartAnswer(
            a_s * b_s,
            r"[R_Z(b)][R_Y(a)] - [R_Y(a)][R_Z(b)] \approx a b\,([\tilde K][\tilde J] - [\tilde J][\tilde K])"
            r" = -a b\,[\tilde I]:\ \gamma \approx a b",
            {"sum": a_s + b_s, "half": a_s * b_s / 2},
        ),
        "gap-axis": PartAnswer(
            choice,
            r"[R_{AB}][R_{BA}]^{\mathsf T} \approx [I] - a b\,[\tilde I]:\ \text{a turn } a b \text{ about } -\bar I",
            {"sense": "x", "turn-axis-y": "y", "turn-axis-z": "z"},
        ),
        "doubled": PartAnswer(
            gap2,
            rf"\gamma(2a, 2b) = {gap2:.4g}^\circ \approx 4\,a b",
            {"twice": 2 * gap},
        ),
    }


# -- 3.6 observations from a moving reference frame --------------------------------------------------------------

SECONDS_PER_HOUR = 3600.0


def foucault_plane_turn(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A Foucault pendulum at latitude λ: the plane's rate relative to the floor, Ω|sin λ| (deg/h), the time of one
    full turn 2π/(Ω|sin λ|), and its sense seen from above (clockwise north of the equator)."""
    lam = math.radians(given["latitude_deg"])
    if abs(given["latitude_deg"]) < 10.0:
        raise ValueError("too near the equator: the plane hardly turns")
    omega = EARTH_RATE_RAD_S
    rate = math.degrees(omega * abs(math.sin(lam))) * SECONDS_PER_HOUR
    period = 2 * math.pi / (omega * abs(math.sin(lam)))
    sense = "clockwise" if lam > 0 else "counterclockwise"
    return {
        "rate": PartAnswer(
            rate,
            rf"\Omega_z = \Omega\sin\lambda,\ |\dot\psi| = \Omega|\sin\lambda| = {omega:.6g} \times "
            rf"{abs(math.sin(lam)):.4g}\ \mathrm{{rad/s}} = {rate:.4g}\ \mathrm{{deg/h}}",
            {
                "cos-lat": math.degrees(omega * math.cos(lam)) * SECONDS_PER_HOUR,
                "full-rate": math.degrees(omega) * SECONDS_PER_HOUR,
            },
        ),
        "period": PartAnswer(
            period,
            rf"T = \frac{{2\pi}}{{\Omega|\sin\lambda|}} = {period:.5g}\ \mathrm{{s}} = "
            rf"{period / SECONDS_PER_HOUR:.4g}\ \mathrm{{h}}",
            {"one-day": 2 * math.pi / omega, "cos-lat": 2 * math.pi / (omega * math.cos(lam))},
        ),
        "sense": PartAnswer(
            sense,
            r"\dot\psi = -\Omega\sin\lambda:\ "
            + (r"\text{clockwise (north)}" if lam > 0 else r"\text{counterclockwise (south)}"),
            {
                "reversed": "counterclockwise" if lam > 0 else "clockwise",
                "none": "none",
            },
        ),
    }


def stone_dropped_east(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A stone dropped from rest from height h at latitude λ: the fall time √(2h/g), the first-order eastward
    deflection ⅓ Ω g t³ cos λ in symbols and its value, and its direction."""
    h, lam, g = given["height_m"], math.radians(given["latitude_deg"]), given["g_m_s2"]
    omega = EARTH_RATE_RAD_S
    t = math.sqrt(2 * h / g)
    east = omega * g * t**3 * math.cos(lam) / 3
    return {
        "fall-time": PartAnswer(
            t,
            rf"t = \sqrt{{2h/g}} = {t:.4g}\ \mathrm{{s}}",
            {"missing-two": math.sqrt(h / g)},
        ),
        "formula": PartAnswer(
            sympy.Rational(1, 3) * Omega * g_s * t_s**3 * sympy.cos(lam_s),
            r"-2\bar\Omega\times(-g t\,\bar k) = 2 g t\,\Omega\cos\lambda\,\bar i,\ "
            r"x = \int_0^t\!\!\int_0^{t'} 2 g \tau\,\Omega\cos\lambda\,d\tau\,dt' = \tfrac13\Omega g t^3\cos\lambda",
            {
                "sin-lat": sympy.Rational(1, 3) * Omega * g_s * t_s**3 * sympy.sin(lam_s),
                "constant-coriolis": Omega * g_s * t_s**3 * sympy.cos(lam_s),
            },
        ),
        "deflection": PartAnswer(
            east,
            rf"x = \tfrac13 \Omega g t^3\cos\lambda = {east * 1000:.4g}\ \mathrm{{mm}}",
            {
                "sin-lat": omega * g * t**3 * math.sin(lam) / 3,
                "constant-coriolis": 3 * east,
            },
        ),
        "direction": PartAnswer(
            "east",
            r"x > 0\ \text{for}\ \cos\lambda > 0:\ \text{east in both hemispheres}",
            {"west": "west", "equator": "equator"},
        ),
    }


def puck_on_turntable(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A frictionless puck moving straight at a constant velocity (u_x, u_y) (ground frame) over a turntable that
    turns counterclockwise at Ω; at the instant it is at (d, 0, 0) and the table's axes xyz coincide with XYZ.
    What a rider measures: v_rel = v − Ω×r, a_rel = −Ω×(Ω×r) − 2Ω×v_rel, and which way the path bends."""
    spin, d, ux, uy = given["table_rate_rad_s"], given["distance_m"], given["u_x_m_s"], given["u_y_m_s"]
    omega_vec = np.array([0.0, 0.0, spin])
    r = np.array([d, 0.0, 0.0])
    v = np.array([ux, uy, 0.0])
    v_rel = v - np.cross(omega_vec, r)
    centrifugal = -np.cross(omega_vec, np.cross(omega_vec, r))
    coriolis = -2 * np.cross(omega_vec, v_rel)
    a_rel = centrifugal + coriolis
    speed, size = float(np.linalg.norm(v_rel)), float(np.linalg.norm(a_rel))
    if speed < 0.1 or size < 0.1 * spin**2 * d:
        raise ValueError("keep the puck moving on the table and its relative acceleration clear of zero")
    turning = float(np.cross(v_rel, a_rel)[2]) / (speed * size)
    if abs(turning) < 0.1:
        raise ValueError("the relative path hardly bends here")
    bend = "left" if turning > 0 else "right"
    return {
        "v-rel": PartAnswer(
            _vec(v_rel),
            rf"\bar v_{{\text{{rel}}}} = \bar v - \bar\Omega\times\bar r = {_tex(v)} - {_tex(np.cross(omega_vec, r))}"
            rf" = {_tex(v_rel)}\ \mathrm{{m/s}}",
            {"transport-sign": _vec(v + np.cross(omega_vec, r)), "no-transport": _vec(v)},
        ),
        "a-rel": PartAnswer(
            _vec(a_rel),
            r"\bar a_{\text{rel}} = \bar a - \bar\Omega\times(\bar\Omega\times\bar r) - 2\bar\Omega\times"
            rf"\bar v_{{\text{{rel}}}} = \bar 0 + {_tex(centrifugal)} + {_tex(coriolis)} = {_tex(a_rel)}\ "
            r"\mathrm{m/s^2}",
            {
                "no-coriolis": _vec(centrifugal),
                "ground-velocity": _vec(centrifugal - 2 * np.cross(omega_vec, v)),
                "straight-means-zero": (0.0, 0.0, 0.0),
            },
        ),
        "bend": PartAnswer(
            bend,
            rf"(\bar v_{{\text{{rel}}}}\times\bar a_{{\text{{rel}}}})\cdot\bar k = "
            rf"{float(np.cross(v_rel, a_rel)[2]):.4g}\ \mathrm{{m^2/s^3}}"
            + (r" > 0:\ \text{left}" if bend == "left" else r" < 0:\ \text{right}"),
            {"opposite": "right" if bend == "left" else "left", "straight": "straight"},
        ),
    }


def train_coriolis_rails(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A train at speed v on a straight, level track heading ψ (compass bearing, clockwise from north) at latitude λ:
    the Coriolis term −2Ω × v on the ground's (east, north, up) axes, the side force the rails give, 2 m Ω v |sin λ|
    whatever the heading, which rail gives it, and the change in the vertical load, −2 m Ω v cos λ sin ψ."""
    mass, v = given["mass_kg"], given["speed_m_s"]
    psi, lam = math.radians(given["heading_deg"]), math.radians(given["latitude_deg"])
    if abs(given["latitude_deg"]) < 10.0 or abs(math.sin(psi)) < 0.2:
        raise ValueError(
            "keep away from the equator and from a heading so near north-south that the load hardly changes"
        )
    omega_vec = EARTH_RATE_RAD_S * np.array([0.0, math.cos(lam), math.sin(lam)])
    velocity = v * np.array([math.sin(psi), math.cos(psi), 0.0])
    coriolis = -2 * np.cross(omega_vec, velocity)
    side = mass * math.hypot(coriolis[0], coriolis[1])
    load = -mass * float(coriolis[2])
    vertical_only = -2 * np.cross(np.array([0.0, 0.0, omega_vec[2]]), velocity)
    rail = "right" if lam > 0 else "left"
    return {
        "coriolis": PartAnswer(
            _vec(coriolis),
            rf"\bar\Omega = \Omega(0,\ \cos\lambda,\ \sin\lambda),\ \bar v = v(\sin\psi,\ \cos\psi,\ 0),\ "
            r"-2\bar\Omega\times\bar v = 2\Omega v(\sin\lambda\cos\psi,\ -\sin\lambda\sin\psi,\ \cos\lambda\sin\psi)"
            rf" = {_tex(coriolis)}\ \mathrm{{m/s^2}}",
            {"sign": _vec(-coriolis), "vertical-omega-only": _vec(vertical_only)},
        ),
        "side-force": PartAnswer(
            side,
            rf"F = 2 m\Omega v|\sin\lambda| = {side:.4g}\ \mathrm{{N}}\ \text{{(for any heading)}}",
            {
                "cos-lat": 2 * mass * EARTH_RATE_RAD_S * v * abs(math.cos(lam)),
                "no-two": side / 2,
            },
        ),
        "rail": PartAnswer(
            rail,
            r"-2\bar\Omega\times\bar v\ \text{points to the "
            + ("right" if lam > 0 else "left")
            + r" of }\bar v\text{; that rail pushes back}",
            {"opposite": "left" if lam > 0 else "right", "neither": "neither"},
        ),
        "load": PartAnswer(
            load,
            rf"\Delta N = -m\,(-2\bar\Omega\times\bar v)\cdot\bar k = -2 m\Omega v\cos\lambda\sin\psi = {load:.4g}\ "
            r"\mathrm{N}",
            {"sign": -load},
        ),
    }
