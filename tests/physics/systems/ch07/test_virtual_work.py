"""Virtual work against Newton: the toggle press against both bars' equilibrium, the slider-crank's
dynamic virtual work against chapter 6's Newton–Euler solve."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from app.physics.core.parameters import ParameterError
from app.physics.systems.ch06 import mechanism_kinetics as mk
from app.physics.systems.ch07 import virtual_work as vw

#: Both answers take a few dozen flops from the same inputs; the 6×6 and 8×8 solves have condition numbers
#: below about 1e4 over the geometries swept (θ ≥ 0.5°, BC at least 3° off vertical), so round-off stays
#: near 1e-12 of the force scale: 1e-10 leaves a hundredfold margin and still catches any wrong term.
AGREEMENT = 1e-10


def press_of(**overrides) -> vw.TogglePress:
    return vw.TogglePress.from_params(vw.TOGGLE_PARAMETERS.validate(overrides))


def load_scale(press: vw.TogglePress) -> float:
    return abs(press.load_B_N) + press.weight_AB_N + press.weight_BC_N


# --- the toggle press -----------------------------------------------------------------------------------------


def test_defaults_give_the_equal_bar_formula_and_the_member_equilibrium():
    press = press_of()
    q = vw.holding_force_by_virtual_work(press)
    # Equal bars: δW = −(P + W₁/2 + W₂/2) a cos θ δθ + 2 Q a sin θ δθ, so Q = (P + (W₁ + W₂)/2) / (2 tan θ).
    assert q == pytest.approx((500.0 + 50.0) / (2.0 * math.tan(math.radians(20.0))), rel=1e-14)
    assert q == pytest.approx(755.5562903500211, rel=1e-12)
    check = vw.toggle_equilibrium(press)
    assert abs(q - check.holding_force_N) <= AGREEMENT * abs(check.holding_force_N)
    # Symmetric frame: the 600 N of load is shared equally by A and the guide at C.
    assert check.pin_A_N[1] == pytest.approx(300.0, rel=1e-12) and check.guide_C_N == pytest.approx(300.0, rel=1e-12)


@settings(max_examples=200, deadline=None)
@given(
    a=st.floats(0.1, 5.0),
    b=st.floats(0.1, 5.0),
    angle_deg=st.floats(0.5, 85.0),
    load=st.floats(-10_000.0, 10_000.0),
    w1=st.floats(0.0, 10_000.0),
    w2=st.floats(0.0, 10_000.0),
)
def test_virtual_work_agrees_with_both_bars_equilibrium_over_geometries_and_loads(a, b, angle_deg, load, w1, w2):
    values = {"bar_AB_m": a, "bar_BC_m": b, "angle_deg": angle_deg, "load_B_N": load, "weight_AB_N": w1, "weight_BC_N": w2}
    try:
        press = vw.TogglePress.from_params(vw.TOGGLE_PARAMETERS.validate(values))
    except ParameterError as exc:
        assert exc.field == "bar_BC_m"  # the only refusal: BC too short to reach the line AC well off vertical
        return
    q = vw.holding_force_by_virtual_work(press)
    check = vw.toggle_equilibrium(press)
    # Relative to the larger of Q and the loads: Q itself may be near zero when P pulls up against the weights.
    assert abs(q - check.holding_force_N) <= AGREEMENT * max(abs(check.holding_force_N), load_scale(press), 1.0)


@pytest.mark.parametrize("overrides", [{}, {"angle_deg": 3.0}, {"angle_deg": 60.0, "bar_AB_m": 0.6, "bar_BC_m": 1.2}, {"bar_BC_m": 2.5, "angle_deg": 45.0}])
def test_virtual_displacements_are_the_derivatives_of_the_positions(overrides):
    """r′(θ) against a central difference of the loop-closed positions (h = 1e-6 rad: truncation ~h² ≈ 1e-12 m,
    round-off ~1e-16/h ≈ 1e-10 m per rad; 1e-8 m/rad holds both with margin)."""
    press = press_of(**overrides)
    h = 1e-6
    ahead = vw.TogglePress(press.bar_AB_m, press.bar_BC_m, press.angle_rad + h, press.load_B_N, press.weight_AB_N, press.weight_BC_N).points()
    behind = vw.TogglePress(press.bar_AB_m, press.bar_BC_m, press.angle_rad - h, press.load_B_N, press.weight_AB_N, press.weight_BC_N).points()
    for point, displacement in press.virtual_displacements().items():
        np.testing.assert_allclose(displacement, (ahead[point] - behind[point]) / (2.0 * h), atol=1e-8, err_msg=point)


def test_the_toggle_position_is_refused_with_its_reason_never_an_infinity():
    press = press_of(angle_deg=0.0)
    with pytest.raises(vw.TogglePositionError, match=r"^θ \(deg\): .*toggle position.*no finite Q") as refused:
        vw.holding_force_by_virtual_work(press)
    assert "angle_deg" not in str(refused.value)  # the page reads θ, the name its control shows
    with pytest.raises(vw.TogglePositionError):
        vw.toggle_equilibrium(press)
    unloaded = press_of(angle_deg=0.0, load_B_N=0.0, weight_AB_N=0.0, weight_BC_N=0.0)
    with pytest.raises(vw.TogglePositionError, match="does not fix Q"):
        vw.holding_force_by_virtual_work(unloaded)


def test_near_the_toggle_the_holding_force_grows_like_one_over_theta():
    """Equal bars: Q θ → (P + (W₁ + W₂)/2)/2 = 275 N as θ → 0; at θ = 0.01° the 1/tan θ formula differs from 1/θ by 1e-8."""
    theta = math.radians(0.01)
    q = vw.holding_force_by_virtual_work(press_of(angle_deg=0.01))
    assert math.isfinite(q) and q * theta == pytest.approx(275.0, rel=1e-7)


def test_a_bar_too_short_to_reach_the_line_is_refused_naming_it():
    with pytest.raises(ParameterError) as refused:
        vw.TOGGLE_PARAMETERS.validate({"bar_AB_m": 2.0, "bar_BC_m": 0.5, "angle_deg": 60.0})
    assert refused.value.field == "bar_BC_m"


# --- the slider-crank by dynamic virtual work ------------------------------------------------------------------

CASES = {
    "defaults": {},
    "offset": {"offset_m": 0.25, "rod_m": 0.8},
    "short rod": {"rod_m": 0.31, "crank_speed_rad_s": -7.0},
    "heavy slider": {"slider_mass_kg": 100.0, "crank_mass_kg": 0.05, "rod_mass_kg": 0.05},
    "no gravity": {"g_m_s2": 0.0},
}
THETA = np.linspace(0.0, 2.0 * math.pi, 97)


def links_of(overrides) -> mk.SliderCrankLinks:
    return mk.SliderCrankLinks.from_params(vw.PARAMETERS.validate(overrides))


@pytest.mark.parametrize("name", CASES)
@pytest.mark.parametrize("alpha", [0.0, 3.0, -40.0])
def test_drive_torque_by_virtual_work_equals_newton_euler(name, alpha):
    links = links_of(CASES[name])
    omega = vw.PARAMETERS.validate(CASES[name])["crank_speed_rad_s"]
    by_virtual_work = vw.driving_torque_by_virtual_work(links, THETA, omega, crank_acceleration_rad_s2=alpha)
    by_newton_euler = mk.newton_euler(links, THETA, omega, crank_acceleration_rad_s2=alpha).driving_torque_N_m
    scale = float(np.max(np.abs(by_newton_euler)))
    assert scale > 1.0  # a real torque, not two zeros agreeing
    np.testing.assert_allclose(by_virtual_work, by_newton_euler, rtol=0.0, atol=AGREEMENT * scale)


@pytest.mark.parametrize("name", CASES)
def test_crank_acceleration_for_a_given_torque_equals_newton_euler(name):
    links = links_of(CASES[name])
    for torque in (2.0, -15.0):
        alpha = vw.crank_acceleration_by_virtual_work(links, THETA, 6.0, drive_torque_N_m=torque)
        expected = mk.newton_euler(links, THETA, 6.0, drive_torque_N_m=torque).crank_acceleration_rad_s2
        np.testing.assert_allclose(alpha, expected, rtol=0.0, atol=AGREEMENT * float(np.max(np.abs(expected))))


@pytest.mark.parametrize("name", CASES)
def test_the_coefficient_of_alpha_is_the_generalized_inertia_from_the_kinetic_energy(name):
    """τ(α = 1) − τ(α = 0) against M(θ) = 2T/θ̇² of chapter 6 (an energy, not a force balance): 1e-12 relative."""
    links = links_of(CASES[name])
    coefficient = vw.driving_torque_by_virtual_work(links, THETA, 5.0, crank_acceleration_rad_s2=1.0) - vw.driving_torque_by_virtual_work(links, THETA, 5.0)
    np.testing.assert_allclose(coefficient, mk.generalized_inertia_kg_m2(links, THETA), rtol=1e-12)


@pytest.mark.parametrize("name", CASES)
def test_pin_and_guide_forces_do_no_virtual_work_though_each_pin_force_alone_does(name):
    links = links_of(CASES[name])
    forces = mk.newton_euler(links, THETA, 10.0, crank_acceleration_rad_s2=0.0)
    work = vw.constraint_virtual_work(links, THETA, forces)
    scale = float(np.max(np.abs(forces.driving_torque_N_m)))
    np.testing.assert_allclose(work.total, 0.0, atol=1e-12 * scale)
    np.testing.assert_array_equal(work.guide, 0.0)  # δr_B is along x, N along y: exactly zero
    assert float(np.max(np.abs(work.crank_pin_on_rod))) > 0.1 * scale  # each term alone is not zero …
    np.testing.assert_allclose(work.crank_pin_on_rod, -work.crank_pin_on_crank, atol=1e-12 * scale)  # … its pair cancels it


def test_worked_numbers_of_the_lesson_at_the_defaults():
    links = links_of({})
    table = vw.dynamic_virtual_work(links, np.radians([0.0, 90.0]), 10.0, 0.0)
    # θ = 0: only gravity needs a torque, (m_c + m_r) g r/2 = 3 (9.80665)(0.15) N·m; the inertia forces do no virtual work.
    assert table.driving_torque_N_m[0] == pytest.approx(3.0 * 9.80665 * 0.15, rel=1e-12)
    assert table.inertia_work_N_m[0] == pytest.approx(0.0, abs=1e-12)
    # θ = 90°: the weights' virtual work vanishes (G₁, G₂ move sideways) and τ = −11.3215 N·m brakes the crank.
    assert table.gravity_work_N_m[1] == pytest.approx(0.0, abs=1e-12)
    assert table.driving_torque_N_m[1] == pytest.approx(-11.32147624, abs=1e-7)


def test_the_closed_form_model_reports_agreeing_torques_over_ten_seconds():
    params = vw.PARAMETERS.defaults()
    report = vw.SliderCrankVirtualWork().simulate(params, {}, t_end_s=10.0, frame_rate_hz=30.0).as_dict()
    assert report["stats"]["status"] == "ok"
    assert report["stats"]["max_invariant_drift"] < AGREEMENT
    series = report["series"]
    np.testing.assert_allclose(series["driving_torque_virtual_work_N_m"], series["driving_torque_newton_euler_N_m"], atol=AGREEMENT * 30.0)
    np.testing.assert_allclose(series["constraint_virtual_work_N_m"], 0.0, atol=1e-10)
