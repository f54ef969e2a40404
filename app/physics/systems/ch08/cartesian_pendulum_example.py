"""Worked example ``cartesian-pendulum-drift``: a consistent start, the multiplier, and the drift of the rod's length.

System, frame and the first seven inputs: :mod:`app.physics.systems.ch08.cartesian_pendulum_model` (the lesson 8.2
scene's model): a bob of mass m at (x, y) on a massless rod of length L from the pivot at the origin, y up, gravity
along −y, the rod as the constraint ``g = (L² − x² − y²)/2 = 0``. The requested start is moved the least distance
onto the circle and its velocity onto the tangent; the index-1 form ``[m I, −Cᵀ; C, 0] [a; λ] = [f; c]`` gives the
multiplier λ (N/m; the rod's tension is λ L) and the bob's acceleration.

Drift: the index-1 equations are integrated by the classical fourth-order Runge–Kutta method with the fixed step
``step_s`` for ``duration_s`` seconds, once without any correction (the position residual g grows by the
integration error, O(h⁴)) and once with a projection back onto the circle and its tangent after every step.

Check: the tension from the multiplier against the polar form ``m L θ̇² + m g cos θ``, and the consistent start
against the project's general algorithm (:func:`~app.physics.constrained.initial_conditions.
consistent_initial_conditions`, a Gauss–Newton projection that knows nothing about circles).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.constrained.initial_conditions import consistent_initial_conditions
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch08.cartesian_pendulum import pendulum_system
from app.physics.systems.ch08.cartesian_pendulum_model import CartesianPendulum

_SCENE = CartesianPendulum.parameters
#: Most Runge–Kutta steps one solution takes (each run), so that a page's request stays quick.
MAX_STEPS = 6000
#: A run whose speed exceeds this multiple of the fastest speed its energy allows (√(2 g L + v₀²)), or whose bob is
#: more than 2 L from the pivot, has diverged: the step is too long for the motion (h times its fastest rate ≳ 3).
DIVERGED_SPEED_FACTOR = 10.0


def _check(values: Mapping[str, Any]) -> None:
    if math.hypot(values["x0_m"], values["y0_m"]) == 0.0:
        raise ParameterError("y0_m", "a start at the pivot has no nearest point on the rod's circle: move it off")
    if _SCENE.check is not None:
        try:
            _SCENE.check(values)
        except ParameterError:
            raise
        except ValueError as exc:  # named, so that the API answers 422, not 500
            raise ParameterError("y0_m", str(exc)) from None
    steps = values["duration_s"] / values["step_s"]
    if steps > MAX_STEPS:
        raise ParameterError(
            "step_s",
            f"{values['duration_s']:g} s in steps of {values['step_s']:g} s is {steps:.0f} steps, more than "
            f"{MAX_STEPS}: take a longer step or a shorter duration",
        )


INPUTS = ParameterSet(
    (
        *_SCENE.parameters,
        Parameter("step_s", "s", 1.0 / 30.0, 0.002, 0.2, "Fixed Runge–Kutta step h of the drift runs", "h", step=0.001),
        Parameter("duration_s", "s", 10.0, 0.5, 60.0, "How long the drift runs integrate", "t_end", step=0.5),
    ),
    check=_check,
)


def _rk4(
    state: np.ndarray, g: float, length: float, step: float, n_steps: int, project: bool
) -> tuple[float, float, float, float] | None:
    """Integrate ``(x, y, ẋ, ẏ)`` by RK4 on the index-1 pendulum; optionally project onto g = 0, C v = 0 after every
    step. Returns the final state, or None when the run diverges (see :data:`DIVERGED_SPEED_FACTOR`)."""
    speed_limit2 = DIVERGED_SPEED_FACTOR**2 * (2.0 * g * length + float(state[2] ** 2 + state[3] ** 2) + 1e-300)

    def rate(x: float, y: float, vx: float, vy: float) -> tuple[float, float, float, float]:
        per_mass = (vx * vx + vy * vy - g * y) / (x * x + y * y)  # λ/m from C M⁻¹Cᵀ λ = c − C M⁻¹ f
        return vx, vy, -per_mass * x, -g - per_mass * y

    x, y, vx, vy = (float(s) for s in state)
    h = step
    for _ in range(n_steps):
        k1 = rate(x, y, vx, vy)
        k2 = rate(x + 0.5 * h * k1[0], y + 0.5 * h * k1[1], vx + 0.5 * h * k1[2], vy + 0.5 * h * k1[3])
        k3 = rate(x + 0.5 * h * k2[0], y + 0.5 * h * k2[1], vx + 0.5 * h * k2[2], vy + 0.5 * h * k2[3])
        k4 = rate(x + h * k3[0], y + h * k3[1], vx + h * k3[2], vy + h * k3[3])
        x += h / 6.0 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        y += h / 6.0 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        vx += h / 6.0 * (k1[2] + 2 * k2[2] + 2 * k3[2] + k4[2])
        vy += h / 6.0 * (k1[3] + 2 * k2[3] + 2 * k3[3] + k4[3])
        if project:
            radius = math.hypot(x, y)
            x, y = length * x / radius, length * y / radius
            radial = (vx * x + vy * y) / (length * length)
            vx, vy = vx - radial * x, vy - radial * y
        if not (x * x + y * y <= 4.0 * length * length and vx * vx + vy * vy <= speed_limit2):
            return None  # off by more than the rod's length, much faster than the energy allows, or not finite
    return x, y, vx, vy


def solve(inputs: Mapping[str, Any]) -> Solution:
    m, length, g = float(inputs["mass_kg"]), float(inputs["length_m"]), float(inputs["g_m_s2"])
    q0 = np.array([inputs["x0_m"], inputs["y0_m"]], dtype=float)
    v0 = np.array([inputs["vx0_m_s"], inputs["vy0_m_s"]], dtype=float)
    radius0 = float(np.hypot(*q0))
    if radius0 == 0.0:
        raise ParameterError("y0_m", "a start at the pivot has no nearest point on the rod's circle: move it off")
    n_steps = max(1, round(inputs["duration_s"] / inputs["step_s"]))
    if n_steps > MAX_STEPS:
        raise ParameterError("step_s", f"{n_steps} steps is more than {MAX_STEPS}: take a longer step")

    residual0 = 0.5 * (length**2 - radius0**2)
    rate_residual0 = -float(q0 @ v0)
    q = length * q0 / radius0
    unit = q / length
    v = v0 - float(v0 @ unit) * unit

    jacobian = -q[None, :]
    convective = np.array([float(v @ v)])
    forces = np.array([0.0, -m * g])
    augmented = np.block([[m * np.eye(2), -jacobian.T], [jacobian, np.zeros((1, 1))]])
    a_x, a_y, multiplier = (float(s) for s in np.linalg.solve(augmented, np.concatenate([forces, convective])))
    tension = multiplier * length

    start = np.concatenate([q, v])
    free = _rk4(start, g, length, inputs["step_s"], n_steps, project=False)
    projected = _rk4(start, g, length, inputs["step_s"], n_steps, project=True)
    if free is None or projected is None:
        fastest = (math.sqrt(g / length) + math.sqrt(float(v @ v)) / length) * inputs["step_s"]
        raise ParameterError(
            "step_s",
            f"the RK4 run diverges: a step of {inputs['step_s']:g} s is too long for this motion (h times its "
            f"fastest rate is {fastest:.3g}); take a shorter step, a slower start or a longer rod",
        )

    def energy(state: tuple[float, ...] | np.ndarray) -> float:
        return 0.5 * m * (state[2] ** 2 + state[3] ** 2) + m * g * state[1]

    def residual(state: tuple[float, ...]) -> float:
        return 0.5 * (length**2 - state[0] ** 2 - state[1] ** 2)

    energy0 = energy(start)
    speed_scale = math.sqrt(g * length) + math.sqrt(float(v @ v))
    energy_scale = m * (g * length + float(v @ v)) + 1e-300

    theta = math.atan2(q[0], -q[1])
    theta_rate = float(q[0] * v[1] - q[1] * v[0]) / length**2
    tension_polar = m * length * theta_rate**2 + m * g * math.cos(theta)
    general = consistent_initial_conditions(pendulum_system(m, length, g), q0, v0)

    steps = (
        Step(
            "Residuals of the requested start",
            r"g(\bar q_0) = \tfrac12\left(L^2 - x_0^2 - y_0^2\right),\qquad C\bar v_0 = -(x_0\dot x_0 + y_0\dot y_0)",
            {"g_0": residual0, "Cv_0": rate_residual0},
            {"g_0": "m²", "Cv_0": "m²/s"},
            scales={"g_0": length**2, "Cv_0": length * speed_scale},
        ),
        Step(
            "Consistent position: the nearest point of the circle",
            r"\bar q = L\,\frac{\bar q_0}{|\bar q_0|},\qquad \Delta\bar q = \bar q - \bar q_0",
            {"q": q, "Delta_q": q - q0},
            {"q": "m", "Delta_q": "m"},
            scales={"Delta_q": length},
        ),
        Step(
            "Consistent velocity: remove the part along the rod (the least change with C v = 0)",
            r"\bar v = \bar v_0 - (\bar v_0\cdot\hat e_r)\,\hat e_r,\quad \hat e_r = \bar q/L",
            {"v": v, "Delta_v": v - v0},
            {"v": "m/s", "Delta_v": "m/s"},
            scales={"v": speed_scale, "Delta_v": speed_scale},
        ),
        Step(
            "Multiplier and accelerations from the index-1 form",
            r"\begin{bmatrix} m I & -C^{\mathsf T}\\ C & 0\end{bmatrix}\begin{bmatrix}\bar a\\ \lambda\end{bmatrix}"
            r" = \begin{bmatrix}0\\ -m g\\ \dot x^2 + \dot y^2\end{bmatrix},\quad C = (-x,\ -y),\quad T = \lambda L",
            {"a": np.array([a_x, a_y]), "lambda": multiplier, "T": tension},
            {"a": "m/s²", "lambda": "N/m", "T": "N"},
            scales={"a": g + speed_scale**2 / length},
        ),
        Step(
            "Drift: RK4 on the index-1 equations, uncorrected and projected after each step",
            r"g(t_{\rm end}) = \tfrac12\left(L^2 - x^2 - y^2\right),\quad \Delta L = \sqrt{x^2+y^2} - L,\quad "
            r"\Delta E = E(t_{\rm end}) - E(0)",
            {
                "steps": n_steps,
                "g_end_uncorrected": residual(free),
                "Delta_L_uncorrected": math.hypot(free[0], free[1]) - length,
                "Delta_E_uncorrected": energy(free) - energy0,
                "g_end_projected": residual(projected),
                "Delta_E_projected": energy(projected) - energy0,
            },
            {
                "steps": "",
                "g_end_uncorrected": "m²",
                "Delta_L_uncorrected": "m",
                "Delta_E_uncorrected": "J",
                "g_end_projected": "m²",
                "Delta_E_projected": "J",
            },
            scales={
                "g_end_uncorrected": length**2,
                "Delta_L_uncorrected": length,
                "Delta_E_uncorrected": energy_scale,
                "g_end_projected": length**2,
                "Delta_E_projected": energy_scale,
            },
        ),
        Step(
            "Check: the tension in polar form, and the general Gauss–Newton projection of the start",
            r"T = m L\dot\theta^2 + m g\cos\theta,\quad \theta = \operatorname{atan2}(x, -y),\ \dot\theta = "
            r"\frac{x\dot y - y\dot x}{L^2};\qquad \min|\Delta\bar q| \text{ s.t. } g = 0,\ \min|\Delta\bar v|"
            r" \text{ s.t. } C\bar v = 0",
            {
                "T_multiplier": tension,
                "T_polar": tension_polar,
                "q_general": general.q,
                "v_general": general.v,
            },
            {"T_multiplier": "N", "T_polar": "N", "q_general": "m", "v_general": "m/s"},
            scales={"v_general": speed_scale},
        ),
    )
    outputs = {
        "consistent_position_m": q,
        "consistent_velocity_m_s": v,
        "multiplier_N_m": multiplier,
        "tension_N": tension,
        "drift_uncorrected_m2": residual(free),
        "drift_projected_m2": residual(projected),
        "energy_change_uncorrected_J": energy(free) - energy0,
        "energy_change_projected_J": energy(projected) - energy0,
    }
    return Solution(
        outputs=outputs,
        steps=steps,
        output_scales={
            "consistent_velocity_m_s": speed_scale,
            "drift_uncorrected_m2": length**2,
            "drift_projected_m2": length**2,
            "energy_change_uncorrected_J": energy_scale,
            "energy_change_projected_J": energy_scale,
        },
    )


EXAMPLE = WorkedExample(
    id="cartesian-pendulum-drift",
    title="The pendulum in x and y: a consistent start, the rod's force, and how far the rod drifts",
    chapter=8,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "consistent_position_m": "m",
        "consistent_velocity_m_s": "m/s",
        "multiplier_N_m": "N/m",
        "tension_N": "N",
        "drift_uncorrected_m2": "m²",
        "drift_projected_m2": "m²",
        "energy_change_uncorrected_J": "J",
        "energy_change_projected_J": "J",
    },
    section="8.2",
    story=ExampleStory(
        situation=(
            "A 1 kg bob hangs on a 1 m massless rod, described by its Cartesian position $(x, y)$, with the rod "
            "as the constraint $x^2 + y^2 = L^2$. We ask to start it at $(x_0, y_0) = (0.8, -0.6)$ m at rest, "
            "with $g = 9.81$ m/s². A requested start need not lie on the circle: the scene's controls $x_0$, "
            "$y_0$, $\\dot x_0$, $\\dot y_0$ set any point and any velocity."
        ),
        wanted=(
            "A start that satisfies the rod at position and velocity level, changed as little as possible. Then "
            "the multiplier $\\lambda$ and the rod's tension at that start. Finally, how far the rod's length "
            "drifts when the equations are integrated for 10 s in fixed steps of 1/30 s, with and without a "
            "correction."
        ),
        approach=(
            "Two coordinates and one constraint make an index-3 differential-algebraic system. Differentiating "
            "the constraint twice gives the index-1 form: a linear system for the acceleration and $\\lambda$ "
            "that any ODE solver can integrate. That form only enforces $\\ddot g = 0$, so it needs a start with "
            "$g = 0$ and $\\dot g = 0$; for a circle the least change is a radial projection and removing the "
            "velocity's radial part. Even from a consistent start, integration errors let $g$ wander, so we "
            "compare an uncorrected run with one projected after every step. The angle $\\theta$ alone "
            "(chapter 7) has no drift, but needs a new derivation for every system."
        ),
        check=(
            "The rod's tension found from the multiplier must equal the polar-coordinate result $mL\\dot\\theta^2 "
            "+ mg\\cos\\theta$: the centripetal force plus the weight's component along the rod. The project's "
            "general algorithm for consistent starts uses Gauss–Newton steps on $g(\\bar q) = 0$ and a "
            "minimum-norm velocity correction, with no idea that the constraint is a circle, and must land on "
            "the same position and velocity."
        ),
        what_if=(
            "Move **y₀** from −0.6 to −0.3 m: the requested point is now inside the circle. Step 2 pushes it out "
            "along its radius to about $(0.94, -0.35)$ m, a higher start with a larger swing, so the drift grows "
            "too. Then give the bob a **horizontal velocity ẋ₀**: only its part across the rod survives step 3. "
            "In the scene, choose the *uncorrected* method and watch the bob leave the grey circle."
        ),
    ),
)
