"""The rotation package against independent computations, over all twelve sequences at once.

References: scipy's ``Rotation`` (an independent implementation of intrinsic
sequences and rotation vectors), complex-step derivatives of the rotation matrix
(exact to rounding, no step-size error), and identities that must hold exactly
(orthonormality, composition, inverses, the gimbal-lock degeneracy).

Tolerances: a matrix built from a few products of sines and cosines carries
rounding errors of a few ulp (measured ≤ 2e-15), so identities on matrices use
1e-13 — a hundred times the measured error, ten orders of magnitude below any
real mistake (a wrong sign or axis is an O(1) error). Angles recovered from a
matrix are ill-conditioned near gimbal lock (error ≈ 1e-16 / lock distance), so
angle-by-angle comparisons stay ≥ 1e-3 rad from lock with tolerance 1e-10;
at and near lock angle sets are compared through the matrix they produce.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation

from app.physics.math import rotations as rot
from app.physics.math.rotations import (
    PROPER_EULER,
    SEQUENCES,
    TAIT_BRYAN,
    angle_rate_matrix_body,
    angle_rates_from_angular_velocity_body,
    angle_rates_from_angular_velocity_world,
    angles_from_matrix,
    angles_from_quaternion,
    angular_velocity_body,
    angular_velocity_world,
    axis_angle_from_matrix,
    axis_angle_from_quaternion,
    intermediate_frames,
    matrix_from_angles,
    matrix_from_axis_angle,
    quaternion_from_angles,
    quaternion_from_axis_angle,
    quaternion_from_matrix,
    quaternion_multiply,
    rotation_matrix,
)

MATRIX_TOL = 1e-13
ANGLE_TOL_RAD = 1e-10
FAR_FROM_LOCK_RAD = 1e-3

NAMES = list(SEQUENCES)
sequences = st.sampled_from(NAMES)
angle = st.floats(min_value=-2.0 * math.pi, max_value=2.0 * math.pi, allow_nan=False)
angle_sets = st.tuples(angle, angle, angle).map(np.array)
rates = st.tuples(*[st.floats(min_value=-20.0, max_value=20.0, allow_nan=False)] * 3).map(np.array)
unit_quaternions = (
    st.tuples(*[st.floats(min_value=-1.0, max_value=1.0, allow_nan=False)] * 4)
    .map(np.array)
    .filter(lambda q: np.linalg.norm(q) > 1e-3)
    .map(lambda q: q / np.linalg.norm(q))
)
PROPERTY = settings(max_examples=400, deadline=None)


def scipy_letters(name: str) -> str:
    """Upper-case letters are scipy's intrinsic (body-fixed) sequences."""
    return "".join("XYZ"[int(a) - 1] for a in name.split("-"))


def lock_angles(name: str) -> list[float]:
    """Middle angles at gimbal lock, in rad, including the rounded values a student's degrees give."""
    if SEQUENCES[name].is_proper:
        return [0.0, math.pi, -math.pi, math.radians(180.0)]
    return [0.5 * math.pi, -0.5 * math.pi, math.radians(90.0), math.radians(-90.0)]


def worst(a, b) -> float:
    return float(np.abs(np.asarray(a) - np.asarray(b)).max())


# -- the registry ---------------------------------------------------------------------------------


def test_twelve_sequences_six_of_each_kind():
    assert len(SEQUENCES) == 12 and set(SEQUENCES) == set(PROPER_EULER) | set(TAIT_BRYAN)
    assert all(SEQUENCES[n].kind == "proper Euler" for n in PROPER_EULER)
    assert all(SEQUENCES[n].kind == "Tait–Bryan" for n in TAIT_BRYAN)
    for seq in SEQUENCES.values():
        assert seq.axes[0] != seq.axes[1] != seq.axes[2]
        # Parity: e_a1 × e_a2 = parity · e_third.
        third = 3 - seq.axes[0] - seq.axes[1]
        cross = np.cross(np.eye(3)[seq.axes[0]], np.eye(3)[seq.axes[1]])
        assert np.array_equal(cross, seq.parity * np.eye(3)[third])


def test_each_angle_meaning_names_its_axis():
    meanings = SEQUENCES["3-2-1"].angle_meanings()
    assert meanings[0].startswith("θ1 (yaw (heading)): turn about Z")
    assert "about y′" in meanings[1] and "about x″" in meanings[2]
    assert "about x′" in SEQUENCES["3-1-3"].angle_meanings()[1]


def test_unknown_sequence_is_a_clear_error():
    with pytest.raises(ValueError, match="unknown rotation sequence '3-3-1'.*3-1-3"):
        matrix_from_angles([0.1, 0.2, 0.3], "3-3-1")


# -- matrices, quaternions and angles ---------------------------------------------------------------


@PROPERTY
@given(sequences, angle_sets)
def test_matrix_is_a_rotation_and_matches_scipy(name, angles):
    R = matrix_from_angles(angles, name)
    assert worst(R.T @ R, np.eye(3)) < MATRIX_TOL
    assert abs(np.linalg.det(R) - 1.0) < MATRIX_TOL
    assert worst(R, Rotation.from_euler(scipy_letters(name), angles).as_matrix()) < MATRIX_TOL


@PROPERTY
@given(sequences, angle_sets)
def test_quaternion_and_matrix_from_angles_agree(name, angles):
    q = quaternion_from_angles(angles, name)
    assert abs(np.linalg.norm(q) - 1.0) < MATRIX_TOL
    assert worst(rotation_matrix(q), matrix_from_angles(angles, name)) < MATRIX_TOL


@PROPERTY
@given(sequences, angle_sets)
def test_angles_round_trip_through_matrix_and_quaternion(name, angles):
    R = matrix_from_angles(angles, name)
    for recovered in (angles_from_matrix(R, name), angles_from_quaternion(quaternion_from_angles(angles, name), name)):
        a = recovered.angles_rad
        assert worst(matrix_from_angles(a, name), R) < MATRIX_TOL
        # Canonical ranges: θ1, θ3 in [−π, π); θ2 in [0, π] (proper) or [−π/2, π/2] (Tait–Bryan).
        assert -math.pi <= a[0] < math.pi and -math.pi <= a[2] < math.pi
        if SEQUENCES[name].is_proper:
            assert 0.0 <= a[1] <= math.pi
        else:
            assert -0.5 * math.pi <= a[1] <= 0.5 * math.pi


@PROPERTY
@given(sequences, angle_sets)
def test_angles_in_canonical_range_are_recovered_exactly_away_from_lock(name, angles):
    """Away from lock the canonical set is unique: decomposing gives back the very angles."""
    seq = SEQUENCES[name]
    canonical = np.array([rot.wrap_angle_rad(angles[0]), angles[1], rot.wrap_angle_rad(angles[2])])
    canonical[1] = abs(rot.wrap_angle_rad(angles[1])) if seq.is_proper else math.asin(math.sin(angles[1]))
    if rot.gimbal_lock_distance_rad(canonical, name) < FAR_FROM_LOCK_RAD:
        return
    recovered = angles_from_matrix(matrix_from_angles(canonical, name), name)
    assert not recovered.degenerate
    difference = np.angle(np.exp(1j * (recovered.angles_rad - canonical)))  # compare angles modulo 2π
    assert np.abs(difference).max() < ANGLE_TOL_RAD


@pytest.mark.parametrize("name", NAMES)
def test_decomposition_at_gimbal_lock_is_valid_and_flagged(name):
    rng = np.random.default_rng(7)
    for theta2 in lock_angles(name):
        for _ in range(50):
            angles = np.array([rng.uniform(-4, 4), theta2, rng.uniform(-4, 4)])
            R = matrix_from_angles(angles, name)
            recovered = angles_from_matrix(R, name)
            assert np.all(np.isfinite(recovered.angles_rad))
            assert recovered.degenerate and recovered.lock_distance_rad < 1e-15
            assert worst(matrix_from_angles(recovered.angles_rad, name), R) < MATRIX_TOL
            # Only θ1 + s·θ3 is fixed: the recovered set has the same combination (mod 2π).
            s = SEQUENCES[name].lock_combination_sign(theta2)
            combination = recovered.angles_rad[0] + s * recovered.angles_rad[2] - (angles[0] + s * angles[2])
            assert abs(np.angle(np.exp(1j * combination))) < 1e-12


@PROPERTY
@given(sequences, angle, angle, st.floats(min_value=1e-14, max_value=1e-4), st.sampled_from([-1.0, 1.0]))
def test_decomposition_near_gimbal_lock_reproduces_the_matrix(name, theta1, theta3, offset, side):
    for theta2 in lock_angles(name):
        angles = np.array([theta1, theta2 + side * offset, theta3])
        R = matrix_from_angles(angles, name)
        recovered = angles_from_matrix(R, name)
        assert worst(matrix_from_angles(recovered.angles_rad, name), R) < MATRIX_TOL
        assert recovered.lock_distance_rad == pytest.approx(offset, abs=1e-12)


@pytest.mark.parametrize("name", NAMES)
def test_at_lock_first_and_third_turns_trade_off(name):
    """At lock R(θ1 + δ, θ2, θ3 − s δ) is the same attitude; with the other sign it is not."""
    seq = SEQUENCES[name]
    for theta2 in lock_angles(name):
        s = float(seq.lock_combination_sign(theta2))
        base = matrix_from_angles([0.4, theta2, -0.9], name)
        for delta in (0.3, -1.7, 2.9):
            assert worst(matrix_from_angles([0.4 + delta, theta2, -0.9 - s * delta], name), base) < MATRIX_TOL
            assert worst(matrix_from_angles([0.4 + delta, theta2, -0.9 + s * delta], name), base) > 0.1
        # And the body's third axis lies along the fixed first axis (that is what "lock" means).
        a1, a3 = seq.axes[0], seq.axes[2]
        assert abs(abs(base[a1, a3]) - 1.0) < MATRIX_TOL


def test_gimbal_lock_distance_is_the_angle_between_fixed_axis_1_and_body_axis_3():
    """Lock is where body axis a3 lies on the line of fixed axis a1: distance = acos |R[a1, a3]|."""
    rng = np.random.default_rng(3)
    for name, seq in SEQUENCES.items():
        for _ in range(100):
            angles = rng.uniform(-4, 4, 3)
            R = matrix_from_angles(angles, name)
            expected = math.acos(min(abs(R[seq.axes[0], seq.axes[2]]), 1.0))
            # acos loses precision near 1 (error ≈ 1e-16 / distance); 1e-7 rad covers it, a wrong formula is off by O(0.1).
            assert float(rot.gimbal_lock_distance_rad(angles, name)) == pytest.approx(expected, abs=1e-7)


# -- quaternions and axis–angle ---------------------------------------------------------------------


@PROPERTY
@given(unit_quaternions)
def test_quaternion_from_matrix_inverts_rotation_matrix(q):
    back = quaternion_from_matrix(rotation_matrix(q))
    assert back[0] >= 0.0
    assert min(worst(back, q), worst(back, -q)) < MATRIX_TOL
    x, y, z, w = Rotation.from_matrix(rotation_matrix(q)).as_quat()  # scipy: scalar last
    reference = np.array([w, x, y, z]) * (1.0 if w >= 0.0 else -1.0)
    if abs(w) > 1e-6:  # at w = 0 both signs are canonical
        assert worst(back, reference) < MATRIX_TOL


@pytest.mark.parametrize("axis", [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0), (1, -2, 3)])
def test_half_turns_survive_matrix_to_quaternion(axis):
    """At a half turn the trace is −1 and the naive formula divides by zero; Shepperd's does not."""
    R = matrix_from_axis_angle(axis, math.pi)
    q = quaternion_from_matrix(R)
    n, alpha = axis_angle_from_matrix(R)
    assert alpha == pytest.approx(math.pi, abs=1e-12)
    assert abs(abs(n @ np.asarray(axis, float)) - np.linalg.norm(axis)) < 1e-12
    assert worst(rotation_matrix(q), R) < MATRIX_TOL


@PROPERTY
@given(
    st.tuples(*[st.floats(min_value=-1, max_value=1, allow_nan=False)] * 3).map(np.array).filter(lambda v: np.linalg.norm(v) > 1e-2),
    st.floats(min_value=FAR_FROM_LOCK_RAD, max_value=math.pi - FAR_FROM_LOCK_RAD),
)
def test_axis_angle_round_trips_and_matches_scipy(axis, alpha):
    n = axis / np.linalg.norm(axis)
    R = matrix_from_axis_angle(axis, alpha)
    assert worst(R, Rotation.from_rotvec(alpha * n).as_matrix()) < MATRIX_TOL
    assert worst(R, rotation_matrix(quaternion_from_axis_angle(axis, alpha))) < MATRIX_TOL
    assert worst(R @ n, n) < MATRIX_TOL  # the axis is the line the rotation leaves fixed
    assert np.trace(R) == pytest.approx(1.0 + 2.0 * math.cos(alpha), abs=MATRIX_TOL)
    for recovered_axis, recovered_angle in (axis_angle_from_matrix(R), axis_angle_from_quaternion(quaternion_from_axis_angle(axis, alpha))):
        assert recovered_angle == pytest.approx(alpha, abs=ANGLE_TOL_RAD)
        assert worst(recovered_axis, n) < ANGLE_TOL_RAD


@PROPERTY
@given(sequences, angle_sets)
def test_angles_axis_angle_matrix_quaternion_close_the_loop(name, angles):
    """angles → quaternion → axis–angle → matrix → angles → matrix: one attitude all the way."""
    R = matrix_from_angles(angles, name)
    axis, alpha = axis_angle_from_quaternion(quaternion_from_angles(angles, name))
    R_axis_angle = matrix_from_axis_angle(axis, alpha)
    assert worst(R_axis_angle, R) < MATRIX_TOL
    assert 0.0 <= alpha <= math.pi
    back = angles_from_matrix(R_axis_angle, name).angles_rad
    assert worst(matrix_from_angles(back, name), R) < MATRIX_TOL


def test_identity_axis_is_plus_z_and_zero_axis_is_refused():
    axis, alpha = axis_angle_from_quaternion(np.array([1.0, 0.0, 0.0, 0.0]))
    assert alpha == 0.0 and np.array_equal(axis, [0.0, 0.0, 1.0])
    with pytest.raises(ValueError, match="non-zero"):
        matrix_from_axis_angle([0.0, 0.0, 0.0], 1.0)


def test_non_rotation_matrices_are_refused():
    with pytest.raises(ValueError, match="reflection"):
        quaternion_from_matrix(np.diag([1.0, 1.0, -1.0]))
    with pytest.raises(ValueError, match="not orthonormal"):
        angles_from_matrix(np.diag([1.0, 2.0, 1.0]), "3-2-1")
    with pytest.raises(ValueError, match="3×3"):
        quaternion_from_matrix(np.eye(4))


# -- composition ------------------------------------------------------------------------------------


@PROPERTY
@given(unit_quaternions, unit_quaternions)
def test_quaternion_product_is_matrix_product(qa, qb):
    assert worst(rotation_matrix(quaternion_multiply(qa, qb)), rotation_matrix(qa) @ rotation_matrix(qb)) < MATRIX_TOL


@PROPERTY
@given(sequences, angle_sets)
def test_each_turn_is_about_the_current_axis_and_inverse_reverses_the_sequence(name, angles):
    seq = SEQUENCES[name]
    frames = intermediate_frames(angles, name)
    R = frames.R_world_frame
    assert worst(R[0], np.eye(3)) == 0.0 and worst(R[3], matrix_from_angles(angles, name)) < MATRIX_TOL
    for k in range(3):
        n = frames.rotation_axes_world[k]
        # Turn k is a turn by θk about an axis fixed in the frame being turned: the same
        # line before and after, and applying it in world components gives the next frame.
        assert worst(n, R[k][:, seq.axes[k]]) == 0.0 and worst(n, R[k + 1][:, seq.axes[k]]) < MATRIX_TOL
        assert worst(matrix_from_axis_angle(n, angles[k]) @ R[k], R[k + 1]) < MATRIX_TOL
        assert worst(rotation_matrix(frames.q_world_frame[k + 1]), R[k + 1]) < MATRIX_TOL
    # Intrinsic a1-a2-a3 = extrinsic (fixed-axis) turns a3, then a2, then a1.
    fixed = np.eye(3)
    for k in (2, 1, 0):
        fixed = matrix_from_axis_angle(np.eye(3)[seq.axes[k]], angles[k]) @ fixed
    assert worst(fixed, R[3]) < MATRIX_TOL
    # The inverse is the reversed sequence with negated angles.
    reversed_name = "-".join(reversed(name.split("-")))
    assert worst(matrix_from_angles(-angles[::-1], reversed_name), R[3].T) < MATRIX_TOL


def test_functions_broadcast_like_their_scalar_calls():
    rng = np.random.default_rng(11)
    angles = rng.uniform(-3, 3, (5, 7, 3))
    for name in ("3-1-3", "2-3-1"):
        R = matrix_from_angles(angles, name)
        q = quaternion_from_angles(angles, name)
        back = angles_from_quaternion(q, name).angles_rad
        J = angle_rate_matrix_body(angles, name)
        assert R.shape == (5, 7, 3, 3) and q.shape == (5, 7, 4) and back.shape == (5, 7, 3) and J.shape == (5, 7, 3, 3)
        for idx in [(0, 0), (4, 6), (2, 3)]:
            assert worst(R[idx], matrix_from_angles(angles[idx], name)) == 0.0
            assert worst(back[idx], angles_from_quaternion(q[idx], name).angles_rad) == 0.0


# -- angular velocity -------------------------------------------------------------------------------


def rotation_matrix_rate(angles: np.ndarray, angle_rates: np.ndarray, name: str) -> np.ndarray:
    """Ṙ by the complex step: Im R(θ + i h θ̇) / h, exact to rounding for h = 1e-30 (no cancellation)."""
    h = 1e-30
    return matrix_from_angles(angles + 1j * h * angle_rates, name).imag / h


def vee(skew: np.ndarray) -> np.ndarray:
    return np.array([skew[2, 1], skew[0, 2], skew[1, 0]])


@PROPERTY
@given(sequences, angle_sets, rates)
def test_angular_velocity_equals_the_rate_of_the_rotation_matrix(name, angles, angle_rates):
    R = matrix_from_angles(angles, name)
    R_dot = rotation_matrix_rate(angles, angle_rates, name)
    scale = 1.0 + np.abs(angle_rates).sum()
    body_skew, world_skew = R.T @ R_dot, R_dot @ R.T
    assert worst(body_skew, -body_skew.T) < MATRIX_TOL * scale  # ω̃ is skew-symmetric
    assert worst(angular_velocity_body(angles, angle_rates, name), vee(body_skew)) < MATRIX_TOL * scale
    assert worst(angular_velocity_world(angles, angle_rates, name), vee(world_skew)) < MATRIX_TOL * scale
    assert worst(R @ angular_velocity_body(angles, angle_rates, name), angular_velocity_world(angles, angle_rates, name)) < MATRIX_TOL * scale


slow_rates = st.tuples(*[st.floats(min_value=-3.0, max_value=3.0, allow_nan=False)] * 3).map(np.array)


@PROPERTY
@given(sequences, angle_sets, slow_rates, slow_rates)
def test_angular_acceleration_is_the_rate_of_angular_velocity(name, angles, angle_rates, angle_accelerations):
    """Along θ(t) = θ0 + θ̇0 t + ½ θ̈ t²: α from the formula against dω/dt of the reference ω = vee(Ṙ Rᵀ).

    dω/dt by a 4th-order central difference in t (dt = 1e-3): truncation ≈ dt⁴/30 · |ω⁽⁵⁾| ≲ 3e-11 for
    rates and accelerations ≤ 3 (rad/s, rad/s²), rounding ≈ 1e-16 · |ω| / dt ≈ 1e-12; tolerance 1e-9.
    A missing or mis-signed cross term is an error of order θ̇² ~ 1.
    """

    def omega_world_reference(t: float) -> np.ndarray:
        theta = angles + angle_rates * t + 0.5 * angle_accelerations * t * t
        theta_dot = angle_rates + angle_accelerations * t
        return vee(rotation_matrix_rate(theta, theta_dot, name) @ matrix_from_angles(theta, name).T)

    dt = 1e-3
    omega = [omega_world_reference(k * dt) for k in (-2, -1, 1, 2)]
    alpha_reference = (omega[0] - 8.0 * omega[1] + 8.0 * omega[2] - omega[3]) / (12.0 * dt)
    alpha = rot.angular_acceleration_world(angles, angle_rates, angle_accelerations, name)
    assert worst(alpha, alpha_reference) < 1e-9
    R = matrix_from_angles(angles, name)
    assert worst(R @ rot.angular_acceleration_body(angles, angle_rates, angle_accelerations, name), alpha) < MATRIX_TOL * 100


def test_complex_step_agrees_with_central_differences():
    """Guards the reference itself: a central difference (error ~h²) tells the same story."""
    angles, angle_rates = np.array([0.3, 1.1, -2.0]), np.array([1.5, -0.7, 4.0])
    for name in NAMES:
        h = 1e-5
        central = (matrix_from_angles(angles + h * angle_rates, name) - matrix_from_angles(angles - h * angle_rates, name)) / (2 * h)
        assert worst(central, rotation_matrix_rate(angles, angle_rates, name)) < 1e-8  # h²·|θ̇|³/6 ≈ 1e-8


@PROPERTY
@given(sequences, angle_sets, rates)
def test_rates_from_angular_velocity_invert_it_away_from_lock(name, angles, angle_rates):
    distance = float(rot.gimbal_lock_distance_rad(angles, name))
    if distance < 0.05:
        return
    # Solving J θ̇ = ω amplifies rounding by the condition number, ≲ 2/sin(distance) ≤ 40 here.
    tol = 1e-12 * (1.0 + np.abs(angle_rates).sum()) / math.sin(distance)
    omega_b = angular_velocity_body(angles, angle_rates, name)
    omega_w = angular_velocity_world(angles, angle_rates, name)
    assert worst(angle_rates_from_angular_velocity_body(angles, omega_b, name), angle_rates) < tol
    assert worst(angle_rates_from_angular_velocity_world(angles, omega_w, name), angle_rates) < tol


@pytest.mark.parametrize("name", NAMES)
def test_rates_at_gimbal_lock_are_a_clear_error_and_the_jacobian_is_singular(name):
    for theta2 in lock_angles(name):
        angles = np.array([0.2, theta2, 0.5])
        assert abs(np.linalg.det(angle_rate_matrix_body(angles, name))) < 1e-15
        with pytest.raises(ValueError, match="gimbal lock.*only the sum or difference"):
            angle_rates_from_angular_velocity_body(angles, [0.1, 0.2, 0.3], name)
        with pytest.raises(ValueError, match="gimbal lock"):
            angle_rates_from_angular_velocity_world(angles, [0.1, 0.2, 0.3], name)


@PROPERTY
@given(sequences, angle_sets)
def test_jacobian_determinant_is_the_sine_of_the_lock_distance(name, angles):
    det = abs(np.linalg.det(angle_rate_matrix_body(angles, name)))
    assert det == pytest.approx(math.sin(float(rot.gimbal_lock_distance_rad(angles, name))), abs=MATRIX_TOL)


# -- the 3-1-3 names the tops use -------------------------------------------------------------------


def test_313_functions_keep_their_closed_forms():
    """Closed forms written out here, independently of the general code."""
    rng = np.random.default_rng(5)
    for _ in range(200):
        phi, theta, psi = rng.uniform(-4, 4, 3)
        c, s = math.cos(theta / 2), math.sin(theta / 2)
        q = np.array([c * math.cos((phi + psi) / 2), s * math.cos((phi - psi) / 2), s * math.sin((phi - psi) / 2), c * math.sin((phi + psi) / 2)])
        assert worst(rot.quaternion_from_euler_313(phi, theta, psi), q) < 1e-15
        phi_dot, theta_dot, psi_dot = rng.normal(size=3)
        expected = [
            phi_dot * math.sin(theta) * math.sin(psi) + theta_dot * math.cos(psi),
            phi_dot * math.sin(theta) * math.cos(psi) - theta_dot * math.sin(psi),
            phi_dot * math.cos(theta) + psi_dot,
        ]
        assert worst(rot.body_rates_from_euler_313_rates(theta, psi, phi_dot, theta_dot, psi_dot), expected) < 1e-14
        angles = rot.euler_313_from_quaternion(q)
        assert worst(rotation_matrix(rot.quaternion_from_euler_313(*angles)), rotation_matrix(q)) < MATRIX_TOL


def test_313_at_lock_splits_the_sum_equally():
    """At θ = 0 only φ + ψ is determined; the free difference is zero, never NaN."""
    phi, theta, psi = rot.euler_313_from_quaternion(rot.quaternion_from_euler_313(0.9, 0.0, 0.5))
    assert theta == 0.0 and phi == pytest.approx(0.7, abs=1e-15) and psi == pytest.approx(0.7, abs=1e-15)
    # −0.0 components do not turn the split into φ − ψ = 2π (they did before the general code).
    phi, _, psi = rot.euler_313_from_quaternion(np.array([0.6, -0.0, 0.0, 0.8]))
    assert phi == psi


def test_one_quaternion_takes_the_scalar_path_and_agrees_with_the_array_path():
    """rotation_matrix has a plain-float path for a single attitude (every live frame); it must be the same matrix."""
    rng = np.random.default_rng(7)
    quaternions = rng.normal(size=(200, 4)) * rng.uniform(0.1, 10.0, size=(200, 1))  # not normalised: both paths normalise
    batched = rotation_matrix(quaternions)
    for q, expected in zip(quaternions, batched):
        np.testing.assert_allclose(rotation_matrix(q), expected, rtol=0.0, atol=4e-16)  # the same formula: round-off only
    assert np.all(np.isnan(rotation_matrix(np.zeros(4))))  # no rotation has a zero quaternion; as the array path says
