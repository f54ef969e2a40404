"""The four-bar with link masses in absolute coordinates: three bodies, nine coordinates, eight constraints.

Frame and lengths as in :mod:`app.physics.systems.ch04.four_bar`: crank pivot
O₂ at the origin, rocker pivot O₄ at (d, 0), y up, gravity along −y. Bodies,
each a uniform slender bar with coordinates (x_G, y_G, φ) (m, m, rad): the crank
a (φ = θ₂), the coupler b (φ = θ₃, direction A→B) and the rocker c (φ = θ₄,
direction O₄→B). Joints (:mod:`.planar_linkages`) and their multipliers:

* ``O₂`` ground pin, crank end s = −a/2: λ = ground's force on the crank (N);
* ``A`` pin, coupler end s = −b/2 to crank end s = +a/2: λ = crank's force on the coupler (N);
* ``B`` pin, rocker end s = +c/2 to coupler end s = +b/2: λ = coupler's force on the rocker (N);
* ``O₄`` ground pin, rocker end s = −c/2 at (d, 0): λ = ground's force on the rocker (N).

9 − 8 = 1 degree of freedom; a constant torque τ drives the crank. The
one-degree-of-freedom equation in the crank angle (:func:`one_dof_terms`) uses
chapter 4's rates and accelerations as kinematic coefficients; it is singular at
a toggle position (coupler and rocker in line), which a crank that turns fully
(Grashof, crank shortest) never reaches — the absolute coordinates do not mind.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np

from app.physics.constrained.system import ConstrainedSystem
from app.physics.core.parameters import ParameterError, ParameterSet
from app.physics.systems.ch04 import four_bar as kinematics
from app.physics.systems.ch06 import mechanism_kinetics as kinetics
from app.physics.systems.ch08.planar_linkages import PlanarLinkage, RigidLink, ground_pin, pin
from app.physics.systems.ch08.planar_linkages_model import PlanarLinkageModel, linkage_series_units

_GEOMETRY = kinematics.PARAMETERS.by_name
_MASSES = kinetics.PARAMETERS.by_name


def _check(values: Mapping[str, Any]) -> None:
    motion = kinematics.FourBarMotion.from_params(values)
    state = motion.at(np.zeros(1))
    if state.singular[0]:
        raise ParameterError(
            "crank_angle0_deg",
            "the linkage starts at a toggle or change point, where its rates are undefined; choose another crank angle",
        )


PARAMETERS = ParameterSet(
    (
        _GEOMETRY["ground_m"],
        _GEOMETRY["crank_m"],
        _GEOMETRY["coupler_m"],
        _GEOMETRY["rocker_m"],
        _GEOMETRY["branch"],
        _GEOMETRY["crank_angle0_deg"],
        replace(
            _GEOMETRY["crank_speed_rad_s"],
            default=4.0,
            min=-30.0,
            max=30.0,
            description="Crank speed ω₂ at t = 0 (counterclockwise positive)",
        ),
        replace(
            _MASSES["drive_torque_N_m"],
            default=1.0,
            description="Constant torque τ on the crank (counterclockwise positive)",
        ),
        replace(_MASSES["crank_mass_kg"], description="Mass of the crank (a uniform slender bar)"),
        replace(
            _MASSES["rod_mass_kg"],
            name="coupler_mass_kg",
            label="coupler mass",
            description="Mass of the coupler (a uniform slender bar)",
        ),
        replace(
            _MASSES["rod_mass_kg"],
            name="rocker_mass_kg",
            label="rocker mass",
            description="Mass of the rocker (a uniform slender bar)",
        ),
        _MASSES["g_m_s2"],
    ),
    check=_check,
)
JOINT_NAMES = ("O₂", "A", "B", "O₄")


def four_bar_motion(params: Mapping[str, Any]) -> kinematics.FourBarMotion:
    """Chapter 4's four-bar for these lengths, assembly and start (the start angle kept inside the crank's travel)."""
    return kinematics.FourBarMotion.from_params(params)


def massive_four_bar_linkage(params: Mapping[str, Any]) -> PlanarLinkage:
    """Bodies crank, coupler, rocker and the joints O₂, A, B, O₄ (module docstring)."""
    a, b, c, d = params["crank_m"], params["coupler_m"], params["rocker_m"], params["ground_m"]
    bodies = (
        RigidLink.slender_bar("crank", params["crank_mass_kg"], a),
        RigidLink.slender_bar("coupler", params["coupler_mass_kg"], b),
        RigidLink.slender_bar("rocker", params["rocker_mass_kg"], c),
    )
    joints = (
        ground_pin("O₂", 0, -0.5 * a, (0.0, 0.0)),
        pin("A", 1, -0.5 * b, 0, 0.5 * a),
        pin("B", 2, 0.5 * c, 1, 0.5 * b),
        ground_pin("O₄", 2, -0.5 * c, (d, 0.0)),
    )
    return PlanarLinkage(bodies, joints, params["g_m_s2"], float(params["drive_torque_N_m"]), driven=0)


def _unit(angle: np.ndarray) -> np.ndarray:
    return np.stack([np.cos(angle), np.sin(angle)], axis=-1)


def _normal(angle: np.ndarray) -> np.ndarray:
    return np.stack([-np.sin(angle), np.cos(angle)], axis=-1)


def centre_motion(
    linkage: kinematics.FourBar,
    angles: tuple[np.ndarray, np.ndarray, np.ndarray],
    rates: tuple[np.ndarray, np.ndarray, np.ndarray],
    angular_accelerations: tuple[np.ndarray, np.ndarray, np.ndarray],
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Absolute coordinates, rates and accelerations (N, 9) from the link angles θ₂, θ₃, θ₄ (rad), their rates
    (rad/s) and accelerations (rad/s²), each (N,): the centres are O₂ + ½a e₂, A + ½b e₃ and O₄ + ½c e₄."""
    a, b, c, d = linkage.crank_m, linkage.coupler_m, linkage.rocker_m, linkage.ground_m
    (t2, t3, t4), (w2, w3, w4), (al2, al3, al4) = (
        np.broadcast_arrays(*(np.atleast_1d(np.asarray(x, float)) for x in group))
        for group in (angles, rates, angular_accelerations)
    )

    def point(length, angle, rate, acceleration):
        """Position, velocity, acceleration of the point ``length`` along a link at ``angle`` from its base."""
        e, n = _unit(angle), _normal(angle)
        return length * e, length * rate[:, None] * n, length * (acceleration[:, None] * n - (rate**2)[:, None] * e)

    crank_pin = point(a, t2, w2, al2)
    crank_centre = point(0.5 * a, t2, w2, al2)
    coupler_half = point(0.5 * b, t3, w3, al3)
    rocker_centre = point(0.5 * c, t4, w4, al4)
    coupler_centre = tuple(p + h for p, h in zip(crank_pin, coupler_half))
    rocker_centre = (rocker_centre[0] + np.array([d, 0.0]), rocker_centre[1], rocker_centre[2])
    columns = []
    for level, angle_terms in enumerate(((t2, t3, t4), (w2, w3, w4), (al2, al3, al4))):
        columns.append(
            np.column_stack(
                [
                    crank_centre[level],
                    angle_terms[0],
                    coupler_centre[level],
                    angle_terms[1],
                    rocker_centre[level],
                    angle_terms[2],
                ]
            )
        )
    return columns[0], columns[1], columns[2]


def four_bar_absolute_motion(
    params: Mapping[str, Any], theta: np.ndarray, omega: np.ndarray, alpha: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(q, v, a) (N, 9) from the crank's θ₂ (rad), ω₂ (rad/s), α₂ (rad/s²) (N,) by chapter 4's loop closure
    in the chosen assembly (coupler and rocker angles wrapped to [−π, π); NaN rates at a toggle)."""
    motion = four_bar_motion(params)
    theta = np.atleast_1d(np.asarray(theta, dtype=float))
    omega, alpha = np.broadcast_to(omega, theta.shape), np.broadcast_to(alpha, theta.shape)
    positions = motion.linkage.positions(theta, motion.branch)
    t3, t4 = positions.coupler_angle, positions.rocker_angle
    w3, w4, _ = motion.linkage.rates(theta, t3, t4, omega)
    al3, al4 = motion.linkage.accelerations(theta, t3, t4, omega, w3, w4, alpha)
    return centre_motion(motion.linkage, (theta, t3, t4), (omega, w3, w4), (alpha, al3, al4))


def massive_four_bar_system(params: Mapping[str, Any]) -> ConstrainedSystem:
    """The four-bar as a :class:`ConstrainedSystem` (9 coordinates, 8 holonomic rows). The crank angle is the
    independent coordinate when the crank turns fully; otherwise the algorithm picks one by pivoting."""
    independent = (2,) if four_bar_motion(params).crank_range.turns_fully else None
    return massive_four_bar_linkage(params).system(independent=independent)


def massive_four_bar_initial_state(params: Mapping[str, Any]) -> tuple[np.ndarray, np.ndarray]:
    """Consistent ``(q, v)`` (9,) each from ``crank_angle0_deg`` and ``crank_speed_rad_s`` by chapter 4's loop
    closure."""
    motion = four_bar_motion(params)
    state = motion.at(np.zeros(1))
    q, v, _ = centre_motion(
        motion.linkage,
        (state.crank_angle, state.coupler_angle, state.rocker_angle),
        (np.full(1, float(params["crank_speed_rad_s"])), state.coupler_rate, state.rocker_rate),
        (np.zeros(1),) * 3,
    )
    return q[0], v[0]


def one_dof_terms(params: Mapping[str, Any], theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``M(θ)`` (kg·m²), ``½M′(θ)`` (kg·m²) and ``V′(θ)`` (N·m) at crank angles θ (N,), from chapter 4's rates and
    accelerations at θ̇ = 1, θ̈ = 0 (the kinematic coefficients). NaN at a toggle position."""
    theta = np.atleast_1d(np.asarray(theta, dtype=float))
    _, first, second = four_bar_absolute_motion(params, theta, np.ones_like(theta), np.zeros_like(theta))
    return massive_four_bar_linkage(params).one_dof_terms(first, second)


def crank_acceleration_rad_s2(params: Mapping[str, Any], theta: np.ndarray, omega: np.ndarray) -> np.ndarray:
    """θ̈ = (τ − ½M′θ̇² − V′)/M (rad/s²) of the one-degree-of-freedom equation at θ (rad), θ̇ (rad/s) (N,)."""
    inertia, half_slope, potential_slope = one_dof_terms(params, theta)
    return (float(params["drive_torque_N_m"]) - half_slope * np.asarray(omega) ** 2 - potential_slope) / inertia


class MassiveFourBar(PlanarLinkageModel):
    """The four-bar in absolute coordinates under a constant crank torque (every DAE algorithm).

    The live ``minimal`` method is not offered: the one-degree-of-freedom equation
    (:func:`crank_acceleration_rad_s2`) is evaluated through chapter 4's numpy
    loop closure, which is the tests' reference, not a compiled kernel.
    """

    parameters = PARAMETERS
    pin_joints = JOINT_NAMES
    series_units = linkage_series_units(JOINT_NAMES)

    def linkage(self, params: Mapping[str, Any]) -> PlanarLinkage:
        return massive_four_bar_linkage(params)

    def absolute_motion(self, params, theta, omega, alpha):
        return four_bar_absolute_motion(params, theta, omega, alpha)

    def loop_closure_start(self, params: Mapping[str, Any]) -> tuple[np.ndarray, np.ndarray]:
        return massive_four_bar_initial_state(params)

    def crank_travel_rad(self, params: Mapping[str, Any]) -> tuple[float, float]:
        motion = four_bar_motion(params)
        if motion.drive.limits_rad is None:  # the crank turns fully
            return 0.0, 2.0 * math.pi
        return motion.drive.limits_rad
