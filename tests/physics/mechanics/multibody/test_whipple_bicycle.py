"""The Whipple bicycle described by its parts, against the benchmark of Meijaard, Papadopoulos, Ruina and Schwab (2007).

The published figures: their eq. (5.4) matrices M, C1, K0, K2 of the linearised equations (14 significant digits),
their Table 2 eigenvalues at 0 and 5 m/s, and the weave and capsize speeds. The model is nonlinear and knows none of
them: its eigenvalues come from linearising the generated equations about upright rolling.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.linalg import expm

from app.physics.mechanics.multibody.compiled import compiled
from app.physics.mechanics.multibody.linearise import eigenvalues, state_matrix
from app.physics.systems.ch09 import whipple_bicycle as bicycle

G = 9.81
#: Meijaard et al. (2007), eq. (5.4): M q̈ + v C1 q̇ + (g K0 + v² K2) q = 0, q = (lean, steer).
M = np.array([[80.81722, 2.31941332208709], [2.31941332208709, 0.29784188199686]])
C1 = np.array([[0.0, 33.86641391492494], [-0.85035641456978, 1.68540397397560]])
K0 = np.array([[-80.95, -2.59951685249872], [-2.59951685249872, -0.80329488458618]])
K2 = np.array([[0.0, 76.59734589573222], [0.0, 2.65431523794604]])
#: Their Table 2 and section 5: eigenvalues (1/s) at 0 and 5 m/s; the self-stable band's ends (m/s).
TABLE_EIGENVALUES = {
    0.0: [-5.53094371765393, -3.13164324790656, 3.13164324790656, 5.53094371765393],
    5.0: [-14.07838969279822, -0.77534188219585 - 4.46486771378823j, -0.77534188219585 + 4.46486771378823j,
          -0.32286642900409],
}  # fmt: skip
WEAVE_M_S, CAPSIZE_M_S = 4.29238253634111, 6.02426201538837


@pytest.fixture(scope="module")
def model():
    return compiled(bicycle.SYSTEM)


def _eigenvalues(model, speed_m_s: float) -> np.ndarray:
    return eigenvalues(
        state_matrix(model, {**bicycle.PARAMETERS.defaults(), "speed_m_s": speed_m_s}, bicycle.REFERENCE)
    )


def _published_eigenvalues(speed_m_s: float) -> np.ndarray:
    stiffness, damping = G * K0 + speed_m_s**2 * K2, speed_m_s * C1
    A = np.block([[np.zeros((2, 2)), np.eye(2)], [-np.linalg.solve(M, stiffness), -np.linalg.solve(M, damping)]])
    return eigenvalues(A)


@pytest.mark.parametrize("speed_m_s", sorted(TABLE_EIGENVALUES))
def test_eigenvalues_match_the_published_table_to_1e_8(model, speed_m_s):
    got = _eigenvalues(model, speed_m_s)
    want = np.array(TABLE_EIGENVALUES[speed_m_s], dtype=complex)
    assert np.max(np.abs(got - want)) < 1e-8, (got, want)


def test_eigenvalues_match_the_published_linear_equations_from_0_to_10_m_s_to_1e_8(model):
    for speed_m_s in np.arange(0.0, 10.01, 0.5):
        got, want = _eigenvalues(model, speed_m_s), _published_eigenvalues(speed_m_s)
        assert np.max(np.abs(got - want)) < 1e-8, (speed_m_s, got, want)


def test_the_weave_and_capsize_speeds_are_found_to_1e_6_m_s(model):
    weave, capsize = bicycle.weave_and_capsize(model, bicycle.PARAMETERS.defaults())
    assert weave is not None and abs(weave - WEAVE_M_S) < 1e-6, weave
    assert capsize is not None and abs(capsize - CAPSIZE_M_S) < 1e-6, capsize


def test_kane_and_lagrange_agree_at_random_states_to_1e_10(model):
    lagrange = compiled(bicycle.SYSTEM, formulation="lagrange")
    p = model.parameter_array(bicycle.PARAMETERS.defaults())
    rng = np.random.default_rng(7)
    for _ in range(20):
        q, u = model.assemble(rng.uniform(-0.6, 0.6, model.n), rng.uniform(-3, 3, model.n), p)
        kane, other = model.accelerations(q, u, p), lagrange.accelerations(q, u, p)
        assert np.max(np.abs(kane - other)) <= 1e-10 * np.max(np.abs(kane)), (kane, other)


def _coast(model, speed_m_s: float, lean_rate_rad_s: float, t_end_s: float):
    params = {**bicycle.PARAMETERS.defaults(), "speed_m_s": speed_m_s}
    p = model.parameter_array(params)
    q, u = bicycle.REFERENCE.state(params)
    u[bicycle.SYSTEM.index("lean")] = lean_rate_rad_s  # a sideways push
    q, u = model.assemble(q, u, p)
    n = model.n

    def rates(_t: float, y: np.ndarray) -> np.ndarray:
        out = np.empty(2 * n)
        model.rhs(0.0, y, p, out)
        return out

    run = solve_ivp(rates, (0.0, t_end_s), np.concatenate([q, u]), method="DOP853", rtol=1e-11, atol=1e-12)
    assert run.success, run.message
    return p, (q, u), (run.y[:n, -1], run.y[n:, -1])


def test_a_pushed_bicycle_coasting_for_60_s_keeps_its_energy_to_1e_8_and_its_constraints(model):
    p, (q0, u0), (q1, u1) = _coast(model, 5.0, 0.5, 60.0)
    start, end = sum(model.energy(q0, u0, p)), sum(model.energy(q1, u1, p))
    assert abs(end - start) <= 1e-8 * abs(start), (start, end)
    g = np.empty(1)
    model.configuration(q1, p, g)
    A = np.empty(5 * model.n)
    model.constraint_matrix(q1, p, A)
    assert abs(g[0]) < 1e-9 and np.max(np.abs(A.reshape(5, model.n) @ u1)) < 1e-9
    # Inside the self-stable band the push dies out: upright again, steering straight.
    assert abs(q1[bicycle.SYSTEM.index("lean")]) < 1e-6 and abs(q1[bicycle.SYSTEM.index("steer")]) < 1e-6


def test_below_the_weave_speed_a_small_push_grows_as_the_linear_model_says(model):
    """At 3 m/s the weave pair is unstable (Re λ > 0). A push of 1e-6 rad/s: the nonlinear lean and steer after 6 s are
    the linear model's exp(A t) x₀ to 1e-4 relative (the neglected terms are of the order of the amplitude squared)."""
    A = state_matrix(model, {**bicycle.PARAMETERS.defaults(), "speed_m_s": 3.0}, bicycle.REFERENCE)
    assert max(eigenvalues(A).real) > 0.5
    _, _, (q1, _) = _coast(model, 3.0, 1e-6, 6.0)
    linear = expm(A * 6.0) @ np.array([0.0, 0.0, 1e-6, 0.0])
    nonlinear = np.array([q1[bicycle.SYSTEM.index("lean")], q1[bicycle.SYSTEM.index("steer")]])
    assert np.max(np.abs(nonlinear - linear[:2])) < 1e-4 * np.max(np.abs(linear[:2])), (nonlinear, linear)
    assert np.max(np.abs(linear[:2])) > 1e-5  # it grew, tenfold or more


def test_the_equations_shrink_under_common_subexpression_elimination(model):
    operations = model.operations
    assert operations["speeds"] == 8 and operations["constraints"] == 5
    assert operations["after_cse"] * 10 < operations["before_cse"]


#: Basu-Mandal, Chatterjee and Papadopoulos (2007, "Hands-free circular motions of a benchmark bicycle", Proc. R.
#: Soc. A 463), Table 1: a general nonlinear state
#: of the benchmark bicycle (leaned 35.6°, steered 13.2°, turning) and its accelerations, to 12–14 significant figures.
#: Their frame has z up and x backwards; their lean ψ is π/2 upright, their pitch φ is π less the rear frame's angle
#: from the steer axis. Turned into this model's coordinates (x forward, y left, z up; lean positive to the right,
#: steer positive to the left, pitch zero at the nominal pose, wheel spins about the left axle, the rear one relative
#: to the unpitched axle frame): q, q̇ and q̈ below. The rear contact's x, y rates and accelerations are the table's
#: wheel-centre values moved to the contact (as DynamicistToolKit's basu_to_moore_input does; symbrim's test of its
#: Whipple model uses the same numbers).
BASU_MANDAL_Q = {"y": 0.17447337661787718, "lean": 0.6206670416476966, "steer": 0.2311385135743}
BASU_MANDAL_PITCH = -0.0158853521003932
BASU_MANDAL_FREE_RATES = {
    "lean": -0.6068425835418,
    "rear_spin": 8.9129896614890 - 0.0119185528069,
    "steer": 0.4859824687093,
}
BASU_MANDAL_RATES = {"x": 2.6703213326046784, "y": 0.0, "yaw": 0.7830033527065, "pitch": -0.0119185528069,
                     "front_spin": 8.0133620584155}  # fmt: skip
BASU_MANDAL_ACCELERATIONS = {
    "x": 0.5903429412631302, "y": 2.090870556233152, "yaw": 0.8353281706379, "lean": 7.8555281128244,
    "rear_spin": 1.8472554144217 + 0.1205543897884, "pitch": 0.1205543897884, "steer": -4.6198904039403,
    "front_spin": 2.4548072904550,
}  # fmt: skip


def test_the_nonlinear_accelerations_match_basu_mandal_2007_table_1_to_1e_11(model):
    """The only inputs are the free coordinates and rates; the pitch and the five dependent rates come from the
    model's own constraints (against the table: 1e-12), the accelerations from its equations (1e-11; the table has
    13 significant figures, |q̈| ≤ 8)."""
    system = bicycle.SYSTEM
    p = model.parameter_array(bicycle.PARAMETERS.defaults())
    q, u = np.zeros(model.n), np.zeros(model.n)
    for name, value in BASU_MANDAL_Q.items():
        q[system.index(name)] = value
    for name, value in BASU_MANDAL_FREE_RATES.items():
        u[system.index(name)] = value
    q, u = model.assemble(q, u, p)
    assert abs(q[system.index("pitch")] - BASU_MANDAL_PITCH) < 1e-12
    for name, value in BASU_MANDAL_RATES.items():
        assert abs(u[system.index(name)] - value) < 1e-12, name
    accelerations = model.accelerations(q, u, p)
    for name, value in BASU_MANDAL_ACCELERATIONS.items():
        assert abs(accelerations[system.index(name)] - value) < 1e-11, (name, accelerations[system.index(name)], value)


@pytest.mark.parametrize(("start", "speed_m_s"), [("weave mode", 4.0), ("capsize mode", 7.0)])
def test_a_mode_start_moves_in_that_mode_alone_as_the_linear_model_says(start, speed_m_s):
    """Started in a mode's shape at 0.05° of lean, the nonlinear lean and steer over 3 s are the linear mode's
    lean₀ Re(v e^{λt}) to 1e-3 of the amplitude (the neglected terms are of the order of the amplitude squared)."""
    from app.physics.systems.ch09.whipple_bicycle_model import PARAMETERS, WhippleBicycleMotion, mode_shape

    motion = WhippleBicycleMotion()
    params = PARAMETERS.validate({"speed_m_s": speed_m_s, "start": start, "mode_lean_deg": 0.05})
    shape = mode_shape(params, "weave" if start == "weave mode" else "capsize")
    controls = {c.name: c.default for c in motion.controls()}
    report = motion.simulate(params, controls, t_end_s=3.0, frame_rate_hz=20)
    assert report.status == "ok", report.message
    t = np.asarray(report.t_s)
    lean0 = np.radians(0.05)
    linear = lean0 * np.real(np.outer(np.exp(shape.eigenvalue * t), shape.vector[:2]))
    nonlinear = np.column_stack([report.series["lean_rad"], report.series["steer_rad"]])
    assert np.max(np.abs(nonlinear - linear)) < 1e-3 * lean0 * max(1.0, np.max(np.abs(linear)) / lean0)
