"""The one contract every model keeps, however it finds its motion.

A :class:`Model` states its parameters (names are API contracts), the controls of
how its motion is found (none for a formula), the unit of each output — series
and invariants by name — and answers :meth:`Model.simulate`: parameters,
controls and a span in, a :class:`~app.physics.core.report.SimulationReport` out
(series, invariants and their drift, events, counters, and a status with a
message where the motion leaves what the model describes).

Closed-form models (:mod:`.closed_form`) evaluate a formula in time; integrated
models (:mod:`app.physics.solvers.integrated_model`, and the derived and
constrained models built on them) step their equations, with the step chosen by
:mod:`app.physics.solvers.step_policy`. The simulate route, the "Open as Python"
scripts, the benchmarks and the scenes ask a model only through this contract,
never which kind it is.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Mapping
from typing import Any, ClassVar

from app.physics.core.parameters import Parameter, ParameterSet
from app.physics.core.report import SimulationReport

__all__ = ["Model"]


class Model(ABC):
    """A physical model: its parameters, outputs and controls, and one way to ask for its motion over a span."""

    #: Physical parameters (names are API contracts).
    parameters: ClassVar[ParameterSet]
    #: Unit of each series / invariant, by name.
    series_units: ClassVar[Mapping[str, str]]
    invariant_units: ClassVar[Mapping[str, str]] = {}
    #: What a student reads for a series or invariant whose name is cryptic (a symbol: ``"θ"``, ``"ω₃"``), by name;
    #: a name not here is shown in a readable form of itself.
    series_labels: ClassVar[Mapping[str, str]] = {}
    #: Whether the motion is stepped from a state: a live scene then advances it frame by frame and keeps its
    #: states (graphs, energy bars, invariant drift); False for a formula evaluated at any time.
    integrated: ClassVar[bool] = False
    #: How the motion is found, as a sentence's predicate ("integrates its model"): an "Open as Python" script's
    #: docstring says it.
    how_computed: ClassVar[str]

    @classmethod
    def controls(cls) -> tuple[Parameter, ...]:
        """The controls of how the motion is found (method, steps per frame, tolerance, …); none by default."""
        return ()

    @classmethod
    def validate_controls(cls, controls: Mapping[str, Any]) -> dict[str, Any]:
        """``controls`` checked against :meth:`controls`, defaults filled in; ParameterError naming a bad one."""
        return ParameterSet(cls.controls()).validate(controls)

    @abstractmethod
    def simulate(
        self,
        params: Mapping[str, Any],
        controls: Mapping[str, Any],
        *,
        t_end_s: float,
        frame_rate_hz: float,
        request_limits: bool = True,
    ) -> SimulationReport:
        """The motion for validated ``params`` and ``controls`` over ``t_end_s`` (s), sampled at ``frame_rate_hz``
        (Hz) from t = 0 on.

        ``request_limits`` applies the bounds of one request (:mod:`.report`: span, frames, work); tests and
        benchmarks that need longer or denser runs switch it off where a model's cost allows. Raises
        ParameterError naming the input or limit at fault, ValueError where the values have no motion.
        """

    def prepare(self, params: Mapping[str, Any]) -> None:
        """Build now what a first run for ``params`` would otherwise build (compiled equations): a scene worker
        calls it at start-up so that no student waits for it. Nothing by default."""
        return None  # an optional hook: models with nothing to build keep this
