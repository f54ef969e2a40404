"""Worked example ``tilted-ride-angular-velocity``: ω and α of a fairground ride from its three angle rates.

The system is :mod:`app.physics.systems.ch03.angle_rates` (the lesson's scene), read as a ride whose seat disc is
turned by a 3-1-3 sequence: θ1 is the tower's turn about the vertical Z (precession), θ2 the tilt of the disc's axis
(nutation), θ3 the disc's spin about its own axis. Each angle moves with a constant angular acceleration. At the
instant ``t = time_s`` modulo ``replay_s`` (the scene's instant) the example finds

* ``ω = θ̇1 n1 + θ̇2 n2 + θ̇3 n3`` (rad/s) from the turn axes ``nk`` (XYZ components), and its body components;
* ``α = Σ θ̈k nk + θ̇1 n1 × θ̇2 n2 + (θ̇1 n1 + θ̇2 n2) × θ̇3 n3`` (rad/s²), split into its two parts;
* the rates back from ω (``θ̇ = J⁻¹ ω``), which fails at gimbal lock: there the step says so and gives the one
  combination ``θ̇1 ± θ̇3`` that ω still fixes.

Every sequence of the scene is allowed. No combination of the inputs is impossible (gimbal lock is a failure of
the description, not of the motion), so nothing is refused beyond the ranges.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.math.rotations import angle_rate_matrix_body, matrix_from_angles
from app.physics.systems.ch03.angle_rates import PARAMETERS, AngleMotion

#: The ``gimbal_lock`` output, in words (a verdict the page shows as it is).
AT_GIMBAL_LOCK, CLEAR_OF_GIMBAL_LOCK = "at gimbal lock", "clear of gimbal lock"


#: Step (s) of the fourth-order central differences in the check: truncation h⁴|f⁽⁵⁾|/30 ≈ 1e-13 at rates of a few
#: rad/s, round-off about ε/h ≈ 2e-13 rad/s.
DIFFERENCE_STEP_S = 1e-3

INPUTS = ParameterSet(
    (
        *PARAMETERS.parameters,
        Parameter(
            "time_s",
            "s",
            1.0,
            0.0,
            60.0,
            "Instant t at which ω and α are worked out (the scene's instant)",
            "instant t",
            step=0.05,
        ),
        Parameter(
            "replay_s",
            "s",
            10.0,
            2.0,
            60.0,
            "The scene replays the motion from t = 0 after this long",
            "replay length",
            step=1.0,
        ),
    ),
)


def _difference(f, t: float, h: float) -> np.ndarray:
    """Fourth-order central difference of ``f`` (array-valued) at ``t``."""
    return (f(t - 2.0 * h) - 8.0 * f(t - h) + 8.0 * f(t + h) - f(t + 2.0 * h)) / (12.0 * h)


def solve(inputs: Mapping[str, Any]) -> Solution:
    motion = AngleMotion.from_params(inputs)
    seq = motion.sequence
    t = float(inputs["time_s"]) % float(inputs["replay_s"])
    k = motion.kinematics(np.array([t]))
    angles, rates, accelerations = k.angles_rad[0], k.rates_rad_s[0], motion.accelerations_rad_s2
    axes = k.turn_axes_world[0]
    omega, omega_body = k.omega_world_rad_s[0], k.omega_body_rad_s[0]
    alpha = k.alpha_world_rad_s2[0]
    along, turning = k.alpha_along_axes_world_rad_s2[0], k.alpha_turning_axes_world_rad_s2[0]
    J = angle_rate_matrix_body(angles, seq)
    det_J = float(np.linalg.det(J))

    recovered, _ = k.recovered_rates(0)
    if recovered is not None:
        back = Step(
            "Back from ω to the angle rates",
            r"\{\omega\}_{xyz} = [J(\theta)]\,\dot{\bar\theta}\ \Rightarrow\ "
            r"\dot{\bar\theta} = [J]^{-1}\{\omega\}_{xyz},"
            r"\quad |\det J| = |\sin\theta_2|\ \text{(proper) or } |\cos\theta_2|\ \text{(Tait–Bryan)}",
            {"det_J": det_J, "theta_dot_back": recovered},
            {"det_J": "", "theta_dot_back": "rad/s"},
        )
    else:
        sign = float(seq.lock_combination_sign(angles[1]))
        back = Step(
            "Back from ω to the angle rates: impossible here (gimbal lock)",
            r"\det J = 0:\ \bar n_3 \parallel \bar n_1,\ \text{so } \bar\omega \text{ fixes only } "
            r"\dot\theta_1 \pm \dot\theta_3 = \bar\omega\cdot\bar n_1",
            {"det_J": det_J, "theta1_dot_pm_theta3_dot": float(rates[0] + sign * rates[2])},
            {"det_J": "", "theta1_dot_pm_theta3_dot": "rad/s"},
        )

    def attitude(s: float) -> np.ndarray:
        return matrix_from_angles(motion.angles(np.array([s]))[0], seq)

    def omega_at(s: float) -> np.ndarray:
        return motion.kinematics(np.array([s])).omega_world_rad_s[0]

    h = DIFFERENCE_STEP_S
    R = attitude(t)
    spin_matrix = _difference(attitude, t, h) @ R.T
    omega_from_R = 0.5 * np.array(
        [
            spin_matrix[2, 1] - spin_matrix[1, 2],
            spin_matrix[0, 2] - spin_matrix[2, 0],
            spin_matrix[1, 0] - spin_matrix[0, 1],
        ]
    )
    alpha_from_omega = _difference(omega_at, t, h)
    a1, a2, a3 = (seq.axis_label(j) for j in (1, 2, 3))
    steps = (
        Step(
            "The angles and their rates at the instant",
            r"\theta_k(t) = \theta_k(0) + \dot\theta_k(0)\,t + \tfrac12\ddot\theta_k t^2,\quad "
            r"\dot\theta_k(t) = \dot\theta_k(0) + \ddot\theta_k t",
            {"t": t, "theta": np.degrees(angles), "theta_dot": rates, "theta_ddot": accelerations},
            {"t": "s", "theta": "deg", "theta_dot": "rad/s", "theta_ddot": "rad/s²"},
        ),
        Step(
            f"The three turn axes: {a1} fixed, {a2} carried by the first turn, {a3} by the first two",
            r"\bar n_1 = \bar e_{a_1},\quad \bar n_2 = [R_{a_1}(\theta_1)]\,\bar e_{a_2},\quad "
            r"\bar n_3 = [R_{a_1}(\theta_1)][R_{a_2}(\theta_2)]\,\bar e_{a_3}",
            {"n_1": axes[0], "n_2": axes[1], "n_3": axes[2]},
            {"n_1": "", "n_2": "", "n_3": ""},
        ),
        Step(
            "Angular velocity: the rates add along their own axes",
            r"\bar\omega = \dot\theta_1\bar n_1 + \dot\theta_2\bar n_2 + \dot\theta_3\bar n_3,\quad "
            r"\{\omega\}_{xyz} = [R]^{\mathsf T}\{\omega\}_{XYZ}",
            {"omega_XYZ": omega, "omega_xyz": omega_body, "|omega|": float(np.linalg.norm(omega))},
            {"omega_XYZ": "rad/s", "omega_xyz": "rad/s", "|omega|": "rad/s"},
        ),
        Step(
            "Angular acceleration: the axes' own rates add the cross products",
            r"\bar\alpha = \sum_k \ddot\theta_k\bar n_k + \dot\theta_1\bar n_1\times\dot\theta_2\bar n_2 + "
            r"(\dot\theta_1\bar n_1 + \dot\theta_2\bar n_2)\times\dot\theta_3\bar n_3",
            {"alpha_along_axes": along, "alpha_turning_axes": turning, "alpha": alpha},
            {"alpha_along_axes": "rad/s²", "alpha_turning_axes": "rad/s²", "alpha": "rad/s²"},
        ),
        back,
        Step(
            "Check: ω from the rate of the attitude matrix, and α by differencing ω",
            r"[\tilde\omega] = \dot{[R]}\,[R]^{\mathsf T},\quad \dot{[R]} \approx "
            r"\frac{[R](t-2h) - 8[R](t-h) + 8[R](t+h) - [R](t+2h)}{12h},\quad "
            r"\bar\alpha \approx \frac{\bar\omega(t-2h) - 8\bar\omega(t-h) + 8\bar\omega(t+h) - \bar\omega(t+2h)}{12h}",
            {
                "omega": omega,
                "omega_from_R_dot": omega_from_R,
                "alpha": alpha,
                "alpha_differenced": alpha_from_omega,
                "h": h,
            },
            {
                "omega": "rad/s",
                "omega_from_R_dot": "rad/s",
                "alpha": "rad/s²",
                "alpha_differenced": "rad/s²",
                "h": "s",
            },
        ),
    )
    outputs = {
        "t_s": t,
        "omega_world_rad_s": omega,
        "omega_body_rad_s": omega_body,
        "alpha_world_rad_s2": alpha,
        "alpha_along_axes_rad_s2": along,
        "alpha_turning_axes_rad_s2": turning,
        "gimbal_lock": AT_GIMBAL_LOCK if recovered is None else CLEAR_OF_GIMBAL_LOCK,
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="tilted-ride-angular-velocity",
    title="A tilted fairground ride: angular velocity and acceleration from three angle rates",
    chapter=3,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "t_s": "s",
        "omega_world_rad_s": "rad/s",
        "omega_body_rad_s": "rad/s",
        "alpha_world_rad_s2": "rad/s²",
        "alpha_along_axes_rad_s2": "rad/s²",
        "alpha_turning_axes_rad_s2": "rad/s²",
        "gimbal_lock": "",
    },
    section="3.4",
    story=ExampleStory(
        situation=(
            "A fairground ride carries a disc of seats on an arm. The central tower turns the arm about the "
            "vertical at $\\dot\\theta_1 = 0.6$ rad/s, the disc's axis is tilted $\\theta_2 = 40°$ from the "
            "vertical, and the disc spins about its own axis at $\\dot\\theta_3 = 2.0$ rad/s: a 3-1-3 "
            "sequence of precession, nutation and spin, the same angles that describe a spinning top. The "
            "operator can also make any of the angles speed up at a constant rate."
        ),
        wanted=(
            "At the instant $t$ (1 s by default): the disc's angular velocity $\\bar\\omega$ in fixed and in "
            "disc components, its angular acceleration $\\bar\\alpha$ split into the part from the angle "
            "accelerations and the part from the turning of the axes, and, going backwards, the three rates "
            "that a gyroscope on the disc measuring $\\bar\\omega$ would report."
        ),
        approach=(
            "Each angle turns the disc about its own axis, so the rates simply add as vectors along the three "
            "turn axes; we only need those axes at the instant, which the first one or two turns carry round. "
            "Differentiating the sum gives $\\bar\\alpha$ with one cross product for every axis that is carried "
            "by an earlier turn. The other route, differentiating the rotation matrix and reading $\\bar\\omega$ "
            "from $\\dot{[R]}[R]^{\\mathsf T}$, needs nine derivatives of products of sines and cosines and "
            "then a second derivative for $\\bar\\alpha$: it is kept for the check. Going back from "
            "$\\bar\\omega$ to the rates is a $3\\times3$ solve whose determinant is $\\pm\\sin\\theta_2$ here."
        ),
        check=(
            "The angular velocity is defined by the attitude's own rate of change, "
            "$[\\tilde\\omega] = \\dot{[R]}[R]^{\\mathsf T}$. The last step differences the rotation matrix in "
            "time, with no turn axes at all, reads $\\bar\\omega$ from the skew-symmetric result and prints it "
            "beside the sum of the rates; it then differences $\\bar\\omega$ itself and prints the result beside "
            "the formula for $\\bar\\alpha$. Both pairs agree to about ten significant figures."
        ),
        what_if=(
            "Set all three angle accelerations to zero: $\\bar\\alpha$ does not vanish, because the spin axis "
            "is carried round by the tower; its size is $\\dot\\theta_1\\dot\\theta_3\\sin\\theta_2$. Then "
            "move **θ2(0)** to 0°. The spin axis falls onto the tower's axis, the rate arrows in the scene "
            "line up, and the step going back from $\\bar\\omega$ reports gimbal lock with only "
            "$\\dot\\theta_1 + \\dot\\theta_3$ left to find."
        ),
    ),
)
