"""``/api/exercises``, ``/api/learners`` and ``/api/progress``: exercises, answers checked part by part, a learner's
progress."""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Field, StrictBool, StrictInt


class ExerciseSummary(BaseModel):
    id: str
    title: str
    chapter: int
    section: str
    parts: int = Field(description="How many parts the exercise has")


class GivenNumber(BaseModel):
    value: float
    unit: str


class ExpressionSymbolSpec(BaseModel):
    name: str = Field(description="The symbol as typed in an answer")
    meaning: str


class ChoiceSpec(BaseModel):
    id: str
    text: str


class PartSpec(BaseModel):
    id: str
    prompt: str = Field(description="Markdown with $…$ LaTeX")
    prompt_html: str = Field(description="The prompt as HTML (LaTeX in span.math for KaTeX)")
    answer_kind: Literal["number", "vector", "expression", "choice"]
    unit: str | None = Field(description="The unit the answer is asked in (any unit of its dimension is accepted)")
    frame: str | None = Field(description="A vector's frame: its components are asked in this frame")
    choices: list[ChoiceSpec] | None
    symbols: list[ExpressionSymbolSpec] | None = Field(description="The symbols an expression answer may use")
    up_to_constant: bool = Field(False, description="An expression that may differ from the answer by a constant")
    tolerance: float = Field(description="Relative tolerance of a number, vector or expression (0.01: 1 %)")
    hints: list[str] = Field(description="Hints, to be shown one at a time on request")
    hints_html: list[str]


class SceneAt(BaseModel):
    scene_id: str
    params: dict[str, Any]
    url: str | None = Field(description="A lesson showing the scene, opened at these parameters")


class RoomAssigning(BaseModel):
    room_id: str
    code: str
    lesson_id: str | None = Field(description="The lesson the room shows (a page to go back to)")
    class_variant: bool = Field(description="The class works on one set of numbers")


class ExerciseVariant(BaseModel):
    """One variant of an exercise: its statement with this variant's numbers, the numbers, the parts."""

    id: str
    title: str
    chapter: int
    section: str
    statement: str = Field(description="Markdown with $…$ LaTeX and this variant's numbers")
    statement_html: str = Field(description="The statement as HTML (LaTeX in span.math for KaTeX)")
    given: dict[str, GivenNumber]
    parts: list[PartSpec]
    scene: SceneAt | None = Field(description='The scene at this variant\'s numbers ("See it")')
    variant: int
    room: RoomAssigning | None = Field(None, description="The room the exercise was opened from (?room=), or null")


class NumberAnswer(BaseModel):
    model_config = ConfigDict(extra="forbid")
    value: float
    unit: str = Field("", max_length=40, description="Any unit of the asked dimension; empty: the part's unit")


class VectorAnswer(BaseModel):
    model_config = ConfigDict(extra="forbid")
    vector: list[float] = Field(min_length=3, max_length=3)
    unit: str = Field("", max_length=40)
    frame: str = Field("", max_length=40, description="The frame of the components (the part's)")


class ExpressionAnswer(BaseModel):
    model_config = ConfigDict(extra="forbid")
    expression: str = Field(max_length=400, description="Typed with + - * / ^ ( ), sqrt sin cos tan exp log and pi")


class ChoiceAnswer(BaseModel):
    model_config = ConfigDict(extra="forbid")
    choice: str = Field(max_length=32)


class AttemptRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    variant: int = Field(ge=0, le=2**31 - 1)
    part: str = Field(max_length=32)
    answer: NumberAnswer | VectorAnswer | ExpressionAnswer | ChoiceAnswer
    room_id: str | None = Field(
        None,
        pattern=r"^[0-9a-f]{16}$",
        description="Work assigned in this room (with the room's X-Student-Token): the instructor's results count it",
    )


class MistakeNamed(BaseModel):
    id: str
    text: str


class AttemptAnswer(BaseModel):
    correct: bool
    feedback: str = Field(description="Markdown with $…$ LaTeX")
    feedback_html: str
    mistake: MistakeNamed | None


class GiveUpRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    variant: int = Field(ge=0, le=2**31 - 1)
    room_id: str | None = Field(
        None,
        pattern=r"^[0-9a-f]{16}$",
        description="Work assigned in this room (with the room's X-Student-Token): the instructor's results count it",
    )


class PartSolution(BaseModel):
    id: str
    answer: dict[str, Any] = Field(description="In the form an attempt would send it, in the part's unit")
    working: str = Field(description="LaTeX: how the answer is reached, with this variant's numbers")


class ExerciseSolution(BaseModel):
    id: str
    variant: int
    given: dict[str, GivenNumber]
    parts: list[PartSolution]


class NewLearner(BaseModel):
    learner_id: str
    token: str = Field(description="This browser's secret: send it as X-Learner-Token; shown once")
    resume_code: str | None = Field(description="Type it on another device to carry the progress there; shown once")


class ResumeRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    code: str = Field(max_length=40)


class PartProgressView(BaseModel):
    exercise_id: str
    part: str
    variant: int
    attempts: int
    solved: bool
    gave_up: bool
    mistakes: list[str]


class SectionProgress(BaseModel):
    exercises: int = Field(description="Exercises in the section")
    started: int = Field(description="Exercises with at least one part attempted")
    solved: int = Field(description="Exercises with every part solved")


class ProgressView(BaseModel):
    learner_id: str
    parts: list[PartProgressView]
    sections: dict[str, SectionProgress]


class Forgotten(BaseModel):
    learner_id: str
    forgotten: bool = Field(description="True: the learner and every part of their progress are gone")


class AssignmentRequest(BaseModel):
    """Exercises to assign a room: a section's set, or chosen ones (in the order given)."""

    model_config = ConfigDict(extra="forbid")
    section: str | None = Field(
        None, pattern=r"^\d{1,2}\.\d{1,2}$", description="Every exercise of a section, e.g. 5.2"
    )
    exercise_ids: list[Annotated[str, Field(pattern=r"^[a-z0-9][a-z0-9-]{0,31}$")]] | None = Field(
        None, min_length=1, max_length=24, description="Chosen exercises (instead of a section)"
    )
    class_variant: StrictBool = Field(
        False, description="Every student works on the same numbers (kept while the assignment is changed)"
    )
    seed: StrictInt | None = Field(
        None, ge=0, le=2**31 - 1, description="The class's numbers (with class_variant; default: the room's, or drawn)"
    )
    show_names: StrictBool = Field(False, description="The results name the students (else 'student 3')")


class MistakeCount(BaseModel):
    mistake: str
    text: str = Field(description="What the feedback says when an answer matches it")
    students: int = Field(description="Students whose answers matched it")


class StudentPartWork(BaseModel):
    student: str = Field(description="The name they gave (or 'student 3')")
    student_id: str = Field(description="Their id in the room (s3): two students may give the same name")
    attempts: int
    solved: bool
    gave_up: bool
    mistakes: list[str]


class PartResults(BaseModel):
    part: str
    kind: str
    tried: int = Field(description="Students who answered it at least once, or gave up")
    solved: int
    gave_up: int
    mistakes: list[MistakeCount] = Field(description="Named mistakes, most common first")
    names: list[StudentPartWork] | None = Field(None, description="Each student's work (only when names are on)")


class ExerciseResults(BaseModel):
    exercise_id: str
    title: str
    section: str
    variant: int | None = Field(description="The class's variant (null: each student works on their own)")
    parts: list[PartResults]


class AssignmentResults(BaseModel):
    assignment: dict[str, Any] | None
    students: int = Field(description="Students in the room now")
    show_names: bool
    exercises: list[ExerciseResults]


class AssignmentView(BaseModel):
    """The room's assignment as the instructor set it."""

    exercise_ids: list[str]
    class_variant: bool
    assigned_at: str = Field(description="UTC, ISO 8601")
    show_names: bool
    seed: int | None = Field(description="The class's numbers (null: each student works on their own)")


class Unassigned(BaseModel):
    assignment: None = Field(description="Nothing is assigned now")
