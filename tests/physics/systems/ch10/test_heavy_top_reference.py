"""The heavy-top scene's integration against its quadrature reference, and the locus classification.

The scene integrates with its default controls at 30 frames/s; the readout puts
the quadrature's nutation band, period and mean precession beside it. Here the
integration (the scene's own model, method and step choice) is checked against
those predictions, and the locus shape the readout names against the sign of
the integrated precession rate.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.systems.ch10 import heavy_top
from app.scenes.kit import FRAME_DT_S

MODEL = heavy_top.HeavyTop()
DEFAULTS = heavy_top.PARAMETERS.defaults()


def scene_run(params: dict, t_end_s: float, frame_rate_hz: float = 1.0 / FRAME_DT_S):
    return MODEL.simulate(params, {}, t_end_s=t_end_s, frame_rate_hz=frame_rate_hz, request_limits=False)


@pytest.mark.parametrize("spin_rad_s, precession0", [(60.0, 0.0), (25.0, 0.0), (40.0, 1.5), (40.0, -1.5)])
def test_scene_integration_follows_the_quadrature(spin_rad_s, precession0):
    """θ(t) and φ(t) at every 30 Hz frame for 20 s within 1e-5 rad of the quadrature (default splitting4, automatic step).

    1e-5 rad on the unit-length axis is a hundredth of a pixel at 1000 px per
    axis length: the reference tip and the integrated tip are drawn on top of
    each other. (The φ error is a phase error growing about linearly in time,
    ~1.8e-6 rad after 20 s at ω3 = 25 rad/s.)
    """
    params = dict(DEFAULTS, spin_rad_s=spin_rad_s, precession_rate0_rad_s=precession0)
    report = scene_run(params, 20.0)
    assert report.status == "ok"
    reference = heavy_top.quadrature(params)
    assert np.max(np.abs(report.series["theta"] - reference.theta(report.t_s))) < 1e-5
    assert np.max(np.abs(report.series["phi"] - reference.phi(report.t_s))) < 1e-5


def test_nutation_band_period_and_mean_precession_from_the_integration():
    """Turning points within 1e-6 rad, period within 1e-5 s, mean precession within 1e-5 relative."""
    params = dict(DEFAULTS, spin_rad_s=30.0)
    reference = heavy_top.quadrature(params)
    periods = 6
    t_end = periods * reference.nutation_period_s
    report = scene_run(params, t_end, frame_rate_hz=4000.0)
    theta, t = report.series["theta"], report.t_s
    assert theta.min() == pytest.approx(reference.theta_min_rad, abs=1e-6)
    assert theta.max() == pytest.approx(reference.theta_max_rad, abs=1e-6)
    # Successive maxima of θ (parabolic refinement) are one nutation period apart.
    interior = np.flatnonzero((theta[1:-1] > theta[:-2]) & (theta[1:-1] >= theta[2:])) + 1
    peaks = []
    for i in interior:
        c = np.polyfit(t[i - 2 : i + 3] - t[i], theta[i - 2 : i + 3], 2)
        peaks.append(t[i] - c[1] / (2 * c[0]))
    assert len(peaks) == periods
    assert np.diff(peaks) == pytest.approx(reference.nutation_period_s, abs=1e-5)
    measured = (report.series["phi"][-1] - report.series["phi"][0]) / t[-1]
    assert measured == pytest.approx(reference.mean_precession_rate_rad_s, rel=1e-5)


def integrated_precession_rates(params: dict) -> np.ndarray:
    reference = heavy_top.quadrature(params)
    report = scene_run(params, 2.0 * reference.nutation_period_s, frame_rate_hz=3000.0)
    return np.diff(report.series["phi"]) * 3000.0


@pytest.mark.parametrize(
    "precession0, shape",
    [(0.0, "cusps"), (0.6, "waves"), (-0.6, "loops")],
)
def test_locus_shape_matches_the_sign_of_the_integrated_precession_rate(precession0, shape):
    """Cusps: φ̇ touches 0; waves: φ̇ > 0 throughout; loops: φ̇ takes both signs (integration, 3 kHz samples)."""
    params = dict(DEFAULTS, spin_rad_s=25.0, precession_rate0_rad_s=precession0)
    assert heavy_top.locus_shape(heavy_top.quadrature(params)) == shape
    rates = integrated_precession_rates(params)
    scale = np.max(np.abs(rates))
    if shape == "waves":
        assert rates.min() > 0.05 * scale
    elif shape == "loops":
        assert rates.min() < -0.05 * scale and rates.max() > 0.05 * scale
    else:
        assert -1e-3 * scale < rates.min() < 0.02 * scale


def test_steady_precession_is_a_circle_and_a_sleeping_top_is_vertical():
    params = dict(DEFAULTS, spin_rad_s=60.0)
    # Slow steady precession: I_t φ̇² cosθ − I_a ω3 φ̇ + mgl = 0, the smaller root.
    It, Ia, mgl = params["I_transverse_pivot"], params["I_axial"], params["mass_kg"] * params["g_m_s2"] * params["cg_distance_m"]
    c = math.cos(math.radians(params["theta0_deg"]))
    slow = (Ia * 60.0 - math.sqrt((Ia * 60.0) ** 2 - 4 * It * c * mgl)) / (2 * It * c)
    assert heavy_top.locus_shape(heavy_top.quadrature(dict(params, precession_rate0_rad_s=slow))) == "circle"
    upright = dict(params, theta0_deg=0.0)
    assert heavy_top.locus_shape(heavy_top.quadrature(upright)) == "vertical"


def test_critical_spin_matches_the_quadratures_threshold():
    """The scene's sleeping-threshold mark is the quadrature module's threshold (4 mgl I_t / I_a²)^½."""
    from app.physics.systems.ch10.heavy_top_quadrature import critical_spin_rad_s

    params = dict(DEFAULTS, mass_kg=2.0, cg_distance_m=0.08)
    mgl = 2.0 * params["g_m_s2"] * 0.08
    assert heavy_top.critical_spin_rad_s(params) == pytest.approx(
        critical_spin_rad_s(params["I_transverse_pivot"], params["I_axial"], mgl), rel=1e-15
    )
