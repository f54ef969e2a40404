"""Worked example ``rate-gyro-step``: a single-axis rate gyro meets a step in turn rate.

The instrument and its frames are those of :mod:`app.physics.systems.ch10.rate_gyro`: case axes input ``z`` (the case
turns at Ω about it), output ``x`` (the gimbal deflects by β about it against a spring k and a damper c), spin ``y``
(the rotor's spin ω_s, held constant by its motor). For small β the output equation is
``I_g β̈ + c β̇ + k β = I_a ω_s Ω``. The example finds the spin angular momentum, the steady deflection and gain, the
natural frequency and damping ratio, the step response's overshoot, peak time and settling time, and the steady
response to a sine at the frequency w. The closed forms are the project's (:func:`rate_gyro.steady_gain_s`,
:func:`rate_gyro.frequency_response` …); the check integrates the output equation numerically (scipy's DOP853 at
rtol 1e-11) from rest and sets β at the peak time (or at one undamped period, for a gimbal with ζ ≥ 1) beside the
closed form.

The inputs carry the names of the scene ``rate-gyro``'s controls (the scene's ``input_kind`` is not one: the example
works the step and gives the sine's steady amplitude beside it). A rotor without spin senses nothing and is refused.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from scipy.integrate import solve_ivp

from app.physics.core.parameters import ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch10 import rate_gyro

#: Relative tolerance of the check's integration (the closed form is exact; the integrator's error is far below the
#: six figures shown).
CHECK_RTOL = 1e-11

#: The scene's own controls (its ``input_kind`` aside: the example works both inputs), so the page's sliders drive it.
INPUTS = ParameterSet(
    tuple(
        rate_gyro.PARAMETERS.by_name[name]
        for name in (
            "rotor_axial_inertia_kg_m2",
            "spin_rad_s",
            "gimbal_inertia_kg_m2",
            "stiffness_N_m_rad",
            "damping_N_m_s_rad",
            "input_rate_rad_s",
            "input_frequency_rad_s",
        )
    ),
    check=rate_gyro._check,
)


def _params(inputs: Mapping[str, Any]) -> dict[str, Any]:
    """The inputs as the project's rate-gyro model reads them, for a step input."""
    return {**inputs, "input_kind": "step"}


def integrated_beta_rad(inputs: Mapping[str, Any], t_end_s: float) -> float:
    """β (rad) at ``t_end_s`` from integrating I_g β̈ + c β̇ + k β = I_a ω_s Ω₀ from rest (DOP853)."""
    J, c, k = inputs["gimbal_inertia_kg_m2"], inputs["damping_N_m_s_rad"], inputs["stiffness_N_m_rad"]
    moment = inputs["rotor_axial_inertia_kg_m2"] * inputs["spin_rad_s"] * inputs["input_rate_rad_s"]
    scale = abs(moment) / k
    result = solve_ivp(
        lambda _t, y: (y[1], (moment - c * y[1] - k * y[0]) / J),
        (0.0, t_end_s),
        (0.0, 0.0),
        method="DOP853",
        rtol=CHECK_RTOL,
        atol=(CHECK_RTOL * scale + 1e-300, CHECK_RTOL * scale * math.sqrt(k / J) + 1e-300),
    )
    return float(result.y[0, -1])


def solve(inputs: Mapping[str, Any]) -> Solution:
    rate_gyro._check(inputs)
    p = _params(inputs)
    H = rate_gyro.angular_momentum_N_m_s(p)
    gain = rate_gyro.steady_gain_s(p)
    omega0 = inputs["input_rate_rad_s"]
    beta_ss = gain * omega0
    wn = rate_gyro.natural_frequency_rad_s(p)
    zeta = rate_gyro.damping_ratio(p)
    c_crit = rate_gyro.critical_damping_N_m_s_rad(p)
    underdamped = zeta < 1.0
    if underdamped:
        wd = wn * math.sqrt((1.0 - zeta) * (1.0 + zeta))
        t_peak = math.pi / wd
        overshoot = math.exp(-zeta * math.pi / math.sqrt((1.0 - zeta) * (1.0 + zeta)))
        beta_peak = beta_ss * (1.0 + overshoot)
        response_values: dict[str, float] = {"ω_d": wd, "t_p": t_peak, "OS": overshoot, "β_peak": beta_peak}
        response_units = {"ω_d": "rad/s", "t_p": "s", "OS": "", "β_peak": "rad"}
        response_title = "Step response (ζ < 1): it overshoots, peaks at t_p and rings down"
        t_check = t_peak
        closed_check = beta_peak
    else:
        overshoot, beta_peak, t_peak = 0.0, beta_ss, math.nan
        response_values, response_units = {"β_peak": beta_peak}, {"β_peak": "rad"}
        response_title = "Step response (ζ ≥ 1): no overshoot, β creeps up to β_ss"
        t_check = 2.0 * math.pi / wn
        closed_check = float(rate_gyro.gimbal_response(p, t_check).beta_rad[0])
    if zeta > 0.0:
        # The slowest decay rate of the free response: ζω_n under critical damping, ω_n(ζ − √(ζ² − 1)) above it.
        slowest = zeta * wn if underdamped else wn / (zeta + math.sqrt((zeta - 1.0) * (zeta + 1.0)))
        response_values["t_s (2 %)"] = 4.0 / slowest
        response_units["t_s (2 %)"] = "s"
    w = inputs["input_frequency_rad_s"]
    ratio, lag = rate_gyro.frequency_response(p, w)
    sine_values: dict[str, float] = {"w/ω_n": w / wn, "lag": math.degrees(lag)}
    sine_units = {"w/ω_n": "", "lag": "deg"}
    if math.isfinite(ratio):
        sine_values = {"|β|/Ω₀": ratio, "β amplitude": ratio * abs(omega0), **sine_values}
        sine_units = {"|β|/Ω₀": "s", "β amplitude": "rad", **sine_units}
    integrated = integrated_beta_rad(inputs, t_check)
    steps = (
        Step(
            "Spin angular momentum of the rotor",
            r"H = I_a\,\omega_s",
            {"I_a": inputs["rotor_axial_inertia_kg_m2"], "ω_s": inputs["spin_rad_s"], "H": H},
            {"I_a": "kg·m²", "ω_s": "rad/s", "H": "N·m·s"},
        ),
        Step(
            "Moments about the output axis: turning H needs H Ω from the spring and damper; steady deflection",
            r"I_g\ddot\beta + c\dot\beta + k\beta = H\,\Omega(t),\qquad \beta_{ss} = \frac{H}{k}\,\Omega_0 = "
            r"G\,\Omega_0",
            {"G": gain, "β_ss": beta_ss, "β_ss (deg)": math.degrees(beta_ss)},
            {"G": "s", "β_ss": "rad", "β_ss (deg)": "deg"},
        ),
        Step(
            "Natural frequency and damping ratio of the gimbal",
            r"\omega_n = \sqrt{\frac{k}{I_g}},\qquad \zeta = \frac{c}{2\sqrt{k I_g}} = \frac{c}{c_{cr}}",
            {"ω_n": wn, "c_cr": c_crit, "ζ": zeta},
            {"ω_n": "rad/s", "c_cr": "N·m·s/rad", "ζ": ""},
        ),
        Step(
            response_title,
            r"\omega_d = \omega_n\sqrt{1-\zeta^2},\quad t_p = \frac{\pi}{\omega_d},\quad "
            r"\beta_{\max} = \beta_{ss}\left(1 + e^{-\zeta\pi/\sqrt{1-\zeta^2}}\right),\quad t_s \approx "
            r"\frac{4}{\zeta\,\omega_n}\ \ \left(\zeta > 1:\ \frac{4}{\omega_n(\zeta - \sqrt{\zeta^2 - 1})}\right)",
            response_values,
            response_units,
        ),
        Step(
            "Steady response to a sine input Ω₀ sin wt",
            r"\frac{|\beta|}{\Omega_0} = \frac{G}{\sqrt{(1-r^2)^2 + (2\zeta r)^2}},\quad \tan\varphi = "
            r"\frac{2\zeta r}{1-r^2},\quad r = \frac{w}{\omega_n}",
            sine_values,
            sine_units,
        ),
        Step(
            "Check: the output equation integrated numerically from rest",
            r"\beta(t_c)\ \text{closed form} \;=\; \int_0^{t_c}\!\dot\beta\,dt\ \text{(DOP853)},\qquad t_c = "
            r"\begin{cases} t_p & \zeta < 1\\ 2\pi/\omega_n & \zeta \ge 1\end{cases}",
            {"t_c": t_check, "β(t_c) closed form": closed_check, "β(t_c) integrated": integrated},
            {"t_c": "s", "β(t_c) closed form": "rad", "β(t_c) integrated": "rad"},
        ),
    )
    outputs = {
        "angular_momentum_N_m_s": H,
        "gain_s": gain,
        "steady_deflection_rad": beta_ss,
        "natural_frequency_rad_s": wn,
        "damping_ratio": zeta,
        "overshoot": overshoot,
        "peak_deflection_rad": beta_peak,
        "sine_amplitude_ratio_s": ratio if math.isfinite(ratio) else None,
        "sine_phase_lag_deg": math.degrees(lag),
    }
    if underdamped:
        outputs["peak_time_s"] = t_peak
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="rate-gyro-step",
    title="A rate gyro meets a step in turn rate",
    chapter=10,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "angular_momentum_N_m_s": "N·m·s",
        "gain_s": "s",
        "steady_deflection_rad": "rad",
        "natural_frequency_rad_s": "rad/s",
        "damping_ratio": "",
        "overshoot": "",
        "peak_deflection_rad": "rad",
        "peak_time_s": "s",
        "sine_amplitude_ratio_s": "s",
        "sine_phase_lag_deg": "deg",
    },
    section="10.3",
    story=ExampleStory(
        situation=(
            "A rate gyro of an autopilot has a rotor of axial moment $I_a = 2\\times10^{-4}$ kg·m² spinning at "
            "1000 rad/s (about 9500 rpm) in a gimbal of moment $I_g = 0.005$ kg·m² about its output axis, held by "
            "a torsion spring $k = 0.5$ N·m/rad and a damper $c = 0.02$ N·m·s/rad. The aircraft, at rest in yaw, "
            "suddenly starts turning at $\\Omega_0 = 0.5$ rad/s about the gyro's input axis."
        ),
        wanted=(
            "The deflection the gimbal settles to and its gain in radians per rad/s of turn rate; how fast the "
            "gimbal answers (natural frequency, damping ratio), how far it overshoots and when it peaks; and how a "
            "sine-wave turn rate at $w$ would be read."
        ),
        approach=(
            "We write the moment equation about the output axis only, in the case frame, which turns with the "
            "aircraft. Turning the spin angular momentum $H = I_a\\omega_s$ at rate $\\Omega$ needs a moment "
            "$H\\Omega$, and only the spring and damper can supply it, so the gimbal deflects until $k\\beta$ "
            "carries it. For small $\\beta$ that is a damped oscillator forced by $H\\Omega$, whose step and sine "
            "responses are textbook closed forms. The full three-axis Euler equations of rotor and gimbal would add "
            "terms in $\\Omega^2$ and $\\beta\\Omega$ that are smaller by the ratio $\\Omega/\\omega_s$ and change "
            "nothing a designer reads."
        ),
        check=(
            "The check integrates the output equation step by step from rest, with no formula for its solution, "
            "up to the peak time $t_p$ (or one undamped period when $\\zeta \\ge 1$). The integrated $\\beta(t_c)$ "
            "must agree with the closed-form peak $\\beta_{ss}(1 + \\mathrm{OS})$ to many figures: the two are "
            "independent routes to the same linear equation, so any slip in the overshoot or peak-time formula "
            "would show at once."
        ),
        what_if=(
            "Move the **damping c** up from 0.02 towards $c_{cr} = 0.1$ N·m·s/rad. The damping ratio climbs to 1, "
            "the overshoot falls from about 53 % to nothing and the settling time shortens; in the scene the red "
            "pointer stops ringing round the steady reading and creeps onto it. The steady deflection does not "
            "change: it depends only on $H\\Omega_0/k$. Past $c_{cr}$ the gimbal "
            "turns sluggish and takes ever longer to reach its reading."
        ),
    ),
)
