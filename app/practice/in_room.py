"""Exercises in a class room (issue 27, point 7): the instructor assigns exercises, optionally with one set of numbers
for the whole class, and watches per exercise and per part how many students tried, solved or gave up, and which
named mistakes are common; the results download as CSV.

A student works an assigned exercise on its page with two tokens: the room's (``X-Student-Token``: they are in the
room) and their learner's (``X-Learner-Token``: their own progress, app.practice.progress). Each attempt is kept twice:
in the learner's progress, and in the room's record of that student's work (:class:`SqlRoomWorkStore`), which the
results read — a learner forgetting their progress, or working from another device, leaves the room's record as it
was. Anonymous ("student 3") unless the instructor turns names on.
"""

from __future__ import annotations

import csv
import io
import secrets
from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from fastapi import APIRouter, HTTPException
from fastapi.responses import PlainTextResponse

from app.api.schemas.errors import ErrorDetail, error_responses
from app.api.schemas.exercises import AssignmentRequest, AssignmentResults, AssignmentView, Unassigned
from app.classroom.assignment import MAX_ASSIGNED, Assignment
from app.classroom.hub import RoomHubDep
from app.classroom.polls import spreadsheet_text
from app.classroom.registry import Rooms
from app.classroom.room import Room, Student, StudentRemoved
from app.classroom.routes import _FORBIDDEN, _NO_ROOM, Instructor, RoomDep, room_of
from app.practice.book import ExerciseBook
from app.practice.deps import BookDep, RoomWorkDep
from app.practice.exercise import Exercise
from app.practice.progress import PartProgress, SqlRoomWorkStore
from app.practice.variants import class_variant, room_student_variant

router = APIRouter(prefix="/api", tags=["exercises"])

#: The CSV's columns: one row per student, exercise and part they worked on.
CSV_HEADER = (
    "student_id",
    "student",
    "exercise_id",
    "part",
    "variant",
    "attempts",
    "solved",
    "gave_up",
    "mistakes",
    "updated_at_utc",
)


@dataclass(frozen=True)
class RoomWork:
    """A student working an exercise assigned in their room."""

    room: Room
    student: Student
    exercise: Exercise


def assigned_variant(room: Room, exercise: Exercise, student_id: str | None) -> int | None:
    """The variant a student of ``room`` works on for ``exercise``: the class's when the instructor gave the class
    one set of numbers, else the student's own in that room, the same on each of their devices (None: the exercise
    is not assigned there, or no student to ask)."""
    assignment = room.assignment
    if assignment is None or exercise.id not in assignment.exercise_ids:
        return None
    if assignment.class_seed is not None:
        return class_variant(exercise.id, assignment.class_seed)
    return room_student_variant(room.room_id, student_id, exercise.id) if student_id is not None else None


def room_work(rooms: Rooms, room_id: str, student_token: str | None, exercise: Exercise) -> RoomWork:
    """The student of ``student_token`` in room ``room_id`` working ``exercise``, which must be assigned there:
    404 no room, 403 not a student of it, 409 not assigned (any more)."""
    room = room_of(room_id, rooms)
    try:
        student = room.student(student_token)
    except StudentRemoved as exc:
        raise HTTPException(status_code=403, detail=str(exc)) from None
    if student is None:
        raise HTTPException(
            status_code=403, detail="work in a room needs the X-Student-Token this room gave when you joined"
        )
    if room.assignment is None or exercise.id not in room.assignment.exercise_ids:
        raise HTTPException(
            status_code=409,
            detail=f"exercise {exercise.id!r} is not assigned in room {room.code} (any more); it is still yours to "
            "practise without the room",
        )
    return RoomWork(room=room, student=student, exercise=exercise)


# ---- the instructor's routes --------------------------------------------------------------------------
_BAD_ASSIGNMENT = "Neither or both of section and exercise_ids, an unknown exercise, or a section without exercises"


def _requested_ids(book: ExerciseBook, body: AssignmentRequest) -> tuple[str, ...]:
    if (body.section is None) == (body.exercise_ids is None):
        raise HTTPException(status_code=422, detail="give either section (5.2) or exercise_ids, not both")
    if body.section is not None:
        ids = tuple(exercise.id for exercise in book.of_section(body.section))
        if not ids:
            raise HTTPException(status_code=422, detail=f"section {body.section} has no exercises yet")
        return ids[:MAX_ASSIGNED]
    assert body.exercise_ids is not None
    unknown = [i for i in body.exercise_ids if book.get(i) is None]
    if unknown:
        raise HTTPException(status_code=422, detail="no exercise " + ", ".join(map(repr, unknown)))
    return tuple(dict.fromkeys(body.exercise_ids))  # each once, in the order given


@router.put(
    "/rooms/{room_id}/assignment",
    response_model=AssignmentView,
    dependencies=[Instructor],
    responses={**_FORBIDDEN, **error_responses(not_found=_NO_ROOM, unprocessable=_BAD_ASSIGNMENT)},
)
def assign(room: RoomDep, body: AssignmentRequest, book: BookDep, hub: RoomHubDep) -> dict[str, Any]:
    """Assign exercises to the room (instructor only), replacing what was assigned: a section's set or chosen ones;
    ``class_variant`` gives every student the same numbers (a ``seed`` of the instructor's, or the room's own, kept
    while the assignment changes); ``show_names`` names the students in the results. Every page sees it at once."""
    ids = _requested_ids(book, body)
    seed = None
    if body.class_variant:  # the room's seed, kept while the assignment changes (students keep their numbers)
        kept = room.class_seed
        seed = body.seed if body.seed is not None else kept if kept is not None else secrets.randbelow(2**31)
    earlier = room.assignment
    same_work = earlier is not None and earlier.exercise_ids == ids and earlier.class_seed == seed
    assigned = room.assign(
        Assignment(
            exercise_ids=ids,
            class_seed=seed,
            show_names=body.show_names,
            **({"assigned_at": earlier.assigned_at} if same_work and earlier is not None else {}),
        )
    )
    hub.publish_state(room)
    assert assigned is not None
    return {**assigned.public(), "show_names": assigned.show_names, "seed": assigned.class_seed}


@router.delete(
    "/rooms/{room_id}/assignment",
    response_model=Unassigned,
    dependencies=[Instructor],
    responses={**_FORBIDDEN, **error_responses(not_found=_NO_ROOM, unprocessable="A malformed room id")},
)
def unassign(room: RoomDep, hub: RoomHubDep) -> dict[str, Any]:
    """Take the assignment back (instructor only): pages stop showing it; the students' work stays theirs."""
    room.assign(None)
    hub.publish_state(room)
    return {"assignment": None}


@router.get(
    "/rooms/{room_id}/assignment/results",
    response_model=AssignmentResults,
    response_model_exclude_none=True,
    dependencies=[Instructor],
    responses={
        **_FORBIDDEN,
        **error_responses(not_found=_NO_ROOM, unprocessable="A malformed room id"),
        503: {"model": ErrorDetail, "description": "This server keeps no progress (started with nothing kept)"},
    },
)
def results(room: RoomDep, book: BookDep, room_work: RoomWorkDep) -> dict[str, Any]:
    """Per assigned exercise and part (instructor only): how many students tried, solved and gave up, and the named
    mistakes their answers matched, most common first; each student's work when names are on."""
    return assignment_results(room, book, _kept_work(room, room_work))


@router.get("/rooms/{room_id}/assignment/results.csv", dependencies=[Instructor], include_in_schema=False)
def results_csv(room: RoomDep, book: BookDep, room_work: RoomWorkDep) -> PlainTextResponse:
    """Every student's work on every assigned part, one row each (instructor only); anonymous unless names are on."""
    filename = f"room-{room.code}-exercises.csv"
    return PlainTextResponse(
        results_to_csv(room, book, _kept_work(room, room_work)),
        media_type="text/csv",
        headers={"Content-Disposition": f'attachment; filename="{filename}"'},
    )


# ---- the results ------------------------------------------------------------------------------------
@dataclass(frozen=True)
class StudentWork:
    """One student's work on one part, as the room kept it."""

    student_id: str
    label: str
    variant: int
    attempts: int
    solved: bool
    gave_up: bool
    mistakes: tuple[str, ...]
    updated_at: str


def _kept_work(room: Room, room_work: SqlRoomWorkStore | None) -> list[tuple[str, PartProgress]]:
    if room_work is None:
        raise HTTPException(
            status_code=503,
            detail="this server keeps no progress (it was started with nothing kept): no results to show",
            headers={"Retry-After": "3600"},
        )
    with room.lock:
        assigned = list(room.assignment.exercise_ids) if room.assignment is not None else []
    return room_work.work_of(room.room_id, assigned)


def _work_by_part(
    room: Room, book: ExerciseBook, kept: Iterable[tuple[str, PartProgress]]
) -> dict[tuple[str, str], dict[str, StudentWork]]:
    """By (exercise, part), then student id: each student's work on the variant the room gives them now (work on
    another — before the class was given one set of numbers, or another set — does not count), students still in the
    room only. Given up counts over solved: a right answer typed after giving up is the solution's, copied."""
    with room.lock:
        students = {s.student_id: s.name for s in room.students.values()}
        show_names = room.assignment is not None and room.assignment.show_names
    work: dict[tuple[str, str], dict[str, StudentWork]] = {}
    for student_id, part in kept:
        exercise = book.get(part.exercise_id)
        if exercise is None or student_id not in students:
            continue
        if part.variant != assigned_variant(room, exercise, student_id):
            continue
        name = students[student_id]
        work.setdefault((part.exercise_id, part.part_id), {})[student_id] = StudentWork(
            student_id=student_id,
            label=name if show_names and name else f"student {student_id[1:]}",
            variant=part.variant,
            attempts=part.attempts,
            solved=part.solved and not part.gave_up,
            gave_up=part.gave_up,
            mistakes=part.mistakes,
            updated_at=part.updated_at.strftime("%Y-%m-%dT%H:%M:%SZ"),
        )
    return work


def assignment_results(room: Room, book: ExerciseBook, kept: Iterable[tuple[str, PartProgress]]) -> dict[str, Any]:
    """The instructor's view of the room's assigned exercises (``GET …/assignment/results``)."""
    work = _work_by_part(room, book, kept)
    assignment = room.assignment
    show_names = assignment is not None and assignment.show_names
    exercises = []
    for exercise in _assigned(book, assignment):
        parts = []
        for part in exercise.parts:
            by_student = work.get((exercise.id, part.id), {})
            counted = Counter(m for w in by_student.values() for m in w.mistakes)
            texts = {m.id: m.text for m in exercise.mistakes_of(part.id)}
            shown: dict[str, Any] = {
                "part": part.id,
                "kind": part.kind,
                "tried": sum(1 for w in by_student.values() if w.attempts or w.gave_up),
                "solved": sum(1 for w in by_student.values() if w.solved),
                "gave_up": sum(1 for w in by_student.values() if w.gave_up),
                "mistakes": [
                    {"mistake": m, "text": texts.get(m, m), "students": n}
                    for m, n in counted.most_common()
                    if m in texts
                ],
            }
            if show_names:
                shown["names"] = [
                    {
                        "student": w.label,
                        "student_id": w.student_id,
                        "attempts": w.attempts,
                        "solved": w.solved,
                        "gave_up": w.gave_up,
                        "mistakes": list(w.mistakes),
                    }
                    for _, w in sorted(by_student.items(), key=lambda item: int(item[0][1:]))
                ]
            parts.append(shown)
        seed = assignment.class_seed if assignment is not None else None
        variant = class_variant(exercise.id, seed) if seed is not None else None
        exercises.append(
            {
                "exercise_id": exercise.id,
                "title": exercise.title,
                "section": exercise.section,
                "variant": variant,
                "parts": parts,
            }
        )
    with room.lock:
        joined = len(room.students)
    return {
        "assignment": assignment.public() if assignment is not None else None,
        "students": joined,
        "show_names": show_names,
        "exercises": exercises,
    }


def results_to_csv(room: Room, book: ExerciseBook, kept: Iterable[tuple[str, PartProgress]]) -> str:
    """One row per student, assigned exercise and part worked on. Every text cell is made safe to open in a
    spreadsheet (:func:`spreadsheet_text`): a student's name is what they typed."""
    work = _work_by_part(room, book, kept)
    buffer = io.StringIO()
    # Every text cell quoted too: a spreadsheet whose list separator is ";" would otherwise split "x;=1+1" into a
    # second cell that starts with a formula. Numbers stay numbers.
    writer = csv.writer(buffer, lineterminator="\n", quoting=csv.QUOTE_NONNUMERIC)
    writer.writerow(CSV_HEADER)
    for exercise in _assigned(book, room.assignment):
        for part in exercise.parts:
            by_student = work.get((exercise.id, part.id), {})
            for _, w in sorted(by_student.items(), key=lambda item: int(item[0][1:])):
                writer.writerow(
                    (
                        w.student_id,
                        spreadsheet_text(w.label),
                        spreadsheet_text(exercise.id),
                        spreadsheet_text(part.id),
                        w.variant,
                        w.attempts,
                        "yes" if w.solved else "no",
                        "yes" if w.gave_up else "no",
                        spreadsheet_text(" ".join(w.mistakes)),
                        w.updated_at,
                    )
                )
    return buffer.getvalue()


def _assigned(book: ExerciseBook, assignment: Assignment | None) -> list[Exercise]:
    if assignment is None:
        return []
    return [e for e in (book.get(i) for i in assignment.exercise_ids) if e is not None]
