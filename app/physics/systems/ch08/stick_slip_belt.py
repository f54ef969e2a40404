"""Stick–slip: a block on a moving belt, held by a spring, with Coulomb friction.

Frame: x (m) along the belt, the spring's anchor at x = 0 (spring force −k x on
the block, unstretched at x = 0); the belt moves at the constant speed v_b (+x
for v_b > 0). The normal force is N = m g. The friction force F (N, +x) on the
block obeys Coulomb's law as a set-valued relation of the relative velocity
v_rel = ẋ − v_b:

* ``stick`` (v_rel = 0): the block rides with the belt, ẋ = v_b, and friction is
  whatever holds it there, F = k x, as long as |F| ≤ μ_s N;
* ``slip`` (v_rel ≠ 0): F = −μ_k N sign(v_rel), and m ẍ = −k x + F — a harmonic
  motion about x_eq = F / k.

The mode lives in the state and only reset maps change it, at located events:
stick → slip where |k x| reaches μ_s N; slip → stick where v_rel reaches zero and
the force needed to stick, k x, is within μ_s N (otherwise the block slips on,
the other way). So a frame of any length contains no chattering: between events
the right-hand side is smooth.

Energy account (J): friction does work F ẋ = F v_rel + F v_b on the block; the
first part is dissipated (−μ_k N |v_rel| in slip, 0 in stick), the second is what
the belt delivers. So ½ m ẋ² + ½ k x² + dissipated − belt work stays at its
initial value (the invariant ``energy_budget_J``).

Parameters (API contract names): ``mass_kg``, ``stiffness_N_m``, ``belt_speed_m_s``,
``mu_static``, ``mu_kinetic`` (≤ ``mu_static``), ``g_m_s2``, ``x0_m``, ``v0_m_s``.
Series: ``x_m``, ``v_m_s``, ``friction_force_N``, ``friction_limit_N`` (μ N of the
mode: μ_s N in stick, μ_k N in slip), ``mode`` (0 stick, 1 slip), ``dissipated_J``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numba.extending import register_jitable

from app.physics.core.energy import EnergyParts
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.solvers import DormandPrince, Events, OdeSystem, simulate
from app.physics.solvers.integrated_model import IntegratedModel
from app.physics.solvers.kernels import EVENTS_SIGNATURE, RESET_SIGNATURE, RHS_SIGNATURE, kernel
from app.physics.solvers.step_choice import AccuracyTarget

#: State slots: position (m), velocity (m/s), energy dissipated by friction (J, ≥ 0), work done by the
#: belt through friction (J), mode code, slip direction sign(v_rel) (±1, meaningful in slip).
STATE_NAMES = ("x_m", "v_m_s", "dissipated_J", "belt_work_J", "mode", "slip_direction")
X, V, DISSIPATED, BELT_WORK, MODE, SLIP = range(6)
#: Kernel parameters p: [m (kg), k (N/m), v_b (m/s), μ_s, μ_k, g (m/s²)].
P_MASS, P_STIFFNESS, P_BELT_SPEED, P_MU_STATIC, P_MU_KINETIC, P_G = range(6)

STICK, SLIP_MODE = 0, 1
MODE_WORDS = {STICK: "stick", SLIP_MODE: "slip"}
#: Event indices.
SLIP_STOPS, STICK_BREAKS = range(2)
EVENT_WORDS = {
    SLIP_STOPS: "relative velocity reaches zero",
    STICK_BREAKS: "friction reaches μ_s N: the block breaks loose",
}


def _check(values: Mapping[str, Any]) -> None:
    if values["mu_kinetic"] > values["mu_static"]:
        raise ParameterError(
            "mu_kinetic",
            f"the kinetic coefficient ({values['mu_kinetic']:g}) may not exceed the static one "
            f"({values['mu_static']:g})",
        )


PARAMETERS = ParameterSet(
    (
        Parameter("mass_kg", "kg", 1.0, 0.1, 20.0, "Mass of the block", "m", step=0.1),
        Parameter("stiffness_N_m", "N/m", 20.0, 1.0, 500.0, "Stiffness of the spring holding the block", "k", step=1.0),
        Parameter(
            "belt_speed_m_s", "m/s", 0.5, -2.0, 2.0, "Speed of the belt (+x away from the anchor)", "v_b", step=0.01
        ),
        Parameter(
            "mu_static",
            "",
            0.6,
            0.0,
            1.5,
            "Static friction coefficient (stick holds while |F| ≤ μ_s N)",
            "μ_s",
            step=0.01,
        ),
        Parameter(
            "mu_kinetic", "", 0.4, 0.0, 1.5, "Kinetic friction coefficient (slip: |F| = μ_k N)", "μ_k", step=0.01
        ),
        Parameter("g_m_s2", "m/s²", 9.807, 0.1, 100.0, "Gravitational acceleration (N = m g)", "g", step=0.001),
        Parameter("x0_m", "m", 0.0, -1.0, 1.0, "Initial position (spring unstretched at 0)", "x₀", step=0.01),
        Parameter("v0_m_s", "m/s", 0.0, -2.0, 2.0, "Initial velocity of the block", "v₀", step=0.01),
    ),
    check=_check,
)


@register_jitable
def friction_force_and_limit(y, p):
    """(F, μN) in N: the friction force on the block (+x) in its mode and the limit of that mode."""
    normal = p[P_MASS] * p[P_G]
    if int(y[MODE]) == STICK:
        return p[P_STIFFNESS] * y[X], p[P_MU_STATIC] * normal
    return -y[SLIP] * p[P_MU_KINETIC] * normal, p[P_MU_KINETIC] * normal


@kernel(RHS_SIGNATURE)
def belt_rhs(t, y, p, dydt):
    """d/dt of the state (STATE_NAMES); p = [m, k, v_b, μ_s, μ_k, g]. In stick ẋ = v_b exactly."""
    friction, limit = friction_force_and_limit(y, p)
    dydt[X] = y[V]
    if int(y[MODE]) == STICK:
        dydt[V] = 0.0
        dydt[DISSIPATED] = 0.0
    else:
        dydt[V] = (friction - p[P_STIFFNESS] * y[X]) / p[P_MASS]
        # σ v_rel rather than |v_rel|: the same value in slip, and smooth past the located end of the slip,
        # so the step that contains the event keeps its order (|v_rel| would put a kink inside it).
        dydt[DISSIPATED] = limit * y[SLIP] * (y[V] - p[P_BELT_SPEED])
    dydt[BELT_WORK] = friction * p[P_BELT_SPEED]
    dydt[MODE] = 0.0
    dydt[SLIP] = 0.0


@kernel(EVENTS_SIGNATURE)
def belt_events(t, y, p, g_out):
    """Two event functions (see the event indices); the one that cannot happen in this mode reads 1."""
    g_out[SLIP_STOPS] = 1.0
    g_out[STICK_BREAKS] = 1.0
    if int(y[MODE]) == STICK:
        g_out[STICK_BREAKS] = p[P_MU_STATIC] * p[P_MASS] * p[P_G] - abs(p[P_STIFFNESS] * y[X])
    else:
        g_out[SLIP_STOPS] = y[SLIP] * (y[V] - p[P_BELT_SPEED])


@register_jitable
def stick_or_slip_from_relative_rest(y, p, breaking):
    """At v_rel = 0: stick if μ_s N can hold the spring (and ``breaking`` is false), else slip against k x."""
    y[V] = p[P_BELT_SPEED]
    needed = p[P_STIFFNESS] * y[X]
    if not breaking and abs(needed) <= p[P_MU_STATIC] * p[P_MASS] * p[P_G]:
        y[MODE] = STICK
    else:
        # The spring wins: the block moves relative to the belt the way the spring pulls it, −sign(k x).
        y[MODE] = SLIP_MODE
        y[SLIP] = -1.0 if needed > 0.0 else 1.0


@kernel(RESET_SIGNATURE)
def belt_reset(t, y, p, index):
    """Mode changes at the located events."""
    stick_or_slip_from_relative_rest(y, p, index == STICK_BREAKS)


def kernel_parameters(params: Mapping[str, Any]) -> np.ndarray:
    """p = [m (kg), k (N/m), v_b (m/s), μ_s, μ_k, g (m/s²)] for the kernels."""
    names = ("mass_kg", "stiffness_N_m", "belt_speed_m_s", "mu_static", "mu_kinetic", "g_m_s2")
    return np.array([float(params[name]) for name in names])


def initial_state(params: Mapping[str, Any]) -> np.ndarray:
    """Slip in the direction of v₀ − v_b; with v₀ = v_b, stick if the spring force is within μ_s N."""
    y = np.zeros(len(STATE_NAMES))
    y[X], y[V] = params["x0_m"], params["v0_m_s"]
    relative = params["v0_m_s"] - params["belt_speed_m_s"]
    if relative == 0.0:
        stick_or_slip_from_relative_rest(y, kernel_parameters(params), False)
    else:
        y[MODE], y[SLIP] = SLIP_MODE, math.copysign(1.0, relative)
    return y


def belt_system(params: Mapping[str, Any]) -> OdeSystem:
    return OdeSystem(
        rhs=belt_rhs,
        parameters=kernel_parameters(params),
        state_names=STATE_NAMES,
        events=Events(
            belt_events,
            directions=(-1, -1),
            terminal=(False, False),
            reset=belt_reset,
            resets=(True, True),
            # A quarter of the fastest slip period (2π/ω ≥ 0.089 s over the parameter ranges) bounds the step,
            # so a slip phase that starts and ends inside one step is still seen at the step's middle.
            max_step_s=0.02,
        ),
    )


def friction_forces(params: Mapping[str, Any], states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Friction force on the block (N, +x) and the limit μN of its mode (N), each (N_states,)."""
    p = kernel_parameters(params)
    states = np.atleast_2d(states)
    pairs = np.array([friction_force_and_limit(np.asarray(s, dtype=float), p) for s in states])
    return pairs[:, 0], pairs[:, 1]


@dataclass(frozen=True)
class EnergyBudget:
    """Energies along N states (J, arrays (N,)): ``total_J`` = kinetic + spring + dissipated − belt work stays
    constant."""

    kinetic_J: np.ndarray
    spring_J: np.ndarray
    dissipated_J: np.ndarray
    belt_work_J: np.ndarray

    @property
    def total_J(self) -> np.ndarray:
        return self.kinetic_J + self.spring_J + self.dissipated_J - self.belt_work_J


def energy_budget(params: Mapping[str, Any], states: np.ndarray) -> EnergyBudget:
    """Kinetic, spring, dissipated and belt work along ``states`` (N, 6)."""
    states = np.atleast_2d(states)
    return EnergyBudget(
        0.5 * params["mass_kg"] * states[:, V] ** 2,
        0.5 * params["stiffness_N_m"] * states[:, X] ** 2,
        states[:, DISSIPATED].copy(),
        states[:, BELT_WORK].copy(),
    )


@dataclass(frozen=True)
class Transition:
    """A located mode change: time (s), event index and words, the state there (before the reset)."""

    t_s: float
    index: int
    words: str
    state: np.ndarray


def transitions(
    params: Mapping[str, Any], *, t_end_s: float, rtol: float = 1e-10, frame_rate_hz: float = 10.0
) -> tuple[Transition, ...]:
    """Every stick/slip transition in [0, t_end_s], located by Dormand–Prince (rtol as given)."""
    result = simulate(
        belt_system(params),
        DormandPrince(rtol=rtol),
        initial_state(params),
        t_end_s=t_end_s,
        frame_rate_hz=frame_rate_hz,
    )
    return tuple(Transition(e.t_s, e.index, EVENT_WORDS[e.index], e.state) for e in result.events)


@dataclass(frozen=True)
class LimitCycle:
    """The periodic stick–slip motion (closed form), durations in s, positions in m."""

    stick_s: float
    slip_s: float
    #: Where sticking starts and where it breaks (m).
    stick_from_m: float
    stick_to_m: float

    @property
    def period_s(self) -> float:
        return self.stick_s + self.slip_s


def limit_cycle(params: Mapping[str, Any]) -> LimitCycle | None:
    """The stick–slip cycle for v_b ≠ 0 and μ_k < μ_s (None otherwise).

    Sticking ends where k|x| = μ_s N; the slip that follows is harmonic about
    x_eq = sign(v_b) μ_k N / k and returns to v_rel = 0 at the mirror point
    x_eq − (x_break − x_eq), after turning through π + 2 atan(|v_b| / (ω d))
    with d = (μ_s − μ_k) N / k; there k|x| ≤ μ_s N, so it sticks again.
    """
    speed = params["belt_speed_m_s"]
    mu_s, mu_k = params["mu_static"], params["mu_kinetic"]
    if speed == 0.0 or mu_k >= mu_s:
        return None
    normal = params["mass_kg"] * params["g_m_s2"]
    k = params["stiffness_N_m"]
    omega = math.sqrt(k / params["mass_kg"])
    d = (mu_s - mu_k) * normal / k
    direction = math.copysign(1.0, speed)
    x_break = direction * mu_s * normal / k
    x_stick = direction * (2.0 * mu_k - mu_s) * normal / k
    return LimitCycle(
        stick_s=abs(x_break - x_stick) / abs(speed),
        slip_s=(math.pi + 2.0 * math.atan(abs(speed) / (omega * d))) / omega,
        stick_from_m=x_stick,
        stick_to_m=x_break,
    )


class StickSlipBelt(IntegratedModel):
    parameters = PARAMETERS
    methods = ("dopri5",)
    default_method = "dopri5"
    #: Stick and slip change at located events, so the tolerance pilot's two runs meet the same mode changes.
    accuracy_target = AccuracyTarget(
        1e-6, "", "block position and velocity: largest error relative to the larger of them"
    )
    accuracy_components = (X, V)
    series_units = {
        "x_m": "m",
        "v_m_s": "m/s",
        "friction_force_N": "N",
        "friction_limit_N": "N",
        "mode": "",
        "dissipated_J": "J",
    }
    invariant_units = {"energy_budget_J": "J"}

    def system(self, params):
        return belt_system(params)

    def initial_state(self, params):
        return initial_state(params)

    def fastest_rate_rad_s(self, params, state):
        return math.sqrt(params["stiffness_N_m"] / params["mass_kg"])

    def series(self, params, t_s, states):
        friction, limit = friction_forces(params, states)
        return {
            "x_m": states[:, X].copy(),
            "v_m_s": states[:, V].copy(),
            "friction_force_N": friction,
            "friction_limit_N": limit,
            "mode": states[:, MODE].copy(),
            "dissipated_J": states[:, DISSIPATED].copy(),
        }

    def invariants(self, params, states):
        return {"energy_budget_J": energy_budget(params, states).total_J}

    series_labels = {
        "x_m": "x",
        "v_m_s": "ẋ",
        "friction_force_N": "F",
        "friction_limit_N": "μN",
        "dissipated_J": "dissipated by friction",
        "energy_budget_J": "energy + dissipated − belt work",
    }

    def energy_parts(self, params, states, *, t_s=None):
        """The block translates only (½ m ẋ²); the spring's ½ k x²; the belt's work through friction is the drive's."""
        budget = energy_budget(params, states)
        return EnergyParts(
            budget.spring_J,
            translational_kinetic_J=budget.kinetic_J,
            rotational_kinetic_J=np.zeros_like(budget.kinetic_J),
            drive_work_J=budget.belt_work_J,
        )

    def invariant_scales(self, params, state):
        # The energy stored in the spring at the static limit, or the initial energy if larger.
        normal = params["mass_kg"] * params["g_m_s2"]
        stored = 0.5 * (params["mu_static"] * normal) ** 2 / params["stiffness_N_m"]
        budget = energy_budget(params, state)
        return {"energy_budget_J": max(stored, float(budget.kinetic_J[0] + budget.spring_J[0]), 1e-12)}
