"""MuJoCo counterparts of Dynamics Lab models, for work-precision benchmarks.

Only used by the benchmark (``mujoco`` is in the optional ``bench`` dependency
group), so ``mujoco`` is imported inside the functions that need it.

Rigid body about a fixed point (heavy top; torque-free body when ``l = 0``)
---------------------------------------------------------------------------
Our model: body frame = principal axes at the pivot, body +3 the symmetry axis,
principal moments about the PIVOT ``(I1, I2, I3)``, mass ``m`` with its centre of
mass on body +3 at distance ``l`` from the pivot, gravity ``g`` along world −Z.
State: ``q_world_body`` (``wxyz``, see :mod:`app.physics.math.rotations`) and the
body-frame angular velocity ``omega``.

MuJoCo model: one body whose frame coincides with the pivot frame, attached to
the world by a ball joint at its origin. Its ``inertial`` element puts the centre
of mass at ``pos = (0, 0, l)`` with ``diaginertia`` the moments about the CENTRE
OF MASS, ``(I1 − m l², I2 − m l², I3)`` (parallel-axis theorem), so the joint-space
mass matrix is ``diag(I1, I2, I3)``. No geoms (hence no contacts; contacts and
constraints are disabled anyway), no damping, armature, friction loss or limits.

Verified against MuJoCo (see ``tests/bench/test_mujoco_models.py``):

* a ball joint's ``qvel`` is the angular velocity in the child body's LOCAL frame
  (``mj_objectVelocity(..., flg_local=1)`` returns it unchanged, the world value is
  ``R @ qvel``), i.e. exactly our ``omega`` — no conversion;
* with the body frame at the joint and no body ``quat``, ``qpos`` (``wxyz``) equals
  ``data.xquat`` of the body, i.e. our ``q_world_body`` — no conversion;
* ``mj_fullM`` gives ``diag(I1, I2, I3)``, and MuJoCo keeps ``diaginertia`` in the
  given order (``body_iquat`` is the identity), so body axes are not permuted.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.bodies.inertia import check_principal_inertia

#: Our names for MuJoCo's integrators (``mjtIntegrator``). "Euler" is MuJoCo's
#: semi-implicit Euler; "implicitfast" drops the Coriolis terms from the
#: implicit velocity derivative, "implicit" keeps them.
INTEGRATORS: dict[str, str] = {
    "RK4": "mjINT_RK4",
    "Euler": "mjINT_EULER",
    "implicitfast": "mjINT_IMPLICITFAST",
    "implicit": "mjINT_IMPLICIT",
}


@dataclass(frozen=True)
class MujocoRigidBodyRun:
    """Frames sampled from a MuJoCo run of the rigid body about a fixed point.

    ``t`` (F+1,) frame times from 0 s; ``quaternion`` (F+1, 4) ``q_world_body`` ``wxyz``;
    ``omega_body`` (F+1, 3) body-frame angular velocity, rad/s; ``cpu_s`` process CPU
    time and ``wall_s`` wall time of the stepping loop only (``mj_step`` plus copying
    the state out once per frame; model compilation excluded); ``steps`` the number
    of MuJoCo steps taken; ``timestep_s`` their size.
    """

    t: np.ndarray
    quaternion: np.ndarray
    omega_body: np.ndarray
    cpu_s: float
    wall_s: float
    steps: int
    timestep_s: float
    integrator: str


def _fmt(x: float) -> str:
    """A float written so MJCF parses it back exactly (shortest round-trip repr)."""
    return repr(float(x))


def rigid_body_mjcf(
    *,
    inertia_pivot: tuple[float, float, float],
    mass_kg: float,
    cg_distance_m: float,
    g_m_s2: float,
    timestep_s: float = 0.002,
    integrator: str = "RK4",
) -> str:
    """MJCF text of the rigid body about a fixed point (see the module docstring).

    Raises ``ValueError`` for an unknown integrator, non-positive mass or timestep,
    or moments that are not those of a real body about the pivot (moments about the
    centre of mass must be positive and satisfy the triangle inequality).
    """
    if integrator not in INTEGRATORS:
        raise ValueError(f"integrator must be one of {sorted(INTEGRATORS)}, got {integrator!r}")
    if not (mass_kg > 0.0):
        raise ValueError("mass_kg must be positive")
    if not (timestep_s > 0.0):
        raise ValueError("timestep_s must be positive")
    i1, i2, i3 = (float(v) for v in inertia_pivot)
    shift = mass_kg * cg_distance_m * cg_distance_m
    cm = (i1 - shift, i2 - shift, i3)
    check_principal_inertia(cm, about="the centre of mass")
    return f"""<mujoco model="rigid_body_fixed_point">
  <compiler angle="radian" inertiafromgeom="false" autolimits="false"/>
  <option timestep="{_fmt(timestep_s)}" integrator="{integrator}" gravity="0 0 {_fmt(-g_m_s2)}">
    <flag contact="disable" constraint="disable" energy="enable"/>
  </option>
  <worldbody>
    <body name="body" pos="0 0 0">
      <joint name="pivot" type="ball" pos="0 0 0" limited="false"
             damping="0" armature="0" frictionloss="0" stiffness="0"/>
      <inertial pos="0 0 {_fmt(cg_distance_m)}" mass="{_fmt(mass_kg)}"
                diaginertia="{_fmt(cm[0])} {_fmt(cm[1])} {_fmt(cm[2])}"/>
    </body>
  </worldbody>
</mujoco>
"""


def build_rigid_body_model(**mjcf_options: Any):
    """Compiled ``(mujoco.MjModel, mujoco.MjData)`` of :func:`rigid_body_mjcf` (same keyword options)."""
    import mujoco

    xml = rigid_body_mjcf(**mjcf_options)
    model = mujoco.MjModel.from_xml_string(xml)
    return model, mujoco.MjData(model)


def simulate_rigid_body_mujoco(
    *,
    inertia_pivot: tuple[float, float, float],
    mass_kg: float,
    cg_distance_m: float,
    g_m_s2: float,
    q0: np.ndarray,
    omega0_body: np.ndarray,
    t_end_s: float,
    frame_rate_hz: float,
    steps_per_frame: int,
    integrator: str,
) -> MujocoRigidBodyRun:
    """Run the rigid body about a fixed point in MuJoCo, sampling once per frame.

    ``timestep = 1/(frame_rate_hz·steps_per_frame)``; ``t_end_s·frame_rate_hz`` must
    be a whole number of frames F. ``q0`` (``wxyz`` ``q_world_body``, normalised
    here) and ``omega0_body`` (rad/s, body frame) are the state at t = 0. The model
    is compiled before timing starts; the timed loop is F calls of
    ``mj_step(model, data, nstep=steps_per_frame)`` plus a copy of ``qpos``/``qvel``
    after each.
    """
    import mujoco

    steps_per_frame = int(steps_per_frame)
    if steps_per_frame < 1:
        raise ValueError("steps_per_frame must be >= 1")
    if not (frame_rate_hz > 0.0):
        raise ValueError("frame_rate_hz must be positive")
    frames_exact = t_end_s * frame_rate_hz
    frames = int(round(frames_exact))
    if frames < 0 or abs(frames - frames_exact) > 1e-9 * max(1.0, frames_exact):
        raise ValueError(f"t_end_s·frame_rate_hz = {frames_exact} is not a whole number of frames")
    timestep_s = 1.0 / (frame_rate_hz * steps_per_frame)

    model, data = build_rigid_body_model(
        inertia_pivot=inertia_pivot,
        mass_kg=mass_kg,
        cg_distance_m=cg_distance_m,
        g_m_s2=g_m_s2,
        timestep_s=timestep_s,
        integrator=integrator,
    )
    # Energy is only for diagnostics; don't pay for it in the timed loop.
    model.opt.enableflags &= ~int(mujoco.mjtEnableBit.mjENBL_ENERGY)

    q0 = np.asarray(q0, dtype=float).reshape(4)
    norm = float(np.linalg.norm(q0))
    if not math.isfinite(norm) or norm == 0.0:
        raise ValueError("q0 must be a non-zero finite quaternion")
    data.qpos[:] = q0 / norm
    data.qvel[:] = np.asarray(omega0_body, dtype=float).reshape(3)
    data.time = 0.0

    quaternion = np.empty((frames + 1, 4))
    omega = np.empty((frames + 1, 3))
    quaternion[0] = data.qpos
    omega[0] = data.qvel

    step = mujoco.mj_step
    qpos, qvel = data.qpos, data.qvel  # views into MjData, updated in place by mj_step
    wall0 = time.perf_counter()
    cpu0 = time.process_time()
    for k in range(1, frames + 1):
        step(model, data, steps_per_frame)
        quaternion[k] = qpos
        omega[k] = qvel
    cpu_s = time.process_time() - cpu0
    wall_s = time.perf_counter() - wall0

    return MujocoRigidBodyRun(
        t=np.arange(frames + 1) / frame_rate_hz,
        quaternion=quaternion,
        omega_body=omega,
        cpu_s=cpu_s,
        wall_s=wall_s,
        steps=frames * steps_per_frame,
        timestep_s=timestep_s,
        integrator=integrator,
    )
