"""The integrated model shared by the one-degree-of-freedom linkages in absolute coordinates (every DAE algorithm).

A mechanism gives its parameters, its :class:`~.planar_linkages.PlanarLinkage` and
its loop-closure motion ``absolute_motion(params, θ, θ̇, θ̈) -> (q, v, a)`` (N, 9)
each; this base builds the start (loop closure, confirmed by the consistent
initial-conditions solver), the step choice, the energy and the series.

The energy invariant is ``E = T + V − τ (θ − θ₀)`` (J): kinetic plus potential
energy less the constant torque's work, which the exact motion keeps at its
initial value. The series are the crank angle (rad) and speed (rad/s), each pin
force's size (N, from the multipliers) and the work–energy residual ``E − E₀`` (J).
"""

from __future__ import annotations

import math
from abc import abstractmethod
from collections.abc import Callable, Mapping
from typing import Any, ClassVar

import numpy as np

from app.physics.constrained.initial_conditions import ConsistentStart, consistent_initial_conditions
from app.physics.constrained.model import ConstrainedModel
from app.physics.constrained.system import ConstrainedSystem
from app.physics.core.energy import EnergyParts
from app.physics.systems.ch08.planar_linkages import PlanarLinkage

#: The step is chosen for the speed a constant torque builds up over this many crank turns (as in chapter 6).
TURNS_FOR_STEP_CHOICE = 10.0
#: Crank angles sampled (over a turn, or the crank's travel) for M(θ) and V(θ).
_SAMPLES = 145

MotionFunction = Callable[
    [Mapping[str, Any], np.ndarray, np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]
]


class PlanarLinkageModel(ConstrainedModel):
    """A crank-driven linkage of three links in absolute coordinates (9 coordinates, 8 constraints)."""

    #: The joints whose multipliers are pin forces (two rows each), in the order of the linkage's joints.
    pin_joints: ClassVar[tuple[str, ...]]
    start_parameters = ("crank_angle0_deg", "crank_speed_rad_s")
    invariant_units = {"energy": "J", "constraint_position": "m", "constraint_velocity": "m/s"}

    @abstractmethod
    def linkage(self, params: Mapping[str, Any]) -> PlanarLinkage: ...

    @abstractmethod
    def absolute_motion(
        self, params: Mapping[str, Any], theta: np.ndarray, omega: np.ndarray, alpha: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(q, v, a) (N, 9) from the crank's angle (rad), speed (rad/s) and acceleration (rad/s²) (N,)."""

    @abstractmethod
    def loop_closure_start(self, params: Mapping[str, Any]) -> tuple[np.ndarray, np.ndarray]:
        """(q, v) (9,) each at t = 0 from the crank's start angle and speed."""

    @abstractmethod
    def crank_travel_rad(self, params: Mapping[str, Any]) -> tuple[float, float]:
        """The crank angles (rad) the loop closes between (a full turn, or a non-Grashof crank's arc)."""

    # --- ConstrainedModel ------------------------------------------------------------------------------------
    def consistent_start(self, params: Mapping[str, Any]) -> ConsistentStart:
        """Loop closure's start, passed through the initial-conditions solver (which finds nothing to change)."""
        q0, v0 = self.loop_closure_start(params)
        return consistent_initial_conditions(self.constrained_system(params), q0, v0)

    def constrained_system(self, params: Mapping[str, Any]) -> ConstrainedSystem:
        independent = (2,) if self.crank_turns_fully(params) else None
        return self.linkage(params).system(independent=independent)

    def crank_turns_fully(self, params: Mapping[str, Any]) -> bool:
        low, high = self.crank_travel_rad(params)
        return high - low >= 2.0 * math.pi - 1e-12

    def energy_J(self, params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
        """T + V − τ (θ − θ₀) (J) along ``states`` (N, 18)."""
        states = np.atleast_2d(states)
        linkage = self.linkage(params)
        q0, _ = self.loop_closure_start(params)
        q, v = states[:, :9], states[:, 9:]
        return linkage.kinetic_energy_J(v) + linkage.potential_energy_J(q) - linkage.torque_work_J(q, q0)

    def constrained_energy_parts(self, params: Mapping[str, Any], states: np.ndarray) -> EnergyParts:
        """Each link's ½ I_G φ̇² (rotational) and ½ m v_G² (the rest of T), gravity, and the torque's work τ (θ −
        θ₀)."""
        states = np.atleast_2d(states)
        linkage = self.linkage(params)
        q0, _ = self.loop_closure_start(params)
        q, v = states[:, :9], states[:, 9:]
        kinetic = linkage.kinetic_energy_J(v)
        rotational = 0.5 * np.sum(linkage.mass_diagonal[2::3] * v[:, 2::3] ** 2, axis=-1)
        return EnergyParts(
            linkage.potential_energy_J(q),
            translational_kinetic_J=kinetic - rotational,
            rotational_kinetic_J=rotational,
            drive_work_J=linkage.torque_work_J(q, q0),
        )

    def _inertia_and_potential(self, params: Mapping[str, Any]) -> tuple[np.ndarray, np.ndarray]:
        """M(θ) (kg·m²) and V(θ) (J) over the crank's travel, where defined."""
        low, high = self.crank_travel_rad(params)
        theta = np.linspace(low, high, _SAMPLES)
        q, first, second = self.absolute_motion(params, theta, np.ones_like(theta), np.zeros_like(theta))
        linkage = self.linkage(params)
        inertia, _, _ = linkage.one_dof_terms(first, second)
        potential = linkage.potential_energy_J(q)
        keep = np.isfinite(inertia) & np.isfinite(potential)
        return inertia[keep], potential[keep]

    def energy_scale_J(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """Initial kinetic energy, the potential's range over the travel and one turn of the torque's work (J)."""
        _, potential = self._inertia_and_potential(params)
        kinetic0 = float(self.linkage(params).kinetic_energy_J(state[9:]))
        return max(kinetic0 + float(np.ptp(potential)) + 2.0 * math.pi * abs(float(params["drive_torque_N_m"])), 1e-12)

    def speed_limit_rad_s(self, params: Mapping[str, Any]) -> float:
        """The crank speed the step is chosen for (rad/s): reached where M(θ) is least once the torque has worked
        :data:`TURNS_FOR_STEP_CHOICE` turns on top of the energy in play (frictionless, it speeds up without limit)."""
        inertia, _ = self._inertia_and_potential(params)
        q0, v0 = self.loop_closure_start(params)
        energy = self.energy_scale_J(params, np.concatenate([q0, v0])) + 2.0 * math.pi * TURNS_FOR_STEP_CHOICE * abs(
            float(params["drive_torque_N_m"])
        )
        return max(
            math.sqrt(2.0 * energy / float(np.min(inertia))), 2.0 * abs(float(params["crank_speed_rad_s"])) + 1.0
        )

    def fastest_rate_rad_s(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """The speed limit times how sharply M(θ) changes, √(M_max/M_min), at least 2 (rad/s), as in chapter 6."""
        inertia, _ = self._inertia_and_potential(params)
        sharpness = max(2.0, math.sqrt(float(np.max(inertia) / np.min(inertia))))
        return sharpness * self.speed_limit_rad_s(params)

    def residual_scales(self, params: Mapping[str, Any]) -> tuple[float, float]:
        """Position residuals against the shortest link (m), velocity residuals against it times the speed limit
        (m/s)."""
        shortest = min(link.length_m for link in self.linkage(params).links)
        return shortest, shortest * self.speed_limit_rad_s(params)

    def pin_forces_N(self, params: Mapping[str, Any], multipliers: np.ndarray) -> dict[str, np.ndarray]:
        """Each pin's force components (N, 2) (N) from the multipliers (N, 8), by joint name (signs:
        :mod:`.planar_linkages`)."""
        rows = self.linkage(params).multiplier_rows()
        multipliers = np.atleast_2d(multipliers)
        return {name: multipliers[:, rows[name]] for name in self.pin_joints}

    def constrained_series(
        self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray, multipliers: np.ndarray
    ) -> dict[str, np.ndarray]:
        states = np.atleast_2d(states)
        energy = self.energy_J(params, states)
        q0, v0 = self.loop_closure_start(params)
        series = {"crank_angle": states[:, 2].copy(), "crank_speed_rad_s": states[:, 11].copy()}
        for name, force in self.pin_forces_N(params, multipliers).items():
            series[pin_force_series_name(name)] = np.linalg.norm(force, axis=-1)
        series["work_energy_residual_J"] = energy - float(self.energy_J(params, np.concatenate([q0, v0]))[0])
        return series


def linkage_series_units(pin_joints: tuple[str, ...]) -> dict[str, str]:
    """The units of :meth:`PlanarLinkageModel.constrained_series` for a linkage with these pin joints."""
    return {
        "crank_angle": "rad",
        "crank_speed_rad_s": "rad/s",
        **{pin_force_series_name(j): "N" for j in pin_joints},
        "work_energy_residual_J": "J",
    }


def pin_force_series_name(joint: str) -> str:
    """``pin_force_<joint>_N`` with subscript digits made plain (O₂ → O2)."""
    plain = joint.translate(str.maketrans("₀₁₂₃₄₅₆₇₈₉", "0123456789"))
    return f"pin_force_{plain}_N"
