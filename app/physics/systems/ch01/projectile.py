"""A particle in flight under gravity and air drag: work–energy and impulse–momentum.

Frame: fixed xyz, z vertical, launch in the xz plane from (0, 0, height0).
Forces: weight -m g k and drag -(b + c|v|) v, with b the linear coefficient
(kg/s) and c the quadratic one (kg/m). The motion is integrated to landing
(z = 0) together with the work and impulse of the drag force, so the two
principles can be checked against each other:

    T(t) - T(0) = W_gravity + W_drag,      m v(t) - m v(0) = I_gravity + I_drag.

With c = 0 the motion has a closed form (:func:`linear_drag_closed_form`), used
to check the integrator; without any drag it is the vacuum parabola
(:func:`vacuum_flight`), the comparison a lesson draws.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.core.solution import ExampleStory, Plot, PlotSeries, Solution, Step, WorkedExample
from app.physics.solvers import DormandPrince, Events, OdeSystem
from app.physics.solvers.kernels import EVENTS_SIGNATURE, RHS_SIGNATURE, kernel

INPUTS = ParameterSet(
    (
        Parameter("mass_kg", "kg", 0.145, 0.001, 1000.0, "Mass of the particle", "m", step=0.005),
        Parameter("speed0_m_s", "m/s", 40.0, 0.1, 200.0, "Launch speed", "v₀", step=0.5),
        Parameter("elevation_deg", "deg", 35.0, 1.0, 90.0, "Launch angle above the horizontal", "α", step=1),
        Parameter("height0_m", "m", 0.0, 0.0, 200.0, "Launch height above the ground", "h₀", step=1),
        Parameter("linear_drag_kg_s", "kg/s", 0.0, 0.0, 10.0, "Linear drag coefficient b in F = −b v", "b", step=0.001),
        Parameter(
            "quadratic_drag_kg_m",
            "kg/m",
            7.6e-4,
            0.0,
            1.0,
            "Quadratic drag coefficient c in F = −c|v| v",
            "c",
            step=1e-5,
        ),
        Parameter("g_m_s2", "m/s²", 9.807, 0.1, 30.0, "Gravitational acceleration", "g", step=0.001),
    )
)

#: Integration tolerances: relative 1e-11 keeps the energy balance residual near
#: 1e-9 of the launch kinetic energy, far below anything a plot can show.
RTOL, ATOL = 1e-11, 1e-12
MAX_FLIGHT_S = 2000.0


@dataclass(frozen=True)
class ProjectileTrajectory:
    """Samples of one flight, uniform in time from launch to landing.

    Arrays have N rows; vectors are (N, 3) on xyz. SI units throughout.
    """

    t_s: np.ndarray
    position_m: np.ndarray
    velocity_m_s: np.ndarray
    kinetic_energy_J: np.ndarray
    work_gravity_J: np.ndarray
    work_drag_J: np.ndarray
    momentum_change_N_s: np.ndarray
    impulse_gravity_N_s: np.ndarray
    impulse_drag_N_s: np.ndarray
    drag_force_N: np.ndarray
    rhs_evaluations: int
    #: Time (s) and position (m, shape (3,)) of the highest point, located as the event v_z = 0
    #: (the launch itself if the particle starts moving down).
    apex_time_s: float
    apex_position_m: np.ndarray

    @property
    def climb_time_s(self) -> float:
        """Launch to the highest point (s)."""
        return self.apex_time_s

    @property
    def fall_time_s(self) -> float:
        """Highest point to landing (s)."""
        return float(self.t_s[-1]) - self.apex_time_s

    @property
    def energy_residual_J(self) -> np.ndarray:
        """ΔT − (W_gravity + W_drag): zero in exact arithmetic."""
        return (self.kinetic_energy_J - self.kinetic_energy_J[0]) - (self.work_gravity_J + self.work_drag_J)

    @property
    def momentum_residual_N_s(self) -> np.ndarray:
        """m Δv − (I_gravity + I_drag), shape (N, 3): zero in exact arithmetic."""
        return self.momentum_change_N_s - (self.impulse_gravity_N_s + self.impulse_drag_N_s)


def initial_velocity(speed0_m_s: float, elevation_deg: float) -> np.ndarray:
    a = np.radians(elevation_deg)
    return np.array([speed0_m_s * np.cos(a), 0.0, speed0_m_s * np.sin(a)])


def _drag_force(m: float, b: float, c: float, v: np.ndarray) -> np.ndarray:
    return -(b + c * np.linalg.norm(v, axis=-1, keepdims=True)) * v


@kernel(RHS_SIGNATURE)
def projectile_rhs(t, y, p, dydt):
    """y = [position (3), velocity (3), drag work (1), drag impulse (3)]; p = [m, g, b, c]."""
    m, g, b, c = p[0], p[1], p[2], p[3]
    speed = math.sqrt(y[3] * y[3] + y[4] * y[4] + y[5] * y[5])
    k = -(b + c * speed)
    for i in range(3):
        dydt[i] = y[3 + i]
        dydt[3 + i] = k * y[3 + i] / m
        dydt[7 + i] = k * y[3 + i]
    dydt[5] -= g
    dydt[6] = k * speed * speed


@dataclass(frozen=True)
class VacuumFlight:
    """The same launch without drag (closed form): times in s, lengths in m."""

    flight_time_s: float
    range_m: float
    apex_height_m: float
    apex_time_s: float


#: The two legs of a flight differ "equally long" below this fraction of the flight time: the event
#: times are located to ~1e-12 s, while the smallest drag the controls allow (c = 1e-5 kg/m) makes
#: the fall longer by ~1e-4 of the flight.
EQUAL_LEGS_RTOL = 1e-9
#: Words of :func:`longer_leg`: the climb, the fall, neither.
LONGER_LEG_WORDS = ("the climb", "the fall", "neither: equal")


@kernel(EVENTS_SIGNATURE)
def landing_and_apex(t, y, p, g_out):
    """g_out[0] = z (m): the flight ends where it reaches 0 falling; g_out[1] = v_z (m/s): the apex, recorded."""
    g_out[0] = y[2]
    g_out[1] = y[5]


def simulate(inputs: Mapping[str, Any], samples: int = 241) -> ProjectileTrajectory:
    """Integrate launch to landing (Dormand–Prince 5(4), rtol 1e-11, landing as an event) and sample ``samples``
    instants."""
    m, g = inputs["mass_kg"], inputs["g_m_s2"]
    b, c = inputs["linear_drag_kg_s"], inputs["quadratic_drag_kg_m"]
    r0 = np.array([0.0, 0.0, inputs["height0_m"]])
    v0 = initial_velocity(inputs["speed0_m_s"], inputs["elevation_deg"])
    if r0[2] == 0.0 and v0[2] <= 0.0:
        raise ValueError("the particle starts on the ground moving down: raise height0_m or elevation_deg")
    system = OdeSystem(
        rhs=projectile_rhs,
        parameters=np.array([m, g, b, c], dtype=float),
        state_names=("x", "y", "z", "vx", "vy", "vz", "work_drag", "impulse_x", "impulse_y", "impulse_z"),
        events=Events(landing_and_apex, directions=(-1, -1), terminal=(True, False)),
    )
    y0 = np.concatenate([r0, v0, [0.0], np.zeros(3)])
    solver = DormandPrince(rtol=RTOL, atol=ATOL)
    # Pass 1 finds the landing time; pass 2 samples the flight uniformly up to it.
    y = y0.copy()
    first = solver.solve(system, 0.0, y, np.array([MAX_FLIGHT_S]), np.empty((1, 10)))
    if first.status not in ("ok", "event"):
        raise ValueError(f"integration failed: {first.status}")
    if first.t_event_s is None:
        raise ValueError(f"the particle did not land within {MAX_FLIGHT_S:g} s")
    t_land = first.t_event_s
    apex = next((event for event in first.events if event.index == 1), None)
    apex_time_s, apex_position_m = (apex.t_s, apex.state[0:3].copy()) if apex is not None else (0.0, r0.copy())
    t = np.linspace(0.0, t_land, samples)
    y_samples = np.empty((samples, 10))
    y_samples[0] = y0
    second = solver.solve(system, 0.0, y0.copy(), t[1:], y_samples[1:], events=False)
    y = y_samples
    rhs_evaluations = first.rhs_evals + second.rhs_evals
    y[-1, 2] = 0.0  # the event root is exact to ~1e-12 m; pin it for display
    position, velocity = y[:, 0:3], y[:, 3:6]
    k = np.array([0.0, 0.0, 1.0])
    return ProjectileTrajectory(
        t_s=t,
        position_m=position,
        velocity_m_s=velocity,
        kinetic_energy_J=0.5 * m * np.einsum("ij,ij->i", velocity, velocity),
        work_gravity_J=-m * g * (position[:, 2] - r0[2]) + 0.0,  # + 0.0 turns -0.0 into 0.0
        work_drag_J=y[:, 6],
        momentum_change_N_s=m * (velocity - v0),
        impulse_gravity_N_s=-m * g * t[:, None] * k,
        impulse_drag_N_s=y[:, 7:10],
        drag_force_N=_drag_force(m, b, c, velocity),
        rhs_evaluations=int(rhs_evaluations),
        apex_time_s=float(apex_time_s),
        apex_position_m=apex_position_m,
    )


def vacuum_flight(inputs: Mapping[str, Any]) -> VacuumFlight:
    """The launch of ``inputs`` with no drag, landing on z = 0: the parabola's closed form."""
    g, h0 = inputs["g_m_s2"], inputs["height0_m"]
    v0 = initial_velocity(inputs["speed0_m_s"], inputs["elevation_deg"])
    climb_rate = float(v0[2])
    if h0 == 0.0 and climb_rate <= 0.0:
        raise ValueError("the particle starts on the ground moving down: raise height0_m or elevation_deg")
    flight_time = (climb_rate + math.sqrt(climb_rate**2 + 2.0 * g * h0)) / g
    apex_time = max(climb_rate, 0.0) / g
    return VacuumFlight(
        flight_time_s=flight_time,
        range_m=float(v0[0]) * flight_time,
        apex_height_m=h0 + 0.5 * g * apex_time**2,
        apex_time_s=apex_time,
    )


def range_percent_of_vacuum(trajectory: ProjectileTrajectory, vacuum: VacuumFlight) -> float:
    """The range with drag as a percentage of the vacuum range; NaN for a (nearly) vertical launch, whose
    ranges are rounding noise (below 1e-9 of the highest point in a vacuum)."""
    if vacuum.range_m <= 1e-9 * vacuum.apex_height_m:
        return math.nan
    return 100.0 * float(trajectory.position_m[-1, 0]) / vacuum.range_m


def longer_leg(trajectory: ProjectileTrajectory) -> str:
    """Which leg of the flight takes longer, as one of :data:`LONGER_LEG_WORDS` (equal within :data:`EQUAL_LEGS_RTOL`).

    Drag slows the climb more than gravity alone and brakes the fall, so with drag the fall takes longer;
    in a vacuum from ground level the two are equal.
    """
    climb, fall, neither = LONGER_LEG_WORDS
    difference = trajectory.fall_time_s - trajectory.climb_time_s
    if abs(difference) <= EQUAL_LEGS_RTOL * float(trajectory.t_s[-1]):
        return neither
    return fall if difference > 0.0 else climb


def linear_drag_closed_form(inputs: Mapping[str, Any], t_s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Exact position (m) and velocity (m/s), shape (N, 3), for c = 0 and b > 0."""
    m, g, b = inputs["mass_kg"], inputs["g_m_s2"], inputs["linear_drag_kg_s"]
    if b <= 0:
        raise ValueError("the closed form needs linear_drag_kg_s > 0")
    k = b / m
    v0 = initial_velocity(inputs["speed0_m_s"], inputs["elevation_deg"])
    t = np.asarray(t_s, dtype=float)
    decay = np.exp(-k * t)
    vx = v0[0] * decay
    vz = (v0[2] + g / k) * decay - g / k
    x = v0[0] / k * (1.0 - decay)
    z = inputs["height0_m"] + (v0[2] + g / k) / k * (1.0 - decay) - g / k * t
    zeros = np.zeros_like(t)
    return np.stack([x, zeros, z], axis=-1), np.stack([vx, zeros, vz], axis=-1)


def solve(inputs: Mapping[str, Any]) -> Solution:
    traj = simulate(inputs)
    dT = float(traj.kinetic_energy_J[-1] - traj.kinetic_energy_J[0])
    Wg, Wd = float(traj.work_gravity_J[-1]), float(traj.work_drag_J[-1])
    dp = traj.momentum_change_N_s[-1]
    Ig, Id = traj.impulse_gravity_N_s[-1], traj.impulse_drag_N_s[-1]
    energy_residual = float(np.max(np.abs(traj.energy_residual_J)))
    momentum_residual = float(np.max(np.linalg.norm(traj.momentum_residual_N_s, axis=1)))
    speed = np.linalg.norm(traj.velocity_m_s, axis=1)
    outputs = {
        "flight_time_s": float(traj.t_s[-1]),
        "range_m": float(traj.position_m[-1, 0]),
        "max_height_m": float(traj.position_m[:, 2].max()),
        "landing_speed_m_s": float(speed[-1]),
        "kinetic_energy_change_J": dT,
        "work_gravity_J": Wg,
        "work_drag_J": Wd,
        "energy_residual_J": energy_residual,
        "momentum_change_N_s": dp,
        "impulse_N_s": Ig + Id,
        "momentum_residual_N_s": momentum_residual,
    }
    steps = (
        Step(
            "Equation of motion",
            r"m\dot{\bar v} = -mg\,\bar k - (b + c|\bar v|)\,\bar v",
            {"v0": traj.velocity_m_s[0], "flight_time": outputs["flight_time_s"], "range": outputs["range_m"]},
            {"v0": "m/s", "flight_time": "s", "range": "m"},
        ),
        Step(
            "Work–energy: kinetic energy change equals the work done",
            r"T_2 - T_1 = \underbrace{-mg(z_2 - z_1)}_{W_g} + \underbrace{\int_{t_1}^{t_2} \bar F_d\cdot\bar "
            r"v\,dt}_{W_d}",
            {
                "T1": traj.kinetic_energy_J[0],
                "T2": traj.kinetic_energy_J[-1],
                "W_g": Wg,
                "W_d": Wd,
                "residual": energy_residual,
            },
            {"T1": "J", "T2": "J", "W_g": "J", "W_d": "J", "residual": "J"},
        ),
        Step(
            "Impulse–momentum: momentum change equals the impulse",
            r"m\bar v_2 - m\bar v_1 = \underbrace{-mg\,t\,\bar k}_{\bar I_g} + \underbrace{\int_{t_1}^{t_2}\bar "
            r"F_d\,dt}_{\bar I_d}",
            {"m_dv": dp, "I_g": Ig, "I_d": Id, "residual": momentum_residual},
            {"m_dv": "N·s", "I_g": "N·s", "I_d": "N·s", "residual": "N·s"},
        ),
        Step(
            "Check: each principle balances at landing, and drag only takes energy away",
            r"T_2 - T_1 = W_g + W_d,\quad m\bar v_2 - m\bar v_1 = \bar I_g + \bar I_d,\quad W_d \le 0"
            r"\ \Rightarrow\ v_2 \le \sqrt{v_0^2 + 2gh_0}\ \text{(no drag)}",
            {
                "T2 - T1": dT,
                "W_g + W_d": Wg + Wd,
                "m_dv": dp,
                "I_g + I_d": Ig + Id,
                "v2": outputs["landing_speed_m_s"],
                "v2 (no drag)": math.sqrt(inputs["speed0_m_s"] ** 2 + 2.0 * inputs["g_m_s2"] * inputs["height0_m"]),
            },
            {"T2 - T1": "J", "W_g + W_d": "J", "m_dv": "N·s", "I_g + I_d": "N·s", "v2": "m/s", "v2 (no drag)": "m/s"},
            scales={"T2 - T1": float(traj.kinetic_energy_J[0]), "W_g + W_d": float(traj.kinetic_energy_J[0])},
        ),
    )
    plots = (
        Plot(
            "Work–energy along the flight",
            "t (s)",
            "energy (J)",
            (
                PlotSeries("T − T₁", traj.t_s, traj.kinetic_energy_J - traj.kinetic_energy_J[0]),
                PlotSeries("W_gravity", traj.t_s, traj.work_gravity_J),
                PlotSeries("W_drag", traj.t_s, traj.work_drag_J),
                PlotSeries("W_gravity + W_drag", traj.t_s, traj.work_gravity_J + traj.work_drag_J),
            ),
        ),
        Plot(
            "Impulse–momentum along the flight (x and z components)",
            "t (s)",
            "momentum (N·s)",
            (
                PlotSeries("m Δv_x", traj.t_s, traj.momentum_change_N_s[:, 0]),
                PlotSeries("I_x", traj.t_s, traj.impulse_gravity_N_s[:, 0] + traj.impulse_drag_N_s[:, 0]),
                PlotSeries("m Δv_z", traj.t_s, traj.momentum_change_N_s[:, 2]),
                PlotSeries("I_z", traj.t_s, traj.impulse_gravity_N_s[:, 2] + traj.impulse_drag_N_s[:, 2]),
            ),
        ),
    )
    return Solution(outputs=outputs, steps=steps, plots=plots)


EXAMPLE = WorkedExample(
    id="particle-work-energy",
    title="A projectile with drag: work–energy and impulse–momentum",
    chapter=1,
    inputs=INPUTS,
    solve=solve,
    output_units={
        "flight_time_s": "s",
        "range_m": "m",
        "max_height_m": "m",
        "landing_speed_m_s": "m/s",
        "kinetic_energy_change_J": "J",
        "work_gravity_J": "J",
        "work_drag_J": "J",
        "energy_residual_J": "J",
        "momentum_change_N_s": "N·s",
        "impulse_N_s": "N·s",
        "momentum_residual_N_s": "N·s",
    },
    section="1.2",
    story=ExampleStory(
        situation=(
            "A baseball of mass 0.145 kg is hit from ground level at 40 m/s, 35° above the horizontal. Air "
            "resists it with a quadratic drag force $-c|\\bar v|\\bar v$, $c = 7.6\\times10^{-4}$ kg/m, "
            "strong enough that at launch the drag is nearly as large as the ball's weight; gravity is "
            "9.807 m/s². The ball flies until it comes back down to the ground."
        ),
        wanted=(
            "The flight time, the range and the highest point; the landing speed; and both integral "
            "principles over the flight: the change of kinetic energy against the work of gravity and of drag, "
            "and the change of momentum against the impulse of gravity and of drag."
        ),
        approach=(
            "Newton's second law in a fixed, inertial frame $xyz$ ($z$ up) gives three coupled equations: "
            "quadratic drag ties the components together through $|\\bar v|$, so there is no closed form and we "
            "integrate numerically to the landing. Alongside the motion we integrate the drag's power and its "
            "force, so the work and impulse come out of the same run. Finding them afterwards from sampled "
            "points instead would add a quadrature error of its own, and the two principles could then no "
            "longer tell us how accurate the integration itself is."
        ),
        check=(
            "Work–energy and impulse–momentum are consequences of Newton's law, not extra physics, so on an "
            "accurate solution each must balance: $T_2 - T_1$ beside $W_g + W_d$ and $m\\Delta\\bar v$ beside "
            "$\\bar I_g + \\bar I_d$. Drag always opposes the velocity, so $W_d$ is negative and the ball must "
            "land slower than it would without air, $\\sqrt{v_0^2 + 2gh_0}$. The last step shows each pair."
        ),
        what_if=(
            "Move the **quadratic drag coefficient c** down to 0. The drag work and drag impulse vanish, the "
            "landing speed climbs back to the launch speed of 40 m/s, and the range grows from about 100 m to "
            "the vacuum parabola's 153 m. In the scene, watch the trajectory open into a symmetric arc, and in "
            "the plots watch $W_{\\rm drag}$ lie flat on zero."
        ),
    ),
)
