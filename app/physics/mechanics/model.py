"""An integrated model whose right-hand side is a derivation: what the catalogue's live scenes run.

A subclass names its :class:`SystemDescription`, its initial-condition
parameters and how they map to the state (q, q̇); the control ``formulation``
picks which derivation drives the motion (all give the same q̈ to rounding,
which :meth:`DerivedModel.agreement` shows on any state). The compiled
right-hand side comes from :func:`~app.physics.mechanics.engine.derived`:
derived and compiled once per process (and cached on disk), never per frame.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import sympy

from app.physics.core.energy import EnergyParts
from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.mechanics.description import TIME, SystemDescription
from app.physics.mechanics.engine import Derived, available_formulations, derived
from app.physics.mechanics.kinematics import body_motions, coordinate_motion, kinetic_energy, potential_energy
from app.physics.solvers.integrated_model import IntegratedModel
from app.physics.solvers.step_choice import AccuracyTarget
from app.physics.solvers.system import OdeSystem


def formulation_parameter(system: SystemDescription, *, default: str = "lagrange") -> Parameter:
    """The ``formulation`` choice: the derivations that apply to ``system``."""
    choices = tuple(f for f, reason in available_formulations(system).items() if not reason)
    return Parameter(
        "formulation",
        "",
        default if default in choices else choices[0],
        kind="choice",
        choices=choices,
        label="formulation",
        description="Which derivation's equations drive the motion (all agree to rounding)",
    )


def derived_parameters(
    system: SystemDescription, *initial_conditions: Parameter, default_formulation: str = "lagrange", check=None
) -> ParameterSet:
    """A derived model's parameters: the system's, its initial conditions, then ``formulation``."""
    return ParameterSet(
        (
            *system.parameters.parameters,
            *initial_conditions,
            formulation_parameter(system, default=default_formulation),
        ),
        check=check,
    )


_energy_functions: dict[str, tuple] = {}


def energy_functions(system: SystemDescription):
    """(T, V) as numpy functions of (t, q (n, N), q̇ (n, N), p), in J (built once per system, kept by fingerprint)."""
    key = system.fingerprint()
    if key not in _energy_functions:
        _energy_functions[key] = _lambdified_energies(system)
    return _energy_functions[key]


def _lambdified_energies(system: SystemDescription):
    motion = coordinate_motion(system)
    arguments = [TIME, system.q, system.qd, system.parameter_symbols]
    T = sympy.lambdify(arguments, kinetic_energy(system, motion), modules="numpy", cse=True)
    V = sympy.lambdify(arguments, potential_energy(system, tidied=False), modules="numpy", cse=True)
    return T, V


_translational_functions: dict[str, Any] = {}


def translational_kinetic_function(system: SystemDescription):
    """½ Σ m v_G·v_G over the particles and bodies as a numpy function of (t, q (n, N), q̇ (n, N), p), in J; None
    where the system states its kinetic energy directly (a typed T: no split into translation and rotation)."""
    if system.kinetic_energy is not None:
        return None
    key = system.fingerprint()
    if key not in _translational_functions:
        translational = sum(
            (
                sympy.Rational(1, 2) * item.mass * (item.velocity.T * item.velocity)[0]
                for item in body_motions(system, coordinate_motion(system))
            ),
            sympy.Integer(0),
        )
        _translational_functions[key] = sympy.lambdify(
            [TIME, system.q, system.qd, system.parameter_symbols], translational, modules="numpy", cse=True
        )
    return _translational_functions[key]


class DerivedModel(IntegratedModel):
    """Integrate a catalogue system from its derived equations (state: q then q̇).

    A subclass gives ``description``, ``parameters`` (see :func:`derived_parameters`) and the
    abstract methods of :class:`IntegratedModel`: initial_state, series, invariants, invariant_scales.
    """

    # Set on the class by a catalogue system; the typed Lagrangian sets its own on each instance.
    description: SystemDescription
    methods = ("rk4", "dopri5")
    default_method = "rk4"
    accuracy_target = AccuracyTarget(
        1e-6, "", "state (q, q̇): largest component error relative to the largest component"
    )

    # --- derived pieces ---------------------------------------------------------------------------------------
    def parameter_array(self, params: Mapping[str, Any]) -> np.ndarray:
        return np.array(self.description.parameter_array(params), dtype=float)

    def derived(self, params: Mapping[str, Any]) -> Derived:
        return derived(self.description, params.get("formulation", "lagrange"))

    def prepare(self, params: Mapping[str, Any]) -> None:
        """Derive (or load from the disk cache) and compile the equations of the formulation ``params`` name."""
        self.derived(params).kernel()

    def system(self, params: Mapping[str, Any]) -> OdeSystem:
        names = [c.name for c in self.description.coordinates]
        return OdeSystem(
            rhs=self.derived(params).kernel(),
            parameters=self.parameter_array(params),
            state_names=(*names, *(f"{n}_rate" for n in names)),
        )

    def fastest_rate_rad_s(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """The largest eigenvalue magnitude of the linearised flow at ``state`` plus the fastest rate (rad/s), at least
        1.

        The Jacobian is taken by central differences of the generated right-hand side.
        """
        rhs, p = self.derived(params), self.parameter_array(params)
        n = len(state)
        jacobian = np.empty((n, n))
        for j in range(n):
            h = 1e-6 * max(1.0, abs(state[j]))
            up, down = state.copy(), state.copy()
            up[j] += h
            down[j] -= h
            jacobian[:, j] = (rhs.state_derivative(0.0, up, p) - rhs.state_derivative(0.0, down, p)) / (2 * h)
        if not np.all(np.isfinite(jacobian)):
            return 10.0
        rates = np.abs(state[n // 2 :])
        return max(1.0, float(np.max(np.abs(np.linalg.eigvals(jacobian)))) + float(np.max(rates, initial=0.0)))

    def energies(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(T, V) along ``states`` (N, 2n) at times ``t_s`` (N,), J."""
        T, V = energy_functions(self.description)
        n = len(self.description.coordinates)
        q, qd, p = states[:, :n].T, states[:, n:].T, self.parameter_array(params)
        kinetic = np.broadcast_to(np.asarray(T(t_s, q, qd, p), dtype=float), t_s.shape)
        potential = np.broadcast_to(np.asarray(V(t_s, q, qd, p), dtype=float), t_s.shape)
        return np.array(kinetic), np.array(potential)

    def drive_work_J(self, params: Mapping[str, Any], states: np.ndarray) -> np.ndarray | None:
        """Work (J, (N,)) done on the system by its drives since t = 0 along ``states``, where the state tracks it."""
        return None

    def energy_parts(
        self, params: Mapping[str, Any], states: np.ndarray, *, t_s: np.ndarray | None = None
    ) -> EnergyParts:
        """T split as ½ Σ m v_G² (translational) and the rest, ½ Σ ω·I_G ω (rotational), unless the system states T
        itself; V; the drives' work from :meth:`drive_work_J`. Only the first 2n state slots are the motion."""
        states = np.atleast_2d(np.asarray(states, dtype=float))
        p = self.parameter_array(params)  # (a typed Lagrangian prepares its description here)
        n = len(self.description.coordinates)
        t = np.zeros(len(states)) if t_s is None else np.asarray(t_s, dtype=float)
        kinetic, potential = self.energies(params, t, states[:, : 2 * n])
        work = self.drive_work_J(params, states)
        translational_of = translational_kinetic_function(self.description)
        if translational_of is None:
            return EnergyParts(potential, kinetic_J=kinetic, drive_work_J=work)
        translational = np.broadcast_to(
            np.asarray(translational_of(t, states[:, :n].T, states[:, n : 2 * n].T, p), dtype=float), t.shape
        )
        return EnergyParts(
            potential,
            translational_kinetic_J=np.array(translational),
            rotational_kinetic_J=kinetic - translational,
            drive_work_J=work,
        )

    def agreement(self, params: Mapping[str, Any], state: np.ndarray, t_s: float = 0.0) -> dict[str, float]:
        """Per available formulation, |ẏ_f − ẏ_ref| / |ẏ_ref| at ``state`` (ref: the running formulation)."""
        p = self.parameter_array(params)
        reference = self.derived(params).state_derivative(t_s, state, p)
        scale = max(float(np.linalg.norm(reference)), 1e-300)
        found = {}
        for formulation, reason in available_formulations(self.description).items():
            if not reason:
                other = derived(self.description, formulation).state_derivative(t_s, state, p)
                found[formulation] = float(np.linalg.norm(other - reference)) / scale
        return found
