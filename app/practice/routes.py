"""Exercises checked part by part, and the progress of a learner working alone.

A learner has no account: ``POST /api/learners`` gives a browser a secret token (sent back as ``X-Learner-Token``)
and a resume code for another device. Without a token an answer is still checked, and nothing is kept. A server
started with nothing kept (no database) checks answers and keeps no learners (503 on the learner routes).
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Annotated, Any
from urllib.parse import urlencode

from fastapi import APIRouter, Depends, Header, HTTPException, Path, Query, Request
from starlette.requests import HTTPConnection

from app.api.deps import CatalogueDep, ClientDep
from app.api.errors import unprocessable
from app.api.rate_limit import TokenBuckets, retry_after_s
from app.api.schemas.errors import ErrorDetail, error_responses
from app.api.schemas.exercises import (
    AttemptAnswer,
    AttemptRequest,
    ExerciseSolution,
    ExerciseSummary,
    ExerciseVariant,
    Forgotten,
    GiveUpRequest,
    NewLearner,
    ProgressView,
    ResumeRequest,
)
from app.classroom.registry import Rooms
from app.classroom.room import Room, StudentRemoved
from app.classroom.routes import RoomsDep, StudentToken, is_instructor, room_of
from app.course import Catalogue, render_markdown
from app.practice.book import ExerciseBook
from app.practice.checking import AnswerUnreadable, check
from app.practice.deps import BookDep, ProgressDep, RoomWorkDep
from app.practice.exercise import Exercise, Part, fill
from app.practice.in_room import RoomWork, assigned_variant, room_work
from app.practice.progress import Learner, PartProgress, SqlProgressStore, SqlRoomWorkStore
from app.practice.variants import NoValidVariant, Variant, learner_variant

router = APIRouter(prefix="/api", tags=["exercises"])

#: The learner refusals a route that reads ``X-Learner-Token`` can give, documented with the others.
_NOT_OWN: dict[int | str, dict[str, Any]] = {
    409: {
        "model": ErrorDetail,
        "description": "A learner's request names a variant that is not their own (in a room: the room's), or the "
        "room (room_id) does not assign this exercise",
    },
}
_NOT_ASSIGNED: dict[int | str, dict[str, Any]] = {
    409: {"model": ErrorDetail, "description": "The room (?room=) does not assign this exercise (any more)"},
}
_NO_LEARNER: dict[int | str, dict[str, Any]] = {
    401: {"model": ErrorDetail, "description": "No learner has this token (or none was sent where one is needed)"},
    503: {"model": ErrorDetail, "description": "This server keeps no progress (started with nothing kept)"},
}

LEARNER_HEADER = "X-Learner-Token"
#: New learners (and resumes) one client address may ask for at once, and per second after that: a class behind one
#: school address starts sixty at the start of a lesson; a script making thousands is refused (429).
LEARNER_BURST = 120
LEARNER_RATE_PER_S = 1.0
#: Answers one client address may have checked at once, and per second after that (an expression costs a few ms).
ATTEMPT_BURST = 120
ATTEMPT_RATE_PER_S = 10.0

ExerciseId = Annotated[str, Path(pattern=r"^[a-z0-9][a-z0-9-]{0,31}$", description="The exercise's id")]
LearnerToken = Annotated[
    str | None, Header(alias=LEARNER_HEADER, max_length=64, description="The token POST /api/learners gave")
]
RoomQuery = Annotated[
    str | None,
    Query(pattern=r"^[0-9a-f]{16}$", description="A room that assigned the exercise: the variant it gives"),
]
VariantQuery = Annotated[
    int | None,
    Query(ge=0, le=2**31 - 1, description="The variant (its numbers); default: the learner's own, else 0"),
]


def get_practice_limits(request: HTTPConnection) -> PracticeLimits:
    return request.app.state.practice_limits


class PracticeLimits:
    """Per client address: learners made or resumed, and answers checked (token buckets)."""

    def __init__(self) -> None:
        self.learners = TokenBuckets(burst=LEARNER_BURST, rate_per_s=LEARNER_RATE_PER_S, max_clients=10_000)
        self.attempts = TokenBuckets(burst=ATTEMPT_BURST, rate_per_s=ATTEMPT_RATE_PER_S, max_clients=10_000)


LimitsDep = Annotated[PracticeLimits, Depends(get_practice_limits)]


def _limit(buckets: TokenBuckets, client: str | None, what: str) -> None:
    wait_s = buckets.take(client or "local")
    if wait_s > 0:
        raise HTTPException(
            status_code=429,
            detail=f"too many {what} from this address just now; try again in {retry_after_s(wait_s)} s",
            headers={"Retry-After": str(retry_after_s(wait_s))},
        )


def _exercise(book: ExerciseBook, exercise_id: str) -> Exercise:
    exercise = book.get(exercise_id)
    if exercise is None:
        raise HTTPException(status_code=404, detail=f"no exercise {exercise_id!r}: GET /api/exercises lists them")
    return exercise


def _store(progress: SqlProgressStore | None) -> SqlProgressStore:
    if progress is None:
        raise HTTPException(
            status_code=503,
            detail="this server keeps no progress (it was started with nothing kept); answers are still checked",
            headers={"Retry-After": "3600"},
        )
    return progress


def _learner(progress: SqlProgressStore | None, token: str | None, *, required: bool) -> Learner | None:
    """The learner of ``token``; None without a token (unless ``required``); 401 for a token no learner has."""
    if not required and (token is None or progress is None):  # nothing to find, or nowhere to keep it
        return None
    if token is None:
        raise HTTPException(status_code=401, detail=f"send the learner's token as {LEARNER_HEADER}")
    learner = _store(progress).learner(token)
    if learner is None:
        raise HTTPException(
            status_code=401, detail="no learner has this token (forgotten after long unused?): POST /api/learners"
        )
    return learner


def _kept_parts(
    progress: SqlProgressStore, learner: Learner, exercise: Exercise, number: int
) -> dict[str, PartProgress]:
    """The learner's kept progress on the parts of variant ``number`` of ``exercise``, by part id."""
    return {
        p.part_id: p
        for p in progress.progress(learner.learner_id)
        if p.exercise_id == exercise.id and p.variant == number
    }


def _own_variant(exercise: Exercise, learner: Learner, number: int, *, expected: int | None = None) -> None:
    """409 unless ``number`` is the learner's own variant, or the ``expected`` one (the variant a room gives its
    student): progress, solutions and give-ups are per learner's numbers (an outside attack gave up on a classmate's
    variant to read its answers, and solved variant 0 to count as solved)."""
    own = expected if expected is not None else learner_variant(exercise.id, learner.learner_id)
    if number != own:
        raise HTTPException(
            status_code=409,
            detail=f"this learner works on variant {own} of {exercise.id!r}, not {number}: open the exercise again",
        )


def _in_room(rooms: Rooms, room_id: str | None, student_token: str | None, exercise: Exercise) -> RoomWork | None:
    return room_work(rooms, room_id, student_token, exercise) if room_id is not None else None


def _student_here(room: Room, student_token: str | None) -> str | None:
    """The id of the student of ``room`` holding ``student_token`` (None: no token, not theirs, or removed)."""
    try:
        student = room.student(student_token)
    except StudentRemoved:
        return None
    return student.student_id if student is not None else None


def _room_work_store(store: SqlRoomWorkStore | None) -> SqlRoomWorkStore:
    if store is None:
        raise HTTPException(
            status_code=503,
            detail="this server keeps no progress (it was started with nothing kept)",
            headers={"Retry-After": "3600"},
        )
    return store


def _room_view(room: Room) -> dict[str, Any]:
    with room.lock:
        return {
            "room_id": room.room_id,
            "code": room.code,
            "lesson_id": room.lesson_id,
            "class_variant": room.assignment is not None and room.assignment.class_seed is not None,
        }


def _variant(book: ExerciseBook, exercise: Exercise, number: int) -> Variant:
    try:
        return book.variant(exercise, number)
    except NoValidVariant as exc:  # a defect of the exercise's ranges (the tests draw 100 of each): say so, no 500
        raise HTTPException(status_code=422, detail=str(exc)) from None


def _given(variant: Variant) -> dict[str, dict[str, Any]]:
    return {g.name: {"value": variant.given[g.name], "unit": g.unit} for g in variant.exercise.given}


@router.get(
    "/exercises",
    response_model=list[ExerciseSummary],
    responses=error_responses(unprocessable="The section is not written as a section number (5.2)"),
)
def list_exercises(
    book: BookDep,
    section: Annotated[str | None, Query(pattern=r"^\d{1,2}\.\d{1,2}$", description="A section, e.g. 5.2")] = None,
) -> list[dict[str, Any]]:
    """The exercises of a section (or all), in course order."""
    return [exercise.summary() for exercise in book.of_section(section)]


@router.get(
    "/exercises/{exercise_id}",
    response_model=ExerciseVariant,
    responses={
        **error_responses(not_found="No exercise (or room) has this id", unprocessable="The variant is out of range"),
        **_NO_LEARNER,
        **_NOT_ASSIGNED,
    },
)
def get_exercise(
    exercise_id: ExerciseId,
    book: BookDep,
    progress: ProgressDep,
    catalogue: CatalogueDep,
    rooms: RoomsDep,
    variant: VariantQuery = None,
    room: RoomQuery = None,
    token: LearnerToken = None,
    student_token: StudentToken = None,
) -> dict[str, Any]:
    """One variant of an exercise: its statement and parts with that variant's numbers. Without ``variant`` a learner
    (``X-Learner-Token``) gets their own variant, the same every time; anyone else variant 0. With ``room`` (the
    exercise assigned there): the variant the room gives its student (``X-Student-Token``): the class's when the
    instructor gave the class one set of numbers, else the student's own in that room."""
    exercise = _exercise(book, exercise_id)
    in_room = room_of(room, rooms) if room is not None else None
    if in_room is not None and (in_room.assignment is None or exercise.id not in in_room.assignment.exercise_ids):
        raise HTTPException(status_code=409, detail=f"exercise {exercise.id!r} is not assigned in room {in_room.code}")
    if variant is None:
        learner = _learner(progress, token, required=False)
        learner_id = learner.learner_id if learner is not None else None
        student_id = _student_here(in_room, student_token) if in_room is not None else None
        variant = assigned_variant(in_room, exercise, student_id) if in_room is not None else None
        if variant is None:
            variant = learner_variant(exercise.id, learner_id) if learner_id is not None else 0
    drawn = _variant(book, exercise, variant)
    text = drawn.given_text()
    statement = fill(exercise.statement, text)
    parts = []
    for part in exercise.parts:
        shown = part.public(text)
        shown["prompt_html"] = render_markdown(shown["prompt"])
        shown["hints_html"] = [render_markdown(hint) for hint in shown["hints"]]
        parts.append(shown)
    scene = None
    if exercise.scene is not None:
        scene = exercise.scene.at(drawn.given)
        scene["url"] = scene_url(catalogue, scene["scene_id"], scene["params"])
    return {
        **exercise.summary(),
        "statement": statement,
        "statement_html": render_markdown(statement),
        "given": _given(drawn),
        "parts": parts,
        "scene": scene,
        "variant": variant,
        "room": _room_view(in_room) if in_room is not None else None,
    }


def scene_url(catalogue: Catalogue, scene_id: str, params: Mapping[str, Any]) -> str | None:
    """The first lesson showing ``scene_id``, opened at ``params`` (its share link's form), or None if no lesson
    shows it."""
    lesson = next((lesson for lesson in catalogue.lessons.values() if scene_id in lesson.scenes), None)
    if lesson is None:
        return None
    query = urlencode({"scene": scene_id, "params": json.dumps(dict(params), separators=(",", ":"))})
    return f"{lesson.url}?{query}"


def _part(exercise: Exercise, part_id: str) -> Part:
    part = exercise.part(part_id)
    if part is None:
        raise unprocessable(
            ["body", "part"],
            f"exercise {exercise.id!r} has no part {part_id!r}; its parts: " + ", ".join(p.id for p in exercise.parts),
        )
    return part


@router.post(
    "/exercises/{exercise_id}/attempts",
    response_model=AttemptAnswer,
    responses={
        **error_responses(
            not_found="No exercise has this id",
            unprocessable="The answer cannot be read (its unit, expression or form) or names no part; not counted",
        ),
        **_NO_LEARNER,
        **_NOT_OWN,
    },
)
def attempt(
    exercise_id: ExerciseId,
    request: AttemptRequest,
    book: BookDep,
    progress: ProgressDep,
    limits: LimitsDep,
    client: ClientDep,
    rooms: RoomsDep,
    kept_work: RoomWorkDep,
    token: LearnerToken = None,
    student_token: StudentToken = None,
) -> dict[str, Any]:
    """Check an answer to one part of one variant: ``correct``, ``feedback`` and, when it matches a named mistake,
    ``mistake``. With ``X-Learner-Token`` the attempt is kept in the learner's progress; with ``room_id`` (and the
    room's ``X-Student-Token``) as the student's work on an exercise assigned there, which the instructor's results
    count."""
    _limit(limits.attempts, client, "answers")
    exercise = _exercise(book, exercise_id)
    part = _part(exercise, request.part)
    answer = request.answer.model_dump()
    kind = {"value": "number", "vector": "vector", "expression": "expression", "choice": "choice"}
    sent = next(kind[key] for key in kind if key in answer)
    if sent != part.kind:
        raise unprocessable(["body", "answer"], f"part {part.id!r} asks for a {part.kind}, not a {sent}")
    work = _in_room(rooms, request.room_id, student_token, exercise)
    learner = _learner(progress, token, required=work is not None)
    expected = assigned_variant(work.room, exercise, work.student.student_id) if work is not None else None
    if learner is not None:
        _own_variant(exercise, learner, request.variant, expected=expected)
    drawn = _variant(book, exercise, request.variant)
    try:
        verdict = check(exercise, part, answer, drawn.answers[part.id])
    except AnswerUnreadable as exc:
        raise unprocessable(["body", "answer"], str(exc)) from None
    if learner is not None and progress is not None:
        progress.record(
            learner.learner_id,
            exercise_id=exercise.id,
            part_id=part.id,
            variant=request.variant,
            correct=verdict.correct,
            mistake_id=verdict.mistake.id if verdict.mistake else None,
        )
    if work is not None:
        _room_work_store(kept_work).record(
            work.room.room_id,
            work.student.student_id,
            exercise_id=exercise.id,
            part_id=part.id,
            variant=request.variant,
            correct=verdict.correct,
            mistake_id=verdict.mistake.id if verdict.mistake else None,
        )
    return {**verdict.public(), "feedback_html": render_markdown(verdict.feedback)}


def _solution(drawn: Variant) -> dict[str, Any]:
    parts = []
    for part in drawn.exercise.parts:
        answer = drawn.answers[part.id]
        value = answer.value
        if part.kind == "number":
            shown: dict[str, Any] = {"value": float(value), "unit": part.unit}  # type: ignore[arg-type]
        elif part.kind == "vector":
            shown = {"vector": [float(c) for c in value], "unit": part.unit, "frame": part.frame}  # type: ignore[union-attr]
        elif part.kind == "expression":
            shown = {"expression": str(value).replace("**", "^")}
        else:
            shown = {"choice": value}
        parts.append({"id": part.id, "answer": shown, "working": answer.working})
    return {"id": drawn.exercise.id, "variant": drawn.variant, "given": _given(drawn), "parts": parts}


@router.post(
    "/exercises/{exercise_id}/give-up",
    response_model=ExerciseSolution,
    responses={
        **error_responses(not_found="No exercise has this id", unprocessable="The variant is out of range"),
        **_NO_LEARNER,
        **_NOT_OWN,
    },
)
def give_up(
    exercise_id: ExerciseId,
    request: GiveUpRequest,
    book: BookDep,
    progress: ProgressDep,
    rooms: RoomsDep,
    kept_work: RoomWorkDep,
    token: LearnerToken = None,
    student_token: StudentToken = None,
) -> dict[str, Any]:
    """Give up on a variant (every part not yet solved is kept as given up) and get its worked solution; with
    ``room_id`` as work on an exercise assigned there (as for an attempt)."""
    exercise = _exercise(book, exercise_id)
    work = _in_room(rooms, request.room_id, student_token, exercise)
    learner = _learner(progress, token, required=True)
    assert learner is not None and progress is not None
    expected = assigned_variant(work.room, exercise, work.student.student_id) if work is not None else None
    _own_variant(exercise, learner, request.variant, expected=expected)
    drawn = _variant(book, exercise, request.variant)
    kept = _kept_parts(progress, learner, exercise, request.variant)
    for part in exercise.parts:
        if part.id not in kept or not kept[part.id].solved:
            progress.record(
                learner.learner_id, exercise_id=exercise.id, part_id=part.id, variant=request.variant, gave_up=True
            )
    if work is not None:
        store = _room_work_store(kept_work)
        room_id, student_id = work.room.room_id, work.student.student_id
        done = {
            p.part_id
            for s, p in store.work_of(room_id, [exercise.id])
            if s == student_id and p.variant == request.variant and p.solved
        }
        for part in exercise.parts:
            if part.id not in done:
                store.record(
                    room_id, student_id, exercise_id=exercise.id, part_id=part.id, variant=request.variant, gave_up=True
                )
    return _solution(drawn)


@router.get(
    "/exercises/{exercise_id}/solution",
    response_model=ExerciseSolution,
    responses={
        **error_responses(not_found="No exercise has this id", unprocessable="The variant is out of range"),
        **_NO_LEARNER,
        **_NOT_OWN,
        403: {"model": ErrorDetail, "description": "A learner who has not yet solved or given up every part"},
    },
)
def solution(
    exercise_id: ExerciseId,
    http: Request,
    book: BookDep,
    progress: ProgressDep,
    rooms: RoomsDep,
    variant: VariantQuery = None,
    room: RoomQuery = None,
    token: LearnerToken = None,
    student_token: StudentToken = None,
) -> dict[str, Any]:
    """A variant's worked solution with every part's answer: for an instructor always; for a learner once every part
    is solved or given up (with ``room``: the variant that room gives them)."""
    exercise = _exercise(book, exercise_id)
    in_room = room_of(room, rooms) if room is not None else None
    student_id = _student_here(in_room, student_token) if in_room is not None else None
    assigned = assigned_variant(in_room, exercise, student_id) if in_room is not None else None
    if is_instructor(http) and variant is None and assigned is not None:
        variant = assigned  # the class's numbers, for the instructor of a room that gives the class one set
    if not is_instructor(http):
        learner = _learner(progress, token, required=True)
        assert learner is not None and progress is not None
        own = assigned if assigned is not None else learner_variant(exercise.id, learner.learner_id)
        number = variant if variant is not None else own
        _own_variant(exercise, learner, number, expected=assigned)
        kept = _kept_parts(progress, learner, exercise, number)
        if not all(part.id in kept and (kept[part.id].solved or kept[part.id].gave_up) for part in exercise.parts):
            raise HTTPException(
                status_code=403, detail="the solution opens once every part is solved, or you give up on it"
            )
        variant = number
    return _solution(_variant(book, exercise, variant or 0))


@router.post("/learners", response_model=NewLearner, responses={503: _NO_LEARNER[503]})
def new_learner(progress: ProgressDep, limits: LimitsDep, client: ClientDep) -> dict[str, Any]:
    """A new learner: this browser's secret token and a resume code for another device (each shown only now)."""
    _limit(limits.learners, client, "new learners")
    learner = _store(progress).new_learner()
    return {"learner_id": learner.learner_id, "token": learner.token, "resume_code": learner.resume_code}


@router.post(
    "/learners/resume",
    response_model=NewLearner,
    responses={
        **error_responses(not_found="No learner has this resume code", unprocessable="The code is too long"),
        503: _NO_LEARNER[503],
    },
)
def resume(request: ResumeRequest, progress: ProgressDep, limits: LimitsDep, client: ClientDep) -> dict[str, Any]:
    """Carry a learner's progress to this browser: a resume code gives it a token of its own."""
    _limit(limits.learners, client, "resume codes")
    learner = _store(progress).resume(request.code)
    if learner is None:
        raise HTTPException(status_code=404, detail="no learner has this resume code (check it, letter by letter)")
    return {"learner_id": learner.learner_id, "token": learner.token, "resume_code": None}


@router.get(
    "/progress",
    response_model=ProgressView,
    responses={**error_responses(unprocessable="The token header is too long"), **_NO_LEARNER},
)
def get_learner_progress(book: BookDep, progress: ProgressDep, token: LearnerToken = None) -> dict[str, Any]:
    """The learner's progress: every part worked on, and per section how many exercises are started and solved."""
    learner = _learner(progress, token, required=True)
    assert learner is not None and progress is not None
    parts = progress.progress(learner.learner_id)
    sections: dict[str, dict[str, int]] = {}
    for exercise in book.exercises.values():
        mine = [p for p in parts if p.exercise_id == exercise.id]
        counts = sections.setdefault(exercise.section, {"exercises": 0, "started": 0, "solved": 0})
        counts["exercises"] += 1
        counts["started"] += bool(mine)
        counts["solved"] += {p.part_id for p in mine if p.solved} == {part.id for part in exercise.parts}
    return {"learner_id": learner.learner_id, "parts": [p.public() for p in parts], "sections": sections}


@router.delete(
    "/progress",
    response_model=Forgotten,
    responses={**error_responses(unprocessable="The token header is too long"), **_NO_LEARNER},
)
def forget_learner(progress: ProgressDep, token: LearnerToken = None) -> dict[str, Any]:
    """Forget this learner and all their progress (every device's token stops working)."""
    learner = _learner(progress, token, required=True)
    assert learner is not None and progress is not None
    progress.forget(learner.learner_id)
    return {"learner_id": learner.learner_id, "forgotten": True}
