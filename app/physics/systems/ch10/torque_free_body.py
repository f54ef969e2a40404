"""The torque-free body of arbitrary inertia, and Poinsot's construction of its motion.

Parameters (API contract names): ``I1``, ``I2``, ``I3`` (kg·m², principal moments about
the centre of mass, body axes 1-2-3) and ``omega0_rad_s`` (angular velocity at t = 0,
rad/s, body components ``[ω1, ω2, ω3]``). Series ``omega1``, ``omega2``, ``omega3``
(rad/s, body frame); invariants ``energy`` (J) and ``angular_momentum`` (|L|, kg·m²/s),
evaluated along the solution so their constancy is a check, not an assumption.

The motion is the Jacobi-elliptic closed form of :mod:`.free_body_elliptic`. The
attitude at t = 0 is chosen so that the (constant) angular momentum points along
world −Z: the invariable plane is then horizontal, below the centre of mass, and the
energy ellipsoid rolls on it like a ball on a table.

Poinsot's construction lives in ω-space (rad/s), centred on the fixed centre of mass:

* the energy ellipsoid ``ωᵀ I ω = 2T`` is fixed in the body, semi-axes ``√(2T/Ii)``;
* the invariable plane ``ω · L̂ = 2T/|L|`` is fixed in space (``L̂`` = −Z here);
* ω's tip lies on both; the ellipsoid's normal there, ``∇(ωᵀIω)/2 = Iω = L``, is the
  plane's normal, so the two are tangent; and the body point at ω's tip moves with
  ``ω × ω = 0``: the ellipsoid rolls without slipping;
* ω's tip traces the *polhode* on the ellipsoid (a closed curve in the body) and the
  *herpolhode* on the plane (fixed in space, in general never closing).

A *flip* is a reversal of the intermediate axis relative to L (ω along that axis
changes sign). It is reported only when that axis swings from within 45° of L to
within 45° of −L (``I_mid · max|ω_mid| > |L|/√2``), the tennis-racket tumble; a small
wobble about the major or minor axis also makes ω_mid change sign but turns nothing over.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.bodies.inertia import check_principal_inertia
from app.physics.bodies.rigid_body import PivotedBody
from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution, Event
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.math.rotations import quaternion_conjugate, quaternion_multiply, rotate_vector
from app.physics.solvers import LiveRun, make_integrator
from app.physics.systems.ch10.free_body_elliptic import FreeBodyElliptic, free_body_elliptic

INERTIA_NAMES = ("I1", "I2", "I3")
#: Below this |ω0| (rad/s) the energy underflows and the invariable plane is undefined.
SMALLEST_RATE_RAD_S = 1e-6
#: A flip needs the intermediate axis to come within this angle of ±L.
FLIP_CONE_RAD = math.pi / 4.0


def _check(values: Mapping[str, Any]) -> None:
    first, second, third = (float(values[name]) for name in INERTIA_NAMES)
    inertia = (first, second, third)
    try:
        check_principal_inertia(inertia, about="the centre of mass")
    except ValueError as exc:
        raise ParameterError(INERTIA_NAMES[int(np.argmax(inertia))], str(exc)) from None
    if float(np.linalg.norm(values["omega0_rad_s"])) < SMALLEST_RATE_RAD_S:
        raise ParameterError(
            "omega0_rad_s",
            f"must not be zero (|ω0| ≥ {SMALLEST_RATE_RAD_S:g} rad/s): a body at rest does not move, and Poinsot's "
            "invariable plane, 2T/|L| from the centre, is undefined when T and L vanish",
        )


#: A 1 kg hardback book, 24 cm × 17 cm × 4 cm: axis 1 along its length, axis 3 through its covers.
BOOK_INERTIA_KG_M2 = {"I1": 0.0025, "I2": 0.0049, "I3": 0.0072}

PARAMETERS = ParameterSet(
    (
        Parameter(
            "I1",
            "kg·m²",
            BOOK_INERTIA_KG_M2["I1"],
            1e-5,
            100.0,
            "Principal moment of inertia about body axis 1, through the centre of mass",
            "I₁",
            scale="log",
        ),
        Parameter(
            "I2",
            "kg·m²",
            BOOK_INERTIA_KG_M2["I2"],
            1e-5,
            100.0,
            "Principal moment of inertia about body axis 2, through the centre of mass",
            "I₂",
            scale="log",
        ),
        Parameter(
            "I3",
            "kg·m²",
            BOOK_INERTIA_KG_M2["I3"],
            1e-5,
            100.0,
            "Principal moment of inertia about body axis 3, through the centre of mass",
            "I₃",
            scale="log",
        ),
        Parameter(
            "omega0_rad_s",
            "rad/s",
            (1.2, 2.6, 2.4),
            -20.0,
            20.0,
            "Angular velocity at t = 0, body components [ω1, ω2, ω3]",
            "ω₀",
            kind="vector",
            length=3,
        ),
    ),
    check=_check,
)


# ---- the motion ------------------------------------------------------------------------------


def inertia_of(params: Mapping[str, Any]) -> np.ndarray:
    """Principal moments ``[I1, I2, I3]`` (kg·m²) from validated parameters."""
    return np.array([params[name] for name in INERTIA_NAMES], dtype=float)


def attitude_with_momentum_down(momentum_body: np.ndarray) -> np.ndarray:
    """``q_world_body`` (wxyz) turning the body vector ``momentum_body`` onto world −Z (shortest turn)."""
    a = np.asarray(momentum_body, dtype=float) / np.linalg.norm(momentum_body)
    down = np.array([0.0, 0.0, -1.0])
    c = float(a @ down)
    if c < -1.0 + 1e-12:  # L along +Z: half a turn about X
        return np.array([0.0, 1.0, 0.0, 0.0])
    q = np.concatenate([[1.0 + c], np.cross(a, down)])
    return q / np.linalg.norm(q)


def motion(params: Mapping[str, Any]) -> FreeBodyElliptic:
    """The closed-form motion for validated parameters, with L along world −Z."""
    inertia = inertia_of(params)
    omega0 = np.asarray(params["omega0_rad_s"], dtype=float)
    return free_body_elliptic(inertia=inertia, omega0_body=omega0, q0=attitude_with_momentum_down(inertia * omega0))


def omega_amplitudes_rad_s(body: FreeBodyElliptic) -> np.ndarray:
    """Largest |ωi| over the motion (rad/s), per body axis, from the two invariants.

    On the working axes (other o, middle m, circled c; ``D = L²/2T``) each component
    peaks where the other two allow:  ``ωc² ≤ 2T (D − Io)/(Ic (Ic − Io))``,
    ``ωo² ≤ 2T (Ic − D)/(Io (Ic − Io))``, ``ωm² ≤ 2T (Ic − D)/(Im (Ic − Im))``. On the
    separatrix any choice of circled extreme gives the same numbers.
    """
    if body.kind == "steady":
        return np.abs(body.omega0_body)
    inertia = body.inertia
    two_T = 2.0 * body.energy_J
    D = body.angular_momentum_norm**2 / two_T
    order = np.argsort(inertia, kind="stable")
    i_min, i_max = int(order[0]), int(order[2])
    c = body.circled_axis if body.circled_axis is not None else i_max
    o = i_min if c == i_max else i_max
    m = body.intermediate_axis
    Ic, Io, Im = inertia[c], inertia[o], inertia[m]
    out = np.empty(3)
    out[c] = math.sqrt(max(two_T * (D - Io) / (Ic * (Ic - Io)), 0.0))
    out[o] = math.sqrt(max(two_T * (Ic - D) / (Io * (Ic - Io)), 0.0))
    out[m] = math.sqrt(max(two_T * (Ic - D) / (Im * (Ic - Im)), 0.0))
    return out


def flips_apply(body: FreeBodyElliptic) -> bool:
    """True when the intermediate axis turns over (see the module docstring for the 45° rule)."""
    lo, mid, hi = np.sort(body.inertia)
    if body.kind == "steady" or not lo < mid < hi:  # the theorem needs three different moments
        return False
    m = body.intermediate_axis
    swing = body.inertia[m] * omega_amplitudes_rad_s(body)[m] / body.angular_momentum_norm
    return swing > math.cos(FLIP_CONE_RAD)


def flip_times_s(body: FreeBodyElliptic, t_end_s: float) -> np.ndarray:
    """Times in (0, t_end] (s) of the flips (empty when the motion has none)."""
    return body.flip_times(t_end_s) if flips_apply(body) else np.empty(0)


def next_flip_s(body: FreeBodyElliptic, t_s: float) -> float | None:
    """Time of the first flip after ``t_s`` (s), or None when there is none to come."""
    if not flips_apply(body):
        return None
    horizon = t_s + (body.period_s if math.isfinite(body.period_s) else 1e6)
    later = body.flip_times(horizon)
    later = later[later > t_s]
    return float(later[0]) if later.size else None


# ---- Poinsot's construction ------------------------------------------------------------------


@dataclass(frozen=True)
class PoinsotFrames:
    """The construction at times ``t_s`` (N,): attitude, and ω in body and world components.

    ``q_world_body`` (N, 4) wxyz; ``omega_body`` (N, 3) rad/s — a polhode point;
    ``omega_world`` (N, 3) rad/s — the contact point with the invariable plane, a herpolhode point.
    """

    t_s: np.ndarray
    q_world_body: np.ndarray
    omega_body: np.ndarray
    omega_world: np.ndarray


def energy_ellipsoid_semi_axes_rad_s(body: FreeBodyElliptic) -> np.ndarray:
    """Semi-axes ``√(2T/Ii)`` (rad/s) of ``ωᵀ I ω = 2T`` along body axes 1, 2, 3."""
    return np.sqrt(2.0 * body.energy_J / body.inertia)


def invariable_plane(body: FreeBodyElliptic) -> tuple[np.ndarray, float]:
    """``(n, d)``: unit normal ``L̂`` (world) and distance ``2T/|L|`` (rad/s) of the plane ``ω · n = d``."""
    L = body.angular_momentum_norm
    return body.angular_momentum_world / L, 2.0 * body.energy_J / L


def herpolhode_radii_rad_s(body: FreeBodyElliptic) -> tuple[float, float]:
    """Smallest and largest distance (rad/s) of the herpolhode from the foot of L on the plane.

    That distance is ``√(|ω|² − d²)``. With T and |L| fixed, ωo² and ωc² are linear in ωm²
    (solve ``Σ Ii ωi² = 2T``, ``Σ Ii² ωi² = L²`` for them), so |ω|² is too, and its extremes
    are at ωm = 0 and at ωm = ±(its amplitude).
    """
    if body.kind == "steady":
        return 0.0, 0.0
    inertia = body.inertia
    two_T, L2 = 2.0 * body.energy_J, body.angular_momentum_norm**2
    m = body.intermediate_axis
    o, c = (i for i in range(3) if i != m)
    Io, Ic, Im = inertia[o], inertia[c], inertia[m]
    det = Io * Ic * (Ic - Io)
    d2 = two_T * two_T / L2

    def radius(y: float) -> float:
        x = ((two_T - Im * y) * Ic * Ic - Ic * (L2 - Im * Im * y)) / det
        z = (Io * (L2 - Im * Im * y) - Io * Io * (two_T - Im * y)) / det
        return math.sqrt(max(x + y + z - d2, 0.0))

    ends = (radius(0.0), radius(omega_amplitudes_rad_s(body)[m] ** 2))
    return min(ends), max(ends)


def poinsot_frames(body: FreeBodyElliptic, t_s: np.ndarray) -> PoinsotFrames:
    """Evaluate the construction at times ``t_s`` (s, 1-D)."""
    t_s = np.asarray(t_s, dtype=float)
    q = body.quaternion(t_s)
    omega_body = body.omega_body(t_s)
    return PoinsotFrames(t_s, q, omega_body, rotate_vector(q, omega_body))


def polhode_family(body: FreeBodyElliptic, *, loops_per_axis: int = 4, samples: int = 241) -> list[np.ndarray]:
    """Polhodes of this body at this energy (body frame, rad/s), each a closed (samples, 3) curve.

    Around each extreme axis c (other extreme o, middle m) a polhode with ``D = L²/2T``
    between Im and Ic is, projected on the o-m plane, the ellipse
    ``Io (Ic − Io) ωo² + Im (Ic − Im) ωm² = 2T (Ic − D)``, with ωc from the energy; each
    loop and its mirror image (ωc < 0) are returned. The separatrices (D = Im) are the two
    planes ``ωc/ωo = ±√(Io (Im − Io)/(Ic (Ic − Im)))`` cut with the ellipsoid. Families
    that do not exist (equal moments) are skipped.
    """
    inertia = body.inertia
    two_T = 2.0 * body.energy_J
    lo, mid, hi = (int(i) for i in np.argsort(inertia, kind="stable"))
    theta = np.linspace(0.0, 2.0 * math.pi, samples)
    curves: list[np.ndarray] = []
    for c, o in ((hi, lo), (lo, hi)):
        Ic, Io, Im = inertia[c], inertia[o], inertia[mid]
        if Ic == Im or Ic == Io:
            continue
        for f in np.linspace(0.0, 1.0, loops_per_axis + 2)[1:-1] ** 0.8:
            D = Im + (Ic - Im) * f
            a = math.sqrt(two_T * (Ic - D) / (Io * (Ic - Io)))
            b = math.sqrt(two_T * (Ic - D) / (Im * (Ic - Im)))
            omega = np.zeros((samples, 3))
            omega[:, o] = a * np.cos(theta)
            omega[:, mid] = b * np.sin(theta)
            omega[:, c] = np.sqrt(np.maximum(two_T - Io * omega[:, o] ** 2 - Im * omega[:, mid] ** 2, 0.0) / Ic)
            curves.append(omega)
            curves.append(omega * np.array([1.0 if k != c else -1.0 for k in range(3)]))
    if inertia[lo] < inertia[mid] < inertia[hi]:
        Ic, Io, Im = inertia[hi], inertia[lo], inertia[mid]
        slope = math.sqrt(Io * (Im - Io) / (Ic * (Ic - Im)))
        for sign in (1.0, -1.0):
            direction = np.zeros(3)
            direction[lo], direction[hi] = 1.0, sign * slope
            u = direction / math.sqrt(float(inertia @ direction**2) / two_T)  # on the ellipsoid
            pole = np.zeros(3)
            pole[mid] = math.sqrt(two_T / Im)
            curves.append(np.outer(np.cos(theta), u) + np.outer(np.sin(theta), pole))
    return curves


def uniform_box_sides(inertia: np.ndarray, *, mass_kg: float = 1.0) -> np.ndarray:
    """Sides (m) along body axes 1, 2, 3 of the uniform box with these principal moments.

    ``Ii = m (aj² + ak²)/12`` inverts to ``ai² = 6 (Ij + Ik − Ii)/m``: the triangle
    inequality is exactly the condition that every side is real (a flat plate has one
    side zero).
    """
    inertia = np.asarray(inertia, dtype=float)
    squares = 6.0 * (inertia.sum() - 2.0 * inertia) / mass_kg
    return np.sqrt(np.maximum(squares, 0.0))


# ---- the closed-form model -------------------------------------------------------------------


class TorqueFreeBody(ClosedFormModel):
    """Body-frame ω(t) of a torque-free body in Jacobi elliptic functions, with its flips as events."""

    parameters = PARAMETERS
    series_units = {"omega1": "rad/s", "omega2": "rad/s", "omega3": "rad/s"}
    invariant_units = {"energy": "J", "angular_momentum": "kg·m²/s"}
    description = "Jacobi elliptic functions sn, cn, dn (exact in the complementary parameter near the separatrix)"

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        body = motion(params)
        omega = body.omega_body(np.asarray(t_s, dtype=float))
        momentum = body.inertia * omega
        axis = body.intermediate_axis + 1
        events = [
            Event(float(t), "flip", f"the intermediate axis {axis} turns over: ω{axis} changes sign")
            for t in flip_times_s(body, float(t_s[-1]))
        ]
        return ClosedFormSolution(
            series={f"omega{i + 1}": omega[:, i] for i in range(3)},
            invariants={
                "energy": 0.5 * np.sum(momentum * omega, axis=1),
                "angular_momentum": np.linalg.norm(momentum, axis=1),
            },
            events=events,
        )


# ---- the same body integrated numerically ("ghost") -------------------------------------------

#: The ghost's RK4 step: h · max|ω| ≤ this. RK4's classical rule is 0.1; 0.02 keeps the
#: tennis-racket preset's attitude error tiny (the tests bound it) while the physics of a frame
#: stays a small share of the budget (docs/bench/live-frame-costs.svg): steps here are nearly free.
GHOST_STEP_RATIO = 0.02


def attitude_difference_rad(q_a: np.ndarray, q_b: np.ndarray) -> np.ndarray:
    """Rotation angle (rad) taking attitude ``q_a`` to ``q_b`` (wxyz, (..., 4)); sign-insensitive, exact near 0."""
    d = quaternion_multiply(quaternion_conjugate(q_a), q_b)
    d = d / np.linalg.norm(d, axis=-1, keepdims=True)
    return 2.0 * np.arctan2(np.linalg.norm(d[..., 1:], axis=-1), np.abs(d[..., 0]))


class IntegratedTwin:
    """The same free body integrated by the solver core (RK4 on quaternion and ω), frame by frame.

    Starts from the closed form's state at t = 0 (``body.q0``, ``body.omega0_body``) and
    is advanced with :class:`~app.physics.solvers.LiveRun`, exactly as a live
    integrated scene would be, so comparing it with the closed form measures the
    integrator, not a different model.
    """

    def __init__(self, body: FreeBodyElliptic, *, frame_dt_s: float, step_ratio: float = GHOST_STEP_RATIO) -> None:
        self.rigid_body = PivotedBody((float(body.inertia[0]), float(body.inertia[1]), float(body.inertia[2])))
        rate = float(np.linalg.norm(omega_amplitudes_rad_s(body)))
        steps = max(1, min(4096, math.ceil(rate * frame_dt_s / step_ratio - 1e-9)))
        integrator = make_integrator("rk4", steps_per_frame=steps)
        self.frame_dt_s = frame_dt_s
        self.description = integrator.describe(frame_dt_s)
        self.run = LiveRun(self.rigid_body.system(), integrator, np.concatenate([body.q0, body.omega0_body]))

    def advance(self) -> bool:
        """One frame forward; False (and ``run.message`` says why) if the integration failed."""
        return self.run.advance(self.frame_dt_s)

    @property
    def t_s(self) -> float:
        return self.run.t_s

    @property
    def q_world_body(self) -> np.ndarray:
        q = self.run.y[0:4]
        return q / np.linalg.norm(q)

    @property
    def omega_body(self) -> np.ndarray:
        return self.run.y[4:7].copy()
