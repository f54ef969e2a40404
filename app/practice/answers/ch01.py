"""Answers of chapter 1's exercises: vectors, moments, differentiation in a fixed frame, Newton's laws, units,
work–energy and impulse–momentum for a particle."""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
import sympy

from app.physics.systems.ch01 import robot_arm_cable
from app.practice.exercise import PartAnswer

#: The link lengths of the robotic arm exercise (m), the lesson's Example 1.1 values.
ARM_AB_M, ARM_BC_M = 2.0, 1.5


def _vec(v: np.ndarray) -> tuple[float, float, float]:
    return (float(v[0]), float(v[1]), float(v[2]))


def _latex_vec(v: np.ndarray, unit: str) -> str:
    return rf"({v[0]:.4g},\ {v[1]:.4g},\ {v[2]:.4g})\ \mathrm{{{unit}}}"


def arm_cable_moments(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """Example 1.1's arm (AB = 2 m in the horizontal plane at θ from x, BC = 1.5 m raised γ in the same vertical
    plane) pulled from C toward D = x_D i by a cable of tension T: the force on the arm at C, its component along BC,
    its moment about the vertical axis through A, and its moment about the line AB. Uses the scene's own model."""
    loads = robot_arm_cable.cable_loads(
        {
            "theta_deg": given["theta_deg"],
            "gamma_deg": given["gamma_deg"],
            "tension_N": given["tension_n"],
            "AB_m": ARM_AB_M,
            "BC_m": ARM_BC_M,
            "D_x_m": given["anchor_x_m"],
        }
    )
    geo = loads.geometry
    force = loads.F_N
    r_dc = geo.D - geo.C
    moment_b = np.cross(geo.B, force)  # r_B is not on the cable's line of action
    return {
        "force": PartAnswer(
            _vec(force),
            r"\bar F = T\,\frac{\bar r_D - \bar r_C}{|\bar r_D - \bar r_C|} = " + _latex_vec(force, "N"),
            {"reversed": _vec(-force), "not-unit": _vec(given["tension_n"] * r_dc)},
        ),
        "f-bc": PartAnswer(
            loads.F_BC_N,
            rf"F_{{BC}} = \bar F\cdot\bar e_{{BC}} = {loads.F_BC_N:.4g}\ \mathrm{{N}}",
            {"reversed": -loads.F_BC_N},
        ),
        "m-z": PartAnswer(
            loads.M_z_Nm,
            rf"M_z = (\bar r_C\times\bar F)\cdot\bar k = {loads.M_z_Nm:.4g}\ \mathrm{{N\,m}}",
            {"order-swapped": -loads.M_z_Nm, "point-b": float(moment_b[2])},
        ),
        "m-ab": PartAnswer(
            loads.M_AB_Nm,
            rf"M_{{AB}} = (\bar r_C\times\bar F)\cdot\bar e_{{AB}} = {loads.M_AB_Nm:.4g}\ \mathrm{{N\,m}}",
            {"magnitude": float(np.linalg.norm(loads.M_A_Nm)), "order-swapped": -loads.M_AB_Nm},
        ),
    }


def guyed_pole_hinge(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A vertical pole from O to B = h k, a cable from B to D = (x_D, y_D, 0) with tension T; the pole's base hinge
    runs along OE, E = (x_E, y_E, 0). The cable's force on the pole, its moment about O, and its moment about the
    hinge axis (right-hand rule about e from O toward E)."""
    h, tension = given["height_m"], given["tension_n"]
    b = np.array([0.0, 0.0, h])
    d = np.array([given["anchor_x_m"], given["anchor_y_m"], 0.0])
    e_point = np.array([given["hinge_x_m"], given["hinge_y_m"], 0.0])
    length = float(np.linalg.norm(d - b))
    force = tension * (d - b) / length
    moment = np.cross(b, force)
    e = e_point / np.linalg.norm(e_point)
    about_axis = float(moment @ e)
    return {
        "force": PartAnswer(
            _vec(force),
            rf"|BD| = {length:.4g}\ \mathrm{{m}},\ \bar F = T\,\frac{{\bar r_D - \bar r_B}}{{|BD|}} = "
            + _latex_vec(force, "N"),
            {"reversed": _vec(-force)},
        ),
        "moment-o": PartAnswer(
            _vec(moment),
            r"\bar M_O = \bar r_{B/O}\times\bar F = " + _latex_vec(moment, r"N\,m"),
            {"order-swapped": _vec(-moment)},
        ),
        "hinge": PartAnswer(
            about_axis,
            r"\bar e = \frac{\bar r_E}{|\bar r_E|},"
            rf"\ M_e = \bar M_O\cdot\bar e = {about_axis:.4g}\ \mathrm{{N\,m}}",
            {
                "not-unit": float(moment @ e_point),
                "magnitude": float(np.linalg.norm(moment)),
            },
        ),
    }


r_s, rd_s, theta_s, thetad_s, beta_s, betad_s = sympy.symbols("r rd theta thetad beta betad", real=True)


def radar_velocity(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A radar at O reports range r, azimuth θ (from x toward y) and elevation β with their rates: ẋ by the chain
    rule, the velocity on the fixed xyz, and the speed."""
    xdot = (
        rd_s * sympy.cos(beta_s) * sympy.cos(theta_s)
        - r_s * betad_s * sympy.sin(beta_s) * sympy.cos(theta_s)
        - r_s * thetad_s * sympy.cos(beta_s) * sympy.sin(theta_s)
    )
    r, rd = given["range_m"], given["range_rate_m_s"]
    th, thd = math.radians(given["azimuth_deg"]), given["azimuth_rate_rad_s"]
    be, bed = math.radians(given["elevation_deg"]), given["elevation_rate_rad_s"]
    e_r = np.array([math.cos(be) * math.cos(th), math.cos(be) * math.sin(th), math.sin(be)])
    e_theta = np.array([-math.sin(th), math.cos(th), 0.0])
    e_beta = np.array([-math.sin(be) * math.cos(th), -math.sin(be) * math.sin(th), math.cos(be)])
    velocity = rd * e_r + r * bed * e_beta + r * thd * math.cos(be) * e_theta
    speed = float(np.linalg.norm(velocity))
    return {
        "xdot": PartAnswer(
            xdot,
            r"\dot x = \dot r\cos\beta\cos\theta - r\dot\beta\sin\beta\cos\theta - r\dot\theta\cos\beta\sin\theta",
            {
                "fixed-angles": rd_s * sympy.cos(beta_s) * sympy.cos(theta_s),
                "derivative-sign": rd_s * sympy.cos(beta_s) * sympy.cos(theta_s)
                + r_s * betad_s * sympy.sin(beta_s) * sympy.cos(theta_s)
                + r_s * thetad_s * sympy.cos(beta_s) * sympy.sin(theta_s),
            },
        ),
        "velocity": PartAnswer(
            _vec(velocity),
            r"\bar v = (\dot x,\ \dot y,\ \dot z) = " + _latex_vec(velocity, "m/s"),
            {"fixed-angles": _vec(rd * e_r)},
        ),
        "speed": PartAnswer(
            speed,
            r"v = \sqrt{\dot r^2 + (r\dot\beta)^2 + (r\dot\theta\cos\beta)^2}" + rf" = {speed:.4g}\ \mathrm{{m/s}}",
            {"no-cos-beta": math.sqrt(rd**2 + (r * bed) ** 2 + (r * thd) ** 2)},
        ),
    }


def drag_terminal_speed(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A ball (mass m, diameter d, drag coefficient C_d) in air of density ρ, quadratic drag F = c v² with
    c = ½ ρ C_d A: the unit of c, the drag at speed v, the terminal speed √(mg/c), and drag over weight at v."""
    m, d, cd, rho, v, g = (
        given["mass_kg"],
        given["diameter_m"],
        given["drag_coefficient"],
        given["air_density_kg_m3"],
        given["speed_m_s"],
        given["g_m_s2"],
    )
    area = math.pi * d**2 / 4
    c = 0.5 * rho * cd * area
    drag = c * v**2
    terminal = math.sqrt(m * g / c)
    ratio = drag / (m * g)
    return {
        "unit": PartAnswer(
            "kg-per-m", r"[c] = \frac{\mathrm N}{(\mathrm{m/s})^2} = \mathrm{kg/m}", {"linear": "kg-per-s"}
        ),
        "drag": PartAnswer(
            drag,
            rf"A = \tfrac{{\pi}}{{4}} d^2 = {area:.4g}\ \mathrm{{m^2}},"
            rf"\ c = \tfrac12\rho C_d A = {c:.4g}\ \mathrm{{kg/m}},"
            rf"\ F_d = c v^2 = {drag:.4g}\ \mathrm{{N}}",
            {"diameter-as-radius": 4 * drag, "no-half": 2 * drag},
        ),
        "terminal": PartAnswer(
            terminal,
            rf"v_t = \sqrt{{m g / c}} = {terminal:.4g}\ \mathrm{{m/s}}",
            {"mass-not-weight": math.sqrt(m / c), "diameter-as-radius": terminal / 2},
        ),
        "ratio": PartAnswer(
            ratio,
            rf"\frac{{F_d}}{{m g}} = \left(\frac{{v}}{{v_t}}\right)^2 = {ratio:.4g}",
            {"linear-ratio": v / terminal},
        ),
    }


m_s, b_s, g_s, t_s = sympy.symbols("m b g t", real=True)


def falling_linear_drag(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A body released from rest falls against linear drag b v (z down, so the speed is v ≥ 0): the terminal speed
    m g/b, the speed v(t), and the work done by drag up to t₁ by the work–energy principle."""
    m, b, t1, g = given["mass_kg"], given["drag_kg_s"], given["time_s"], given["g_m_s2"]
    terminal = m * g / b
    k = b / m
    speed_expr = m_s * g_s / b_s * (1 - sympy.exp(-b_s * t_s / m_s))
    v1 = terminal * (1 - math.exp(-k * t1))
    drop = terminal * (t1 - (1 - math.exp(-k * t1)) / k)
    kinetic = 0.5 * m * v1**2
    work_drag = kinetic - m * g * drop
    return {
        "terminal": PartAnswer(
            terminal, rf"v_t = \frac{{m g}}{{b}} = {terminal:.4g}\ \mathrm{{m/s}}", {"no-mass": g / b}
        ),
        "speed": PartAnswer(
            speed_expr,
            r"m\dot v = m g - b v,\ v(0) = 0\ \Rightarrow\ v = \frac{m g}{b}\left(1 - e^{-b t/m}\right)",
            {
                "no-drag": g_s * t_s,
                "decaying": m_s * g_s / b_s * sympy.exp(-b_s * t_s / m_s),
            },
        ),
        "work": PartAnswer(
            work_drag,
            rf"v(t_1) = {v1:.4g}\ \mathrm{{m/s}},\ d = v_t\left(t_1 - \tfrac{{m}}{{b}}(1 - e^{{-b t_1/m}})\right)"
            rf" = {drop:.4g}\ \mathrm{{m}},\ W_d = \tfrac12 m v_1^2 - m g d = {work_drag:.4g}\ \mathrm{{J}}",
            {"kinetic-only": kinetic, "gravity-sign": kinetic + m * g * drop},
        ),
    }


def bat_impulse(given: Mapping[str, float]) -> dict[str, PartAnswer]:
    """A ball arrives at speed v₁ moving toward the batter (−x), descending δ below the horizontal, and leaves at v₂
    rising α above it toward the pitcher (+x); contact lasts Δt (ms). Impulse of the bat, average force, work done."""
    m = given["mass_kg"]
    v1, delta = given["in_speed_m_s"], math.radians(given["in_angle_deg"])
    v2, alpha = given["out_speed_m_s"], math.radians(given["out_angle_deg"])
    contact_s = given["contact_ms"] * 1e-3
    before = v1 * np.array([-math.cos(delta), 0.0, -math.sin(delta)])
    after = v2 * np.array([math.cos(alpha), 0.0, math.sin(alpha)])
    impulse = m * (after - before)
    force = float(np.linalg.norm(impulse)) / contact_s
    work = 0.5 * m * (v2**2 - v1**2)
    e_after = after / v2
    return {
        "impulse": PartAnswer(
            _vec(impulse),
            r"\bar I = m(\bar v_2 - \bar v_1) = " + _latex_vec(impulse, r"N\,s"),
            {"speed-difference": _vec(m * (v2 - v1) * e_after), "reversed": _vec(-impulse)},
        ),
        "force": PartAnswer(
            force,
            rf"|\bar F_{{avg}}| = |\bar I| / \Delta t = {force:.4g}\ \mathrm{{N}}",
            {"ms-as-s": force * 1e-3},
        ),
        "work": PartAnswer(
            work,
            rf"W = T_2 - T_1 = \tfrac12 m (v_2^2 - v_1^2) = {work:.4g}\ \mathrm{{J}}",
            {"velocity-change": 0.5 * m * float(np.sum((after - before) ** 2))},
        ),
    }
