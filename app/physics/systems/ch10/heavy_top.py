"""The heavy symmetric top: a spinning axisymmetric body on a fixed pivot under gravity.

Parameters (API contract names): ``mass_kg``, ``cg_distance_m`` (pivot to centre
of mass, along the symmetry axis), ``I_transverse_pivot`` and ``I_axial``
(kg·m², about the pivot), ``spin_rad_s`` (ω3, the body-3 component of the
angular velocity), ``theta0_deg`` (initial tilt from +Z),
``precession_rate0_rad_s`` (φ̇0), ``nutation_rate0_rad_s`` (θ̇0) and ``g_m_s2``.
Series: ``theta``, ``phi``, ``psi`` — 3-1-3 Euler angles in rad with Z up,
``phi`` and ``psi`` unwrapped.

The motion is integrated (:mod:`app.physics.bodies.rigid_body`); the
quadrature solution (:mod:`app.physics.systems.ch10.heavy_top_quadrature`) is the
reference it is checked against.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.bodies.inertia import centroidal_from_point
from app.physics.bodies.rigid_body import RigidBody
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.math.rotations import body_rates_from_euler_313_rates, euler_313_from_quaternion, quaternion_from_euler_313
from app.physics.solvers.integrated_model import IntegratedModel
from app.physics.systems.ch10.heavy_top_quadrature import HeavyTopQuadrature, heavy_top_quadrature


def _check(values: Mapping[str, Any]) -> None:
    m, l = values["mass_kg"], values["cg_distance_m"]
    inertia_pivot = np.diag([values["I_transverse_pivot"], values["I_transverse_pivot"], values["I_axial"]])
    transverse_cm = float(centroidal_from_point(inertia_pivot, m, np.array([0.0, 0.0, l]))[0, 0])
    if transverse_cm <= 0.0:
        raise ParameterError(
            "I_transverse_pivot",
            f"must exceed m·l² = {m * l * l:.4g} kg·m² (the parallel-axis share); "
            f"the moment about the centre of mass would be {transverse_cm:.4g} kg·m²",
        )
    if values["I_axial"] > 2.0 * transverse_cm * (1 + 1e-12):
        raise ParameterError(
            "I_axial",
            f"must not exceed twice the transverse moment about the centre of mass "
            f"(2 × {transverse_cm:.4g} kg·m², triangle inequality; a flat disc is the limit)",
        )


PARAMETERS = ParameterSet(
    (
        Parameter("mass_kg", "kg", 1.0, 0.01, 100.0, "Mass of the top", "m", scale="log"),
        Parameter("cg_distance_m", "m", 0.05, 0.001, 2.0, "Pivot to centre of mass, along the symmetry axis", "l", scale="log"),
        Parameter("I_transverse_pivot", "kg·m²", 0.0125, 1e-5, 100.0, "Moment of inertia about a transverse axis through the pivot", "I_t", scale="log"),
        Parameter("I_axial", "kg·m²", 0.01, 1e-5, 100.0, "Moment of inertia about the symmetry axis", "I_a", scale="log"),
        Parameter("spin_rad_s", "rad/s", 60.0, -2000.0, 2000.0, "Spin ω3: angular velocity component along the symmetry axis", "ω₃", scale="symlog"),
        Parameter("theta0_deg", "deg", 30.0, 0.0, 179.0, "Initial tilt of the symmetry axis from the upward vertical", "θ₀", step=0.5),
        Parameter("precession_rate0_rad_s", "rad/s", 0.0, -100.0, 100.0, "Initial precession rate φ̇₀", "φ̇₀", step=0.05),
        Parameter("nutation_rate0_rad_s", "rad/s", 0.0, -100.0, 100.0, "Initial nutation rate θ̇₀", "θ̇₀", step=0.05),
        Parameter("g_m_s2", "m/s²", 9.807, 0.0, 100.0, "Gravitational acceleration", "g", step=0.001),
    ),
    check=_check,
)


def rigid_body(params: Mapping[str, Any]) -> RigidBody:
    """The top as a body about its pivot (checked once per set of values: frames ask for it every 1/30 s)."""
    return _rigid_body(params["I_transverse_pivot"], params["I_axial"], params["mass_kg"], params["cg_distance_m"], params["g_m_s2"])


@functools.lru_cache(maxsize=256)
def _rigid_body(I_transverse: float, I_axial: float, mass_kg: float, cg_distance_m: float, g_m_s2: float) -> RigidBody:
    return RigidBody((I_transverse, I_transverse, I_axial), mass_kg=mass_kg, cg_distance_m=cg_distance_m, g_m_s2=g_m_s2)


def initial_state(params: Mapping[str, Any]) -> np.ndarray:
    """``[q, ω_body]`` at t = 0 with φ0 = ψ0 = 0 (the axis tilts towards −Y... see :func:`quaternion_from_euler_313`)."""
    theta0 = math.radians(params["theta0_deg"])
    q0 = quaternion_from_euler_313(0.0, theta0, 0.0)
    omega = body_rates_from_euler_313_rates(theta0, 0.0, params["precession_rate0_rad_s"], params["nutation_rate0_rad_s"], 0.0)
    omega[2] = params["spin_rad_s"]
    return np.concatenate([q0, omega])


def euler_angles(states: np.ndarray) -> dict[str, np.ndarray]:
    """``theta``, ``phi``, ``psi`` (rad) of states (N, 7); phi and psi unwrapped in time."""
    angles = euler_313_from_quaternion(np.asarray(states)[:, 0:4])
    return {"theta": angles[:, 1], "phi": np.unwrap(angles[:, 0]), "psi": np.unwrap(angles[:, 2])}


def critical_spin_rad_s(params: Mapping[str, Any]) -> float:
    """Sleeping-top threshold: ω3² = 4 m g l I_t / I_a² (rad/s); zero without gravity (any spin stays up)."""
    mgl = params["mass_kg"] * params["g_m_s2"] * params["cg_distance_m"]
    return math.sqrt(4.0 * mgl * params["I_transverse_pivot"]) / params["I_axial"]


def quadrature(params: Mapping[str, Any]) -> HeavyTopQuadrature:
    """The quadrature solution from the same initial state as :func:`initial_state` (φ0 = ψ0 = 0).

    Raises ValueError for the one motion it cannot represent (exactly on the
    separatrix, reaching the upright position in infinite time).
    """
    return heavy_top_quadrature(
        I_transverse=params["I_transverse_pivot"], I_axial=params["I_axial"],
        mgl=params["mass_kg"] * params["g_m_s2"] * params["cg_distance_m"], spin_rad_s=params["spin_rad_s"],
        theta0_rad=math.radians(params["theta0_deg"]), phi_dot0=params["precession_rate0_rad_s"],
        theta_dot0=params["nutation_rate0_rad_s"],
    )


#: Relative size of φ̇ at a turning point below which the locus counts as cusped.
CUSP_TOLERANCE = 1e-6


def locus_shape(solution: HeavyTopQuadrature) -> str:
    """What the tip of the symmetry axis traces on the unit sphere.

    ``"circle"`` (steady precession, θ constant), ``"waves"`` (φ̇ keeps one sign
    between the turning points), ``"loops"`` (φ̇ changes sign) or ``"cusps"``
    (φ̇ = 0 at one turning point, as when released with no precession rate).
    ``"vertical"`` when the axis stays on the vertical (a sleeping top).
    """
    if solution.theta_max_rad - solution.theta_min_rad <= 1e-12 * max(solution.theta_max_rad, 1.0):
        return "vertical" if math.sin(solution.theta_min_rad) < 1e-12 else "circle"
    It = solution.I_transverse
    rates = []
    for theta in (solution.theta_min_rad, solution.theta_max_rad):
        u, sin2 = math.cos(theta), math.sin(theta) ** 2
        # φ̇ = (p_φ − p_ψ u) / (I_t sin²θ); at a pole the axis passes through it (no azimuth: skip).
        rates.append(None if sin2 < 1e-15 else (solution.p_phi - solution.p_psi * u) / (It * sin2))
    known = [r for r in rates if r is not None]
    scale = max(max((abs(r) for r in known), default=0.0), abs(solution.p_psi / It), 1e-300)
    if any(abs(r) <= CUSP_TOLERANCE * scale for r in known):
        return "cusps"
    if len(known) == 2 and known[0] * known[1] < 0.0:
        return "loops"
    return "waves"


class HeavyTop(IntegratedModel):
    parameters = PARAMETERS
    methods = ("splitting4", "splitting2", "rk4", "dopri5")
    default_method = "splitting4"
    series_units = {"theta": "rad", "phi": "rad", "psi": "rad"}
    #: ``angular_momentum`` (|L|) is conserved, and reported, only without gravity (``g_m_s2 = 0``).
    invariant_units = {"energy": "J", "angular_momentum_z": "kg·m²/s", "spin": "rad/s", "quaternion_norm_error": "", "angular_momentum": "kg·m²/s"}

    def system(self, params):
        return rigid_body(params).system()

    def initial_state(self, params):
        return initial_state(params)

    def fastest_rate_rad_s(self, params, state):
        return rigid_body(params).fastest_rate_rad_s(state)

    def series(self, params, t_s, states):
        return euler_angles(states)

    def invariants(self, params, states):
        return rigid_body(params).invariants(states)

    def describable(self, params, states):
        """Finite states whose quaternion is still a unit one to within a half: every step renormalises it,
        so a norm far from 1 (a zero quaternion, say) means a norm overflowed in a run that blew up."""
        states = np.asarray(states, dtype=float)
        finite = np.all(np.isfinite(states), axis=1)
        with np.errstate(over="ignore", invalid="ignore"):
            norm = np.linalg.norm(np.where(finite[:, None], states[:, 0:4], 0.0), axis=1)
        return finite & (np.abs(norm - 1.0) < 0.5)

    def invariant_scales(self, params, state):
        body = rigid_body(params)
        kinetic = 0.5 * float(np.sum(np.asarray(body.inertia_pivot_kg_m2) * state[4:7] ** 2))
        momentum = float(np.linalg.norm(body.angular_momentum_world(state)))
        scales = {
            "energy": max(kinetic + body.gravity_moment_N_m, 1e-300),
            "angular_momentum_z": max(momentum, 1e-300),
            "angular_momentum": max(momentum, 1e-300),
            "spin": max(float(np.linalg.norm(state[4:7])), 1e-300),
            "quaternion_norm_error": 1.0,
        }
        # One scale per invariant the body reports (|L| only when it is torque-free, g = 0).
        return {name: scales[name] for name in body.invariants(state)}
