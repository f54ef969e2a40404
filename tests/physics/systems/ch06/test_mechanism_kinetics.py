"""The slider-crank's kinetics: Newton–Euler per link against energy, momentum and an independent integration."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from app.physics.core.parameters import ParameterError, ParameterSet
from app.physics.systems.ch06 import mechanism_kinetics as mk

CASES = {
    "defaults": {},
    "offset": {"offset_m": 0.25, "rod_m": 0.8},
    "short rod": {"rod_m": 0.31, "crank_speed_rad_s": -7.0},
    "heavy slider": {"slider_mass_kg": 100.0, "crank_mass_kg": 0.05, "rod_mass_kg": 0.05},
    "no gravity": {"g_m_s2": 0.0},
}


def params(**overrides):
    return mk.PARAMETERS.validate(overrides)


def links_of(values):
    return mk.SliderCrankLinks.from_params(values)


def mechanical_energy_J(links, theta, omega):
    motion = mk.link_motion(links, theta, omega, np.zeros_like(theta))
    return mk.kinetic_energy_J(links, motion) + mk.potential_energy_J(links, motion)


def angles_with_dead_centres(links, n=181):
    """A turn of crank angles plus each dead centre and points 1e-6 rad either side of it (rad)."""
    dead = np.array(links.mechanism.dead_centre_angles_rad)
    return np.concatenate([np.linspace(0.0, 2.0 * math.pi, n), dead, dead - 1e-6, dead + 1e-6])


@pytest.mark.parametrize("case", CASES)
def test_speed_drive_torque_matches_power_balance(case):
    """τ ω = d(T + V)/dt at constant crank speed, with d/dt from a central difference of the energy along the motion.

    The energy comes from the kinematics alone (no force in it). Step h = 1e-5 rad:
    truncation ~ h² E‴/6 and round-off ~ 1e-16 E / h are both below 1e-8 of the
    largest power, so 1e-6 of it is a safe bound that any wrong term (a sign, a
    missing inertia) breaks by orders of magnitude.
    """
    values = params(**CASES[case])
    links = links_of(values)
    omega = values["crank_speed_rad_s"]
    theta = angles_with_dead_centres(links)
    torque = mk.newton_euler(links, theta, omega, crank_acceleration_rad_s2=0.0).driving_torque_N_m
    h = 1e-5
    speed = np.full_like(theta, omega)
    power = (mechanical_energy_J(links, theta + h, speed) - mechanical_energy_J(links, theta - h, speed)) / (2.0 * h) * omega
    assert np.all(np.isfinite(torque))
    np.testing.assert_allclose(torque * omega, power, rtol=0.0, atol=1e-6 * np.max(np.abs(power)))


@pytest.mark.parametrize("case", CASES)
def test_forces_satisfy_whole_mechanism_momentum(case):
    """The external forces (pivot, guide, gravity) equal Σ m a_G of all three links, to round-off (1e-9 relative)."""
    values = params(**CASES[case])
    links = links_of(values)
    theta = angles_with_dead_centres(links, n=37)
    alpha = 3.0 * np.sin(theta)  # an arbitrary crank acceleration: the balance must hold for any motion
    forces = mk.newton_euler(links, theta, values["crank_speed_rad_s"], crank_acceleration_rad_s2=alpha)
    motion = mk.link_motion(links, theta, values["crank_speed_rad_s"], alpha)
    m_c, m_r, m_s, g = links.crank_mass_kg, links.rod_mass_kg, links.slider_mass_kg, links.g_m_s2
    momentum_rate = m_c * motion.crank_centre_acceleration + m_r * motion.rod_centre_acceleration + m_s * motion.slider_acceleration
    external = forces.pivot_O_N + np.stack([np.zeros_like(theta), forces.guide_force_N - (m_c + m_r + m_s) * g], axis=-1)
    scale = np.max(np.abs(momentum_rate)) + (m_c + m_r + m_s) * g
    np.testing.assert_allclose(external, momentum_rate, rtol=0.0, atol=1e-9 * scale)


def test_at_rest_the_pivot_and_guide_carry_the_weight():
    """Statics (ω = α = 0, crank straight up so gravity has no moment about O): no torque, O_y + N = total weight."""
    values = params()
    links = links_of(values)
    forces = mk.newton_euler(links, np.array([math.pi / 2]), 0.0, crank_acceleration_rad_s2=0.0)
    weight = (links.crank_mass_kg + links.rod_mass_kg + links.slider_mass_kg) * links.g_m_s2
    assert abs(forces.driving_torque_N_m[0]) < 1e-12 * weight * values["crank_m"]
    assert forces.pivot_O_N[0, 1] + forces.guide_force_N[0] == pytest.approx(weight, rel=1e-12)


@pytest.mark.parametrize("case", CASES)
def test_compiled_equation_of_motion_matches_newton_euler(case):
    """The kernel's M(θ) form and the per-link Newton–Euler solve are two derivations of one motion: they agree to 1e-9.

    Speed drive: the kernel's motor torque (Ẇ/ω) against Newton–Euler's τ at α = 0.
    Torque drive: the kernel's θ̈ against Newton–Euler's forward solve for α.
    Both sides are exact formulas; 1e-9 of the scale leaves room only for round-off
    in the 8×8 solve near the dead centres.
    """
    values = params(**CASES[case])
    links = links_of(values)
    theta = angles_with_dead_centres(links, n=73)
    omega = values["crank_speed_rad_s"]
    speed_p = links.kernel_parameters(drive="speed", drive_torque_N_m=0.0)
    torque_p = links.kernel_parameters(drive="torque", drive_torque_N_m=4.0)
    motor, alpha = [], []
    for angle in theta:
        rate = np.zeros(3)
        mk.mechanism_rhs.compiled(0.0, np.array([angle, omega, 0.0]), speed_p, rate)
        motor.append(rate[2] / omega)
        mk.mechanism_rhs.compiled(0.0, np.array([angle, omega, 0.0]), torque_p, rate)
        alpha.append(rate[1])
    inverse = mk.newton_euler(links, theta, omega, crank_acceleration_rad_s2=0.0)
    forward = mk.newton_euler(links, theta, omega, drive_torque_N_m=4.0)
    np.testing.assert_allclose(motor, inverse.driving_torque_N_m, rtol=0.0, atol=1e-9 * np.max(np.abs(inverse.driving_torque_N_m)))
    np.testing.assert_allclose(alpha, forward.crank_acceleration_rad_s2, rtol=0.0, atol=1e-9 * np.max(np.abs(forward.crank_acceleration_rad_s2)))
    round_trip = mk.newton_euler(links, theta, omega, crank_acceleration_rad_s2=forward.crank_acceleration_rad_s2)
    np.testing.assert_allclose(round_trip.driving_torque_N_m, 4.0, rtol=1e-9)


def test_generalized_inertia_is_the_crank_alone_at_the_dead_centres_of_an_in_line_crank():
    """In line, at θ = 0 the slider and the rod's translation are still (ẋ = 0, A moves ⊥ the rod): M = I_O + m_r (r/2)²·… exactly.

    At θ = 0, A moves at r ω straight up and B is still, so the rod turns about B at
    φ̇ = −r ω / l: G₂ moves at r ω / 2. M = m_c r²/3 + m_r r²/4 + (m_r l²/12)(r/l)².
    """
    values = params()
    links = links_of(values)
    r, m_c, m_r = values["crank_m"], values["crank_mass_kg"], values["rod_mass_kg"]
    expected = m_c * r**2 / 3.0 + m_r * r**2 / 4.0 + m_r * r**2 / 12.0
    assert mk.generalized_inertia_kg_m2(links, 0.0)[0] == pytest.approx(expected, rel=1e-14)


def equation_of_motion(values):
    """The compiled M(θ) equation of motion as a plain function of (t, [θ, ω, W]) for solve_ivp.

    That it is the Newton–Euler motion is checked point by point above
    (:func:`test_compiled_equation_of_motion_matches_newton_euler`); here scipy
    integrates it independently of the solver core.
    """
    p = links_of(values).kernel_parameters(drive=values["drive"], drive_torque_N_m=values["drive_torque_N_m"])

    def rhs(t, y):
        rate = np.zeros(3)
        mk.mechanism_rhs.compiled(t, np.ascontiguousarray(y, dtype=float), p, rate)
        return rate

    return rhs


TORQUE_CASES = {
    "defaults": {"drive": "torque"},
    "coasting (zero torque)": {"drive": "torque", "drive_torque_N_m": 0.0},
    "braking against gravity": {"drive": "torque", "drive_torque_N_m": -3.0, "offset_m": 0.2, "rod_m": 0.7},
    "heavy slider": {"drive": "torque", "slider_mass_kg": 100.0, "drive_torque_N_m": 40.0},
    "from rest near a dead centre": {"drive": "torque", "crank_speed_rad_s": 0.0, "crank_angle0_deg": 0.5, "drive_torque_N_m": 1.0, "g_m_s2": 0.0},
}


@pytest.mark.parametrize("case", TORQUE_CASES)
def test_torque_drive_agrees_with_scipy_and_accounts_for_energy(case):
    """The solver core's RK4 run (automatic step) against scipy DOP853 (rtol 1e-12) on the same equation.

    The reference's own error (~1e-10 rad) is negligible. RK4 with the step from
    h·ω_fast ≤ 0.1 (ω_fast includes the heavy slider's sharp dip of M(θ) at the
    dead centres) leaves a few 1e-5 rad after 3 s (measured: 5e-8 to 1.6e-5 rad
    in θ, ≤ 1.6e-5 of the top speed in ω); 1e-4 in both is the bound, which a
    step choice that ignores the dip (measured 1.3e-2 rad) or any wrong term in
    M(θ) fails. The work–energy residual T + V − W − T₀ − V₀ stays within 1e-5 of
    the energy in play (measured 4e-8 to 7e-6).
    """
    values = params(**TORQUE_CASES[case])
    model = mk.MechanismKinetics()
    controls = ParameterSet(model.controls()).validate({})
    t_end = 3.0
    report = model.simulate(values, controls, t_end_s=t_end, frame_rate_hz=30.0)
    assert report.status == "ok"
    y0 = model.initial_state(values)
    reference = solve_ivp(equation_of_motion(values), (0.0, t_end), y0, method="DOP853", rtol=1e-12, atol=1e-12, t_eval=report.t_s)
    theta_ref, omega_ref = reference.y[0], reference.y[1]
    assert np.max(np.abs(report.series["crank_angle"] - theta_ref)) < 1e-4
    assert np.max(np.abs(report.series["crank_speed_rad_s"] - omega_ref)) < 1e-4 * max(np.max(np.abs(omega_ref)), 1.0)
    residual = report.series["work_energy_residual_J"]
    assert np.max(np.abs(residual)) < 1e-5 * mk.energy_scale_J(values)
    # Newton–Euler with the given torque reproduces that torque at every frame.
    np.testing.assert_allclose(report.series["driving_torque_N_m"], values["drive_torque_N_m"], rtol=0.0, atol=1e-9 * (1.0 + abs(values["drive_torque_N_m"])))


def test_free_coasting_conserves_mechanical_energy():
    """Zero torque, gravity on: T + V is constant (W stays 0) to 1e-6 of the energy over 20 s of the RK4 run."""
    values = params(drive="torque", drive_torque_N_m=0.0, crank_speed_rad_s=6.0)
    model = mk.MechanismKinetics()
    report = model.simulate(values, ParameterSet(model.controls()).validate({}), t_end_s=20.0, frame_rate_hz=30.0)
    links = links_of(values)
    theta, omega = report.series["crank_angle"], report.series["crank_speed_rad_s"]
    energy = mechanical_energy_J(links, theta, omega)
    assert np.ptp(energy) < 1e-6 * mk.energy_scale_J(values)
    assert np.ptp(omega) > 0.5  # gravity does speed it up and slow it down: the check is not vacuous


def test_speed_drive_work_equals_energy_change_over_a_run():
    """Constant speed: ω stays exact, and the integrated motor work matches ΔV (ΔT = 0 after whole turns) to 1e-8 of the scale."""
    values = params(offset_m=0.2, rod_m=0.7)
    model = mk.MechanismKinetics()
    report = model.simulate(values, ParameterSet(model.controls()).validate({}), t_end_s=5.0, frame_rate_hz=30.0)
    assert np.all(report.series["crank_speed_rad_s"] == values["crank_speed_rad_s"])
    assert np.max(np.abs(report.series["work_energy_residual_J"])) < 1e-8 * mk.energy_scale_J(values)
    assert np.ptp(report.series["driving_torque_N_m"]) > 1.0  # the motor's torque does vary over a turn


@pytest.mark.parametrize(
    "overrides, field",
    [
        ({"drive": "brake"}, "drive"),
        ({"crank_mass_kg": 0.0}, "crank_mass_kg"),
        ({"slider_mass_kg": float("nan")}, "slider_mass_kg"),
        ({"drive_torque_N_m": 1e6}, "drive_torque_N_m"),
        ({"g_m_s2": -1.0}, "g_m_s2"),
    ],
)
def test_bad_input_names_the_field(overrides, field):
    with pytest.raises(ParameterError) as info:
        mk.PARAMETERS.validate(overrides)
    assert info.value.field == field


def test_a_rod_too_short_to_follow_the_crank_is_refused():
    with pytest.raises(ValueError, match="connecting rod"):
        mk.PARAMETERS.validate({"crank_m": 0.5, "rod_m": 0.6, "offset_m": 0.2})


def test_newton_euler_wants_exactly_one_of_acceleration_and_torque():
    links = links_of(params())
    with pytest.raises(ValueError, match="exactly one"):
        mk.newton_euler(links, np.zeros(1), 1.0)
