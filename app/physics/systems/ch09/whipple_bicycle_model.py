"""The Whipple bicycle coasting on a floor after a sideways push, integrated by the chapter-8 DAE algorithms.

State ``(q, v)`` (16,): the coordinates of :mod:`.whipple_bicycle` (x, y, yaw, lean, rear_spin, pitch, steer,
front_spin; m and rad) and their rates. The equations are the engine's (Kane's with dependent speeds, generated code,
:mod:`app.physics.mechanics.multibody`): the front wheel touching the floor is the one configuration row, no slip at
both wheels the four rolling rows. The start is upright or leaned and steered as asked, rolling at ``speed_m_s`` with
the push's lean rate; the pitch and the five dependent rates are solved from the constraints (only they change).

The model holds while both knife-edge wheels roll on the floor: it stops where the bicycle has fallen (lean beyond
:data:`FALLEN_LEAN_DEG`: the pedals and bars of a real one would strike the floor first; the model has no such parts)
or where the floor would have to pull the front wheel down (its normal force, the configuration row's multiplier,
below zero: the wheel would lift off).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from app.physics.constrained.initial_conditions import ConsistentStart, consistent_initial_conditions
from app.physics.constrained.model import ConstrainedModel
from app.physics.constrained.multibody import multibody_constrained_system
from app.physics.constrained.residuals import multipliers
from app.physics.constrained.system import ConstrainedSystem
from app.physics.core.energy import EnergyParts
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.math.rotations import elementary_rotation_matrix, matrix_from_axis_angle
from app.physics.mechanics.multibody.compiled import CompiledSystem, compiled
from app.physics.mechanics.multibody.linearise import state_matrix
from app.physics.solvers.integrated_model import ModelLimit
from app.physics.systems.ch09.whipple_bicycle import PARAMETERS as BICYCLE_PARAMETERS
from app.physics.systems.ch09.whipple_bicycle import REFERENCE, SYSTEM

COORDINATES = tuple(c.name for c in SYSTEM.coordinates)
N = len(COORDINATES)
X, Y, YAW, LEAN, REAR_SPIN, PITCH, STEER, FRONT_SPIN = range(N)
#: Beyond this lean the model stops: a real bicycle's pedals or handlebar would have struck the floor.
FALLEN_LEAN_DEG = 60.0
FALLEN = "fallen"
LIFT_OFF = "lift_off"

#: How the run starts: a push from upright, or one of the two modes of the linear model at the speed.
START_CHOICES = ("push", "weave mode", "capsize mode")

PARAMETERS = ParameterSet(
    (
        *BICYCLE_PARAMETERS.parameters,
        Parameter(
            "push_lean_rate_rad_s", "rad/s", 0.5, -5.0, 5.0,
            "The sideways push: the lean rate it gives the bicycle at the start", "φ̇₀",
        ),
        Parameter("lean_0_deg", "deg", 0.0, -45.0, 45.0, "Lean at the start (positive: to the right)", "φ₀"),
        Parameter("steer_0_deg", "deg", 0.0, -45.0, 45.0, "Steer angle at the start (positive: to the left)", "δ₀"),
        Parameter("start", "", "push", kind="choice", choices=START_CHOICES, label="start",
                  description="push: the lean rate above, from upright; weave mode or capsize mode: lean, steer and "
                  "their rates in the proportions of that eigenvector of the linear model at this speed"),
        Parameter("mode_lean_deg", "deg", 3.0, 0.01, 20.0, "A mode start's lean (its largest lean for the weave)",
                  "φ_mode"),
    )
)  # fmt: skip


def bicycle_model() -> CompiledSystem:
    """The generated equations (derived once, kept on disk; see :mod:`app.physics.mechanics.multibody.compiled`)."""
    return compiled(SYSTEM)


def pose(params: Mapping[str, Any], q: np.ndarray) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """Each body's (origin (3,) m, R (3, 3) body → world) at coordinates ``q``: the wheels' origins are their
    centres, the rear frame's the rear wheel's centre, the front frame's the steer axis's foot (level with the rear
    contact when upright)."""
    w, c, tilt = (float(params[k]) for k in ("wheelbase_m", "trail_m", "steer_axis_tilt_rad"))
    r_rear, r_front = float(params["rear_wheel_radius_m"]), float(params["front_wheel_radius_m"])
    axle = elementary_rotation_matrix(2, float(q[YAW])) @ elementary_rotation_matrix(0, float(q[LEAN]))
    rear_centre = np.array([float(q[X]), float(q[Y]), 0.0]) + axle @ np.array([0.0, 0.0, r_rear])
    rear_frame = axle @ elementary_rotation_matrix(1, float(q[PITCH]))
    foot = rear_centre + rear_frame @ np.array([w + c, 0.0, -r_rear])
    front_frame = rear_frame @ matrix_from_axis_angle(np.array([-math.sin(tilt), 0.0, math.cos(tilt)]), float(q[STEER]))
    front_centre = foot + front_frame @ np.array([-c, 0.0, r_front])
    return {
        "rear_wheel": (rear_centre, axle @ elementary_rotation_matrix(1, float(q[REAR_SPIN]))),
        "rear_frame": (rear_centre, rear_frame),
        "front_frame": (foot, front_frame),
        "front_wheel": (front_centre, front_frame @ elementary_rotation_matrix(1, float(q[FRONT_SPIN]))),
    }


def forward_speed_m_s(params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
    """The rear wheel's rolling speed r_R θ̇_R (m/s) along ``states`` (N, 16)."""
    return float(params["rear_wheel_radius_m"]) * np.atleast_2d(states)[:, N + REAR_SPIN]


@dataclass(frozen=True)
class ModeShape:
    """One mode of the linear model about upright rolling: its eigenvalue (1/s) and eigenvector over (lean, steer,
    lean rate, steer rate), the lean component made real and positive."""

    name: str
    eigenvalue: complex
    vector: np.ndarray

    def start(self, lean_rad: float) -> tuple[float, float, float, float]:
        """(lean, steer, lean rate, steer rate) at the mode's start: the vector's real part, scaled to ``lean_rad``
        of lean (for an oscillating mode, the lean's largest value; the phase where it is)."""
        x = np.real(self.vector) * lean_rad
        return float(x[0]), float(x[1]), float(x[2]), float(x[3])

    @property
    def steer_per_lean(self) -> complex:
        """Steer over lean in the mode (rad/rad): its size and, for an oscillating mode, its phase lead."""
        return complex(self.vector[1] / self.vector[0])


def mode_shape(params: Mapping[str, Any], name: str) -> ModeShape:
    """The weave (the oscillating pair, the one with Im λ > 0) or the capsize (the real mode nearest zero) of the
    linear model at ``params``' speed. Raises ParameterError where the model has no such mode at that speed (the
    weave is two real modes below about 0.7 m/s for the benchmark)."""
    design = {name_: params[name_] for name_ in BICYCLE_PARAMETERS.by_name}
    values, vectors = np.linalg.eig(state_matrix(bicycle_model(), design, REFERENCE))
    if name == "weave":
        oscillating = [k for k in range(len(values)) if values[k].imag > 1e-9]
        if not oscillating:
            raise ParameterError(
                "start", f"at {float(params['speed_m_s']):g} m/s the linear model has no oscillating (weave) mode"
            )
        k = max(oscillating, key=lambda i: values[i].real)
    else:
        real = [k for k in range(len(values)) if abs(values[k].imag) <= 1e-9]
        k = min(real, key=lambda i: abs(values[i].real))
    vector = vectors[:, k] / vectors[0, k]  # lean component 1: real and positive
    return ModeShape(name, complex(values[k]), vector)


class WhippleBicycleMotion(ConstrainedModel):
    """The riderless bicycle given a sideways push while rolling at ``speed_m_s``: inside the self-stable band the
    wobble dies away; below it the weave grows, above it the bicycle slowly capsizes."""

    parameters = PARAMETERS
    start_parameters = ()  # the start is built from the speed and the push (see consistent_start)
    series_units = {
        "x_m": "m",
        "y_m": "m",
        "yaw_rad": "rad",
        "lean_rad": "rad",
        "steer_rad": "rad",
        "forward_speed_m_s": "m/s",
        "energy_J": "J",
        "front_normal_force_N": "N",
    }
    invariant_units = {"energy": "J", "constraint_position": "m", "constraint_velocity": "m/s"}

    def model(self) -> CompiledSystem:
        return bicycle_model()

    def constrained_system(self, params: Mapping[str, Any]) -> ConstrainedSystem:
        return multibody_constrained_system(self.model(), params)

    def consistent_start(self, params: Mapping[str, Any]) -> ConsistentStart:
        """Upright (or leaned and steered as asked) at the origin heading along +x, the rear wheel rolling at
        speed_m_s with the push's lean rate; the pitch and the dependent rates are solved for, nothing else moves."""
        speed = float(params["speed_m_s"])
        q0, v0 = np.zeros(N), np.zeros(N)
        q0[LEAN], q0[STEER] = math.radians(float(params["lean_0_deg"])), math.radians(float(params["steer_0_deg"]))
        v0[X], v0[REAR_SPIN] = speed, speed / float(params["rear_wheel_radius_m"])
        v0[FRONT_SPIN] = speed / float(params["front_wheel_radius_m"])
        v0[LEAN] = float(params["push_lean_rate_rad_s"])
        start = params.get("start", "push")
        if start != "push":
            shape = mode_shape(params, "weave" if start == "weave mode" else "capsize")
            q0[LEAN], q0[STEER], v0[LEAN], v0[STEER] = shape.start(math.radians(float(params["mode_lean_deg"])))
        system = self.constrained_system(params)
        dependent_q = {SYSTEM.index(name) for name in SYSTEM.dependent_coordinates}
        dependent_v = {SYSTEM.index(name) for name in SYSTEM.dependent_speeds}
        units = ("m", "m", *("rad",) * 6, "m/s", "m/s", *("rad/s",) * 6)
        return consistent_initial_conditions(
            system,
            q0,
            v0,
            fixed_positions=[i for i in range(N) if i not in dependent_q],
            fixed_velocities=[i for i in range(N) if i not in dependent_v],
            names=(*COORDINATES, *(f"{name}_rate" for name in COORDINATES)),
            units=units,
        )

    def energy_J(self, params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
        """T + V (J) along ``states`` (N, 16); V = 0 with every mass centre on the floor."""
        return self.constrained_energy_parts(params, states).total_J

    def constrained_energy_parts(self, params: Mapping[str, Any], states: np.ndarray) -> EnergyParts:
        """½ Σ m v_G², ½ Σ ω·I_G ω over the four bodies, and Σ m g z_G (J) along ``states`` (N, 16)."""
        model, p = self.model(), self.model().parameter_array(params)
        parts = np.array([model.energy_parts(state[:N], state[N:], p) for state in np.atleast_2d(states)])
        return EnergyParts(parts[:, 2], translational_kinetic_J=parts[:, 0], rotational_kinetic_J=parts[:, 1])

    def energy_scale_J(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """The rider's fall m_B g |z_B| or the energy, whichever is larger (J)."""
        fall = (
            float(params["rear_frame_mass_kg"]) * float(params["gravity_m_s2"]) * abs(float(params["rear_frame_z_m"]))
        )
        return max(fall, float(abs(self.energy_J(params, state[None, :])[0])), 1e-12)

    def residual_scales(self, params: Mapping[str, Any]) -> tuple[float, float]:
        """The rear wheel's radius (m) and the speed, at least 1 m/s (m/s)."""
        return float(params["rear_wheel_radius_m"]), max(abs(float(params["speed_m_s"])), 1.0)

    def fastest_rate_rad_s(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """The wheels' spin rates, the lean and steer rates, and the fastest linear mode (about 3 v + 5 1/s for the
        benchmark: 14 1/s at 5 m/s), rad/s."""
        rates = np.abs(np.asarray(state[N:], dtype=float))
        speed = abs(float(params["speed_m_s"]))
        return max(float(np.max(rates)), 3.0 * speed + 5.0, 1.0)

    def constrained_series(self, params, t_s, states, multipliers_N):
        return {
            "x_m": states[:, X],
            "y_m": states[:, Y],
            "yaw_rad": states[:, YAW],
            "lean_rad": states[:, LEAN],
            "steer_rad": states[:, STEER],
            "forward_speed_m_s": forward_speed_m_s(params, states),
            "energy_J": self.energy_J(params, states),
            "front_normal_force_N": multipliers_N[:, 0],
        }

    def front_normal_force_N(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> np.ndarray:
        """The floor's push on the front wheel (N): the multiplier of the row that keeps it on the floor."""
        return multipliers(self.constrained_system(params), t_s, np.atleast_2d(states))[:, 0]

    def model_limit(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> ModelLimit | None:
        """Where the bicycle has fallen (|lean| > 60°) or the front wheel would lift off (its normal force < 0)."""
        full = self.constrained_view(params, states)
        fallen = np.nonzero(np.abs(np.degrees(full[:, LEAN])) > FALLEN_LEAN_DEG)[0]
        normal = self.front_normal_force_N(params, t_s, full)
        lifted = np.nonzero(normal < 0.0)[0]
        first = min([*fallen[:1], *lifted[:1]], default=None)
        if first is None:
            return None
        frames = max(int(first), 1)
        if first in fallen[:1]:
            return ModelLimit(
                frames,
                FALLEN,
                f"At t = {float(t_s[first]):.2f} s the bicycle has fallen: its lean passed {FALLEN_LEAN_DEG:.0f}° "
                f"({math.degrees(float(full[first, LEAN])):.1f}°). A real one's pedals or handlebar would have struck "
                "the floor; the model has no such parts, so the motion stops here.",
            )
        return ModelLimit(
            frames,
            LIFT_OFF,
            f"At t = {float(t_s[first]):.2f} s the floor would have to pull the front wheel down (normal force "
            f"{float(normal[first]):.1f} N): it would lift off, which this model (wheels always on the floor) cannot "
            "describe, so the motion stops here.",
        )
