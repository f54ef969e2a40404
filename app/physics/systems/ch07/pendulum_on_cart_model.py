"""The pendulum on the sprung, driven cart integrated from its derived equations, with the work of the drive.

State: (x (m), θ (rad), ẋ (m/s), θ̇ (rad/s), W (J)), the first four as in
:mod:`.pendulum_on_cart`; W = ∫ F₀ cos(Ω t) ẋ dt is the work the driving
force has done since the start, integrated alongside the motion (its rate is
the force's power). The energy balance T + V − W is then the invariant,
whether the force is on or off (the spring is inside V).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from functools import cache
from typing import Any

import numba
import numpy as np

from app.physics.core.parameters import Parameter
from app.physics.mechanics.engine import derived
from app.physics.mechanics.model import DerivedModel, derived_parameters
from app.physics.solvers.kernels import RHS_SIGNATURE, Kernel
from app.physics.solvers.system import OdeSystem
from app.physics.systems.ch07.pendulum_on_cart import SYSTEM

#: Slots of the state: the derived (q, q̇) first, then the drive's work.
MOTION_SLOTS = 2 * len(SYSTEM.coordinates)
WORK_SLOT = MOTION_SLOTS
CART_RATE_SLOT = len(SYSTEM.coordinates)
_NAMES = [p.name for p in SYSTEM.parameters.parameters]
FORCE_AMPLITUDE, FORCE_FREQUENCY = _NAMES.index("force_amplitude_N"), _NAMES.index("force_frequency_rad_s")


def drive_force_N(params_array: np.ndarray, t_s):
    """F₀ cos(Ω t) in N on the cart, along the rail (+x), for the system's parameter array."""
    return params_array[FORCE_AMPLITUDE] * np.cos(params_array[FORCE_FREQUENCY] * t_s)


@cache
def motion_with_work_kernel(formulation: str) -> Kernel:
    """The derived right-hand side of ``formulation`` with Ẇ = F(t) ẋ appended (compiled once per process)."""
    motion_python = derived(SYSTEM, formulation).rhs_python
    motion_compiled = numba.njit(motion_python)

    def with_work(motion):
        def rhs(t, y, p, dydt):
            motion(t, y[:MOTION_SLOTS], p, dydt[:MOTION_SLOTS])
            dydt[WORK_SLOT] = p[FORCE_AMPLITUDE] * math.cos(p[FORCE_FREQUENCY] * t) * y[CART_RATE_SLOT]

        return rhs

    # numba's stubs leave out nopython, which cfunc still reads: without it object mode is allowed.
    compiled = numba.cfunc(RHS_SIGNATURE, nopython=True, error_model="numpy")(  # type: ignore[call-arg]
        with_work(motion_compiled)
    )
    return Kernel(compiled=compiled, python=with_work(motion_python))


class CartPendulumMotion(DerivedModel):
    """The cart and its pendulum started from the positions and rates the controls give."""

    description = SYSTEM
    parameters = derived_parameters(
        SYSTEM,
        Parameter("x0_m", "m", 0.0, -2.0, 2.0, "Initial position of the cart (the spring is relaxed at x = 0)", "x₀"),
        Parameter(
            "theta_0_deg", "deg", 30.0, -180.0, 180.0, "Initial angle of the rod from the downward vertical", "θ₀"
        ),
        Parameter("x_rate_0_m_s", "m/s", 0.0, -5.0, 5.0, "Initial speed of the cart", "ẋ₀"),
        Parameter("theta_rate_0_deg_s", "deg/s", 0.0, -720.0, 720.0, "Initial rate of the rod's angle", "θ̇₀"),
        default_formulation="lagrange",
    )
    series_units = {
        "x_m": "m",
        "theta_rad": "rad",
        "x_rate_m_s": "m/s",
        "theta_rate_rad_s": "rad/s",
        "force_N": "N",
        "force_work_J": "J",
        "energy_J": "J",
    }
    invariant_units = {"energy_balance": "J"}

    def initial_state(self, params: Mapping[str, Any]) -> np.ndarray:
        return np.array(
            [
                float(params["x0_m"]),
                math.radians(float(params["theta_0_deg"])),
                float(params["x_rate_0_m_s"]),
                math.radians(float(params["theta_rate_0_deg_s"])),
                0.0,
            ]
        )

    def system(self, params: Mapping[str, Any]) -> OdeSystem:
        return OdeSystem(
            rhs=motion_with_work_kernel(params.get("formulation", "lagrange")),
            parameters=self.parameter_array(params),
            state_names=("x", "theta", "x_rate", "theta_rate", "force_work"),
        )

    def fastest_rate_rad_s(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """The motion's fastest rate (the work slot adds none), at least the drive's Ω (rad/s)."""
        motion = super().fastest_rate_rad_s(params, state[:MOTION_SLOTS])
        return max(motion, float(params["force_frequency_rad_s"]))

    def agreement(self, params: Mapping[str, Any], state: np.ndarray, t_s: float = 0.0) -> dict[str, float]:
        return super().agreement(params, state[:MOTION_SLOTS], t_s)

    def energy_J(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> np.ndarray:
        """T + V (J) along ``states`` (N, 5): both bodies' kinetic energy, gravity (zero at the rail) and the spring."""
        kinetic, potential = self.energies(params, t_s, states[:, :MOTION_SLOTS])
        return kinetic + potential

    def series(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> dict[str, np.ndarray]:
        return {
            "x_m": states[:, 0],
            "theta_rad": states[:, 1],
            "x_rate_m_s": states[:, 2],
            "theta_rate_rad_s": states[:, 3],
            "force_N": np.asarray(drive_force_N(self.parameter_array(params), t_s), dtype=float) * np.ones(len(t_s)),
            "force_work_J": states[:, WORK_SLOT],
            "energy_J": self.energy_J(params, t_s, states),
        }

    def drive_work_J(self, params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
        """W (J): the work of the force on the cart, integrated in the state."""
        return np.atleast_2d(states)[:, WORK_SLOT].copy()

    def invariants(self, params: Mapping[str, Any], states: np.ndarray) -> dict[str, np.ndarray]:
        """T + V − W (J); T and V do not depend on t itself (only the force does), so t = 0 is used."""
        return {"energy_balance": self.energy_J(params, np.zeros(len(states)), states) - states[:, WORK_SLOT]}

    def invariant_scales(self, params: Mapping[str, Any], state: np.ndarray) -> dict[str, float]:
        """The balance's scale: m g l·2, the spring's energy at l of stretch, the start's T, and F₀ l (J)."""
        m, l, k = float(params["bob_mass_kg"]), float(params["length_m"]), float(params["stiffness_N_m"])
        g, force = float(params["g_m_s2"]), float(params["force_amplitude_N"])
        kinetic, _ = self.energies(params, np.zeros(1), state[None, :MOTION_SLOTS])
        return {"energy_balance": max(2.0 * m * g * l + 0.5 * k * l * l + float(kinetic[0]) + force * l, 1e-12)}
