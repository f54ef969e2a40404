"""``GET /api/chapters``: the course outline with its lessons."""

from __future__ import annotations

from pydantic import BaseModel


class SectionEntry(BaseModel):
    number: str
    title: str
    topics: list[str]


class LessonEntry(BaseModel):
    """A lesson in the outline; ``scene`` is the first scene it shows (``null`` for a lesson without one)."""

    id: str
    title: str
    url: str
    section: str
    scene: str | None


class ChapterEntry(BaseModel):
    number: int
    title: str
    summary: str
    sections: list[SectionEntry]
    lessons: list[LessonEntry]
