"""MuJoCo counterpart of the rigid body about a fixed point (app/bench/mujoco_models.py).

The checks pin down the two things that are easy to get wrong when porting the
model: the inertia shift (moments about the pivot vs about the centre of mass)
and the frame of the ball joint's velocity (body vs world). Each would change
the mass matrix, the conserved quantities or the trajectory far beyond the
tolerances used here.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

mujoco = pytest.importorskip("mujoco")

from app.bench.mujoco_models import (  # noqa: E402
    INTEGRATORS,
    build_rigid_body_model,
    rigid_body_mjcf,
    simulate_rigid_body_mujoco,
)
from app.physics.math.rotations import (  # noqa: E402
    quaternion_from_euler_313,
    rotate_vector,
    rotation_matrix,
)

G = 9.807
E3 = np.array([0.0, 0.0, 1.0])

# Heavy top: moments about the pivot; about the centre of mass the transverse
# moment is 0.0125 − 1·0.05² = 0.01 (≥ I3/2, a real body).
TOP = dict(inertia_pivot=(0.0125, 0.0125, 0.01), mass_kg=1.0, cg_distance_m=0.05, g_m_s2=G)
# Torque-free asymmetric body (no centre-of-mass offset).
FREE = dict(inertia_pivot=(0.010, 0.015, 0.020), mass_kg=2.0, cg_distance_m=0.0, g_m_s2=G)


def reference_rigid_body(inertia_pivot, mass_kg, cg_distance_m, g_m_s2, q0, omega0_body, t_eval):
    """Euler's equations about the pivot + quaternion kinematics, DOP853 at rtol 1e-12.

    Written independently of MuJoCo: I ω̇ = r_cm × m g_body − ω × I ω with
    g_body = Rᵀ(0, 0, −g), r_cm = (0, 0, l); q̇ = ½ q ⊗ (0, ω) (wxyz, world←body).
    Returns (quaternion (N, 4) normalised, omega_body (N, 3)).
    """
    inertia = np.asarray(inertia_pivot, dtype=float)
    weight_moment = mass_kg * g_m_s2 * cg_distance_m  # |r_cm| · m g

    def rhs(_t, y):
        w, x, yq, z = y[:4]
        om = y[4:]
        # Body components of world −Z (third row of R, negated): gravity direction.
        down = -np.array([2 * (x * z - w * yq), 2 * (yq * z + w * x), 1 - 2 * (x * x + yq * yq)])
        torque = weight_moment * np.cross(E3, down)
        om_dot = (torque - np.cross(om, inertia * om)) / inertia
        p, q_, r = om
        q_dot = 0.5 * np.array(
            [-x * p - yq * q_ - z * r, w * p + yq * r - z * q_, w * q_ - x * r + z * p, w * r + x * q_ - yq * p]
        )
        return np.concatenate([q_dot, om_dot])

    y0 = np.concatenate([np.asarray(q0, float) / np.linalg.norm(q0), np.asarray(omega0_body, float)])
    sol = solve_ivp(rhs, (t_eval[0], t_eval[-1]), y0, method="DOP853", rtol=1e-12, atol=1e-14, t_eval=t_eval)
    assert sol.success, sol.message
    quat = sol.y[:4].T
    return quat / np.linalg.norm(quat, axis=1, keepdims=True), sol.y[4:].T


def axis_angle_error(q_a, q_b):
    """Angle (rad) between the body +3 axes of two attitude series."""
    a = rotate_vector(q_a, E3)
    b = rotate_vector(q_b, E3)
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=-1), np.sum(a * b, axis=-1))


def energy(run, inertia_pivot, mass_kg, cg_distance_m, g_m_s2):
    inertia = np.asarray(inertia_pivot)
    kinetic = 0.5 * np.sum(inertia * run.omega_body**2, axis=1)
    height = rotate_vector(run.quaternion, E3)[:, 2] * cg_distance_m
    return kinetic + mass_kg * g_m_s2 * height


def world_angular_momentum(run, inertia_pivot):
    return rotate_vector(run.quaternion, np.asarray(inertia_pivot) * run.omega_body)


def test_mass_matrix_is_the_inertia_about_the_pivot():
    # The parallel-axis shift must give diag(I1, I2, I3) about the pivot, in our axis order.
    model, data = build_rigid_body_model(**TOP)
    data.qpos[:] = quaternion_from_euler_313(0.4, 0.7, -1.1)
    mujoco.mj_forward(model, data)
    full = np.zeros((3, 3))
    mujoco.mj_fullM(model, data, full)
    np.testing.assert_allclose(full, np.diag(TOP["inertia_pivot"]), rtol=0, atol=1e-15)
    np.testing.assert_allclose(model.body_ipos[1], [0.0, 0.0, 0.05], rtol=0, atol=0)
    np.testing.assert_allclose(model.body_inertia[1], [0.01, 0.01, 0.01], rtol=1e-14)
    np.testing.assert_array_equal(model.body_iquat[1], [1.0, 0.0, 0.0, 0.0])


def test_ball_joint_state_is_our_attitude_and_body_rate():
    model, data = build_rigid_body_model(**FREE)
    q = quaternion_from_euler_313(0.4, 0.7, -1.1)
    omega = np.array([1.0, -2.0, 3.0])
    data.qpos[:] = q
    data.qvel[:] = omega
    mujoco.mj_forward(model, data)
    # qpos is the body's world attitude (xquat) and xmat is our rotation_matrix of it.
    np.testing.assert_allclose(data.xquat[1], q, rtol=0, atol=1e-15)
    np.testing.assert_allclose(data.xmat[1].reshape(3, 3), rotation_matrix(q), rtol=0, atol=1e-15)
    # qvel is the body-frame angular velocity: local object velocity equals it,
    # world object velocity is R @ qvel (and R @ qvel differs from qvel here).
    local = np.zeros(6)
    world = np.zeros(6)
    mujoco.mj_objectVelocity(model, data, mujoco.mjtObj.mjOBJ_BODY, 1, local, 1)
    mujoco.mj_objectVelocity(model, data, mujoco.mjtObj.mjOBJ_BODY, 1, world, 0)
    np.testing.assert_allclose(local[:3], omega, rtol=0, atol=1e-14)
    np.testing.assert_allclose(world[:3], rotation_matrix(q) @ omega, rtol=0, atol=1e-14)
    assert np.linalg.norm(world[:3] - omega) > 1.0


def test_torque_free_body_conserves_energy_and_world_angular_momentum():
    # Asymmetric body spinning near its intermediate axis (tumbles): 1 s, RK4, h = 1/7680 s.
    q0 = quaternion_from_euler_313(0.3, 1.0, 0.2)
    omega0 = np.array([1.0, 8.0, 1.0])
    run = simulate_rigid_body_mujoco(
        **FREE, q0=q0, omega0_body=omega0, t_end_s=1.0, frame_rate_hz=60.0, steps_per_frame=128, integrator="RK4"
    )
    assert run.t.shape == (61,) and run.quaternion.shape == (61, 4) and run.omega_body.shape == (61, 3)
    assert run.t[0] == 0.0 and run.t[-1] == pytest.approx(1.0) and run.steps == 60 * 128
    # The body really tumbles: ω changes a lot, so conservation is not trivially satisfied.
    assert np.ptp(run.omega_body[:, 0]) > 1.0
    e = energy(run, **FREE)
    h = world_angular_momentum(run, FREE["inertia_pivot"])
    # E ≈ 0.50 J, |H| ≈ 0.12 N·m·s; relative drift ≤ 1e-8 (RK4 at this step gives ~1e-14).
    assert np.max(np.abs(e - e[0])) <= 1e-8 * e[0]
    assert np.max(np.linalg.norm(h - h[0], axis=1)) <= 1e-8 * np.linalg.norm(h[0])
    # And it matches the independent reference.
    q_ref, omega_ref = reference_rigid_body(**FREE, q0=q0, omega0_body=omega0, t_eval=run.t)
    assert np.max(np.abs(run.omega_body - omega_ref)) <= 1e-7
    assert np.max(axis_angle_error(run.quaternion, q_ref)) <= 1e-8


def test_heavy_top_matches_independent_reference():
    # θ0 = 30°, spin 60 rad/s, released with no precession or nutation rate: 2 s, RK4, h = 1/7680 s.
    q0 = quaternion_from_euler_313(0.0, math.radians(30.0), 0.0)
    omega0 = np.array([0.0, 0.0, 60.0])
    run = simulate_rigid_body_mujoco(
        **TOP, q0=q0, omega0_body=omega0, t_end_s=2.0, frame_rate_hz=60.0, steps_per_frame=128, integrator="RK4"
    )
    q_ref, omega_ref = reference_rigid_body(**TOP, q0=q0, omega0_body=omega0, t_eval=run.t)
    err = axis_angle_error(run.quaternion, q_ref)
    assert np.max(err) <= 1e-6
    np.testing.assert_allclose(run.omega_body, omega_ref, rtol=0, atol=1e-5)
    # The top precesses by a lot in 2 s (≈ m g l / (I3 ω3) ≈ 0.8 rad/s), so an error in
    # the torque, inertia or velocity frame could not hide below the tolerance.
    axis = rotate_vector(run.quaternion, E3)
    assert abs(math.atan2(axis[-1, 1], axis[-1, 0]) - math.atan2(axis[0, 1], axis[0, 0])) > 0.5
    # Conserved: energy, the vertical angular momentum and the spin rate ω3 (I1 = I2).
    e = energy(run, **TOP)
    assert np.max(np.abs(e - e[0])) <= 1e-9 * e[0]
    hz = world_angular_momentum(run, TOP["inertia_pivot"])[:, 2]
    assert np.max(np.abs(hz - hz[0])) <= 1e-9 * abs(hz[0])
    assert np.max(np.abs(run.omega_body[:, 2] - 60.0)) <= 1e-9


def test_a_model_with_uncorrected_inertia_would_be_caught():
    # Control for the test above: giving MuJoCo the pivot moments as CM moments
    # (forgetting the shift) is detected at far more than the 1e-6 rad tolerance.
    q0 = quaternion_from_euler_313(0.0, math.radians(30.0), 0.0)
    omega0 = np.array([0.0, 0.0, 60.0])
    wrong = dict(TOP, inertia_pivot=(0.0125 + 0.0025, 0.0125 + 0.0025, 0.01))  # CM moments = 0.0125
    run = simulate_rigid_body_mujoco(
        **wrong, q0=q0, omega0_body=omega0, t_end_s=2.0, frame_rate_hz=60.0, steps_per_frame=16, integrator="RK4"
    )
    q_ref, _ = reference_rigid_body(**TOP, q0=q0, omega0_body=omega0, t_eval=run.t)
    assert np.max(axis_angle_error(run.quaternion, q_ref)) > 1e-3


@pytest.mark.parametrize("integrator", sorted(INTEGRATORS))
def test_every_integrator_is_selected_and_converges(integrator):
    model, _ = build_rigid_body_model(**TOP, integrator=integrator)
    assert model.opt.integrator == int(getattr(mujoco.mjtIntegrator, INTEGRATORS[integrator]))
    q0 = quaternion_from_euler_313(0.0, math.radians(30.0), 0.0)
    omega0 = np.array([0.0, 0.0, 60.0])
    errors = []
    for steps in (4, 16):
        run = simulate_rigid_body_mujoco(
            **TOP, q0=q0, omega0_body=omega0, t_end_s=0.5, frame_rate_hz=60.0, steps_per_frame=steps,
            integrator=integrator,
        )
        assert run.timestep_s == pytest.approx(1.0 / (60.0 * steps)) and run.cpu_s >= 0.0
        q_ref, _ = reference_rigid_body(**TOP, q0=q0, omega0_body=omega0, t_eval=run.t)
        errors.append(np.max(axis_angle_error(run.quaternion, q_ref)))
    # 4× smaller steps: ≥ 3× smaller error for the first-order methods, ≥ 100× for RK4.
    assert errors[1] < errors[0] / (100.0 if integrator == "RK4" else 3.0)


def test_rejects_bad_arguments():
    with pytest.raises(ValueError, match="integrator"):
        rigid_body_mjcf(**TOP, integrator="rk4")
    with pytest.raises(ValueError, match="centre of mass"):
        rigid_body_mjcf(**dict(TOP, cg_distance_m=0.2))  # 0.0125 − 0.04 < 0
    with pytest.raises(ValueError, match="triangle"):
        rigid_body_mjcf(**dict(TOP, inertia_pivot=(0.0125, 0.0125, 0.03)))
    with pytest.raises(ValueError, match="whole number of frames"):
        simulate_rigid_body_mujoco(
            **TOP, q0=[1, 0, 0, 0], omega0_body=[0, 0, 1], t_end_s=0.01, frame_rate_hz=60.0, steps_per_frame=1,
            integrator="RK4",
        )
