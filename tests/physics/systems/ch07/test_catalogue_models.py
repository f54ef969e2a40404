"""Chapter-7 catalogue models (double pendulum, cart pendulum, bead on a spinning hoop) against the physics.

The linearisations take the Jacobian of the *generated* right-hand side by
central differences with step h = 1e-5: the truncation error is about
h² |f'''| / 6 ≈ 1e-10 relative here and rounding about ε/h ≈ 1e-11, so
frequencies agree with the closed forms to far better than the 1e-6 asked.
Long runs use dopri5 at rtol 1e-11 (atol follows): its global error over 10 s
is below 1e-9 of the invariants' scales, so 1e-8 is a bound that a wrong
equation (or a wrong invariant) exceeds by orders of magnitude.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import simpson

from app.physics.mechanics.engine import available_formulations
from app.physics.solvers import simulate
from app.physics.solvers.step_policy import choose_integrator
from app.physics.systems.ch07.bead_on_hoop_model import BeadOnHoopMotion, critical_spin_rad_s, hoop_equilibria
from app.physics.systems.ch07.double_pendulum_model import DoublePendulumMotion, normal_mode_frequencies_rad_s
from app.physics.systems.ch07.pendulum_on_cart_model import CartPendulumMotion, drive_force_N

TIGHT = {"method": "dopri5", "rtol": 1e-11}
#: Conserved quantities over 10 s at TIGHT, relative to the model's invariant scale.
CONSERVED_TO = 1e-8


def formulations(model) -> list[str]:
    return [f for f, reason in available_formulations(model.description).items() if not reason]


def linearised_flow(model, params, state: np.ndarray) -> np.ndarray:
    """∂ẏ/∂y (2n, 2n) of the model's generated right-hand side at ``state``, by central differences."""
    derivation, p = model.derived(params), model.parameter_array(params)
    columns = []
    for j in range(len(state)):
        step = np.zeros(len(state))
        step[j] = 1e-5
        up = derivation.state_derivative(0.0, state + step, p)
        down = derivation.state_derivative(0.0, state - step, p)
        columns.append((up - down) / 2e-5)
    return np.array(columns).T


def oscillation_frequencies(model, params, state) -> np.ndarray:
    """The positive imaginary parts (rad/s) of the linearised flow's eigenvalues, ascending."""
    eigenvalues = np.linalg.eigvals(linearised_flow(model, params, state))
    return np.sort(eigenvalues.imag[eigenvalues.imag > 0])


def run(model, params, t_end_s: float = 10.0, frame_rate_hz: float = 30.0):
    return simulate(model.system(params), choose_integrator(model, params, TIGHT, 1.0 / frame_rate_hz)[0], model.initial_state(params),
                    t_end_s=t_end_s, frame_rate_hz=frame_rate_hz)  # fmt: skip


# --- double pendulum ------------------------------------------------------------------------------------------


@pytest.mark.parametrize("formulation", formulations(DoublePendulumMotion))
def test_double_pendulum_equal_masses_small_oscillations_match_two_minus_and_plus_root_two(formulation):
    params = DoublePendulumMotion.parameters.validate({"l1_m": 0.8, "l2_m": 0.8, "formulation": formulation})
    found = oscillation_frequencies(DoublePendulumMotion(), params, np.zeros(4))
    expected = np.sqrt(9.81 / 0.8 * np.array([2.0 - math.sqrt(2.0), 2.0 + math.sqrt(2.0)]))
    np.testing.assert_allclose(found, expected, rtol=1e-6)


@pytest.mark.parametrize("masses_lengths", [(2.0, 0.5, 1.3, 0.7), (0.3, 3.0, 0.5, 2.0)])
def test_double_pendulum_general_small_oscillations_match_the_closed_form(masses_lengths):
    m1, m2, l1, l2 = masses_lengths
    params = DoublePendulumMotion.parameters.validate({"m1_kg": m1, "m2_kg": m2, "l1_m": l1, "l2_m": l2})
    found = oscillation_frequencies(DoublePendulumMotion(), params, np.zeros(4))
    np.testing.assert_allclose(found, normal_mode_frequencies_rad_s(params), rtol=1e-6)


def test_double_pendulum_conserves_energy_through_a_chaotic_swing():
    model = DoublePendulumMotion()
    params = model.parameters.validate({"theta1_0_deg": 120.0, "theta2_0_deg": -30.0, "theta2_rate_0_deg_s": 200.0})
    result = run(model, params)
    assert result.status == "ok"
    assert np.ptp(result.states[:, 1]) > math.pi, "a chaotic swing: the lower rod should go far"
    assert model.relative_drift(params, result.states)["energy"].max() < CONSERVED_TO


# --- cart pendulum -----------------------------------------------------------------------------------------------


def test_cart_energy_change_equals_the_work_of_the_drive():
    """ΔE = ∫ F ẋ dt: against the work slot, and against Simpson's rule on the power sampled at 2 kHz.

    Simpson at 2 kHz on a power that varies at a few rad/s has error ~ (ω h)⁴ ≈ 1e-13 relative; 1e-7 leaves
    room for the dense-output interpolation of the samples.
    """
    model = CartPendulumMotion()
    params = model.parameters.validate({"force_amplitude_N": 8.0, "force_frequency_rad_s": 2.5, "theta_0_deg": 10.0})
    result = run(model, params, t_end_s=10.0, frame_rate_hz=2000.0)
    assert result.status == "ok"
    energy = model.energy_J(params, result.t_s, result.states)
    power = drive_force_N(model.parameter_array(params), result.t_s) * result.states[:, 2]
    work_quadrature = simpson(power, x=result.t_s)
    work_slot = result.states[-1, 4]
    assert abs(work_slot) > 1.0, "the test needs the drive to do real work"
    assert abs(work_quadrature - work_slot) < 1e-7 * abs(work_slot)
    scale = model.invariant_scales(params, result.states[0])["energy_balance"]
    assert abs((energy[-1] - energy[0]) - work_slot) < CONSERVED_TO * scale
    assert model.relative_drift(params, result.states)["energy_balance"].max() < CONSERVED_TO


def test_cart_without_the_drive_conserves_energy_and_does_no_work():
    model = CartPendulumMotion()
    params = model.parameters.validate({"x0_m": 0.3, "theta_0_deg": 40.0})
    result = run(model, params)
    energy = model.energy_J(params, result.t_s, result.states)
    scale = model.invariant_scales(params, result.states[0])["energy_balance"]
    assert np.all(result.states[:, 4] == 0.0)
    assert np.max(np.abs(energy - energy[0])) < CONSERVED_TO * scale


@pytest.mark.parametrize("formulation", formulations(CartPendulumMotion))
def test_cart_kernel_with_work_matches_the_derivation(formulation):
    """The appended work slot leaves (q̇, q̈) exactly as derived: python twin against the derivation."""
    model = CartPendulumMotion()
    params = model.parameters.validate({"force_amplitude_N": 3.0, "formulation": formulation})
    state = np.array([0.2, 0.5, -0.3, 1.1, 0.0])
    p = model.parameter_array(params)
    out = np.empty(5)
    model.system(params).rhs.python(0.7, state, p, out)
    np.testing.assert_array_equal(out[:4], model.derived(params).state_derivative(0.7, state[:4], p))
    assert out[4] == pytest.approx(3.0 * math.cos(3.0 * 0.7) * -0.3, rel=1e-15)


# --- bead on the spinning hoop ------------------------------------------------------------------------------------


@pytest.mark.parametrize("spin_rad_s", [5.0, 6.0, 12.0])
def test_hoop_off_bottom_equilibrium_has_zero_acceleration_and_is_stable(spin_rad_s):
    """At cos θ* = g/(RΩ²) the derived θ̈ vanishes (to 1e-10 of g/R); linearised, δθ̈ = −Ω² sin²θ* δθ."""
    model = BeadOnHoopMotion()
    params = model.parameters.validate({"hoop_speed_rad_s": spin_rad_s})
    g_over_R = 9.81 / 0.5
    assert spin_rad_s > critical_spin_rad_s(params)
    off_bottom = math.acos(g_over_R / spin_rad_s**2)
    for equilibrium in hoop_equilibria(params)[2:]:
        assert abs(equilibrium.theta_rad) == pytest.approx(off_bottom, rel=1e-15) and equilibrium.stable
        for formulation in formulations(model):
            derivation = model.derived({**params, "formulation": formulation})
            acceleration = derivation.state_derivative(0.0, np.array([equilibrium.theta_rad, 0.0]), model.parameter_array(params))[1]
            assert abs(acceleration) < 1e-10 * g_over_R
    frequency = oscillation_frequencies(model, params, np.array([off_bottom, 0.0]))
    np.testing.assert_allclose(frequency, [spin_rad_s * math.sin(off_bottom)], rtol=1e-6)


def test_hoop_bottom_loses_stability_at_the_critical_spin():
    model = BeadOnHoopMotion()
    below = model.parameters.validate({"hoop_speed_rad_s": 3.0})
    above = model.parameters.validate({"hoop_speed_rad_s": 6.0})
    assert critical_spin_rad_s(below) == pytest.approx(math.sqrt(9.81 / 0.5), rel=1e-15)
    np.testing.assert_allclose(oscillation_frequencies(model, below, np.zeros(2)), [math.sqrt(9.81 / 0.5 - 9.0)], rtol=1e-6)
    growth = np.linalg.eigvals(linearised_flow(model, above, np.zeros(2))).real.max()
    assert growth == pytest.approx(math.sqrt(36.0 - 9.81 / 0.5), rel=1e-6)
    assert [e.stable for e in hoop_equilibria(below)] == [True, False]
    assert [e.stable for e in hoop_equilibria(above)] == [False, False, True, True]


def test_hoop_conserves_the_jacobi_integral_while_the_energy_changes():
    model = BeadOnHoopMotion()
    params = model.parameters.validate({"theta_0_deg": 20.0})
    result = run(model, params)
    assert result.status == "ok"
    scale = model.invariant_scales(params, result.states[0])["jacobi_integral"]
    series = model.series(params, result.t_s, result.states)
    assert np.max(np.abs(series["jacobi_integral_J"] - series["jacobi_integral_J"][0])) < CONSERVED_TO * scale
    assert np.ptp(series["energy_J"]) > 0.1 * scale, "the motor's work should change the energy visibly"
