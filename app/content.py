"""The course outline and lesson files under ``lessons/``.

``lessons/course.toml`` lists the ten chapters and their sections. Each lesson
is ``lessons/chNN/<id>.md``: TOML front matter between ``+++`` lines (id,
chapter, section, order, title, summary, optional scene and examples) and a
Markdown body with LaTeX math (``$...$`` inline, ``$$...$$`` display). Math is
set aside before Markdown runs and rendered in the browser by the vendored KaTeX.
"""

from __future__ import annotations

import html
import re
import tomllib
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import Any

from markdown_it import MarkdownIt

LESSONS_DIR = Path(__file__).resolve().parent.parent / "lessons"

_DISPLAY_MATH = re.compile(r"\$\$(.+?)\$\$", re.DOTALL)
_INLINE_MATH = re.compile(r"(?<![\\$])\$(?!\$)([^\n$]+?)(?<!\\)\$")
_PLACEHOLDER = re.compile(r"MATHSPAN(\d+)END")
_markdown = MarkdownIt("commonmark", {"html": False, "typographer": False}).enable("table")


def render_markdown(text: str) -> str:
    """Markdown to HTML, with math kept verbatim in ``span.math`` for KaTeX."""
    spans: list[str] = []

    def stash(display: bool):
        def replace(match: re.Match[str]) -> str:
            tex = html.escape(match.group(1).strip())
            cls = "math math-display" if display else "math math-inline"
            spans.append(f'<span class="{cls}">{tex}</span>')
            return f"MATHSPAN{len(spans) - 1}END"

        return replace

    text = _DISPLAY_MATH.sub(stash(True), text)
    text = _INLINE_MATH.sub(stash(False), text)
    rendered = _markdown.render(text)
    return _PLACEHOLDER.sub(lambda m: spans[int(m.group(1))], rendered)


@dataclass(frozen=True)
class Lesson:
    id: str
    chapter: int
    section: str
    order: int
    title: str
    summary: str
    body_markdown: str
    scene: str | None = None
    examples: tuple[str, ...] = ()

    @property
    def url(self) -> str:
        return f"/lessons/{self.id}"

    @cached_property
    def body_html(self) -> str:
        return render_markdown(self.body_markdown)


@dataclass(frozen=True)
class Section:
    number: str
    title: str
    topics: tuple[str, ...] = ()


@dataclass(frozen=True)
class Chapter:
    number: int
    title: str
    summary: str
    sections: tuple[Section, ...]
    lessons: tuple[Lesson, ...] = field(default=())


def parse_lesson(text: str, source: str) -> Lesson:
    """Parse one lesson file; raises ValueError naming ``source`` on a malformed file."""
    parts = text.split("+++", 2)
    if len(parts) != 3 or parts[0].strip():
        raise ValueError(f"{source}: a lesson starts with TOML front matter between '+++' lines")
    try:
        meta: dict[str, Any] = tomllib.loads(parts[1])
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{source}: front matter: {exc}") from None
    required = ("id", "chapter", "section", "order", "title")
    missing = [k for k in required if k not in meta]
    if missing:
        raise ValueError(f"{source}: front matter lacks {', '.join(missing)}")
    return Lesson(
        id=str(meta["id"]),
        chapter=int(meta["chapter"]),
        section=str(meta["section"]),
        order=int(meta["order"]),
        title=str(meta["title"]),
        summary=str(meta.get("summary", "")),
        body_markdown=parts[2].strip(),
        scene=meta.get("scene"),
        examples=tuple(meta.get("examples", ())),
    )


class Course:
    """All chapters and lessons, loaded once at start-up."""

    def __init__(self, root: Path = LESSONS_DIR) -> None:
        outline = tomllib.loads((root / "course.toml").read_text(encoding="utf-8"))
        lessons = sorted(
            (parse_lesson(p.read_text(encoding="utf-8"), str(p)) for p in sorted(root.glob("ch*/*.md"))),
            key=lambda lesson: (lesson.chapter, lesson.order),
        )
        self.lessons: dict[str, Lesson] = {}
        for lesson in lessons:
            if lesson.id in self.lessons:
                raise ValueError(f"two lessons share the id {lesson.id!r}")
            self.lessons[lesson.id] = lesson
        self.chapters: tuple[Chapter, ...] = tuple(
            Chapter(
                number=int(ch["number"]),
                title=ch["title"],
                summary=ch.get("summary", ""),
                sections=tuple(Section(s["number"], s["title"], tuple(s.get("topics", ()))) for s in ch["sections"]),
                lessons=tuple(lesson for lesson in lessons if lesson.chapter == int(ch["number"])),
            )
            for ch in outline["chapter"]
        )

    def chapter_of(self, lesson: Lesson) -> Chapter:
        return next(ch for ch in self.chapters if ch.number == lesson.chapter)

    def neighbours(self, lesson: Lesson) -> tuple[Lesson | None, Lesson | None]:
        ordered = list(self.lessons.values())
        i = ordered.index(lesson)
        return (ordered[i - 1] if i > 0 else None, ordered[i + 1] if i + 1 < len(ordered) else None)
