"""Geometric splitting for a rigid body about a fixed point (order 2, 4, 6 or 8).

The Hamiltonian of a rigid body with principal moments ``I1, I2, I3`` about
the fixed point (body frame) and a torque that depends on attitude only is
split into three pieces, each of which can be solved *exactly*:

* ``T_axi = (L1² + L2²)/(2 I1) + L3²/(2 I3)`` — the free motion of an
  axisymmetric body: the body turns about its angular momentum at
  ``|L|/I1`` while ``L`` turns about body axis 3 at ``L3 (1/I3 − 1/I1)``;
* ``T_asym = (1/I2 − 1/I1) L2²/2`` — zero for an axisymmetric body, else a
  rotation about body axis 2;
* ``V(q)`` — a kick ``L ← L + h τ_body(q)`` at fixed attitude.

Strang's symmetric composition of the exact flows is order 2; symmetric
compositions of Strang steps raise the order (see :data:`COMPOSITIONS`):
Suzuki's five stages give order 4, Kahan and Li's nine and seventeen stages
orders 6 and 8. The torque after a Strang step's last kick is the torque at
the next one's first kick (same attitude), so a run evaluates the torque once
per Strang stage plus once at its start. Every sub-flow is a rotation, so
the quaternion stays unit (it is renormalised once per frame against
round-off), the spin of an axisymmetric body costs nothing however fast it is,
and energy errors stay bounded instead of drifting.

Cost: a Strang stage is a chain of dependent operations (kick, ``|L|``, a sine
and cosine, a quaternion product, the torque), so its time is latency, not
arithmetic. A torque with no component about the symmetry axis (gravity on a
symmetric top) leaves ``L3`` exactly unchanged, so the spin rotation of each
stage has the same sine and cosine every step: they are kept per stage and
recomputed only when ``L3`` changes (bit-identical to recomputing them).

State layout (shared with the other rigid-body integrators):
``y = [q_w, q_x, q_y, q_z, ω1, ω2, ω3]`` with ``q`` = ``q_world_body`` and ``ω``
body-frame angular velocity (rad/s); ``p[0:3]`` are ``I1, I2, I3`` (kg·m²).
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numba import types
from numba.extending import register_jitable

from app.physics.solvers.base import FixedStepIntegrator
from app.physics.solvers.kernels import MATRIX, TORQUE_TYPE, VECTOR, Kernel
from app.physics.solvers.spec import MethodSpec, Supports

_SUZUKI_P = 1.0 / (4.0 - 4.0 ** (1.0 / 3.0))


def symmetric_composition(leading: tuple[float, ...]) -> np.ndarray:
    """The full palindrome ``γ1 … γk γ(k+1) γk … γ1`` with the middle weight ``1 − 2 Σ γi`` (the weights sum to 1)."""
    head = np.array(leading)
    return np.concatenate([head, [1.0 - 2.0 * float(np.sum(head))], head[::-1]])


#: Kahan & Li's symmetric 9-stage order-6 composition "s9odr6a" (W. Kahan and R.-C. Li, "Composition
#: constants for raising the orders of unconventional schemes for ordinary differential equations",
#: Math. Comp. 66 (1997) 1089–1099; quoted in Hairer, Lubich & Wanner, *Geometric Numerical
#: Integration*, 2nd ed. (2006), §V.3.2, p. 158). The middle weight is 1 − 2 Σ γi = 0.798543990934830.
_KAHAN_LI_6 = (
    0.39216144400731413927925056,
    0.33259913678935943859974864,
    -0.70624617255763935980996482,
    0.08221359629355080023149045,
)
#: Kahan & Li's symmetric 17-stage order-8 composition "s17odr8a" (same sources, HLW p. 158);
#: middle weight 1 − 2 Σ γi = −0.605508533830035.
_KAHAN_LI_8 = (
    0.13020248308889008087881763,
    0.56116298177510838456196441,
    -0.38947496264484728640807860,
    0.15884190655515560089621075,
    -0.39590389413323757733623154,
    0.18453964097831570709183254,
    0.25837438768632204729397911,
    0.29501172360931029887096624,
)

#: Sub-step weights of each composition (fractions of h for one Strang step each), keyed by order.
COMPOSITIONS = {
    2: np.array([1.0]),
    4: np.array([_SUZUKI_P, _SUZUKI_P, 1.0 - 4.0 * _SUZUKI_P, _SUZUKI_P, _SUZUKI_P]),
    6: symmetric_composition(_KAHAN_LI_6),
    8: symmetric_composition(_KAHAN_LI_8),
}


@register_jitable
def _multiply_body(q, c, bx, by, bz):
    """``q ← q ⊗ (c, bx, by, bz)``: a body-frame rotation quaternion ``(cos ½θ, sin ½θ · axis)`` applied to ``q``."""
    w, x, y, z = q[0], q[1], q[2], q[3]
    q[0] = w * c - x * bx - y * by - z * bz
    q[1] = w * bx + x * c + y * bz - z * by
    q[2] = w * by - x * bz + y * c + z * bx
    q[3] = w * bz + x * by - y * bx + z * c


@register_jitable
def _rotate_quaternion_body(q, axis_x, axis_y, axis_z, angle):
    """``q ← q ⊗ rot(axis, angle)`` for a unit body-frame ``axis``."""
    half = 0.5 * angle
    s = math.sin(half)
    _multiply_body(q, math.cos(half), s * axis_x, s * axis_y, s * axis_z)


@register_jitable
def _asymmetric_flow(q, L, asym, duration):
    """Exact flow of ``T_asym = asym·L2²/2``: L turns by −asym·L2·t about body 2, the body by +asym·L2·t."""
    if asym == 0.0:
        return
    alpha = asym * L[1] * duration
    ca = math.cos(alpha)
    sa = math.sin(alpha)
    l0 = L[0]
    L[0] = ca * l0 - sa * L[2]
    L[2] = sa * l0 + ca * L[2]
    _rotate_quaternion_body(q, 0.0, 1.0, 0.0, alpha)


@register_jitable
def _turn_about_angular_momentum(q, L, angle_per_L):
    """``q ← q ⊗ rot(L/|L|, |L|·angle_per_L)``: the free flow of ``|L|²/(2 I1)`` (``angle_per_L = h/I1``, s/(kg·m²)).

    One division, by ``|L|``, scales the sine of the half angle onto ``L``'s components.
    """
    norm_L = math.sqrt(L[0] * L[0] + L[1] * L[1] + L[2] * L[2])
    if norm_L > 0.0:
        half = 0.5 * norm_L * angle_per_L
        s_per_L = math.sin(half) / norm_L
        _multiply_body(q, math.cos(half), s_per_L * L[0], s_per_L * L[1], s_per_L * L[2])


#: The one function inlined in numba's own IR (``inline="always"``): its ``asymmetric`` flag then is a constant at
#: each call. The small flows above and :func:`_composed_step` are left to LLVM's inliner: inlining them all in the
#: IR as well made the kernel's first compile 36 s of CPU instead of 12 s, for runs within 2 % of the same speed
#: and bit-identical frames (heavy top, orders 4 and 8, axisymmetric and not; measured 2026-11-28).
@register_jitable(inline="always")
def _strang_step(q, L, h, inv_I1, inv_I3, asym, torque, p, tau, asymmetric, spin_cache, stage):
    """One symmetric step: kick(h/2) asym(h/2) axi(h) asym(h/2) kick(h/2).

    ``tau`` (3,) holds the body torque (N·m) at the entry attitude and is left holding the torque at
    the exit attitude, so consecutive Strang steps share one torque evaluation. ``asymmetric`` is a
    constant at each (inlined) call, so an axisymmetric body's loop carries no asymmetric branch.
    ``spin_cache[stage]`` is ``(L3, cos γ/2, sin γ/2)`` of this stage's last spin rotation (NaN: none yet).
    """
    half = 0.5 * h
    for i in range(3):
        L[i] += half * tau[i]
    if asymmetric:
        _asymmetric_flow(q, L, asym, half)
    # Exact axisymmetric free flow over h: the body turns about L, then L and the body turn about body 3.
    _turn_about_angular_momentum(q, L, inv_I1 * h)
    # One sine and cosine of γ/2 serve both the quaternion (half angle) and L (double-angle formulas);
    # γ = L3 (1/I3 − 1/I1) h depends on L3 alone, so an unchanged L3 reuses this stage's last pair.
    if L[2] == spin_cache[stage, 0]:
        c = spin_cache[stage, 1]
        s = spin_cache[stage, 2]
    else:
        gamma = L[2] * (inv_I3 - inv_I1) * h
        c = math.cos(0.5 * gamma)
        s = math.sin(0.5 * gamma)
        spin_cache[stage, 0] = L[2]
        spin_cache[stage, 1] = c
        spin_cache[stage, 2] = s
    w, x, y, z = q[0], q[1], q[2], q[3]
    q[0] = w * c - z * s
    q[1] = x * c + y * s
    q[2] = y * c - x * s
    q[3] = z * c + w * s
    cg = 1.0 - 2.0 * s * s
    sg = 2.0 * s * c
    l0 = L[0]
    L[0] = cg * l0 + sg * L[1]
    L[1] = -sg * l0 + cg * L[1]
    if asymmetric:
        _asymmetric_flow(q, L, asym, half)
    torque(q, p, tau)
    for i in range(3):
        L[i] += half * tau[i]


@register_jitable
def _composed_step(q, L, h, weights, inv_I1, inv_I3, asym, torque, p, tau, asymmetric, spin_cache):
    """One step ``h`` of the composition: one Strang step per weight (``tau`` holds the torque at the start)."""
    for w in range(weights.shape[0]):
        _strang_step(q, L, weights[w] * h, inv_I1, inv_I3, asym, torque, p, tau, asymmetric, spin_cache, w)


def _splitting_frames(torque, t0, y, h, steps_per_frame, n_frames, p, weights, y_frames, work, spin_cache):
    """Advance the rigid-body state ``y`` (in place) ``n_frames`` frames.

    Each frame is ``steps_per_frame`` composed steps of ``h`` s with the Strang
    sub-step ``weights``; the state after frame ``i`` goes to ``y_frames[i]``.
    ``work`` (10,) is scratch for ``q``, ``L`` (kg·m²/s, body frame) and the
    torque (N·m, body frame); ``spin_cache`` (len(weights), 3) scratch for the
    spin rotations' sines and cosines (see :func:`_strang_step`).
    Returns the number of frames completed (fewer: the state became non-finite).
    The torque is evaluated once here and then once per Strang stage: the torque
    left by a step's last stage serves the next step's first kick (the
    renormalisation between frames moves ``q`` by round-off only). On a
    non-finite state ``y`` is left at the last finite frame.
    """
    I1 = p[0]
    I2 = p[1]
    I3 = p[2]
    inv_I1 = 1.0 / I1
    inv_I3 = 1.0 / I3
    asym = 1.0 / I2 - 1.0 / I1
    q = work[0:4]
    L = work[4:7]
    tau = work[7:10]
    for stage in range(spin_cache.shape[0]):
        spin_cache[stage, 0] = np.nan
    for i in range(4):
        q[i] = y[i]
    L[0] = I1 * y[4]
    L[1] = I2 * y[5]
    L[2] = I3 * y[6]
    torque(q, p, tau)
    for frame in range(n_frames):
        for _ in range(steps_per_frame):
            if asym == 0.0:
                _composed_step(q, L, h, weights, inv_I1, inv_I3, asym, torque, p, tau, False, spin_cache)
            else:
                _composed_step(q, L, h, weights, inv_I1, inv_I3, asym, torque, p, tau, True, spin_cache)
        # Every sub-flow is an exact rotation, so |q| leaves 1 by round-off only: once a frame is enough
        # (a square root and a division less on each step's chain of dependent operations).
        norm_q = math.sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3])
        if not (math.isfinite(norm_q) and math.isfinite(L[0] + L[1] + L[2])):
            if frame > 0:
                for i in range(7):
                    y[i] = y_frames[frame - 1, i]
            return frame
        inv_norm_q = 1.0 / norm_q
        for i in range(4):
            q[i] *= inv_norm_q
            y_frames[frame, i] = q[i]
        y_frames[frame, 4] = L[0] * inv_I1
        y_frames[frame, 5] = L[1] / I2
        y_frames[frame, 6] = L[2] * inv_I3
    if n_frames > 0:
        for i in range(7):
            y[i] = y_frames[n_frames - 1, i]
    return n_frames


#: :func:`_splitting_frames` compiled without reference counting (``_nrt=False``): every array it touches
#: is passed in, and the inlined stages otherwise pay an atomic increment and decrement per array argument
#: per call: a quarter of a run of the heavy top (measured with splitting2 and splitting4). Same options as
#: :func:`~app.physics.solvers.kernels.kernel` otherwise.
splitting_frames = Kernel(
    compiled=numba.njit(  # type: ignore[call-overload]  # numba's stub omits the _nrt option
        types.int64(
            TORQUE_TYPE,
            types.float64,
            VECTOR,
            types.float64,
            types.int64,
            types.int64,
            VECTOR,
            VECTOR,
            MATRIX,
            VECTOR,
            MATRIX,
        ),
        cache=True,
        nogil=True,
        error_model="numpy",
        _nrt=False,
    )(_splitting_frames),
    python=_splitting_frames,
)


class RigidBodySplitting(FixedStepIntegrator):
    """Symmetric splitting with the exact axisymmetric free flow (order 2, 4, 6 or 8)."""

    def __init__(self, *, order: int, steps_per_frame: int) -> None:
        super().__init__(steps_per_frame=steps_per_frame)
        if order not in SPLITTING_SPECS:
            raise ValueError(f"splitting order must be one of {sorted(SPLITTING_SPECS)} (got {order!r})")
        self.spec = SPLITTING_SPECS[order]
        self.weights = COMPOSITIONS[order]

    def _run_frames(self, system, t0_s, y, frame_dt_s, n_frames, y_frames, *, backend="numba"):
        h = frame_dt_s / self.steps_per_frame
        done = splitting_frames.get(backend)(
            system.torque.get(backend),
            float(t0_s),
            y,
            h,
            self.steps_per_frame,
            int(n_frames),
            system.parameters,
            self.weights,
            y_frames,
            np.empty(10),
            np.empty((self.weights.shape[0], 3)),
        )
        # The torque at the start of the run comes on top of one per Strang stage.
        return self.outcome(done, n_frames, evals_per_run=1)


def _splitting_spec(order: int, *, short_label: str, description: str, step_ratio: float) -> MethodSpec:
    """The spec of the order-``order`` composition (one torque evaluation per Strang sub-step, one more per run)."""
    substeps = len(COMPOSITIONS[order])
    return MethodSpec(
        name=f"splitting{order}",
        label=f"Splitting, order {order} (exact free flow)",
        short_label=short_label,
        description=description,
        order=order,
        evals_per_step=substeps,
        substeps_per_step=substeps,
        adaptive=False,
        geometric=True,
        step_ratio=step_ratio,
        # The quaternion is renormalised inside the kernel; the model's own hook is not needed.
        supports=Supports(projection=True),
        needs_torque=True,
        factory=lambda *, steps_per_frame: RigidBodySplitting(order=order, steps_per_frame=steps_per_frame),
    )


#: The splittings integrate the fastest rotation exactly, so their step limit comes from how
#: well the kicks sample the torque (calibrated on the heavy top to keep invariant drift below
#: 1e-6 over 60 s; see tests/physics/solvers/test_integrators.py). Orders 6 and 8 at h·ω_max = 1: drift at
#: most 8e-10 over 60 s on the default, fast (150 and 1000 rad/s) and slow heavy tops (measured).
SPLITTING_SPECS = {
    8: _splitting_spec(
        8,
        short_label="Splitting 8, Kahan–Li",
        step_ratio=1.0,
        description="Splitting, order 8 (Kahan–Li, 17 Strang stages): the cheapest at tight tolerances (geometric)",
    ),
    6: _splitting_spec(
        6,
        short_label="Splitting 6, Kahan–Li",
        step_ratio=1.0,
        description="Splitting, order 6 (Kahan–Li, 9 Strang stages): exact free flow + gravity kicks (geometric)",
    ),
    4: _splitting_spec(
        4,
        short_label="Splitting 4, exact free flow",
        step_ratio=0.25,
        description="Splitting, order 4: exact free flow + gravity kicks (geometric, bounded energy error)",
    ),
    2: _splitting_spec(
        2,
        short_label="Splitting 2, Strang",
        step_ratio=0.02,
        description="Splitting, order 2 (Strang): cheap, geometric, less accurate",
    ),
}
