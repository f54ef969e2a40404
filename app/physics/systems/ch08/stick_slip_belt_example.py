"""Worked example ``stick-slip-cycle``: the stick–slip cycle of a block on a moving belt, in closed form.

System, frame and inputs (the six that shape the cycle; the start does not): :mod:`app.physics.systems.ch08.
stick_slip_belt` (the lesson 8.2 friction scene's model). x (m) along the belt from the spring's anchor, the belt at
the constant speed v_b, N = m g, Coulomb friction with μ_s (stick) and μ_k (slip), μ_k < μ_s.

Once the block has stuck to the belt it rides with it until the spring force reaches μ_s N at
``x_break = sign(v_b) μ_s N / k``; it then slips, harmonically about ``x_eq = sign(v_b) μ_k N / k``, and its relative
velocity returns to zero at the mirror point ``x_stick = 2 x_eq − x_break``, where ``k |x_stick| ≤ μ_s N``: it sticks
again. The durations are those of :func:`~app.physics.systems.ch08.stick_slip_belt.limit_cycle`.

Check: over one cycle the block returns to the same state, so the work the belt does through friction must equal the
energy friction dissipates by sliding: ``W_belt = ∫ F v_b dt`` against ``E_diss = μ_k N ∫ |v_rel| dt``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from app.physics.core.parameters import ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch08.stick_slip_belt import PARAMETERS, limit_cycle

_USED = ("mass_kg", "stiffness_N_m", "belt_speed_m_s", "mu_static", "mu_kinetic", "g_m_s2")


def _check(values: Mapping[str, Any]) -> None:
    if PARAMETERS.check is not None:
        PARAMETERS.check(values)
    if values["belt_speed_m_s"] == 0.0:
        raise ParameterError(
            "belt_speed_m_s",
            "a belt at rest drives no cycle: the block's swings shrink by 2 μ_k N / k each until friction holds it",
        )
    if not values["mu_kinetic"] < values["mu_static"]:
        raise ParameterError(
            "mu_kinetic",
            "with μ_k = μ_s there is no stick phase to return to (the block slips in one unbroken harmonic motion "
            "that only grazes the belt's speed); make μ_k smaller than μ_s",
        )


INPUTS = ParameterSet(tuple(PARAMETERS.by_name[name] for name in _USED), check=_check)


def solve(inputs: Mapping[str, Any]) -> Solution:
    _check(inputs)
    m, k, v_b = inputs["mass_kg"], inputs["stiffness_N_m"], inputs["belt_speed_m_s"]
    mu_s, mu_k, g = inputs["mu_static"], inputs["mu_kinetic"], inputs["g_m_s2"]
    cycle = limit_cycle({**inputs, "x0_m": 0.0, "v0_m_s": 0.0})
    assert cycle is not None  # v_b ≠ 0 and μ_k < μ_s: checked above
    normal = m * g
    omega = math.sqrt(k / m)
    direction = math.copysign(1.0, v_b)
    x_break, x_stick = cycle.stick_to_m, cycle.stick_from_m
    x_eq = direction * mu_k * normal / k
    d = (mu_s - mu_k) * normal / k
    amplitude = math.hypot(d, v_b / omega)
    phase = math.pi + 2.0 * math.atan(abs(v_b) / (omega * d))

    # Energy over one cycle (J). Stick: F = k x while x goes from x_stick to x_break at v_b. Slip: F = sign(v_b) μ_k N.
    belt_work_stick = 0.5 * k * (x_break**2 - x_stick**2)
    belt_work_slip = abs(v_b) * mu_k * normal * cycle.slip_s
    sliding_distance = abs((x_stick - x_break) - v_b * cycle.slip_s)  # |∫ v_rel dt| over the slip: one sign
    dissipated = mu_k * normal * sliding_distance
    energy_scale = 0.5 * (mu_s * normal) ** 2 / k + 0.5 * m * v_b**2

    steps = (
        Step(
            "Normal force, friction limits and the slip frequency",
            r"N = m g,\quad F_s = \mu_s N,\quad F_k = \mu_k N,\quad \omega = \sqrt{k/m}",
            {"N": normal, "F_s": mu_s * normal, "F_k": mu_k * normal, "omega": omega},
            {"N": "N", "F_s": "N", "F_k": "N", "omega": "rad/s"},
        ),
        Step(
            "Stick: the block rides with the belt until the spring needs more than static friction",
            r"\dot x = v_b,\quad F = k x,\quad |k x| \le \mu_s N\ \Rightarrow\ x_{\rm break} = "
            r"\operatorname{sign}(v_b)\,\frac{\mu_s N}{k}",
            {"x_break": x_break},
            {"x_break": "m"},
        ),
        Step(
            "Slip: harmonic about x_eq, starting at x_break with the belt's speed",
            r"m\ddot x = -k x + \operatorname{sign}(v_b)\,\mu_k N,\quad x_{\rm eq} = \operatorname{sign}(v_b)\,"
            r"\frac{\mu_k N}{k},\quad d = \frac{(\mu_s-\mu_k)N}{k},\quad A = \sqrt{d^2 + (v_b/\omega)^2}",
            {"x_eq": x_eq, "d": d, "A": amplitude},
            {"x_eq": "m", "d": "m", "A": "m"},
        ),
        Step(
            "Slip ends where the block's speed is the belt's again: at the mirror point, after the phase ωt_slip",
            r"x_{\rm stick} = 2x_{\rm eq} - x_{\rm break},\quad \omega t_{\rm slip} = \pi + 2\arctan\frac{|v_b|}"
            r"{\omega d},\quad |k\,x_{\rm stick}| = |2\mu_k - \mu_s|\,N \le \mu_s N \ \text{(it sticks)}",
            {
                "x_stick": x_stick,
                "omega_t_slip": phase,
                "t_slip": cycle.slip_s,
                "k_x_stick": k * x_stick,
                "F_s": mu_s * normal,
            },
            {"x_stick": "m", "omega_t_slip": "rad", "t_slip": "s", "k_x_stick": "N", "F_s": "N"},
        ),
        Step(
            "The cycle: stick from x_stick to x_break at the belt's speed, then slip back",
            r"t_{\rm stick} = \frac{|x_{\rm break} - x_{\rm stick}|}{|v_b|} = \frac{2d}{|v_b|},\quad T = "
            r"t_{\rm stick} + t_{\rm slip}",
            {"t_stick": cycle.stick_s, "t_slip": cycle.slip_s, "T": cycle.period_s},
            {"t_stick": "s", "t_slip": "s", "T": "s"},
        ),
        Step(
            "Check: over one cycle the belt's work through friction equals the energy friction dissipates",
            r"W_{\rm belt} = \int F v_b\,dt = \tfrac12 k\left(x_{\rm break}^2 - x_{\rm stick}^2\right) + |v_b|\,\mu_k N"
            r"\,t_{\rm slip},\qquad E_{\rm diss} = \mu_k N \left|\,x_{\rm stick} - x_{\rm break} - v_b t_{\rm slip}"
            r"\right|",
            {
                "W_belt_stick": belt_work_stick,
                "W_belt_slip": belt_work_slip,
                "W_belt": belt_work_stick + belt_work_slip,
                "E_diss": dissipated,
            },
            {"W_belt_stick": "J", "W_belt_slip": "J", "W_belt": "J", "E_diss": "J"},
            scales={"W_belt_stick": energy_scale, "W_belt": energy_scale},
        ),
    )
    outputs = {
        "break_position_m": x_break,
        "stick_position_m": x_stick,
        "stick_time_s": cycle.stick_s,
        "slip_time_s": cycle.slip_s,
        "period_s": cycle.period_s,
        "slip_amplitude_m": amplitude,
        "dissipated_per_cycle_J": dissipated,
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="stick-slip-cycle",
    title="Stick–slip: the cycle of a block on a moving belt, and the energy it passes on",
    chapter=8,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "break_position_m": "m",
        "stick_position_m": "m",
        "stick_time_s": "s",
        "slip_time_s": "s",
        "period_s": "s",
        "slip_amplitude_m": "m",
        "dissipated_per_cycle_J": "J",
    },
    section="8.2",
    story=ExampleStory(
        situation=(
            "A 1 kg block rests on a conveyor belt running at 0.5 m/s and is held back by a spring of stiffness "
            "20 N/m anchored beside the belt. The contact has static friction $\\mu_s = 0.6$ and kinetic friction "
            "$\\mu_k = 0.4$, and $g = 9.807$ m/s². These are the scene's controls; the block's start ($x_0$, "
            "$\\dot x_0$) does not change the cycle, only how it is reached."
        ),
        wanted=(
            "The repeating motion the block settles into: where it breaks loose and where it sticks again, how long "
            "it sticks and how long it slips, the period of the cycle, and how much energy friction turns into heat "
            "in each cycle."
        ),
        approach=(
            "Coulomb friction is a set, not a function of the sliding speed. So we do not integrate a smoothed "
            "friction law, which would be stiff and would blur the instant of sticking. Instead we split the "
            "motion into **modes**. While stuck, the block moves with the belt and friction is whatever the spring "
            "needs, up to $\\mu_s N$. While slipping, friction is exactly $\\mu_k N$ and the motion is harmonic, "
            "which has a closed form. Each mode ends at an event we can solve for: $k|x| = \\mu_s N$, or the relative "
            "velocity returning to zero. Chaining the closed forms gives the cycle exactly, with no step size at all."
        ),
        check=(
            "Over one full cycle the block comes back to the same position and speed, so its kinetic and spring "
            "energy are unchanged. All the work the belt does on the block through friction must therefore leave "
            "as heat from sliding. The last step computes the belt's work, stick and slip parts separately, beside "
            "the energy dissipated, $\\mu_k N$ times the distance slid relative to the belt; the two must agree."
        ),
        what_if=(
            "Raise **μ_k** towards **μ_s**: the stick phase shrinks (it lasts $2d/|v_b|$ with $d = (\\mu_s - "
            "\\mu_k)N/k$), the slip phase lengthens towards a whole period $2\\pi/\\omega$, and the heat per cycle "
            "grows, because the block slides farther against a larger force. Raising the **belt speed** does much "
            "the same. From the scene's start at rest at the anchor, the block only catches the belt if "
            "$\\mu_k g/\\omega \\ge v_b$ (0.88 m/s here); beyond that the scene shows pure slip, and this cycle is "
            "never reached."
        ),
    ),
)
