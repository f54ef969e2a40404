"""``POST /api/scenes/{scene_id}/simulate``: a scene's motion computed off-screen, frame by frame."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from app.api.schemas.parameters import ParameterValue


class SimulateRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    params: dict[str, Any] = Field(
        default_factory=dict, description="Physical parameters; omitted ones take their defaults"
    )
    t_end: float = Field(description="Simulated time span (s), at most 600 s")
    frame_rate: float = Field(60.0, description="Samples per second of simulated time (Hz), 1–240")
    method: str | None = Field(None, description="Integrator: 'auto' or one the scene lists; default auto")
    steps_per_frame: int | None = Field(None, description="Fixed steps per frame (0 or omitted: automatic)")
    rtol: float | None = Field(None, description="Relative tolerance of the adaptive method")
    # Constrained-coordinate scenes (chapter 8): there ``method`` names the DAE algorithm.
    integrator: str | None = Field(
        None,
        description=(
            "Integrator of a constrained-coordinate scene ('auto', 'rk4', 'dopri5'); `method` is then the DAE algorithm"
        ),
    )
    baumgarte_alpha_1_s: float | None = Field(
        None, description="Baumgarte damping gain α (1/s) of a constrained-coordinate scene"
    )
    baumgarte_beta_1_s: float | None = Field(
        None, description="Baumgarte stiffness gain β (1/s) of a constrained-coordinate scene"
    )


class SimulationEvent(BaseModel):
    """Something that happens at an instant of a closed-form motion (e.g. a linkage's toggle position)."""

    t_s: float
    kind: str
    message: str


class InitialConditionChange(BaseModel):
    """One coordinate or rate a constrained scene's start had to change to satisfy its constraints."""

    name: str
    requested: float
    consistent: float
    change: float
    unit: str


class SimulationStats(BaseModel):
    """How the motion was computed: ``method`` (``closed-form`` for a formula), work done, CPU time, worst invariant
    drift."""

    method: str
    description: str
    steps: int
    rhs_evals: int
    cpu_s: float
    max_invariant_drift: float | None
    status: str = Field(description="Empty when the run finished; otherwise why it stopped")
    message: str
    # Accuracy, for integrated models that state a target (absent otherwise).
    target_error: float | None = Field(
        None, description="Error the automatic step aims at over the span, in error_unit"
    )
    error_unit: str | None = Field(None, description="'rad', or '' for a relative error")
    error_measure: str | None = Field(None, description="What the error compares (e.g. the attitude angle)")
    error_horizon_s: float | None = Field(None, description="Span (s) the target and the estimate are for")
    estimated_error: float | None = Field(
        None, description="Error estimated from the method's order and a pilot run, in error_unit"
    )
    accuracy: str | None = Field(
        None, description="The same in one line: target, estimate, steps per frame or tolerance"
    )
    max_reference_error: float | None = Field(
        None, description="Largest error against the model's reference solution, in error_unit"
    )
    reference: str | None = Field(None, description="The reference solution max_reference_error is measured against")
    # Constrained-coordinate scenes (chapter 8): ``method`` is the DAE algorithm.
    integrator: str | None = Field(None, description="The integrator that advanced the DAE algorithm named by method")
    initial_conditions: list[InitialConditionChange] | None = Field(
        None, description="What the requested start had to change to satisfy the constraints (empty: nothing)"
    )


class SimulationAnswer(BaseModel):
    """Frame-sampled motion: ``t`` (s), ``series`` and ``invariants`` by name (``null`` where a formula is undefined).

    ``events`` is present for closed-form motions only; ``units`` gives the unit of
    ``t``, of every series and of every invariant (as ``invariants.<name>``).
    """

    t: list[float]
    series: dict[str, list[float | None]]
    invariants: dict[str, list[float | None]]
    events: list[SimulationEvent] = []
    stats: SimulationStats
    params: dict[str, ParameterValue]
    units: dict[str, str]
