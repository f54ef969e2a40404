"""``/api/rooms``: a classroom's room, its state, students joining, polls and answers."""

from __future__ import annotations

from typing import Any, Literal

from pydantic import BaseModel, ConfigDict, Field, StrictBool, StrictInt

from app.classroom.polls import CHOICES_RANGE, MAX_QUESTION_CHARS, MAX_UNIT_CHARS
from app.classroom.room import CODE_LENGTH, MAX_NAME_LENGTH, MAX_TYPED_CODE_LENGTH
from app.scenes.host.host import TIME_SCALE_RANGE

POLL_ID_PATTERN = r"^p[0-9]{1,6}$"
STUDENT_ID_PATTERN = r"^s[0-9]{1,6}$"


class RoomCreateRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    lesson_id: str | None = Field(None, max_length=100, description="The lesson the room opens on (default: none yet)")
    scene_id: str | None = Field(None, max_length=100, description="One of the lesson's scenes (default: its first)")


class RoomCreated(BaseModel):
    room_id: str
    code: str = Field(description=f"What students type to join: {CODE_LENGTH} capitals and digits")
    join_url: str = Field(description="The address students open (also shown as a QR code on the projector)")
    state: RoomState


class JoinRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    code: str = Field(
        min_length=1, max_length=MAX_TYPED_CODE_LENGTH, description="The room's code, as on the projector"
    )
    name: str = Field("", max_length=MAX_NAME_LENGTH, description="Shown to the instructor only if names are turned on")


class JoinAnswer(BaseModel):
    room_id: str
    student_token: str = Field(
        description=(
            "Send as X-Student-Token with answers, and in the room "
            "socket's hello; the same for a device that joins again"
        )
    )
    student_id: str = Field(
        description="This student's public id in the room (s1, s2, …): how the instructor's list names them"
    )
    state: RoomState


class StudentListed(BaseModel):
    """One student as the instructor's list shows them: never their token."""

    student_id: str = Field(description="Public id in the room: s1, s2, … in the order they joined")
    name: str = Field(description="As they gave it on joining (may be empty)")
    connected: bool = Field(description="Their page has the room open now")
    following: bool


class StudentList(BaseModel):
    students: list[StudentListed]


class StudentRemovedAnswer(BaseModel):
    removed: str = Field(description="The public id of the student removed")


class RoomStateChange(BaseModel):
    """Any of these; fields left out keep their values. ``preset`` and ``reset`` are actions on the room's scene."""

    model_config = ConfigDict(extra="forbid")
    lesson_id: str | None = Field(None, max_length=100)
    scene_id: str | None = Field(None, max_length=100)
    params: dict[str, Any] | None = Field(None, description="Parameters to change; others keep their values")
    playing: StrictBool | None = None
    time_scale: float | None = Field(
        None, ge=TIME_SCALE_RANGE[0], le=TIME_SCALE_RANGE[1], allow_inf_nan=False, description="× real time"
    )
    mode: Literal["follow", "explore"] | None = None
    preset: str | None = Field(None, max_length=100, description="A preset name of the room's scene")
    reset: StrictBool = Field(False, description="Start the motion again from t = 0")
    if_lesson_id: str | None = Field(
        None,
        max_length=100,
        description="Apply only if the room still shows this lesson (the lesson the sending page shows), else 409",
    )
    if_scene_id: str | None = Field(
        None, max_length=100, description="Apply only if the room still shows this scene (null: no scene), else 409"
    )


class PollRequest(BaseModel):
    """A question to the room: multiple choice or a number with a unit; or one of the ready questions by id."""

    model_config = ConfigDict(extra="forbid")
    ready_id: str | None = Field(
        None, max_length=100, description="A ready question (GET .../polls/ready); the other fields override it"
    )
    question: str | None = Field(None, max_length=MAX_QUESTION_CHARS)
    kind: Literal["choice", "number"] | None = None
    choices: list[str] | None = Field(None, max_length=CHOICES_RANGE[1])
    unit: str | None = Field(None, max_length=MAX_UNIT_CHARS)
    answer_quantity: str | None = Field(
        None, max_length=100, description="A readout quantity of the room's scene that computes the answer"
    )
    answer_choices: dict[str, StrictInt] | None = Field(
        None, description="For a word quantity: its value -> the right choice's index"
    )
    answer_value: float | None = Field(
        None,
        strict=True,
        allow_inf_nan=False,
        description="The instructor's own answer to a number poll, in its unit (a JSON number): Reveal shows it",
    )
    answer_choice: StrictInt | None = Field(
        None, description="The instructor's own answer to a choice poll: the right choice's index; Reveal shows it"
    )
    show_names: StrictBool | None = None


class PollUpdate(BaseModel):
    model_config = ConfigDict(extra="forbid")
    open: StrictBool | None = None
    reveal: StrictBool | None = Field(
        None, description="Close the poll and show the answer, computed by the room's scene now"
    )
    show_names: StrictBool | None = None


class AnswerRequest(BaseModel):
    """``{"choice": index}`` for a multiple-choice poll, ``{"value": number}`` (in the poll's unit) for a number
    poll."""

    model_config = ConfigDict(extra="forbid")
    choice: StrictInt | None = None
    value: float | None = Field(None, strict=True, allow_inf_nan=False)  # a JSON number: not "1", not true


# ---- answers ----------------------------------------------------------------------------------------
class Role(BaseModel):
    role: Literal["instructor", "student"]


class Revealed(BaseModel):
    text: str = Field(description="The answer as shown, with its unit")
    value: float | None
    choice: int | None
    unit: str
    source: str = Field(description='"computed by the scene: <quantity>" or "given by the instructor"')


class PollPublic(BaseModel):
    """What every page sees of a poll: never names, never anyone's answer."""

    poll_id: str
    question: str
    kind: Literal["choice", "number"]
    choices: list[str]
    unit: str
    open: bool
    answers: int
    revealed: Revealed | None


class HistogramBin(BaseModel):
    label: str
    lo: float | None = Field(description="Lower edge (number polls; null for a choice)")
    hi: float | None
    count: int


class NamedAnswer(BaseModel):
    name: str
    answer: str


class PollResults(BaseModel):
    """The instructor's view of a poll: counts per choice or bin; names only when turned on."""

    poll_id: str
    question: str
    kind: Literal["choice", "number"]
    unit: str
    choices: list[str]
    open: bool
    answers: int
    histogram: list[HistogramBin]
    revealed: Revealed | None
    show_names: bool
    names: list[NamedAnswer] | None = None


class AnswerAccepted(BaseModel):
    accepted: bool
    poll: PollPublic


class StudentCounts(BaseModel):
    joined: int = Field(description="Students in the room (one per device; removed students not counted)")
    connected: int = Field(description="Students with the room open now")
    following: int = Field(description="Of those, following the instructor's scene")


class AssignmentPublic(BaseModel):
    """What every page of a room sees of its assigned exercises."""

    exercise_ids: list[str]
    class_variant: bool = Field(description="Every student works on the same numbers (else each on their own)")
    assigned_at: str = Field(description="When they were assigned (UTC, ISO 8601)")


class RoomState(BaseModel):
    """What the room shows now; every page in the room follows it."""

    room_id: str
    code: str
    join_url: str
    lesson_id: str | None
    scene_id: str | None
    params: dict[str, Any]
    playing: bool
    time_scale: float = Field(description="× real time")
    mode: Literal["follow", "explore"]
    revision: int = Field(description="Grows with every change")
    reset_count: int
    explore_start: dict[str, Any] | None = Field(
        description="Where explorers start: scene_id, params and motion (t_s, y), or null"
    )
    students: StudentCounts
    instructor_connected: bool
    poll: PollPublic | None
    assignment: AssignmentPublic | None = Field(
        None, description="The exercises the instructor assigned (GET /api/exercises/{id}?room= for each), or null"
    )
    followers: int | None = Field(
        None, description="3D viewers showing the room's shared scene now (in the state route's answer)"
    )


class RoomClosed(BaseModel):
    closed: str = Field(description="The id of the room closed")


class ReadyQuestionSchema(BaseModel):
    id: str
    chapter: int
    scene_id: str
    question: str
    kind: Literal["choice", "number"]
    choices: list[str]
    unit: str
    preset: str | None
    params: dict[str, Any]
    answer_quantity: str
