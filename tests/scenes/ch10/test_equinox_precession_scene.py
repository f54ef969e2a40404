"""The equinox scene's readout of how far the axis has turned: whole turns are counted, never wrapped away.

The angle is φ = Ω t with Ω the worked example's precession rate; 725.29° is two turns and 5.29°, and the
readout must say so (it once showed "5.29°"). The scene's clock is set to reach the angle exactly, so the
value is compared with the closed form to 1e-9° (a few ulps of 725°, times the few operations between).
"""

from __future__ import annotations

import math

import pytest

from app.physics.systems.ch10 import equinox_precession as physics
from app.scenes.ch10.equinox_precession import EquinoxPrecessionScene, turns_and_degrees


def turned(scene) -> object:
    return next(q for q in scene.readout().quantities if q.name == "precession_angle_deg")


def test_the_axis_turned_725_degrees_reads_two_turns_and_5_29_degrees(client):
    scene = EquinoxPrecessionScene(client, EquinoxPrecessionScene.parameters.defaults())
    rate_deg_per_year = math.degrees(scene.result.rate_rad_s) * physics.JULIAN_YEAR_S

    def turn_to(angle_deg: float) -> None:
        scene.t_s = angle_deg / rate_deg_per_year / scene.params["years_per_second"]
        scene.redraw()

    turn_to(725.29)
    quantity = turned(scene)
    assert quantity.value == pytest.approx(725.29, abs=1e-9) and quantity.unit == "deg"
    assert quantity.text == "2 turns + 5.29°"
    assert "2 turns + 5.29° westward" in scene.time_label.text
    turn_to(400.5)  # one turn: singular
    assert turned(scene).text == "1 turn + 40.50°"
    turn_to(12.25)  # under a turn: the number alone, no words
    assert turned(scene).value == pytest.approx(12.25, abs=1e-9) and turned(scene).text == ""
    assert "turned 12.25° westward" in scene.time_label.text
    scene.close()


def test_turns_and_degrees_never_shows_a_full_turn_as_360_degrees():
    assert turns_and_degrees(5.29) == "5.29°"
    assert turns_and_degrees(719.999) == "2 turns + 0.00°"
    assert turns_and_degrees(1080.0) == "3 turns + 0.00°"
