"""The bouncing bar (app/physics/systems/ch06/bouncing_bar.py): impacts in sequence with events and reset maps.

Checked independently of the code under test: the inverse effective mass against a
direct impulse; angular momentum about the contact point before and after every
impact; energy never created at an impact (hypothesis sweep) and the energy ledger
balanced over whole runs; the flat landing's equal impulses and zero spin; event
times against the free-fall closed form; the Zeno cut-off; bad input.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from app.physics.core.parameters import ParameterError
from app.physics.solvers import DormandPrince, simulate
from app.physics.systems.ch06 import bouncing_bar as bb

FLOOR_EVENTS = (bb.EVENT_END_A, bb.EVENT_END_B)


def params(**values):
    return bb.PARAMETERS.validate(values)


def run(values, *, t_end_s=8.0, rtol=1e-10, backend="numba"):
    system = bb.system(values)
    result = simulate(system, DormandPrince(rtol=rtol), bb.initial_state(values), t_end_s=t_end_s, frame_rate_hz=30.0, backend=backend)
    assert result.status == "ok", result.message
    return system, result


def after_reset(event, p):
    """The state just after the reset map at a recorded event (the log holds the state before it)."""
    y = event.state.copy()
    bb.reset_state(y, p, event.t_s, event.index)
    return y


def contact_point(y, p, end):
    return np.array([y[bb.X], y[bb.Z]]) + bb.lever_arm_m(y[bb.THETA], p[bb.P_LENGTH], end)


# -- the contact's inverse effective mass -------------------------------------------------------
@given(theta=st.floats(-math.pi, math.pi), end=st.sampled_from((bb.END_A, bb.END_B)),
       pn=st.floats(-5.0, 5.0), pt=st.floats(-5.0, 5.0))
def test_inverse_effective_mass_maps_an_impulse_to_the_change_of_contact_velocity(theta, end, pn, pt):
    p = bb.parameter_array(params(mass_kg=2.0, length_m=1.5))
    y = bb.initial_state(params())
    y[bb.THETA], y[[bb.VX, bb.VZ, bb.OMEGA]] = theta, (0.3, -1.2, 0.7)
    r = bb.lever_arm_m(theta, p[bb.P_LENGTH], end)
    before = bb.contact_velocity_m_s(y, r)
    bb._apply_impulse(y, p, r, np.array([pn, pt]))
    expected = bb.inverse_effective_mass(p[bb.P_MASS], p[bb.P_INERTIA], r) @ np.array([pn, pt])
    # Δv = W P is linear algebra on O(10) numbers: round-off only.
    np.testing.assert_allclose(bb.contact_velocity_m_s(y, r) - before, expected, rtol=0.0, atol=1e-13)


def test_inertia_is_the_slender_rod_moment():
    p = bb.parameter_array(params(mass_kg=3.0, length_m=2.0))
    assert p[bb.P_INERTIA] == pytest.approx(3.0 * 2.0**2 / 12.0, rel=1e-15)


# -- one impact: angular momentum about the contact point, energy never created -----------------
@settings(max_examples=300, deadline=None)
@given(
    theta=st.floats(0.1, 1.5), omega=st.floats(-10.0, 10.0), vx=st.floats(-3.0, 3.0), vz=st.floats(-6.0, 1.0),
    e=st.floats(0.0, 1.0), mu=st.floats(0.0, 2.0), end=st.sampled_from((bb.END_A, bb.END_B)),
)
def test_a_single_impact_keeps_angular_momentum_about_the_contact_and_never_creates_energy(theta, omega, vx, vz, e, mu, end):
    values = params(restitution=e, friction_coefficient=mu)
    p = bb.parameter_array(values)
    y = bb.initial_state(values)
    sign = 1.0 if end == bb.END_A else -1.0
    y[bb.THETA] = sign * theta  # the striking end is the lower one, on the floor; the other is ≥ 10 cm up
    y[bb.Z] = 0.5 * p[bb.P_LENGTH] * math.sin(theta)
    y[bb.VX], y[bb.VZ], y[bb.OMEGA] = vx, vz, omega
    r = bb.lever_arm_m(y[bb.THETA], p[bb.P_LENGTH], end)
    assume(bb.contact_velocity_m_s(y, r)[0] < -1e-3)
    point = contact_point(y, p, end)
    h_before, energy_before = bb.angular_momentum_about_point(y, p, point), float(bb.mechanical_energy_J(y, p))
    bb.reset_state(y, p, 0.0, bb.EVENT_END_A if end == bb.END_A else bb.EVENT_END_B)
    assert y[bb.IMPACTS] == 1.0
    energy_after = float(bb.mechanical_energy_J(y, p)) + y[bb.LOST]
    scale = energy_before + p[bb.P_MASS] * 1.0  # J: round-off is relative to the kinetic energy in play
    # The ledger: kinetic + potential + lost is what it was (round-off: ~1e-15 of the energies involved).
    assert energy_after == pytest.approx(energy_before, abs=1e-12 * scale)
    assert y[bb.LOST] >= 0.0 and y[bb.LAST_LOSS] >= -1e-12 * scale
    if y[bb.MODE] == bb.FLIGHT:  # (a settled bar has been stopped on purpose; its momentum is not kept)
        # The floor's impulse acts through the contact point and gravity's impulse is zero in an instant.
        h_scale = p[bb.P_INERTIA] * abs(omega) + p[bb.P_MASS] * p[bb.P_LENGTH] * (abs(vx) + abs(vz)) + 1e-3
        assert bb.angular_momentum_about_point(y, p, point) == pytest.approx(h_before, abs=1e-13 * h_scale)
        # And the struck end leaves the floor (or slides along it): never into it.
        assert bb.contact_velocity_m_s(y, r)[0] >= -1e-12


def test_every_impact_of_a_run_keeps_angular_momentum_about_its_contact_point():
    values = params(angle0_deg=40.0, restitution=0.7, friction_coefficient=0.5)
    system, result = run(values)
    p = system.parameters
    impacts = [event for event in result.events if event.index in FLOOR_EVENTS]
    assert len(impacts) >= 8
    for event in impacts:
        after = after_reset(event, p)
        struck = [end for end in (bb.END_A, bb.END_B) if after[bb.PN_A + 2 * end] != 0.0]
        if after[bb.MODE] != bb.FLIGHT or len(struck) != 1:
            continue
        point = contact_point(event.state, p, struck[0])
        before_h = bb.angular_momentum_about_point(event.state, p, point)
        assert bb.angular_momentum_about_point(after, p, point) == pytest.approx(before_h, rel=1e-12, abs=1e-12)


# -- whole runs: the energy ledger ------------------------------------------------------------
def test_perfectly_elastic_frictionless_bouncing_keeps_energy_to_1e12():
    values = params(restitution=1.0, friction_coefficient=0.0, angle0_deg=35.0)
    system, result = run(values, t_end_s=10.0)
    impacts = [event for event in result.events if event.index in FLOOR_EVENTS]
    assert len(impacts) >= 20
    energy = bb.mechanical_energy_J(result.states, system.parameters)
    # Free flight is a polynomial Dormand–Prince integrates exactly and e = 1, μ = 0 loses nothing:
    # what is left is round-off (observed ≈ 2e-15 relative).
    assert np.max(np.abs(energy - energy[0])) <= 1e-12 * energy[0]
    assert np.all(result.states[:, bb.LOST] == 0.0)
    assert np.all(result.states[:, bb.MODE] == bb.FLIGHT)


@pytest.mark.parametrize("overrides", [{}, {"angle0_deg": 0.0}, {"angle0_deg": 80.0, "friction_coefficient": 1.5}, {"restitution": 0.0}])
def test_kinetic_plus_potential_plus_losses_stays_the_initial_energy(overrides):
    values = params(**overrides)
    system, result = run(values, t_end_s=10.0)
    balance = bb.BouncingBar().invariants(values, result.states)["energy_balance"]
    initial = balance[0]
    # Every loss (impacts, settling, friction while sliding) is booked: the balance moves only by the
    # integration error of the resting slide's friction work (rtol 1e-10) and round-off; 1e-9 relative.
    assert np.max(np.abs(balance - initial)) <= 1e-9 * initial
    assert np.all(np.diff(result.states[:, bb.LOST]) >= 0.0)


def test_the_bar_comes_to_rest_and_the_zeno_cascade_is_cut_off():
    values = params()
    _, result = run(values, t_end_s=10.0)
    final = result.states[-1]
    assert final[bb.MODE] == bb.RESTING
    assert final[bb.Z] == 0.0 and final[bb.VZ] == 0.0 and final[bb.OMEGA] == 0.0 and final[bb.VX] == 0.0
    assert math.sin(final[bb.THETA]) == pytest.approx(0.0, abs=1e-15)
    # All the initial energy m g h₀ has been lost (lying flat at z = 0 there is none left).
    assert final[bb.LOST] == pytest.approx(values["mass_kg"] * values["g_m_s2"] * values["drop_height_m"], rel=1e-9)
    # Finitely many impacts, and the last followed bounce was still slower than the cut-off permits to go on.
    assert 5 <= final[bb.IMPACTS] < 100


def test_a_plastic_landing_on_one_end_stops_the_model_and_says_so():
    values = params(restitution=0.0)
    _, result = run(values, t_end_s=2.0)
    final = result.states[-1]
    assert final[bb.MODE] == bb.SETTLED_ON_END and final[bb.IMPACTS] == 1.0
    # The end stayed on the floor: nothing sank through it.
    end_a, end_b = bb.end_positions_m(result.states, values["length_m"])
    assert min(end_a[:, 1].min(), end_b[:, 1].min()) >= -1e-9


# -- the flat landing ---------------------------------------------------------------------------
def test_a_flat_landing_strikes_both_ends_at_once_with_equal_impulses_and_no_spin():
    values = params(angle0_deg=0.0, restitution=0.6, friction_coefficient=0.4)
    system, result = run(values, t_end_s=0.6)
    first = next(event for event in result.events if event.index in FLOOR_EVENTS)
    after = after_reset(first, system.parameters)
    assert after[bb.IMPACTS] == 1.0  # one simultaneous impact, not two in a row
    assert after[bb.PN_A] == after[bb.PN_B] > 0.0
    assert after[bb.OMEGA] == 0.0
    # The common mode is a point mass on the floor: ż after = −e ż before (energetic e, no tangential motion).
    assert after[bb.VZ] == pytest.approx(-0.6 * first.state[bb.VZ], rel=1e-14)
    assert np.all(result.states[:, bb.OMEGA] == 0.0)


def test_a_flat_rocking_bar_gets_positive_impulses_and_each_end_rebounds_at_e():
    values = params(restitution=0.5, friction_coefficient=0.0)
    p = bb.parameter_array(values)
    y = bb.initial_state(values)
    y[bb.Z], y[bb.THETA], y[bb.VZ], y[bb.OMEGA] = 0.0, 0.0, -2.0, 1.5  # ends: −2.75 and −1.25 m/s
    before = [bb.contact_velocity_m_s(y, bb.lever_arm_m(0.0, 1.0, end))[0] for end in (bb.END_A, bb.END_B)]
    energy_before = float(bb.mechanical_energy_J(y, p))
    bb.reset_state(y, p, 0.0, bb.EVENT_END_A)
    after = [bb.contact_velocity_m_s(y, bb.lever_arm_m(0.0, 1.0, end))[0] for end in (bb.END_A, bb.END_B)]
    assert y[bb.IMPACTS] == 1.0 and y[bb.PN_A] > 0.0 and y[bb.PN_B] > 0.0
    # Frictionless and decoupled: each mode, and so each end, rebounds at −e times its approach (round-off).
    np.testing.assert_allclose(after, -0.5 * np.array(before), rtol=1e-14)
    assert float(bb.mechanical_energy_J(y, p)) + y[bb.LOST] == pytest.approx(energy_before, rel=1e-14)


def test_a_nearly_flat_landing_is_two_impacts_in_sequence_and_makes_the_bar_spin():
    # 0.01° of tilt puts end B 0.17 mm above end A: they strike 22 µs apart, one after the other.
    values = params(angle0_deg=0.01, restitution=0.6, friction_coefficient=0.4)
    system, result = run(values, t_end_s=0.6)
    impacts = [event for event in result.events if event.index in FLOOR_EVENTS]
    assert [event.index for event in impacts[:2]] == [bb.EVENT_END_A, bb.EVENT_END_B]
    assert impacts[1].t_s - impacts[0].t_s < 1e-3
    assert abs(after_reset(impacts[1], system.parameters)[bb.OMEGA]) > 1.0  # rad/s: the order of the strikes shows


# -- event location ---------------------------------------------------------------------------
def test_the_first_impact_is_located_at_the_free_fall_time():
    values = params(angle0_deg=30.0, drop_height_m=1.2, length_m=0.8)
    system, result = run(values, t_end_s=1.0)
    first = result.events[0]
    fall_m = values["drop_height_m"] - 0.4 * math.sin(math.radians(30.0))
    # The fall is a parabola the integrator follows exactly; the Illinois iteration stops at ~1e-13 of a
    # step (≤ 2.5 ms): 1e-12 s is far below anything else in the model.
    assert first.index == bb.EVENT_END_A
    assert first.t_s == pytest.approx(math.sqrt(2.0 * fall_m / values["g_m_s2"]), abs=1e-12)


def test_every_impact_is_located_on_the_floor():
    values = params(angle0_deg=60.0, restitution=0.8, friction_coefficient=0.2)
    _, result = run(values, t_end_s=6.0, rtol=1e-8)
    for event in result.events:
        if event.index in FLOOR_EVENTS:
            end = bb.END_A if event.index == bb.EVENT_END_A else bb.END_B
            height = bb.end_positions_m(event.state, values["length_m"])[end][0, 1]
            # The root of the dense output's height: within 1e-9 m (the sin θ term carries the step's
            # local error, ~rtol × L² θ̇² scale, measured ≤ 1e-12 m here).
            assert abs(height) <= 1e-9


def test_no_end_ever_goes_through_the_floor():
    for overrides in ({}, {"angle0_deg": 45.0}, {"angle0_deg": 80.0}, {"friction_coefficient": 0.0}, {"restitution": 0.9}):
        values = params(**overrides)
        _, result = run(values, t_end_s=8.0, rtol=1e-8)
        end_a, end_b = bb.end_positions_m(result.states, values["length_m"])
        assert min(end_a[:, 1].min(), end_b[:, 1].min()) >= -1e-9, overrides


def test_the_compiled_kernels_and_their_python_twins_agree():
    values = params(angle0_deg=50.0)
    _, compiled = run(values, t_end_s=2.0)
    _, python = run(values, t_end_s=2.0, backend="python")
    np.testing.assert_allclose(compiled.states, python.states, rtol=1e-12, atol=1e-12)
    assert [e.index for e in compiled.events] == [e.index for e in python.events]


def test_the_simulate_answer_says_the_bar_settled_on_one_end_in_the_readouts_words():
    """Issue 24, Found 12: e = 0, released at 30°: end A lands at t = √(2 (h − L/2 sin 30°)/g) and stays down, tilted;
    the answer ran on to 3 s with status ok and no message. It now ends at the frame it settled in, status "settled",
    with :func:`mode_message` (the live readout's text) for that state."""
    values = params(restitution=0.0)
    report = bb.BouncingBar().simulate(values, {}, t_end_s=3.0, frame_rate_hz=60.0)
    landing_s = math.sqrt(2.0 * (values["drop_height_m"] - values["length_m"] / 2 * math.sin(math.radians(30.0))) / values["g_m_s2"])
    assert report.status == bb.SETTLED
    assert report.t_s[-1] == pytest.approx(math.ceil(landing_s * 60.0) / 60.0, abs=1e-12)
    _, result = run(values, t_end_s=3.0)  # the same motion, whole: its last state is the settled one
    final = result.states[-1]
    assert final[bb.MODE] == bb.SETTLED_ON_END
    assert report.message == bb.mode_message(values, final) and report.message.startswith(f"Settled on one end at t = {landing_s:.2f} s")


def test_a_bar_that_comes_to_rest_flat_is_still_ok():
    """Laid flat by the cut-off, the bar is a body at rest on the floor, which the model describes: no limit is met."""
    report = bb.BouncingBar().simulate(params(angle0_deg=0.0), {}, t_end_s=5.0, frame_rate_hz=30.0)
    assert report.status == "ok" and report.t_s[-1] == pytest.approx(5.0)


# -- contract and input --------------------------------------------------------------------------
def test_simulate_reports_the_contract_series():
    values = params()
    report = bb.BouncingBar().simulate(values, {}, t_end_s=5.0, frame_rate_hz=30.0)
    assert report.status == "ok"
    assert set(report.series) == {"angle", "centre_height_m", "energy_J", "impact_count", "energy_lost_J"}
    assert report.series["angle"][0] == pytest.approx(math.radians(30.0))
    assert report.series["centre_height_m"][0] == 1.0
    assert report.max_invariant_drift < 1e-9


def test_a_bar_released_through_the_floor_is_refused_naming_the_height():
    with pytest.raises(ParameterError, match=r"^h₀ \(m\): must put the lower end") as info:  # as its control shows it
        params(drop_height_m=0.3, angle0_deg=60.0, length_m=1.0)
    assert info.value.field == "drop_height_m"
