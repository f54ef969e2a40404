"""Worked example ``unbalanced-rotor-reactions``: the bearing reactions of a skewed, eccentric disk on a shaft.

The system is :mod:`app.physics.systems.ch06.unbalanced_rotor` (the lesson 6.1 scene's model), with the same
inputs. Frames as there: the shaft along +X from bearing A (origin) to bearing B at ``X = L``, +Z up, gravity
along −Z; the rotor frame turns with the shaft and coincides with the world frame at the spin angle φ = 0,
the instant the steps show (G level with the shaft, its eccentricity along +Y).

The steps use the imbalance form of Newton–Euler at constant ω: the first moment of mass about the shaft
``S = Σ m_k (y_k, z_k)`` and the products of inertia with the shaft about A, ``P = (∫xy dm, ∫xz dm)``, give the
inertial loads ``Σ m a = −ω² S`` and ``Σ dH/dt about A = ω² (P_z, −P_y)`` (transverse components), hence
``R_B = −ω² P / L`` and ``R_A = ω² (P − L S) / L`` for the rotating parts of the reactions. The check takes
moments about B instead (products about B from the parts moved by −L) and compares both reactions with the
scene model's per-part Newton–Euler (``ω × I_G ω + r × m a``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch06.unbalanced_rotor import (
    PARAMETERS,
    RotorPart,
    UnbalancedRotor,
    first_moment_kg_m,
    products_about_bearing_A_kg_m2,
)

INPUTS = PARAMETERS


def _transverse(yz: np.ndarray) -> np.ndarray:
    """A (y, z) pair as a rotor-frame vector (0, y, z)."""
    return np.array([0.0, float(yz[0]), float(yz[1])])


def solve(inputs: Mapping[str, Any]) -> Solution:
    rotor = UnbalancedRotor.from_params(inputs)
    disk = rotor.disk
    parts = rotor.parts
    omega, g, span = rotor.shaft_speed_rad_s, rotor.g_m_s2, disk.bearing_span_m
    m, r, e, a, beta = disk.disk_mass_kg, disk.disk_radius_m, disk.eccentricity_m, disk.disk_position_m, disk.skew_rad

    S = first_moment_kg_m(parts)
    P = products_about_bearing_A_kg_m2(parts)
    force_inertial = -(omega**2) * _transverse(S)
    moment_inertial = omega**2 * np.array([0.0, P[1], -P[0]])
    axis = np.array([1.0, 0.0, 0.0])
    b_rot = np.cross(moment_inertial, axis) / span
    a_rot = force_inertial - b_rot

    total_mass = sum(p.mass_kg for p in parts)
    centre_x = sum(p.mass_kg * p.centre_m[0] for p in parts) / total_mass
    share_b = total_mass * g * centre_x / span
    share_a = total_mass * g - share_b
    a_total = a_rot + np.array([0.0, 0.0, share_a])
    b_total = b_rot + np.array([0.0, 0.0, share_b])
    torque = g * float(S[0])  # T = g (Σ m y) at φ = 0: it holds the weight's moment about the shaft

    # Check: moments about B (every part moved by −L along the shaft), and the scene model's per-part Newton–Euler.
    about_b = tuple(RotorPart(p.mass_kg, p.centre_m - span * axis, p.inertia_cm_kg_m2) for p in parts)
    P_B = products_about_bearing_A_kg_m2(about_b)
    a_rot_about_b = omega**2 * _transverse(P_B) / span
    steady = rotor.steady_loads()

    fitted = inputs["balanced"] == "on"
    masses = rotor.correction.masses_kg
    steps: tuple[Step, ...] = (
        Step(
            "Imbalance of the rotor: first moment S and products of inertia P about A",
            r"\bar S = \sum_k m_k\,(y_k, z_k),\quad \bar P = \Big(\int x y\,dm,\ \int x z\,dm\Big)_A;\quad"
            r"\text{disk alone: } \bar S = (m e,\ 0),\ \ \bar P = \big(m a e,\ -\tfrac18 m r^2 \sin 2\beta\big)",
            {"m": m, "e": e, "a": a, "r": r, "beta": math.degrees(beta), "S": S, "P": P},
            {"m": "kg", "e": "m", "a": "m", "r": "m", "beta": "deg", "S": "kg·m", "P": "kg·m²"},
        ),
        Step(
            "Inertial loads at constant ω (rotor frame): Σ m a and the rate of the angular momentum about A",
            r"\sum m_k \bar a_k = -\omega^2 (0,\ S_y,\ S_z),\qquad \dot{\bar H}_A = \bar\omega\times(I_A\bar\omega) "
            r"= \omega^2 (0,\ P_z,\ -P_y)",
            {"omega": omega, "sum_m_a": force_inertial, "dH_A_dt": moment_inertial},
            {"omega": "rad/s", "sum_m_a": "N", "dH_A_dt": "N·m"},
        ),
        Step(
            "Moments about A give bearing B's rotating reaction",
            r"L\,\bar i\times\bar R_B = \dot{\bar H}_A \ \Rightarrow\ \bar R_B = \frac{\dot{\bar H}_A\times\bar i}{L}"
            r" = -\frac{\omega^2}{L}(0,\ P_y,\ P_z)",
            {"L": span, "R_B_rot": b_rot, "R_B_rot_size": float(np.linalg.norm(b_rot))},
            {"L": "m", "R_B_rot": "N", "R_B_rot_size": "N"},
        ),
        Step(
            "The force sum gives bearing A's rotating reaction",
            r"\bar R_A + \bar R_B = \sum m_k \bar a_k\ \Rightarrow\ \bar R_A = -\omega^2(0,\ S_y,\ S_z) - \bar R_B",
            {"R_A_rot": a_rot, "R_A_rot_size": float(np.linalg.norm(a_rot))},
            {"R_A_rot": "N", "R_A_rot_size": "N"},
        ),
        Step(
            "Add the weight (at φ = 0) and find the drive torque",
            r"W_B = \frac{M g\,\bar x}{L},\ W_A = M g - W_B,\quad \bar R = \bar R_{\rm rot} + W\,\bar k,\quad "
            r"T = g\,S_y\cos\varphi - g\,S_z\sin\varphi,\quad |R|_{\max} = |R_{\rm rot}| + W",
            {
                "M": total_mass,
                "W_A": share_a,
                "W_B": share_b,
                "R_A": a_total,
                "R_B": b_total,
                "T": torque,
                "R_A_max": float(np.linalg.norm(a_rot)) + share_a,
                "R_B_max": float(np.linalg.norm(b_rot)) + share_b,
            },
            {
                "M": "kg",
                "W_A": "N",
                "W_B": "N",
                "R_A": "N",
                "R_B": "N",
                "T": "N·m",
                "R_A_max": "N",
                "R_B_max": "N",
            },
            scales={"T": g * m * r},
        ),
        Step(
            "Check: moments about B give R_A directly, and per-part Newton–Euler gives both reactions",
            r"\bar P_B = \Big(\int (x-L)\,y\,dm,\ \int (x-L)\,z\,dm\Big),\quad \bar R_A = \frac{\omega^2}{L}"
            r"(0,\ P_{B,y},\ P_{B,z});\qquad \sum_k\big(\bar\omega\times I_{G_k}\bar\omega + \bar r_k\times m_k"
            r"\bar a_k\big)",
            {
                "P_B": P_B,
                "R_A_rot_about_B": a_rot_about_b,
                "R_A_rot_per_part": steady.bearing_A_rotating_rotor_N,
                "R_B_rot_per_part": steady.bearing_B_rotating_rotor_N,
            },
            {"P_B": "kg·m²", "R_A_rot_about_B": "N", "R_A_rot_per_part": "N", "R_B_rot_per_part": "N"},
            scales={
                "R_A_rot_about_B": float(np.linalg.norm(a_rot)) + float(np.linalg.norm(b_rot)),
                "R_A_rot_per_part": float(np.linalg.norm(a_rot)) + float(np.linalg.norm(b_rot)),
                "R_B_rot_per_part": float(np.linalg.norm(a_rot)) + float(np.linalg.norm(b_rot)),
            },
        ),
    )
    if fitted:
        steps = (
            *steps[:1],
            Step(
                "The two correction masses fitted (solving U₁ + U₂ = −S and x₁U₁ + x₂U₂ = −P for the disk)",
                r"\bar U_i = m_i\,\rho\,(\cos\theta_i,\ \sin\theta_i)",
                {"m_1": float(masses[0]), "m_2": float(masses[1]), "rho": rotor.correction.radius_m},
                {"m_1": "kg", "m_2": "kg", "rho": "m"},
            ),
            *steps[1:],
        )
    rotating_scale = float(np.linalg.norm(a_rot)) + float(np.linalg.norm(b_rot)) + m * r * omega**2
    outputs = {
        "bearing_A_rotating_N": a_rot,
        "bearing_B_rotating_N": b_rot,
        "bearing_A_N": a_total,
        "bearing_B_N": b_total,
        "bearing_A_peak_N": float(np.linalg.norm(a_rot)) + share_a,
        "bearing_B_peak_N": float(np.linalg.norm(b_rot)) + share_b,
        "driving_torque_Nm": torque,
        "imbalance": rotor.imbalance,
    }
    return Solution(
        outputs=outputs,
        steps=steps,
        output_scales={
            "bearing_A_rotating_N": rotating_scale,
            "bearing_B_rotating_N": rotating_scale,
            "bearing_A_N": rotating_scale + total_mass * g,
            "bearing_B_N": rotating_scale + total_mass * g,
            "driving_torque_Nm": g * m * r,
        },
    )


EXAMPLE = WorkedExample(
    id="unbalanced-rotor-reactions",
    title="Bearing reactions of an eccentric, skewed disk on a turning shaft",
    chapter=6,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "bearing_A_rotating_N": "N",
        "bearing_B_rotating_N": "N",
        "bearing_A_N": "N",
        "bearing_B_N": "N",
        "bearing_A_peak_N": "N",
        "bearing_B_peak_N": "N",
        "driving_torque_Nm": "N·m",
        "imbalance": "",
    },
    section="6.1",
    story=ExampleStory(
        situation=(
            "A 10 kg disk of radius 0.2 m sits on a light shaft 0.2 m from bearing A; bearing B is 0.6 m from A. "
            "The shaft turns at a steady 100 rad/s. The disk was mounted badly: its centre of mass is 1 mm off "
            "the shaft's axis, and its own axis is tilted 2° from the shaft. Gravity acts across the shaft. "
            "All of these numbers are the controls of the scene above."
        ),
        wanted=(
            "The forces the two bearings exert on the shaft at the instant the centre of mass is level with the "
            "shaft: the part that turns with the rotor and the part that carries the weight. Also the largest "
            "force each bearing feels over a turn, and the torque the motor must supply."
        ),
        approach=(
            "The rotor turns at constant speed about a fixed axis, so every acceleration and every rate of angular "
            "momentum is **fixed in the rotor frame**: we work there, and Newton–Euler becomes algebra. Rather "
            "than adding up each part's $\\bar\\omega\\times I_G\\bar\\omega$ and $\\bar r\\times m\\bar a$, we "
            "compress the whole rotor into two imbalance numbers, the first moment $\\bar S$ (where the mass "
            "centre is) and the products of inertia $\\bar P$ with the shaft (how the mass is tilted). Then "
            "moments about A give B's force in one line, and the force sum gives A's. Taking moments about A "
            "first is what keeps A's unknown force out of that equation; a world-frame treatment would make the "
            "inertia tensor change with time and hide that the loads simply rotate."
        ),
        check=(
            "The last step works the problem a second way twice over. Taking moments about B instead of A "
            "must give A's rotating force directly from the products of inertia about B, $\\bar P_B = \\bar P - "
            "L\\bar S$. The scene's model sums $\\bar\\omega\\times I_G\\bar\\omega + \\bar r\\times m\\bar a$ "
            "part by part with the full inertia tensor. All three answers must agree to round-off, because they "
            "are the same Newton–Euler equations organised differently."
        ),
        what_if=(
            "Turn the **skew β** to 0 and then the **eccentricity e** to 0, one at a time. With only eccentricity "
            "(static imbalance) both rotating bearing forces point the same way, from the mass centre towards the "
            "shaft: together they pull it round its circle. With only skew (dynamic imbalance) they are equal and "
            "opposite, a rotating couple, and $\\bar S = 0$. Then switch the **correction masses** on: $\\bar S$ "
            "and $\\bar P$ become zero and only the weight is left in the arrows of the scene."
        ),
    ),
)
