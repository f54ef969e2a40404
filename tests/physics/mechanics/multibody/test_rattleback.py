"""The rattleback described by its parts (Kane and Levinson's ellipsoid), against independent computations.

Checks: Kane's and Lagrange's equations agree; the energy is conserved; the floor's push (the configuration row's
multiplier) is Newton's m (z̈_G + g); the small rocking frequencies at rest are the closed form of a body rocking on
its radii of curvature; and the whole motion, through the spin's reversal, is that of an independent Newton–Euler
model written here from scratch (Euler's equations about G with the contact force, the touching point moving over
the ellipsoid), with no part of the engine.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.linalg import eigh

from app.physics.core.parameters import ParameterError
from app.physics.math.rotations import elementary_rotation_matrix
from app.physics.mechanics.multibody.compiled import compiled
from app.physics.mechanics.multibody.linearise import eigenvalues, state_matrix
from app.physics.systems.ch08 import rattleback
from app.physics.systems.ch08.rattleback_model import (
    PARAMETERS,
    RattlebackMotion,
    body_velocity,
    check_body,
    orientation,
    system_params,
)

DEFAULTS = rattleback.PARAMETERS.defaults()


@pytest.fixture(scope="module")
def model():
    return compiled(rattleback.SYSTEM)


def _kane_levinson_start(model, p, spin_rad_s: float):
    """Kane and Levinson's start: roll 0.5°, their pitch 0.5° (ours −0.5°), ω = (0, 0, spin) in the body's axes."""
    q = np.zeros(6)
    q[4], q[5] = math.radians(0.5), -math.radians(0.5)
    rates_to_omega = np.column_stack([body_velocity(q, np.eye(6)[k]) for k in range(3, 6)])
    u = np.zeros(6)
    u[3:] = np.linalg.solve(rates_to_omega, [0.0, 0.0, spin_rad_s])
    return model.assemble(q, u, p)


def _run(model, p, q, u, t_end_s: float, **tolerances):
    def rates(_t: float, y: np.ndarray) -> np.ndarray:
        out = np.empty(12)
        model.rhs(0.0, y, p, out)
        return out

    run = solve_ivp(rates, (0.0, t_end_s), np.concatenate([q, u]), method="DOP853", dense_output=True, **tolerances)
    assert run.success, run.message
    return run


def test_kane_and_lagrange_agree_at_random_states_to_1e_10(model):
    lagrange = compiled(rattleback.SYSTEM, formulation="lagrange")
    p = model.parameter_array(DEFAULTS)
    rng = np.random.default_rng(11)
    for _ in range(20):
        q, u = model.assemble(rng.uniform(-0.5, 0.5, 6), rng.uniform(-8, 8, 6), p)
        kane, other = model.accelerations(q, u, p), lagrange.accelerations(q, u, p)
        assert np.max(np.abs(kane - other)) <= 1e-10 * np.max(np.abs(kane)), (kane, other)


def test_rocking_at_rest_has_the_closed_form_frequencies_to_1e_8(model):
    """At rest, rocking on radii of curvature a²/c (pitch) and b²/c (roll) with G at c − h above the floor: stiffness
    m g (ρ − (c − h)), inertia about the touching point I_G + m (c − h)², the product D coupling the two."""
    m, g, a, b, c, h = (DEFAULTS[k] for k in ("mass_kg", "gravity_m_s2", "semi_axis_a_m", "semi_axis_b_m",
                                              "semi_axis_c_m", "mass_centre_drop_m"))  # fmt: skip
    height = c - h
    stiffness = m * g * np.diag([b * b / c - height, a * a / c - height])
    xx, xy, yy = (DEFAULTS[k] for k in ("inertia_xx_kg_m2", "inertia_xy_kg_m2", "inertia_yy_kg_m2"))
    inertia = np.array([[xx, xy], [xy, yy]]) + m * height**2 * np.eye(2)
    closed_form = np.sqrt(eigh(stiffness, inertia, eigvals_only=True))
    values = eigenvalues(state_matrix(model, {**DEFAULTS, "spin_rad_s": 0.0}, rattleback.REFERENCE))
    frequencies = np.sort(np.unique(np.round(np.abs(values.imag[np.abs(values.imag) > 1]), 6)))
    assert np.max(np.abs(values.real)) < 1e-8
    np.testing.assert_allclose(frequencies, closed_form, rtol=1e-8)
    assert closed_form == pytest.approx([33.829, 107.2077], abs=1e-3)


def test_spun_one_way_the_pitching_grows_the_other_way_the_roll_grows_more_slowly(model):
    """Linear about steady upright spin at ±5 rad/s: anticlockwise, the pitching pair (109 rad/s) grows at 2.12 1/s;
    clockwise, the roll pair (34 rad/s) grows at 0.20 1/s: neither sense is stable without dissipation."""
    growing = {}
    for spin in (5.0, -5.0):
        values = eigenvalues(state_matrix(model, {**DEFAULTS, "spin_rad_s": spin}, rattleback.REFERENCE))
        worst = values[np.argmax(values.real)]
        growing[spin] = (worst.real, abs(worst.imag))
    assert growing[5.0][0] == pytest.approx(2.1207, abs=1e-4) and growing[5.0][1] == pytest.approx(109.392, abs=1e-3)
    assert growing[-5.0][0] == pytest.approx(0.2025, abs=1e-4) and growing[-5.0][1] == pytest.approx(34.144, abs=1e-3)


def _newton_euler_rates(params, y: np.ndarray) -> np.ndarray:
    """An independent model: y = (R (9, body → N, row-major), ω (3, body axes)). Euler's equations about G with the
    contact force F = m (a_G + g n): (I + m(|p|² 1 − p pᵀ)) ω̇ = −ω × Iω + m p × (g n − ω × (ṗ + ω × p)), p the
    touching point from G, ṗ its motion over the surface as the up vector n turns in the body (ṅ = −ω × n)."""
    m, g = params["mass_kg"], params["gravity_m_s2"]
    squares = np.array([params["semi_axis_a_m"], params["semi_axis_b_m"], params["semi_axis_c_m"]]) ** 2
    centre = np.array([0.0, 0.0, params["mass_centre_drop_m"]])
    inertia = np.array([[params["inertia_xx_kg_m2"], params["inertia_xy_kg_m2"], 0.0],
                        [params["inertia_xy_kg_m2"], params["inertia_yy_kg_m2"], 0.0],
                        [0.0, 0.0, params["inertia_zz_kg_m2"]]])  # fmt: skip
    R, omega = y[:9].reshape(3, 3), y[9:]
    n = R[2]  # N's z in the body's axes: the third row of R
    reach = math.sqrt(float(squares @ (n * n)))
    p = centre - squares * n / reach
    n_rate = -np.cross(omega, n)
    p_rate = -squares * n_rate / reach + squares * n * float(squares @ (n * n_rate)) / reach**3
    lhs = inertia + m * (float(p @ p) * np.eye(3) - np.outer(p, p))
    rhs = -np.cross(omega, inertia @ omega) + m * np.cross(p, g * n - np.cross(omega, p_rate + np.cross(omega, p)))
    skew = np.array([[0.0, -omega[2], omega[1]], [omega[2], 0.0, -omega[0]], [-omega[1], omega[0], 0.0]])
    return np.concatenate([(R @ skew).ravel(), np.linalg.solve(lhs, rhs)])


def test_the_spin_reverses_as_an_independent_newton_euler_model_says_to_1e_7(model):
    """Kane and Levinson's start spun anticlockwise at 5 rad/s: both models reverse the spin (first through zero at
    2.35 s, then on to about −5.2 rad/s); the body's ω agrees to 1e-7 rad/s over 3 s, the reversal included."""
    p = model.parameter_array(DEFAULTS)
    q, u = _kane_levinson_start(model, p, 5.0)
    tight = {"rtol": 1e-11, "atol": 1e-12}
    ours = _run(model, p, q, u, 3.0, **tight)
    start = np.concatenate([orientation(q).ravel(), body_velocity(q, u)])
    theirs = solve_ivp(lambda _t, y: _newton_euler_rates(DEFAULTS, y), (0.0, 3.0), start, method="DOP853",
                       dense_output=True, **tight)  # fmt: skip
    times = np.linspace(0.0, 3.0, 3001)
    ours_omega = np.array([body_velocity(y[:6], y[6:]) for y in ours.sol(times).T])
    theirs_omega = theirs.sol(times)[9:].T
    assert np.max(np.abs(ours_omega - theirs_omega)) < 1e-7
    spin = ours_omega[:, 2]
    first_zero = times[np.argmax(spin < 0)]
    assert 2.3 < first_zero < 2.4, first_zero
    assert spin[-1] < 0.0  # spinning clockwise now (it goes on to about −5.2 rad/s by 6 s)


def test_through_two_reversals_in_20_s_the_energy_is_kept_to_1e_8_and_the_constraints_to_1e_9(model):
    """Spun at 5 rad/s it reverses at 2.35 s and again at about 17 s (no dissipation: the clockwise spin's slow roll
    instability undoes it); the energy is constant throughout."""
    p = model.parameter_array(DEFAULTS)
    q0, u0 = _kane_levinson_start(model, p, 5.0)
    run = _run(model, p, q0, u0, 20.0, rtol=1e-11, atol=1e-12)
    q1, u1 = run.y[:6, -1], run.y[6:, -1]
    start, end = sum(model.energy(q0, u0, p)), sum(model.energy(q1, u1, p))
    assert abs(end - start) <= 1e-8 * abs(start), (start, end)
    assert model.constraint_residual(q1, u1, p) < 1e-9


def test_the_floor_push_is_the_multiplier_and_newtons_m_times_z_acceleration_plus_g_to_1e_9(model):
    """Along the reversal, the configuration row's multiplier (the DAE algorithms' λ) is N = m (z̈_G + g), Newton's
    second law upward with z̈_G from the accelerations."""
    params = PARAMETERS.validate({"spin_0_rad_s": 5.0})
    p = model.parameter_array(system_params(params))
    q, u = _kane_levinson_start(model, p, 5.0)
    states = _run(model, p, q, u, 3.0, rtol=1e-10, atol=1e-12).sol(np.linspace(0.0, 3.0, 31)).T
    normal = RattlebackMotion().normal_force_N(params, np.zeros(len(states)), states)
    newton = [params["mass_kg"] * (model.accelerations(s[:6], s[6:], p)[2] + params["gravity_m_s2"]) for s in states]
    np.testing.assert_allclose(normal, newton, rtol=1e-9)
    assert normal.min() > 0.0


def test_no_rigid_body_has_these_moments():
    with pytest.raises(ParameterError) as refused:
        check_body({**DEFAULTS, "inertia_xy_kg_m2": 1e-3})
    assert refused.value.field == "inertia_xy_kg_m2"
    check_body(DEFAULTS)
    assert np.allclose(orientation(np.zeros(6)), elementary_rotation_matrix(2, 0.0))


def test_a_mass_centre_below_the_lowest_point_is_refused():
    with pytest.raises(ParameterError) as refused:
        check_body({**DEFAULTS, "mass_centre_drop_m": 0.03})
    assert refused.value.field == "mass_centre_drop_m"


def test_a_start_that_would_throw_it_off_the_floor_is_refused_before_any_integration():
    violent = PARAMETERS.validate(
        {"spin_0_rad_s": 30.0, "roll_0_deg": 10.0, "pitch_0_deg": 10.0, "roll_rate_0_rad_s": 10.0,
         "pitch_rate_0_rad_s": 10.0, "mass_centre_drop_m": 0.019}
    )  # fmt: skip
    with pytest.raises(ParameterError) as refused:
        RattlebackMotion().consistent_start(violent)
    assert refused.value.field == "spin_0_rad_s" and "off the floor" in str(refused.value)
