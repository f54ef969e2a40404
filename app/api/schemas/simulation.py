"""``POST /api/scenes/{scene_id}/simulate``: a scene's motion computed off-screen, frame by frame."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from app.api.schemas.parameters import ParameterValue


class SimulateRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    params: dict[str, Any] = Field(default_factory=dict, description="Physical parameters; omitted ones take their defaults")
    t_end: float = Field(description="Simulated time span (s), at most 600 s")
    frame_rate: float = Field(60.0, description="Samples per second of simulated time (Hz), 1–240")
    method: str | None = Field(None, description="Integrator: 'auto' or one the scene lists; default auto")
    steps_per_frame: int | None = Field(None, description="Fixed steps per frame (0 or omitted: automatic)")
    rtol: float | None = Field(None, description="Relative tolerance of the adaptive method")


class SimulationEvent(BaseModel):
    """Something that happens at an instant of a closed-form motion (e.g. a linkage's toggle position)."""

    t_s: float
    kind: str
    message: str


class SimulationStats(BaseModel):
    """How the motion was computed: ``method`` (``closed-form`` for a formula), work done, CPU time, worst invariant drift."""

    method: str
    description: str
    steps: int
    rhs_evals: int
    cpu_s: float
    max_invariant_drift: float | None
    status: str = Field(description="Empty when the run finished; otherwise why it stopped")
    message: str


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
