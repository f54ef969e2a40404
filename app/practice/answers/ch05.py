"""Answers of chapter 5's exercises: inertia properties and angular momentum."""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import sympy

from app.physics.bodies import inertia
from app.practice.exercise import PartAnswer


def plate_about_corner(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A thin rectangular plate, sides a along x and b along y, axes xyz at corner O with the plate in the first
    quadrant of the xy plane: I_xx, I_xy (products with the minus sign, I = Σ m(ρ²1 − ρρᵀ)) and I_zz about O."""
    m, a, b = given["mass_kg"], given["length_m"], given["width_m"]
    centroidal = inertia.thin_plate(m, a, b)
    offset = np.array([a / 2, b / 2, 0.0])
    about_corner = inertia.parallel_axis(centroidal, m, offset)
    ixx, ixy, izz = float(about_corner[0, 0]), float(about_corner[0, 1]), float(about_corner[2, 2])
    return {
        "ixx": PartAnswer(
            ixx,
            r"I_{xx} = \tfrac{1}{12} m b^2 + m \left(\tfrac{b}{2}\right)^2 = \tfrac13 m b^2"
            rf" = {ixx:.4g}\ \mathrm{{kg\,m^2}}",
            {"no-parallel-axis": float(centroidal[0, 0]), "wrong-side": m * a**2 / 3},
        ),
        "ixy": PartAnswer(
            ixy,
            rf"I_{{xy}} = -m\,x_G\,y_G = -m \tfrac{{a}}{{2}} \tfrac{{b}}{{2}} = {ixy:.4g}\ \mathrm{{kg\,m^2}}",
            {"product-sign": -ixy, "centroidal-product": 0.0},
        ),
        "izz": PartAnswer(
            izz,
            r"I_{zz} = \tfrac{1}{12} m (a^2 + b^2) + m \tfrac{a^2 + b^2}{4} = \tfrac13 m (a^2 + b^2)"
            rf" = {izz:.4g}\ \mathrm{{kg\,m^2}}",
            {"no-parallel-axis": float(centroidal[2, 2])},
        ),
    }


def tilted_disk_bearings(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A thin disk (m, r) on a shaft through its centre G, its axis tilted β from the shaft, spun at constant Ω;
    bearings a span L apart, G midway. |H_G|, the angle between H_G and ω, and the force on each bearing."""
    m, r, beta, omega, span = (
        given["mass_kg"],
        given["radius_m"],
        math.radians(given["tilt_deg"]),
        given["spin_rate_rad_s"],
        given["bearing_span_m"],
    )
    axial, transverse = 0.5 * m * r**2, 0.25 * m * r**2
    # ω in the disk's axes (axis z, the tilt about x): Ω (0, sin β, cos β); H_G = I ω.
    h_body = omega * np.array([0.0, transverse * math.sin(beta), axial * math.cos(beta)])
    h = float(np.linalg.norm(h_body))
    omega_body = omega * np.array([0.0, math.sin(beta), math.cos(beta)])
    cos_angle = float(np.dot(omega_body, h_body)) / (abs(omega) * h)
    angle = math.degrees(math.acos(min(1.0, cos_angle)))
    moment = omega**2 * (axial - transverse) * math.sin(beta) * math.cos(beta)
    force = abs(moment) / span
    return {
        "h": PartAnswer(
            h,
            r"\mathbf H_G = \Omega\,(0,\ I_t \sin\beta,\ I_a \cos\beta),"
            rf"\ |\mathbf H_G| = {h:.4g}\ \mathrm{{kg\,m^2/s}}",
            {
                "h-along-axis": axial * abs(omega),
                "h-along-shaft": (axial * math.cos(beta) ** 2 + transverse * math.sin(beta) ** 2) * abs(omega),
            },
        ),
        "angle": PartAnswer(
            angle,
            r"\cos\gamma = \frac{\boldsymbol\omega \cdot \mathbf H_G}{|\boldsymbol\omega|\,|\mathbf H_G|},"
            rf"\ \gamma = {angle:.4g}^\circ",
            {"radian-number": math.radians(angle)},
        ),
        "force": PartAnswer(
            force,
            r"|\dot{\mathbf H}_G| = |\boldsymbol\omega \times \mathbf H_G| = \Omega^2 (I_a - I_t) \sin\beta\cos\beta"
            rf" = {abs(moment):.4g}\ \mathrm{{N\,m}},\ F = |\dot{{\mathbf H}}_G| / L = {force:.4g}\ \mathrm{{N}}",
            {"half-span": 2 * force, "moment-not-force": abs(moment)},
        ),
    }


def _vector(values: np.ndarray) -> tuple[float, float, float]:
    return (float(values[0]), float(values[1]), float(values[2]))


def _rotation_x(angle_rad: float) -> np.ndarray:
    """A right-handed turn by ``angle_rad`` about x: its columns are the turned axes in the original components."""
    c, s = math.cos(angle_rad), math.sin(angle_rad)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def tilted_box_momentum(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A box (a along x, b along y, c along z of its own axes) on a vertical shaft Z through G, turned by the tilt β
    about its x axis (R = R_x(β)) and spun at Ω: H_G in fixed XYZ at this instant, T, and whether H_A = H_G about a
    bearing A on the shaft."""
    m, a, b, c = given["mass_kg"], given["length_m"], given["width_m"], given["height_m"]
    beta, spin = math.radians(given["tilt_deg"]), given["spin_rate_rad_s"]
    body = inertia.box(m, a, b, c)
    rotation = _rotation_x(beta)
    world = inertia.rotate_tensor(body, rotation)
    omega = np.array([0.0, 0.0, spin])
    h = world @ omega
    omega_body = rotation.T @ omega
    h_body = body @ omega_body
    energy = 0.5 * float(omega @ h)
    return {
        "h": PartAnswer(
            _vector(h),
            r"\mathbf H_G = [I_G]\,\Omega\mathbf Z = \Omega\,(-I_{XZ},\ -I_{YZ},\ I_{ZZ}),"
            r"\ -I_{YZ} = (I_{yy} - I_{zz})\sin\beta\cos\beta,\ I_{ZZ} = I_{yy}\sin^2\beta + I_{zz}\cos^2\beta;"
            rf"\ \mathbf H_G = ({h[0]:.4g},\ {h[1]:.4g},\ {h[2]:.4g})\ \mathrm{{kg\,m^2/s}}",
            {"along-shaft": (0.0, 0.0, float(h[2])), "body-components": _vector(h_body)},
        ),
        "energy": PartAnswer(
            energy,
            rf"T = \tfrac12\,\boldsymbol\omega\cdot\mathbf H_G = \tfrac12\,\Omega\,H_Z = {energy:.4g}\ \mathrm{{J}}",
            {"body-axis-moment": 0.5 * float(body[2, 2]) * spin**2, "no-half": 2 * energy},
        ),
        "bearing": PartAnswer(
            "equal",
            r"\mathbf H_A = \mathbf H_G + \mathbf r_{G/A} \times m\,\mathbf v_G = \mathbf H_G"
            r"\quad(\mathbf v_G = \mathbf 0)",
            {"parallel-axis": "larger"},
        ),
    }


def dumbbell_moving_centre(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """Two particles m₁, m₂ on a light rod of length L, spinning at ω about the vertical through their centre of mass
    G while G moves at v along +x, at (0, d, 0) from O at this instant: T as an expression, H_G and H_O (z)."""
    m1, m2 = given["mass1_kg"], given["mass2_kg"]
    length, spin = given["length_m"], given["spin_rad_s"]
    speed, offset = given["speed_m_s"], given["offset_m"]
    s_m1, s_m2, s_l, s_v, s_w = sympy.symbols("m1 m2 L v omega", real=True)
    total = m1 + m2
    moment = m1 * m2 * length**2 / total
    midpoint_moment = total * length**2 / 4
    h_g = moment * spin
    h_o = h_g - total * offset * speed
    if abs(h_o) < 0.2 * h_g:
        raise ValueError("H_O nearly cancels: a student's rounding would decide the answer")
    energy = (s_m1 + s_m2) * s_v**2 / 2 + s_m1 * s_m2 * s_l**2 * s_w**2 / (2 * (s_m1 + s_m2))
    midpoint = (s_m1 + s_m2) * s_v**2 / 2 + (s_m1 + s_m2) * s_l**2 * s_w**2 / 8
    return {
        "energy": PartAnswer(
            energy,
            r"T = \tfrac12 (m_1 + m_2) v^2 + \tfrac12 \frac{m_1 m_2}{m_1 + m_2} L^2 \omega^2"
            r"\quad(\text{the masses are } \tfrac{m_2 L}{m_1 + m_2} \text{ and } \tfrac{m_1 L}{m_1 + m_2}"
            r"\text{ from } G)",
            {"midpoint": midpoint, "no-translation": s_m1 * s_m2 * s_l**2 * s_w**2 / (2 * (s_m1 + s_m2))},
        ),
        "hg": PartAnswer(
            h_g,
            rf"H_G = \frac{{m_1 m_2}}{{m_1 + m_2}} L^2 \omega = {h_g:.4g}\ \mathrm{{kg\,m^2/s}}",
            {"midpoint": midpoint_moment * spin},
        ),
        "ho": PartAnswer(
            h_o,
            r"H_{O} = H_G + (\mathbf r_G \times m\,\mathbf v_G)_z = H_G - (m_1 + m_2)\,d\,v"
            rf" = {h_o:.4g}\ \mathrm{{kg\,m^2/s}}",
            {"no-transport": h_g, "transport-sign": h_g + total * offset * speed},
        ),
    }


def edge_mill_roller(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A thin disk (m, r) rolling upright on the floor, its centre G moving at v round a circle of radius R about the
    vertical Z through O (on the floor), counter-clockwise seen from above; at this instant G = (R, 0, r) and the
    axle lies along X. ω, H_O (about the fixed floor point O) in XYZ, and T."""
    m, r, speed, circle = given["mass_kg"], given["radius_m"], given["speed_m_s"], given["circle_m"]
    axial, transverse = 0.5 * m * r**2, 0.25 * m * r**2
    omega = np.array([-speed / r, 0.0, speed / circle])
    h_g = np.array([axial * omega[0], 0.0, transverse * omega[2]])
    centre = np.array([circle, 0.0, r])
    momentum = np.array([0.0, m * speed, 0.0])
    h_o = h_g + np.cross(centre, momentum)
    h_o_floor = h_g + np.cross(np.array([circle, 0.0, 0.0]), momentum)
    rotation = 0.5 * (axial * omega[0] ** 2 + transverse * omega[2] ** 2)
    energy = float(0.5 * m * speed**2 + rotation)
    return {
        "omega": PartAnswer(
            _vector(omega),
            r"\boldsymbol\omega = -\frac{v}{r}\,\mathbf X + \frac{v}{R}\,\mathbf Z"
            rf" = ({omega[0]:.4g},\ 0,\ {omega[2]:.4g})\ \mathrm{{rad/s}}",
            {"spin-only": (float(omega[0]), 0.0, 0.0), "spin-sign": (-float(omega[0]), 0.0, float(omega[2]))},
        ),
        "ho": PartAnswer(
            _vector(h_o),
            r"\mathbf H_G = (I_a\omega_X,\ 0,\ I_t\omega_Z),"
            r"\ \mathbf H_O = \mathbf H_G + \mathbf r_G\times m\mathbf v_G"
            r" = \left(-\tfrac32 m r v,\ 0,\ m R v + \tfrac14 m r^2 \tfrac{v}{R}\right)"
            rf" = ({h_o[0]:.4g},\ 0,\ {h_o[2]:.4g})\ \mathrm{{kg\,m^2/s}}",
            {"no-transport": _vector(h_g), "centre-on-floor": _vector(h_o_floor)},
        ),
        "energy": PartAnswer(
            energy,
            r"T = \tfrac12 m v^2 + \tfrac12\left(I_a \tfrac{v^2}{r^2} + I_t \tfrac{v^2}{R^2}\right)"
            rf" = {energy:.4g}\ \mathrm{{J}}",
            {"translation-only": 0.5 * m * speed**2, "rotation-only": rotation},
        ),
    }


def bent_bar_principal(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """An L of two uniform slender rods welded at O, a along +x and b along +y, total mass m shared in proportion to
    length: the product I_xy = ∫xy dm about G, the angle from x of the in-plane principal axis of least moment, and
    that least moment."""
    m, a, b = given["mass_kg"], given["length_a_m"], given["length_b_m"]
    m1, m2 = m * a / (a + b), m * b / (a + b)
    about_o = np.diag([m2 * b**2 / 3, m1 * a**2 / 3, m1 * a**2 / 3 + m2 * b**2 / 3])  # no product about O
    centre = np.array([m1 * a / 2, m2 * b / 2, 0.0]) / m
    about_g = inertia.centroidal_from_point(about_o, m, centre)
    product = -float(about_g[0, 1])  # the tensor holds −I_xy
    moments, axes = np.linalg.eigh(about_g[:2, :2])
    least = float(moments[0])
    angle = math.degrees(math.atan2(axes[1, 0], axes[0, 0]))
    angle = (angle + 90.0) % 180.0 - 90.0  # the axis as a line: an angle in [−90°, 90°)
    if abs(angle + 90.0) < 1e-9:
        angle = 90.0
    double = (2 * angle + 90.0) % 180.0 - 90.0  # what arctan gives for 2θ, left unhalved
    other = (angle + 180.0) % 180.0 - 90.0  # the perpendicular root: the axis of the larger in-plane moment
    diagonal = min(float(about_g[0, 0]), float(about_g[1, 1]))
    return {
        "product": PartAnswer(
            product,
            r"I_{xy,O} = 0,\quad I_{xy,G} = I_{xy,O} - m\,x_G\,y_G = -\frac{m_1 m_2\,a\,b}{4m}"
            rf" = {product:.4g}\ \mathrm{{kg\,m^2}}",
            {"about-o": 0.0, "sign": -product},
        ),
        "angle": PartAnswer(
            angle,
            r"\tan 2\theta_p = \frac{2 I_{xy}}{I_{yy} - I_{xx}}\ \text{(the root with the smaller moment)},"
            rf"\ \theta_p = {angle:.4g}^\circ",
            {"no-half": double, "radian-number": math.radians(angle), "other-root": other},
        ),
        "least": PartAnswer(
            least,
            r"I_{1,2} = \frac{I_{xx} + I_{yy}}{2} \mp \sqrt{\left(\frac{I_{xx} - I_{yy}}{2}\right)^2 + I_{xy}^2}"
            rf" = {least:.4g}\ \mathrm{{kg\,m^2}}",
            {"diagonal": diagonal},
        ),
    }


def cylinder_turned_frame(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A solid cylinder (m, r, length h; axis z) and the frame x'y'z' turned by α about x: I_z'z', the product
    I_y'z' = ∫y'z' dm, and along which axis the inertia ellipsoid is longest."""
    m, r, h = given["mass_kg"], given["radius_m"], given["length_m"]
    if abs(h**2 - 3 * r**2) < 0.1 * (h**2 + 3 * r**2):
        raise ValueError("the axial and transverse moments are nearly equal: the product is lost in rounding")
    alpha = math.radians(given["angle_deg"])
    tensor = inertia.solid_cylinder(m, r, h)
    turned = _rotation_x(alpha).T @ tensor @ _rotation_x(alpha)
    axial, transverse = float(tensor[2, 2]), float(tensor[0, 0])
    izz = float(turned[2, 2])
    product = -float(turned[1, 2])
    longest = "along-axis" if axial < transverse else "across-axis"
    return {
        "izz": PartAnswer(
            izz,
            r"I_{z'z'} = \mathbf e_{z'}^{\mathsf T}[I]\,\mathbf e_{z'} = I_a\cos^2\alpha + I_t\sin^2\alpha"
            rf" = {izz:.4g}\ \mathrm{{kg\,m^2}}",
            {"swapped": axial * math.sin(alpha) ** 2 + transverse * math.cos(alpha) ** 2},
        ),
        "product": PartAnswer(
            product,
            r"I_{y'z'} = -\mathbf e_{y'}^{\mathsf T}[I]\,\mathbf e_{z'} = (I_t - I_a)\sin\alpha\cos\alpha"
            rf" = {product:.4g}\ \mathrm{{kg\,m^2}}",
            {"sign": -product, "double-angle": 2 * product},
        ),
        "ellipsoid": PartAnswer(
            longest,
            rf"I_a = {axial:.4g},\ I_t = {transverse:.4g}\ \mathrm{{kg\,m^2}};"
            r"\ \text{semi-axis } 1/\sqrt{I}\text{ is longest about the least moment}",
            {"largest-moment": "across-axis" if longest == "along-axis" else "along-axis"},
        ),
    }


def wheel_on_turntable(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A thin disk (m, r) on a horizontal axle through its centre G, carried by a turntable turning at constant Ω
    about the vertical through G, and spinning on the axle at ω_s (relative to the turntable), speeding up at ω̇_s.
    Frame xyz turns with the turntable (x along the axle, z up): H_G, dH_G/dt, and the bearing forces (span s)."""
    m, r, spin, spin_rate = given["mass_kg"], given["radius_m"], given["spin_rad_s"], given["spin_accel_rad_s2"]
    table, span = given["table_rad_s"], given["span_m"]
    axial, transverse = 0.5 * m * r**2, 0.25 * m * r**2
    h = np.array([axial * spin, 0.0, transverse * table])
    frame = np.array([0.0, 0.0, table])
    relative = np.array([axial * spin_rate, 0.0, 0.0])
    rate = relative + np.cross(frame, h)
    body_omega = np.array([spin, 0.0, table])
    force = abs(float(rate[1])) / span
    return {
        "h": PartAnswer(
            _vector(h),
            rf"\mathbf H_G = (I_a\omega_s,\ 0,\ I_t\Omega) = ({h[0]:.4g},\ 0,\ {h[2]:.4g})\ \mathrm{{kg\,m^2/s}}",
            {"spin-only": (float(h[0]), 0.0, 0.0), "one-moment": (float(h[0]), 0.0, axial * table)},
        ),
        "rate": PartAnswer(
            _vector(rate),
            r"\dot{\mathbf H}_G = \frac{\delta\mathbf H_G}{\delta t} + \Omega\mathbf z \times \mathbf H_G"
            r" = (I_a\dot\omega_s,\ I_a\omega_s\Omega,\ 0)"
            rf" = ({rate[0]:.4g},\ {rate[1]:.4g},\ 0)\ \mathrm{{N\,m}}",
            {
                "body-omega": _vector(relative + np.cross(body_omega, h)),
                "no-relative": _vector(np.cross(frame, h)),
                "transport-sign": _vector(relative - np.cross(frame, h)),
            },
        ),
        "force": PartAnswer(
            force,
            rf"F = \frac{{I_a\omega_s\Omega}}{{s}} = {force:.4g}\ \mathrm{{N}}"
            r"\quad(\text{the } x \text{ part, } I_a\dot\omega_s, \text{ is the motor's torque})",
            {"half-span": 2 * force, "with-motor": float(np.hypot(rate[0], rate[1])) / span},
        ),
    }


def plate_spin_up(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A thin plate (a along x, b along y) on a vertical shaft Z through G, tilted β about its x axis (R = R_x(β)),
    turning at Ω and speeding up at Ω̇ at this instant: the moment about G in fixed XYZ, the motor's torque (Z part)
    and each bearing's force (span s)."""
    m, a, b = given["mass_kg"], given["length_m"], given["width_m"]
    beta, spin, spin_rate, span = (
        math.radians(given["tilt_deg"]),
        given["spin_rate_rad_s"],
        given["spin_accel_rad_s2"],
        given["bearing_span_m"],
    )
    body = inertia.thin_plate(m, a, b)
    world = inertia.rotate_tensor(body, _rotation_x(beta))
    z = np.array([0.0, 0.0, 1.0])
    column = world @ z  # (−I_XZ, −I_YZ, I_ZZ)
    h = spin * column
    steady = np.cross(spin * z, h)
    moment = spin_rate * column + steady
    torque = float(moment[2])
    force = float(np.hypot(moment[0], moment[1])) / span
    flipped = np.array([-moment[0], -moment[1], moment[2]])
    return {
        "moment": PartAnswer(
            _vector(moment),
            r"\sum\mathbf M_G = [I_G]\,\dot\Omega\mathbf Z + \Omega\mathbf Z\times[I_G]\,\Omega\mathbf Z"
            r" = \left(\Omega^2 I_{YZ},\ -\dot\Omega I_{YZ},\ \dot\Omega I_{ZZ}\right)"
            rf" = ({moment[0]:.4g},\ {moment[1]:.4g},\ {moment[2]:.4g})\ \mathrm{{N\,m}}",
            {
                "steady-only": _vector(steady),
                "no-transport": _vector(spin_rate * column),
                "product-sign": _vector(flipped),
            },
        ),
        "torque": PartAnswer(
            torque,
            rf"M_Z = I_{{ZZ}}\,\dot\Omega = (I_{{yy}}\sin^2\beta + I_{{zz}}\cos^2\beta)\,\dot\Omega = {torque:.4g}"
            r"\ \mathrm{N\,m}",
            {"body-axis-moment": float(body[2, 2]) * spin_rate},
        ),
        "force": PartAnswer(
            force,
            r"F = \frac{\sqrt{M_X^2 + M_Y^2}}{s} = \frac{|I_{YZ}|\sqrt{\Omega^4 + \dot\Omega^2}}{s}"
            rf" = {force:.4g}\ \mathrm{{N}}",
            {"steady-only": float(np.hypot(steady[0], steady[1])) / span},
        ),
    }
