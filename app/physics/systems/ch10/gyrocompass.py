"""The gyrocompass: a spin axis held horizontal, free in azimuth, on the rotating Earth.

Local frame at latitude ``λ`` (carried by the Earth): ``x`` east, ``y`` north,
``z`` up. The Earth's angular velocity there is ``Ω (cos λ ŷ + sin λ ẑ)``.
The housing turns only about the local vertical, by the azimuth ``α`` of the
spin axis, measured from north and positive toward east (clockwise seen from
above): ``ŝ = (sin α, cos α, 0)``. The rotor spins about ``ŝ`` with the constant
spin component ``ω_s`` (no torque acts about its own axis); ``I_a`` is its axial
moment and ``I_t`` the moment of rotor and housing about the vertical.

Taking the vertical component of ``dH/dt = τ`` (the mounting passes no torque
about the vertical) with the housing rotating at ``Ω_E + (−α̇) ẑ`` gives, exactly,

    I_t α̈ + I_a ω_s Ω cos λ sin α − A Ω² cos²λ sin α cos α = 0,

``A`` the rotor's transverse moment plus the housing's horizontal moment across
the spin axis minus the one along it (``A ≲ I_t``). The last term is smaller
than the second by at most ``ε = I_t Ω cos λ / (I_a ω_s)`` (about 1e-6 for a
real compass); dropping it leaves the reduced (gyroscopic) model integrated
here, with optional viscous damping ``c`` about the vertical:

    I_t α̈ + c α̇ + I_a ω_s Ω cos λ sin α = 0.

It is a pendulum equation: for ``ω_s > 0`` the stable rest is ``α = 0`` — the
spin axis, and the spin angular momentum with it, points north. The spin itself
never appears except through ``H = I_a ω_s``, so the step is set by the slow
north-seeking period, not by the fast spin.

Series: ``alpha_rad``, ``alpha_rate_rad_s``, ``dissipated_energy_J`` (work done
by the damper). Invariant: ``energy_plus_dissipated_J`` (constant in exact
arithmetic, with or without damping).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from scipy.special import ellipk

from app.physics.core.energy import EnergyParts
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.solvers import OdeSystem
from app.physics.solvers.integrated_model import IntegratedModel
from app.physics.solvers.kernels import RHS_SIGNATURE, kernel
from app.physics.solvers.step_choice import AccuracyTarget

#: Sidereal rotation rate of the Earth (rad/s).
EARTH_RATE_RAD_S = 7.292115e-5
#: Beyond this latitude (deg) the horizontal component of the Earth's rate is too small to use.
MAX_LATITUDE_DEG = 89.9
#: Largest ε = I_t Ω cos λ / (I_a ω_s) for which the reduced model is accepted.
MAX_REDUCTION_RATIO = 0.01
#: RK4 step rule for a full rigid-body integration of the rotor (h·ω_s ≲ 0.1, as in the live scenes).
FULL_MODEL_STEP_RATIO = 0.1


def _check(values: Mapping[str, Any]) -> None:
    latitude = values["latitude_deg"]
    if abs(latitude) > MAX_LATITUDE_DEG:
        raise ParameterError(
            "latitude_deg",
            f"must lie within ±{MAX_LATITUDE_DEG:g}° (got {latitude:g}°): at a pole the Earth's rotation axis is "
            "vertical, "
            "so its horizontal component Ω cos λ, the only part a horizontal spin axis can feel, vanishes and there is "
            "no north for the gyrocompass to seek",
        )
    if values["spin_rad_s"] == 0.0:
        raise ParameterError(
            "spin_rad_s",
            "must be non-zero: without spin there is no angular momentum, no north-seeking torque and the period "
            "would be infinite",
        )
    ratio = reduction_ratio(values)
    if ratio > MAX_REDUCTION_RATIO:
        raise ParameterError(
            "spin_rad_s",
            f"is too small for the gyroscopic (reduced) model: I_t Ω cos λ / (I_a |ω_s|) = {ratio:.3g} must be at most "
            f"{MAX_REDUCTION_RATIO:g} (raise the spin or the rotor inertia, or lower the Earth rate)",
        )


PARAMETERS = ParameterSet(
    (
        Parameter("latitude_deg", "deg", 45.0, -90.0, 90.0, "Latitude λ of the site (positive north)", "λ", step=0.5),
        Parameter(
            "spin_rad_s",
            "rad/s",
            2000.0,
            -50000.0,
            50000.0,
            "Rotor spin ω_s about its axis (positive: spin vector along the axis)",
            "ω_s",
            step=10.0,
        ),
        Parameter(
            "rotor_axial_inertia_kg_m2",
            "kg·m²",
            0.02,
            1e-5,
            10.0,
            "Rotor moment of inertia about its spin axis",
            "I_a",
            scale="log",
        ),
        Parameter(
            "vertical_inertia_kg_m2",
            "kg·m²",
            0.5,
            1e-5,
            100.0,
            "Moment of inertia of rotor and housing about the local vertical",
            "I_t",
            scale="log",
        ),
        Parameter(
            "damping_N_m_s_rad", "N·m·s/rad", 0.0, 0.0, 10.0, "Viscous damping about the vertical", "c", step=1e-4
        ),
        Parameter(
            "alpha0_deg",
            "deg",
            40.0,
            -179.0,
            179.0,
            "Initial azimuth of the spin axis from north (positive toward east)",
            "α₀",
            step=1.0,
        ),
        Parameter("alpha_rate0_rad_s", "rad/s", 0.0, -1.0, 1.0, "Initial azimuth rate α̇₀", "α̇₀", step=0.001),
        Parameter(
            "earth_rate_rad_s",
            "rad/s",
            EARTH_RATE_RAD_S,
            1e-6,
            1.0,
            "Rotation rate of the planet (the Earth: 7.292115e-5 rad/s)",
            "Ω",
            scale="log",
        ),
    ),
    check=_check,
)


def horizontal_earth_rate_rad_s(params: Mapping[str, Any]) -> float:
    """``Ω cos λ`` (rad/s): the part of the planet's rotation along local north."""
    return params["earth_rate_rad_s"] * math.cos(math.radians(params["latitude_deg"]))


def spin_momentum_N_m_s(params: Mapping[str, Any]) -> float:
    """``H = I_a ω_s`` (N·m·s), signed along the spin axis."""
    return params["rotor_axial_inertia_kg_m2"] * params["spin_rad_s"]


def restoring_moment_N_m(params: Mapping[str, Any]) -> float:
    """``K = I_a ω_s Ω cos λ`` (N·m): the north-seeking moment about the vertical is ``−K sin α``."""
    return spin_momentum_N_m_s(params) * horizontal_earth_rate_rad_s(params)


def reduction_ratio(params: Mapping[str, Any]) -> float:
    """``ε = I_t Ω cos λ / (I_a |ω_s|)``: bound on the term the reduced model drops, relative to the one it keeps."""
    return (
        params["vertical_inertia_kg_m2"] * abs(horizontal_earth_rate_rad_s(params)) / abs(spin_momentum_N_m_s(params))
    )


def stable_azimuth_rad(params: Mapping[str, Any]) -> float:
    """Where the axis settles: 0 (north) for ω_s > 0, π for ω_s < 0 (then H points north)."""
    return 0.0 if restoring_moment_N_m(params) > 0.0 else math.pi


def natural_frequency_rad_s(params: Mapping[str, Any]) -> float:
    """``ω_n = √(I_a |ω_s| Ω cos λ / I_t)`` (rad/s): small swings about north."""
    return math.sqrt(abs(restoring_moment_N_m(params)) / params["vertical_inertia_kg_m2"])


def small_angle_period_s(params: Mapping[str, Any]) -> float:
    """``T₀ = 2π √(I_t / (I_a |ω_s| Ω cos λ))`` (s), undamped small swings."""
    return 2.0 * math.pi / natural_frequency_rad_s(params)


def damping_ratio(params: Mapping[str, Any]) -> float:
    """``ζ = c / (2 √(I_t K))`` (dimensionless)."""
    return params["damping_N_m_s_rad"] / (
        2.0 * math.sqrt(params["vertical_inertia_kg_m2"] * abs(restoring_moment_N_m(params)))
    )


def deviation_from_rest_rad(params: Mapping[str, Any], alpha_rad: np.ndarray | float) -> np.ndarray:
    """Signed angle (rad) from the stable rest azimuth, wrapped to (−π, π]."""
    delta = np.asarray(alpha_rad, dtype=float) - stable_azimuth_rad(params)
    return np.mod(delta + np.pi, 2.0 * np.pi) - np.pi


def swing_kinetic_J(params: Mapping[str, Any], alpha_rate_rad_s) -> np.ndarray:
    """``½ I_t α̇²`` (J): the housing's and rotor's turning about the vertical (the spin's own energy is constant)."""
    return 0.5 * params["vertical_inertia_kg_m2"] * np.asarray(alpha_rate_rad_s, dtype=float) ** 2


def gyroscopic_potential_J(params: Mapping[str, Any], alpha_rad) -> np.ndarray:
    """``|K| (1 − cos δ)`` (J), δ the deviation from rest: the work of the north-seeking moment, zero at rest."""
    return abs(restoring_moment_N_m(params)) * (1.0 - np.cos(deviation_from_rest_rad(params, alpha_rad)))


def swing_energy_J(params: Mapping[str, Any], alpha_rad, alpha_rate_rad_s) -> np.ndarray:
    """``½ I_t α̇² + |K| (1 − cos δ)`` (J), δ the deviation from rest: kinetic plus gyroscopic potential."""
    return swing_kinetic_J(params, alpha_rate_rad_s) + gyroscopic_potential_J(params, alpha_rad)


def amplitude_rad(params: Mapping[str, Any]) -> float | None:
    """Undamped swing amplitude about the rest azimuth (rad) from the initial state; None if the axis circulates."""
    energy = float(swing_energy_J(params, math.radians(params["alpha0_deg"]), params["alpha_rate0_rad_s"]))
    k = abs(restoring_moment_N_m(params))
    cosine = 1.0 - energy / k
    if cosine <= -1.0:
        return None
    return math.acos(cosine)


def large_amplitude_period_s(params: Mapping[str, Any], amplitude: float) -> float:
    """Undamped period (s) of a swing of ``amplitude`` rad: ``T = 4 K(m) / ω_n``, ``m = sin²(amplitude/2)``.

    ``K`` is the complete elliptic integral of the first kind (parameter ``m``).
    """
    if not 0.0 <= amplitude < math.pi:
        raise ValueError(f"amplitude must lie in [0, π) rad for a swing (got {amplitude!r})")
    return 4.0 * float(ellipk(math.sin(0.5 * amplitude) ** 2)) / natural_frequency_rad_s(params)


def full_model_steps_per_period(params: Mapping[str, Any]) -> float:
    """RK4 steps a full rigid-body integration would take per north-seeking period (h = 0.1/|ω_s|)."""
    return small_angle_period_s(params) * abs(params["spin_rad_s"]) / FULL_MODEL_STEP_RATIO


@kernel(RHS_SIGNATURE)
def gyrocompass_rhs(t, y, p, dydt):
    """y = [α (rad), α̇ (rad/s), dissipated energy (J)]; p = [K/I_t (1/s²), c/I_t (1/s), c (N·m·s/rad)]."""
    dydt[0] = y[1]
    dydt[1] = -p[0] * math.sin(y[0]) - p[1] * y[1]
    dydt[2] = p[2] * y[1] * y[1]


class Gyrocompass(IntegratedModel):
    """Reduced gyrocompass equation, integrated (the nonlinear pendulum form, any amplitude, with damping)."""

    parameters = PARAMETERS
    methods = ("rk4", "dopri5")
    default_method = "rk4"
    series_units = {"alpha_rad": "rad", "alpha_rate_rad_s": "rad/s", "dissipated_energy_J": "J"}
    invariant_units = {"energy_plus_dissipated_J": "J"}
    accuracy_target = AccuracyTarget(1e-6, "rad", "azimuth α of the spin axis")

    def system(self, params):
        inertia = params["vertical_inertia_kg_m2"]
        damping = params["damping_N_m_s_rad"]
        p = np.array([restoring_moment_N_m(params) / inertia, damping / inertia, damping])
        return OdeSystem(
            rhs=gyrocompass_rhs, parameters=p, state_names=("alpha_rad", "alpha_rate_rad_s", "dissipated_energy_J")
        )

    def initial_state(self, params):
        return np.array([math.radians(params["alpha0_deg"]), params["alpha_rate0_rad_s"], 0.0])

    def fastest_rate_rad_s(self, params, state):
        inertia = params["vertical_inertia_kg_m2"]
        return natural_frequency_rad_s(params) + params["damping_N_m_s_rad"] / inertia + abs(float(state[1]))

    def solution_error(self, params, states, reference):
        """|Δα| (rad) between ``states`` and ``reference`` (N, 3)."""
        return np.abs(np.asarray(states)[:, 0] - np.asarray(reference)[:, 0])

    def series(self, params, t_s, states):
        return {"alpha_rad": states[:, 0], "alpha_rate_rad_s": states[:, 1], "dissipated_energy_J": states[:, 2]}

    def invariants(self, params, states):
        return {"energy_plus_dissipated_J": swing_energy_J(params, states[:, 0], states[:, 1]) + states[:, 2]}

    series_labels = {
        "alpha_rad": "α",
        "alpha_rate_rad_s": "α̇",
        "dissipated_energy_J": "damper's work",
        "energy_plus_dissipated_J": "swing energy + damper's work",
    }

    def energy_parts(self, params, states, *, t_s=None):
        """The swing about the vertical (rotational, ½ I_t α̇²) and the gyroscopic potential |K|(1 − cos δ)."""
        states = np.atleast_2d(states)
        kinetic = swing_kinetic_J(params, states[:, 1])
        return EnergyParts(
            gyroscopic_potential_J(params, states[:, 0]),
            translational_kinetic_J=np.zeros_like(kinetic),
            rotational_kinetic_J=kinetic,
        )

    def energy_note(self, params):
        return (
            "the reduced model's swing energy: the rotor's spin energy (constant) is left out, and the potential is "
            "the work of the north-seeking moment I_a ω_s Ω cos λ sin α, not gravity"
        )

    def invariant_scales(self, params, state):
        # The energy that would carry the axis right round (2|K|) plus the initial swing energy: never zero.
        energy = float(swing_energy_J(params, state[0], state[1]))
        return {"energy_plus_dissipated_J": 2.0 * abs(restoring_moment_N_m(params)) + energy}
