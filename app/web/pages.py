"""HTML pages: the course outline, lesson pages and the viser viewer page."""

from __future__ import annotations

import html
import json
from functools import lru_cache
from pathlib import Path
from string import Template

import viser
from fastapi import APIRouter, HTTPException
from fastapi.responses import HTMLResponse, RedirectResponse, Response

from app.api.deps import CourseDep, SceneHostDep
from app.content import Chapter, Lesson
from app.physics.examples import EXAMPLES
from app.scenes.host import SESSION_ID_PATTERN

router = APIRouter(tags=["pages"], include_in_schema=False)
TEMPLATES = Path(__file__).resolve().parent / "templates"
esc = html.escape


@lru_cache(maxsize=None)
def _template(name: str) -> Template:
    return Template((TEMPLATES / name).read_text(encoding="utf-8"))


@lru_cache(maxsize=1)
def _viser_client_html() -> bytes:
    return (Path(viser.__file__).resolve().parent / "client" / "build" / "index.html").read_bytes()


def _page(title: str, body: str, *, scripts: tuple[str, ...] = ()) -> HTMLResponse:
    return HTMLResponse(
        _template("page.html").substitute(
            title=esc(title), body=body, scripts="".join(f'<script src="{src}" defer></script>' for src in scripts)
        )
    )


def _chapter_card(chapter: Chapter) -> str:
    sections = "".join(f"<li><span class=sec-num>{esc(s.number)}</span> {esc(s.title)}</li>" for s in chapter.sections)
    if chapter.lessons:
        lessons = "".join(
            f'<li><a href="{esc(l.url)}"><span class=sec-num>{esc(l.section)}</span> {esc(l.title)}</a>'
            + (' <span class="tag" title="has a live 3D scene">3D</span>' if l.scene else "")
            + "</li>"
            for l in chapter.lessons
        )
        lessons_html = f'<h4>Lessons</h4><ul class="lessons">{lessons}</ul>'
    else:
        lessons_html = '<p class="muted">No interactive lessons for this chapter yet.</p>'
    return (
        f'<section class="chapter" id="chapter-{chapter.number}" aria-labelledby="ch{chapter.number}-title">'
        f'<h3 id="ch{chapter.number}-title"><span class="ch-num">{chapter.number}</span> {esc(chapter.title)}</h3>'
        f'<p class="summary">{esc(chapter.summary)}</p>'
        f'<details><summary>Sections</summary><ul class="sections">{sections}</ul></details>'
        f"{lessons_html}</section>"
    )


@router.get("/", response_class=HTMLResponse)
def course_page(course: CourseDep) -> HTMLResponse:
    body = _template("course.html").substitute(chapters="".join(_chapter_card(ch) for ch in course.chapters))
    return _page("Dynamics Lab — course", body, scripts=("/static/js/common.js",))


def _lesson_config(lesson: Lesson, host_scenes: dict) -> dict:
    scene_cls = host_scenes.get(lesson.scene) if lesson.scene else None
    return {
        "lesson_id": lesson.id,
        "scene": scene_cls.schema() if scene_cls else None,
        "examples": [EXAMPLES[e].schema() for e in lesson.examples if e in EXAMPLES],
    }


@router.get("/lessons/{lesson_id}", response_class=HTMLResponse)
def lesson_page(lesson_id: str, course: CourseDep, host: SceneHostDep) -> HTMLResponse:
    lesson = course.lessons.get(lesson_id)
    if lesson is None:
        raise HTTPException(status_code=404, detail=f"no lesson {lesson_id!r}")
    chapter = course.chapter_of(lesson)
    previous, following = course.neighbours(lesson)
    nav = "".join(
        f'<a class="{cls}" href="{esc(l.url)}">{arrow} {esc(l.section)} {esc(l.title)}</a>' if l else "<span></span>"
        for l, cls, arrow in ((previous, "prev", "←"), (following, "next", "→"))
    )
    config = json.dumps(_lesson_config(lesson, host.scenes)).replace("</", "<\\/")
    body = _template("lesson.html").substitute(
        chapter_number=chapter.number,
        chapter_title=esc(chapter.title),
        section=esc(lesson.section),
        title=esc(lesson.title),
        summary=esc(lesson.summary),
        lesson_html=lesson.body_html,
        nav=nav,
        config=config,
        has_scene="has-scene" if lesson.scene or lesson.examples else "no-scene",
    )
    return _page(
        f"{lesson.section} {lesson.title} — Dynamics Lab",
        body,
        scripts=("/static/vendor/katex/katex.min.js", "/static/js/common.js", "/static/js/plot.js", "/static/js/lesson.js"),
    )


@router.get("/viewer/{scene_id}/{session_id}")
def viewer_redirect(scene_id: str, session_id: str) -> RedirectResponse:
    return RedirectResponse(f"/viewer/{scene_id}/{session_id}/")


@router.get("/viewer/{scene_id}/{session_id}/")
def viewer_page(scene_id: str, session_id: str, host: SceneHostDep) -> Response:
    """viser's single-file client; it connects back to this path's websocket relay."""
    if scene_id not in host.scenes or not SESSION_ID_PATTERN.match(session_id):
        raise HTTPException(status_code=404, detail="unknown scene or malformed session id")
    return Response(_viser_client_html(), media_type="text/html; charset=utf-8")
