"""``/api/scenes`` and ``/api/scenes/{scene_id}/sessions/{session_id}``: the scene list and per-page parameters."""

from __future__ import annotations

from typing import Annotated, Any

from pydantic import BaseModel, ConfigDict, Field

from app.api.schemas.parameters import ParameterSpec, ParameterValue
from app.scenes.host.host import MAX_GO_TO_S, MAX_STEP_FRAMES, TIME_SCALE_RANGE


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
        None,
        pattern=r"^[0-9a-f]{16}$",
        description="A room exploring now: the session starts from where the room's scene was when exploring began "
        "(its parameters, then these params, and its motion)",
    )


class SessionParamsAnswer(BaseModel):
    """The session's parameters after the change, and how many viewers redrew."""

    scene_id: str
    session_id: str
    params: dict[str, ParameterValue]
    viewers: int


class PlaybackRequest(BaseModel):
    """How the session's motion runs: any of these; fields left out keep their values. Numbers are JSON numbers and
    switches JSON booleans (no "5" for 5, no true for 1)."""

    model_config = ConfigDict(extra="forbid")
    playing: bool | None = Field(None, strict=True, description="Play (true) or pause (false)")
    time_scale: float | None = Field(
        None,
        ge=TIME_SCALE_RANGE[0],
        le=TIME_SCALE_RANGE[1],
        strict=True,
        allow_inf_nan=False,
        description="× real time",
    )
    reset: bool = Field(False, strict=True, description="Start the motion again from t = 0")
    step: int = Field(
        0,
        ge=0,
        le=MAX_STEP_FRAMES,
        strict=True,
        description="Advance this many displayed frames (1/30 s each) now, paused",
    )
    seek_s: float | None = Field(
        None,
        ge=0.0,
        strict=True,
        allow_inf_nan=False,
        description="Go back to a kept instant (s; within history_s), paused",
    )
    go_to_s: float | None = Field(
        None,
        ge=0.0,
        le=MAX_GO_TO_S,
        strict=True,
        allow_inf_nan=False,
        description="Compute the motion at this simulated time from the start (s): a share link",
    )
    camera: CameraIn | None = Field(None, description="Point the viewers' cameras (a share link)")
    reset_camera: bool = Field(
        False, strict=True, description="Put every viewer's camera back at the scene's start pose (Reset view)"
    )


#: A coordinate a client sends: a finite JSON number, never a string or a boolean taken as one.
Coordinate = Annotated[float, Field(strict=True, allow_inf_nan=False)]


class CameraIn(BaseModel):
    model_config = ConfigDict(extra="forbid")
    position: list[Coordinate] = Field(min_length=3, max_length=3, description="m, world frame (+Z up)")
    look_at: list[Coordinate] = Field(min_length=3, max_length=3, description="m, world frame")


class CameraOut(BaseModel):
    position: list[float] = Field(description="m, world frame (+Z up)")
    look_at: list[float] = Field(description="m, world frame")


class PlaybackAnswer(BaseModel):
    """The session's play state, its first viewer's simulated time and camera, and the motion kept for scrubbing."""

    playing: bool
    time_scale: float
    t_s: float | None = Field(
        description="Simulated time of the first viewer's scene (s); null before a viewer connects"
    )
    history_s: list[float] | None = Field(description="[earliest, latest] simulated time kept for seek_s (s)")
    camera: CameraOut | None = None
    viewers: int | None = Field(
        None, description="Viewers connected to the session now (0 until its viewer has connected)"
    )
    slowed: Slowed | None = Field(
        None,
        description=(
            "Present when the first viewer's scene runs slower than "
            "the chosen speed to keep within its share of the server"
        ),
    )


class Slowed(BaseModel):
    rate: float = Field(description="Fraction of the chosen speed the scene runs at (0–1)")
    note: str = Field(description="Why, and what to change, in words")
