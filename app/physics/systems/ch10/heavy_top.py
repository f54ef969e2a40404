"""The heavy symmetric top: a spinning axisymmetric body on a fixed pivot under gravity.

Parameters (API contract names): ``mass_kg``, ``cg_distance_m`` (pivot to centre
of mass, along the symmetry axis), ``I_transverse_pivot`` and ``I_axial``
(kg·m², about the pivot), ``spin_rad_s`` (ω3, the body-3 component of the
angular velocity), ``theta0_deg`` (initial tilt from +Z),
``precession_rate0_rad_s`` (φ̇0), ``nutation_rate0_rad_s`` (θ̇0) and ``g_m_s2``.
Series: ``theta``, ``phi``, ``psi`` — 3-1-3 Euler angles in rad with Z up,
``phi`` and ``psi`` unwrapped from the integrated angular velocity (each frame's
increment is the integral of the angle rates, so a spin that turns ψ by more
than π between two frames is counted, not aliased) — and ``attitude_error_rad``,
the rotation angle between the integrated attitude and the quadrature
solution's (rad), where that solution exists.

The motion is integrated (:mod:`app.physics.bodies.rigid_body`); the
quadrature solution (:mod:`app.physics.systems.ch10.heavy_top_quadrature`) is the
reference it is checked against, and answers a request whose automatic step
would exceed the request limits. The default meets 1e-6 rad of attitude error
over the horizon (:class:`~app.physics.solvers.step_choice.AccuracyTarget`).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.bodies.inertia import centroidal_from_point
from app.physics.bodies.rigid_body import PivotedBody
from app.physics.core.energy import EnergyParts
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.core.readout import Quantity
from app.physics.math.rotations import (
    body_rates_from_euler_313_rates,
    euler_313_from_quaternion,
    quaternion_from_euler_313,
)
from app.physics.solvers.integrated_model import IntegratedModel
from app.physics.solvers.registry import METHODS
from app.physics.solvers.step_choice import AccuracyTarget
from app.physics.systems.ch10.heavy_top_quadrature import HeavyTopQuadrature, heavy_top_quadrature
from app.physics.systems.ch10.torque_free_body import attitude_difference_rad


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
        Parameter(
            "cg_distance_m", "m", 0.05, 0.001, 2.0, "Pivot to centre of mass, along the symmetry axis", "l", scale="log"
        ),
        Parameter(
            "I_transverse_pivot",
            "kg·m²",
            0.0125,
            1e-5,
            100.0,
            "Moment of inertia about a transverse axis through the pivot",
            "I_t",
            scale="log",
        ),
        Parameter(
            "I_axial", "kg·m²", 0.01, 1e-5, 100.0, "Moment of inertia about the symmetry axis", "I_a", scale="log"
        ),
        Parameter(
            "spin_rad_s",
            "rad/s",
            60.0,
            -2000.0,
            2000.0,
            "Spin ω3: angular velocity component along the symmetry axis",
            "ω₃",
            scale="symlog",
        ),
        Parameter(
            "theta0_deg",
            "deg",
            30.0,
            0.0,
            179.0,
            "Initial tilt of the symmetry axis from the upward vertical",
            "θ₀",
            step=0.5,
        ),
        Parameter("precession_rate0_rad_s", "rad/s", 0.0, -100.0, 100.0, "Initial precession rate φ̇₀", "φ̇₀", step=0.05),
        Parameter("nutation_rate0_rad_s", "rad/s", 0.0, -100.0, 100.0, "Initial nutation rate θ̇₀", "θ̇₀", step=0.05),
        Parameter("g_m_s2", "m/s²", 9.807, 0.0, 100.0, "Gravitational acceleration", "g", step=0.001),
    ),
    check=_check,
)


def rigid_body(params: Mapping[str, Any]) -> PivotedBody:
    """The top as a body about its pivot (checked once per set of values: frames ask for it every 1/30 s)."""
    return _rigid_body(
        params["I_transverse_pivot"], params["I_axial"], params["mass_kg"], params["cg_distance_m"], params["g_m_s2"]
    )


@functools.lru_cache(maxsize=256)
def _rigid_body(
    I_transverse: float, I_axial: float, mass_kg: float, cg_distance_m: float, g_m_s2: float
) -> PivotedBody:
    return PivotedBody(
        (I_transverse, I_transverse, I_axial), mass_kg=mass_kg, cg_distance_m=cg_distance_m, g_m_s2=g_m_s2
    )


def initial_state(params: Mapping[str, Any]) -> np.ndarray:
    """``[q, ω_body]`` at t = 0 with φ0 = ψ0 = 0 (the axis tilts towards −Y... see
    :func:`quaternion_from_euler_313`)."""
    theta0 = math.radians(params["theta0_deg"])
    q0 = quaternion_from_euler_313(0.0, theta0, 0.0)
    omega = body_rates_from_euler_313_rates(
        theta0, 0.0, params["precession_rate0_rad_s"], params["nutation_rate0_rad_s"], 0.0
    )
    omega[2] = params["spin_rad_s"]
    return np.concatenate([q0, omega])


def euler_313_rates(angles: np.ndarray, omega_body: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(φ̇, ψ̇)`` (rad/s, (N,) each) from 3-1-3 angles (N, 3) and body angular velocity (N, 3).

    ``φ̇ = (ω1 sin ψ + ω2 cos ψ) / sin θ`` and ``ψ̇ = ω3 − φ̇ cos θ``. On the vertical
    (``sin θ = 0``) only ``φ ± ψ`` is defined and :func:`euler_313_from_quaternion`
    splits it equally, so each rate is half of ``ω3`` there (``φ̇ = −ω3/2`` at θ = π).
    """
    _, theta, psi = angles[:, 0], angles[:, 1], angles[:, 2]
    w1, w2, w3 = omega_body[:, 0], omega_body[:, 1], omega_body[:, 2]
    sin_theta, cos_theta = np.sin(theta), np.cos(theta)
    locked = np.abs(sin_theta) < 1e-12
    phi_dot = np.where(
        locked, 0.5 * w3 * np.sign(cos_theta), (w1 * np.sin(psi) + w2 * np.cos(psi)) / np.where(locked, 1.0, sin_theta)
    )
    psi_dot = np.where(locked, 0.5 * w3, w3 - phi_dot * cos_theta)
    return phi_dot, psi_dot


def unwrap_with_rates(angle_rad: np.ndarray, rate_rad_s: np.ndarray, t_s: np.ndarray) -> np.ndarray:
    """Continuous angle (rad, (N,)) from wrapped samples ``angle_rad`` and the rates ``rate_rad_s`` at times ``t_s``.

    Each increment is the wrapped difference brought within ±π of the trapezoidal
    integral of the rate over the interval, so turns of many times 2π between two
    samples are kept; valid while that integral is within π of the true increment.
    """
    if len(angle_rad) < 2:
        return np.asarray(angle_rad, dtype=float).copy()
    predicted = 0.5 * (rate_rad_s[1:] + rate_rad_s[:-1]) * np.diff(t_s)
    offset = np.diff(angle_rad) - predicted
    increments = predicted + (offset + np.pi) % (2.0 * np.pi) - np.pi
    return np.concatenate([[angle_rad[0]], angle_rad[0] + np.cumsum(increments)])


def euler_angles(states: np.ndarray, t_s: np.ndarray | None = None) -> dict[str, np.ndarray]:
    """``theta``, ``phi``, ``psi`` (rad) of states (N, 7) at times ``t_s`` (N,) s.

    phi and psi are unwrapped with the rates of the integrated angular velocity
    (:func:`unwrap_with_rates`); without ``t_s``, from the samples alone (``numpy.unwrap``: aliases fast spins).
    """
    states = np.asarray(states, dtype=float)
    angles = euler_313_from_quaternion(states[:, 0:4])
    if t_s is None:
        return {"theta": angles[:, 1], "phi": np.unwrap(angles[:, 0]), "psi": np.unwrap(angles[:, 2])}
    phi_dot, psi_dot = euler_313_rates(angles, states[:, 4:7])
    return {
        "theta": angles[:, 1],
        "phi": unwrap_with_rates(angles[:, 0], phi_dot, t_s),
        "psi": unwrap_with_rates(angles[:, 2], psi_dot, t_s),
    }


def critical_spin_rad_s(params: Mapping[str, Any]) -> float:
    """Sleeping-top threshold: ω3² = 4 m g l I_t / I_a² (rad/s); zero without gravity (any spin stays up)."""
    mgl = params["mass_kg"] * params["g_m_s2"] * params["cg_distance_m"]
    return math.sqrt(4.0 * mgl * params["I_transverse_pivot"]) / params["I_axial"]


def quadrature(params: Mapping[str, Any]) -> HeavyTopQuadrature:
    """The quadrature solution from the same initial state as :func:`initial_state` (φ0 = ψ0 = 0).

    Raises ValueError for the one motion it cannot represent (exactly on the
    separatrix, reaching the upright position in infinite time). Cached per set of values.
    """
    return _quadrature(
        params["I_transverse_pivot"],
        params["I_axial"],
        params["mass_kg"] * params["g_m_s2"] * params["cg_distance_m"],
        params["spin_rad_s"],
        math.radians(params["theta0_deg"]),
        params["precession_rate0_rad_s"],
        params["nutation_rate0_rad_s"],
    )


@functools.lru_cache(maxsize=64)
def _quadrature(I_transverse, I_axial, mgl, spin_rad_s, theta0_rad, phi_dot0, theta_dot0) -> HeavyTopQuadrature:
    return heavy_top_quadrature(
        I_transverse=I_transverse,
        I_axial=I_axial,
        mgl=mgl,
        spin_rad_s=spin_rad_s,
        theta0_rad=theta0_rad,
        phi_dot0=phi_dot0,
        theta_dot0=theta_dot0,
    )


def quadrature_states(params: Mapping[str, Any], t_s: np.ndarray) -> np.ndarray:
    """``[q, ω_body]`` (N, 7) of the quadrature solution at times ``t_s`` (N,) s.

    The attitude is the quadrature's; ω follows from the Euler angle rates:
    ``φ̇ = (p_φ − p_ψ cos θ)/(I_t sin²θ)``, ``ψ̇ = ω3 − φ̇ cos θ`` (ω3 constant) and
    ``|θ̇|`` from the energy, its sign from the slope of θ(t). Energy, L_z and
    the spin are therefore constant to round-off by construction.
    """
    solution = quadrature(params)
    t_s = np.asarray(t_s, dtype=float)
    theta = solution.theta(t_s)
    q = solution.quaternion(t_s)
    psi = euler_313_from_quaternion(q)[:, 2]
    It, Ia, mgl, spin = solution.I_transverse, params["I_axial"], solution.mgl, params["spin_rad_s"]
    sin2 = np.sin(theta) ** 2
    upright = sin2 < 1e-24
    phi_dot = np.where(
        upright, 0.0, (solution.p_phi - solution.p_psi * np.cos(theta)) / (It * np.where(upright, 1.0, sin2))
    )
    psi_dot = spin - phi_dot * np.cos(theta)
    y0 = initial_state(params)
    energy = float(rigid_body(params).energy_J(y0[None, :])[0])
    theta_dot_sq = (2.0 * energy - Ia * spin**2 - 2.0 * mgl * np.cos(theta)) / It - phi_dot**2 * sin2
    delta = 1e-6 * max(min(solution.nutation_period_s, 1.0), 1e-6)
    slope = solution.theta(t_s + delta) - solution.theta(t_s - delta)
    theta_dot = np.sign(slope) * np.sqrt(np.maximum(theta_dot_sq, 0.0))
    omega = body_rates_from_euler_313_rates(theta, psi, phi_dot, theta_dot, psi_dot)
    omega[..., 2] = spin
    return np.concatenate([q, omega], axis=1)


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


def reference_or_none(params: Mapping[str, Any]) -> tuple[HeavyTopQuadrature | None, str]:
    """``(quadrature solution, "")``, or ``(None, why)`` for the motion it cannot represent (see :func:`quadrature`)."""
    try:
        return quadrature(params), ""
    except ValueError as exc:
        return None, f"No quadrature reference for these values: {exc}"


def readout_quantities(
    params: Mapping[str, Any],
    reference: HeavyTopQuadrature | None,
    theta_swept_rad: tuple[float, float] | None,
) -> list[Quantity]:
    """What the scene's readout shows beside time, the one list the scene and its "Open as Python" script print.

    ``reference``: the quadrature solution (:func:`reference_or_none`; None: no predictions). ``theta_swept_rad``:
    the least and largest nutation angle θ (rad) of the frames integrated so far (None: none yet). Rows: the
    quadrature's nutation band (deg), nutation period (s), mean precession rate (rad/s) and axis locus (a word), the
    band the integration swept (deg), and the sleeping threshold |ω₃| (rad/s; a word without gravity).
    """
    quantities: list[Quantity] = []
    if reference is not None:
        quantities += [
            Quantity(
                "theta_min_deg", "nutation band: θ min (quadrature)", math.degrees(reference.theta_min_rad), "deg"
            ),
            Quantity(
                "theta_max_deg", "nutation band: θ max (quadrature)", math.degrees(reference.theta_max_rad), "deg"
            ),
            # An upright top's axis never comes back: its nutation period is infinite.
            Quantity.or_text(
                "nutation_period_s", "nutation period (quadrature)", reference.nutation_period_s, "s", "never returns"
            ),
            Quantity(
                "mean_precession_rate_rad_s",
                "mean precession rate (quadrature)",
                reference.mean_precession_rate_rad_s,
                "rad/s",
            ),
            Quantity.word("locus", "axis locus", locus_shape(reference)),
        ]
    if theta_swept_rad is not None:
        low, high = theta_swept_rad
        quantities += [
            Quantity("theta_min_swept_deg", "θ min swept so far (integration)", math.degrees(low), "deg"),
            Quantity("theta_max_swept_deg", "θ max swept so far (integration)", math.degrees(high), "deg"),
        ]
    if params["g_m_s2"] == 0.0:
        # Without gravity nothing pulls an upright top over: there is no threshold to cross.
        quantities.append(Quantity.word("critical_spin_rad_s", "sleeping threshold |ω₃|", "none: no gravity"))
    else:
        quantities.append(
            Quantity("critical_spin_rad_s", "sleeping threshold |ω₃|", critical_spin_rad_s(params), "rad/s")
        )
    return quantities


class HeavyTop(IntegratedModel):
    parameters = PARAMETERS
    #: Every registered method: each can step a rigid body about a fixed point (higher-order splittings included).
    methods = tuple(METHODS)
    default_method = "splitting4"
    series_units = {"theta": "rad", "phi": "rad", "psi": "rad", "attitude_error_rad": "rad"}
    accuracy_target = AccuracyTarget(
        1e-6, "rad", "attitude: rotation angle between the integrated and the exact attitude"
    )
    reference_error_series = "attitude_error_rad"
    reference_name = "quadrature solution (elliptic functions for θ, elliptic integrals for φ and ψ)"
    #: ``angular_momentum`` (|L|) is conserved, and reported, only without gravity (``g_m_s2 = 0``).
    invariant_units = {
        "energy": "J",
        "angular_momentum_z": "kg·m²/s",
        "spin": "rad/s",
        "quaternion_norm_error": "",
        "angular_momentum": "kg·m²/s",
    }

    def system(self, params):
        return rigid_body(params).system()

    def initial_state(self, params):
        return initial_state(params)

    def fastest_rate_rad_s(self, params, state):
        return rigid_body(params).fastest_rate_rad_s(state)

    def series(self, params, t_s, states):
        return euler_angles(states, t_s)

    def solution_error(self, params, states, reference):
        """Rotation angle (rad) between the attitudes of ``states`` and ``reference`` (N, 7)."""
        return attitude_difference_rad(np.asarray(states)[:, 0:4], np.asarray(reference)[:, 0:4])

    def reference_states(self, params, t_s):
        return quadrature_states(params, t_s)

    def reference_error(self, params, t_s, states):
        """Attitude error (rad) against the quadrature: only its quaternion is evaluated, not the rates that
        :func:`quadrature_states` adds (they cost twice as much again, and the error does not use them)."""
        try:
            reference = quadrature(params).quaternion(np.asarray(t_s, dtype=float))
        except ValueError:  # exactly on the separatrix: the quadrature cannot represent the motion
            return None
        return attitude_difference_rad(np.asarray(states)[:, 0:4], reference)

    def invariants(self, params, states):
        return rigid_body(params).invariants(states)

    series_labels = {
        "theta": "θ",
        "phi": "φ",
        "psi": "ψ",
        "attitude_error_rad": "attitude error",
        "spin": "ω₃",
        "angular_momentum_z": "L_z",
        "angular_momentum": "|L|",
        "quaternion_norm_error": "|q| − 1",
    }

    def energy_parts(self, params, states, *, t_s=None):
        """About the fixed pivot: ½ m v_G² with v_G = ω × l e₃ (so ½ m l² (ω₁² + ω₂²)) and the rest of ½ ω·I_O ω,
        which is ½ ω·I_G ω; gravity m g l cos θ (zero at the pivot's height)."""
        body = rigid_body(params)
        states = np.atleast_2d(states)
        omega = states[:, 4:7]
        kinetic = 0.5 * np.sum(np.asarray(body.inertia_pivot_kg_m2) * omega**2, axis=-1)
        translational = 0.5 * body.mass_kg * body.cg_distance_m**2 * (omega[:, 0] ** 2 + omega[:, 1] ** 2)
        return EnergyParts(
            body.energy_J(states) - kinetic,
            translational_kinetic_J=translational,
            rotational_kinetic_J=kinetic - translational,
        )

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
