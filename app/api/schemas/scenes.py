"""``/api/scenes`` and ``/api/scenes/{scene_id}/sessions/{session_id}``: the scene list and per-page parameters."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from app.api.schemas.parameters import ParameterSpec, ParameterValue


class Preset(BaseModel):
    """A button on the lesson page that sets several controls at once."""

    name: str
    label: str
    values: dict[str, ParameterValue]
    description: str


class SceneSummary(BaseModel):
    """A scene: id, title, chapter, what it publishes live, its parameter schema and presets."""

    id: str
    title: str
    chapter: int
    animated: bool
    integrated: bool = Field(description="Publishes invariants and their drift at .../live")
    readout: bool = Field(description="Publishes a readout (named quantities, marks on controls) at .../live")
    parameters: list[ParameterSpec]
    presets: list[Preset]


class SessionParamsRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    params: dict[str, Any] = Field(default_factory=dict, description="Parameters to change; others keep their values")
    from_room: str | None = Field(
        None, pattern=r"^[0-9a-f]{16}$",
        description="A room exploring now: the session starts from where the room's scene was when exploring began "
        "(its parameters, then these params, and its motion)",
    )  # fmt: skip


class SessionParamsAnswer(BaseModel):
    """The session's parameters after the change, and how many viewers redrew."""

    scene_id: str
    session_id: str
    params: dict[str, ParameterValue]
    viewers: int
