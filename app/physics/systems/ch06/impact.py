"""The impulse law of a rough planar impact: Stronge's energetic restitution with Coulomb friction.

A contact is described by its 2×2 inverse effective-mass matrix ``W`` (1/kg, symmetric
positive definite) in the contact frame ``[normal, tangent]``: an impulse ``P = [Pn, Pt]`` (N·s)
on the body the normal points into changes the relative contact velocity (that body's
contact point minus the other's, m/s) by ``Δv = W P``.

The impact is followed along the normal impulse ``p`` as its clock. While the contact slides,
friction takes ``dPt/dp = −μ·sign(vt)``; when sliding stops it sticks if ``|W_tn| ≤ μ W_tt``
(then ``dPt/dp = −W_tn/W_tt`` keeps ``vt = 0``), otherwise it slides back the other way.
Compression ends when ``vn = 0``; restitution ends when the work of the normal impulse in
restitution equals ``e²`` times (minus) its work in compression. Along each phase the velocity
is linear in ``p``, so every phase end is found in closed form. The law never creates energy:
the normal work is −(1 − e²)·(compression work magnitude) and friction work is never positive.
Newton's kinematic law (``vn_after = −e·vn``) can create energy once slip stops or reverses;
this one cannot.

The law itself is :func:`impact_core`, on plain arrays and numbers: compiled kernels
(a reset map at a floor) call it directly, and :data:`impact_kernel` holds it
compiled for calls from Python beside its Python twin. :func:`resolve_impact` is
the checked entry point: it validates, calls the compiled core and names the result.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import types
from numba.extending import register_jitable

from app.physics.solvers.kernels import MATRIX, VECTOR, kernel

SLIP_STATES = ("slid throughout", "stuck", "reversed")

_MAX_PHASES = 8  # slip → stick/reverse, each split once at the end of compression: at most 4 are ever used

#: Slots of :func:`impact_core`'s output vector (length :data:`IMPACT_OUT_SIZE`).
(
    OUT_NORMAL_IMPULSE,
    OUT_TANGENTIAL_IMPULSE,
    OUT_NORMAL_VELOCITY_AFTER,
    OUT_TANGENTIAL_VELOCITY_AFTER,
    OUT_ENERGY_LOSS,
    OUT_SLIP_CODE,
) = range(6)
IMPACT_OUT_SIZE = 6
#: ``impact_core(W, v0, restitution, friction_coefficient, out)``.
IMPACT_CORE_SIGNATURE = types.void(MATRIX, VECTOR, types.float64, types.float64, VECTOR)

# What ends a phase of the impact (on a tie, the end of compression or of the impact comes first).
_COMPRESSION_ENDS, _DONE, _SLIP_STOPS = 0, 1, 2


@dataclass(frozen=True)
class ImpactResult:
    """Outcome of one impact, in the contact frame ``[normal, tangent]``."""

    impulse_N_s: np.ndarray  # (2,) [normal, tangential] impulse on the body the normal points into
    contact_velocity_after_m_s: np.ndarray  # (2,) [normal, tangential] relative velocity after
    energy_loss_J: float  # ≥ 0
    slip_state: str  # "slid throughout" | "stuck" | "reversed"


def _check_inputs(W: np.ndarray, v: np.ndarray, restitution: float, friction_coefficient: float) -> None:
    if W.shape != (2, 2) or not np.all(np.isfinite(W)):
        raise ValueError("inverse_effective_mass: must be a finite 2×2 matrix (1/kg)")
    if not np.allclose(W, W.T, rtol=1e-12, atol=0.0) or W[0, 0] <= 0.0 or np.linalg.det(W) <= 0.0:
        raise ValueError("inverse_effective_mass: must be symmetric positive definite (1/kg)")
    if v.shape != (2,) or not np.all(np.isfinite(v)):
        raise ValueError("contact_velocity_m_s: must be two finite numbers [vn, vt] (m/s)")
    if not (math.isfinite(restitution) and 0.0 <= restitution <= 1.0):
        raise ValueError(f"restitution: must lie between 0 and 1 (got {restitution!r})")
    if not (math.isfinite(friction_coefficient) and friction_coefficient >= 0.0):
        raise ValueError(f"friction_coefficient: must be a finite number ≥ 0 (got {friction_coefficient!r})")
    if not v[0] < 0.0:
        raise ValueError(
            f"contact_velocity_m_s: the bodies are not approaching at the contact (vn = {v[0]:g} m/s ≥ 0), so "
            "there is no impact"
        )


@register_jitable
def _first_root_of_work(vn, rate, work):
    """Smallest Δp ≥ 0 with ``vn Δp + ½ rate Δp² = work`` (vn ≥ 0, rate > 0, work ≥ 0), cancellation-free.

    At vn = 0 (restitution starts from rest along the normal) the root is √(2 work / rate), taken directly: the
    general form's ``2 rate work`` underflows to 0 for a work of a few 1e-324 (a restitution of 1e-161 squared) and
    would divide by zero."""
    if work <= 0.0:
        return 0.0
    if vn == 0.0:
        return math.sqrt(2.0 * work / rate)
    return 2.0 * work / (vn + math.sqrt(vn * vn + 2.0 * rate * work))


@register_jitable
def impact_core(W, v0, restitution, friction_coefficient, out):
    """The impulse law on raw values, unchecked (:func:`resolve_impact` checks; a kernel must pass valid input).

    ``W``: (2, 2) inverse effective mass, 1/kg, symmetric positive definite, frame [normal, tangent].
    ``v0``: (2,) relative contact velocity [vn, vt] before, m/s, with vn < 0.
    ``restitution``: energetic e in [0, 1]; ``friction_coefficient``: Coulomb μ ≥ 0.
    ``out``: (IMPACT_OUT_SIZE,) filled with [Pn, Pt] (N·s), [vn, vt] after (m/s), the energy
    loss (J, ≥ 0) and the slip code (index into :data:`SLIP_STATES`); all NaN if the phase
    sequence did not end (never seen: the count of phases is bounded).
    """
    mu = friction_coefficient
    stick_ratio = -W[1, 0] / W[1, 1]  # dPt/dp that holds vt = 0
    can_stick = abs(W[1, 0]) <= mu * W[1, 1]

    # The law is positively homogeneous in the velocity (impulses scale with it, works with its square), so it is
    # followed for the approach scaled to unit size: an approach of 1e-163 m/s would otherwise underflow its works.
    speed = max(abs(v0[0]), abs(v0[1]))
    vn, vt = v0[0] / speed, v0[1] / speed
    p_n = 0.0
    p_t = 0.0
    compression_work = 0.0  # ∫ vn dp while vn < 0 (≤ 0), J
    restitution_work = 0.0  # ∫ vn dp while vn > 0 (≥ 0), J
    friction_loss = 0.0  # −∫ vt dPt, ≥ 0 phase by phase (zero while stuck), J
    compressing = True
    slip_sign = float(np.sign(vt))
    stuck = slip_sign == 0.0 and can_stick  # no slip to begin with, and friction can hold it
    reversed_ = False
    finished = False
    for _ in range(_MAX_PHASES):
        if slip_sign == 0.0 and not can_stick:
            slip_sign = float(np.sign(W[1, 0]))  # stick impossible: slides the way W_tn pushes
        slope_t = stick_ratio if slip_sign == 0.0 else -mu * slip_sign
        rate_n = W[0, 0] + W[0, 1] * slope_t
        rate_t = 0.0 if slip_sign == 0.0 else W[1, 0] + W[1, 1] * slope_t
        # The phase's end, Δp: the first of these (W positive definite: one always comes).
        dp, event = math.inf, _COMPRESSION_ENDS
        if compressing and rate_n > 0.0:
            dp = -vn / rate_n
        if not compressing:
            dp, event = _first_root_of_work(vn, rate_n, -(restitution**2) * compression_work - restitution_work), _DONE
        if slip_sign != 0.0 and rate_t * slip_sign < 0.0 and -vt / rate_t < dp:
            dp, event = -vt / rate_t, _SLIP_STOPS
        work = vn * dp + 0.5 * rate_n * dp * dp
        if slip_sign != 0.0:
            friction_loss += mu * abs(vt * dp + 0.5 * rate_t * dp * dp)
        if compressing:
            compression_work += work
        else:
            restitution_work += work
        p_n += dp
        p_t += slope_t * dp
        vn += rate_n * dp
        vt += rate_t * dp
        if event == _DONE:
            finished = True
            break
        if event == _COMPRESSION_ENDS:
            vn, compressing = 0.0, False
        else:
            vt = 0.0
            slip_sign = 0.0 if can_stick else float(np.sign(W[1, 0]))
            stuck |= can_stick
            reversed_ |= not can_stick
    if not finished:  # pragma: no cover - the phase count is bounded above; reaching here is a bug
        out[:] = math.nan
        return
    p_n *= speed
    p_t *= speed
    out[OUT_NORMAL_IMPULSE] = p_n
    out[OUT_TANGENTIAL_IMPULSE] = p_t
    out[OUT_NORMAL_VELOCITY_AFTER] = v0[0] + (W[0, 0] * p_n + W[0, 1] * p_t)
    out[OUT_TANGENTIAL_VELOCITY_AFTER] = v0[1] + (W[1, 0] * p_n + W[1, 1] * p_t)
    # Summed from its non-negative parts; equals −½ Pᵀ(v_before + v_after) to rounding (tests check both).
    out[OUT_ENERGY_LOSS] = ((1.0 - restitution**2) * -compression_work + friction_loss) * speed * speed
    out[OUT_SLIP_CODE] = 2.0 if reversed_ else 1.0 if stuck else 0.0


#: :func:`impact_core` compiled for calls from Python, with its Python twin (the same source).
impact_kernel = kernel(IMPACT_CORE_SIGNATURE)(impact_core)


def resolve_impact(
    *,
    inverse_effective_mass: np.ndarray,
    contact_velocity_m_s: np.ndarray,
    restitution: float,
    friction_coefficient: float,
) -> ImpactResult:
    """Impulse of a rough planar impact under Stronge's energetic restitution.

    ``inverse_effective_mass``: (2, 2) W, 1/kg, contact frame [normal, tangent].
    ``contact_velocity_m_s``: (2,) relative contact velocity [vn, vt] before, m/s; vn < 0 approaches.
    ``restitution``: energetic coefficient e in [0, 1]; ``friction_coefficient``: Coulomb μ ≥ 0.
    Raises ValueError naming the argument for bad input, and "not approaching" when vn ≥ 0.
    """
    W = np.ascontiguousarray(inverse_effective_mass, dtype=float)
    v0 = np.ascontiguousarray(contact_velocity_m_s, dtype=float)
    _check_inputs(W, v0, restitution, friction_coefficient)
    out = np.empty(IMPACT_OUT_SIZE)
    impact_kernel.compiled(W, v0, float(restitution), float(friction_coefficient), out)
    if not np.all(np.isfinite(out)):  # pragma: no cover - see impact_core
        raise RuntimeError("resolve_impact: phase sequence did not end")
    return ImpactResult(
        impulse_N_s=out[OUT_NORMAL_IMPULSE : OUT_TANGENTIAL_IMPULSE + 1].copy(),
        contact_velocity_after_m_s=out[OUT_NORMAL_VELOCITY_AFTER : OUT_TANGENTIAL_VELOCITY_AFTER + 1].copy(),
        energy_loss_J=float(out[OUT_ENERGY_LOSS]),
        slip_state=SLIP_STATES[int(out[OUT_SLIP_CODE])],
    )
