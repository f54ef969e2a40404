"""The free gyroscope: a spinning rotor in two ideal gimbals on a turning vehicle.

Frames (all right-handed, +Z up at t = 0):

* ``N`` — inertial (the world frame of the scene);
* ``B`` — the vehicle (base). It coincides with ``N`` at t = 0 and turns at a
  constant angular velocity ``ω_B`` whose vehicle-frame components are the
  parameter ``vehicle_rate_rad_s``. A constant body-frame rate is a rotation
  about a fixed axis ``n̂ = ω_B/|ω_B|`` (the same in ``N`` and ``B``), so
  ``R_NB(t) = Rot(n̂, |ω_B| t)``.
* outer gimbal ``O`` — pivots on the vehicle about ``b_z``: ``R_BO = Rz(φ_o)``;
* inner gimbal ``I`` — pivots on the outer ring about ``o_x``: ``R_OI = Rx(φ_i)``;
* the rotor spins about the inner ring's ``i_y`` axis.

So the spin axis in vehicle components is

    s_B = Rz(φ_o) Rx(φ_i) ŷ = (−sin φ_o cos φ_i,  cos φ_o cos φ_i,  sin φ_i).

Ideal gimbals (massless, frictionless bearings) pass no torque to the rotor, so
its angular momentum, and with it the spin axis, keeps its inertial direction
``s_N``. The gimbal angles are then pure kinematics, a closed form in time:

    s_B(t) = R_NB(t)ᵀ s_N,   φ_i = asin s_B,z,   φ_o = atan2(−s_B,x, s_B,y),

and their rates follow from ``ṡ_B = s_B × ω_B`` (a vector fixed in ``N`` seen
from the turning vehicle). When the spin axis lines up with the outer gimbal
axis (φ_i = ±90°) the two rings lie in one plane — gimbal lock: φ_o is
undefined there and its rate needed to keep up grows like 1/cos φ_i.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution, Event
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.math.rotations import rotate_vector

#: Within this angle of the outer gimbal axis the rings are reported as (nearly) locked.
LOCK_WARNING_DEG = 5.0


def _check(values: Mapping[str, Any]) -> None:
    if values["spin_rad_s"] == 0.0:
        raise ParameterError(
            "spin_rad_s", "must be non-zero: a rotor that does not spin has no angular momentum to hold its direction"
        )


PARAMETERS = ParameterSet(
    (
        Parameter(
            "vehicle_rate_rad_s",
            "rad/s",
            [0.0, 0.0, 0.3],
            -2.0,
            2.0,
            "Constant angular velocity of the vehicle, components on its own roll (x), pitch (y) and yaw (z) axes",
            "ω_B",
            kind="vector",
            step=0.05,
        ),
        Parameter("spin_rad_s", "rad/s", 2000.0, -30000.0, 30000.0, "Rotor spin rate about its axis", "ω_s", step=10.0),
        Parameter(
            "rotor_inertia_kg_m2",
            "kg·m²",
            2e-3,
            1e-6,
            10.0,
            "Rotor moment of inertia about its spin axis",
            "I_a",
            scale="log",
        ),
        Parameter(
            "inner_gimbal0_deg",
            "deg",
            0.0,
            -89.0,
            89.0,
            "Inner gimbal angle at t = 0: elevation of the spin axis above the vehicle's x-y plane",
            "φ_i(0)",
            step=1.0,
        ),
        Parameter(
            "outer_gimbal0_deg",
            "deg",
            0.0,
            -180.0,
            180.0,
            "Outer gimbal angle at t = 0: turn of the outer ring about the vehicle's z axis",
            "φ_o(0)",
            step=1.0,
        ),
    ),
    check=_check,
)


def spin_axis_from_gimbals(outer_rad: np.ndarray | float, inner_rad: np.ndarray | float) -> np.ndarray:
    """Unit spin axis in vehicle components, ``Rz(φ_o) Rx(φ_i) ŷ`` (shape (..., 3))."""
    outer = np.asarray(outer_rad, dtype=float)
    inner = np.asarray(inner_rad, dtype=float)
    return np.stack([-np.sin(outer) * np.cos(inner), np.cos(outer) * np.cos(inner), np.sin(inner)], axis=-1)


def gimbal_angles(spin_axis_vehicle: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(φ_o, φ_i)`` in rad of unit spin axes in vehicle components (shape (..., 3)).

    ``φ_i`` ∈ [−π/2, π/2]; ``φ_o`` ∈ (−π, π], NaN where it is undefined (axis on the outer gimbal axis).
    """
    s = np.asarray(spin_axis_vehicle, dtype=float)
    inner = np.arcsin(np.clip(s[..., 2], -1.0, 1.0))
    horizontal = np.hypot(s[..., 0], s[..., 1])
    outer = np.where(horizontal > 1e-12, np.arctan2(-s[..., 0], s[..., 1]), np.nan)
    return outer, inner


def vehicle_rate(params: Mapping[str, Any]) -> np.ndarray:
    """``ω_B`` (rad/s), vehicle-frame components (equal to its inertial components: the axis is fixed)."""
    return np.asarray(params["vehicle_rate_rad_s"], dtype=float)


def spin_axis_inertial(params: Mapping[str, Any]) -> np.ndarray:
    """The spin axis ``s_N`` (unit, inertial components): where the gimbals point it at t = 0."""
    return spin_axis_from_gimbals(math.radians(params["outer_gimbal0_deg"]), math.radians(params["inner_gimbal0_deg"]))


def vehicle_attitude(params: Mapping[str, Any], t_s: np.ndarray) -> np.ndarray:
    """``q_world_vehicle`` (wxyz, shape (N, 4)) at times ``t_s`` (s): ``Rot(n̂, |ω_B| t)``."""
    omega = vehicle_rate(params)
    rate = float(np.linalg.norm(omega))
    t = np.atleast_1d(np.asarray(t_s, dtype=float))
    axis = omega / rate if rate > 0.0 else np.array([0.0, 0.0, 1.0])
    half = 0.5 * rate * t
    return np.column_stack([np.cos(half), np.sin(half)[:, None] * axis])


def _rotate(axis: np.ndarray, angle_rad: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Rodrigues: ``v`` rotated by ``angle_rad`` (N,) about unit ``axis``; shape (N, 3)."""
    c, s = np.cos(angle_rad)[:, None], np.sin(angle_rad)[:, None]
    return v * c + np.cross(axis, v) * s + axis * float(axis @ v) * (1.0 - c)


@dataclass(frozen=True)
class GimbalMotion:
    """Gimbal angles and rates at N instants (rad, rad/s); vectors (N, 3)."""

    t_s: np.ndarray
    outer_rad: np.ndarray
    inner_rad: np.ndarray
    outer_rate_rad_s: np.ndarray
    inner_rate_rad_s: np.ndarray
    #: The spin axis in vehicle components.
    spin_axis_vehicle: np.ndarray
    #: ``q_world_vehicle`` (wxyz).
    q_world_vehicle: np.ndarray

    @property
    def lock_angle_rad(self) -> np.ndarray:
        """Angle between the spin axis and the outer gimbal axis (±b_z): 0 at gimbal lock."""
        return 0.5 * np.pi - np.abs(self.inner_rad)


def gimbal_motion(params: Mapping[str, Any], t_s: np.ndarray | float) -> GimbalMotion:
    """The closed-form gimbal angles and rates at times ``t_s`` (s) for ideal gimbals."""
    t = np.atleast_1d(np.asarray(t_s, dtype=float))
    omega = vehicle_rate(params)
    rate = float(np.linalg.norm(omega))
    s_world = spin_axis_inertial(params)
    if rate > 0.0:
        # s_B = R_NBᵀ s_N: the inertial axis rotated backwards about n̂.
        s_vehicle = _rotate(omega / rate, -rate * t, s_world)
    else:
        s_vehicle = np.tile(s_world, (t.size, 1))
    outer, inner = gimbal_angles(s_vehicle)
    s_dot = np.cross(s_vehicle, omega)  # rate of s_B seen from the vehicle
    sx, sy = s_vehicle[:, 0], s_vehicle[:, 1]
    horizontal_sq = sx * sx + sy * sy
    with np.errstate(divide="ignore", invalid="ignore"):
        inner_rate = np.where(horizontal_sq > 1e-24, s_dot[:, 2] / np.sqrt(horizontal_sq), np.nan)
        outer_rate = np.where(horizontal_sq > 1e-24, (sx * s_dot[:, 1] - sy * s_dot[:, 0]) / horizontal_sq, np.nan)
    return GimbalMotion(
        t_s=t,
        outer_rad=outer,
        inner_rad=inner,
        outer_rate_rad_s=outer_rate,
        inner_rate_rad_s=inner_rate,
        spin_axis_vehicle=s_vehicle,
        q_world_vehicle=vehicle_attitude(params, t),
    )


def closest_approaches_to_lock(params: Mapping[str, Any], t_end_s: float) -> list[tuple[float, float]]:
    """``(t_s, angle_rad)`` of every closest approach of the spin axis to the outer gimbal axis in [0, t_end].

    Exact: with ``θ = |ω_B| t``, ``s_B,z(θ) = A + B cos θ + C sin θ`` (Rodrigues), whose
    extremes are at ``θ* = atan2(C, B)`` (largest) and ``θ* + π`` (smallest) plus whole turns.
    Empty when the vehicle does not turn or the distance to lock never changes.
    """
    omega = vehicle_rate(params)
    rate = float(np.linalg.norm(omega))
    if rate == 0.0:
        return []
    n = omega / rate
    s = spin_axis_inertial(params)
    z = np.array([0.0, 0.0, 1.0])
    # s_B,z = (R_NB ẑ)·s_N with R_NB = Rot(n̂, θ).
    a = n[2] * float(n @ s)
    b = s[2] - a
    c = float(np.cross(n, z) @ s)
    amplitude = math.hypot(b, c)
    if amplitude < 1e-12:
        return []
    theta_star = math.atan2(c, b)
    out: list[tuple[float, float]] = []
    theta_end = rate * t_end_s
    for offset, extreme in ((0.0, a + amplitude), (math.pi, a - amplitude)):
        angle = 0.5 * math.pi - math.asin(min(1.0, abs(extreme)))
        first = (theta_star + offset) % (2.0 * math.pi)
        out.extend((float(theta / rate), angle) for theta in np.arange(first, theta_end + 1e-12, 2.0 * math.pi))
    return sorted(out)


def angular_momentum_N_m_s(params: Mapping[str, Any]) -> float:
    """Spin angular momentum magnitude ``I_a |ω_s|`` (N·m·s = kg·m²/s)."""
    return params["rotor_inertia_kg_m2"] * abs(params["spin_rad_s"])


class FreeGyroscope(ClosedFormModel):
    """Gimbal angles of an ideal free gyroscope on a vehicle turning at a constant rate."""

    parameters = PARAMETERS
    series_units = {
        "outer_gimbal_rad": "rad",
        "inner_gimbal_rad": "rad",
        "outer_gimbal_rate_rad_s": "rad/s",
        "inner_gimbal_rate_rad_s": "rad/s",
        "lock_angle_rad": "rad",
        "vehicle_turn_rad": "rad",
    }
    invariant_units = {"spin_axis_error_rad": "rad"}
    description = (
        "Kinematics of ideal gimbals: spin axis fixed in inertial space, gimbal angles from the vehicle's attitude"
    )

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        motion = gimbal_motion(params, t_s)
        # The outer angle is continuous except where the axis passes (through) the lock: unwrap the finite stretches.
        outer = motion.outer_rad.copy()
        finite = np.isfinite(outer)
        outer[finite] = np.unwrap(outer[finite])
        # Check of the formulas: rebuild the inertial axis from vehicle attitude and gimbal angles.
        rebuilt = rotate_vector(
            motion.q_world_vehicle, spin_axis_from_gimbals(np.nan_to_num(motion.outer_rad), motion.inner_rad)
        )
        s_world = spin_axis_inertial(params)
        error = np.arctan2(np.linalg.norm(np.cross(rebuilt, s_world), axis=-1), rebuilt @ s_world)
        events = [
            Event(t, "gimbal-lock", _lock_message(params, t, angle))
            for t, angle in closest_approaches_to_lock(params, float(t_s[-1]))
            if angle < math.radians(LOCK_WARNING_DEG)
        ]
        return ClosedFormSolution(
            series={
                "outer_gimbal_rad": outer,
                "inner_gimbal_rad": motion.inner_rad,
                "outer_gimbal_rate_rad_s": motion.outer_rate_rad_s,
                "inner_gimbal_rate_rad_s": motion.inner_rate_rad_s,
                "lock_angle_rad": motion.lock_angle_rad,
                "vehicle_turn_rad": float(np.linalg.norm(vehicle_rate(params))) * motion.t_s,
            },
            invariants={"spin_axis_error_rad": error},
            events=events,
        )

    def invariant_scales(self, params, invariants):
        return {"spin_axis_error_rad": 1.0}  # an angle: compared with 1 rad


def _lock_message(params: Mapping[str, Any], t_s: float, angle_rad: float) -> str:
    if angle_rad < 1e-9:
        return (
            f"At t = {t_s:.3f} s the spin axis lies on the outer gimbal axis: the rings are in one plane "
            "(gimbal lock). The outer gimbal angle is undefined there and flips by 180°; real gimbals would "
            "have to turn infinitely fast and instead push on the rotor."
        )
    outer_rate = abs(float(gimbal_motion(params, t_s).outer_rate_rad_s[0]))
    return (
        f"At t = {t_s:.3f} s the spin axis passes {math.degrees(angle_rad):.2f}° from the outer gimbal axis "
        f"(near gimbal lock): the outer ring must turn at {outer_rate:.3g} rad/s there to keep the rotor free of "
        "torque."
    )
