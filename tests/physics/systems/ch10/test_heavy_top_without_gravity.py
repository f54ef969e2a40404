"""The heavy top with g = 0 is a torque-free axisymmetric top: every piece must still answer.

Checked: the invariant scales cover every invariant (|L| appears only without gravity),
the sleeping threshold is zero, the quadrature handles a top at rest upright, and a run
that blows up while staying finite (a zeroed quaternion) ends with a status.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.core.parameters import ParameterSet
from app.physics.systems.ch10 import heavy_top as ht

FREE = ht.PARAMETERS.validate({"g_m_s2": 0.0, "nutation_rate0_rad_s": 2.0})


def test_invariant_scales_cover_every_invariant_with_and_without_gravity():
    model = ht.HeavyTop()
    for params in (FREE, ht.PARAMETERS.validate({})):
        y0 = model.initial_state(params)
        assert set(model.invariant_scales(params, y0)) == set(model.invariants(params, y0[None, :]))
    assert "angular_momentum" in model.invariants(FREE, model.initial_state(FREE)[None, :])


def test_torque_free_top_conserves_angular_momentum_and_its_direction():
    model = ht.HeavyTop()
    controls = ParameterSet(model.controls()).validate({})
    report = model.simulate(FREE, controls, t_end_s=5.0, frame_rate_hz=30.0)
    assert report.status == "ok"
    momentum = report.invariants["angular_momentum"]
    # Splitting with the exact free flow: |L| is kept to round-off (1e-12 relative is 1e4 × eps, far below real drift).
    assert np.max(np.abs(momentum - momentum[0])) <= 1e-12 * momentum[0]
    # The quadrature (with mgl = 0) is an independent solution of the same motion. The splitting's free
    # flow is exact without gravity, so only round-off separates them: 1e-9 rad is 1e7 × eps over 150 frames.
    axis = ht.quadrature(FREE).symmetry_axis(report.t_s)
    theta_reference = np.arccos(np.clip(axis[:, 2], -1.0, 1.0))
    assert np.max(np.abs(report.series["theta"] - theta_reference)) < 1e-9
    assert np.ptp(theta_reference) > 0.01  # and the axis does nutate (the check is not of a constant)


def test_sleeping_threshold_without_gravity_is_zero_and_an_upright_top_at_rest_has_a_quadrature():
    assert ht.critical_spin_rad_s(FREE) == 0.0
    at_rest = ht.PARAMETERS.validate({"g_m_s2": 0.0, "spin_rad_s": 0.0, "theta0_deg": 0.0})
    solution = ht.quadrature(at_rest)
    assert solution.theta_min_rad == solution.theta_max_rad == 0.0
    assert solution.nutation_period_s == math.inf
    assert ht.locus_shape(solution) == "vertical"


def test_a_run_that_zeroes_the_quaternion_stops_with_a_status():
    model = ht.HeavyTop()
    params = ht.PARAMETERS.validate({"spin_rad_s": 2000, "I_axial": 1e-5, "I_transverse_pivot": 100, "mass_kg": 100, "cg_distance_m": 0.001})
    controls = ParameterSet(model.controls()).validate({"method": "rk4", "steps_per_frame": 1})
    report = model.simulate(params, controls, t_end_s=600.0, frame_rate_hz=1.0)
    assert report.status == "non_finite" and report.message.startswith("Stopped at t = ")
    assert len(report.t_s) < 601
    assert model.describable(params, np.array([[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0]])).tolist() == [False]
    for values in (*report.series.values(), *report.invariants.values()):
        assert np.all(np.isfinite(values)) and len(values) == len(report.t_s)
