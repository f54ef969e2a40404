"""``GET /api/scenes/{scene_id}/sessions/{session_id}/live``: the running scene's numbers (see
app/physics/core/readout.py)."""

from __future__ import annotations

from pydantic import BaseModel, ConfigDict


class QuantityOut(BaseModel):
    """One readout row: ``value`` in ``unit``, or ``null`` with ``text`` saying why (or carrying a word)."""

    name: str
    label: str
    value: float | None
    unit: str
    text: str = ""
    #: The text carries numbers in ``unit`` (a vector's components): shown with the unit, as a number is.
    text_in_unit: bool = False


class MarkOut(BaseModel):
    """A labelled tick on a control's slider, at ``value`` in that control's unit."""

    value: float
    label: str


class ReadoutOut(BaseModel):
    quantities: list[QuantityOut]
    marks: dict[str, list[MarkOut]]
    message: str


class InvariantNow(BaseModel):
    value: float | None
    initial: float | None
    unit: str
    relative_drift: float | None


class DriftHistory(BaseModel):
    t_s: list[float]
    max_relative_drift: list[float | None]


class LiveAnswer(BaseModel):
    """A live scene's numbers. Integrated scenes add time, method and step, invariants and drift, and cost per frame.

    Scenes may publish further keys of their own; they are passed through after these.
    """

    model_config = ConfigDict(extra="allow")
    scene_id: str
    viewers: int
    t_s: float = 0.0
    method: str = ""
    description: str = ""
    running: bool = False
    status: str = ""
    physics_us_per_frame: float = 0.0
    invariants: dict[str, InvariantNow] = {}
    drift_history: DriftHistory | None = None
    readout: ReadoutOut | None = None
