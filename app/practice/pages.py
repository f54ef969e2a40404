"""The practice pages: an exercise (its numbers, parts, hints, feedback and worked solution come from
static/js/exercise.js through the exercise API)."""

from __future__ import annotations

from fastapi import APIRouter, HTTPException
from fastapi.responses import HTMLResponse

from app.api.deps import CatalogueDep
from app.practice.deps import BookDep
from app.web.pages import _page, _template, esc

router = APIRouter(tags=["pages"], include_in_schema=False)


@router.get("/exercises/{exercise_id}", response_class=HTMLResponse)
def exercise_page(exercise_id: str, book: BookDep, catalogue: CatalogueDep) -> HTMLResponse:
    """An exercise: its numbers (the learner's own variant) and parts are fetched by static/js/exercise.js."""
    exercise = book.get(exercise_id)
    if exercise is None:
        raise HTTPException(status_code=404, detail=f"no exercise {exercise_id!r}")
    lesson = next((l for l in catalogue.lessons.values() if l.section == exercise.section), None)
    section_link = (
        f'<a href="{esc(lesson.url)}#practice">Section {esc(exercise.section)}</a>'
        if lesson
        else f"Section {esc(exercise.section)}"
    )
    body = _template("exercise.html").substitute(
        chapter_number=exercise.chapter,
        section_link=section_link,
        section=esc(exercise.section),
        title=esc(exercise.title),
        exercise_id=esc(exercise.id),
    )
    return _page(
        f"{exercise.section} {exercise.title} — exercise — Dynamics Lab", body, scripts=("/static/js/exercise.js",)
    )
