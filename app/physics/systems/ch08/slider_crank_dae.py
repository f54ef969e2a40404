"""The slider-crank with link masses in absolute coordinates: three bodies, nine coordinates, eight constraints.

Frame and links as in :mod:`app.physics.systems.ch06.mechanism_kinetics` (crank
pivot O at the origin, the slider's line y = e, y up, gravity along −y). Bodies,
each (x_G, y_G, φ) (m, m, rad): the crank (a uniform slender bar of length r, φ = θ),
the connecting rod (slender bar of length l, φ = the rod angle) and the slider
(its centre at the wrist pin B). Joints (:mod:`.planar_linkages`), with the
multipliers' meaning — the same forces, with the same signs, as chapter 6's
Newton–Euler unknowns:

* ``O`` ground pin, crank end s = −r/2 at the origin: λ_O = ground's force on the crank (N);
* ``A`` pin, rod end s = −l/2 to crank end s = +r/2: λ_A = crank's force on the rod (N);
* ``B`` pin, slider centre to rod end s = +l/2: λ_B = rod's force on the slider (N);
* ``guide``: slider centre on y = e: λ = guide's force on the slider along +y (N);
* ``slider angle``: slider at φ = 0: λ = the guide's moment on the slider (N·m).

9 − 8 = 1 degree of freedom. A constant torque τ drives the crank. The slider
never turns, so its moment of inertia only fills M's diagonal: it is taken as a
square block of side r/2 (``I = m (r/2)²/6``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.constrained.system import ConstrainedSystem
from app.physics.core.parameters import ParameterSet
from app.physics.solvers.system import OdeSystem
from app.physics.systems.ch06 import mechanism_kinetics as kinetics
from app.physics.systems.ch08.planar_linkages import PlanarLinkage, RigidLink, fixed_angle, ground_pin, guide, pin
from app.physics.systems.ch08.planar_linkages_model import PlanarLinkageModel, linkage_series_units

#: The chapter-6 parameters, minus its drive choice: here the crank is always driven by the torque.
PARAMETERS = ParameterSet(
    tuple(p for p in kinetics.PARAMETERS.parameters if p.name != "drive"),
    check=lambda values: kinetics.SliderCrankLinks.from_params(values),
)
JOINT_NAMES = ("O", "A", "B", "guide", "slider angle")
#: The crank angle θ (index 2) is the independent coordinate: the slider-crank has no toggle when driven by its crank.
INDEPENDENT = (2,)


def chapter6_links(params: Mapping[str, Any]) -> kinetics.SliderCrankLinks:
    """The same mechanism as chapter 6 sees it (geometry, masses, gravity)."""
    return kinetics.SliderCrankLinks.from_params(params)


def slider_crank_linkage(params: Mapping[str, Any]) -> PlanarLinkage:
    """Bodies crank, rod, slider and the joints O, A, B, guide, slider angle (module docstring)."""
    links = chapter6_links(params)
    r, l, e = links.mechanism.crank_m, links.mechanism.rod_m, links.mechanism.offset_m
    block = 0.5 * r
    bodies = (
        RigidLink.slender_bar("crank", links.crank_mass_kg, r),
        RigidLink.slender_bar("rod", links.rod_mass_kg, l),
        RigidLink("slider", links.slider_mass_kg, links.slider_mass_kg * block**2 / 6.0, block),
    )
    joints = (
        ground_pin("O", 0, -0.5 * r, (0.0, 0.0)),
        pin("A", 1, -0.5 * l, 0, 0.5 * r),
        pin("B", 2, 0.0, 1, 0.5 * l),
        guide("guide", 2, 0.0, (0.0, e), 0.0),
        fixed_angle("slider angle", 2, 0.0),
    )
    return PlanarLinkage(bodies, joints, links.g_m_s2, float(params["drive_torque_N_m"]), driven=0)


def slider_crank_absolute_motion(
    params: Mapping[str, Any], theta: np.ndarray | float, omega: np.ndarray | float, alpha: np.ndarray | float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Absolute coordinates, rates and accelerations, each (N, 9), from the crank's θ (rad), ω (rad/s), α (rad/s²)
    (N,), by chapter 4's loop closure through :func:`~app.physics.systems.ch06.mechanism_kinetics.link_motion`."""
    motion = kinetics.link_motion(chapter6_links(params), theta, omega, alpha)
    zeros = np.zeros_like(motion.crank_angle)

    def stack(crank, crank_angle, rod, rod_angle, slider):
        return np.column_stack([crank, crank_angle, rod, rod_angle, slider, zeros])

    q = stack(motion.crank_centre, motion.crank_angle, motion.rod_centre, motion.rod_angle, motion.slider_pin)
    v = stack(
        motion.crank_centre_velocity,
        motion.crank_speed_rad_s,
        motion.rod_centre_velocity,
        motion.rod_rate,
        motion.slider_velocity,
    )
    a = stack(
        motion.crank_centre_acceleration,
        motion.crank_acceleration_rad_s2,
        motion.rod_centre_acceleration,
        motion.rod_acceleration,
        motion.slider_acceleration,
    )
    return q, v, a


def slider_crank_system(params: Mapping[str, Any]) -> ConstrainedSystem:
    """The slider-crank as a :class:`ConstrainedSystem` (9 coordinates, 8 holonomic rows)."""
    return slider_crank_linkage(params).system(independent=INDEPENDENT)


def slider_crank_initial_state(params: Mapping[str, Any]) -> tuple[np.ndarray, np.ndarray]:
    """Consistent ``(q, v)`` (9,) each from ``crank_angle0_deg`` and ``crank_speed_rad_s`` by loop closure."""
    q, v, _ = slider_crank_absolute_motion(
        params, math.radians(params["crank_angle0_deg"]), params["crank_speed_rad_s"], 0.0
    )
    return q[0], v[0]


def minimal_parameters(params: Mapping[str, Any]) -> dict[str, Any]:
    """The chapter-6 model's parameters for the same mechanism under the torque drive (its one-DOF equation)."""
    return {**{name: params[name] for name in PARAMETERS.by_name}, "drive": "torque"}


class SliderCrankDae(PlanarLinkageModel):
    """The slider-crank in absolute coordinates under a constant crank torque; ``minimal`` is chapter 6's equation."""

    parameters = PARAMETERS
    pin_joints = ("O", "A", "B")
    series_units = linkage_series_units(pin_joints)

    def linkage(self, params: Mapping[str, Any]) -> PlanarLinkage:
        return slider_crank_linkage(params)

    def absolute_motion(self, params, theta, omega, alpha):
        return slider_crank_absolute_motion(params, theta, omega, alpha)

    def loop_closure_start(self, params: Mapping[str, Any]) -> tuple[np.ndarray, np.ndarray]:
        return slider_crank_initial_state(params)

    def crank_travel_rad(self, params: Mapping[str, Any]) -> tuple[float, float]:
        return 0.0, 2.0 * math.pi

    def minimal_system(self, params: Mapping[str, Any]) -> OdeSystem:
        """Chapter 6's compiled M(θ)θ̈ + ½M′θ̇² + V′ = τ on (θ, θ̇, W)."""
        return kinetics.MechanismKinetics().system(minimal_parameters(params))

    def minimal_state(self, params: Mapping[str, Any], state: np.ndarray) -> np.ndarray:
        return np.array([state[2], state[11], 0.0])

    def constrained_states(self, params: Mapping[str, Any], minimal_states: np.ndarray) -> np.ndarray:
        minimal_states = np.atleast_2d(minimal_states)
        q, v, _ = slider_crank_absolute_motion(
            params, minimal_states[:, 0], minimal_states[:, 1], np.zeros(len(minimal_states))
        )
        return np.hstack([q, v])
