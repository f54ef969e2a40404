"""The unsteady rolling disk as a chapter-8 model: five coordinates, two no-slip multiplier rows, every DAE algorithm.

State ``(x, y, ψ, θ, φ, ẋ, ẏ, ψ̇, θ̇, φ̇)`` (m, rad, m/s, rad/s; see
:mod:`.rolling_disk_constrained`), the same layout as the chapter-9
independent-speed model, which is its cross-check. The start is built
consistent: at the origin, heading ψ₀, lean θ₀, the angle rates given, and the
contact point moving along the heading at r φ̇₀ (so nothing is changed to make
it consistent). The rolling model holds while the disk stands on its rim and the
floor pushes: chapter 9's rule (:mod:`app.physics.systems.ch09.rolling_disk_contact`)
stops a run where the disk has fallen or would lift off, with a message.

The method ``minimal`` integrates chapter 9's equations in the independent speeds
(Kane's, :class:`~app.physics.systems.ch09.rolling_disk_model.RollingDiskMotion`):
the same state, with ẋ and ẏ following from the angle rates, so there are no
multipliers to solve for and the rows are kept by construction (to the integrator's
error in ẋ, ẏ). It is the reference the multiplier algorithms are compared with.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.constrained.initial_conditions import ConsistentStart, consistent_initial_conditions
from app.physics.constrained.model import ConstrainedModel
from app.physics.constrained.system import ConstrainedSystem
from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.solvers.integrated_model import ModelLimit
from app.physics.solvers.system import OdeSystem
from app.physics.systems.ch08.rolling_disk_constrained import (
    COORDINATE_NAMES,
    energy_J,
    energy_parts,
    rolling_disk_system,
    rolling_state,
)
from app.physics.systems.ch08.rolling_disk_stability import critical_spin_rad_s, stability_sentence
from app.physics.systems.ch09.rolling_disk import SYSTEM as CHAPTER_9_DISK
from app.physics.systems.ch09.rolling_disk_contact import (
    FALLEN,
    FALLEN_LEAN_DEG,
    LIFT_OFF,
    contact_limit,
    fallen_message,
    normal_force_N,
)
from app.physics.systems.ch09.rolling_disk_model import RollingDiskMotion

__all__ = ["FALLEN", "FALLEN_LEAN_DEG", "LIFT_OFF", "PARAMETERS", "UnsteadyRollingDisk", "fallen_message"]

_CHAPTER_9_START = RollingDiskMotion.parameters.by_name
PARAMETERS = ParameterSet(
    (
        *CHAPTER_9_DISK.parameters.parameters,
        _CHAPTER_9_START["lean_0_deg"],
        _CHAPTER_9_START["spin_rate_0_rad_s"],
        _CHAPTER_9_START["heading_rate_0_rad_s"],
        Parameter(
            "heading_0_deg", "deg", 0.0, -180.0, 180.0, "Initial heading ψ of the rolling direction from +x", "ψ₀"
        ),
        Parameter("lean_rate_0_rad_s", "rad/s", 0.0, -20.0, 20.0, "Initial lean rate θ̇", "θ̇₀"),
    )
)


def _mass_radius_g(params: Mapping[str, Any]) -> tuple[float, float, float]:
    return float(params["mass_kg"]), float(params["radius_m"]), float(params["g_m_s2"])


class UnsteadyRollingDisk(ConstrainedModel):
    """The disk rolling without slip from any lean, spin and heading, its no-slip rows kept by the chosen DAE
    algorithm."""

    parameters = PARAMETERS
    start_parameters = ("heading_0_deg", "lean_0_deg", "heading_rate_0_rad_s", "lean_rate_0_rad_s", "spin_rate_0_rad_s")
    series_units = {
        "x_m": "m",
        "y_m": "m",
        "heading_rad": "rad",
        "lean_rad": "rad",
        "spin_rate_rad_s": "rad/s",
        "energy_J": "J",
        "friction_x_N": "N",
        "friction_y_N": "N",
        "normal_force_N": "N",
    }
    invariant_units = {"energy": "J", "constraint_position": "m", "constraint_velocity": "m/s"}

    def constrained_system(self, params: Mapping[str, Any]) -> ConstrainedSystem:
        return rolling_disk_system(params)

    def consistent_start(self, params: Mapping[str, Any]) -> ConsistentStart:
        """The start at the origin, rolling along its heading: consistent as built (``changes`` is empty)."""
        state = rolling_state(
            radius_m=float(params["radius_m"]),
            heading_rad=math.radians(float(params["heading_0_deg"])),
            lean_rad=math.radians(float(params["lean_0_deg"])),
            heading_rate_rad_s=float(params["heading_rate_0_rad_s"]),
            lean_rate_rad_s=float(params["lean_rate_0_rad_s"]),
            spin_rate_rad_s=float(params["spin_rate_0_rad_s"]),
        )
        names = (*COORDINATE_NAMES, *(f"{name}_rate" for name in COORDINATE_NAMES))
        units = ("m", "m", "rad", "rad", "rad", "m/s", "m/s", "rad/s", "rad/s", "rad/s")
        return consistent_initial_conditions(
            self.constrained_system(params), state[:5], state[5:], names=names, units=units
        )

    def energy_J(self, params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
        return energy_J(params, states)

    def constrained_energy_parts(self, params: Mapping[str, Any], states: np.ndarray):
        return energy_parts(params, states)

    def energy_scale_J(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """m g r (upright to flat) or the energy if larger (J)."""
        m, r, g = _mass_radius_g(params)
        return max(m * g * r, float(abs(energy_J(params, state[None, :])[0])), 1e-12)

    def residual_scales(self, params: Mapping[str, Any]) -> tuple[float, float]:
        """r (m; there are no position rows) and the rolling speed r·max(|φ̇₀|, √(g/r)) (m/s) for the contact
        velocity."""
        _, r, g = _mass_radius_g(params)
        return r, r * max(abs(float(params["spin_rate_0_rad_s"])), math.sqrt(g / r) if g > 0 else 0.0, 1e-6)

    def fastest_rate_rad_s(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """The wobble's 2|φ̇| (axial over transverse moment times the spin), the fall's √(g/r) and the heading and lean
        rates (rad/s)."""
        _, r, g = _mass_radius_g(params)
        heading_rate, lean_rate, spin_rate = (abs(float(value)) for value in state[7:10])
        return max(2.0 * spin_rate + heading_rate + lean_rate + math.sqrt(g / r), 1.0)

    def constrained_series(self, params, t_s, states, multipliers):
        """The chapter-9 series, and the multipliers: the floor's friction force on the disk (N, world x and y)."""
        return {
            "x_m": states[:, 0],
            "y_m": states[:, 1],
            "heading_rad": states[:, 2],
            "lean_rad": states[:, 3],
            "spin_rate_rad_s": states[:, 9],
            "energy_J": energy_J(params, states),
            "friction_x_N": multipliers[:, 0],
            "friction_y_N": multipliers[:, 1],
            "normal_force_N": normal_force_N(params, states),
        }

    # --- the minimal method: chapter 9's independent-speed equations ---------------------------------------------
    def minimal_system(self, params: Mapping[str, Any]) -> OdeSystem:
        """Chapter 9's Kane equations for the same disk, on the same state ``(q, v)`` (10,)."""
        chapter_9 = RollingDiskMotion()
        values = {name: params[name] for name in chapter_9.parameters.by_name if name in params}
        return chapter_9.system(chapter_9.parameters.validate(values | {"formulation": "kane"}))

    def minimal_state(self, params: Mapping[str, Any], state: np.ndarray) -> np.ndarray:
        """The consistent ``(q, v)`` itself (10,): chapter 9 integrates the same layout."""
        return np.array(state, dtype=float)

    def constrained_states(self, params: Mapping[str, Any], minimal_states: np.ndarray) -> np.ndarray:
        """The minimal states (N, 10) are already ``(q, v)`` rows."""
        return np.atleast_2d(minimal_states)

    # --- where the model stops ------------------------------------------------------------------------------
    def model_limit(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> ModelLimit | None:
        """Where the disk has fallen or would lift off (chapter 9's rule, on the (q, v) rows of any algorithm)."""
        return contact_limit(params, t_s, self.constrained_view(params, states))

    # --- stability of upright rolling ---------------------------------------------------------------------------
    def critical_spin_rad_s(self, params: Mapping[str, Any]) -> float:
        """Ω_c (rad/s) from the linearised equations (:mod:`.rolling_disk_stability`)."""
        return critical_spin_rad_s(self.constrained_system(params))

    def stability(self, params: Mapping[str, Any]) -> str:
        """'upright rolling at 12.0 rad/s is stable (critical 5.7 rad/s)' for the start's spin."""
        return stability_sentence(float(params["spin_rate_0_rad_s"]), self.critical_spin_rad_s(params))
