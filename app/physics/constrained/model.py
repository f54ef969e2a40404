"""The integrated-model base for systems in constrained coordinates: one model, every DAE algorithm.

A subclass states its :class:`~.system.ConstrainedSystem` and the physics a
student reads (energy, series); this base supplies the controls (``method`` = the
DAE algorithm, ``integrator``, ``steps_per_frame``, ``rtol`` and the two
Baumgarte gains), the consistent start (:mod:`.initial_conditions`), the
invariants every chapter-8 scene shows — ``constraint_position`` (max |g|),
``constraint_velocity`` (max |C v|) and ``energy`` — and the simulate report with
the algorithm, the integrator and what the start had to change.

:meth:`ConstrainedModel.integration_controls` records the algorithm and gains from the
controls; :meth:`~ConstrainedModel.system`, :meth:`~ConstrainedModel.initial_state`,
:meth:`~ConstrainedModel.series` and :meth:`~ConstrainedModel.invariants` then follow
it (the step policy asks it first, on a fresh model instance, for a simulate
answer and a live scene alike). A system whose minimal-coordinate equations exist offers the
method ``minimal`` by implementing the three ``minimal_*`` hooks.
"""

from __future__ import annotations

from abc import abstractmethod
from collections.abc import Mapping
from dataclasses import replace
from typing import Any, ClassVar

import numpy as np

from app.physics.constrained.algorithms import ALGORITHMS, algorithm_kernels, algorithm_system, repartition_count
from app.physics.constrained.initial_conditions import ConsistentStart, consistent_initial_conditions
from app.physics.constrained.residuals import constraint_residuals, multipliers
from app.physics.constrained.system import ConstrainedSystem
from app.physics.core.energy import EnergyParts
from app.physics.core.parameters import Parameter
from app.physics.core.report import SimulationReport
from app.physics.solvers.controls import AUTO, integration_parameters
from app.physics.solvers.integrated_model import IntegratedModel
from app.physics.solvers.step_choice import AccuracyTarget
from app.physics.solvers.system import OdeSystem

#: The integrators a constrained model offers (both run the algorithms' ``project`` hook).
INTEGRATORS = ("rk4", "dopri5")
MINIMAL = "minimal"
#: Largest Baumgarte gain a control accepts (1/s).
MAX_BAUMGARTE_GAIN_1_S = 1000.0


class ConstrainedModel(IntegratedModel):
    """An :class:`IntegratedModel` over a :class:`ConstrainedSystem` (state ``(q, v)``, 2n; ``minimal``: the subclass's
    own).

    A subclass gives ``parameters``, ``series_units``, ``invariant_units`` (with
    ``energy``, ``constraint_position``, ``constraint_velocity``), ``start_parameters``
    and the abstract methods below.
    """

    methods = INTEGRATORS
    default_method = "rk4"
    how_computed = "integrates its model in constrained coordinates (method: the DAE algorithm)"
    #: The DAE algorithms a student may pick (``minimal`` is added when :meth:`has_minimal`), and what ``auto`` means.
    algorithms: ClassVar[tuple[str, ...]] = tuple(ALGORITHMS)
    default_algorithm: ClassVar[str] = "projection"
    #: Default Baumgarte gains α, β (1/s).
    default_baumgarte_1_s: ClassVar[tuple[float, float]] = (5.0, 5.0)
    #: Names of the 2n parameters holding the requested q₀ then v₀ (their units label the changes).
    start_parameters: ClassVar[tuple[str, ...]]

    # --- what a subclass gives ------------------------------------------------------------------------------
    @abstractmethod
    def constrained_system(self, params: Mapping[str, Any]) -> ConstrainedSystem: ...

    @abstractmethod
    def energy_J(self, params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
        """Total energy (J) along ``states`` (N, 2n)."""

    @abstractmethod
    def energy_scale_J(self, params: Mapping[str, Any], state: np.ndarray) -> float:
        """Positive energy (J) the energy drift is measured against."""

    @abstractmethod
    def residual_scales(self, params: Mapping[str, Any]) -> tuple[float, float]:
        """Positive (position, velocity) residuals the drifts are measured against, in the rows' units."""

    @abstractmethod
    def constrained_series(
        self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray, multipliers: np.ndarray
    ) -> dict[str, np.ndarray]:
        """Named series along ``states`` (N, 2n) with the multipliers (N, m)."""

    def constrained_energy_parts(self, params: Mapping[str, Any], states: np.ndarray) -> EnergyParts | None:
        """The energies (J) along ``(q, v)`` states (N, 2n) whose sum less the drives' work is :meth:`energy_J`;
        None for a system that states no split."""
        return None

    def minimal_system(self, params: Mapping[str, Any]) -> OdeSystem | None:
        """The minimal-coordinate equations as an OdeSystem, or None where there are none."""
        return None

    def minimal_state(self, params: Mapping[str, Any], state: np.ndarray) -> np.ndarray:
        """The minimal state of a consistent ``(q, v)`` state (2n,)."""
        raise NotImplementedError(f"{type(self).__name__} has no minimal coordinates")

    def constrained_states(self, params: Mapping[str, Any], minimal_states: np.ndarray) -> np.ndarray:
        """``(q, v)`` rows (N, 2n) of minimal states (N, k)."""
        raise NotImplementedError(f"{type(self).__name__} has no minimal coordinates")

    # --- controls and the algorithm in use ------------------------------------------------------------------
    @classmethod
    def has_minimal(cls) -> bool:
        return cls.minimal_system is not ConstrainedModel.minimal_system

    @classmethod
    def controls(cls) -> tuple[Parameter, ...]:
        """``method`` (the DAE algorithm), ``integrator``, ``steps_per_frame``, ``rtol``, ``baumgarte_alpha_1_s``,
        ``baumgarte_beta_1_s``."""
        integrator, steps, rtol = integration_parameters(
            INTEGRATORS, default_method=cls.default_method, target=cls.accuracy_target, auto_methods=cls.auto_methods
        )
        choices = (*cls.algorithms, *((MINIMAL,) if cls.has_minimal() else ()))
        described = "; ".join(f"{ALGORITHMS[a].name}: {ALGORITHMS[a].description}" for a in cls.algorithms)
        if cls.has_minimal():
            described += f"; {MINIMAL}: the minimal-coordinate equations (no constraints to keep; the reference)"
        alpha, beta = cls.default_baumgarte_1_s
        return (
            Parameter(
                "method",
                "",
                AUTO,
                kind="choice",
                choices=(AUTO, *choices),
                label="DAE algorithm",
                description=f"How the constraints are kept ({AUTO} = {cls.default_algorithm}). {described}",
            ),
            replace(integrator, name="integrator"),
            steps,
            rtol,
            Parameter(
                "baumgarte_alpha_1_s",
                "1/s",
                alpha,
                0.0,
                MAX_BAUMGARTE_GAIN_1_S,
                label="Baumgarte α",
                step=0.5,
                description=(
                    "Damping gain α of Baumgarte's ë + 2α ė + β² e = 0 for a "
                    "residual e (method baumgarte only); 0 with β = 0: uncorrected"
                ),
            ),
            Parameter(
                "baumgarte_beta_1_s",
                "1/s",
                beta,
                0.0,
                MAX_BAUMGARTE_GAIN_1_S,
                label="Baumgarte β",
                step=0.5,
                description=(
                    "Stiffness gain β of Baumgarte's ë + 2α ė + β² e = 0 (method "
                    "baumgarte only); h·β near 1 or more makes the step unstable"
                ),
            ),
        )

    def algorithm(self) -> str:
        """The algorithm recorded by :meth:`integration_controls` (``auto`` resolved); the default before any."""
        return getattr(self, "_algorithm", self.default_algorithm)

    def integration_controls(self, params: Mapping[str, Any], controls: Mapping[str, Any]) -> dict[str, Any]:
        """Records (and checks) the DAE algorithm ``method`` names and the Baumgarte gains; the ``integrator``
        control's method, with ``steps_per_frame`` and ``rtol``, are the integrator's."""
        method = controls.get("method", AUTO)
        self._algorithm = self.default_algorithm if method == AUTO else method
        if self._algorithm not in (*self.algorithms, MINIMAL) or (
            self._algorithm == MINIMAL and not self.has_minimal()
        ):
            raise ValueError(f"method: {method!r} is not an algorithm of this model")
        alpha, beta = self.default_baumgarte_1_s
        self._gains_1_s = (
            float(controls.get("baumgarte_alpha_1_s", alpha)),
            float(controls.get("baumgarte_beta_1_s", beta)),
        )
        return {
            "method": controls.get("integrator", AUTO),
            "steps_per_frame": controls.get("steps_per_frame", 0),
            "rtol": controls.get("rtol"),
        }

    # --- the accuracy target (each algorithm's pilot is its own: the key holds the algorithm and the gains) ----
    accuracy_target = AccuracyTarget(
        1e-6, "", "state (q, v): largest component error relative to the largest component"
    )

    def pilot_key(self, params: Mapping[str, Any]):
        return (super().pilot_key(params), self.algorithm(), getattr(self, "_gains_1_s", self.default_baumgarte_1_s))

    def starting_rate_rad_s(self, params: Mapping[str, Any]) -> float:
        return self.fastest_rate_rad_s(params, self.consistent_start(params).state)  # (q, v) even when minimal runs

    # --- the consistent start ---------------------------------------------------------------------------------
    def consistent_start(self, params: Mapping[str, Any]) -> ConsistentStart:
        """The least change to the requested start that satisfies the constraints (ValueError if there is none)."""
        requested = np.array([float(params[name]) for name in self.start_parameters])
        n = len(requested) // 2
        units = [self.parameters.by_name[name].unit for name in self.start_parameters]
        return consistent_initial_conditions(
            self.constrained_system(params), requested[:n], requested[n:], names=self.start_parameters, units=units
        )

    # --- IntegratedModel ----------------------------------------------------------------------------------------
    def prepare(self, params: Mapping[str, Any]) -> None:
        """Compile the system's right-hand-side and after-step callbacks, which are built per system at run time."""
        system = self.constrained_system(params)
        n, holonomic, constraints = system.n_coordinates, system.n_holonomic, system.n_constraints
        algorithm_kernels(system.dynamics, system.constraints, n, holonomic, constraints)

    def system(self, params: Mapping[str, Any]) -> OdeSystem:
        if self.algorithm() == MINIMAL:
            minimal = self.minimal_system(params)
            assert minimal is not None
            return minimal
        alpha, beta = getattr(self, "_gains_1_s", self.default_baumgarte_1_s)
        start = self.consistent_start(params)
        self._last_system = algorithm_system(
            self.constrained_system(params), self.algorithm(), alpha_1_s=alpha, beta_1_s=beta, q=start.q
        )
        return self._last_system

    def initial_state(self, params: Mapping[str, Any]) -> np.ndarray:
        state = self.consistent_start(params).state
        return self.minimal_state(params, state) if self.algorithm() == MINIMAL else state

    def constrained_view(self, params: Mapping[str, Any], states: np.ndarray) -> np.ndarray:
        """``(q, v)`` rows (N, 2n) of the states the running algorithm integrates."""
        states = np.atleast_2d(states)
        return self.constrained_states(params, states) if self.algorithm() == MINIMAL else states

    def series(self, params: Mapping[str, Any], t_s: np.ndarray, states: np.ndarray) -> dict[str, np.ndarray]:
        full = self.constrained_view(params, states)
        return self.constrained_series(params, t_s, full, multipliers(self.constrained_system(params), t_s, full))

    def invariants(self, params: Mapping[str, Any], states: np.ndarray) -> dict[str, np.ndarray]:
        full = self.constrained_view(params, states)
        position, velocity = constraint_residuals(self.constrained_system(params), full)
        return {"energy": self.energy_J(params, full), "constraint_position": position, "constraint_velocity": velocity}

    def energy_parts(
        self, params: Mapping[str, Any], states: np.ndarray, *, t_s: np.ndarray | None = None
    ) -> EnergyParts | None:
        return self.constrained_energy_parts(params, self.constrained_view(params, states))

    def invariant_scales(self, params: Mapping[str, Any], state: np.ndarray) -> dict[str, float]:
        """Energy: :meth:`energy_scale_J`; residuals: :meth:`residual_scales` (a residual of 20% of these pauses a live
        scene)."""
        position, velocity = self.residual_scales(params)
        full = self.constrained_view(params, state)[0]
        return {
            "energy": self.energy_scale_J(params, full),
            "constraint_position": position,
            "constraint_velocity": velocity,
        }

    # --- the simulate answer --------------------------------------------------------------------------------------
    def simulate(
        self,
        params: Mapping[str, Any],
        controls: Mapping[str, Any],
        *,
        t_end_s: float,
        frame_rate_hz: float,
        request_limits: bool = True,
    ) -> SimulationReport:
        """The integrated answer, with ``stats.method`` the algorithm, ``stats.integrator``,
        ``stats.initial_conditions``."""
        report = super().simulate(
            params, controls, t_end_s=t_end_s, frame_rate_hz=frame_rate_hz, request_limits=request_limits
        )
        start = self.consistent_start(params)
        algorithm = self.algorithm()
        label = ALGORITHMS[algorithm].label if algorithm in ALGORITHMS else "minimal coordinates"
        description = f"{label} with {report.description}"
        system = getattr(self, "_last_system", None)
        if algorithm == "partitioning" and system is not None:
            count = repartition_count(system.parameters, self.constrained_system(params).n_coordinates)
            description += f"; independent coordinates re-chosen {count} time{'' if count == 1 else 's'}"
        return replace(
            report,
            method=algorithm,
            integrator=report.method,
            description=description,
            initial_conditions=[change.as_dict() for change in start.changes],
        )
