"""Torque-free body in closed form (app/physics/models/free_body_elliptic.py).

Reference: Euler's equations I ω̇ = (I ω) × ω with q̇ = ½ q ⊗ (0, ω), written out here and
integrated by DOP853 at rtol = atol = 1e-12 (independent of the module and of the app's
integrators). Away from the separatrix that integration and the closed form agree to
≤ 3e-11 (rad/s relative to |ω|, and rad of attitude) over 20 s. In the intermediate-axis
("Dzhanibekov") case, 1 − m = 2e-6, every flip amplifies the integrator's error: over 10 s
it is 2e-9 rad/s and 2e-10 rad, over 60 s ~2e-7 rad/s, and its zero crossings drift by up
to 1e-8 s (all shrinking as rtol is tightened), while the closed form agrees with a 40-digit
mpmath evaluation to 3e-13 rad/s and 1e-14 s; the tolerances there are looser and say so.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from app.physics.math.rotations import quaternion_conjugate, quaternion_from_axis_angle, quaternion_multiply, rotation_matrix
from app.physics.systems.ch10.free_body_elliptic import complete_elliptic_k, free_body_elliptic, jacobi_reduced

DZHANIBEKOV = dict(inertia=(1e-3, 2e-3, 3e-3), omega0_body=np.array([0.01, 10.0, 0.01]))
Q0 = np.array([0.9, 0.1, -0.3, 0.2]) / np.linalg.norm([0.9, 0.1, -0.3, 0.2])


def reference_rhs(t, y, inertia):
    q, omega = y[:4], y[4:]
    omega_dot = np.cross(inertia * omega, omega) / inertia
    q_dot = 0.5 * quaternion_multiply(q, np.concatenate([[0.0], omega]))
    return np.concatenate([q_dot, omega_dot])


def integrate(inertia, omega0, q0, t, **kwargs):
    sol = solve_ivp(
        reference_rhs, (0.0, t[-1]), np.concatenate([q0, omega0]), method="DOP853", rtol=1e-12, atol=1e-12,
        t_eval=t, args=(np.asarray(inertia, dtype=float),), **kwargs,
    )
    return sol.y[:4].T, sol.y[4:].T


def attitude_error_rad(q, q_ref):
    d = quaternion_multiply(quaternion_conjugate(q), q_ref)
    return 2.0 * np.arcsin(np.minimum(1.0, np.linalg.norm(d[..., 1:], axis=-1)))


CASES = {
    # Circles the axis of largest moment (m ≈ 0.10).
    "circles-max": ((1.0, 2.0, 3.0), (1.0, 0.5, 2.0)),
    # Same rates, moments in descending order: circles the smallest moment, body axes reversed.
    "circles-min": ((3.0, 2.0, 1.0), (1.0, 0.5, 2.0)),
    # Moments in an odd permutation, negative rates, close to the separatrix (1 − m = 0.012).
    "odd-permutation": ((2.0, 3.0, 1.0), (3.0, -0.2, -0.1)),
    # Oblate axisymmetric body (m = 0): the harmonic special case of the same formulas.
    "axisymmetric": ((1.0, 1.0, 1.7), (0.5, 0.2, 3.0)),
}


@pytest.mark.parametrize("name", CASES)
def test_closed_form_matches_a_tight_integration(name):
    inertia, omega0 = CASES[name]
    body = free_body_elliptic(inertia=inertia, omega0_body=np.array(omega0), q0=Q0)
    t = np.linspace(0.0, 20.0, 401)
    q_ref, omega_ref = integrate(inertia, np.array(omega0), Q0, t)
    scale = np.linalg.norm(omega0)
    assert np.abs(body.omega_body(t) - omega_ref).max() < 1e-10 * scale
    assert attitude_error_rad(body.quaternion(t), q_ref).max() < 1e-9
    # The initial state is reproduced to rounding.
    assert np.abs(body.omega_body(np.zeros(1))[0] - omega0).max() < 1e-14 * scale
    assert attitude_error_rad(body.quaternion(np.zeros(1)), Q0[None])[0] < 1e-14


def test_dzhanibekov_flip_times_match_the_integrations_zero_crossings():
    # 1 − m ≈ 2e-6: ω2 ≈ ±10 rad/s for ~2.7 s, then reverses in ~0.5 s; 22 flips in 60 s.
    body = free_body_elliptic(**DZHANIBEKOV)
    assert body.intermediate_axis == 1 and body.circled_axis == 2
    assert 1e-6 < body._w.mc < 3e-6
    flips = body.flip_times(60.0)
    inertia = np.array(DZHANIBEKOV["inertia"])

    def omega2(t, omega):
        return omega[1]

    sol = solve_ivp(lambda t, w: np.cross(inertia * w, w) / inertia, (0.0, 60.0), DZHANIBEKOV["omega0_body"],
                    method="DOP853", rtol=1e-12, atol=1e-12, events=omega2)
    crossings = sol.t_events[0]
    assert len(flips) == len(crossings) == 22
    # Measured: ≤ 1.1e-8 s (the integration's own drift; 1e-9 s at atol 1e-14). Spec bound: 1e-6 s.
    assert np.abs(flips - crossings).max() < 1e-7
    # Successive flips are half a period apart (ω2 ∝ sn has period 4K/λ).
    assert np.diff(flips) == pytest.approx(np.full(21, 0.5 * body.period_s), rel=1e-13, abs=0)
    assert np.all(np.diff(np.sign(body.omega_body(flips[:-1] + 0.25 * body.period_s)[:, 1])) != 0)


def test_dzhanibekov_flip_times_match_a_30_digit_evaluation():
    # The same formula t_j = (2K j − x0)/λ in 30-digit arithmetic from the same float inputs:
    # checks K, x0 and λ where 1 − m = 2e-6 (forming 1 − m in double would cost ~1e-10 in K,
    # ~1e-8 s by the 22nd flip). Measured agreement: 1.4e-14 s.
    mpmath = pytest.importorskip("mpmath")
    mpmath.mp.dps = 30
    I1, I2, I3 = (mpmath.mpf(v) for v in DZHANIBEKOV["inertia"])
    w1, w2, w3 = (mpmath.mpf(v) for v in DZHANIBEKOV["omega0_body"])
    two_T = I1 * w1**2 + I2 * w2**2 + I3 * w3**2
    D = (I1**2 * w1**2 + I2**2 * w2**2 + I3**2 * w3**2) / two_T
    m = (I2 - I1) * (I3 - D) / ((I3 - I2) * (D - I1))
    rate = mpmath.sqrt(two_T * (I3 - I2) * (D - I1) / (I1 * I2 * I3))
    A1 = mpmath.sqrt(two_T * (I3 - D) / (I1 * (I3 - I1)))
    A2 = mpmath.sqrt(two_T * (I3 - D) / (I2 * (I3 - I2)))
    x0 = mpmath.ellipf(mpmath.atan2(w2 / A2, w1 / A1), m)
    K = mpmath.ellipk(m)
    expected = [float((2 * K * j - x0) / rate) for j in range(1, 23)]
    flips = free_body_elliptic(**DZHANIBEKOV).flip_times(60.0)
    assert np.abs(flips - np.array(expected)).max() < 1e-12


def test_quaternion_output_is_continuous_in_time():
    # No sign flips of q(t) (Ψ is unwrapped across half periods): over dt the quaternion moves by
    # ≤ |ω| dt / 2; a sign flip would jump by ~2.
    body = free_body_elliptic(**DZHANIBEKOV, q0=Q0)
    t = np.linspace(0.0, 20.0, 20001)
    steps = np.linalg.norm(np.diff(body.quaternion(t), axis=0), axis=1)
    fastest = np.linalg.norm(body.omega_body(t), axis=1).max()
    assert steps.max() < 0.5 * fastest * (t[1] - t[0]) * 1.001


def test_dzhanibekov_motion_matches_the_integration_within_its_accuracy():
    body = free_body_elliptic(**DZHANIBEKOV)
    t = np.linspace(0.0, 10.0, 401)
    q_ref, omega_ref = integrate(DZHANIBEKOV["inertia"], DZHANIBEKOV["omega0_body"], np.array([1.0, 0, 0, 0]), t)
    # Measured after 3 flips: 2e-9 rad/s in ω (ω2's slope at a flip is ~60 rad/s², so that is a
    # ~4e-11 s timing error of the integrator) and 2e-10 rad of attitude; 10× margin.
    assert np.abs(body.omega_body(t) - omega_ref).max() < 2e-8
    assert attitude_error_rad(body.quaternion(t), q_ref).max() < 2e-9


ODD_PERMUTATION = dict(inertia=CASES["odd-permutation"][0], omega0_body=np.array(CASES["odd-permutation"][1]))


@pytest.mark.parametrize("case", [DZHANIBEKOV, ODD_PERMUTATION], ids=["dzhanibekov", "odd-permutation"])
def test_energy_and_angular_momentum_are_conserved_along_the_closed_form(case):
    body = free_body_elliptic(**case, q0=Q0)
    inertia = np.asarray(case["inertia"])
    t = np.linspace(0.0, 60.0, 3001)
    omega = body.omega_body(t)
    energy = 0.5 * np.sum(inertia * omega**2, axis=1)
    L_body = inertia * omega
    L_world = np.einsum("nij,nj->ni", rotation_matrix(body.quaternion(t)), L_body)
    assert body.energy_J == pytest.approx(0.5 * np.sum(inertia * case["omega0_body"] ** 2), rel=1e-15, abs=0)
    assert np.abs(energy / body.energy_J - 1.0).max() < 1e-13
    assert np.abs(np.linalg.norm(L_body, axis=1) / body.angular_momentum_norm - 1.0).max() < 1e-13
    # L fixed in the world: checks the attitude's two angles that tilt L (not the one about it).
    assert np.abs(L_world - body.angular_momentum_world).max() < 1e-12 * body.angular_momentum_norm
    assert body.angular_momentum_world == pytest.approx(rotation_matrix(Q0) @ (inertia * case["omega0_body"]), rel=1e-14, abs=0)


def test_attitude_obeys_the_kinematics_with_the_closed_form_rates():
    # q̇ = ½ q ⊗ (0, ω) by 4th-order central differences (h = 1e-4 s: truncation ~1e-13, rounding
    # ~1e-12): checks the angle about L, which conservation of L cannot see.
    body = free_body_elliptic(**DZHANIBEKOV, q0=Q0)
    t = np.linspace(0.3, 30.0, 200)
    h = 1e-4
    q = body.quaternion
    q_dot = (8.0 * (q(t + h) - q(t - h)) - (q(t + 2 * h) - q(t - 2 * h))) / (12.0 * h)
    omega_fd = 2.0 * quaternion_multiply(quaternion_conjugate(q(t)), q_dot)[:, 1:]
    assert np.abs(omega_fd - body.omega_body(t)).max() < 1e-8 * 10.0


@pytest.mark.parametrize("symmetry_axis", [2, 0])
@pytest.mark.parametrize("I_axial", [1.7, 0.6])  # oblate, prolate
def test_axisymmetric_body_against_the_textbook_solution(symmetry_axis, I_axial):
    # I1 = I2 = I_t about a symmetry axis 3: ω⊥ turns about body 3 at Ω = (I3 − I1)/I1·ω3, and
    # q(t) = rot(L̂_world, |L| t / I_t) ⊗ q0 ⊗ rot(e3, −Ω t)   (ω = (|L|/I_t) L̂ − Ω e3).
    I_t = 1.0
    omega_sym = np.array([0.5, -0.2, 3.0])  # (transverse, transverse, axial)
    perm = [(symmetry_axis + 1) % 3, (symmetry_axis + 2) % 3, symmetry_axis]  # cyclic: a proper relabelling
    inertia, omega0 = np.empty(3), np.empty(3)
    inertia[perm], omega0[perm] = [I_t, I_t, I_axial], omega_sym
    body = free_body_elliptic(inertia=inertia, omega0_body=omega0, q0=Q0)
    e_sym = np.eye(3)[symmetry_axis]
    Omega = (I_axial - I_t) / I_t * omega_sym[2]
    t = np.linspace(0.0, 10.0, 201)
    # ω(t): the transverse part rotated by Ω t about the symmetry axis, the axial part constant.
    expected_omega = np.array([rotation_matrix(quaternion_from_axis_angle(e_sym, Omega * ti)) @ omega0 for ti in t])
    assert np.abs(body.omega_body(t) - expected_omega).max() < 1e-13 * np.linalg.norm(omega0)
    assert body.period_s == pytest.approx(2.0 * math.pi / abs(Omega), rel=1e-14, abs=0)
    L_hat = body.angular_momentum_world / body.angular_momentum_norm
    expected_q = np.array([
        quaternion_multiply(quaternion_multiply(quaternion_from_axis_angle(L_hat, body.angular_momentum_norm * ti / I_t), Q0),
                            quaternion_from_axis_angle(e_sym, -Omega * ti))
        for ti in t
    ])
    assert attitude_error_rad(body.quaternion(t), expected_q).max() < 1e-12


@pytest.mark.parametrize(
    ("inertia", "omega0"),
    [
        ((1.0, 2.0, 3.0), (0.0, 5.0, 0.0)),
        ((1.0, 2.0, 3.0), (0.0, 0.0, -5.0)),
        ((1.0, 2.0, 3.0), (0.0, 0.0, 0.0)),
        ((1.0, 1.0, 1.5), (1.0, 2.0, 0.0)),  # any axis in the plane of equal moments is principal
        ((1.0, 1.0, 1.0), (1.0, 2.0, 3.0)),  # spherical body
    ],
    ids=["intermediate-axis", "major-axis", "at-rest", "axisymmetric-equator", "sphere"],
)
def test_rotation_about_a_principal_axis_is_steady(inertia, omega0):
    body = free_body_elliptic(inertia=inertia, omega0_body=np.array(omega0), q0=Q0)
    assert body.kind == "steady" and body.period_s == math.inf and len(body.flip_times(100.0)) == 0
    t = np.linspace(0.0, 10.0, 11)
    assert np.all(body.omega_body(t) == np.array(omega0))
    rate = np.linalg.norm(omega0)
    axis = np.array(omega0) / rate if rate else np.array([0.0, 0.0, 1.0])
    expected = np.array([quaternion_multiply(Q0, quaternion_from_axis_angle(axis, rate * ti)) for ti in t])
    assert attitude_error_rad(body.quaternion(t), expected).max() < 1e-13


@pytest.mark.parametrize("signs", [(1, 1, 1), (-1, 1, 1), (1, 1, -1), (-1, -1, -1)])
def test_exactly_on_the_separatrix_uses_the_hyperbolic_form(signs):
    # I = (3, 4, 6), ω0 = (±2, ±1.3, ±1): I1(I1 − I2)ω1² + I3(I3 − I2)ω3² = −12 + 12 = 0 exactly, so L² = 2T·I2.
    inertia, omega0 = (3.0, 4.0, 6.0), np.array(signs) * np.array([2.0, 1.3, 1.0])
    body = free_body_elliptic(inertia=inertia, omega0_body=omega0, q0=Q0)
    assert body.kind == "separatrix" and body.period_s == math.inf
    t = np.linspace(0.0, 10.0, 201)
    q_ref, omega_ref = integrate(inertia, omega0, Q0, t)
    assert np.abs(body.omega_body(t) - omega_ref).max() < 1e-10
    assert attitude_error_rad(body.quaternion(t), q_ref).max() < 1e-9
    if signs != (1, 1, 1):
        return
    # Asymptotically a rotation about the intermediate axis at √(2T/I2); ω2 > 0 here, so no flip.
    omega_late = body.omega_body(np.array([40.0]))[0]
    assert omega_late[1] == pytest.approx(math.sqrt(2.0 * body.energy_J / 4.0), rel=1e-12, abs=0)
    assert len(body.flip_times(100.0)) == 0
    # The same orbit entered with ω2 < 0 crosses zero once, where the integration does.
    flipping = free_body_elliptic(inertia=inertia, omega0_body=np.array([2.0, -1.3, 1.0]))
    (t_flip,) = flipping.flip_times(100.0)
    sol = solve_ivp(lambda t, w: np.cross(np.array(inertia) * w, w) / np.array(inertia), (0.0, 5.0), [2.0, -1.3, 1.0],
                    method="DOP853", rtol=1e-12, atol=1e-12, events=lambda t, w: w[1])
    assert t_flip == pytest.approx(sol.t_events[0][0], abs=1e-10)


def test_jacobi_functions_keep_relative_precision_near_the_separatrix():
    # Against mpmath (60 digits) at the Dzhanibekov parameter and much closer to 1. scipy's ellipj
    # takes m alone (1 − m then known to ~1e-16 absolute) and uses a first-order series for
    # m > 1 − 1e-9; a plain AGM loses ~1e-9 relative in cn, dn at 1 − m = 1e-15.
    mpmath = pytest.importorskip("mpmath")
    mpmath.mp.dps = 60
    eps = np.finfo(float).eps
    for mc in (0.3, 2e-6, 1e-15, 1e-25, 1e-40):
        m = 1.0 - mc  # the float m is not exact for small mc: it is not used where that matters
        m_exact = 1 - mpmath.mpf(mc)
        K = complete_elliptic_k(m=m, mc=mc)
        assert K == pytest.approx(float(mpmath.ellipk(m_exact)), rel=5e-16, abs=0)  # ≤ 2 ulp
        x = np.array([1e-9, 0.3, 0.4 * K, 0.7 * K, K - 1.0, K - 1e-2, K + 0.2, 3.0 * K - 1.0, -5.5 * K])
        k, sn, cn, dn = jacobi_reduced(x, m=m, mc=mc, K=K)
        parity = (-1.0) ** k
        for xi, s, c, d in zip(x, parity * sn, parity * cn, dn):
            s_ref, c_ref, d_ref = (float(mpmath.ellipfun(kind, mpmath.mpf(xi), m=m_exact)) for kind in ("sn", "cn", "dn"))
            # Near ±K, cn ∝ (K − |x|) is only as good as the rounding of x and K relative to that gap.
            gap = abs(abs(xi - 2.0 * K * round(xi / (2.0 * K))) - K)
            assert s == pytest.approx(s_ref, rel=1e-13, abs=0)
            assert c == pytest.approx(c_ref, rel=1e-13 + 4.0 * eps * abs(xi) / gap, abs=0)
            assert d == pytest.approx(d_ref, rel=1e-13, abs=0)


@pytest.mark.parametrize(
    ("inertia", "message"),
    [
        ((1.0, 1.0, 3.0), r"I3 = 3 kg·m² exceeds I1 \+ I2 = 2 kg·m²"),
        ((5.0, 2.0, 2.5), r"I1 = 5 kg·m² exceeds I2 \+ I3 = 4.5 kg·m²"),
        ((0.0, 1.0, 1.0), "I1 must be a finite positive moment of inertia"),
        ((1.0, -2.0, 2.0), "I2 must be a finite positive moment of inertia"),
        ((1.0, 1.0, math.nan), "I3 must be a finite positive moment of inertia"),
        ((1.0, 2.0), "three principal moments"),
    ],
)
def test_invalid_inertia_is_rejected_with_a_named_violation(inertia, message):
    with pytest.raises(ValueError, match=message):
        free_body_elliptic(inertia=inertia, omega0_body=np.array([1.0, 2.0, 3.0]))


def test_invalid_rates_and_attitude_are_rejected():
    with pytest.raises(ValueError, match="omega0_body"):
        free_body_elliptic(inertia=(1.0, 2.0, 3.0), omega0_body=np.array([1.0, math.inf, 0.0]))
    with pytest.raises(ValueError, match="q0"):
        free_body_elliptic(inertia=(1.0, 2.0, 3.0), omega0_body=np.array([1.0, 2.0, 3.0]), q0=np.zeros(4))
