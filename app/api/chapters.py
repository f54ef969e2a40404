from __future__ import annotations

from typing import Any

from fastapi import APIRouter

from app.api.deps import CatalogueDep
from app.api.schemas.chapters import ChapterEntry

router = APIRouter(prefix="/api", tags=["course"])


@router.get("/chapters", response_model=list[ChapterEntry])
def list_chapters(catalogue: CatalogueDep) -> list[dict[str, Any]]:
    """The ten chapters in order, with their sections and lessons (each with the first scene it shows)."""
    return [
        {
            "number": ch.number,
            "title": ch.title,
            "summary": ch.summary,
            "sections": [{"number": s.number, "title": s.title, "topics": list(s.topics)} for s in ch.sections],
            "lessons": [
                {
                    "id": lesson.id,
                    "title": lesson.title,
                    "url": lesson.url,
                    "section": lesson.section,
                    "scene": lesson.scene,
                }
                for lesson in ch.lessons
            ],
        }
        for ch in catalogue.chapters
    ]
