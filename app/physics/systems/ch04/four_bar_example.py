"""Worked example ``four-bar-instant``: a four-bar linkage at one crank angle: positions, rates, accelerations, and
the coupler point's velocity and acceleration.

The linkage, its frame and its names are those of :mod:`app.physics.systems.ch04.four_bar` (O₂ at the origin, O₄ at
(d, 0), angles counterclockwise from the ground line), and its inputs are that scene's parameters, so the lesson's
controls drive it. The instant solved is t = 0 of the scene: crank angle θ₂ = ``crank_angle0_deg`` (kept inside the
crank's reach as the scene keeps it), crank rate ω₂ = ``crank_speed_rad_s`` and no crank acceleration (the motor turns
at constant speed). Vectors are [x, y] on the ground frame (m, m/s, m/s²).

Inputs the loop cannot close for (links that cannot be assembled, a crank angle out of reach) and a crank angle at a
toggle position (coupler and rocker in line: the rocker rate is unbounded) are refused with a ParameterError.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.parameters import ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch04.four_bar import PARAMETERS, FourBar, FourBarMotion


def _perp(vector: np.ndarray) -> np.ndarray:
    """k × r for a planar vector r = [x, y]: [−y, x]."""
    return np.array([-vector[1], vector[0]])


@dataclass(frozen=True)
class FourBarInstant:
    """The linkage at the instant solved: angles (rad), rates (rad/s), accelerations (rad/s²), joints (m)."""

    linkage: FourBar
    theta2: float
    omega2: float
    theta3: float
    theta4: float
    omega3: float
    omega4: float
    alpha3: float
    alpha4: float
    pin_a: np.ndarray
    pin_b: np.ndarray
    singular: bool


def instant(inputs: Mapping[str, Any]) -> FourBarInstant:
    """The linkage at t = 0 of the scene for validated inputs (ValueError if it cannot be assembled there)."""
    motion = FourBarMotion.from_params(inputs)
    linkage = motion.linkage
    theta2 = float(motion.drive.angle0_rad)
    omega2 = float(inputs["crank_speed_rad_s"])
    pos = linkage.positions(np.array([theta2]), inputs["branch"])
    theta3, theta4 = float(pos.coupler_angle[0]), float(pos.rocker_angle[0])
    t2, t3, t4 = (np.array([x]) for x in (theta2, theta3, theta4))
    omega3, omega4, singular = linkage.rates(t2, t3, t4, np.array([omega2]))
    alpha3, alpha4 = linkage.accelerations(t2, t3, t4, np.array([omega2]), omega3, omega4, np.zeros(1))
    return FourBarInstant(
        linkage,
        theta2,
        omega2,
        theta3,
        theta4,
        float(omega3[0]),
        float(omega4[0]),
        float(alpha3[0]),
        float(alpha4[0]),
        pos.crank_pin[0],
        pos.rocker_pin[0],
        bool(singular[0]) or not math.isfinite(theta3),
    )


def _check(values: Mapping[str, Any]) -> None:
    try:
        FourBar(values["ground_m"], values["crank_m"], values["coupler_m"], values["rocker_m"])
    except ValueError as exc:
        raise ParameterError("coupler_m", str(exc)) from None
    try:
        state = instant(values)
    except ValueError as exc:
        raise ParameterError("crank_angle0_deg", str(exc)) from None
    if state.singular:
        raise ParameterError(
            "crank_angle0_deg",
            f"at θ₂ = {math.degrees(state.theta2):.2f}° the coupler and rocker are in line (a toggle position or a "
            "change point): the differentiated loop cannot be solved and the rocker rate is unbounded or undefined; "
            "move the crank angle away from it",
        )


INPUTS = ParameterSet(PARAMETERS.parameters, check=_check)


def solve(inputs: Mapping[str, Any]) -> Solution:
    _check(inputs)
    s_ = instant(inputs)
    b, c, d = s_.linkage.coupler_m, s_.linkage.rocker_m, s_.linkage.ground_m
    o4 = np.array([d, 0.0])
    r_a, r_b = s_.pin_a, s_.pin_b
    to_o4 = o4 - r_a
    s = float(np.hypot(*to_o4))
    along = (s * s + b * b - c * c) / (2.0 * s)
    h = math.sqrt(max(b * b - along * along, 0.0))
    mu = float(s_.linkage.transmission_angle(np.array([s_.theta2]))[0])
    determinant = b * c * math.sin(s_.theta3 - s_.theta4)
    w2, w3, w4, al3, al4 = s_.omega2, s_.omega3, s_.omega4, s_.alpha3, s_.alpha4
    # The general equations of 4.1 on each link (planar: ω = ω k, α = α k; ω × (ω × r) = −ω² r).
    r_ba, r_bo4 = r_b - r_a, r_b - o4
    v_a = w2 * _perp(r_a)
    a_a = -(w2**2) * r_a  # α₂ = 0
    v_b_coupler = v_a + w3 * _perp(r_ba)
    v_b_rocker = w4 * _perp(r_bo4)
    a_b_coupler = a_a + al3 * _perp(r_ba) - w3**2 * r_ba
    a_b_rocker = al4 * _perp(r_bo4) - w4**2 * r_bo4
    direction = s_.theta3 + math.radians(inputs["coupler_point_deg"])
    r_pa = inputs["coupler_point_m"] * np.array([math.cos(direction), math.sin(direction)])
    r_p = r_a + r_pa
    v_p = v_a + w3 * _perp(r_pa)
    a_p = a_a + al3 * _perp(r_pa) - w3**2 * r_pa
    deg = math.degrees
    steps = (
        Step(
            "Crank pin A and its distance s from O₄",
            r"\bar r_A = a\,(\cos\theta_2,\ \sin\theta_2),\qquad s^2 = a^2 + d^2 - 2ad\cos\theta_2",
            {"theta_2": deg(s_.theta2), "r_A": r_a, "s": s},
            {"theta_2": "deg", "r_A": "m", "s": "m"},
        ),
        Step(
            f"Loop closure: B on the circle of radius b about A and of radius c about O₄ ({inputs['branch']} assembly)",
            r"\ell = \frac{s^2 + b^2 - c^2}{2s},\quad h = \pm\sqrt{b^2 - \ell^2},\quad "
            r"a\,e^{i\theta_2} + b\,e^{i\theta_3} = d + c\,e^{i\theta_4}",
            {"l": along, "h": h, "r_B": r_b, "theta_3": deg(s_.theta3), "theta_4": deg(s_.theta4)},
            {"l": "m", "h": "m", "r_B": "m", "theta_3": "deg", "theta_4": "deg"},
        ),
        Step(
            "Transmission angle between coupler and rocker",
            r"\cos\mu = \frac{b^2 + c^2 - s^2}{2bc}",
            {"mu": deg(mu)},
            {"mu": "deg"},
        ),
        Step(
            "Rates from the differentiated loop (a 2 × 2 linear system)",
            r"\begin{bmatrix} -b\sin\theta_3 & c\sin\theta_4 \\ b\cos\theta_3 & -c\cos\theta_4 \end{bmatrix}"
            r"\begin{bmatrix} \omega_3 \\ \omega_4 \end{bmatrix} = "
            r"\begin{bmatrix} a\omega_2\sin\theta_2 \\ -a\omega_2\cos\theta_2 \end{bmatrix},"
            r"\quad \det = bc\sin(\theta_3 - \theta_4)",
            {"omega_2": w2, "det": determinant, "omega_3": w3, "omega_4": w4},
            {"omega_2": "rad/s", "det": "m²", "omega_3": "rad/s", "omega_4": "rad/s"},
        ),
        Step(
            "Angular accelerations from the loop differentiated twice (α₂ = 0)",
            r"[\,\text{same matrix}\,]\begin{bmatrix} \alpha_3 \\ \alpha_4 \end{bmatrix} = "
            r"\begin{bmatrix} a\omega_2^2\cos\theta_2 + b\omega_3^2\cos\theta_3 - c\omega_4^2\cos\theta_4 \\ "
            r"a\omega_2^2\sin\theta_2 + b\omega_3^2\sin\theta_3 - c\omega_4^2\sin\theta_4 \end{bmatrix}",
            {"alpha_3": al3, "alpha_4": al4},
            {"alpha_3": "rad/s²", "alpha_4": "rad/s²"},
        ),
        Step(
            "The coupler point P: the general equations on the coupler, from A",
            r"\bar v_A = \omega_2\bar k\times\bar r_A,\quad \bar a_A = -\omega_2^2\,\bar r_A,\quad "
            r"\bar v_P = \bar v_A + \omega_3\bar k\times\bar r_{P/A},\quad "
            r"\bar a_P = \bar a_A + \alpha_3\bar k\times\bar r_{P/A} - \omega_3^2\,\bar r_{P/A}",
            {"v_A": v_a, "a_A": a_a, "r_P": r_p, "v_P": v_p, "a_P": a_p},
            {"v_A": "m/s", "a_A": "m/s²", "r_P": "m", "v_P": "m/s", "a_P": "m/s²"},
        ),
        Step(
            "Check: B moves the same whether reached through the coupler or through the rocker",
            r"\bar v_A + \omega_3\bar k\times\bar r_{B/A} = \omega_4\bar k\times\bar r_{B/O_4},\qquad "
            r"\bar a_A + \alpha_3\bar k\times\bar r_{B/A} - \omega_3^2\bar r_{B/A} = "
            r"\alpha_4\bar k\times\bar r_{B/O_4} - \omega_4^2\bar r_{B/O_4}",
            {
                "v_B (coupler)": v_b_coupler,
                "v_B (rocker)": v_b_rocker,
                "a_B (coupler)": a_b_coupler,
                "a_B (rocker)": a_b_rocker,
            },
            {"v_B (coupler)": "m/s", "v_B (rocker)": "m/s", "a_B (coupler)": "m/s²", "a_B (rocker)": "m/s²"},
        ),
    )
    outputs = {
        "coupler_angle_rad": s_.theta3,
        "rocker_angle_rad": s_.theta4,
        "transmission_angle_rad": mu,
        "coupler_rate_rad_s": w3,
        "rocker_rate_rad_s": w4,
        "coupler_acceleration_rad_s2": al3,
        "rocker_acceleration_rad_s2": al4,
        "coupler_point_m": r_p,
        "coupler_point_velocity_m_s": v_p,
        "coupler_point_acceleration_m_s2": a_p,
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="four-bar-instant",
    title="A four-bar linkage at one crank angle: angles, rates, accelerations and a coupler point",
    chapter=4,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "coupler_angle_rad": "rad",
        "rocker_angle_rad": "rad",
        "transmission_angle_rad": "rad",
        "coupler_rate_rad_s": "rad/s",
        "rocker_rate_rad_s": "rad/s",
        "coupler_acceleration_rad_s2": "rad/s²",
        "rocker_acceleration_rad_s2": "rad/s²",
        "coupler_point_m": "m",
        "coupler_point_velocity_m_s": "m/s",
        "coupler_point_acceleration_m_s2": "m/s²",
    },
    section="4.3",
    story=ExampleStory(
        situation=(
            "A motor turns the crank of a four-bar linkage at a steady $\\omega_2$. The ground link is "
            "$d = 1.0$ m, the crank $a = 0.3$ m, the coupler $b = 1.0$ m and the rocker $c = 0.9$ m (the default "
            "controls), in the open assembly. At this instant the crank stands at $\\theta_2 = 60°$ and turns at 1.5 "
            "rad/s. A point $P$ "
            "fixed to the coupler, 0.6 m from $A$ and 40° off the line $AB$, is the one a designer cares about: it "
            "might carry a tool or guide a part along its path."
        ),
        wanted=(
            "The coupler and rocker angles $\\theta_3$ and $\\theta_4$, the transmission angle $\\mu$, the rates "
            "$\\omega_3$ and $\\omega_4$ and the angular accelerations $\\alpha_3$ and $\\alpha_4$ of both links, "
            "and then the velocity and acceleration of the coupler point $P$, all at this one instant."
        ),
        approach=(
            "The linkage has one degree of freedom, so everything follows from the crank. We close the loop "
            "$a e^{i\\theta_2} + b e^{i\\theta_3} = d + c e^{i\\theta_4}$: a vector equation in the ground frame, "
            "solved in closed form as the intersection of two circles. Differentiating it once and twice gives "
            "two $2\\times2$ *linear* systems with the same matrix, which is why rates are easy once positions are "
            "known. Only then do we treat the coupler as one rigid body and use the general equations of 4.1 from "
            "$A$ to $P$. The alternative, writing $P$'s coordinates as functions of $\\theta_2$ and differentiating "
            "them, buries the same algebra in long trigonometric expressions and hides where it fails: at a toggle "
            "the matrix's determinant $bc\\sin(\\theta_3-\\theta_4)$ is zero."
        ),
        check=(
            "The pin $B$ belongs to both the coupler and the rocker, so its velocity and acceleration can be "
            "computed twice: from $A$ through the coupler with $\\omega_3$ and $\\alpha_3$, and from the fixed "
            "pivot $O_4$ through the rocker with $\\omega_4$ and $\\alpha_4$. The last step does both. They must "
            "agree, to round-off, because the rates and accelerations were found precisely by demanding that the "
            "loop stay closed; a sign slip in either linear system would show as two different answers for $B$."
        ),
        what_if=(
            "Move the **crank angle** $\\theta_2(0)$ slowly round a full turn. Near 0°, where the crank points at "
            "$O_4$, the transmission angle falls to about 43°. Twice a turn the rocker rate $\\omega_4$ passes "
            "through zero and changes sign: those are the ends of the rocker's swing, where crank and coupler lie "
            "in line. Then press the **Non-Grashof** preset and bring $\\theta_2$ close to 75°: $\\omega_4$ in "
            "the steps grows without bound, and at the toggle itself the example refuses to solve."
        ),
    ),
)
