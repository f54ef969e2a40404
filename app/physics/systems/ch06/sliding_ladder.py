"""The sliding ladder: a uniform bar with its ends on a smooth or rough wall and floor.

Frame (planar, +Z up): the wall is the plane x = 0, the floor z = 0, and the
ladder lies in the x–z plane on the side x > 0. The bar (length L, mass m,
I = mL²/12 about its centre G) makes the angle θ with the floor; its top end A
touches the wall, its bottom end B the floor:

    A = G + (L/2)(−cos θ, sin θ),     B = G + (L/2)(cos θ, −sin θ).

Phases (a mode slot in the state, changed only by the reset maps):

* ``held`` — friction holds the ladder where it was put (tan θ0 ≥ (1 − μw μf)/(2 μf));
* ``on wall and floor`` — both contacts hold: x_A = 0 and z_B = 0 leave one
  degree of freedom θ. A slides down the wall, B away from it, so Coulomb
  friction (μw at A, μf at B) acts up the wall and towards the wall. Newton–Euler
  for G and the moment about G, with the constraint accelerations, are three
  linear equations for θ̈, the wall force N_A and the floor force N_B;
* ``floor only`` — the wall force has fallen to zero (event, then a reset map):
  z_B = 0 alone leaves (x_G, θ). B slides (friction −μf N_B against its
  sliding direction) or, with floor friction, may stop and stick
  (``floor only, bottom end stuck``: B is a pivot while |F| ≤ μf N_B);
* ``lying`` — θ reaches 0: the bar lands flat. Both ends touch at once, so the
  plastic impact (e = 0) removes all vertical velocity and the rotation, and a
  friction impulse of at most μf times the normal impulse slows the sliding
  (the impulse law of :mod:`.impact` with e = 0, for the translation). Then the
  bar slides on the floor until friction stops it.

Energy is accounted for: kinetic + potential + friction work + impact loss is
constant (the invariant ``energy_budget_J``); friction work and impact loss
are state slots integrated and updated by the reset maps.

Parameters (API contract names): ``length_m``, ``mass_kg``, ``angle0_deg``
(from the floor), ``mu_wall``, ``mu_floor``, ``g_m_s2``. The ladder starts
at rest. Series: ``angle_from_floor`` (rad), ``wall_force_N``,
``floor_force_N``, ``top_height_m``. Model limits: the floor force is assumed to
stay compressive (the readout says if it would not), and a top end that swings
back to the wall after leaving it stops the run (a second wall contact is not
modelled). μf ≤ 1 keeps the equations of the sliding phases solvable (the
Painlevé inconsistency needs μf > 4/3).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numba.extending import register_jitable

from app.physics.bodies.inertia import slender_rod
from app.physics.core.contact_energy import ContactEnergyBudget
from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.solvers import DormandPrince, Events, OdeSystem, simulate
from app.physics.solvers.integrated_model import IntegratedModel
from app.physics.solvers.kernels import (
    EVENTS_SIGNATURE,
    RESET_SIGNATURE,
    RHS_SIGNATURE,
    kernel,
)
from app.physics.solvers.step_choice import AccuracyTarget

#: State slots: centre of mass x (m), angle from the floor (rad), their rates (m/s, rad/s),
#: friction work done so far (J, ≥ 0), impact loss so far (J, ≥ 0), phase code, sliding direction of B (±1).
STATE_NAMES = (
    "x_center_m",
    "angle_from_floor_rad",
    "vx_center_m_s",
    "angle_rate_rad_s",
    "friction_work_J",
    "impact_loss_J",
    "phase",
    "slip_direction",
)
X, THETA, VX, OMEGA, FRICTION_WORK, IMPACT_LOSS, PHASE, SLIP = range(8)
#: Kernel parameters p: [L (m), m (kg), g (m/s²), μw, μf, I about G (kg·m²)].
P_LENGTH, P_MASS, P_G, P_MU_WALL, P_MU_FLOOR, P_INERTIA = range(6)

#: Phase codes and their words.
HELD, WALL_AND_FLOOR, FLOOR_SLIDING, FLOOR_STUCK, LYING = 0, 1, 2, 3, 4
PHASE_WORDS = {
    HELD: "held by friction",
    WALL_AND_FLOOR: "on wall and floor",
    FLOOR_SLIDING: "floor only",
    FLOOR_STUCK: "floor only, bottom end stuck",
    LYING: "lying",
}
#: Event indices.
WALL_RELEASE, LANDING, SLIP_STOPS, STICK_BREAKS, COMES_TO_REST, TOP_RETURNS_TO_WALL = range(6)
EVENT_WORDS = {
    WALL_RELEASE: "leaves the wall",
    LANDING: "lands on the floor",
    SLIP_STOPS: "bottom end stops sliding",
    STICK_BREAKS: "bottom end starts sliding",
    COMES_TO_REST: "comes to rest",
    TOP_RETURNS_TO_WALL: "top end back at the wall (not modelled: run stops)",
}
#: Contact quantities from :func:`contact_dynamics`.
N_CONTACT = 7
C_ANGULAR_ACC, C_X_ACC, C_WALL_N, C_FLOOR_N, C_WALL_FRICTION, C_FLOOR_FRICTION, C_FRICTION_POWER = range(N_CONTACT)


PARAMETERS = ParameterSet(
    (
        Parameter("length_m", "m", 4.0, 0.1, 20.0, "Length of the ladder (a uniform bar)", "L", step=0.1),
        Parameter("mass_kg", "kg", 10.0, 0.1, 200.0, "Mass of the ladder", "m", step=0.1),
        Parameter(
            "angle0_deg",
            "deg",
            60.0,
            1.0,
            89.9,
            "Initial angle of the ladder from the floor (released from rest)",
            "θ₀",
            step=0.1,
        ),
        Parameter(
            "mu_wall", "", 0.0, 0.0, 1.0, "Coulomb friction coefficient at the wall (0: smooth)", "μ_w", step=0.01
        ),
        Parameter(
            "mu_floor", "", 0.0, 0.0, 1.0, "Coulomb friction coefficient at the floor (0: smooth)", "μ_f", step=0.01
        ),
        Parameter("g_m_s2", "m/s²", 9.807, 0.1, 100.0, "Gravitational acceleration", "g", step=0.001),
    ),
)


# -- contact dynamics: one function for every phase ---------------------------------------------
@register_jitable
def contact_dynamics(y, p, out):
    """Accelerations and contact forces of the state ``y`` (STATE_NAMES) in its phase, into ``out`` (N_CONTACT,).

    ``out``: θ̈ (rad/s²), ẍ_G (m/s²), wall normal force N_A (N, +x), floor normal force
    N_B (N, +z), wall friction on A (N, +z), floor friction on the bottom end (N, +x; in
    ``lying`` the whole floor friction), friction power (W, ≥ 0). In ``held`` the forces are
    those with friction mobilised equally at both ends (the statics alone is indeterminate).
    """
    half = 0.5 * p[P_LENGTH]
    m, g, mu_w, mu_f, inertia = p[P_MASS], p[P_G], p[P_MU_WALL], p[P_MU_FLOOR], p[P_INERTIA]
    theta, omega, vx = y[THETA], y[OMEGA], y[VX]
    s, c = math.sin(theta), math.cos(theta)
    phase = int(y[PHASE])
    for i in range(N_CONTACT):
        out[i] = 0.0
    if phase == HELD:
        # s_mob² μw μf + 2 s_mob μf tan θ − 1 = 0 with s_mob ∈ (0, 1] the share of each friction limit in use.
        a, b = mu_w * mu_f, 2.0 * mu_f * s / c
        share = 1.0 / b if a == 0.0 else 2.0 / (b + math.sqrt(b * b + 4.0 * a))
        normal_floor = m * g / (1.0 + share * share * a)
        normal_wall = share * mu_f * normal_floor
        out[C_WALL_N], out[C_FLOOR_N] = normal_wall, normal_floor
        out[C_WALL_FRICTION], out[C_FLOOR_FRICTION] = share * mu_w * normal_wall, -normal_wall
    elif phase == WALL_AND_FLOOR:
        # ẍ_G = ax θ̈ + bx, z̈_G = az θ̈ + bz (x_G = L/2 cos θ, z_G = L/2 sin θ).
        ax, bx = -half * s, -half * c * omega * omega
        az, bz = half * c, -half * s * omega * omega
        det = 1.0 + mu_w * mu_f
        # m ẍ_G = N_A − μf N_B,  m z̈_G = N_B + μw N_A − m g  →  N = m (k θ̈ + r) / det.
        k_wall, r_wall = ax + mu_f * az, bx + mu_f * (bz + g)
        k_floor, r_floor = az - mu_w * ax, bz + g - mu_w * bx
        # I θ̈ = (L/2)[(sin θ + μw cos θ) N_A + (μf sin θ − cos θ) N_B]  (θ̈ > 0 turns the bar up).
        arm_wall, arm_floor = half * (s + mu_w * c), half * (mu_f * s - c)
        alpha = (
            (m / det)
            * (arm_wall * r_wall + arm_floor * r_floor)
            / (inertia - (m / det) * (arm_wall * k_wall + arm_floor * k_floor))
        )
        normal_wall = m * (k_wall * alpha + r_wall) / det
        normal_floor = m * (k_floor * alpha + r_floor) / det
        out[C_ANGULAR_ACC], out[C_X_ACC] = alpha, ax * alpha + bx
        out[C_WALL_N], out[C_FLOOR_N] = normal_wall, normal_floor
        out[C_WALL_FRICTION], out[C_FLOOR_FRICTION] = mu_w * normal_wall, -mu_f * normal_floor
        # A moves down at L cos θ |θ̇|, B away from the wall at L sin θ |θ̇|.
        out[C_FRICTION_POWER] = p[P_LENGTH] * abs(omega) * (mu_w * normal_wall * c + mu_f * normal_floor * s)
    elif phase == FLOOR_SLIDING or phase == FLOOR_STUCK:
        if phase == FLOOR_SLIDING:
            # F = −μf σ N_B; I θ̈ = (L/2)(−sin θ F − cos θ N_B), N_B = m (g + z̈_G).
            arm = half * (mu_f * y[SLIP] * s - c)
            alpha = arm * m * (g - half * s * omega * omega) / (inertia - arm * m * half * c)
        else:
            # B is a pivot: I_B θ̈ = −m g (L/2) cos θ.
            alpha = -m * g * half * c / (inertia + m * half * half)
        normal_floor = m * (g + half * (c * alpha - s * omega * omega))
        if phase == FLOOR_SLIDING:
            friction = -mu_f * y[SLIP] * normal_floor
            x_acc = friction / m
            out[C_FRICTION_POWER] = mu_f * normal_floor * abs(vx - half * s * omega)
        else:
            x_acc = half * (c * omega * omega + s * alpha)
            friction = m * x_acc
        out[C_ANGULAR_ACC], out[C_X_ACC] = alpha, x_acc
        out[C_FLOOR_N], out[C_FLOOR_FRICTION] = normal_floor, friction
    else:  # LYING
        friction = -mu_f * m * g * (1.0 if vx > 0.0 else -1.0 if vx < 0.0 else 0.0)
        out[C_X_ACC] = friction / m
        out[C_FLOOR_N], out[C_FLOOR_FRICTION] = m * g, friction
        out[C_FRICTION_POWER] = abs(friction * vx)


@register_jitable
def _bottom_end_velocity(y, p):
    """ẋ_B (m/s): the bottom end's velocity along the floor."""
    return y[VX] - 0.5 * p[P_LENGTH] * math.sin(y[THETA]) * y[OMEGA]


@kernel(RHS_SIGNATURE)
def ladder_rhs(t, y, p, dydt):
    """d/dt of the state (STATE_NAMES); p = [L, m, g, μw, μf, I_G]. On the wall, and with B stuck,
    x_G follows θ from the contact constraints."""
    out = np.empty(N_CONTACT)
    contact_dynamics(y, p, out)
    phase = int(y[PHASE])
    half = 0.5 * p[P_LENGTH]
    if phase == WALL_AND_FLOOR:
        dydt[X] = -half * math.sin(y[THETA]) * y[OMEGA]
    elif phase == FLOOR_STUCK:
        dydt[X] = half * math.sin(y[THETA]) * y[OMEGA]
    elif phase == HELD:
        dydt[X] = 0.0
    else:
        dydt[X] = y[VX]
    dydt[THETA] = 0.0 if phase == HELD or phase == LYING else y[OMEGA]
    dydt[VX] = out[C_X_ACC]
    dydt[OMEGA] = out[C_ANGULAR_ACC]
    dydt[FRICTION_WORK] = out[C_FRICTION_POWER]
    dydt[IMPACT_LOSS] = 0.0
    dydt[PHASE] = 0.0
    dydt[SLIP] = 0.0


@kernel(EVENTS_SIGNATURE)
def ladder_events(t, y, p, g_out):
    """Six event functions (see the event indices); an event that cannot happen in this phase reads 1."""
    out = np.empty(N_CONTACT)
    contact_dynamics(y, p, out)
    phase = int(y[PHASE])
    for i in range(6):
        g_out[i] = 1.0
    if phase == WALL_AND_FLOOR:
        g_out[WALL_RELEASE] = out[C_WALL_N]
    if phase == WALL_AND_FLOOR or phase == FLOOR_SLIDING or phase == FLOOR_STUCK:
        g_out[LANDING] = y[THETA]
    if phase == FLOOR_SLIDING and p[P_MU_FLOOR] > 0.0:
        g_out[SLIP_STOPS] = y[SLIP] * _bottom_end_velocity(y, p)
    if phase == FLOOR_STUCK:
        g_out[STICK_BREAKS] = p[P_MU_FLOOR] * out[C_FLOOR_N] - abs(out[C_FLOOR_FRICTION])
    if phase == LYING and p[P_MU_FLOOR] > 0.0:
        g_out[COMES_TO_REST] = y[SLIP] * y[VX]
    if phase == FLOOR_SLIDING or phase == FLOOR_STUCK:
        g_out[TOP_RETURNS_TO_WALL] = y[X] - 0.5 * p[P_LENGTH] * math.cos(y[THETA])


@register_jitable
def _slide_from_rest(y, p):
    """B has no velocity along the floor: stick if friction can hold it, else slide against the needed force."""
    half = 0.5 * p[P_LENGTH]
    y[VX] = half * math.sin(y[THETA]) * y[OMEGA]
    y[PHASE] = FLOOR_STUCK
    out = np.empty(N_CONTACT)
    contact_dynamics(y, p, out)
    if abs(out[C_FLOOR_FRICTION]) > p[P_MU_FLOOR] * out[C_FLOOR_N]:
        y[PHASE] = FLOOR_SLIDING
        y[SLIP] = -1.0 if out[C_FLOOR_FRICTION] > 0.0 else 1.0


@kernel(RESET_SIGNATURE)
def ladder_reset(t, y, p, index):
    """Phase changes: leave the wall, land (plastic impact), stick or slip at B, come to rest."""
    half = 0.5 * p[P_LENGTH]
    m = p[P_MASS]
    if index == WALL_RELEASE:
        y[X] = half * math.cos(y[THETA])
        y[VX] = -half * math.sin(y[THETA]) * y[OMEGA]
        y[PHASE] = FLOOR_SLIDING
        y[SLIP] = 1.0
    elif index == LANDING:
        # Flat on the floor: both ends touch. Normal impulses (e = 0) stop the vertical motion of G and
        # the rotation; the friction impulse is at most μf times the normal impulse m |ż_G|.
        vz = half * math.cos(y[THETA]) * y[OMEGA]
        if int(y[PHASE]) == FLOOR_STUCK or int(y[PHASE]) == WALL_AND_FLOOR:
            y[VX] = (1.0 if int(y[PHASE]) == FLOOR_STUCK else -1.0) * half * math.sin(y[THETA]) * y[OMEGA]
        kinetic_before = 0.5 * m * (y[VX] ** 2 + vz**2) + 0.5 * p[P_INERTIA] * y[OMEGA] ** 2
        speed_change = min(abs(y[VX]), p[P_MU_FLOOR] * abs(vz))
        y[VX] = y[VX] - speed_change if y[VX] > 0.0 else y[VX] + speed_change
        y[IMPACT_LOSS] += kinetic_before - 0.5 * m * y[VX] ** 2
        y[THETA] = 0.0
        y[OMEGA] = 0.0
        y[PHASE] = LYING
        y[SLIP] = 1.0 if y[VX] > 0.0 else -1.0 if y[VX] < 0.0 else 0.0
    elif index == SLIP_STOPS:
        _slide_from_rest(y, p)
    elif index == STICK_BREAKS:
        _slide_from_rest(y, p)
        if int(y[PHASE]) == FLOOR_STUCK:  # on the friction limit to round-off: it is about to slip
            out = np.empty(N_CONTACT)
            contact_dynamics(y, p, out)
            y[PHASE] = FLOOR_SLIDING
            y[SLIP] = -1.0 if out[C_FLOOR_FRICTION] > 0.0 else 1.0
    elif index == COMES_TO_REST:
        y[VX] = 0.0


# -- the model ----------------------------------------------------------------------------------
def kernel_parameters(params: Mapping[str, Any]) -> np.ndarray:
    """p = [L (m), m (kg), g (m/s²), μw, μf, I about G (kg·m²)] for the kernels."""
    length, mass = params["length_m"], params["mass_kg"]
    inertia = float(slender_rod(mass, length)[0, 0])
    return np.array([length, mass, params["g_m_s2"], params["mu_wall"], params["mu_floor"], inertia])


def friction_holds(params: Mapping[str, Any]) -> bool:
    """Whether friction holds the ladder at rest: tan θ0 ≥ (1 − μw μf)/(2 μf)."""
    mu_w, mu_f = params["mu_wall"], params["mu_floor"]
    if mu_f <= 0.0:
        return False
    return math.tan(math.radians(params["angle0_deg"])) >= (1.0 - mu_w * mu_f) / (2.0 * mu_f)


def initial_state(params: Mapping[str, Any]) -> np.ndarray:
    """At rest at θ0 against the wall (held if friction can hold it)."""
    theta0 = math.radians(params["angle0_deg"])
    y = np.zeros(len(STATE_NAMES))
    y[X] = 0.5 * params["length_m"] * math.cos(theta0)
    y[THETA] = theta0
    y[PHASE] = HELD if friction_holds(params) else WALL_AND_FLOOR
    y[SLIP] = 1.0
    return y


def separation_angle_frictionless_rad(angle0_rad: float) -> float:
    """Closed form, smooth wall and floor, from rest: sin θ_sep = (2/3) sin θ0 (rad)."""
    return math.asin(2.0 / 3.0 * math.sin(angle0_rad))


def contact_forces(params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
    """Per state (N, 8): the :func:`contact_dynamics` quantities, shape (N, N_CONTACT)."""
    p = kernel_parameters(params)
    states = np.atleast_2d(states)
    out = np.empty((states.shape[0], N_CONTACT))
    for row, state in zip(out, states):
        contact_dynamics(np.asarray(state, dtype=float), p, row)
    return out


def energy_budget(params: Mapping[str, Any], states: np.ndarray) -> ContactEnergyBudget:
    """Kinetic, potential (floor level zero), friction work and impact loss along ``states`` (N, 8)."""
    states = np.atleast_2d(states)
    length, mass, g = params["length_m"], params["mass_kg"], params["g_m_s2"]
    inertia = float(slender_rod(mass, length)[0, 0])
    theta, omega = states[:, THETA], states[:, OMEGA]
    phase = states[:, PHASE].astype(int)
    half = 0.5 * length
    vx = np.where(phase == WALL_AND_FLOOR, -half * np.sin(theta) * omega, states[:, VX])
    vx = np.where(phase == FLOOR_STUCK, half * np.sin(theta) * omega, vx)
    vz = half * np.cos(theta) * omega
    return ContactEnergyBudget(
        0.5 * mass * (vx**2 + vz**2),
        0.5 * inertia * omega**2,
        mass * g * half * np.sin(theta),
        states[:, FRICTION_WORK],
        states[:, IMPACT_LOSS],
    )


def top_height_m(params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
    """Height of the top end A above the floor (m), (N,)."""
    return params["length_m"] * np.sin(np.atleast_2d(states)[:, THETA])


def end_positions_m(params: Mapping[str, Any], state: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Top end A and bottom end B as (x, z) in m for one state."""
    half = 0.5 * params["length_m"]
    theta = state[THETA]
    x_center = half * math.cos(theta) if int(state[PHASE]) in (HELD, WALL_AND_FLOOR) else state[X]
    center = np.array([x_center, half * math.sin(theta)])
    along = half * np.array([-math.cos(theta), math.sin(theta)])
    return center + along, center - along


def ladder_system(params: Mapping[str, Any]) -> OdeSystem:
    return OdeSystem(
        rhs=ladder_rhs,
        parameters=kernel_parameters(params),
        state_names=STATE_NAMES,
        events=Events(
            ladder_events,
            directions=(-1, -1, -1, -1, -1, -1),
            terminal=(False, False, False, False, False, True),
            reset=ladder_reset,
            resets=(True, True, True, True, True, False),
            # The fall from the wall to the floor lasts ≳ 0.2 s for the shortest ladder: 0.02 s steps
            # put several checks inside every phase.
            max_step_s=0.02,
        ),
    )


@dataclass(frozen=True)
class PhaseChange:
    """An event located on the motion: time (s), which (index and words), the state there (before any reset)."""

    t_s: float
    index: int
    words: str
    state: np.ndarray


def phase_changes(params: Mapping[str, Any], *, t_end_s: float, rtol: float = 1e-10) -> tuple[PhaseChange, ...]:
    """Every phase change in [0, t_end_s], located by Dormand–Prince with event location (rtol as given)."""
    result = simulate(
        ladder_system(params), DormandPrince(rtol=rtol), initial_state(params), t_end_s=t_end_s, frame_rate_hz=10.0
    )
    return tuple(PhaseChange(e.t_s, e.index, EVENT_WORDS[e.index], e.state) for e in result.events)


class SlidingLadder(IntegratedModel):
    parameters = PARAMETERS
    methods = ("dopri5",)
    default_method = "dopri5"
    #: Events are located (to the tolerance), so the tolerance pilot's two runs meet the same phase changes.
    accuracy_target = AccuracyTarget(
        1e-6, "", "x, angle and their rates: largest error relative to the largest of them"
    )
    accuracy_components = (0, 1, 2, 3)
    series_units = {"angle_from_floor": "rad", "wall_force_N": "N", "floor_force_N": "N", "top_height_m": "m"}
    invariant_units = {"energy_budget_J": "J"}

    def system(self, params):
        return ladder_system(params)

    def initial_state(self, params):
        return initial_state(params)

    def fastest_rate_rad_s(self, params, state):
        return math.sqrt(1.5 * params["g_m_s2"] / params["length_m"]) + abs(float(state[OMEGA]))

    def series(self, params, t_s, states):
        forces = contact_forces(params, states)
        return {
            "angle_from_floor": states[:, THETA].copy(),
            "wall_force_N": forces[:, C_WALL_N],
            "floor_force_N": forces[:, C_FLOOR_N],
            "top_height_m": top_height_m(params, states),
        }

    def invariants(self, params, states):
        return {"energy_budget_J": energy_budget(params, states).total_J}

    def invariant_scales(self, params, state):
        return {"energy_budget_J": max(float(energy_budget(params, state).total_J[0]), 1e-300)}

    series_labels = {
        "angle_from_floor": "θ",
        "wall_force_N": "N_wall",
        "floor_force_N": "N_floor",
        "top_height_m": "height of the top",
        "energy_budget_J": "energy + friction work + impact loss",
    }

    def energy_parts(self, params, states, *, t_s=None):
        return energy_budget(params, states).parts()
