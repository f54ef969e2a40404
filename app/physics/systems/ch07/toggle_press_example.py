"""Worked example ``toggle-press-two-releases`` (section 7.1): two unknown forces of the toggle press by virtual work,
one released constraint each.

The press is :class:`~app.physics.systems.ch07.virtual_work.TogglePress` (same frame and inputs as the scene
``virtual-work-frame``: A at the origin, x along AC, y up; θ the angle of AB above AC). Two constraints are released
in turn, each leaving a mechanism with the one degree of freedom θ:

* the slider's hold along AC (C free to move along x, the guide kept): ``δx_C = x_C′ δθ`` and Q (on C along −x) follows
  from ``Σ F·r′ − Q x_C′ = 0`` (:func:`~app.physics.systems.ch07.virtual_work.holding_force_by_virtual_work`);
* the guide's hold across AC (x_C held, C free to move along y): bar BC stays rigid, so
  ``(r_C − r_B)·(δr_C − δr_B) = 0`` gives ``δy_C = x_C δθ`` at y_C = 0, and the guide's push C_y (up, on C) follows
  from ``C_y x_C + Σ F·r′ = 0``.

The check is the member-by-member equilibrium of both bars
(:func:`~app.physics.systems.ch07.virtual_work.toggle_equilibrium`): six equations, four of whose unknowns virtual work
never needed. At θ = 0 (bars in line) no finite Q holds the loads: a ParameterError (a ValueError) naming
``angle_deg`` says so, from the inputs' check and from :func:`solve`.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.parameters import ParameterError, ParameterSet
from app.physics.core.solution import ExampleStory, Solution, Step, WorkedExample
from app.physics.systems.ch07.virtual_work import (
    TOGGLE_PARAMETERS,
    TogglePositionError,
    TogglePress,
    holding_force_by_virtual_work,
    toggle_equilibrium,
)


def press_force(press: TogglePress) -> float:
    """Q (N) by virtual work; at the toggle position (θ = 0, bars in line) a :class:`ParameterError` naming
    ``angle_deg`` (so the API answers 422 and the page marks the θ control)."""
    try:
        return holding_force_by_virtual_work(press)
    except TogglePositionError:
        raise ParameterError(
            "angle_deg",
            "at θ = 0° the bars lie in line (the toggle position): δx_C = 0 for every δθ, so the press force Q does "
            "no virtual work and no finite Q holds the loads; choose θ above 0°",
        ) from None


def _check(values: Mapping[str, Any]) -> None:
    if TOGGLE_PARAMETERS.check is not None:
        TOGGLE_PARAMETERS.check(values)  # bar BC must reach the guide
    press_force(TogglePress.from_params(values))


INPUTS = ParameterSet(TOGGLE_PARAMETERS.parameters, check=_check)


def guide_release_displacements(press: TogglePress) -> dict[str, np.ndarray]:
    """δr/δθ (m per rad, (2,)) of B, C, G₁, G₂ when C is held along x but free across AC (the guide released).

    B and G₁ move as before; ``δr_C = (0, x_C) δθ`` (bar BC rigid, C at y = 0); G₂ averages B and C.
    """
    knee = press.virtual_displacements()["B"]
    slider = np.array([0.0, float(press.points()["C"][0])])
    return {"B": knee, "C": slider, "G1": 0.5 * knee, "G2": 0.5 * (knee + slider)}


def guide_force_by_virtual_work(press: TogglePress) -> float:
    """C_y (N, the guide's push on C, up positive) from ``C_y δy_C + Σ F·δr = 0`` with the guide released."""
    moved = guide_release_displacements(press)
    loads = float(sum(force @ moved[point] for point, force in press.loads().items()))
    return -loads / float(moved["C"][1])


def solve(inputs: Mapping[str, Any]) -> Solution:
    press = TogglePress.from_params(inputs)
    theta = press.angle_rad
    q_force = press_force(press)  # a ParameterError (a ValueError) at the toggle position
    points = press.points()
    first = press.virtual_displacements()
    loads = press.loads()
    first_work = press.load_virtual_work_N_m()
    second = guide_release_displacements(press)
    second_work = float(sum(force @ second[point] for point, force in loads.items()))
    c_force = guide_force_by_virtual_work(press)
    newton = toggle_equilibrium(press)
    steps = (
        Step(
            "Geometry at the angle θ",
            r"\bar r_B = a(\cos\theta,\ \sin\theta),\quad x_C = a\cos\theta + \sqrt{b^2 - a^2\sin^2\theta},\quad "
            r"\bar r_{G_1} = \tfrac12\bar r_B,\quad \bar r_{G_2} = \tfrac12(\bar r_B + \bar r_C)",
            {"theta": theta, "r_B": points["B"], "x_C": float(points["C"][0]), "r_G2": points["G2"]},
            {"theta": "rad", "r_B": "m", "x_C": "m", "r_G2": "m"},
        ),
        Step(
            "Release 1, the slider's hold along AC: virtual displacements per unit δθ",
            r"\bar r_B' = a(-\sin\theta,\ \cos\theta),\quad x_C' = -a\sin\theta\Big(1 + \frac{a\cos\theta}"
            r"{\sqrt{b^2 - a^2\sin^2\theta}}\Big),\quad \bar r_{G_1}' = \tfrac12\bar r_B',\quad "
            r"\bar r_{G_2}' = \tfrac12(\bar r_B' + x_C'\,\bar i)",
            {"r_B'": first["B"], "x_C'": float(first["C"][0]), "r_G1'": first["G1"], "r_G2'": first["G2"]},
            {"r_B'": "m/rad", "x_C'": "m/rad", "r_G1'": "m/rad", "r_G2'": "m/rad"},
        ),
        Step(
            "δW = 0 for every δθ gives the press force Q",
            r"\delta W = \big(-P\,y_B' - W_1\,y_{G_1}' - W_2\,y_{G_2}' - Q\,x_C'\big)\,\delta\theta = 0"
            r"\ \Rightarrow\ Q = \frac{-P\,y_B' - W_1\,y_{G_1}' - W_2\,y_{G_2}'}{x_C'}",
            {"sum_F_r'": first_work, "Q": q_force},
            {"sum_F_r'": "N·m/rad", "Q": "N"},
        ),
        Step(
            "Release 2, the guide's hold across AC (x_C held): virtual displacements per unit δθ",
            r"(\bar r_C - \bar r_B)\cdot(\delta\bar r_C - \delta\bar r_B) = 0,\ \delta x_C = 0\ \Rightarrow\ "
            r"y_C' = \frac{(\bar r_C - \bar r_B)\cdot\bar r_B'}{y_C - y_B} = x_C,\quad "
            r"\bar r_{G_2}' = \tfrac12(\bar r_B' + x_C\,\bar j)",
            {"y_C'": float(second["C"][1]), "r_G2'": second["G2"]},
            {"y_C'": "m/rad", "r_G2'": "m/rad"},
        ),
        Step(
            "δW = 0 again gives the guide's push C_y (Q does no work now: δx_C = 0)",
            r"\delta W = \big(C_y\,x_C - P\,y_B' - W_1\,y_{G_1}' - W_2\,y_{G_2}'\big)\,\delta\theta = 0"
            r"\ \Rightarrow\ C_y = \frac{P\,a\cos\theta + \tfrac12 W_1\,a\cos\theta + \tfrac12 W_2\,(a\cos\theta + "
            r"x_C)}{x_C}",
            {"sum_F_r'": second_work, "C_y": c_force},
            {"sum_F_r'": "N·m/rad", "C_y": "N"},
        ),
        Step(
            "Check: both bars cut free, six equilibrium equations solved together",
            r"\text{AB: } \bar A - \bar B - (P + W_1)\,\bar j = 0,\ M_A = 0;\quad \text{BC: } \bar B + C_y\,\bar j - "
            r"Q\,\bar i - W_2\,\bar j = 0,\ M_B = 0",
            {
                "Q_virtual_work": q_force,
                "Q_Newton": newton.holding_force_N,
                "C_y_virtual_work": c_force,
                "C_y_Newton": newton.guide_C_N,
                "A_Newton": newton.pin_A_N,
                "B_Newton": newton.pin_B_N,
            },
            {
                "Q_virtual_work": "N",
                "Q_Newton": "N",
                "C_y_virtual_work": "N",
                "C_y_Newton": "N",
                "A_Newton": "N",
                "B_Newton": "N",
            },
        ),
    )
    outputs = {
        "press_force_N": q_force,
        "guide_force_N": c_force,
        "slider_rate_m_per_rad": float(first["C"][0]),
    }
    return Solution(outputs=outputs, steps=steps)


EXAMPLE = WorkedExample(
    id="toggle-press-two-releases",
    title="A toggle press: the press force and the guide's push, one released constraint each",
    chapter=7,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "press_force_N": "N",
        "guide_force_N": "N",
        "slider_rate_m_per_rad": "m/rad",
    },
    section="7.1",
    story=ExampleStory(
        situation=(
            "A toggle press stands still. Bar $AB$ ($a$) is pinned to the ground at $A$ and bar $BC$ ($b$) joins it "
            "at the knee $B$; $C$ is the pin of a slider on a smooth guide along $AC$, and $AB$ makes the angle "
            "$\\theta$ with $AC$. A load $P$ pushes down on the knee, the bars weigh $W_1$ and $W_2$, and a "
            "workpiece pushes back on the slider with $Q$ along $-x$. The guide pushes up or down on the slider "
            "with $C_y$."
        ),
        wanted=(
            "Two of the press's unknown forces and nothing else: the force $Q$ the press exerts on the workpiece "
            "and the guide's push $C_y$ on the slider, for the angle and loads set by the controls."
        ),
        approach=(
            "Virtual work finds a constraint force by letting that constraint go and nothing else. To find $Q$ we "
            "free the slider along its guide; to find $C_y$ we hold the slider along $x$ and free it across the "
            "guide instead. Each time the two bars become a mechanism with the single coordinate $\\theta$, every "
            "point's virtual displacement is its position differentiated with respect to $\\theta$, and "
            "$\\delta W = 0$ is one scalar equation with one unknown. The pins at $A$ and $B$ never appear. Newton's "
            "way would cut both bars free and solve six equations in six unknowns, four of them ($A_x$, $A_y$, "
            "$B_x$, $B_y$) forces nobody asked for."
        ),
        check=(
            "The last step solves exactly those six equations of both bars' equilibrium as one linear system and "
            "sets its $Q$ and $C_y$ beside the two virtual-work answers. They must agree to round-off, because "
            "both methods state the same equilibrium; a wrong sign or a missing factor in any virtual "
            "displacement would show at once as a difference in the third or fourth figure."
        ),
        what_if=(
            "Move **θ** down towards 0 with the scene's slider. The slider's virtual displacement $x_C'$ shrinks "
            "like $\\theta$, so $Q$ grows like $1/\\theta$: about 756 N at 20°, over 5000 N at 3°. The guide's "
            "push $C_y$ does not grow, because $\\delta y_C = x_C\\,\\delta\\theta$ stays large: with equal bars "
            "it stays at $P/2 + W_1/4 + 3W_2/4$ (300 N at the defaults) whatever $\\theta$. In the scene, "
            "watch the green arrow at $C$ shrink as the bars come into line; at exactly 0° the example refuses, "
            "since no finite $Q$ can hold the load."
        ),
    ),
)
