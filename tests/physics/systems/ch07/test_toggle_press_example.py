"""The toggle press's two released constraints (worked example ``toggle-press-two-releases``, section 7.1) against an
independent computation: central differences of the loads' potential along each released mechanism, built from its
own geometry (circle intersections), with no virtual displacement written by hand.

Release 1 (slider free along AC): ``V(θ) = P y_B + W₁ y_G₁ + W₂ y_G₂`` and ``δW = −V′ δθ − Q x_C′ δθ = 0``, so
``Q = −V′/x_C′``. Release 2 (x_C held, C free across AC): with s = y_C the mechanism's coordinate, B is where the
circles of radius a about A and b about C meet, and ``C_y = dV/ds`` at s = 0.

Tolerance 1e-7 relative: a central difference with step h = 1e-5 (rad or m) has truncation error about h²/6 times the
third derivative (≈ 1e-11 of the value for these O(1 m) geometries, a little more near the toggle, where Q ∝ 1/θ
grows fast) and round-off about 1e-16/h = 1e-11; 1e-7 leaves a wide margin for both yet would catch any wrong term (a
missing weight changes the answer by percent).
"""

from __future__ import annotations

import math

import pytest

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch07.toggle_press_example import EXAMPLE

H = 1e-5
RTOL = 1e-7

CASES = [
    {},
    {"bar_AB_m": 0.6, "bar_BC_m": 1.1, "angle_deg": 35.0, "load_B_N": 800.0, "weight_AB_N": 30.0, "weight_BC_N": 70.0},
    {"bar_AB_m": 1.5, "bar_BC_m": 1.0, "angle_deg": 25.0, "load_B_N": 200.0, "weight_AB_N": 120.0, "weight_BC_N": 10.0},
    {"angle_deg": 3.0},
    {"load_B_N": -300.0, "weight_AB_N": 400.0, "weight_BC_N": 100.0, "angle_deg": 50.0},
]


def _potential(P, W1, W2, knee, slider):
    """V of the loads (J): each load times the height of its point (they all point down)."""
    return P * knee[1] + W1 * 0.5 * knee[1] + W2 * 0.5 * (knee[1] + slider[1])


def _press_force(a, b, theta, P, W1, W2):
    def at(angle):
        knee = (a * math.cos(angle), a * math.sin(angle))
        slider = (a * math.cos(angle) + math.sqrt(b * b - (a * math.sin(angle)) ** 2), 0.0)
        return _potential(P, W1, W2, knee, slider), slider[0]

    (v_plus, x_plus), (v_minus, x_minus) = at(theta + H), at(theta - H)
    return -((v_plus - v_minus) / (2 * H)) / ((x_plus - x_minus) / (2 * H))


def _guide_force(a, b, theta, P, W1, W2):
    x_c = a * math.cos(theta) + math.sqrt(b * b - (a * math.sin(theta)) ** 2)

    def at(s):
        d = math.hypot(x_c, s)
        ux, uy = x_c / d, s / d
        along = (a * a - b * b + d * d) / (2 * d)
        across = math.sqrt(a * a - along * along)
        knee = (along * ux - across * uy, along * uy + across * ux)  # the branch above AC, as the press stands
        return _potential(P, W1, W2, knee, (x_c, s))

    return (at(H) - at(-H)) / (2 * H)


@pytest.mark.parametrize("changes", CASES)
def test_both_forces_match_central_differences_of_the_potential(changes):
    values = EXAMPLE.inputs.validate(changes)
    a, b, theta = values["bar_AB_m"], values["bar_BC_m"], math.radians(values["angle_deg"])
    P, W1, W2 = values["load_B_N"], values["weight_AB_N"], values["weight_BC_N"]
    outputs = EXAMPLE.solve(values).outputs
    assert outputs["press_force_N"] == pytest.approx(_press_force(a, b, theta, P, W1, W2), rel=RTOL)
    assert outputs["guide_force_N"] == pytest.approx(_guide_force(a, b, theta, P, W1, W2), rel=RTOL)


def test_defaults_give_the_lessons_numbers():
    outputs = EXAMPLE.solve(EXAMPLE.inputs.defaults()).outputs
    assert outputs["press_force_N"] == pytest.approx(755.556, rel=1e-6)
    assert outputs["guide_force_N"] == pytest.approx(300.0, rel=1e-12)  # equal bars: P/2 + W₁/4 + 3 W₂/4, whatever θ


@pytest.mark.parametrize("changes", CASES)
def test_the_check_step_agrees_with_newton(changes):
    check = EXAMPLE.solve(EXAMPLE.inputs.validate(changes)).steps[-1]
    assert check.title.startswith("Check")
    v = check.values
    assert v["Q_virtual_work"] == pytest.approx(v["Q_Newton"], rel=1e-12)
    assert v["C_y_virtual_work"] == pytest.approx(v["C_y_Newton"], rel=1e-12, abs=1e-9)


def test_with_equal_bars_the_guide_force_does_not_depend_on_the_angle():
    for angle in (3.0, 20.0, 60.0):
        values = EXAMPLE.inputs.validate({"angle_deg": angle, "weight_AB_N": 40.0, "weight_BC_N": 120.0})
        assert EXAMPLE.solve(values).outputs["guide_force_N"] == pytest.approx(
            500 / 2 + 40 / 4 + 3 * 120 / 4, rel=1e-12
        )


def test_the_toggle_position_is_refused_naming_the_angle():
    with pytest.raises(ParameterError, match="toggle position") as refused:
        EXAMPLE.inputs.validate({"angle_deg": 0.0})
    assert refused.value.field == "angle_deg"
    with pytest.raises(ValueError, match="toggle position"):  # solve refuses too, called without the check
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), "angle_deg": 0.0})


def test_a_bar_too_short_to_reach_the_guide_is_refused():
    with pytest.raises(ParameterError):
        EXAMPLE.inputs.validate({"bar_AB_m": 2.0, "bar_BC_m": 0.5, "angle_deg": 60.0})
