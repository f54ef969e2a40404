"""The rattleback spun on a floor, integrated by the chapter-8 DAE algorithms.

State ``(q, v)`` (12,): the coordinates of :mod:`.rattleback` (G's x, y, z in m; yaw, roll, pitch in rad) and their
rates. The equations are the engine's (Kane's with dependent speeds, generated code): the underside touching the
floor is the one configuration row, no slip at the touching point the two rolling rows. The start is tilted and
spinning as asked; z and the rates of x, y, z are solved from the constraints.

The model holds while the ellipsoid rolls on the floor: it stops where the floor would have to pull the body down
(the normal force, the configuration row's multiplier, below zero: the body would hop). The scene also says where the
grip needed to stop slip exceeds a toy's on a table (a friction coefficient above :data:`GRIP_NEEDED`): a real one
would skid there, which this model (no slip ever) does not describe.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.bodies.inertia import check_inertia_tensor
from app.physics.constrained.initial_conditions import ConsistentStart, consistent_initial_conditions
from app.physics.constrained.model import ConstrainedModel
from app.physics.constrained.multibody import multibody_constrained_system
from app.physics.constrained.residuals import multipliers
from app.physics.constrained.system import ConstrainedSystem
from app.physics.core.energy import EnergyParts
from app.physics.core.parameters import Parameter, ParameterError, ParameterSet
from app.physics.math.rotations import elementary_rotation_matrix
from app.physics.mechanics.multibody.compiled import CompiledSystem, compiled
from app.physics.solvers.integrated_model import ModelLimit
from app.physics.systems.ch08.rattleback import PARAMETERS as RATTLEBACK_PARAMETERS
from app.physics.systems.ch08.rattleback import SYSTEM

COORDINATES = tuple(c.name for c in SYSTEM.coordinates)
N = len(COORDINATES)
X, Y, Z, YAW, ROLL, PITCH = range(N)
HOP = "hop"
SKID = "skid"
#: The friction coefficient beyond which a real rattleback on a table would skid rather than roll.
GRIP_NEEDED = 0.5

PARAMETERS = ParameterSet(
    (
        *(p for p in RATTLEBACK_PARAMETERS.parameters if p.name != "spin_rad_s"),
        Parameter("spin_0_rad_s", "rad/s", 5.0, -30.0, 30.0,
                  "Spin about the vertical at the start (positive: anticlockwise seen from above)", "ψ̇₀"),
        Parameter("roll_0_deg", "deg", 0.5, -10.0, 10.0, "Roll about the long (x) axis at the start", "φ₀"),
        Parameter("pitch_0_deg", "deg", -0.5, -10.0, 10.0, "Pitch about the middle (y) axis at the start", "θ₀"),
        Parameter("roll_rate_0_rad_s", "rad/s", 0.0, -10.0, 10.0,
                  "Roll rate at the start (a tap on one side)", "φ̇₀"),
        Parameter("pitch_rate_0_rad_s", "rad/s", 0.0, -10.0, 10.0,
                  "Pitch rate at the start (a tap on one end)", "θ̇₀"),
    )
)  # fmt: skip


def rattleback_model() -> CompiledSystem:
    """The generated equations (derived once, kept on disk)."""
    return compiled(SYSTEM)


def system_params(params: Mapping[str, Any]) -> dict[str, float]:
    """The system's parameters (the steady spin the eigenvalues are about: the start's spin)."""
    physical = {p.name: float(params[p.name]) for p in RATTLEBACK_PARAMETERS.parameters if p.name != "spin_rad_s"}
    return {**physical, "spin_rad_s": float(params.get("spin_0_rad_s", 0.0))}


def orientation(q: np.ndarray) -> np.ndarray:
    """R (3, 3), body → world: yaw about z, then roll about x, then pitch about y."""
    return (
        elementary_rotation_matrix(2, float(q[YAW]))
        @ elementary_rotation_matrix(0, float(q[ROLL]))
        @ elementary_rotation_matrix(1, float(q[PITCH]))
    )


def touching_point(params: Mapping[str, Any], q: np.ndarray) -> np.ndarray:
    """Where the ellipsoid touches the floor, in the body's axes from G (m): its lowest point,
    centre − E n / √(nᵀ E n) with n = up and E = diag(a², b², c²)."""
    squares = np.array([float(params[k]) ** 2 for k in ("semi_axis_a_m", "semi_axis_b_m", "semi_axis_c_m")])
    up = orientation(q).T @ np.array([0.0, 0.0, 1.0])
    centre = np.array([0.0, 0.0, float(params["mass_centre_drop_m"])])
    return centre - squares * up / math.sqrt(float(squares @ (up * up)))


def body_velocity(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    """ω (rad/s) in the body's axes from the angles' rates: yaw about N's z, roll about x, pitch about y."""
    roll, pitch = float(q[ROLL]), float(q[PITCH])
    down_pitch = elementary_rotation_matrix(1, pitch).T
    return down_pitch @ (
        elementary_rotation_matrix(0, roll).T @ np.array([0.0, 0.0, float(v[YAW])]) + np.array([float(v[ROLL]), 0, 0])
    ) + np.array([0.0, float(v[PITCH]), 0.0])


def check_body(params: Mapping[str, Any]) -> None:
    """A ParameterError unless the body can be: its mass centre inside it, above its lowest point (h < c), and its
    central inertia a rigid body's (positive definite, each principal moment at most the sum of the other two)."""
    if not float(params["mass_centre_drop_m"]) < float(params["semi_axis_c_m"]):
        raise ParameterError(
            "mass_centre_drop_m",
            f"the mass centre must lie above the lowest point: h below the centre less than c = "
            f"{float(params['semi_axis_c_m']):g} m (got h = {float(params['mass_centre_drop_m']):g} m)",
        )
    tensor = np.array(
        [
            [float(params["inertia_xx_kg_m2"]), float(params["inertia_xy_kg_m2"]), 0.0],
            [float(params["inertia_xy_kg_m2"]), float(params["inertia_yy_kg_m2"]), 0.0],
            [0.0, 0.0, float(params["inertia_zz_kg_m2"])],
        ]
    )
    try:
        check_inertia_tensor(tensor)
    except ValueError as error:
        raise ParameterError("inertia_xy_kg_m2", f"no rigid body has these moments and product: {error}") from None


class RattlebackMotion(ConstrainedModel):
    """The rattleback spun (or tapped) on a floor: spun against its preferred sense it rocks harder and harder, stops
    spinning and spins the other way; tapped at one end, it starts to spin."""

    parameters = PARAMETERS
    start_parameters = ()  # the start is built from the spin, tilt and taps (see consistent_start)
    series_units = {
        "spin_rad_s": "rad/s",
        "roll_rad": "rad",
        "pitch_rad": "rad",
        "energy_J": "J",
        "normal_force_N": "N",
    }
    invariant_units = {"energy": "J", "constraint_position": "m", "constraint_velocity": "m/s"}

    def model(self) -> CompiledSystem:
        return rattleback_model()

    def constrained_system(self, params: Mapping[str, Any]) -> ConstrainedSystem:
        return multibody_constrained_system(self.model(), system_params(params))

    def consistent_start(self, params: Mapping[str, Any]) -> ConsistentStart:
        """Tilted by the start's roll and pitch, spinning and rocking at the start's rates; G's height and the rates
        of x, y, z are solved for, nothing else moves."""
        check_body(params)
        q0, v0 = np.zeros(N), np.zeros(N)
        q0[Z] = float(params["semi_axis_c_m"]) - float(params["mass_centre_drop_m"])
        q0[ROLL], q0[PITCH] = math.radians(float(params["roll_0_deg"])), math.radians(float(params["pitch_0_deg"]))
        v0[YAW] = float(params["spin_0_rad_s"])
        v0[ROLL], v0[PITCH] = float(params["roll_rate_0_rad_s"]), float(params["pitch_rate_0_rad_s"])
        dependent_q = {SYSTEM.index(name) for name in SYSTEM.dependent_coordinates}
        dependent_v = {SYSTEM.index(name) for name in SYSTEM.dependent_speeds}
        units = ("m", "m", "m", "rad", "rad", "rad", "m/s", "m/s", "m/s", "rad/s", "rad/s", "rad/s")
        start = consistent_initial_conditions(
            self.constrained_system(params),
            q0,
            v0,
            fixed_positions=[i for i in range(N) if i not in dependent_q],
            fixed_velocities=[i for i in range(N) if i not in dependent_v],
            names=(*COORDINATES, *(f"{name}_rate" for name in COORDINATES)),
            units=units,
        )
        normal = float(self.normal_force_N(params, np.zeros(1), np.concatenate([start.q, start.v])[None, :])[0])
        if not normal >= 0.0:
            rates = {k: abs(float(params[k])) for k in ("spin_0_rad_s", "roll_rate_0_rad_s", "pitch_rate_0_rad_s")}
            raise ParameterError(
                max(rates, key=lambda k: rates[k]),
                f"so violent a start would throw the body off the floor at once (the floor would have to pull it "
                f"down with {-normal:.3g} N): spin or rock it more gently",
            )
        return start

    def energy_J(self, params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
        """T + V (J) along ``states`` (N, 12); V = m g z_G."""
        return self.constrained_energy_parts(params, states).total_J

    def constrained_energy_parts(self, params: Mapping[str, Any], states: np.ndarray) -> EnergyParts:
        """½ m v_G², ½ ω·I_G ω and m g z_G (J) along ``states`` (N, 12)."""
        model = self.model()
        p = model.parameter_array(system_params(params))
        parts = np.array([model.energy_parts(state[:N], state[N:], p) for state in np.atleast_2d(states)])
        return EnergyParts(parts[:, 2], translational_kinetic_J=parts[:, 0], rotational_kinetic_J=parts[:, 1])

    def energy_scale_J(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """The energy, or m g c, whichever is larger (J)."""
        lift = float(params["mass_kg"]) * float(params["gravity_m_s2"]) * float(params["semi_axis_c_m"])
        return max(lift, float(abs(self.energy_J(params, state[None, :])[0])), 1e-12)

    def residual_scales(self, params: Mapping[str, Any]) -> tuple[float, float]:
        """The short semi-axis (m) and the spin times the long semi-axis, at least 0.1 m/s."""
        speed = abs(float(params["spin_0_rad_s"])) * float(params["semi_axis_a_m"])
        return float(params["semi_axis_c_m"]), max(speed, 0.1)

    def fastest_rate_rad_s(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """The rates now, and a bound on the rocking frequencies at rest, √(m g ρ / min(A, B)) with ρ the larger
        radius of curvature at the lowest point, a²/c or b²/c (rad/s)."""
        rates = np.abs(np.asarray(state[N + YAW :], dtype=float))
        m, g = float(params["mass_kg"]), float(params["gravity_m_s2"])
        a, b, c = (float(params[k]) for k in ("semi_axis_a_m", "semi_axis_b_m", "semi_axis_c_m"))
        smallest = min(float(params[k]) for k in ("inertia_xx_kg_m2", "inertia_yy_kg_m2"))
        rocking = math.sqrt(m * g * max(a * a, b * b) / c / smallest)
        return max(float(np.max(rates)), rocking, 1.0)

    def constrained_series(self, params, t_s, states, multipliers_N):
        return {
            "spin_rad_s": states[:, N + YAW],
            "roll_rad": states[:, ROLL],
            "pitch_rad": states[:, PITCH],
            "energy_J": self.energy_J(params, states),
            "normal_force_N": multipliers_N[:, 0],
        }

    def normal_force_N(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> np.ndarray:
        """The floor's push up on the body (N): the multiplier of the row that keeps the underside on the floor."""
        return multipliers(self.constrained_system(params), t_s, np.atleast_2d(states))[:, 0]

    def grip_needed(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """The friction coefficient the floor must supply to stop slip at ``state`` (12,): the horizontal part of its
        push, m (ẍ_G, ÿ_G), over the normal part, m (z̈_G + g) (dimensionless; ∞ where the normal part vanishes)."""
        model = self.model()
        accelerations = model.accelerations(state[:N], state[N:], model.parameter_array(system_params(params)))
        normal = float(accelerations[Z]) + float(params["gravity_m_s2"])
        sideways = math.hypot(float(accelerations[X]), float(accelerations[Y]))
        return sideways / normal if normal > 0 else math.inf

    def model_limit(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> ModelLimit | None:
        """Where the floor would have to pull the body down (it would hop)."""
        full = self.constrained_view(params, states)
        normal = self.normal_force_N(params, t_s, full)
        hops = np.nonzero(normal < 0.0)[0]
        if not hops.size:
            return None
        first = int(hops[0])
        return ModelLimit(
            max(first, 1),
            HOP,
            f"At t = {float(t_s[first]):.2f} s the floor would have to pull the body down (normal force "
            f"{float(normal[first]):.3g} N): it would hop, which this model (always touching) cannot describe, so "
            "the motion stops here.",
        )
