"""Worked example ``double-pendulum-coordinates`` (section 7.2): which numbers can serve as the double pendulum's
generalized coordinates?

The system is :mod:`app.physics.systems.ch07.double_pendulum` (frame N: x horizontal in the plane of motion, z up,
the pivot O at the origin; θ₁, θ₂ the rods' angles from the downward vertical). Six Cartesian coordinates of the two
bobs obey four holonomic, scleronomic constraints (two rod lengths, two "stay in the plane"), so two coordinates are
needed. The angles (θ₁, θ₂) satisfy every constraint identically; the lower bob's position (x_B, z_B) does not
qualify: it fixes the configuration only up to a choice of two mirror images (inverse kinematics by the law of
cosines), and its Jacobian ``det ∂(x_B, z_B)/∂(θ₁, θ₂) = l₁ l₂ sin(θ₂ − θ₁)`` vanishes when the rods are in line.

A point out of reach (|OB| > l₁ + l₂ or |OB| < |l₁ − l₂|) and the pivot itself with equal rods (every θ₁ fits) are
refused with a ParameterError (a ValueError) naming ``bob_x_m``, by the inputs' check and by :func:`solve`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch07.double_pendulum import SYSTEM

#: A reach within this fraction of l₁ + l₂ of the pivot counts as the pivot itself (every θ₁ then fits if l₁ = l₂).
PIVOT_ROUND_OFF = 1e-12


def _check(values: Mapping[str, Any]) -> None:
    angles_for(float(values["l1_m"]), float(values["l2_m"]), float(values["bob_x_m"]), float(values["bob_z_m"]))


INPUTS = ParameterSet(
    (
        SYSTEM.parameters.by_name["l1_m"],
        SYSTEM.parameters.by_name["l2_m"],
        Parameter(
            "bob_x_m",
            "m",
            1.2,
            -20.0,
            20.0,
            "Horizontal position x_B of the lower bob, from the pivot",
            "x_B",
            step=0.01,
        ),
        Parameter(
            "bob_z_m",
            "m",
            -1.1,
            -20.0,
            20.0,
            "Height z_B of the lower bob above the pivot (negative: below it)",
            "z_B",
            step=0.01,
        ),
    ),
    check=_check,
)


def _wrapped(angle: float) -> float:
    """``angle`` (rad) brought into (−π, π]."""
    wrapped = math.remainder(angle, 2.0 * math.pi)
    return math.pi if wrapped == -math.pi else wrapped


def bob_positions(l1: float, l2: float, theta1: float, theta2: float) -> tuple[np.ndarray, np.ndarray]:
    """r_A and r_B (m, (3,)) for the angles (rad): ``r_A = l₁(sin θ₁, 0, −cos θ₁)``, ``r_B = r_A + l₂(sin θ₂, 0,
    −cos θ₂)``."""
    first = l1 * np.array([math.sin(theta1), 0.0, -math.cos(theta1)])
    return first, first + l2 * np.array([math.sin(theta2), 0.0, -math.cos(theta2)])


def constraint_residuals(l1: float, l2: float, r_a: np.ndarray, r_b: np.ndarray) -> np.ndarray:
    """The four constraints g = 0 at Cartesian positions: ``|r_A|² − l₁²``, ``|r_B − r_A|² − l₂²`` (m²), ``y_A``,
    ``y_B`` (m)."""
    return np.array([r_a @ r_a - l1 * l1, (r_b - r_a) @ (r_b - r_a) - l2 * l2, r_a[1], r_b[1]])


def constraint_jacobian(r_a: np.ndarray, r_b: np.ndarray) -> np.ndarray:
    """∂g/∂(x_A, y_A, z_A, x_B, y_B, z_B), (4, 6)."""
    jacobian = np.zeros((4, 6))
    jacobian[0, :3] = 2.0 * r_a
    jacobian[1, :3] = -2.0 * (r_b - r_a)
    jacobian[1, 3:] = 2.0 * (r_b - r_a)
    jacobian[2, 1] = 1.0
    jacobian[3, 4] = 1.0
    return jacobian


def angles_for(l1: float, l2: float, x_b: float, z_b: float) -> tuple[tuple[float, float], tuple[float, float]]:
    """The two (θ₁, θ₂) (rad, in (−π, π]) that put the lower bob at (x_B, z_B): θ₁ = β ∓ γ, where β is OB's angle from
    the downward vertical and γ the angle AOB of the triangle with sides l₁, l₂, |OB| (law of cosines).

    A :class:`ParameterError` (a ValueError) naming ``bob_x_m`` when the point is out of reach, or is the pivot with
    equal rods (then every θ₁ fits).
    """
    reach = math.hypot(x_b, z_b)
    if reach <= PIVOT_ROUND_OFF * (l1 + l2):
        if abs(l1 - l2) <= PIVOT_ROUND_OFF * (l1 + l2):
            raise ParameterError(
                "bob_x_m",
                "the lower bob at the pivot with equal rods (l₁ = l₂) fits every θ₁ (the lower rod folds straight "
                "back): the position (x_B, z_B) does not fix the configuration at all there",
            )
        raise ParameterError(
            "bob_x_m", f"the lower bob cannot reach the pivot: |OB| = 0 is less than |l₁ − l₂| = {abs(l1 - l2):.4g} m"
        )
    if reach > l1 + l2 or reach < abs(l1 - l2):
        raise ParameterError(
            "bob_x_m",
            f"no configuration puts the lower bob at ({x_b:g}, {z_b:g}) m: its distance from the pivot, "
            f"{reach:.4g} m, must lie between |l₁ − l₂| = {abs(l1 - l2):.4g} m and l₁ + l₂ = {l1 + l2:.4g} m",
        )
    beta = math.atan2(x_b, -z_b)
    cosine = (l1 * l1 + reach * reach - l2 * l2) / (2.0 * l1 * reach)
    gamma = math.acos(min(1.0, max(-1.0, cosine)))
    found = []
    for theta1 in (beta - gamma, beta + gamma):
        x_a, z_a = l1 * math.sin(theta1), -l1 * math.cos(theta1)
        theta2 = math.atan2(x_b - x_a, -(z_b - z_a))
        found.append((_wrapped(theta1), _wrapped(theta2)))
    return found[0], found[1]


def solve(inputs: Mapping[str, Any]) -> Solution:
    l1, l2 = float(inputs["l1_m"]), float(inputs["l2_m"])
    x_b, z_b = float(inputs["bob_x_m"]), float(inputs["bob_z_m"])
    first, second = angles_for(l1, l2, x_b, z_b)
    reach = math.hypot(x_b, z_b)
    beta = math.atan2(x_b, -z_b)
    gamma = math.acos(min(1.0, max(-1.0, (l1 * l1 + reach * reach - l2 * l2) / (2.0 * l1 * reach))))
    positions = [bob_positions(l1, l2, *angles) for angles in (first, second)]
    residuals = [constraint_residuals(l1, l2, r_a, r_b) for r_a, r_b in positions]
    rank = int(np.linalg.matrix_rank(constraint_jacobian(*positions[0])))
    determinants = np.array([l1 * l2 * math.sin(t2 - t1) for t1, t2 in (first, second)])
    theta1 = np.array([first[0], second[0]])
    theta2 = np.array([first[1], second[1]])
    scale = (l1 + l2) ** 2
    steps = (
        Step(
            "Count: six Cartesian coordinates, four constraint equations",
            r"g_1 = x_A^2 + y_A^2 + z_A^2 - l_1^2,\ g_2 = |\bar r_B - \bar r_A|^2 - l_2^2,\ g_3 = y_A,\ g_4 = y_B;"
            r"\quad N = 6 - 4 = 2",
            {"Cartesian": 6, "constraints": 4, "N": 6 - 4},
            {"Cartesian": "", "constraints": "", "N": ""},
        ),
        Step(
            "Try the lower bob's position (x_B, z_B) as the two coordinates: is the point within reach?",
            r"|OB| = \sqrt{x_B^2 + z_B^2},\quad |l_1 - l_2| \le |OB| \le l_1 + l_2",
            {"|OB|": reach, "l_1+l_2": l1 + l2, "|l_1-l_2|": abs(l1 - l2)},
            {"|OB|": "m", "l_1+l_2": "m", "|l_1-l_2|": "m"},
        ),
        Step(
            "Recover the angles: two configurations put B at the same point",
            r"\beta = \operatorname{atan2}(x_B, -z_B),\quad \cos\gamma = \frac{l_1^2 + |OB|^2 - l_2^2}{2\,l_1\,|OB|},"
            r"\quad \theta_1 = \beta \mp \gamma,\quad \theta_2 = \operatorname{atan2}(x_B - x_A,\ z_A - z_B)",
            {"beta": beta, "gamma": gamma, "theta_1": theta1, "theta_2": theta2},
            {"beta": "rad", "gamma": "rad", "theta_1": "rad", "theta_2": "rad"},
        ),
        Step(
            "Can (x_B, z_B) follow every small motion? The Jacobian of the change of coordinates",
            r"\frac{\partial(x_B, z_B)}{\partial(\theta_1, \theta_2)} = \begin{bmatrix} l_1\cos\theta_1 & "
            r"l_2\cos\theta_2\\ l_1\sin\theta_1 & l_2\sin\theta_2\end{bmatrix},\quad \det = l_1 l_2 "
            r"\sin(\theta_2 - \theta_1)",
            {"det": determinants},
            {"det": "m²"},
            scales={"det": l1 * l2},
        ),
        Step(
            "Check: each pair of angles puts B at the point and satisfies all four constraints, which are independent",
            r"\bar r_A = l_1(\sin\theta_1, 0, -\cos\theta_1),\ \bar r_B = \bar r_A + l_2(\sin\theta_2, 0, "
            r"-\cos\theta_2);\quad g_k(\bar r_A, \bar r_B) = 0,\quad \operatorname{rank}\frac{\partial g}{\partial"
            r"(x_A, \dots, z_B)} = 4",
            {
                "r_B_first": positions[0][1],
                "r_B_second": positions[1][1],
                "g_first": residuals[0],
                "g_second": residuals[1],
                "rank": rank,
            },
            {"r_B_first": "m", "r_B_second": "m", "g_first": "m², m², m, m", "g_second": "m², m², m, m", "rank": ""},
            scales={"g_first": scale, "g_second": scale},
        ),
    )
    outputs = {
        "theta1_rad": theta1,
        "theta2_rad": theta2,
        "jacobian_det_m2": determinants,
        "reach_m": reach,
        "degrees_of_freedom": 2,
    }
    return Solution(outputs=outputs, steps=steps, output_scales={"jacobian_det_m2": l1 * l2})


EXAMPLE = WorkedExample(
    id="double-pendulum-coordinates",
    title="Choosing the double pendulum's generalized coordinates: two angles, not the bob's position",
    chapter=7,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "theta1_rad": "rad",
        "theta2_rad": "rad",
        "jacobian_det_m2": "m²",
        "reach_m": "m",
        "degrees_of_freedom": "",
    },
    section="7.2",
    story=ExampleStory(
        situation=(
            "A double pendulum hangs from a fixed pivot $O$: rod $l_1$ to the upper bob $A$, rod $l_2$ from $A$ to the "
            "lower bob $B$, both swinging in one vertical plane. A camera tracks only the lower bob and reports "
            "its position $(x_B, z_B)$ in that plane, measured from the pivot with $z$ up. Someone proposes to "
            "describe the whole pendulum by those two numbers."
        ),
        wanted=(
            "How many generalized coordinates the pendulum needs, whether the tracked position $(x_B, z_B)$ can "
            "serve as them, and the rod angles $\\theta_1$, $\\theta_2$ (from the downward vertical) that put the "
            "lower bob at the measured point."
        ),
        approach=(
            "We start from the six Cartesian coordinates of the two bobs and count the holonomic constraints that "
            'tie them: two fixed rod lengths and two "stay in the plane" conditions, four in all, so two '
            "coordinates are needed. Any two numbers are not enough, though: a valid set must fix the configuration "
            "uniquely and follow every small motion. Working backwards from $(x_B, z_B)$ with the law of "
            "cosines shows two mirror-image configurations, and the Jacobian of the change of coordinates shows "
            "where small motions are lost. The angles have neither problem, which is why Lagrange's equations for "
            "this system are written in them. Keeping all six Cartesian coordinates would also work, but it "
            "drags four constraint equations and their forces along."
        ),
        check=(
            "The check puts each pair of angles back into the position formulas: both must land the lower bob on "
            "the measured point, and both must satisfy all four constraint equations to round-off, since the "
            "angles satisfy them identically. The constraint Jacobian's rank is computed too: it must be 4, so "
            "the four constraints are independent and $6 - 4 = 2$ really is the number of degrees of freedom."
        ),
        what_if=(
            "Move the point outward until $|OB|$ reaches $l_1 + l_2$ (with the defaults, set $x_B$ to 1.67 m). The "
            "two solutions for $\\theta_1$ close in on each other, $\\gamma$ falls to zero and the Jacobian's "
            "determinant $l_1 l_2\\sin(\\theta_2 - \\theta_1)$ goes to zero: with the rods in line the bob cannot "
            "move outward at all, so $(x_B, z_B)$ fails as coordinates there. One step further the example "
            "refuses: no configuration reaches the point."
        ),
    ),
)
