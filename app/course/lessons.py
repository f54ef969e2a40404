"""Lesson files and the course outline as parsed, before any cross-checking.

``lessons/course.toml`` lists the ten chapters and their sections. Each lesson
is ``lessons/chNN/<id>.md``: TOML front matter between ``+++`` lines (id,
chapter, section, order, title, summary, optional ``scenes``, ``examples``,
``derivations`` and ``linearised`` (systems built of parts whose eigenvalues the
page plots), each a list of ids; ``scene = "id"`` is accepted as a
one-scene shorthand) and a Markdown body with LaTeX math (``$...$`` inline,
``$$...$$`` display). Math is set aside before Markdown runs and rendered in
the browser by the vendored KaTeX. Whether the ids exist is checked by
:mod:`app.course.catalogue`.
"""

from __future__ import annotations

import html
import re
import tomllib
from dataclasses import dataclass
from functools import cached_property
from typing import Any

from markdown_it import MarkdownIt

from app.settings import DEFAULT_LESSONS_DIR as LESSONS_DIR  # the default the catalogue loads

__all__ = [
    "LESSONS_DIR",
    "Chapter",
    "Lesson",
    "Section",
    "parse_lesson",
    "parse_outline",
    "render_markdown",
    "split_front_matter",
]

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
    #: The file it was read from, named in every error about it.
    source: str = ""
    scenes: tuple[str, ...] = ()
    examples: tuple[str, ...] = ()
    derivations: tuple[str, ...] = ()
    #: Systems built of parts whose eigenvalues the page plots against their reference motion's sweep parameter.
    linearised: tuple[str, ...] = ()

    @property
    def scene(self) -> str | None:
        """The first scene, the one the lesson page shows (``None`` for a lesson without one)."""
        return self.scenes[0] if self.scenes else None

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
    lessons: tuple[Lesson, ...] = ()


def split_front_matter(text: str, source: str) -> tuple[dict[str, Any], str]:
    """The TOML front matter (between ``+++`` lines) and the stripped Markdown body of a content file."""
    parts = text.split("+++", 2)
    if len(parts) != 3 or parts[0].strip():
        raise ValueError(f"{source}: a content file starts with TOML front matter between '+++' lines")
    try:
        meta: dict[str, Any] = tomllib.loads(parts[1])
    except tomllib.TOMLDecodeError as exc:
        raise ValueError(f"{source}: front matter: {exc}") from None
    return meta, parts[2].strip()


def parse_lesson(text: str, source: str) -> Lesson:
    """Parse one lesson file; raises ValueError naming ``source`` on a malformed file."""
    meta, body = split_front_matter(text, source)
    required = ("id", "chapter", "section", "order", "title")
    missing = [k for k in required if k not in meta]
    if missing:
        raise ValueError(f"{source}: front matter lacks {', '.join(missing)}")
    if "scene" in meta:
        if "scenes" in meta:
            raise ValueError(f"{source}: front matter has both 'scene' and 'scenes'; keep 'scenes'")
        meta["scenes"] = [meta.pop("scene")]
    return Lesson(
        id=str(meta["id"]),
        chapter=int(meta["chapter"]),
        section=str(meta["section"]),
        order=int(meta["order"]),
        title=str(meta["title"]),
        summary=str(meta.get("summary", "")),
        body_markdown=body,
        source=source,
        scenes=_id_list(meta, "scenes", source),
        examples=_id_list(meta, "examples", source),
        derivations=_id_list(meta, "derivations", source),
        linearised=_id_list(meta, "linearised", source),
    )


def _id_list(meta: dict[str, Any], key: str, source: str) -> tuple[str, ...]:
    """``meta[key]`` as a tuple of ids; ValueError naming the file and key if it is not a list of strings."""
    value = meta.get(key, [])
    if not isinstance(value, list) or not all(isinstance(v, str) and v for v in value):
        raise ValueError(f"{source}: front matter {key!r} must be a list of ids (strings), got {value!r}")
    return tuple(value)


def parse_outline(text: str, source: str) -> tuple[Chapter, ...]:
    """The chapters and sections of ``course.toml`` (no lessons yet); ValueError naming ``source`` if malformed."""
    try:
        outline = tomllib.loads(text)
        return tuple(
            Chapter(
                number=int(ch["number"]),
                title=ch["title"],
                summary=ch.get("summary", ""),
                sections=tuple(Section(s["number"], s["title"], tuple(s.get("topics", ()))) for s in ch["sections"]),
            )
            for ch in outline["chapter"]
        )
    except (tomllib.TOMLDecodeError, KeyError, TypeError, ValueError) as exc:
        raise ValueError(f"{source}: malformed course outline: {exc!r}") from None
