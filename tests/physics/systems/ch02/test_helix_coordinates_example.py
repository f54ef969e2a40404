"""Worked example ``helix-cylindrical-spherical`` (2.3) against an existing project model.

Independent: :class:`~app.physics.systems.ch02.coordinate_paths.CoordinatePath` (the curvilinear-coordinates
scene's model) writes the helix's Cartesian position as a sympy expression, differentiates it exactly and finds the
cylindrical and spherical coordinates, rates and components from the Cartesian motion
(:mod:`app.physics.math.curvilinear`, e.g. Ṙ = (x ẋ + y ẏ)/R); the example instead uses hand-derived closed forms
for the helix (ṙ = z ż / r, φ̇ = −a ż / r², …). Both run in double precision.

Tolerance: 1e-12 of the natural scale (|v| for velocities, a ω² for accelerations, r for coordinates, ω and ω² for
the angle rates). Each side is a few dozen operations on O(1) numbers, exact to a few ulps (≈ 1e-15) of those
scales; the model's conversion divides by R² and r, at least 0.01 m² and 0.1 m here, which can cost a factor ~1e2.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch02.coordinate_paths import CoordinatePath
from app.physics.systems.ch02.helix_coordinates_example import EXAMPLE

RTOL = 1e-12

CASES = [
    {},
    {"size_m": 0.5, "azimuth_rate_rad_s": 2.5, "path_angle_deg": 40.0, "t_s": 1.3},
    {"size_m": 3.0, "azimuth_rate_rad_s": 0.1, "path_angle_deg": 0.0, "t_s": 10.0},
    {"size_m": 0.1, "azimuth_rate_rad_s": 3.0, "path_angle_deg": 60.0, "t_s": 4.0},
    {"size_m": 1.7, "azimuth_rate_rad_s": 0.7, "path_angle_deg": 80.0, "t_s": 0.0},
]


def _close(actual, expected, scale):
    assert np.all(np.abs(np.asarray(actual, float) - np.asarray(expected, float)) <= RTOL * scale), (actual, expected)


@pytest.mark.parametrize("changes", CASES)
def test_both_descriptions_match_the_scene_model(changes):
    inputs = EXAMPLE.inputs.validate(changes)
    a, omega, t = inputs["size_m"], inputs["azimuth_rate_rad_s"], inputs["t_s"]
    path = CoordinatePath("helix", a, omega, math.radians(inputs["path_angle_deg"]))
    position, velocity, acceleration, cyl = path.describe("cylindrical", t)
    *_, sph = path.describe("spherical", t)
    out = EXAMPLE.solve(inputs).outputs
    speed, a_scale = float(np.linalg.norm(velocity[0])), a * omega**2
    r = float(np.linalg.norm(position[0]))
    _close(out["velocity_m_s"], velocity[0], speed)
    _close(out["acceleration_m_s2"], acceleration[0], a_scale)
    _close(out["speed_m_s"], speed, speed)
    _close(out["cylindrical_velocity_m_s"], cyl.velocity[0], speed)
    _close(out["cylindrical_acceleration_m_s2"], cyl.acceleration[0], a_scale)
    _close(out["spherical_velocity_m_s"], sph.velocity[0], speed)
    _close(out["spherical_acceleration_m_s2"], sph.acceleration[0], a_scale)
    r_out, phi_out, theta_out = out["r_m"], out["phi_rad"], out["theta_rad"]
    _close(r_out, sph.coordinates[0, 0], r)
    _close(phi_out, sph.coordinates[0, 1], 1.0)
    # The model's azimuth is atan2(y, x) in (−π, π]; the example's is ω t, unwrapped.
    _close(math.remainder(theta_out - sph.coordinates[0, 2], 2.0 * math.pi), 0.0, 1.0 + abs(theta_out))


@pytest.mark.parametrize("changes", CASES)
def test_the_check_step_rebuilds_one_vector_three_ways(changes):
    inputs = EXAMPLE.inputs.validate(changes)
    solution = EXAMPLE.solve(inputs)
    check = solution.steps[-1]
    assert check.title.startswith("Check")
    speed = solution.outputs["speed_m_s"]
    a_scale = inputs["size_m"] * inputs["azimuth_rate_rad_s"] ** 2
    for how in ("cylindrical", "spherical"):
        _close(check.values[f"v ({how})"], check.values["v (Cartesian)"], speed)
        _close(check.values[f"a ({how})"], check.values["a (Cartesian)"], a_scale)


def test_defaults_have_the_lesson_s_cylindrical_components():
    out = EXAMPLE.solve(EXAMPLE.inputs.defaults()).outputs
    # Lesson 2.3, the Helix preset: v_R = 0, v_θ = 1 m/s, v_z = tan 15° m/s, a = −1 m/s² e_R.
    _close(out["cylindrical_velocity_m_s"], [0.0, 1.0, math.tan(math.radians(15.0))], 1.0)
    _close(out["cylindrical_acceleration_m_s2"], [-1.0, 0.0, 0.0], 1.0)


def test_a_vertical_helix_is_refused():
    with pytest.raises(ParameterError, match="infinitely at 90°") as caught:
        EXAMPLE.inputs.validate({"path_angle_deg": 90.0})
    assert caught.value.field == "path_angle_deg"
    with pytest.raises(ValueError, match="keep β"):
        EXAMPLE.solve({**EXAMPLE.inputs.defaults(), "path_angle_deg": 89.5})
