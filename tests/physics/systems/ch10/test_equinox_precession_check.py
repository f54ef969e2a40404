"""The equinox example's Check step (the orbit-averaged moment two ways) against an average taken in time.

Independent computation: the instantaneous MacCullagh moment per unit C, 3 (GM/r³) H (s·r̂)(r̂ × s), averaged over
equal steps of the *mean* anomaly (equal times, positions from Kepler's equation solved by Newton's method to
rounding), not over the true anomaly with time weights as the example sums; for the Moon also over the node longitude.
The integrand is smooth and periodic in the mean anomaly, so the equally spaced average converges exponentially; 2048
points reach rounding even at e = 0.9. Tolerance 1e-12 relative: both sides are sums of a few thousand terms of one
sign-pattern whose rounding stays near 1e-15, so 1e-12 leaves a thousandfold margin and no room for a wrong weight.
The existing outputs, step titles and the closing warning step are unchanged (tested in test_equinox_precession.py
and the API tests); here also that the check sits before any warning.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.systems.ch10.equinox_precession import EXAMPLE, mean_motion_rad_s

CASES = [
    {},  # the Earth today
    {"obliquity_deg": 70.0, "earth_orbit_eccentricity": 0.9, "moon_orbit_eccentricity": 0.5},
    {"moon_inclination_deg": 30.0, "moon_mass_ratio": 0.3, "obliquity_deg": 5.0, "dynamical_ellipticity": 0.02},
    {"sun_orbital_period_days": 88.0, "moon_orbital_period_days": 3.0, "moon_orbit_eccentricity": 0.0},
]
POINTS = 2048


def _time_average(gm_over_a3, e, incl, H, eps):
    s = np.array([math.sin(eps), 0.0, math.cos(eps)])
    mean = 2.0 * math.pi * np.arange(POINTS) / POINTS
    E = mean + e * np.sin(mean)
    for _ in range(60):
        E = E - (E - e * np.sin(E) - mean) / (1.0 - e * np.cos(E))
    x, y = np.cos(E) - e, math.sqrt(1.0 - e * e) * np.sin(E)  # r/a in the orbit's plane
    r = np.hypot(x, y)
    nodes = np.linspace(0.0, 2.0 * math.pi, 7, endpoint=False) if incl else np.zeros(1)
    total = np.zeros(3)
    for node in nodes:
        # (x, y) in the orbit plane → tilt by i about the node line → turn the node line by `node` about Z.
        px, py, pz = x, y * math.cos(incl), y * math.sin(incl)
        X = px * math.cos(node) - py * math.sin(node)
        Y = px * math.sin(node) + py * math.cos(node)
        unit = np.stack([X, Y, pz], axis=1) / r[:, None]
        moment = 3.0 * gm_over_a3 * H * ((unit @ s) / r**3)[:, None] * np.cross(unit, s)
        total += moment.mean(axis=0)
    return float(np.linalg.norm(total / len(nodes)))


@pytest.mark.parametrize("change", CASES)
def test_both_sides_of_the_check_equal_a_time_average_of_the_instantaneous_moment(change):
    inputs = EXAMPLE.inputs.validate(change)
    solution = EXAMPLE.solve(inputs)
    check = [step for step in solution.steps if step.title.startswith("Check")]
    assert len(check) == 1
    assert not any(step.title.startswith("Warning") for step in solution.steps[solution.steps.index(check[0]) :])
    values = check[0].values
    H, eps, mu = inputs["dynamical_ellipticity"], math.radians(inputs["obliquity_deg"]), inputs["moon_mass_ratio"]
    sun = _time_average(
        mean_motion_rad_s(inputs["sun_orbital_period_days"]) ** 2, inputs["earth_orbit_eccentricity"], 0.0, H, eps
    )
    moon = _time_average(
        mean_motion_rad_s(inputs["moon_orbital_period_days"]) ** 2 * mu / (1.0 + mu),
        inputs["moon_orbit_eccentricity"],
        math.radians(inputs["moon_inclination_deg"]),
        H,
        eps,
    )
    for side in ("formula", "summed"):
        assert values[f"M_sun/C ({side})"] == pytest.approx(sun, rel=1e-12)
        assert values[f"M_moon/C ({side})"] == pytest.approx(moon, rel=1e-12)
    # The precession rate is the averaged moment over C ω sin ε (the gyroscopic step), from either side.
    omega = inputs["earth_spin_rad_s"]
    assert solution.outputs["rate_rad_s"] == pytest.approx((sun + moon) / (omega * math.sin(eps)), rel=1e-12)


def test_the_check_comes_before_the_warning_when_the_model_is_stretched():
    inputs = EXAMPLE.inputs.validate({"earth_spin_rad_s": 1e-7, "moon_orbital_period_days": 0.1})
    titles = [step.title for step in EXAMPLE.solve(inputs).steps]
    assert titles[-1].startswith("Warning.") and titles[-2].startswith("Check")
