"""Gyroscopes for inertial guidance (section 10.3): free gyroscope, gyrocompass, rate gyro.

Every closed form or reduced model in app/physics/models/{free_gyroscope,gyrocompass,rate_gyro}.py
is checked against an independent computation:

* the FULL rigid-body equations, derived from scratch with sympy in gyroscope_references.py:
  each body's attitude is a product of elementary rotation matrices (base or Earth rotation
  prescribed in time, gimbal angles as generalised coordinates), its body-frame
  angular velocity comes from ``Rᵀ Ṙ``, and Lagrange's equations of the total kinetic
  energy (plus spring potential and Rayleigh damping) are integrated by scipy's DOP853
  at rtol = atol = 1e-12. Nothing in that derivation uses the app's formulas. The sampled
  solutions are stored in tests/references/ (the derivation takes a minute); the ``slow``
  test below recomputes them and checks the stored numbers;
* tight DOP853 integrations of the reduced equations (for the closed forms);
* periods measured from the integrated motion against the complete elliptic
  integral, and conservation laws (energy plus the work of the damper).

Each test states its tolerance and why.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.special import ellipk

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch10 import free_gyroscope as fg
from app.physics.systems.ch10 import gyrocompass as gc
from app.physics.systems.ch10 import rate_gyro as rg
from tests.physics.systems.ch10 import gyroscope_references as full

TIGHT = full.TIGHT
ROTOR_TRANSVERSE, SCALED = full.ROTOR_TRANSVERSE, full.SCALED


@pytest.mark.slow
@pytest.mark.parametrize("reference", full.REFERENCES, ids=lambda reference: reference.name)
def test_stored_full_rigid_body_reference_is_reproduced(reference):
    """Re-derive Lagrange's equations with sympy and re-integrate them; each stored series agrees with
    the fresh one to the reference's own ``atol`` (stated and justified in gyroscope_references.py)."""
    reference.check_against_fresh_computation()


# ---------------------------------------------------------------------------------------------
# Free gyroscope
# ---------------------------------------------------------------------------------------------
def free_params(**changes):
    return fg.PARAMETERS.validate(changes)


def test_gimbal_angles_invert_the_gimbal_chain():
    """φ ↦ s ↦ φ is the identity away from the lock (round-off only: 1e-12 rad)."""
    rng = np.random.default_rng(3)
    outer = rng.uniform(-math.pi, math.pi, 500)
    inner = rng.uniform(-1.5, 1.5, 500)
    back_outer, back_inner = fg.gimbal_angles(fg.spin_axis_from_gimbals(outer, inner))
    assert np.max(np.abs(back_inner - inner)) < 1e-12
    assert np.max(np.abs(np.angle(np.exp(1j * (back_outer - outer))))) < 1e-12


def test_yaw_turn_turns_only_the_outer_ring():
    """A pure yaw at 0.3 rad/s with the axis level: φ_o = −0.3 t, φ_i = 0, exactly (1e-12)."""
    params = free_params(vehicle_rate_rad_s=[0.0, 0.0, 0.3])
    t = np.linspace(0.0, 10.0, 101)
    motion = fg.gimbal_motion(params, t)
    assert np.max(np.abs(np.angle(np.exp(1j * (motion.outer_rad + 0.3 * t))))) < 1e-12
    assert np.max(np.abs(motion.inner_rad)) < 1e-12
    assert np.allclose(motion.outer_rate_rad_s, -0.3, atol=1e-12)


def test_roll_reaches_gimbal_lock_at_a_quarter_turn():
    """A pure roll lays the rotor's axis onto the outer gimbal axis after 90°: t = (π/2)/0.3 s, exactly."""
    params = free_params(vehicle_rate_rad_s=[0.3, 0.0, 0.0])
    approaches = fg.closest_approaches_to_lock(params, 16.0)
    assert [round(t, 12) for t, _ in approaches] == [round(0.5 * math.pi / 0.3, 12), round(1.5 * math.pi / 0.3, 12)]
    assert all(angle < 1e-12 for _, angle in approaches)
    solution = fg.FreeGyroscope().evaluate(params, np.linspace(0.0, 16.0, 161))
    assert [e.kind for e in solution.events] == ["gimbal-lock", "gimbal-lock"]
    assert "one plane" in solution.events[0].message


def test_closest_approach_to_lock_matches_dense_sampling():
    """The exact closest approach (time and angle) agrees with a 1e6-sample search to the grid's resolution."""
    params = free_params(vehicle_rate_rad_s=[0.3, -0.2, 0.4], inner_gimbal0_deg=20.0, outer_gimbal0_deg=35.0)
    t = np.linspace(0.0, 20.0, 1_000_001)
    lock = fg.gimbal_motion(params, t).lock_angle_rad
    exact = fg.closest_approaches_to_lock(params, 20.0)
    # Local minima of the sampled angle, away from the ends.
    interior = np.flatnonzero((lock[1:-1] < lock[:-2]) & (lock[1:-1] <= lock[2:])) + 1
    assert len(interior) == len(exact) >= 2
    for index, (t_exact, angle_exact) in zip(interior, exact):
        assert abs(t[index] - t_exact) < 2e-5  # grid step 2e-5 s
        assert abs(lock[index] - angle_exact) < 1e-8  # the angle is flat at its minimum: error ∝ (Δt)²


def test_gimbal_rates_match_finite_differences():
    """Analytic φ̇ against central differences, h = 1e-5 s: truncation ~h²·φ''' ≈ 1e-10, round-off ~1e-11."""
    params = free_params(vehicle_rate_rad_s=[0.25, 0.15, -0.35], inner_gimbal0_deg=10.0, outer_gimbal0_deg=-40.0)
    t = np.linspace(0.5, 15.0, 60)
    h = 1e-5
    plus, minus = fg.gimbal_motion(params, t + h), fg.gimbal_motion(params, t - h)
    motion = fg.gimbal_motion(params, t)
    assert np.min(motion.lock_angle_rad) > 0.2  # far from the lock, where the rates are smooth
    outer_fd = np.angle(np.exp(1j * (plus.outer_rad - minus.outer_rad))) / (2 * h)
    inner_fd = (plus.inner_rad - minus.inner_rad) / (2 * h)
    assert np.max(np.abs(outer_fd - motion.outer_rate_rad_s)) < 1e-8
    assert np.max(np.abs(inner_fd - motion.inner_rate_rad_s)) < 1e-8


def test_free_gyroscope_closed_form_matches_full_rigid_body_equations():
    """Massless gimbals: the full Lagrangian motion of rotor + rings gives the closed-form gimbal angles.

    The vehicle tumbles (roll, pitch and yaw at once) for 12 s; the closest approach to the lock is
    31°, so the equations stay regular. DOP853 at 1e-12 reproduces φ_o, φ_i to ≤ 1e-8 rad (measured
    3e-13); a wrong sign in the chain or a rate error of 1e-6 would be far outside.
    """
    params = free_params(**full.MASSLESS_GIMBALS.inputs["vehicle"])
    reference = full.MASSLESS_GIMBALS.load()  # rotor spin 50 rad/s, I_a 2e-3, I_t 1.2e-3 kg·m²
    t = np.linspace(0.0, 12.0, 121)
    motion = fg.gimbal_motion(params, t)
    assert np.min(motion.lock_angle_rad) > math.radians(10.0)
    assert np.max(np.abs(np.angle(np.exp(1j * (reference["outer_rad"][0] - motion.outer_rad))))) < 1e-8
    assert np.max(np.abs(reference["inner_rad"][0] - motion.inner_rad)) < 1e-8


def test_heavy_gimbals_disturb_the_axis_less_when_the_rotor_spins_faster():
    """Real gimbals have inertia: turning them takes torque, which reaches the rotor and tips its axis.

    With the same ring inertia, the largest tip of the axis away from the ideal direction over 6 s
    falls as 1/H (a gyroscopic deflection, torque/H): from spin 50 to 500 rad/s it drops 10× (measured
    4.76e-4 → 4.75e-5 rad; allowed 8× to 12×).
    """
    params = free_params(**full.HEAVY_GIMBALS.inputs["vehicle"])
    t = np.linspace(0.0, 6.0, 241)
    ideal = fg.gimbal_motion(params, t)
    runs = full.HEAVY_GIMBALS.load()  # one row per spin: 50 and 500 rad/s, rings of 2e-4 kg·m²
    deviation = []
    for outer, inner in zip(runs["outer_rad"], runs["inner_rad"]):
        axis = fg.spin_axis_from_gimbals(outer, inner)
        deviation.append(float(np.max(np.arccos(np.clip(np.sum(axis * ideal.spin_axis_vehicle, axis=1), -1, 1)))))
    assert deviation[0] > 1e-4  # the disturbance is real…
    assert 8.0 < deviation[0] / deviation[1] < 12.0  # …and a faster rotor resists it as 1/H


def test_free_gyroscope_model_reports_lock_and_keeps_the_axis():
    params = free_params(vehicle_rate_rad_s=[0.3, 0.0, 0.0])
    solution = fg.FreeGyroscope().evaluate(params, np.linspace(0.0, 6.0, 361))
    assert np.max(solution.invariants["spin_axis_error_rad"]) < 1e-12
    assert np.isclose(solution.series["inner_gimbal_rad"][100], -0.3 * 100 / 60, atol=1e-12)


def test_free_gyroscope_rejects_a_rotor_without_spin():
    with pytest.raises(ParameterError, match=r"^ω_s \(rad/s\): must be non-zero") as refused:  # as its control shows it
        fg.PARAMETERS.validate({"spin_rad_s": 0.0})
    assert refused.value.field == "spin_rad_s"


# ---------------------------------------------------------------------------------------------
# Gyrocompass
# ---------------------------------------------------------------------------------------------
def compass_params(**changes):
    return gc.PARAMETERS.validate(changes)


def exact_constrained_rhs(params, *, transverse_excess):
    """I_t α̈ + c α̇ + I_a ω_s Ω cos λ sin α − A Ω² cos²λ sin α cos α = 0: the term the reduced model drops.

    Derived by hand from the vertical component of dH/dt = τ: ``A = I_r + J_across − J_along``, the
    rotor's transverse moment plus the housing's horizontal moment across the spin axis minus the one
    along it.
    """
    i_t, c = params["vertical_inertia_kg_m2"], params["damping_N_m_s_rad"]
    k = gc.restoring_moment_N_m(params)
    w = gc.horizontal_earth_rate_rad_s(params)

    def rhs(t, y):
        return [y[1], (-c * y[1] - k * math.sin(y[0]) + transverse_excess * w * w * math.sin(y[0]) * math.cos(y[0])) / i_t]

    return rhs


def test_gyrocompass_equation_matches_full_rigid_body_equations():
    """Full Lagrangian (housing + spinning rotor on the rotating planet) against the one-line equation.

    Scaled planet (Ω = 0.05 rad/s), 4 periods. The hand-derived constrained equation (with the Ω² term)
    agrees with the full equations to ≤ 1e-9 rad (both DOP853 at 1e-12). The reduced model the app
    integrates drops that term, at most ε = I_t Ω cos λ / (I_a ω_s) = 3.2e-4 times the restoring one;
    that shifts the frequency by at most ε/2, so after N periods α differs by at most 2π·N·(ε/2)·|α₀|
    ≈ 2.1e-3 rad (measured 3.6e-4; the hand-derived equation: 1.2e-10) — and by more than 1e-5 rad,
    which shows the check can see a term of relative size ε.
    """
    params = compass_params(**SCALED)
    epsilon = gc.reduction_ratio(params)
    assert math.isclose(epsilon, 0.05 * 0.05 * math.cos(math.radians(40.0)) / (0.02 * 300.0))
    periods = 4
    t_end = periods * gc.small_angle_period_s(params)
    t = np.linspace(0.0, t_end, 401)
    swing = full.COMPASS_SWING.load()["alpha_rad"]  # the full rigid-body equations, DOP853 at 1e-12
    y0 = full.compass_start(params)
    exact = solve_ivp(exact_constrained_rhs(params, transverse_excess=ROTOR_TRANSVERSE), (0.0, t_end), y0[::2], t_eval=t, **TIGHT)
    assert exact.success
    assert np.max(np.abs(swing - exact.y[0])) < 1e-9
    reduced = gc.Gyrocompass().simulate(params, {"method": "dopri5", "rtol": 1e-12}, t_end_s=t_end, frame_rate_hz=400 / t_end, request_limits=False)
    assert reduced.status == "ok"
    difference = np.max(np.abs(reduced.series["alpha_rad"] - swing))
    bound = 2 * math.pi * periods * 0.5 * epsilon * math.radians(30.0)
    assert 1e-5 < difference < bound, (difference, bound)


def test_gyrocompass_seeks_north_in_the_full_equations():
    """Sign check without the app's formulas: with damping the full rigid-body motion settles on north
    (α → 0, spin angular momentum along north) for ω_s > 0, and on south (α → π, H still north) for ω_s < 0."""
    finals = full.COMPASS_SEEKING.load()["final_alpha_rad"]  # after 40 s, damping 0.05 N·m·s/rad
    for (spin, alpha0_deg), rest, alpha_end in zip(full.SEEKING_RELEASES, (0.0, math.pi), finals):
        params = compass_params(**{**SCALED, "spin_rad_s": spin, "damping_N_m_s_rad": 0.05, "alpha0_deg": alpha0_deg})
        final = math.remainder(alpha_end - rest, 2 * math.pi)
        assert abs(final) < 1e-2, (spin, final)  # ζ ≈ 0.23: e^{−ζ ω_n 40 s} ≈ 1e-8 of the start, plus the ε offset
        assert gc.stable_azimuth_rad(params) == rest


def test_reduced_model_integrators_match_a_tight_reference():
    """The app's RK4 (automatic step, h·ω ≤ 0.1) and Dormand–Prince against DOP853 of the same reduced
    equation over 600 s of the default compass (≈ 6 periods, 30° swing, light damping). RK4 at one step
    of 1 s per frame (h·ω_n = 0.064): measured 8.4e-7 rad, allowed 1e-5 (≈ 600 s·ω_n·(hω_n)⁴/120 scale);
    dopri5 at rtol 1e-10: measured 1e-10, allowed 1e-7. The energy + damper-work invariant drifts by
    7e-9 (RK4) of its scale; allowed 1e-6."""
    params = compass_params(alpha0_deg=30.0, damping_N_m_s_rad=2e-3)
    t_end, rate = 600.0, 1.0
    t = np.arange(0.0, t_end + 1e-9, 1.0 / rate)
    k, i_t, c = gc.restoring_moment_N_m(params), params["vertical_inertia_kg_m2"], params["damping_N_m_s_rad"]
    reference = solve_ivp(lambda _, y: [y[1], (-k * math.sin(y[0]) - c * y[1]) / i_t], (0.0, t_end), [math.radians(30.0), 0.0], t_eval=t, **TIGHT)
    for controls, tolerance in (({"method": "rk4"}, 1e-5), ({"method": "dopri5", "rtol": 1e-10}, 1e-7)):
        report = gc.Gyrocompass().simulate(params, controls, t_end_s=t_end, frame_rate_hz=rate)
        assert report.status == "ok"
        error = np.max(np.abs(report.series["alpha_rad"] - reference.y[0]))
        assert error < tolerance, (controls, error)
        # Energy plus the damper's work stays constant (it would not without the dissipated-energy state).
        assert report.max_invariant_drift < 1e-6


def _measured_period_s(params, *, swings=3, rate_hz=50.0):
    """Period from the times α̇ changes sign downward (maxima of α), by linear interpolation; dopri5 at 1e-12."""
    t_end = (swings + 0.6) * gc.large_amplitude_period_s(params, gc.amplitude_rad(params))
    report = gc.Gyrocompass().simulate(params, {"method": "dopri5", "rtol": 1e-12}, t_end_s=t_end, frame_rate_hz=rate_hz, request_limits=False)
    alpha, rate = report.series["alpha_rad"], report.series["alpha_rate_rad_s"]
    t = report.t_s
    # α̇ crosses zero from + to − at maxima of α; released at rest at its maximum, so skip the start.
    crossings = [
        t[i] + (t[i + 1] - t[i]) * rate[i] / (rate[i] - rate[i + 1])
        for i in range(1, len(t) - 1)
        if rate[i] > 0.0 >= rate[i + 1] and alpha[i] > 0
    ]
    assert len(crossings) >= swings - 1
    return (crossings[-1] - crossings[0]) / (len(crossings) - 1)


@pytest.mark.parametrize("alpha0_deg", [150.0, 90.0, 20.0])
def test_large_swing_period_is_the_complete_elliptic_integral(alpha0_deg):
    """T = 4 K(sin²(α₀/2)) / ω_n for a release from rest at α₀ (no damping). The period measured from
    the integrated motion (dopri5 at rtol 1e-12; maxima of α where α̇ changes sign, linearly
    interpolated on a 50 Hz grid — near a maximum α̇ is almost linear in t) agrees to 1e-9 relative
    (measured ≤ 7e-12); the small-angle formula is short by 0.8% at 20°, 15% at 90° and 43% at 150°."""
    params = compass_params(alpha0_deg=alpha0_deg)
    expected = 4.0 * float(ellipk(math.sin(math.radians(alpha0_deg) / 2) ** 2)) / gc.natural_frequency_rad_s(params)
    assert math.isclose(gc.large_amplitude_period_s(params, math.radians(alpha0_deg)), expected, rel_tol=1e-14)
    measured = _measured_period_s(params)
    assert math.isclose(measured, expected, rel_tol=1e-9), (measured, expected)


def test_small_swing_period_is_the_gyroscopic_formula():
    """α₀ = 0.5°: T = 2π √(I_t / (I_a ω_s Ω cos λ)) times (1 + α₀²/16) ≈ 1 + 4.8e-6 (measured 4.76e-6);
    allowed 2e-5 relative, while an error of 2 in the formula (e.g. cos λ missing: 41%) is far outside."""
    params = compass_params(alpha0_deg=0.5)
    formula = 2 * math.pi * math.sqrt(0.5 / (0.02 * 2000.0 * gc.EARTH_RATE_RAD_S * math.cos(math.radians(45.0))))
    assert math.isclose(gc.small_angle_period_s(params), formula, rel_tol=1e-14)
    assert 90.0 < formula < 110.0  # the default compass swings about north in about a minute and a half
    assert math.isclose(_measured_period_s(params), formula, rel_tol=2e-5)


@pytest.mark.parametrize(
    ("changes", "field", "words"),
    [
        ({"latitude_deg": 90.0}, "latitude_deg", "horizontal component"),
        ({"latitude_deg": -90.0}, "latitude_deg", "horizontal component"),
        ({"spin_rad_s": 0.0}, "spin_rad_s", "non-zero"),
        ({"spin_rad_s": 1.0, "earth_rate_rad_s": 0.5}, "spin_rad_s", "reduced"),
        ({"vertical_inertia_kg_m2": -1.0}, "vertical_inertia_kg_m2", "between"),
    ],
)
def test_gyrocompass_rejects_impossible_inputs(changes, field, words):
    with pytest.raises(ParameterError) as error:
        gc.PARAMETERS.validate(changes)
    assert error.value.field == field and words in str(error.value)


def test_full_spin_would_need_millions_of_steps_per_period():
    """The lesson's argument in numbers: T₀·ω_s/0.1 steps per period for the default compass."""
    params = compass_params()
    steps = gc.full_model_steps_per_period(params)
    assert math.isclose(steps, gc.small_angle_period_s(params) * 2000.0 / 0.1)
    assert steps > 1e6


# ---------------------------------------------------------------------------------------------
# Rate gyro
# ---------------------------------------------------------------------------------------------
def rate_params(**changes):
    return rg.PARAMETERS.validate(changes)


def _critical_damping(params):
    return 2 * math.sqrt(params["stiffness_N_m_rad"] * params["gimbal_inertia_kg_m2"])


@pytest.mark.parametrize("kind", ["step", "sine"])
@pytest.mark.parametrize("zeta", [0.0, 0.2, 1.0, 1.0 + 1e-7, 3.0])
def test_rate_gyro_closed_form_matches_tight_integration(kind, zeta):
    """β(t), β̇(t) from rest against DOP853 (rtol 1e-12, atol 1e-14) of I_g β̈ + c β̇ + k β = I_a ω_s Ω(t)
    over 10 s (16 natural periods). Measured ≤ 1.8e-11 of the peak β (≤ 2.1e-10 rad/s in β̇ for ζ = 3,
    whose fast root makes the reference work hardest); allowed 1e-9 relative and 1e-8 rad/s. Includes ζ = 1
    exactly (the critical formula) and ζ = 1 + 1e-7 (the over-damped formula next to it)."""
    probe = rate_params()
    params = rate_params(input_kind=kind, damping_N_m_s_rad=zeta * _critical_damping(probe), input_frequency_rad_s=7.0)
    assert math.isclose(rg.damping_ratio(params), zeta, rel_tol=1e-12, abs_tol=1e-15)
    h, i_g, c, k = rg.angular_momentum_N_m_s(params), params["gimbal_inertia_kg_m2"], params["damping_N_m_s_rad"], params["stiffness_N_m_rad"]
    omega0, w = params["input_rate_rad_s"], params["input_frequency_rad_s"]
    rate = (lambda t: omega0) if kind == "step" else (lambda t: omega0 * math.sin(w * t))
    t = np.linspace(0.0, 10.0, 2001)
    reference = solve_ivp(lambda s, y: [y[1], (h * rate(s) - c * y[1] - k * y[0]) / i_g], (0.0, 10.0), [0.0, 0.0], t_eval=t, method="DOP853", rtol=1e-12, atol=1e-14)
    response = rg.gimbal_response(params, t)
    peak = np.max(np.abs(reference.y[0]))
    assert np.max(np.abs(response.beta_rad - reference.y[0])) < 1e-9 * peak
    assert np.max(np.abs(response.beta_rate_rad_s - reference.y[1])) < 1e-8


def test_step_response_settles_on_the_steady_gain():
    """After 20 time constants 1/(ζω_n) the step response equals G Ω₀ = I_a ω_s Ω₀ / k to 1e-8 rad."""
    params = rate_params(damping_N_m_s_rad=0.02)
    settle = 20.0 / (rg.damping_ratio(params) * rg.natural_frequency_rad_s(params))
    beta = rg.gimbal_response(params, settle).beta_rad[0]
    assert abs(beta - 2e-4 * 1000.0 * 0.5 / 0.5) < 1e-8
    solution = rg.RateGyro().evaluate(params, np.array([0.0, settle]))
    assert abs(solution.series["indicated_rate_rad_s"][-1] - 0.5) < 1e-7


def test_sine_response_has_the_frequency_response_amplitude_and_phase():
    """Once the transient has decayed (e^{−ζω_n t} < 1e-12), β is a sine of amplitude G/√((1−r²)²+(2ζr)²)
    lagging Ω by atan2(2ζr, 1−r²): checked by a least-squares fit over two periods to 1e-9."""
    params = rate_params(input_kind="sine", input_frequency_rad_s=13.0, damping_N_m_s_rad=0.05)
    w = 13.0
    start = 30.0 / (rg.damping_ratio(params) * rg.natural_frequency_rad_s(params))
    t = np.linspace(start, start + 4 * math.pi / w, 400)
    beta = rg.gimbal_response(params, t).beta_rad
    basis = np.column_stack([np.sin(w * t), np.cos(w * t)])
    (a, b), *_ = np.linalg.lstsq(basis, beta, rcond=None)
    ratio, lag = rg.frequency_response(params, w)
    assert math.isclose(math.hypot(a, b), ratio * 0.5, rel_tol=1e-9)
    assert math.isclose(math.atan2(-b, a), lag, rel_tol=1e-9)


def test_full_gimbal_and_rotor_model_reads_the_input_rate():
    """Full rigid-body gimbal + motor-driven rotor (spin 1000 rad/s) on a case stepped to Ω = 0.05 rad/s.

    The steady deflection equals I_a ω_s Ω / k to 1e-3 relative: the neglected effects are the cos β
    factor of the gyroscopic moment (β_ss = 0.02 rad → 2e-4) and Ω² terms from the unequal moments
    (≈ ΔI Ω/(I_a ω_s) ≈ 1e-4); measured 2.0e-4. The whole transient follows the closed form to 1e-3 of
    β_ss for the same reasons (measured 4.6e-4).
    """
    params = rate_params(input_rate_rad_s=0.05, damping_N_m_s_rad=0.03)
    beta = full.RATE_GYRO_STEP.load()["beta_rad"]  # rotor I_t 1.2e-4, gimbal 3e-3 and 4e-3 kg·m² about y, z
    t = np.linspace(0.0, 8.0, 801)
    steady = 2e-4 * 1000.0 * 0.05 / 0.5
    assert math.isclose(beta[-1], steady, rel_tol=1e-3), (beta[-1], steady)
    closed = rg.gimbal_response(params, t).beta_rad
    assert np.max(np.abs(beta - closed)) < 1e-3 * steady
