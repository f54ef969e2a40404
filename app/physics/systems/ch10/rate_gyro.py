"""The single-axis rate gyro: a spinning rotor in one spring-restrained, damped gimbal.

Case frame (right-handed): input axis ``z`` (the case turns about it at the
input rate ``Ω(t)``), output axis ``x`` (the gimbal pivots about it, by ``β``),
spin axis ``y`` (the rotor spins at ``ω_s`` about the gimbal's ``y``). With
``H = I_a ω_s`` along ``y``, turning the case about ``z`` needs the moment
``Ω ẑ × H ŷ = −H Ω x̂`` on the rotor; the gimbal spring and damper supply it
as the gimbal swings to positive ``β``. For small ``β`` the output equation is

    I_g β̈ + c β̇ + k β = I_a ω_s Ω(t),

``I_g`` the moment of gimbal and rotor about the output axis. A steady rate
gives ``β_ss = I_a ω_s Ω / k``: the deflection reads the input rate, with gain
``G = I_a ω_s / k`` (rad per rad/s), natural frequency ``ω_n = √(k/I_g)`` and
damping ratio ``ζ = c / (2√(k I_g))``.

The response from rest to a step ``Ω(t) = Ω₀`` or a sine ``Ω(t) = Ω₀ sin(w t)``
is a closed form (under-, critically or over-damped), evaluated here.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.closed_form import ClosedFormModel, ClosedFormSolution, Event
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet

INPUT_KINDS = ("step", "sine")


#: The output equation linearises the gimbal's motion in β (sin β ≈ β, cos β ≈ 1); beyond this |β| (rad,
#: 20°) sin β differs from β by more than 2 %, and the response is outside the model's assumptions.
SMALL_ANGLE_LIMIT_RAD = 0.35
#: A sine input within this fraction of the natural frequency of an undamped gimbal is treated as exact
#: resonance (the general formula's denominator (ω_n² − w²)² would be round-off).
RESONANCE_TOLERANCE = 1e-9


def _check(values: Mapping[str, Any]) -> None:
    if values["spin_rad_s"] == 0.0:
        raise ParameterError(
            "spin_rad_s",
            "must be non-zero: without spin the rotor has no angular momentum and the gimbal cannot sense rate "
            "(the gain I_a ω_s / k would be zero)",
        )


def resonant(params: Mapping[str, Any]) -> bool:
    """Whether the input is a sine at the natural frequency of an undamped gimbal (β then grows linearly in t)."""
    if params["input_kind"] != "sine" or params["damping_N_m_s_rad"] != 0.0:
        return False
    natural = natural_frequency_rad_s(params)
    return abs(params["input_frequency_rad_s"] - natural) <= RESONANCE_TOLERANCE * natural


def small_angle_excess(t_s: np.ndarray, beta_rad: np.ndarray) -> tuple[float, float] | None:
    """``(first time (s), largest |β| (rad))`` if |β| exceeds :data:`SMALL_ANGLE_LIMIT_RAD` at any of ``t_s``, else
    None."""
    over = np.flatnonzero(np.abs(beta_rad) > SMALL_ANGLE_LIMIT_RAD)
    if over.size == 0:
        return None
    return float(np.asarray(t_s)[over[0]]), float(np.max(np.abs(beta_rad)))


def small_angle_warning(first_t_s: float, largest_beta_rad: float) -> str:
    """The sentence a student reads when the response leaves the small-angle model."""
    return (
        f"Outside the model: from t = {first_t_s:.4g} s the gimbal deflection |β| exceeds "
        f"{SMALL_ANGLE_LIMIT_RAD:g} rad "
        f"({math.degrees(SMALL_ANGLE_LIMIT_RAD):.0f}°), reaching {largest_beta_rad:.3g} rad; the output equation "
        "assumes a small β "
        "(sin β ≈ β), so the numbers beyond it are the linear model's, not a real gyro's (a real gimbal hits its "
        "stops)."
    )


PARAMETERS = ParameterSet(
    (
        Parameter(
            "rotor_axial_inertia_kg_m2",
            "kg·m²",
            2e-4,
            1e-7,
            1.0,
            "Rotor moment of inertia about its spin axis",
            "I_a",
            scale="log",
        ),
        Parameter(
            "spin_rad_s",
            "rad/s",
            1000.0,
            -30000.0,
            30000.0,
            "Rotor spin ω_s (held constant by its motor)",
            "ω_s",
            step=10.0,
        ),
        Parameter(
            "gimbal_inertia_kg_m2",
            "kg·m²",
            5e-3,
            1e-6,
            10.0,
            "Moment of inertia of gimbal and rotor about the output axis",
            "I_g",
            scale="log",
        ),
        Parameter(
            "stiffness_N_m_rad",
            "N·m/rad",
            0.5,
            1e-4,
            1000.0,
            "Torsion-spring stiffness k restraining the gimbal",
            "k",
            scale="log",
        ),
        Parameter("damping_N_m_s_rad", "N·m·s/rad", 0.02, 0.0, 10.0, "Viscous damping c on the gimbal", "c", step=1e-3),
        Parameter(
            "input_kind",
            "",
            "step",
            kind="choice",
            choices=INPUT_KINDS,
            label="input",
            description="Input rate: a step to Ω₀ at t = 0, or a sine Ω₀ sin(w t)",
        ),
        Parameter(
            "input_rate_rad_s",
            "rad/s",
            0.5,
            -5.0,
            5.0,
            "Input rate Ω₀ about the case's input axis (step height or sine amplitude)",
            "Ω₀",
            step=0.05,
        ),
        Parameter(
            "input_frequency_rad_s", "rad/s", 5.0, 0.01, 500.0, "Angular frequency w of a sine input", "w", scale="log"
        ),
    ),
    check=_check,
)


def angular_momentum_N_m_s(params: Mapping[str, Any]) -> float:
    """``H = I_a ω_s`` (N·m·s), along the spin axis."""
    return params["rotor_axial_inertia_kg_m2"] * params["spin_rad_s"]


def steady_gain_s(params: Mapping[str, Any]) -> float:
    """``G = I_a ω_s / k``: steady deflection per unit input rate (rad per rad/s, i.e. s)."""
    return angular_momentum_N_m_s(params) / params["stiffness_N_m_rad"]


def natural_frequency_rad_s(params: Mapping[str, Any]) -> float:
    """``ω_n = √(k / I_g)`` (rad/s)."""
    return math.sqrt(params["stiffness_N_m_rad"] / params["gimbal_inertia_kg_m2"])


def damping_ratio(params: Mapping[str, Any]) -> float:
    """``ζ = c / (2 √(k I_g))`` (dimensionless)."""
    return params["damping_N_m_s_rad"] / (2.0 * math.sqrt(params["stiffness_N_m_rad"] * params["gimbal_inertia_kg_m2"]))


def critical_damping_N_m_s_rad(params: Mapping[str, Any]) -> float:
    """``c_crit = 2 √(k I_g)`` (N·m·s/rad)."""
    return 2.0 * math.sqrt(params["stiffness_N_m_rad"] * params["gimbal_inertia_kg_m2"])


def frequency_response(params: Mapping[str, Any], frequency_rad_s: float) -> tuple[float, float]:
    """Steady sine response: (amplitude ratio |β|/|Ω| in s, phase lag of β behind Ω in rad, in [0, π])."""
    r = frequency_rad_s / natural_frequency_rad_s(params)
    zeta = damping_ratio(params)
    denominator = math.hypot(1.0 - r * r, 2.0 * zeta * r)
    if denominator == 0.0:  # undamped at resonance: no steady sine, the swing −t cos ω_n t grows and lags Ω by 90°
        return math.inf, 0.5 * math.pi
    return abs(steady_gain_s(params)) / denominator, math.atan2(2.0 * zeta * r, 1.0 - r * r)


def free_response(x0: float, v0: float, zeta: float, omega_n: float, t_s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Solution of ``ẍ + 2ζω_n ẋ + ω_n² x = 0`` with ``x(0) = x0``, ``ẋ(0) = v0``: ``(x, ẋ)`` at ``t_s``.

    Written as ``x = x0 C(t) + v0 S(t)`` with the impulse response ``S`` (S(0) = 0, Ṡ(0) = 1)
    and ``C = E + σS``, ``E = e^{−σt}·(cos ω_d t | 1 | cosh γt)``, ``σ = ζω_n``, so the under-,
    critically and over-damped cases share one form and stay accurate near ζ = 1 (no
    difference of nearly equal exponentials).
    """
    t = np.asarray(t_s, dtype=float)
    sigma = zeta * omega_n
    if zeta < 1.0:
        omega_d = omega_n * math.sqrt((1.0 - zeta) * (1.0 + zeta))
        decay = np.exp(-sigma * t)
        e = decay * np.cos(omega_d * t)
        s = decay * np.sin(omega_d * t) / omega_d
    elif zeta == 1.0:
        decay = np.exp(-sigma * t)
        e = decay
        s = t * decay
    else:
        gamma = omega_n * math.sqrt((zeta - 1.0) * (zeta + 1.0))
        slow = np.exp((gamma - sigma) * t)  # e^{−σt}·e^{γt}, never overflows (γ < σ)
        fast_ratio = np.exp(-2.0 * gamma * t)
        e = 0.5 * slow * (1.0 + fast_ratio)
        s = slow * (-np.expm1(-2.0 * gamma * t)) / (2.0 * gamma)
    c = e + sigma * s
    s_dot = e - sigma * s
    x = x0 * c + v0 * s
    x_dot = -x0 * omega_n**2 * s + v0 * s_dot
    return x, x_dot


def input_rate(params: Mapping[str, Any], t_s: np.ndarray) -> np.ndarray:
    """``Ω(t)`` (rad/s) about the input axis, for t ≥ 0."""
    t = np.asarray(t_s, dtype=float)
    if params["input_kind"] == "step":
        return np.full_like(t, params["input_rate_rad_s"])
    return params["input_rate_rad_s"] * np.sin(params["input_frequency_rad_s"] * t)


def case_angle_rad(params: Mapping[str, Any], t_s: np.ndarray | float) -> np.ndarray:
    """Turn of the case about the input axis since t = 0, ``∫₀ᵗ Ω dt`` (rad)."""
    t = np.asarray(t_s, dtype=float)
    rate = params["input_rate_rad_s"]
    if params["input_kind"] == "step":
        return rate * t
    w = params["input_frequency_rad_s"]
    return rate * (1.0 - np.cos(w * t)) / w


@dataclass(frozen=True)
class GimbalResponse:
    """β (rad), β̇ (rad/s) and the input Ω (rad/s) at the requested times."""

    beta_rad: np.ndarray
    beta_rate_rad_s: np.ndarray
    input_rate_rad_s: np.ndarray


def gimbal_response(params: Mapping[str, Any], t_s: np.ndarray | float) -> GimbalResponse:
    """Closed-form response from rest (β = β̇ = 0 at t = 0) of the small-angle output equation."""
    t = np.atleast_1d(np.asarray(t_s, dtype=float))
    omega_n = natural_frequency_rad_s(params)
    zeta = damping_ratio(params)
    gain = steady_gain_s(params)
    rate = params["input_rate_rad_s"]
    if resonant(params):
        # β̈ + ω_n² β = G Ω₀ ω_n² sin ω_n t from rest: β = (G Ω₀ / 2)(sin ω_n t − ω_n t cos ω_n t), growing linearly in
        # t.
        phase = omega_n * t
        beta = 0.5 * gain * rate * (np.sin(phase) - phase * np.cos(phase))
        beta_rate = 0.5 * gain * rate * omega_n * phase * np.sin(phase)
        return GimbalResponse(beta, beta_rate, input_rate(params, t))
    if params["input_kind"] == "step":
        forced, forced_rate = np.full_like(t, gain * rate), np.zeros_like(t)
        forced0, forced_rate0 = gain * rate, 0.0
    else:
        # Particular solution β_p = G Ω₀ ω_n² [(ω_n² − w²) sin wt − 2ζω_n w cos wt] / D.
        w = params["input_frequency_rad_s"]
        d = (omega_n**2 - w**2) ** 2 + (2.0 * zeta * omega_n * w) ** 2
        a = gain * rate * omega_n**2 * (omega_n**2 - w**2) / d
        b = -gain * rate * omega_n**2 * 2.0 * zeta * omega_n * w / d
        forced = a * np.sin(w * t) + b * np.cos(w * t)
        forced_rate = w * (a * np.cos(w * t) - b * np.sin(w * t))
        forced0, forced_rate0 = b, w * a
    free, free_rate = free_response(-forced0, -forced_rate0, zeta, omega_n, t)
    beta = forced + free
    beta_rate = forced_rate + free_rate
    return GimbalResponse(beta, beta_rate, input_rate(params, t))


class RateGyro(ClosedFormModel):
    """Response of the spring-restrained rate gyro to a step or sine input rate, from rest."""

    parameters = PARAMETERS
    series_units = {
        "beta_rad": "rad",
        "beta_rate_rad_s": "rad/s",
        "input_rate_rad_s": "rad/s",
        "indicated_rate_rad_s": "rad/s",
        "case_angle_rad": "rad",
    }
    description = "Linear second-order response from rest (under-, critically or over-damped closed form)"

    def evaluate(self, params: Mapping[str, Any], t_s: np.ndarray) -> ClosedFormSolution:
        response = gimbal_response(params, t_s)
        excess = small_angle_excess(t_s, response.beta_rad)
        warning = small_angle_warning(*excess) if excess else ""
        return ClosedFormSolution(
            warning=warning,
            events=[Event(excess[0], "outside-model", warning)] if excess else [],
            series={
                "beta_rad": response.beta_rad,
                "beta_rate_rad_s": response.beta_rate_rad_s,
                "input_rate_rad_s": response.input_rate_rad_s,
                "indicated_rate_rad_s": response.beta_rad / steady_gain_s(params),
                "case_angle_rad": case_angle_rad(params, t_s),
            },
        )
