"""A bar whose lower end slides on a rough floor: sliding, sticking, lifting off, and Painlevé's paradox.

Frame (planar, +Z up): the floor is z = 0 and the bar moves in the x–z plane. The
uniform bar (length L, mass m, I = mL²/12 about its centre G) touches the floor
with its lower end B = (x_B, 0); θ is its angle from the floor, and it leans
back over −x:

    G = B + (L/2)(−cos θ, sin θ).

So for θ < 90° a positive ``u = ẋ_B`` drags B away from the side the bar leans
to. The contact force on B is N (+z) and F (+x). Newton for G and Euler about G:

    m ẍ_G = F,    m z̈_G = N − m g,    I θ̈ = −(L/2)(N cos θ + F sin θ),

with ẍ_G = u̇ + (L/2)(sin θ θ̈ + cos θ θ̇²) and z̈_G = (L/2)(cos θ θ̈ − sin θ θ̇²).

Phases (a slot in the state, changed only by reset maps at located events):

* ``sliding`` with σ = sign(u): F = −μ σ N. Eliminating θ̈ gives
  ``N = m (g − (L/2) θ̇² sin θ) / D`` with ``D = 1 + κ cos θ (cos θ − σ μ sin θ)``
  and κ = m (L/2)² / I = 3. For D > 0 the contact force is unique. Where
  D ≤ 0 (possible only with μ ≥ 4/3, in the band of angles where
  tan θ lies between the roots of t² − κμ t + 1 + κ = 0, around tan θ = 2)
  sliding has no solution with N ≥ 0 (numerator > 0) or more than one (numerator < 0,
  where lifting off fits too): Painlevé's paradox;
* ``sticking``: B is a pivot while |F| ≤ μ N;
* ``jammed``: the contact problem has no consistent solution (Painlevé). The state
  is frozen and the run stops a nanosecond later (event ``JAM_STOP``) with the
  reason in words: never integrated further.

Events: sliding stops (u → 0: stick if friction can hold B, else slide the other
way, unless that sliding is itself inconsistent); sticking breaks (|F| → μ N);
D → 0 while sliding; the lower end lifts off (N → 0: free flight is not
modelled, the run stops); the bar lands flat (sin θ → 0: the run stops — the
landing impact is the sliding ladder's, chapter 6). Energy: kinetic + potential +
friction work is constant (``energy_budget_J``).

Parameters (API contract names): ``length_m``, ``mass_kg``, ``angle0_deg``,
``slide_speed0_m_s`` (initial u; the bar starts without rotation), ``mu``, ``g_m_s2``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from numba.extending import register_jitable

from app.physics.bodies.inertia import slender_rod
from app.physics.core.contact_energy import ContactEnergyBudget
from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.solvers import DormandPrince, EventRecord, Events, OdeSystem, simulate
from app.physics.solvers.integrated_model import IntegratedModel
from app.physics.solvers.kernels import EVENTS_SIGNATURE, RESET_SIGNATURE, RHS_SIGNATURE, kernel
from app.physics.solvers.step_choice import AccuracyTarget

#: State slots: x of the lower end B (m), angle from the floor (rad), ẋ_B (m/s), θ̇ (rad/s),
#: friction work so far (J, ≥ 0), phase code, sliding direction σ (±1), time the contact jammed (s).
STATE_NAMES = (
    "x_contact_m",
    "angle_rad",
    "contact_speed_m_s",
    "angle_rate_rad_s",
    "friction_work_J",
    "phase",
    "slip_direction",
    "jam_time_s",
)
X, THETA, U, OMEGA, FRICTION_WORK, PHASE, SLIP, JAM_TIME = range(8)
#: Kernel parameters p: [L (m), m (kg), g (m/s²), μ, I about G (kg·m²)].
P_LENGTH, P_MASS, P_G, P_MU, P_INERTIA = range(5)

SLIDING, STICKING, JAMMED = 0, 1, 2
PHASE_WORDS = {SLIDING: "sliding", STICKING: "sticking (B pivots)", JAMMED: "stopped: no consistent contact force"}
#: Event indices.
SLIP_STOPS, STICK_BREAKS, PAINLEVE_LIMIT, JAM_STOP, LIFT_OFF, LANDS = range(6)
EVENT_WORDS = {
    SLIP_STOPS: "B stops sliding",
    STICK_BREAKS: "B starts sliding",
    PAINLEVE_LIMIT: "D reaches 0 while sliding (Painlevé)",
    JAM_STOP: "no consistent contact force (Painlevé): run stops",
    LIFT_OFF: "B leaves the floor (free flight not modelled): run stops",
    LANDS: "the bar lands flat: run stops",
}
#: The phase while the run is held at the terminal event that stopped it (a jam keeps its own phase word).
STOPPED_PHASE_WORDS = {
    LIFT_OFF: "left the floor: the run stopped",
    LANDS: "landed flat: the run stopped",
}
#: A jammed contact stops the run this long after it jammed (s): far below anything shown.
JAM_STOP_DELAY_S = 1e-9
#: Contact quantities from :func:`contact_dynamics`.
N_CONTACT = 7
C_ANGULAR_ACC, C_CONTACT_ACC, C_NORMAL, C_FRICTION, C_FRICTION_POWER, C_PAINLEVE_FACTOR, C_NORMAL_NUMERATOR = range(
    N_CONTACT
)


PARAMETERS = ParameterSet(
    (
        Parameter("length_m", "m", 1.0, 0.1, 10.0, "Length of the bar (uniform)", "L", step=0.1),
        Parameter("mass_kg", "kg", 1.0, 0.1, 100.0, "Mass of the bar", "m", step=0.1),
        Parameter("angle0_deg", "deg", 30.0, 1.0, 89.0, "Initial angle of the bar from the floor", "θ₀", step=0.1),
        Parameter(
            "slide_speed0_m_s",
            "m/s",
            1.0,
            -5.0,
            5.0,
            "Initial sliding speed of the lower end B (+x: away from the side the bar leans to); no initial rotation",
            "u₀",
            step=0.01,
        ),
        Parameter(
            "mu", "", 0.3, 0.0, 3.0, "Coulomb friction coefficient at the floor (static = kinetic)", "μ", step=0.01
        ),
        Parameter("g_m_s2", "m/s²", 9.807, 0.1, 100.0, "Gravitational acceleration", "g", step=0.001),
    ),
)


# -- contact dynamics ------------------------------------------------------------------------------
@register_jitable
def painleve_factor(theta, mu, sigma, kappa):
    """D = 1 + κ cos θ (cos θ − σ μ sin θ): the sliding normal force is m (g − (L/2) θ̇² sin θ) / D."""
    c = math.cos(theta)
    return 1.0 + kappa * c * (c - sigma * mu * math.sin(theta))


@register_jitable
def contact_dynamics(y, p, out):
    """Accelerations and contact force of the state ``y`` (STATE_NAMES) in its phase, into ``out`` (N_CONTACT,).

    ``out``: θ̈ (rad/s²), u̇ = ẍ_B (m/s²), N (N, +z), F (N, +x), friction power (W, ≥ 0 while
    sliding), D (the Painlevé factor for the sliding direction σ; dimensionless), and the numerator
    N·D = m (g − (L/2) θ̇² sin θ) (N). Jammed: all zero but D and the numerator.
    """
    half = 0.5 * p[P_LENGTH]
    m, g, mu, inertia = p[P_MASS], p[P_G], p[P_MU], p[P_INERTIA]
    theta, omega = y[THETA], y[OMEGA]
    s, c = math.sin(theta), math.cos(theta)
    sigma = y[SLIP]
    kappa = m * half * half / inertia
    for i in range(N_CONTACT):
        out[i] = 0.0
    factor = painleve_factor(theta, mu, sigma, kappa)
    numerator = m * (g - half * s * omega * omega)
    out[C_PAINLEVE_FACTOR] = factor
    out[C_NORMAL_NUMERATOR] = numerator
    phase = int(y[PHASE])
    if phase == SLIDING:
        normal = numerator / factor
        friction = -mu * sigma * normal
        alpha = -half * normal * (c - sigma * mu * s) / inertia
        out[C_CONTACT_ACC] = friction / m - half * (s * alpha + c * omega * omega)
        # σ u rather than |u|: equal while sliding, and smooth past the located end of the slide.
        out[C_FRICTION_POWER] = mu * normal * sigma * y[U]
    elif phase == STICKING:
        alpha = -m * g * half * c / (inertia + m * half * half)
        normal = m * (g + half * (c * alpha - s * omega * omega))
        friction = m * half * (s * alpha + c * omega * omega)
    else:
        return
    out[C_ANGULAR_ACC] = alpha
    out[C_NORMAL] = normal
    out[C_FRICTION] = friction


@kernel(RHS_SIGNATURE)
def bar_rhs(t, y, p, dydt):
    """d/dt of the state (STATE_NAMES); p = [L, m, g, μ, I_G]. Jammed: frozen."""
    out = np.empty(N_CONTACT)
    contact_dynamics(y, p, out)
    for i in range(y.shape[0]):
        dydt[i] = 0.0
    if int(y[PHASE]) == JAMMED:
        return
    dydt[X] = y[U]
    dydt[THETA] = y[OMEGA]
    dydt[U] = out[C_CONTACT_ACC]
    dydt[OMEGA] = out[C_ANGULAR_ACC]
    dydt[FRICTION_WORK] = out[C_FRICTION_POWER]


@kernel(EVENTS_SIGNATURE)
def bar_events(t, y, p, g_out):
    """Six event functions (see the event indices); one that cannot happen in this phase reads 1."""
    out = np.empty(N_CONTACT)
    contact_dynamics(y, p, out)
    phase = int(y[PHASE])
    for i in range(6):
        g_out[i] = 1.0
    if phase == SLIDING:
        g_out[SLIP_STOPS] = y[SLIP] * y[U]
        g_out[PAINLEVE_LIMIT] = out[C_PAINLEVE_FACTOR]
        # N = numerator / D with D > 0 here: N reaches 0 with its numerator (which has no pole at D = 0).
        g_out[LIFT_OFF] = out[C_NORMAL_NUMERATOR]
    elif phase == STICKING:
        g_out[STICK_BREAKS] = p[P_MU] * out[C_NORMAL] - abs(out[C_FRICTION])
        g_out[LIFT_OFF] = out[C_NORMAL]
    else:
        g_out[JAM_STOP] = y[JAM_TIME] + JAM_STOP_DELAY_S - t
    if phase != JAMMED:
        g_out[LANDS] = math.sin(y[THETA])


@register_jitable
def _jam(y, t):
    y[PHASE] = JAMMED
    y[JAM_TIME] = t


@register_jitable
def stick_or_slide_from_rest(t, y, p, breaking):
    """B at rest on the floor: stick if friction can hold it (and ``breaking`` is false), else slide against the
    friction that sticking would need; if that sliding has D ≤ 0 there is no consistent contact force: jam."""
    y[U] = 0.0
    y[PHASE] = STICKING
    out = np.empty(N_CONTACT)
    contact_dynamics(y, p, out)
    if not breaking and abs(out[C_FRICTION]) <= p[P_MU] * out[C_NORMAL]:
        return
    y[PHASE] = SLIDING
    y[SLIP] = -1.0 if out[C_FRICTION] > 0.0 else 1.0
    contact_dynamics(y, p, out)
    if out[C_PAINLEVE_FACTOR] <= 0.0:
        _jam(y, t)


@kernel(RESET_SIGNATURE)
def bar_reset(t, y, p, index):
    """Phase changes: B stops or starts sliding; D reaches 0 while sliding (jam)."""
    if index == SLIP_STOPS:
        stick_or_slide_from_rest(t, y, p, False)
    elif index == STICK_BREAKS:
        stick_or_slide_from_rest(t, y, p, True)
    elif index == PAINLEVE_LIMIT:
        _jam(y, t)


# -- the model -------------------------------------------------------------------------------------
def kernel_parameters(params: Mapping[str, Any]) -> np.ndarray:
    """p = [L (m), m (kg), g (m/s²), μ, I about G (kg·m²)] for the kernels."""
    length, mass = params["length_m"], params["mass_kg"]
    return np.array([length, mass, params["g_m_s2"], params["mu"], float(slender_rod(mass, length)[0, 0])])


def initial_state(params: Mapping[str, Any]) -> np.ndarray:
    """At θ0 without rotation, B sliding at u0 (or at rest: stick or slide); jammed at once where D ≤ 0."""
    y = np.zeros(len(STATE_NAMES))
    y[THETA] = math.radians(params["angle0_deg"])
    y[U] = params["slide_speed0_m_s"]
    y[SLIP] = 1.0
    p = kernel_parameters(params)
    if y[U] == 0.0:
        stick_or_slide_from_rest(0.0, y, p, False)
    else:
        y[SLIP] = math.copysign(1.0, y[U])
        kappa = p[P_MASS] * (0.5 * p[P_LENGTH]) ** 2 / p[P_INERTIA]
        if painleve_factor(y[THETA], p[P_MU], y[SLIP], kappa) <= 0.0:
            _jam(y, 0.0)
    return y


def painleve_band_deg(mu: float) -> tuple[float, float] | None:
    """Angles (deg, from the floor) where sliding away from the lean has D ≤ 0, for a uniform bar (κ = 3).

    D = 0 ⇔ tan²θ − 3μ tan θ + 4 = 0: real roots only for μ ≥ 4/3 (touching at tan θ = 2, θ = 63.43°).
    """
    discriminant = 9.0 * mu * mu - 16.0
    if discriminant < 0.0:
        return None
    root = math.sqrt(discriminant)
    return math.degrees(math.atan((3.0 * mu - root) / 2.0)), math.degrees(math.atan((3.0 * mu + root) / 2.0))


def contact_forces(params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
    """Per state (N, 8): the :func:`contact_dynamics` quantities, shape (N, N_CONTACT)."""
    p = kernel_parameters(params)
    states = np.atleast_2d(states)
    out = np.empty((states.shape[0], N_CONTACT))
    for row, state in zip(out, states):
        contact_dynamics(np.asarray(state, dtype=float), p, row)
    return out


def energy_budget(params: Mapping[str, Any], states: np.ndarray) -> ContactEnergyBudget:
    """Kinetic, potential (floor level zero) and friction work along ``states`` (N, 8); the ladder's budget
    (chapter 6) with no impact: the run stops before any landing."""
    states = np.atleast_2d(states)
    length, mass, g = params["length_m"], params["mass_kg"], params["g_m_s2"]
    half, inertia = 0.5 * length, float(slender_rod(mass, length)[0, 0])
    theta, omega = states[:, THETA], states[:, OMEGA]
    vx = states[:, U] + half * np.sin(theta) * omega
    vz = half * np.cos(theta) * omega
    translational, rotational = 0.5 * mass * (vx**2 + vz**2), 0.5 * inertia * omega**2
    potential, friction_work = mass * g * half * np.sin(theta), states[:, FRICTION_WORK].copy()
    return ContactEnergyBudget(translational, rotational, potential, friction_work, np.zeros_like(rotational))


def end_positions_m(params: Mapping[str, Any], state: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Lower end B and upper end A as (x, z) in m for one state."""
    theta = state[THETA]
    bottom = np.array([state[X], 0.0])
    return bottom, bottom + params["length_m"] * np.array([-math.cos(theta), math.sin(theta)])


def bar_system(params: Mapping[str, Any]) -> OdeSystem:
    return OdeSystem(
        rhs=bar_rhs,
        parameters=kernel_parameters(params),
        state_names=STATE_NAMES,
        events=Events(
            bar_events,
            directions=(-1,) * 6,
            terminal=(False, False, False, True, True, True),
            reset=bar_reset,
            resets=(True, True, True, False, False, False),
            # √(L/g) ≥ 0.03 s over the parameter ranges: 0.005 s steps put several checks in every phase.
            max_step_s=0.005,
        ),
    )


def stop_message(params: Mapping[str, Any], event: EventRecord) -> str:
    """Why the run stopped at ``event`` (a terminal one), in words with the state there."""
    state = event.state
    theta_deg = math.degrees(state[THETA])
    where = f"at t = {event.t_s:.4f} s, θ = {theta_deg:.2f}°"
    if event.index == LIFT_OFF:
        return f"The lower end leaves the floor (N = 0) {where}: free flight is not modelled, so the run stops here."
    if event.index == LANDS:
        return (
            f"The bar lands flat {where}: the landing impact is not modelled here (see the sliding ladder, "
            "6.2); the run stops."
        )
    if event.index != JAM_STOP:
        return ""
    forces = contact_forces(params, state)[0]
    factor, numerator = forces[C_PAINLEVE_FACTOR], forces[C_NORMAL_NUMERATOR]
    direction = "away from" if state[SLIP] * math.cos(state[THETA]) > 0.0 else "towards"
    if abs(factor) < 1e-6:
        why = (
            "D fell to 0 while sliding: the normal force needed grows without bound (a tangential impact would follow)"
        )
    elif numerator > 0.0:
        why = f"sliding would need N = m(g − (L/2)θ̇² sin θ)/D < 0 with D = {factor:.3f}: no contact force N ≥ 0 fits"
    else:
        why = (
            f"with D = {factor:.3f} and a negative numerator both sliding with N > 0 and lifting off fit: the "
            "motion is not unique"
        )
    return (
        f"No consistent contact force: Painlevé's paradox at θ = {theta_deg:.2f}°, μ = {params['mu']:.2f} "
        f"(t = {event.t_s:.4f} s, B sliding {direction} the side the bar leans to): {why}. The run stops here, "
        "not integrated further."
    )


def run_events(params: Mapping[str, Any], *, t_end_s: float, rtol: float = 1e-10) -> tuple[EventRecord, ...]:
    """Every event in [0, t_end_s], located by Dormand–Prince (rtol as given)."""
    result = simulate(
        bar_system(params), DormandPrince(rtol=rtol), initial_state(params), t_end_s=t_end_s, frame_rate_hz=10.0
    )
    return result.events


class SlidingBar(IntegratedModel):
    parameters = PARAMETERS
    methods = ("dopri5",)
    default_method = "dopri5"
    #: Phases change at located events, so the tolerance pilot's two runs meet the same changes.
    accuracy_target = AccuracyTarget(
        1e-6, "", "contact position, angle and their rates: largest error relative to the largest of them"
    )
    accuracy_components = (0, 1, 2, 3)
    series_units = {
        "angle_rad": "rad",
        "contact_speed_m_s": "m/s",
        "normal_force_N": "N",
        "friction_force_N": "N",
        "friction_limit_N": "N",
        "phase": "",
        "painleve_factor": "",
    }
    invariant_units = {"energy_budget_J": "J"}

    def system(self, params):
        return bar_system(params)

    def initial_state(self, params):
        return initial_state(params)

    def fastest_rate_rad_s(self, params, state):
        return math.sqrt(1.5 * params["g_m_s2"] / params["length_m"]) + abs(float(state[OMEGA]))

    def series(self, params, t_s, states):
        forces = contact_forces(params, states)
        return {
            "angle_rad": states[:, THETA].copy(),
            "contact_speed_m_s": states[:, U].copy(),
            "normal_force_N": forces[:, C_NORMAL],
            "friction_force_N": forces[:, C_FRICTION],
            "friction_limit_N": params["mu"] * forces[:, C_NORMAL],
            "phase": states[:, PHASE].copy(),
            "painleve_factor": forces[:, C_PAINLEVE_FACTOR],
        }

    def invariants(self, params, states):
        return {"energy_budget_J": energy_budget(params, states).total_J}

    def invariant_scales(self, params, state):
        return {"energy_budget_J": max(float(energy_budget(params, state).total_J[0]), 1e-300)}

    series_labels = {
        "angle_rad": "θ",
        "contact_speed_m_s": "u (speed of B)",
        "normal_force_N": "N",
        "friction_force_N": "F",
        "friction_limit_N": "μN",
        "painleve_factor": "D (Painlevé)",
        "energy_budget_J": "energy + friction work",
    }

    def energy_parts(self, params, states, *, t_s=None):
        return energy_budget(params, states).parts()

    def stop_message(self, params, event):
        return stop_message(params, event)
