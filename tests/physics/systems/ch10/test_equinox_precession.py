"""Precession of the equinoxes: the closed form against a direct average of the exact torque.

The reference sums the gravity-gradient moment (3GM/r⁵)(C − A)(s·r)(r × s) over
Kepler orbits sampled uniformly in time (mean anomaly; Kepler's equation solved
by Newton's method) and, for the Moon, over the longitude of its orbit's node,
then takes the gyroscopic precession rate |⟨M⟩⊥| / (C ω sin ε). It shares no
formula with the solver beyond Kepler's third law.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.systems.ch10.equinox_precession import (
    ARCSEC_PER_RAD,
    EXAMPLE,
    INPUTS,
    JULIAN_YEAR_S,
    equinox_precession,
    mean_motion_rad_s,
)

DEFAULTS = INPUTS.defaults()


def kepler_positions(eccentricity: float, samples: int) -> np.ndarray:
    """(samples, 3) positions on an ellipse with a = 1 in its own plane, uniform in time."""
    mean_anomaly = 2.0 * math.pi * np.arange(samples) / samples
    E = mean_anomaly.copy()
    for _ in range(50):
        E -= (E - eccentricity * np.sin(E) - mean_anomaly) / (1.0 - eccentricity * np.cos(E))
    x = np.cos(E) - eccentricity
    y = math.sqrt(1.0 - eccentricity**2) * np.sin(E)
    return np.stack([x, y, np.zeros_like(x)], axis=1)


def averaged_moment_over_C(*, gm_over_a3: float, eccentricity: float, inclination_rad: float, ellipticity: float, axis: np.ndarray) -> np.ndarray:
    """⟨M⟩ / C (1/s²) for a = 1, averaged over time along the orbit and over the node longitude."""
    orbit = kepler_positions(eccentricity, 512)
    total = np.zeros(3)
    nodes = 2.0 * math.pi * np.arange(16) / 16 if inclination_rad else [0.0]
    periapsis = 0.7  # any argument of periapsis: the average must not depend on it
    for node in nodes:
        rotation = rotation_z(node) @ rotation_x(inclination_rad) @ rotation_z(periapsis)
        r = orbit @ rotation.T
        rn = np.linalg.norm(r, axis=1)
        s_dot_r = r @ axis
        moments = 3.0 * gm_over_a3 * ellipticity * (s_dot_r / rn**5)[:, None] * np.cross(r, axis)
        total += moments.mean(axis=0)
    return total / len(nodes)


def rotation_x(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def rotation_z(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


def reference_rates(inputs: dict) -> tuple[float, float, np.ndarray]:
    """Sun's and Moon's precession rates (rad/s) and the precession angular velocity direction."""
    eps = math.radians(inputs["obliquity_deg"])
    axis = np.array([0.0, -math.sin(eps), math.cos(eps)])  # figure axis, ecliptic normal +Z
    omega, H, mu = inputs["earth_spin_rad_s"], inputs["dynamical_ellipticity"], inputs["moon_mass_ratio"]
    rates, directions = [], []
    for gm_over_a3, e, i in (
        (mean_motion_rad_s(inputs["sun_orbital_period_days"]) ** 2, inputs["earth_orbit_eccentricity"], 0.0),
        (mean_motion_rad_s(inputs["moon_orbital_period_days"]) ** 2 * mu / (1 + mu), inputs["moon_orbit_eccentricity"], math.radians(inputs["moon_inclination_deg"])),
    ):
        moment = averaged_moment_over_C(gm_over_a3=gm_over_a3, eccentricity=e, inclination_rad=i, ellipticity=H, axis=axis)
        # ds/dt = M/(Cω) = Ω_vec × s with Ω_vec along ±Z: Ω_Z = (ds/dt · (Z × s)) / |Z × s|².
        z_cross_s = np.cross([0.0, 0.0, 1.0], axis)
        precession_z = float(moment @ z_cross_s) / omega / float(z_cross_s @ z_cross_s)
        rates.append(abs(precession_z))
        directions.append(precession_z)
    return rates[0], rates[1], np.array(directions)


@pytest.mark.parametrize(
    "changes",
    [{}, {"obliquity_deg": 60.0, "moon_inclination_deg": 20.0, "moon_orbit_eccentricity": 0.3, "earth_orbit_eccentricity": 0.2}],
    ids=["earth", "exaggerated"],
)
def test_closed_form_matches_the_direct_orbit_average(changes):
    """Each body's rate within 1e-9 relative of the averaged exact torque (spectral time average, 16 node longitudes)."""
    inputs = {**DEFAULTS, **changes}
    sun, moon, directions = reference_rates(inputs)
    result = equinox_precession(inputs)
    assert result.sun_rate_rad_s == pytest.approx(sun, rel=1e-9)
    assert result.moon_rate_rad_s == pytest.approx(moon, rel=1e-9)
    # Westward: the precession angular velocity points along −Z while the Earth spins about +s (s·Z > 0).
    assert np.all(directions < 0.0)


def test_the_average_moment_is_perpendicular_to_the_axis_and_the_ecliptic_normal():
    """No component along s (ω stays constant) nor along Z (the cone keeps its angle): to 1e-12 relative."""
    eps = math.radians(DEFAULTS["obliquity_deg"])
    axis = np.array([0.0, -math.sin(eps), math.cos(eps)])
    moment = averaged_moment_over_C(gm_over_a3=1.0, eccentricity=0.0549, inclination_rad=0.09, ellipticity=1.0, axis=axis)
    size = np.linalg.norm(moment)
    assert abs(moment @ axis) < 1e-12 * size
    assert abs(moment[2]) < 1e-12 * size


def test_defaults_reproduce_the_observed_lunisolar_precession():
    """50.31″/yr against the IAU 2006 lunisolar value 50.3875″/yr: within 0.5%.

    The remaining 0.15% is what the model leaves out: the Earth's higher gravity
    harmonics, the Sun's pull on the Moon's orbit beyond the node average, and
    the nutation terms, which average to zero.
    """
    outputs = EXAMPLE.solve(DEFAULTS).outputs
    assert outputs["rate_arcsec_per_year"] == pytest.approx(50.3875, rel=5e-3)
    assert outputs["period_years"] == pytest.approx(1296000.0 / outputs["rate_arcsec_per_year"], rel=1e-12)
    assert 25_000 < outputs["period_years"] < 26_500
    assert outputs["sun_share"] + outputs["moon_share"] == pytest.approx(1.0, abs=1e-15)
    assert outputs["moon_share"] == pytest.approx(0.683, abs=2e-3)  # the Moon does about two thirds
    per_year = JULIAN_YEAR_S * ARCSEC_PER_RAD
    assert outputs["rate_arcsec_per_year"] == pytest.approx(outputs["rate_rad_s"] * per_year, rel=1e-12)


def test_rate_scales_as_the_formula_says():
    """Doubling H doubles the rate; doubling ω halves it; no Moon leaves the Sun alone."""
    base = equinox_precession(DEFAULTS).rate_rad_s
    assert equinox_precession({**DEFAULTS, "dynamical_ellipticity": 2 * DEFAULTS["dynamical_ellipticity"]}).rate_rad_s == pytest.approx(2 * base, rel=1e-14)
    assert equinox_precession({**DEFAULTS, "earth_spin_rad_s": 2 * DEFAULTS["earth_spin_rad_s"]}).rate_rad_s == pytest.approx(base / 2, rel=1e-14)
    no_moon = EXAMPLE.solve({**DEFAULTS, "moon_mass_ratio": 0.0}).outputs
    assert no_moon["moon_share"] == 0.0 and no_moon["sun_share"] == 1.0
