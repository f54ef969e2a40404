"""The floor's hold on a rolling disk (issue 24, Found 12): its normal force, and the one rule both rolling models stop by.

References: the lean equation θ̈ against the Kane equations the engine derives (an independent derivation); the normal
force against m (g + z̈_G) differentiated from a tight run (z_G = r cos θ); and, for a disk toppling without spin, the
closed form N / m g = 0.2 + 2.4 cos²θ − 1.6 cos θ₀ cos θ from energy conservation (θ̇² = (8 g / 5 r)(cos θ₀ − cos θ)),
whose zero is where the disk lifts off: at cos θ = ½ (60°) from upright. (The same reasoning for a slender rod on
its end gives the textbook N / m g = (3 cos θ − 1)² / 4, which touches zero but never goes below: a thin disk's larger
share of its moment of inertia about the contact in m r² is what makes it lift.)
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from app.physics.mechanics.engine import derived
from app.physics.systems.ch08.rolling_disk_constrained_model import UnsteadyRollingDisk
from app.physics.systems.ch09.rolling_disk import SYSTEM
from app.physics.systems.ch09.rolling_disk_contact import (
    FALLEN,
    FALLEN_LEAN_DEG,
    LIFT_OFF,
    contact_limit,
    lean_acceleration_rad_s2,
    normal_force_N,
)
from app.physics.systems.ch09.rolling_disk_model import RollingDiskMotion

PARAMS = {"mass_kg": 1.3, "radius_m": 0.12, "g_m_s2": 9.81}
RNG = np.random.default_rng(2024)


def rolling_states(count: int) -> np.ndarray:
    """(N, 10) states on the rolling constraint: ẋ = r φ̇ cos ψ, ẏ = r φ̇ sin ψ; leans within ±80°, rates of a few rad/s."""
    states = np.zeros((count, 10))
    states[:, :2] = RNG.uniform(-1, 1, (count, 2))
    states[:, 2] = RNG.uniform(-math.pi, math.pi, count)
    states[:, 3] = RNG.uniform(-1.4, 1.4, count)
    states[:, 4] = RNG.uniform(-3, 3, count)
    states[:, 7:10] = RNG.uniform(-6, 6, (count, 3))
    r = PARAMS["radius_m"]
    states[:, 5] = r * states[:, 9] * np.cos(states[:, 2])
    states[:, 6] = r * states[:, 9] * np.sin(states[:, 2])
    return states


def toppling_normal_force_N(lean_0_rad: float, lean_rad: np.ndarray) -> np.ndarray:
    """N (N) of the disk toppling from rest at θ₀ without spin or turn, at lean θ: m g (0.2 + 2.4 c² − 1.6 c₀ c)."""
    m, g = PARAMS["mass_kg"], PARAMS["g_m_s2"]
    c0, c = math.cos(lean_0_rad), np.cos(lean_rad)
    return m * g * (0.2 + 2.4 * c**2 - 1.6 * c0 * c)


@pytest.mark.parametrize("formulation", ["kane", "gibbs-appell", "newton-euler"])
def test_the_lean_equation_is_the_derived_one(formulation):
    """θ̈ of the module's formula against the engine's derivation at 40 rolling states: both evaluate the same exact
    equations in double precision, so they agree to rounding (1e-11 of the largest term, g/r ≈ 80 rad/s²)."""
    states = rolling_states(40)
    p = np.array(SYSTEM.parameter_array(PARAMS))
    derivation = derived(SYSTEM, formulation)
    expected = np.array([derivation.state_derivative(0.0, y, p)[8] for y in states])
    np.testing.assert_allclose(lean_acceleration_rad_s2(PARAMS, states), expected, rtol=0, atol=1e-11 * PARAMS["g_m_s2"] / PARAMS["radius_m"])


def test_upright_the_normal_force_is_m_g_minus_r_theta_dot_squared():
    """At θ = 0, sin θ = 0 removes θ̈: N = m (g − r θ̇²) exactly, whatever the spin and turn."""
    states = rolling_states(20)
    states[:, 3] = 0.0
    m, r, g = PARAMS["mass_kg"], PARAMS["radius_m"], PARAMS["g_m_s2"]
    np.testing.assert_allclose(normal_force_N(PARAMS, states), m * (g - r * states[:, 8] ** 2), rtol=1e-15, atol=1e-15)


def test_the_normal_force_along_a_run_is_m_g_plus_m_times_the_centres_vertical_acceleration():
    """A wobbling turn (lean 20°, spin 20, turn 5 rad/s), dopri5 at rtol 1e-12 sampled at 2000 frames/s: z̈_G from the
    fourth-order central difference of z_G = r cos θ errs by ~h⁴ z⁽⁶⁾/90 ≈ 1e-12·(20 rad/s)⁶ r ≈ 1e-5 m/s², far below
    the 1e-3 N (1e-4 of m g) bound, which a dropped term of N (θ̇² cos θ alone is ~0.3 N here) breaks by 300×."""
    model = RollingDiskMotion()
    params = model.parameters.validate({**PARAMS, "lean_0_deg": 20.0, "spin_rate_0_rad_s": 20.0, "heading_rate_0_rad_s": 5.0})
    report = model.simulate(params, {"method": "dopri5", "rtol": 1e-12}, t_end_s=1.0, frame_rate_hz=2000.0, request_limits=False)
    assert report.status == "ok"
    h = 1.0 / 2000.0
    z = PARAMS["radius_m"] * np.cos(report.series["lean_rad"])
    z_ddot = (-z[4:] + 16 * z[3:-1] - 30 * z[2:-2] + 16 * z[1:-3] - z[:-4]) / (12 * h * h)
    expected = PARAMS["mass_kg"] * (PARAMS["g_m_s2"] + z_ddot)
    np.testing.assert_allclose(report.series["normal_force_N"][2:-2], expected, rtol=0, atol=1e-3)


@pytest.mark.parametrize("model_class", [RollingDiskMotion, UnsteadyRollingDisk])
def test_a_disk_toppling_from_near_upright_lifts_off_where_the_closed_form_says(model_class):
    """From 5° without spin: N follows the closed form at every frame (1e-6 of m g: the run's 1e-6 accuracy target, in
    θ, moves N by less), and the run stops as lift-off at the last frame before N's zero at
    cos θ = (1.6 c₀ + √(2.56 c₀² − 1.92)) / 4.8 (θ = 60.25°), with the same status and words in both models."""
    model = model_class()
    lean_0 = math.radians(5.0)
    params = model.parameters.validate({**PARAMS, "lean_0_deg": 5.0, "spin_rate_0_rad_s": 0.0})
    report = model.simulate(params, {}, t_end_s=3.0, frame_rate_hz=240.0) if hasattr(model, "simulate") else (
        model.simulate(params, {}, t_end_s=3.0, frame_rate_hz=240.0))
    assert report.status == LIFT_OFF and "floor would have to pull" in report.message, report.message
    lean = np.abs(report.series["lean_rad"])
    np.testing.assert_allclose(report.series["normal_force_N"], toppling_normal_force_N(lean_0, lean), rtol=0, atol=1e-6 * 9.81 * 1.3)
    c0 = math.cos(lean_0)
    lift_lean = math.acos((1.6 * c0 + math.sqrt(2.56 * c0**2 - 1.92)) / 4.8)
    assert lean[-1] < lift_lean and np.all(report.series["normal_force_N"] >= 0.0)
    # The next frame (not kept) is past it: the lean grows by θ̇ h per frame, θ̇ = √((8 g / 5 r)(c₀ − c)) = 8.1 rad/s there.
    assert lift_lean - lean[-1] < 8.1 / 240
    assert math.degrees(lift_lean) == pytest.approx(60.25, abs=0.01)


@pytest.mark.parametrize("model_class", [RollingDiskMotion, UnsteadyRollingDisk])
def test_a_disk_falling_from_sixty_degrees_stops_as_fallen_in_both_models(model_class):
    """Issue 24, Found 12: rolling-disk from 60° without spin reached 300° of lean (through the floor) with status ok.
    From 60° N stays positive (its least value is m g (0.2 − 0.2667 c₀²) > 0), so the fall ends it, at 85°."""
    model = model_class()
    params = model.parameters.validate({**PARAMS, "lean_0_deg": 60.0, "spin_rate_0_rad_s": 0.0})
    report = model.simulate(params, {}, t_end_s=3.0, frame_rate_hz=60.0) if hasattr(model, "simulate") else (
        model.simulate(params, {}, t_end_s=3.0, frame_rate_hz=60.0))
    assert report.status == FALLEN and "85°" in report.message
    assert np.all(np.degrees(np.abs(report.series["lean_rad"])) < FALLEN_LEAN_DEG) and report.t_s[-1] < 0.5


def test_the_rule_keeps_the_start_and_says_when_the_floor_would_pull():
    """The unsteady disk rocked upright at 20 rad/s: N(0) = m (g − r θ̇²) < 0, so nothing after the start is kept."""
    m, r, g = PARAMS["mass_kg"], PARAMS["radius_m"], PARAMS["g_m_s2"]
    state = np.zeros((3, 10))
    state[:, 8] = 20.0
    limit = contact_limit(PARAMS, np.array([0.0, 0.1, 0.2]), state)
    assert limit is not None and limit.frames == 1 and limit.status == LIFT_OFF
    assert limit.message.startswith("At the start: the floor would have to pull") and f"N = {m * (g - r * 400.0):.3g} N" in limit.message
    assert contact_limit(PARAMS, np.zeros(1), np.zeros((1, 10))) is None  # standing still upright: N = m g
