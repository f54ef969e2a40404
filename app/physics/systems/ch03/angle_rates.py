"""Angular velocity and angular acceleration of a body turned by a rotation sequence whose angles move.

Each angle of the sequence (conventions of :mod:`app.physics.math.rotations`) moves with a constant
angular acceleration: ``θk(t) = θk₀ + θ̇k₀ t + ½ θ̈k t²`` (rad, rad/s, rad/s²). Then

* ``ω = θ̇1 n1 + θ̇2 n2 + θ̇3 n3`` with ``nk`` the axis of turn k (``n1`` fixed, ``n2`` carried by
  turn 1, ``n3`` by turns 1 and 2); the rates are not components of ω, because the ``nk`` are not
  perpendicular;
* ``α = Σ θ̈k nk + θ̇1 n1 × θ̇2 n2 + (θ̇1 n1 + θ̇2 n2) × θ̇3 n3``: the first sum is the part *along the
  turn axes*, the cross products the part *from turning axes* (present even with constant rates).

Both are computed by :mod:`app.physics.math.rotations` (the only implementation); this module
evaluates them along the motion and splits α into its two parts. At gimbal lock (``θ2 = 0`` or
180° for proper sequences, ±90° for Tait–Bryan) ω still follows from the rates, but the rates can
no longer be recovered from ω: :meth:`AngleKinematics.recovered_rates` says so instead of a number.
World components are on XYZ (+Z up), body components on xyz.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution, Event
from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.math.rotations import (
    GIMBAL_LOCK_TOLERANCE_RAD,
    SEQUENCES,
    RotationSequence,
    angle_rate_matrix_body,
    angle_rates_from_angular_velocity_body,
    angular_acceleration_world,
    angular_velocity_world,
    gimbal_lock_distance_rad,
    intermediate_frames,
    rotation_sequence,
)

_ORDINAL = ("first", "second", "third")


def _angle_parameters() -> tuple[Parameter, ...]:
    defaults = (
        (30.0, 0.6, 0.0),
        (40.0, 0.0, 0.0),
        (0.0, 2.0, 0.0),
    )  # a top: steady precession and spin at a fixed tilt
    parameters: list[Parameter] = []
    for k, (angle, rate, acceleration) in enumerate(defaults, start=1):
        which = _ORDINAL[k - 1]
        parameters += [
            Parameter(
                f"angle{k}_deg",
                "deg",
                angle,
                -180.0,
                180.0,
                f"Angle θ{k} of the {which} turn at t = 0",
                f"θ{k}(0)",
                step=1.0,
            ),
            Parameter(
                f"rate{k}_rad_s",
                "rad/s",
                rate,
                -3.0,
                3.0,
                f"Rate θ̇{k} of the {which} angle at t = 0",
                f"θ̇{k}(0)",
                step=0.05,
            ),
            Parameter(
                f"accel{k}_rad_s2",
                "rad/s²",
                acceleration,
                -2.0,
                2.0,
                f"Constant angular acceleration θ̈{k} of the {which} angle",
                f"θ̈{k}",
                step=0.05,
            ),
        ]
    return tuple(parameters)


PARAMETERS = ParameterSet(
    (
        Parameter(
            "sequence",
            "",
            "3-1-3",
            kind="choice",
            choices=tuple(SEQUENCES),
            label="Sequence",
            description=(
                "Axes of the three body-fixed turns (1 = x, 2 = y, 3 = z): proper Euler (first axis "
                "repeated) or Tait–Bryan (all three)"
            ),
        ),
        *_angle_parameters(),
    )
)


@dataclass(frozen=True)
class AngleMotion:
    """Angles moving with constant angular accelerations (rad, rad/s, rad/s²; each (3,))."""

    sequence: RotationSequence
    angles0_rad: np.ndarray
    rates0_rad_s: np.ndarray
    accelerations_rad_s2: np.ndarray

    @classmethod
    def from_params(cls, params: Mapping[str, Any]) -> AngleMotion:
        return cls(
            sequence=rotation_sequence(params["sequence"]),
            angles0_rad=np.radians([params[f"angle{k}_deg"] for k in (1, 2, 3)]),
            rates0_rad_s=np.array([params[f"rate{k}_rad_s"] for k in (1, 2, 3)], dtype=float),
            accelerations_rad_s2=np.array([params[f"accel{k}_rad_s2"] for k in (1, 2, 3)], dtype=float),
        )

    def angles(self, t_s: np.ndarray) -> np.ndarray:
        """θ(t) (rad, (N, 3)); complex times are allowed (a complex-step derivative)."""
        t = np.atleast_1d(np.asarray(t_s))[:, None]
        return self.angles0_rad + self.rates0_rad_s * t + 0.5 * self.accelerations_rad_s2 * t * t

    def rates(self, t_s: np.ndarray) -> np.ndarray:
        """θ̇(t) (rad/s, (N, 3))."""
        t = np.atleast_1d(np.asarray(t_s, dtype=float))[:, None]
        return self.rates0_rad_s + self.accelerations_rad_s2 * t

    def kinematics(self, t_s: np.ndarray) -> AngleKinematics:
        """Attitude, turn axes, ω and α at times ``t_s`` (s, (N,))."""
        t = np.atleast_1d(np.asarray(t_s, dtype=float))
        angles, rates = self.angles(t), self.rates(t)
        accelerations = np.broadcast_to(self.accelerations_rad_s2, angles.shape)
        frames = intermediate_frames(angles, self.sequence)
        axes = frames.rotation_axes_world
        omega = angular_velocity_world(angles, rates, self.sequence)
        alpha = angular_acceleration_world(angles, rates, accelerations, self.sequence)
        along = np.einsum("nki,nk->ni", axes, accelerations)
        R = frames.R_world_frame[:, 3]
        to_body = lambda v: np.einsum("nji,nj->ni", R, v)  # noqa: E731  {v}_xyz = [R]ᵀ {v}_XYZ
        return AngleKinematics(
            sequence=self.sequence,
            t_s=t,
            angles_rad=angles,
            rates_rad_s=rates,
            R_world_body=R,
            q_world_body=frames.q_world_frame[:, 3],
            turn_axes_world=axes,
            omega_world_rad_s=omega,
            omega_body_rad_s=to_body(omega),
            alpha_world_rad_s2=alpha,
            alpha_body_rad_s2=to_body(alpha),
            alpha_along_axes_world_rad_s2=along,
            alpha_turning_axes_world_rad_s2=alpha - along,
            lock_distance_rad=gimbal_lock_distance_rad(angles, self.sequence),
        )


@dataclass(frozen=True)
class AngleKinematics:
    """The attitude and its rates at N instants.

    ``angles_rad``, ``rates_rad_s`` (N, 3); ``R_world_body`` (N, 3, 3); ``q_world_body`` (N, 4, wxyz);
    ``turn_axes_world`` (N, 3, 3): row k is the unit axis of turn k+1 (XYZ); ω (rad/s) and α (rad/s²)
    (N, 3) in world (XYZ) and body (xyz) components; α split into the part along the turn axes
    (Σ θ̈k nk) and the part from turning axes (the cross products), both XYZ;
    ``lock_distance_rad`` (N,) how far θ2 is from gimbal lock.
    """

    sequence: RotationSequence
    t_s: np.ndarray
    angles_rad: np.ndarray
    rates_rad_s: np.ndarray
    R_world_body: np.ndarray
    q_world_body: np.ndarray
    turn_axes_world: np.ndarray
    omega_world_rad_s: np.ndarray
    omega_body_rad_s: np.ndarray
    alpha_world_rad_s2: np.ndarray
    alpha_body_rad_s2: np.ndarray
    alpha_along_axes_world_rad_s2: np.ndarray
    alpha_turning_axes_world_rad_s2: np.ndarray
    lock_distance_rad: np.ndarray

    def locked(self, i: int) -> bool:
        """Whether instant ``i`` is at gimbal lock (within :data:`GIMBAL_LOCK_TOLERANCE_RAD`)."""
        return bool(self.lock_distance_rad[i] <= GIMBAL_LOCK_TOLERANCE_RAD)

    def rate_gain(self, i: int) -> float:
        """Largest angle rate per unit |ω| at instant ``i``, ``1/σ_min(J)`` ((rad/s)/(rad/s)); inf at lock."""
        if self.locked(i):
            return math.inf
        singular = np.linalg.svd(angle_rate_matrix_body(self.angles_rad[i], self.sequence), compute_uv=False)
        return float(1.0 / singular[-1])

    def recovered_rates(self, i: int) -> tuple[np.ndarray | None, str]:
        """The angle rates solved back from body ω at instant ``i`` (rad/s, (3,)), or None and why not."""
        try:
            return angle_rates_from_angular_velocity_body(
                self.angles_rad[i], self.omega_body_rad_s[i], self.sequence
            ), ""
        except ValueError:
            seq = self.sequence
            combination = "θ̇1 + θ̇3" if float(seq.lock_combination_sign(self.angles_rad[i, 1])) > 0 else "θ̇1 − θ̇3"
            return None, (
                f"the rates cannot be recovered here: θ2 = {math.degrees(float(self.angles_rad[i, 1])):.4g}° "
                "puts the third "
                f"turn's axis {seq.axis_label(3)} on the line of {seq.axis_label(1)} (gimbal lock), so ω fixes "
                f"only {combination}"
            )


class AngleRates(ClosedFormModel):
    """A body turned by a rotation sequence whose angles move with constant angular accelerations."""

    parameters = PARAMETERS
    description = "closed-form kinematics: ω = Σ θ̇k nk, α = Σ θ̈k nk + θ̇1 n1 × θ̇2 n2 + (θ̇1 n1 + θ̇2 n2) × θ̇3 n3"
    series_units = {
        **{f"angle{k}_rad": "rad" for k in (1, 2, 3)},
        **{f"omega_{frame}_{c}": "rad/s" for frame in ("world", "body") for c in "xyz"},
        **{f"alpha_{frame}_{c}": "rad/s²" for frame in ("world", "body") for c in "xyz"},
        "gimbal_lock_distance_rad": "rad",
    }

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        k = AngleMotion.from_params(params).kinematics(t_s)
        series: dict[str, np.ndarray] = {f"angle{j + 1}_rad": k.angles_rad[:, j] for j in range(3)}
        vectors = {
            "omega_world": k.omega_world_rad_s,
            "omega_body": k.omega_body_rad_s,
            "alpha_world": k.alpha_world_rad_s2,
            "alpha_body": k.alpha_body_rad_s2,
        }
        for name, value in vectors.items():
            for i, c in enumerate("xyz"):
                series[f"{name}_{c}"] = value[:, i]
        series["gimbal_lock_distance_rad"] = k.lock_distance_rad
        locked = k.lock_distance_rad <= GIMBAL_LOCK_TOLERANCE_RAD
        starts = np.flatnonzero(locked & ~np.concatenate([[False], locked[:-1]]))
        events = [
            Event(
                float(k.t_s[i]),
                "gimbal_lock",
                f"gimbal lock of the {k.sequence.name} sequence: ω and α still follow from the rates, "
                "but the rates cannot be recovered from ω here",
            )
            for i in starts
        ]
        return ClosedFormSolution(series=series, events=events)
