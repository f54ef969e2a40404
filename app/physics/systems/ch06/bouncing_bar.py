"""A uniform slender bar dropped on a rigid floor: a sequence of impacts, found with events and reset maps.

Frame: fixed x (along the floor) and z (up); the bar moves in the xz plane. Its
centre of mass is at ``(x, z)``; ``θ`` is the angle of the bar from the floor,
counter-clockwise from +x towards +z, and ``θ̇`` its rate (rad/s). End A is at
``centre − (L/2) u`` and end B at ``centre + (L/2) u``, ``u = (cos θ, sin θ)``,
so their heights are ``z ∓ (L/2) sin θ``. A point of the bar at lever arm ``r``
(m, from the centre) moves at ``v_c + θ̇ (−r_z, r_x)``.

Parameters (API contract names): ``length_m``, ``mass_kg``, ``drop_height_m``
(centre height at release, from rest), ``angle0_deg`` (from the floor),
``restitution`` (Stronge's energetic coefficient e), ``friction_coefficient``
(Coulomb μ at the floor) and ``g_m_s2``. Series: ``angle`` (θ, rad),
``centre_height_m``, ``energy_J`` (kinetic + potential), ``impact_count``,
``energy_lost_J`` (summed over impacts, settling and sliding to rest).

Between impacts the bar is in free flight (ẍ = 0, z̈ = −g, θ̈ = 0). Each end's
height is an event function (falling direction); the reset map applies the
shared impulse law :func:`app.physics.systems.ch06.impact.resolve_impact` at
the touching end, in the contact frame ``[normal = +z, tangent = +x]``, with

    W = (1/m) 1 + (1/I) q qᵀ,   q = (r_x, −r_z),   I = m L²/12,

the inverse effective mass of the end at lever arm ``r``: an impulse
``P = [Pn, Pt]`` changes the end's ``[vn, vt]`` by ``W P`` (the impulse moves
the centre by ``P/m`` and turns the bar by ``(r_x Pn − r_z Pt)/I``).

A bar landing flat (both ends within :data:`TOUCH_TOLERANCE_M` of the floor,
both approaching) gets one simultaneous two-contact impulse. Flat, both lever
arms are horizontal, so the impact splits exactly into two independent modes:
the *common* mode (centre velocity, both ends together: ``W = (1/m) 1`` on
``[ż, ẋ]`` for the summed impulse) and the *rocking* mode (``w = (L/2) θ̇``,
half the difference of the ends' normal velocities: ``W = 3/m`` for the impulse
``2Q = P_B − P_A`` that does work on it, frictionless,
since tangential impulses on horizontal lever arms exert no moment). Each mode
goes through the same impulse law; with S the summed normal impulse,
``(1 + e) m |ż|``, the two normal impulses are ``P_A,B = S/2 ∓ Q`` with
``|Q| = (1 + e) m |w| / 6``, positive because both ends approach (|w| < |ż|).
For the symmetric landing Q = 0: equal impulses and no spin. A landing less
flat than that is a sequence of single impacts (the lesson shows how much the
order of two nearly simultaneous strikes matters).

The Zeno cascade (ever shorter bounces in finite time) is cut off: when a
struck end approaches or rebounds slower than :data:`REST_SPEED_M_S` and the bar is
nearly flat (raised end at most :data:`FLAT_FRACTION` of L up), it is laid flat on the floor (mode ``RESTING``) and
slides to a
stop under Coulomb friction; if it is still tilted, the model stops there
(mode ``SETTLED_ON_END``: staying in contact on one end, pivoting or sliding,
is a continuous-contact motion this impact model does not follow). Every joule
that leaves the bar is booked in ``energy_lost_J``, so kinetic + potential +
lost stays equal to the initial energy.

The reset map and its helpers are ``register_jitable``: the compiled reset
kernel runs them with the compiled impulse law
(:func:`~app.physics.systems.ch06.impact.impact_core`) inlined, and the same
source runs as plain Python for the kernel's Python twin and for
:func:`reset_state` called from Python. numba's disk cache keys a compiled kernel on
its own file only, so a change to ``impact.py`` must come with a change here (this
file's date is what makes the reset kernel compile again: last for the restitution
root at zero normal speed, 2026-11-29).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from numba.extending import register_jitable

from app.physics.bodies.inertia import slender_rod
from app.physics.core.energy import EnergyParts
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.solvers import Events, OdeSystem
from app.physics.solvers.integrated_model import IntegratedModel, ModelLimit
from app.physics.solvers.kernels import (
    EVENTS_SIGNATURE,
    RESET_SIGNATURE,
    RHS_SIGNATURE,
    kernel,
)
from app.physics.solvers.step_choice import AccuracyTarget
from app.physics.systems.ch06.impact import (
    IMPACT_OUT_SIZE,
    OUT_ENERGY_LOSS,
    OUT_NORMAL_IMPULSE,
    OUT_SLIP_CODE,
    OUT_TANGENTIAL_IMPULSE,
    SLIP_STATES,
    impact_core,
)

#: Lowest release height of the lower end above the floor (m): the bar starts in flight.
START_CLEARANCE_M = 1e-3


def _check(values: Mapping[str, Any]) -> None:
    """The bar must start above the floor (ParameterError naming ``drop_height_m``)."""
    lowest = values["drop_height_m"] - 0.5 * values["length_m"] * math.sin(math.radians(values["angle0_deg"]))
    if lowest < START_CLEARANCE_M:
        raise ParameterError(
            "drop_height_m",
            f"must put the lower end at least {START_CLEARANCE_M * 1e3:g} mm above the floor: with L = "
            f"{values['length_m']:g} m "
            f"at {values['angle0_deg']:g}° the centre needs h₀ ≥ "
            f"{values['drop_height_m'] - lowest + START_CLEARANCE_M:.4g} m",
        )


PARAMETERS = ParameterSet(
    (
        Parameter("length_m", "m", 1.0, 0.05, 5.0, "Length of the bar", "L", step=0.01),
        Parameter("mass_kg", "kg", 1.0, 0.01, 100.0, "Mass of the bar", "m", scale="log"),
        Parameter(
            "drop_height_m", "m", 1.0, 0.0, 10.0, "Height of the centre of mass at release (from rest)", "h₀", step=0.01
        ),
        Parameter("angle0_deg", "deg", 30.0, 0.0, 90.0, "Angle of the bar from the floor at release", "θ₀", step=0.5),
        Parameter("restitution", "", 0.6, 0.0, 1.0, "Energetic coefficient of restitution e (Stronge)", "e", step=0.01),
        Parameter(
            "friction_coefficient", "", 0.3, 0.0, 2.0, "Coulomb friction coefficient μ at the floor", "μ", step=0.01
        ),
        Parameter("g_m_s2", "m/s²", 9.807, 0.1, 30.0, "Gravitational acceleration", "g", step=0.001),
    ),
    check=_check,
)


# -- named state slots ---------------------------------------------------------------
X, Z, THETA, VX, VZ, OMEGA = range(6)
MODE, IMPACTS, LOST, LAST_LOSS, LAST_T, PN_A, PT_A, PN_B, PT_B, SLIP = range(6, 16)
STATE_NAMES = (
    "x_m",
    "z_m",
    "theta_rad",
    "vx_m_s",
    "vz_m_s",
    "theta_dot_rad_s",
    "mode",
    "impact_count",
    "energy_lost_J",
    "last_energy_loss_J",
    "last_impact_t_s",
    "impulse_normal_a_N_s",
    "impulse_tangential_a_N_s",
    "impulse_normal_b_N_s",
    "impulse_tangential_b_N_s",
    "slip_state",
)
#: Values of the ``mode`` slot.
FLIGHT, RESTING, SETTLED_ON_END = 0.0, 1.0, 2.0
MODE_NAMES = {FLIGHT: "flight", RESTING: "resting", SETTLED_ON_END: "settled on one end"}
#: Values of the ``slip_state`` slot: 0 before the first impact, then 1 + the index in SLIP_STATES.
SLIP_NAMES = ("no impact yet", *SLIP_STATES)
# Parameter slots p = [m, L, I, g, e, μ].
P_MASS, P_LENGTH, P_INERTIA, P_G, P_E, P_MU = range(6)
END_A, END_B = 0, 1
EVENT_END_A, EVENT_END_B, EVENT_STOPS_SLIDING = range(3)

#: An end this close to the floor (m) at the other end's impact touches too: the landing is simultaneous.
#: Events put the striking end within ~1e-12 m of the floor; a flat bar's ends are at exactly equal heights.
TOUCH_TOLERANCE_M = 1e-8
#: An end touching the floor and approaching slower than this (m/s) is grazing it: round-off after an
#: impact (a plastic one leaves vn ≈ ±1e-17 m/s), not a new impact.
GRAZING_SPEED_M_S = 1e-9
#: A struck end approaching or rebounding slower than this (m/s) ends the bouncing (a 0.05 m/s rebound rises 0.13 mm).
REST_SPEED_M_S = 0.05
#: A bar whose raised end is at most this fraction of L above the floor at such a slow impact is laid flat.
FLAT_FRACTION = 0.02
#: Longest integration step (s). Heights are checked at each step's ends and middle, so only a dip of an end
#: below the floor lasting under half a step could go unseen (a grazing touch); with the end's acceleration
#: a ≤ g + θ̇²L/2 (at most 58 m/s² in the presets) it would be at most a·(h/4)²/2 ≈ 11 µm deep. After an
#: impact an end rises and falls back through the floor, which is always seen.
MAX_STEP_S = 2.5e-3


def parameter_array(params: Mapping[str, Any]) -> np.ndarray:
    """``p = [m (kg), L (m), I (kg·m²) about the centre, g (m/s²), e, μ]`` for the kernels."""
    m, L = params["mass_kg"], params["length_m"]
    inertia = float(slender_rod(m, L)[0, 0])  # rod along its own z: any transverse axis
    return np.array(
        [m, L, inertia, params["g_m_s2"], params["restitution"], params["friction_coefficient"]], dtype=float
    )


def initial_state(params: Mapping[str, Any]) -> np.ndarray:
    """Released from rest at x = 0, centre height ``drop_height_m``, angle ``angle0_deg`` (shape (16,))."""
    y = np.zeros(len(STATE_NAMES))
    y[Z] = params["drop_height_m"]
    y[THETA] = math.radians(params["angle0_deg"])
    y[LAST_T] = -1.0  # no impact yet (a time before the start)
    return y


@register_jitable
def lever_arm_m(theta_rad: float, length_m: float, end: int) -> np.ndarray:
    """(2,) [x, z] from the centre to end A (``end`` 0) or B (1), m."""
    sign = -1.0 if end == END_A else 1.0
    return sign * 0.5 * length_m * np.array([math.cos(theta_rad), math.sin(theta_rad)])


def end_positions_m(states: np.ndarray, length_m: float) -> tuple[np.ndarray, np.ndarray]:
    """Ends A and B along ``states`` (N, 16): two arrays (N, 2) of [x, z] in m."""
    states = np.atleast_2d(states)
    half = 0.5 * length_m * np.stack([np.cos(states[:, THETA]), np.sin(states[:, THETA])], axis=1)
    centre = states[:, [X, Z]]
    return centre - half, centre + half


@register_jitable
def contact_velocity_m_s(y: np.ndarray, r: np.ndarray) -> np.ndarray:
    """(2,) [vn, vt] of the bar's point at lever arm ``r`` (m): normal +z, tangent +x, m/s."""
    return np.array([y[VZ] + y[OMEGA] * r[0], y[VX] - y[OMEGA] * r[1]])


@register_jitable
def inverse_effective_mass(mass_kg: float, inertia_kg_m2: float, r: np.ndarray) -> np.ndarray:
    """(2, 2) W (1/kg) of the point at lever arm ``r`` in [normal, tangent]: ``(1/m) 1 + q qᵀ / I``,
    ``q = (r_x, −r_z)``."""
    q = np.array([r[0], -r[1]])
    return np.eye(2) / mass_kg + np.outer(q, q) / inertia_kg_m2


@register_jitable
def _translational_kinetic_J(vx_m_s, vz_m_s, p):
    """½ m v_G² (J) from the centre's velocity (scalars or arrays alike)."""
    return 0.5 * p[P_MASS] * (vx_m_s**2 + vz_m_s**2)


@register_jitable
def _rotational_kinetic_J(omega_rad_s, p):
    """½ I_G ω² (J) (scalar or array)."""
    return 0.5 * p[P_INERTIA] * omega_rad_s**2


@register_jitable
def _potential_J(z_m, p):
    """m g z (J, floor at z = 0) from the centre height (scalar or array)."""
    return p[P_MASS] * p[P_G] * z_m


@register_jitable
def _kinetic_plus_potential_J(vx_m_s, vz_m_s, omega_rad_s, z_m, p):
    """Kinetic + potential energy (J, floor at z = 0) from the velocities and centre height (scalars or arrays
    alike)."""
    return _translational_kinetic_J(vx_m_s, vz_m_s, p) + _rotational_kinetic_J(omega_rad_s, p) + _potential_J(z_m, p)


def mechanical_energy_J(y: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Kinetic + potential energy (J, floor at z = 0) of states ``y`` (..., 16)."""
    return _kinetic_plus_potential_J(y[..., VX], y[..., VZ], y[..., OMEGA], y[..., Z], p)


def energy_parts(y: np.ndarray, p: np.ndarray) -> EnergyParts:
    """½ m v_G², ½ I_G ω² and m g z (J) of states ``y`` (N, 16)."""
    y = np.atleast_2d(y)
    return EnergyParts(
        _potential_J(y[:, Z], p),
        translational_kinetic_J=_translational_kinetic_J(y[:, VX], y[:, VZ], p),
        rotational_kinetic_J=_rotational_kinetic_J(y[:, OMEGA], p),
    )


def angular_momentum_about_point(y: np.ndarray, p: np.ndarray, point_m: np.ndarray) -> float:
    """Angular momentum (kg·m²/s, positive counter-clockwise from +x to +z) about a fixed ``point_m`` [x, z]."""
    d = np.array([y[X], y[Z]]) - point_m
    return float(p[P_INERTIA] * y[OMEGA] + p[P_MASS] * (d[0] * y[VZ] - d[1] * y[VX]))


@register_jitable
def _apply_impulse(y, p, r, impulse_n_t):
    """Change the velocities of ``y`` for impulse [Pn, Pt] (N·s) at lever arm ``r``: Δv = P/m, Δθ̇ = r × P / I."""
    pn, pt = impulse_n_t[0], impulse_n_t[1]
    y[VX] += pt / p[P_MASS]
    y[VZ] += pn / p[P_MASS]
    y[OMEGA] += (r[0] * pn - r[1] * pt) / p[P_INERTIA]


@register_jitable
def _single_contact(y, p, end):
    """One end strikes alone; returns (energy loss J, slip code: index in SLIP_STATES)."""
    r = lever_arm_m(y[THETA], p[P_LENGTH], end)
    law = np.empty(IMPACT_OUT_SIZE)
    impact_core(inverse_effective_mass(p[P_MASS], p[P_INERTIA], r), contact_velocity_m_s(y, r), p[P_E], p[P_MU], law)
    _apply_impulse(y, p, r, law[OUT_NORMAL_IMPULSE : OUT_TANGENTIAL_IMPULSE + 1])
    for k in range(PN_A, SLIP):
        y[k] = 0.0
    y[PN_A + 2 * end] = law[OUT_NORMAL_IMPULSE]
    y[PT_A + 2 * end] = law[OUT_TANGENTIAL_IMPULSE]
    return law[OUT_ENERGY_LOSS], law[OUT_SLIP_CODE]


@register_jitable
def _two_contacts(y, p):
    """Both ends strike a flat bar at once (common + rocking modes, see the module text); (energy loss J, slip code)."""
    m, L = p[P_MASS], p[P_LENGTH]
    common = np.empty(IMPACT_OUT_SIZE)
    impact_core(np.eye(2) / m, np.array([y[VZ], y[VX]]), p[P_E], p[P_MU], common)
    total_normal, total_tangential = common[OUT_NORMAL_IMPULSE], common[OUT_TANGENTIAL_IMPULSE]
    # Rocking mode: w = (L/2) cos θ θ̇ is half of (vn_B − vn_A). Q, half of (P_B − P_A), turns the bar by
    # Δθ̇ = L cos θ Q / I; the impulse that does work on w is 2Q (power P_A vn_A + P_B vn_B = S ż + 2Q w), and
    # Δw = (3 cos²θ / m)(2Q). The law sees the side that approaches: vn = −|w|.
    lever = 0.5 * L * math.cos(y[THETA])
    w = lever * y[OMEGA]
    rocking_q, rocking_loss = 0.0, 0.0
    if w != 0.0:
        rocking = np.empty(IMPACT_OUT_SIZE)
        impact_core(np.eye(2) * (3.0 * math.cos(y[THETA]) ** 2 / m), np.array([-abs(w), 0.0]), p[P_E], 0.0, rocking)
        rocking_q, rocking_loss = -0.5 * math.copysign(rocking[OUT_NORMAL_IMPULSE], w), rocking[OUT_ENERGY_LOSS]
    normal_a, normal_b = 0.5 * total_normal - rocking_q, 0.5 * total_normal + rocking_q
    y[VX] += total_tangential / m
    y[VZ] += total_normal / m
    y[OMEGA] += 2.0 * rocking_q * lever / p[P_INERTIA]
    y[PN_A], y[PN_B] = normal_a, normal_b
    # Friction shared in proportion to the normal impulses keeps each end inside its own cone.
    y[PT_A], y[PT_B] = total_tangential * normal_a / total_normal, total_tangential * normal_b / total_normal
    return common[OUT_ENERGY_LOSS] + rocking_loss, common[OUT_SLIP_CODE]


@register_jitable
def _end_height_and_approach(y, length_m, end):
    """(height m, normal velocity m/s, negative approaching) of end A (``end`` 0) or B (1) of state ``y``."""
    r = lever_arm_m(y[THETA], length_m, end)
    return y[Z] + r[1], contact_velocity_m_s(y, r)[0]


@register_jitable
def floor_impacts(y, p, t_s, end):
    """The reset map at the floor: resolve the impact(s) starting at ``end`` and update the ledger in ``y`` (16,) in
    place.

    After the striking end, the other end is checked too (it may be touching and now
    approaching); at most a few rounds. An impact that comes in or leaves slower than
    :data:`REST_SPEED_M_S` at a struck end ends the bouncing (module text): that end
    would be back on the floor within milliseconds, again and again.
    """
    if y[MODE] != FLIGHT:
        return
    L = p[P_LENGTH]
    struck_a, struck_b = False, False
    slowest_m_s = math.inf  # the slowest approach or rebound of a struck end at this instant
    impacts = 0
    for _ in range(4):
        height_a, approach_a = _end_height_and_approach(y, L, END_A)
        height_b, approach_b = _end_height_and_approach(y, L, END_B)
        striking_a = (
            height_a <= TOUCH_TOLERANCE_M or (end == END_A and impacts == 0)
        ) and approach_a < -GRAZING_SPEED_M_S
        striking_b = (
            height_b <= TOUCH_TOLERANCE_M or (end == END_B and impacts == 0)
        ) and approach_b < -GRAZING_SPEED_M_S
        if not (striking_a or striking_b):
            break
        if striking_a:
            slowest_m_s = min(slowest_m_s, -approach_a)
        if striking_b:
            slowest_m_s = min(slowest_m_s, -approach_b)
        if (
            striking_a and striking_b and L * abs(math.sin(y[THETA])) <= 2.0 * TOUCH_TOLERANCE_M
        ):  # both on the floor: flat
            loss, slip = _two_contacts(y, p)
        else:
            end_striking = striking_a if end == END_A else striking_b
            loss, slip = _single_contact(y, p, end if end_striking else END_A if striking_a else END_B)
        struck_a, struck_b = struck_a or striking_a, struck_b or striking_b
        impacts += 1
        y[IMPACTS] += 1.0
        y[LOST] += loss
        y[LAST_LOSS] = loss if impacts == 1 else y[LAST_LOSS] + loss
        y[LAST_T] = t_s
        y[SLIP] = 1.0 + slip
    if impacts == 0:
        return
    slowest_rebound_m_s = slowest_m_s
    if struck_a:
        slowest_rebound_m_s = min(slowest_rebound_m_s, _end_height_and_approach(y, L, END_A)[1])
    if struck_b:
        slowest_rebound_m_s = min(slowest_rebound_m_s, _end_height_and_approach(y, L, END_B)[1])
    if slowest_rebound_m_s < REST_SPEED_M_S:
        _settle(y, p)


@register_jitable
def _settle(y, p):
    """End the Zeno cascade: lay a nearly flat bar on the floor (RESTING) or stop a tilted one (SETTLED_ON_END).

    The energy the bar gives up here (its remaining vertical and rocking motion,
    and the small drop to lying flat) is booked as lost.
    """
    before = _kinetic_plus_potential_J(y[VX], y[VZ], y[OMEGA], y[Z], p)
    raised_m = p[P_LENGTH] * abs(math.sin(y[THETA]))
    if raised_m <= FLAT_FRACTION * p[P_LENGTH]:
        y[THETA] = math.pi * round(y[THETA] / math.pi)
        y[Z] = 0.0
        y[VZ] = 0.0
        y[OMEGA] = 0.0
        y[MODE] = RESTING
    else:
        y[VX] = 0.0
        y[VZ] = 0.0
        y[OMEGA] = 0.0
        y[MODE] = SETTLED_ON_END
    y[LOST] += before - _kinetic_plus_potential_J(y[VX], y[VZ], y[OMEGA], y[Z], p)


# -- compiled kernels --------------------------------------------------------------------
@kernel(RHS_SIGNATURE)
def bar_rhs(t, y, p, dydt):
    """Flight: free fall and constant spin. Resting: sliding on the floor, μ g deceleration, friction work in the
    ledger."""
    for i in range(y.shape[0]):
        dydt[i] = 0.0
    if y[6] == 0.0:  # FLIGHT
        dydt[0] = y[3]
        dydt[1] = y[4]
        dydt[2] = y[5]
        dydt[4] = -p[3]
    elif y[6] == 1.0 and y[3] != 0.0:  # RESTING and still sliding
        direction = 1.0 if y[3] > 0.0 else -1.0
        dydt[0] = y[3]
        dydt[3] = -p[5] * p[3] * direction
        dydt[8] = p[5] * p[0] * p[3] * abs(y[3])


@kernel(EVENTS_SIGNATURE)
def bar_events(t, y, p, g_out):
    """Heights (m) of ends A and B in flight; the sliding speed (m/s) while resting (1 otherwise: no event)."""
    half_rise = 0.5 * p[1] * math.sin(y[2])
    flying = y[6] == 0.0
    g_out[0] = y[1] - half_rise if flying else 1.0
    g_out[1] = y[1] + half_rise if flying else 1.0
    g_out[2] = y[3] if y[6] == 1.0 else 1.0


@register_jitable
def reset_state(y, p, t_s, index):
    """Event ``index``: an end reaches the floor (impacts), or the resting bar stops sliding (ẋ = 0); ``y`` (16,) in
    place."""
    if index == EVENT_STOPS_SLIDING:
        y[VX] = 0.0
    else:
        floor_impacts(y, p, t_s, END_A if index == EVENT_END_A else END_B)


@kernel(RESET_SIGNATURE)
def bar_reset(t, y, p, index):
    """The reset map :func:`reset_state`, with the impulse law compiled in."""
    reset_state(y, p, t, index)


def system(params: Mapping[str, Any]) -> OdeSystem:
    return OdeSystem(
        rhs=bar_rhs,
        parameters=parameter_array(params),
        state_names=STATE_NAMES,
        events=Events(
            bar_events,
            directions=(-1, -1, 0),
            terminal=(False, False, False),
            reset=bar_reset,
            resets=(True, True, True),
            max_step_s=MAX_STEP_S,
        ),
    )


def series(params: Mapping[str, Any], states: np.ndarray) -> dict[str, np.ndarray]:
    """The contract series along ``states`` (N, 16)."""
    p = parameter_array(params)
    return {
        "angle": states[:, THETA].copy(),
        "centre_height_m": states[:, Z].copy(),
        "energy_J": mechanical_energy_J(states, p),
        "impact_count": states[:, IMPACTS].copy(),
        "energy_lost_J": states[:, LOST].copy(),
    }


#: ``stats.status`` of a run that ended with the bar settled on one end (where this impact model stops).
SETTLED = "settled"


def mode_message(params: Mapping[str, Any], y: np.ndarray) -> str:
    """What the model is doing at state ``y`` (16,), in a student's words: the live readout's message, and the simulate
    answer's where the bar settled on one end."""
    mode = float(y[MODE])
    if mode == RESTING:
        return (
            f"Resting: the bounces fell below {REST_SPEED_M_S:g} m/s, so the endless cascade of ever smaller "
            "bounces is cut off and the bar lies flat on the floor"
            + (", sliding to a stop under friction." if y[VX] != 0.0 else ".")
        )
    if mode == SETTLED_ON_END:
        return (
            f"Settled on one end at t = {y[LAST_T]:.2f} s: the last impact left that end on the floor, tilted "
            f"θ = {math.degrees(math.remainder(float(y[THETA]), 2 * math.pi)):.1f}°, at rest. From here the bar "
            "would pivot or "
            "slide down in continuous contact, which this impact model does not follow, so the motion stops here."
        )
    return f"In flight between impacts; e = {params['restitution']:g}, μ = {params['friction_coefficient']:g}."


class BouncingBar(IntegratedModel):
    parameters = PARAMETERS
    #: Only the adaptive method locates events and applies reset maps.
    methods = ("dopri5",)
    default_method = "dopri5"
    #: Impacts are located events (to the tolerance), so the tolerance pilot's two runs meet the same impacts.
    accuracy_target = AccuracyTarget(1e-6, "", "x, z, θ and their rates: largest error relative to the largest of them")
    accuracy_components = (0, 1, 2, 3, 4, 5)
    series_units = {"angle": "rad", "centre_height_m": "m", "energy_J": "J", "impact_count": "", "energy_lost_J": "J"}
    invariant_units = {"energy_balance": "J"}

    def system(self, params):
        return system(params)

    def initial_state(self, params):
        return initial_state(params)

    def fastest_rate_rad_s(self, params, state):
        return math.sqrt(params["g_m_s2"] / params["length_m"])

    def series(self, params, t_s, states):
        return series(params, states)

    def model_limit(self, params, t_s, states):
        """The frame where the bar settled on one end (mode ``SETTLED_ON_END``): status ``settled``, the readout's
        message."""
        settled = np.atleast_2d(states)[:, MODE] == SETTLED_ON_END
        if not settled.any():
            return None
        k = int(np.argmax(settled))
        return ModelLimit(k + 1, SETTLED, mode_message(params, states[k]))

    def invariants(self, params, states):
        """Kinetic + potential + everything lost so far (J): constant."""
        p = parameter_array(params)
        return {"energy_balance": mechanical_energy_J(states, p) + states[:, LOST]}

    series_labels = {
        "angle": "θ",
        "centre_height_m": "height of G",
        "energy_J": "kinetic + potential",
        "impact_count": "impacts",
        "energy_lost_J": "energy lost",
        "energy_balance": "energy + lost",
    }

    def energy_parts(self, params, states, *, t_s=None):
        return energy_parts(states, parameter_array(params))

    def invariant_scales(self, params, state):
        p = parameter_array(params)
        # Potential energy above the lowest possible rest (flat on the floor): the energy there is to lose.
        return {"energy_balance": max(float(mechanical_energy_J(state, p)), p[P_MASS] * p[P_G] * 1e-3)}
