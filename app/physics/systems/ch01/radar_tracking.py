"""Worked Example 1.2: a ground radar tracking an aircraft.

Frame: fixed xyz at the radar, z vertical. The radar measures range r(t) (m),
azimuth theta(t) (rad, horizontal plane, from x toward y) and elevation beta(t)
(rad, above the horizontal):

    r = 2000 + 100 t,  theta = (pi/2)(1 - exp(-0.15 t)),  beta = pi/3 - 0.1 sqrt(t)

Position: x = r cos(beta) cos(theta), y = r cos(beta) sin(theta), z = r sin(beta).
The velocity is found (a) by a central difference [p(t+h) - p(t-h)] / (2h) and
(b) exactly by the chain rule; the difference between them is the finite
difference's error, which falls as h^2 (truncation) until round-off, growing as
eps |p| / h, takes over.

The radar's own frame gives the same motion without xyz: velocity and
acceleration along e_r (line of sight), e_theta (horizontal, azimuth growing)
and e_beta (elevation growing) from r, theta, beta and their first and second
rates (:func:`velocity_radar_components`, :func:`acceleration_radar_components`).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Plot, PlotSeries, Solution, Step, WorkedExample


def _check_interval_fits(values: Mapping[str, Any]) -> None:
    if values["dt_s"] > values["t_s"]:
        raise ParameterError(
            "dt_s", f"must not exceed the time t = {values['t_s']:g} s (the elevation formula needs t − Δt ≥ 0)"
        )


INPUTS = ParameterSet(
    (
        Parameter("t_s", "s", 2.0, 1.0, 60.0, "Instant at which the velocity is wanted", "t", step=0.1),
        Parameter(
            "dt_s",
            "s",
            1e-3,
            1e-12,
            1.0,
            "Half-width h of the central difference [p(t+h) − p(t−h)]/(2h)",
            "Δt",
            scale="log",
        ),
    ),
    check=_check_interval_fits,
)

#: Sweep of the difference interval for the error plot (s).
SWEEP_DT_S = np.logspace(-12, 0, 97)


def radar_measurements(t_s: np.ndarray | float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Range (m), azimuth (rad), elevation (rad) at time ``t_s`` (s, t ≥ 0)."""
    t = np.asarray(t_s, dtype=float)
    r = 2000.0 + 100.0 * t
    theta = 0.5 * np.pi * (1.0 - np.exp(-0.15 * t))
    beta = np.pi / 3.0 - 0.1 * np.sqrt(t)
    return r, theta, beta


def radar_rates(t_s: float) -> tuple[float, float, float]:
    """Time derivatives of range (m/s), azimuth (rad/s), elevation (rad/s) at t ≥ 0 (the last is −inf at t = 0)."""
    r_dot = 100.0
    theta_dot = 0.5 * np.pi * 0.15 * np.exp(-0.15 * t_s)
    beta_dot = -0.05 / np.sqrt(t_s) if t_s > 0.0 else -np.inf
    return r_dot, theta_dot, beta_dot


def radar_second_rates(t_s: float) -> tuple[float, float, float]:
    """Second time derivatives of range (m/s²), azimuth (rad/s²), elevation (rad/s²); needs t > 0."""
    r_ddot = 0.0
    theta_ddot = -0.5 * np.pi * 0.15**2 * np.exp(-0.15 * t_s)
    beta_ddot = 0.025 * t_s**-1.5
    return r_ddot, theta_ddot, beta_ddot


def _check_rates_defined(t_s: float) -> None:
    if not t_s > 0.0:
        raise ValueError(f"undefined at t = {t_s:g} s: the elevation rate −0.05/√t is infinite at t = 0")


def velocity_radar_components(t_s: float) -> np.ndarray:
    """Velocity (m/s) on the radar's axes (e_r, e_theta, e_beta), shape (3,); ValueError for t ≤ 0.

    v_r = ṙ, v_theta = r cos(beta) θ̇, v_beta = r β̇.
    """
    _check_rates_defined(t_s)
    r, _, beta = (float(v) for v in radar_measurements(t_s))
    r_dot, theta_dot, beta_dot = radar_rates(t_s)
    return np.array([r_dot, r * np.cos(beta) * theta_dot, r * beta_dot])


def acceleration_radar_components(t_s: float) -> np.ndarray:
    """Acceleration (m/s²) on the radar's axes (e_r, e_theta, e_beta), shape (3,); ValueError for t ≤ 0.

    a_r = r̈ − r β̇² − r cos²(beta) θ̇², a_theta = r cos(beta) θ̈ + 2 ṙ cos(beta) θ̇ − 2 r sin(beta) β̇ θ̇,
    a_beta = r β̈ + 2 ṙ β̇ + r sin(beta) cos(beta) θ̇².
    """
    _check_rates_defined(t_s)
    r, _, beta = (float(v) for v in radar_measurements(t_s))
    r_dot, theta_dot, beta_dot = radar_rates(t_s)
    r_ddot, theta_ddot, beta_ddot = radar_second_rates(t_s)
    cb, sb = np.cos(beta), np.sin(beta)
    return np.array(
        [
            r_ddot - r * beta_dot**2 - r * cb**2 * theta_dot**2,
            r * cb * theta_ddot + 2.0 * r_dot * cb * theta_dot - 2.0 * r * sb * beta_dot * theta_dot,
            r * beta_ddot + 2.0 * r_dot * beta_dot + r * sb * cb * theta_dot**2,
        ]
    )


def radar_axes(t_s: float) -> np.ndarray:
    """The radar's unit vectors at time ``t_s`` (s) as rows on xyz, shape (3, 3): e_r (line of sight), e_theta
    (horizontal, azimuth growing), e_beta (elevation growing)."""
    _, theta, beta = (float(v) for v in radar_measurements(t_s))
    cb, sb, ct, st = np.cos(beta), np.sin(beta), np.cos(theta), np.sin(theta)
    return np.array([[cb * ct, cb * st, sb], [-st, ct, 0.0], [-sb * ct, -sb * st, cb]])


def position(t_s: np.ndarray | float) -> np.ndarray:
    """Aircraft position (m) on xyz; shape (3,) or (N, 3)."""
    r, theta, beta = radar_measurements(t_s)
    return np.stack([r * np.cos(beta) * np.cos(theta), r * np.cos(beta) * np.sin(theta), r * np.sin(beta)], axis=-1)


def velocity_exact(t_s: float) -> np.ndarray:
    """Velocity (m/s) on xyz by differentiating each component with the chain rule."""
    r, theta, beta = (float(v) for v in radar_measurements(t_s))
    r_dot, theta_dot, beta_dot = radar_rates(t_s)
    cb, sb, ct, st = np.cos(beta), np.sin(beta), np.cos(theta), np.sin(theta)
    return np.array(
        [
            r_dot * cb * ct - r * sb * beta_dot * ct - r * cb * st * theta_dot,
            r_dot * cb * st - r * sb * beta_dot * st + r * cb * ct * theta_dot,
            r_dot * sb + r * cb * beta_dot,
        ]
    )


def velocity_central_difference(t_s: float, dt_s: float) -> np.ndarray:
    """Velocity (m/s) estimated as [p(t + dt) − p(t − dt)] / (2 dt); needs t ≥ dt."""
    if dt_s > t_s:
        raise ValueError("dt_s must not exceed t_s: the elevation formula needs t - dt >= 0")
    return (position(t_s + dt_s) - position(t_s - dt_s)) / (2.0 * dt_s)


def solve(inputs: Mapping[str, Any]) -> Solution:
    t, h = inputs["t_s"], inputs["dt_s"]
    r, theta, beta = (float(v) for v in radar_measurements(t))
    r_dot, theta_dot, beta_dot = radar_rates(t)
    p = position(t)
    v_fd = velocity_central_difference(t, h)
    v_exact = velocity_exact(t)
    error = float(np.linalg.norm(v_fd - v_exact))
    v_radar = velocity_radar_components(t)

    sweep_dt = SWEEP_DT_S[SWEEP_DT_S <= t]
    sweep_error = np.array([np.linalg.norm(velocity_central_difference(t, d) - v_exact) for d in sweep_dt])
    # Truncation model (h^2/6)|p'''| with p''' from a wide central difference of the
    # exact velocity, and the round-off model eps|p|/h: their sum is least at h*.
    third = (velocity_exact(t + 1e-2) - 2 * velocity_exact(t) + velocity_exact(t - 1e-2)) / 1e-4
    third_norm = float(np.linalg.norm(third))
    eps = float(np.finfo(float).eps)
    optimal_dt = (3.0 * eps * float(np.linalg.norm(p)) / third_norm) ** (1.0 / 3.0)
    best = int(np.argmin(sweep_error))

    steps = (
        Step(
            "Radar readings and their rates",
            r"r = 2000 + 100t,\ \ \theta = \tfrac{\pi}{2}(1-e^{-0.15t}),\ \ \beta = \tfrac{\pi}{3} - 0.1\sqrt{t};\quad "
            r"\dot r = 100,\ \ \dot\theta = 0.075\pi e^{-0.15t},\ \ \dot\beta = -\frac{0.05}{\sqrt t}",
            {"r": r, "θ": theta, "β": beta, "ṙ": r_dot, "θ̇": theta_dot, "β̇": beta_dot},
            {"r": "m", "θ": "rad", "β": "rad", "ṙ": "m/s", "θ̇": "rad/s", "β̇": "rad/s"},
        ),
        Step(
            "Position on the fixed frame",
            r"\bar r = r\cos\beta\cos\theta\,\bar i + r\cos\beta\sin\theta\,\bar j + r\sin\beta\,\bar k",
            {"r_vec": p},
            {"r_vec": "m"},
        ),
        Step(
            "(a) Central difference",
            r"\bar v \approx \frac{\bar r(t+\Delta t) - \bar r(t-\Delta t)}{2\,\Delta t}",
            {"v_fd": v_fd, "dt": h},
            {"v_fd": "m/s", "dt": "s"},
        ),
        Step(
            "(b) Chain rule",
            r"\dot x = \dot r\cos\beta\cos\theta - r\dot\beta\sin\beta\cos\theta - r\dot\theta\cos\beta\sin\theta,\ "
            r"\dot y = \dot r\cos\beta\sin\theta - r\dot\beta\sin\beta\sin\theta + r\dot\theta\cos\beta\cos\theta,\ "
            r"\dot z = \dot r\sin\beta + r\dot\beta\cos\beta",
            {"v_exact": v_exact, "speed": float(np.linalg.norm(v_exact))},
            {"v_exact": "m/s", "speed": "m/s"},
        ),
        Step(
            "Error of the finite difference",
            r"|\bar v_{fd} - \bar v| \approx \frac{\Delta t^2}{6}\left|\dddot{\bar r}\right| + "
            r"\frac{\varepsilon\,|\bar r|}{\Delta t},"
            r"\quad \Delta t^{*} \approx \left(\frac{3\varepsilon|\bar r|}{|\dddot{\bar r}|}\right)^{1/3}",
            {
                "error": error,
                "third_derivative": third_norm,
                "optimal_dt_model": optimal_dt,
                "optimal_dt_measured": float(sweep_dt[best]),
            },
            {"error": "m/s", "third_derivative": "m/s³", "optimal_dt_model": "s", "optimal_dt_measured": "s"},
        ),
        Step(
            "Check: the radar's own axes give the same velocity",
            r"\bar v = \dot r\,\bar e_r + r\cos\beta\,\dot\theta\,\bar e_\theta + r\dot\beta\,\bar e_\beta,"
            r"\quad \bar e_r = \cos\beta\cos\theta\,\bar i + \cos\beta\sin\theta\,\bar j + \sin\beta\,\bar k,\ "
            r"\bar e_\theta = -\sin\theta\,\bar i + \cos\theta\,\bar j,\ "
            r"\bar e_\beta = -\sin\beta\cos\theta\,\bar i - \sin\beta\sin\theta\,\bar j + \cos\beta\,\bar k",
            {
                "v_radar": v_radar,
                "v (radar axes)": v_radar @ radar_axes(t),
                "v (chain rule)": v_exact,
                "speed (radar axes)": float(np.linalg.norm(v_radar)),
                "speed (chain rule)": float(np.linalg.norm(v_exact)),
            },
            {
                "v_radar": "m/s",
                "v (radar axes)": "m/s",
                "v (chain rule)": "m/s",
                "speed (radar axes)": "m/s",
                "speed (chain rule)": "m/s",
            },
        ),
    )
    plot = Plot(
        title=f"Central-difference error at t = {t:g} s",
        x_label="Δt (s)",
        y_label="|v_fd − v_exact| (m/s)",
        series=(
            PlotSeries("measured error", sweep_dt, sweep_error),
            PlotSeries("truncation model Δt²|r⃛|/6", sweep_dt, sweep_dt**2 * third_norm / 6.0),
            PlotSeries("round-off model ε|r|/Δt", sweep_dt, eps * float(np.linalg.norm(p)) / sweep_dt),
        ),
        log_x=True,
        log_y=True,
    )
    outputs = {
        "position_m": p,
        "velocity_fd_m_s": v_fd,
        "velocity_exact_m_s": v_exact,
        "fd_error_m_s": error,
        "optimal_dt_s": optimal_dt,
        "error_sweep_dt_s": sweep_dt,
        "error_sweep_m_s": sweep_error,
    }
    return Solution(outputs=outputs, steps=steps, plots=(plot,))


EXAMPLE = WorkedExample(
    id="1.2",
    title="Radar tracking: finite difference against the chain rule",
    chapter=1,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "position_m": "m",
        "velocity_fd_m_s": "m/s",
        "velocity_exact_m_s": "m/s",
        "fd_error_m_s": "m/s",
        "optimal_dt_s": "s",
        "error_sweep_dt_s": "s",
        "error_sweep_m_s": "m/s",
    },
    section="1.1",
    story=ExampleStory(
        situation=(
            "A ground radar at the origin of a fixed frame $xyz$ ($z$ up) tracks an aircraft. It reports the "
            "range $r = 2000 + 100t$ m, the azimuth $\\theta = \\tfrac{\\pi}{2}(1 - e^{-0.15t})$ rad measured "
            "from $x$ towards $y$, and the elevation $\\beta = \\tfrac{\\pi}{3} - 0.1\\sqrt t$ rad above "
            "the horizontal, with $t$ in seconds. We want the aircraft's velocity at $t = 2$ s."
        ),
        wanted=(
            "The aircraft's position and velocity on $xyz$ at the chosen instant, found twice: (a) by a central "
            "difference of two positions $\\Delta t = 1$ ms either side, as software fed only with positions "
            "would do, and (b) exactly; then how large the difference's error is and which $\\Delta t$ makes it "
            "smallest."
        ),
        approach=(
            "We convert the three readings to Cartesian components on the fixed frame first. Its unit vectors "
            "never turn, so the velocity is just the derivative of each component, taken exactly with the chain "
            "rule through $r(t)$, $\\theta(t)$ and $\\beta(t)$. The central difference needs no calculus at "
            "all, only positions, which is why tracking software uses it; its price is an error that we measure "
            "against the exact answer. Differentiating on the radar's own turning axes is a third route, but it "
            "needs the rates of those axes, which is chapter 2's subject."
        ),
        check=(
            "The radar's own axes give an independent route: along the line of sight the speed is $\\dot r$, "
            "across it horizontally $r\\cos\\beta\\,\\dot\\theta$ and across it vertically "
            "$r\\dot\\beta$. Put back on $xyz$ with the radar's unit vectors, these must rebuild the "
            "chain-rule velocity exactly, and the speeds must match. The last step computes both; they agree to "
            "round-off, while the central difference is off by the error shown above."
        ),
        what_if=(
            "Slide **Δt** down from 1 ms towards $10^{-12}$ s. At first the error falls as $\\Delta t^2$ (the "
            "truncation error), to about $3\\times10^{-8}$ m/s at $10^{-5}$ s, near the best $\\Delta t$ of "
            "about $4\\times10^{-5}$ s. Below that it rises again as round-off takes over, to about 0.05 m/s at "
            "$10^{-12}$ s. In the error plot below the steps, the measured error follows the truncation line, "
            "then the round-off line."
        ),
    ),
)
