"""The compiled splitting kernel (app/physics/solvers/splitting.py) against an independent rotation-matrix version.

The kernel keeps the attitude as a quaternion, shares one torque evaluation between consecutive
Strang stages and reuses each stage's spin sine and cosine while ``L3`` is unchanged. The reference
below does the same exact flows the plain way — rotation matrices from scipy, the torque evaluated at
every kick, every sine and cosine computed afresh — so the two differ by round-off only, and any
slip in the bookkeeping (a stale torque, a stale spin rotation, a wrong stage weight) shows as an
error of the size of the method's truncation error, at least 1e-6 here.

The torque kernel lives at module level so numba's on-disk cache can key it to this file.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from app.physics.bodies.rigid_body import PivotedBody
from app.physics.solvers import OdeSystem, make_integrator, simulate
from app.physics.solvers.kernels import TORQUE_SIGNATURE, kernel
from app.physics.solvers.splitting import COMPOSITIONS
from app.physics.systems.ch10 import heavy_top


@kernel(TORQUE_SIGNATURE)
def gravity_and_spin_motor_torque(q, p, torque_body):
    """Gravity about the pivot (``p[3]`` = m g l, N·m) plus a motor torque ``p[4]`` (N·m) about body axis 3."""
    w, x, y, z = q[0], q[1], q[2], q[3]
    torque_body[0] = p[3] * 2.0 * (y * z + w * x)
    torque_body[1] = -p[3] * 2.0 * (x * z - w * y)
    torque_body[2] = p[4]


def reference_splitting(y0: np.ndarray, parameters: np.ndarray, *, order: int, h: float, steps: int, torque) -> np.ndarray:
    """The composed splitting with rotation matrices: (steps+1, 7) states ``[q_wxyz, ω_body]`` after each step.

    ``torque(q_wxyz, p, out)`` is the model's torque (its Python twin); it is called at every kick.
    """
    I1, I2, I3 = parameters[:3]
    asym = 1.0 / I2 - 1.0 / I1
    R = Rotation.from_quat(y0[[1, 2, 3, 0]]).as_matrix()  # world ← body
    L = np.array([I1, I2, I3]) * y0[4:7]
    tau = np.empty(3)

    def kick(duration: float) -> None:
        q = Rotation.from_matrix(R).as_quat()[[3, 0, 1, 2]]
        torque(q, parameters, tau)
        L[:] += duration * tau

    def turn(axis_body: np.ndarray, angle: float) -> tuple[np.ndarray, np.ndarray]:
        """The body turns by ``angle`` about ``axis_body``; a vector fixed in space turns the other way in body components."""
        rotation = Rotation.from_rotvec(angle * axis_body).as_matrix()
        return R @ rotation, rotation.T @ L

    def asymmetric(duration: float) -> None:
        nonlocal R, L
        R, L = turn(np.array([0.0, 1.0, 0.0]), asym * L[1] * duration)

    out = [y0.copy()]
    for _ in range(steps):
        for weight in COMPOSITIONS[order]:
            sub = weight * h
            kick(0.5 * sub)
            asymmetric(0.5 * sub)
            norm_L = np.linalg.norm(L)
            R, _ = turn(L / norm_L, norm_L / I1 * sub)  # L is along the rotation axis: unchanged
            R, L = turn(np.array([0.0, 0.0, 1.0]), L[2] * (1.0 / I3 - 1.0 / I1) * sub)
            asymmetric(0.5 * sub)
            kick(0.5 * sub)
        q = Rotation.from_matrix(R).as_quat()[[3, 0, 1, 2]]
        q *= np.sign(q @ out[-1][:4])  # the kernel's quaternion is continuous in time
        out.append(np.concatenate([q, L / np.array([I1, I2, I3])]))
    return np.array(out)


PARAMS = heavy_top.PARAMETERS.defaults()
TOP = heavy_top.rigid_body(PARAMS)
TOP_Y0 = heavy_top.initial_state(PARAMS)
#: An asymmetric body (I = (2, 3, 4)·10⁻³ kg·m² about the pivot, m g l = 0.05 N·m) with a motor torque of
#: 2·10⁻³ N·m about body 3: L3 changes every kick, so no spin rotation can be reused.
MOTOR_PARAMETERS = np.array([2e-3, 3e-3, 4e-3, 0.05, 2e-3])
MOTOR_Y0 = np.concatenate([Rotation.from_euler("x", 0.4).as_quat()[[3, 0, 1, 2]], [1.0, -2.0, 30.0]])
MOTOR_SYSTEM = OdeSystem(
    rhs=PivotedBody((2e-3, 3e-3, 4e-3)).system().rhs, parameters=MOTOR_PARAMETERS, state_names=TOP.system().state_names,
    torque=gravity_and_spin_motor_torque,
)


@pytest.mark.parametrize("order", [2, 4, 6])
@pytest.mark.parametrize("case", ["symmetric top (spin rotations reused)", "asymmetric body with a spin motor"])
def test_kernel_matches_the_rotation_matrix_splitting(order, case):
    if case.startswith("symmetric"):
        system, y0 = TOP.system(), TOP_Y0
        torque = TOP.system().torque.python
    else:
        system, y0 = MOTOR_SYSTEM, MOTOR_Y0
        torque = gravity_and_spin_motor_torque.python
    frames, rate = 30, 60.0  # 0.5 s, one step per frame (h·ω3 = 1 rad on the top, 0.5 rad on the motor body)
    result = simulate(system, make_integrator(f"splitting{order}", steps_per_frame=1), y0, t_end_s=frames / rate, frame_rate_hz=rate)
    assert result.status == "ok"
    reference = reference_splitting(y0, system.parameters, order=order, h=1.0 / rate, steps=frames, torque=torque)
    scale = np.max(np.abs(reference), axis=0)
    # Observed at most 1.8e-13 of each component's scale (q ~ 1, ω3 = 60 and 30 rad/s); 1e-11 leaves room for
    # round-off growing over 30 steps. A stale torque or spin rotation is a truncation-size error, ≥ 1e-6 here.
    assert np.all(np.abs(result.states - reference) <= 1e-11 * scale), np.max(np.abs(result.states - reference) / scale)
