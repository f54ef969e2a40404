"""The Foucault pendulum: a spherical pendulum seen from the rotating Earth.

Frame: the local frame of :mod:`app.physics.systems.earth` (x east, y north, z up along
the plumb line), fixed to the ground. The bob hangs at the origin when at rest;
the pivot is at ``(0, 0, L)``. State ``y = [x, y, z, v_x, v_y, v_z]``: the bob's
position (m) and its velocity relative to the ground (m/s), local frame.

Equations (per unit mass): ``r̈ = −g Z − 2 Ω × ṙ + μ u`` with ``u = r − pivot`` the
string vector and ``μ u`` the string's pull. ``μ`` keeps the string length fixed:
differentiating ``|u|² = L²`` twice gives ``u·r̈ + |ṙ|² = 0``, so
``μ = −(u·f + |ṙ|²)/|u|²`` where ``f = −g Z − 2 Ω × ṙ``. The centrifugal part of
the Earth's rotation is inside g (see :mod:`app.physics.systems.earth`); with an
exaggerated Earth rate the centrifugal term relative to the pivot, Ω²·L, is also
left out, so the model stays "the Earth's rotation, only faster".
After each step the state is projected back onto ``|u| = L``, ``u·ṙ = 0``.

Conserved: the **Jacobi integral** ``½|ṙ|² + g z`` (J/kg): the Coriolis force is
perpendicular to the velocity and the string's pull to the path, so neither does
work in the Earth's frame.

For small swings the horizontal motion ``ξ = x + i y`` obeys
``ξ̈ + 2iΩ_z ξ̇ + ω₀² ξ = 0`` (Ω_z = Ω sin λ, ω₀² = g/L), whose solution
``ξ = e^{−iΩ_z t}(A e^{iω't} + B e^{−iω't})``, ``ω' = √(ω₀² + Ω_z²)``, is an ellipse of
fixed shape turning clockwise (seen from above, for Ω_z > 0) at exactly Ω_z:
:func:`small_amplitude_solution`. Finite swings add the spherical pendulum's own
slow turning of the ellipse (about ⅜ ω₀ a b / L² for semi-axes a, b).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.core.energy import EnergyParts
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.solvers.integrated_model import IntegratedModel
from app.physics.solvers.kernels import PROJECT_SIGNATURE, RHS_SIGNATURE, kernel
from app.physics.solvers.step_choice import AccuracyTarget
from app.physics.solvers.system import OdeSystem
from app.physics.systems.earth import (
    EARTH_RATE_RAD_S,
    STANDARD_GRAVITY_M_S2,
    bearing_deg_from_east_north,
    direction_from_bearing,
    earth_rate_local,
    latitude_parameter,
    vertical_earth_rate_rad_s,
)

STATE_NAMES = ("x_east", "y_north", "z_up", "v_east", "v_north", "v_up")
RELEASES = ("from rest", "from the centre")
#: Largest horizontal amplitude as a fraction of the string length (the swing stays below 64°).
MAX_AMPLITUDE_FRACTION = 0.9


def _check(values: Mapping[str, Any]) -> None:
    limit = MAX_AMPLITUDE_FRACTION * values["length_m"]
    if values["amplitude_m"] > limit:
        raise ParameterError(
            "amplitude_m",
            f"must be at most {MAX_AMPLITUDE_FRACTION:g} × the string length = {limit:.4g} m "
            f"(the bob cannot swing out further than the string is long)",
        )


PARAMETERS = ParameterSet(
    (
        Parameter(
            "length_m",
            "m",
            10.0,
            0.5,
            100.0,
            "Length L of the string from pivot to bob",
            "string length L",
            scale="log",
        ),
        Parameter(
            "amplitude_m", "m", 1.0, 0.001, 90.0, "Horizontal amplitude a of the swing", "amplitude a", scale="log"
        ),
        latitude_parameter(48.85),
        Parameter(
            "earth_rate_factor",
            "×",
            1000.0,
            1.0,
            5000.0,
            "EXAGGERATION: the Earth's rotation rate is multiplied by this factor so the swing plane turns in "
            "minutes instead of a day and a half (1 = the real Earth, 7.292115e-5 rad/s)",
            "Earth-rate exaggeration",
            scale="log",
        ),
        Parameter(
            "release",
            "",
            RELEASES[0],
            kind="choice",
            choices=RELEASES,
            label="release",
            description="'from rest': pulled aside and let go (a rosette with sharp points); "
            "'from the centre': pushed through the rest position (a rosette of loops through the centre)",
        ),
        Parameter(
            "swing_bearing_deg",
            "deg",
            90.0,
            0.0,
            180.0,
            "Compass bearing of the first swing (0 = north–south, 90 = east–west)",
            "first swing bearing",
            step=1.0,
        ),
        Parameter(
            "g_m_s2",
            "m/s²",
            STANDARD_GRAVITY_M_S2,
            0.1,
            30.0,
            "Gravitational acceleration along the plumb line",
            "g",
            step=0.001,
        ),
    ),
    check=_check,
)


def earth_rate_vector(params: Mapping[str, Any]) -> np.ndarray:
    """The (possibly exaggerated) Earth rotation in the local frame (rad/s), shape (3,)."""
    return earth_rate_local(params["latitude_deg"], EARTH_RATE_RAD_S * params["earth_rate_factor"])


def natural_frequency_rad_s(params: Mapping[str, Any]) -> float:
    """ω₀ = √(g/L) (rad/s)."""
    return math.sqrt(params["g_m_s2"] / params["length_m"])


def clockwise_precession_rate_rad_s(params: Mapping[str, Any]) -> float:
    """Ω sin λ at the scene's (exaggerated) Earth rate: the swing plane's turning rate relative to the
    ground, positive clockwise seen from above (northern hemisphere), rad/s."""
    return vertical_earth_rate_rad_s(params["latitude_deg"], EARTH_RATE_RAD_S * params["earth_rate_factor"])


def expected_clockwise_rate_rad_s(params: Mapping[str, Any]) -> float:
    """Ω sin λ corrected for the swing's finite size (rad/s, clockwise from above positive).

    A spherical pendulum's elliptical path turns by itself, in the sense the bob
    goes round, at about ``⅜ h_z / L²`` (Airy's result for small swings), with
    ``h_z = (r × w)_z`` the bob's angular momentum per unit mass about the vertical
    measured against non-turning axes (``w = v + Ω_z Z × r``). Released from rest
    the bob has ``h_z = Ω_z a²``, so the swing plane falls behind Ω sin λ by the
    fraction ``⅜ (a/L)²``; pushed through the centre it has ``h_z = 0`` and no lag.
    """
    omega_z = clockwise_precession_rate_rad_s(params)
    y0 = initial_state(params)
    x, y = y0[0], y0[1]
    wx, wy = y0[3] - omega_z * y, y0[4] + omega_z * x
    h_z = x * wy - y * wx
    return omega_z - 0.375 * h_z / params["length_m"] ** 2


def kernel_parameters(params: Mapping[str, Any]) -> np.ndarray:
    """``p = [g, L, Ω_east, Ω_north, Ω_up]`` for the kernels."""
    return np.array([params["g_m_s2"], params["length_m"], *earth_rate_vector(params)], dtype=float)


def initial_state(params: Mapping[str, Any]) -> np.ndarray:
    """Bob at the amplitude and at rest ("from rest"), or at the centre with the speed that reaches it."""
    L, a, g = params["length_m"], params["amplitude_m"], params["g_m_s2"]
    direction = direction_from_bearing(params["swing_bearing_deg"])
    rise = L - math.sqrt(L * L - a * a)  # height of the bob at the amplitude above its rest position
    if params["release"] == RELEASES[0]:
        position, velocity = a * direction + np.array([0.0, 0.0, rise]), np.zeros(3)
    else:
        position, velocity = np.zeros(3), math.sqrt(2.0 * g * rise) * direction
    return np.concatenate([position, velocity])


@kernel(RHS_SIGNATURE)
def foucault_rhs(t, y, p, dydt):
    """``[ṙ, r̈]`` of the spherical pendulum in the Earth's frame (see the module docstring)."""
    g, L, ox, oy, oz = p[0], p[1], p[2], p[3], p[4]
    vx, vy, vz = y[3], y[4], y[5]
    ux, uy, uz = y[0], y[1], y[2] - L
    # f = −g Z − 2 Ω × v
    fx = -2.0 * (oy * vz - oz * vy)
    fy = -2.0 * (oz * vx - ox * vz)
    fz = -g - 2.0 * (ox * vy - oy * vx)
    mu = -(ux * fx + uy * fy + uz * fz + vx * vx + vy * vy + vz * vz) / (ux * ux + uy * uy + uz * uz)
    dydt[0] = vx
    dydt[1] = vy
    dydt[2] = vz
    dydt[3] = fx + mu * ux
    dydt[4] = fy + mu * uy
    dydt[5] = fz + mu * uz


@kernel(PROJECT_SIGNATURE)
def keep_string_length(y, p):
    """Put the bob back at distance L from the pivot and remove its velocity along the string."""
    L = p[1]
    ux, uy, uz = y[0], y[1], y[2] - L
    norm = math.sqrt(ux * ux + uy * uy + uz * uz)
    scale = L / norm
    ux *= scale
    uy *= scale
    uz *= scale
    y[0] = ux
    y[1] = uy
    y[2] = uz + L
    along = (ux * y[3] + uy * y[4] + uz * y[5]) / (L * L)
    y[3] -= along * ux
    y[4] -= along * uy
    y[5] -= along * uz


def relative_kinetic_J_kg(states: np.ndarray) -> np.ndarray:
    """``½|ṙ|²`` (J/kg) of states (..., 6): the bob's kinetic energy relative to the ground."""
    return 0.5 * np.sum(np.asarray(states, dtype=float)[..., 3:6] ** 2, axis=-1)


def gravity_potential_J_kg(params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
    """``g z`` (J/kg) of states (..., 6), zero at the bob's rest position."""
    return params["g_m_s2"] * np.asarray(states, dtype=float)[..., 2]


def jacobi_integral_J_kg(params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
    """``½|ṙ|² + g z`` (J/kg) of states (..., 6): conserved in the rotating frame."""
    return relative_kinetic_J_kg(states) + gravity_potential_J_kg(params, states)


def swing_plane_bearing_deg(params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
    """Compass bearing (deg in [0, 180), clockwise from north) of the swing's long axis, states (N, 6).

    The long axis of the ellipse comes from the tensor ``ω'² r rᵀ + w wᵀ`` of the
    horizontal motion, with ``w = v + Ω_z Z × r`` the velocity measured against
    non-turning axes: for the small-amplitude motion that tensor is constant in
    those axes (it is the conserved Fradkin tensor of an isotropic oscillator),
    so its principal direction is the swing plane at every instant, not only at
    the ends of a swing.
    """
    states = np.atleast_2d(np.asarray(states, dtype=float))
    omega_z = float(earth_rate_vector(params)[2])
    omega_sq = natural_frequency_rad_s(params) ** 2 + omega_z**2
    x, y = states[:, 0], states[:, 1]
    wx = states[:, 3] - omega_z * y
    wy = states[:, 4] + omega_z * x
    txx = omega_sq * x * x + wx * wx
    tyy = omega_sq * y * y + wy * wy
    txy = omega_sq * x * y + wx * wy
    angle_east_ccw = 0.5 * np.arctan2(2.0 * txy, txx - tyy)
    return np.mod(90.0 - np.degrees(angle_east_ccw), 180.0)


def small_amplitude_solution(params: Mapping[str, Any], t_s: np.ndarray) -> np.ndarray:
    """Horizontal position (east, north) in m, shape (N, 2), of the linearised motion from the same start.

    ``ξ = x + iy = e^{−iΩ_z t}(A e^{iω't} + B e^{−iω't})`` with ``A + B = ξ₀`` and
    ``iω'(A − B) = ξ̇₀ + iΩ_z ξ₀`` (the vertical motion and the horizontal part of
    Ω enter only at second order in the amplitude).
    """
    t = np.asarray(t_s, dtype=float)
    y0 = initial_state(params)
    omega_z = float(earth_rate_vector(params)[2])
    omega_p = math.sqrt(natural_frequency_rad_s(params) ** 2 + omega_z**2)
    xi0 = complex(y0[0], y0[1])
    xi_dot0 = complex(y0[3], y0[4])
    difference = (xi_dot0 + 1j * omega_z * xi0) / (1j * omega_p)
    A, B = 0.5 * (xi0 + difference), 0.5 * (xi0 - difference)
    xi = np.exp(-1j * omega_z * t) * (A * np.exp(1j * omega_p * t) + B * np.exp(-1j * omega_p * t))
    return np.stack([xi.real, xi.imag], axis=-1)


class FoucaultPendulum(IntegratedModel):
    parameters = PARAMETERS
    methods = ("rk4", "dopri5")
    default_method = "rk4"
    series_units = {"bob_east": "m", "bob_north": "m", "bob_up": "m", "swing_plane_bearing": "deg"}
    invariant_units = {"jacobi_integral": "J/kg", "string_length_error": "m"}
    accuracy_target = AccuracyTarget(
        1e-6, "", "bob position and velocity: largest component error relative to the largest component"
    )
    auto_methods = ("rk4",)  # the simulate contract answers with RK4; the target sets its step

    def system(self, params):
        return OdeSystem(
            rhs=foucault_rhs, parameters=kernel_parameters(params), state_names=STATE_NAMES, project=keep_string_length
        )

    def initial_state(self, params):
        return initial_state(params)

    def fastest_rate_rad_s(self, params, state):
        """The faster of ω₀ and the largest swing speed over L, plus 2Ω (the Coriolis rate)."""
        g, L = params["g_m_s2"], params["length_m"]
        speed_max = math.sqrt(max(2.0 * float(jacobi_integral_J_kg(params, state)), 0.0))
        return max(math.sqrt(g / L), speed_max / L) + 2.0 * float(np.linalg.norm(earth_rate_vector(params)))

    def series(self, params, t_s, states):
        return {
            "bob_east": states[:, 0].copy(),
            "bob_north": states[:, 1].copy(),
            "bob_up": states[:, 2].copy(),
            "swing_plane_bearing": np.degrees(
                np.unwrap(np.radians(swing_plane_bearing_deg(params, states)), period=math.pi)
            ),
        }

    def invariants(self, params, states):
        states = np.asarray(states, dtype=float)
        string = np.linalg.norm(states[..., 0:3] - np.array([0.0, 0.0, params["length_m"]]), axis=-1)
        return {
            "jacobi_integral": jacobi_integral_J_kg(params, states),
            "string_length_error": string - params["length_m"],
        }

    series_labels = {
        "bob_east": "x (east)",
        "bob_north": "y (north)",
        "bob_up": "z (up)",
        "swing_plane_bearing": "swing plane bearing",
        "jacobi_integral": "½|ṙ|² + g z",
        "string_length_error": "|r − pivot| − L",
    }

    def energy_parts(self, params, states, *, t_s=None):
        """For a 1 kg bob (the model is per unit mass): ½|ṙ|² relative to the ground (a point: no rotation) and g z."""
        states = np.atleast_2d(states)
        kinetic = relative_kinetic_J_kg(states)
        return EnergyParts(
            gravity_potential_J_kg(params, states),
            translational_kinetic_J=kinetic,
            rotational_kinetic_J=np.zeros_like(kinetic),
        )

    def energy_note(self, params):
        return (
            "energies of a 1 kg bob (the motion does not depend on its mass), with its speed measured against "
            "the turning ground"
        )

    def invariant_scales(self, params, state):
        # The swing's energy above the rest position (the Jacobi integral is zero there).
        rise = params["length_m"] - math.sqrt(params["length_m"] ** 2 - params["amplitude_m"] ** 2)
        return {"jacobi_integral": max(params["g_m_s2"] * rise, 1e-300), "string_length_error": params["length_m"]}


class ApexTracker:
    """Measures the swing plane's turning from the bob's turning points (no theory involved).

    Feed it the bob's horizontal position frame by frame; at each local maximum
    of the distance from the rest position it records the bearing of the bob,
    folded to [0°, 180°) and unwrapped, so successive apexes on opposite sides
    count as the same plane. ``clockwise_rate_rad_s`` is the least-squares slope
    of bearing against time (positive clockwise seen from above).
    """

    def __init__(self) -> None:
        self.times_s: list[float] = []
        self.bearings_rad: list[float] = []
        self._recent: list[tuple[float, float, float]] = []

    def add(self, t_s: float, east_m: float, north_m: float) -> None:
        self._recent.append((t_s, east_m, north_m))
        if len(self._recent) < 3:
            return
        (_, e0, n0), (t1, e1, n1), (_, e2, n2) = self._recent[-3:]
        self._recent = self._recent[-2:]
        r0, r1, r2 = math.hypot(e0, n0), math.hypot(e1, n1), math.hypot(e2, n2)
        if r1 > r0 and r1 >= r2:
            self._record(t1, math.radians(float(bearing_deg_from_east_north(e1, n1))))

    def _record(self, t_s: float, bearing_rad: float) -> None:
        folded = bearing_rad % math.pi
        if self.bearings_rad:
            previous = self.bearings_rad[-1]
            folded += math.pi * round((previous - folded) / math.pi)
        self.times_s.append(t_s)
        self.bearings_rad.append(folded)

    @property
    def count(self) -> int:
        return len(self.times_s)

    def clockwise_rate_rad_s(self) -> float | None:
        """Slope of the apex bearings (rad/s, clockwise positive), or None before three apexes."""
        if len(self.times_s) < 3:
            return None
        t = np.asarray(self.times_s)
        b = np.asarray(self.bearings_rad)
        return float(np.polyfit(t - t[0], b, 1)[0])


def apex_bearings(t_s: np.ndarray, east_m: np.ndarray, north_m: np.ndarray) -> ApexTracker:
    """Run an :class:`ApexTracker` over a sampled path (arrays of equal length)."""
    tracker = ApexTracker()
    for t, e, n in zip(np.asarray(t_s, float), np.asarray(east_m, float), np.asarray(north_m, float)):
        tracker.add(float(t), float(e), float(n))
    return tracker
