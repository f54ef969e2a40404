"""The course outline, the lesson files and the Markdown + math renderer (app/course/lessons.py)."""

from __future__ import annotations

import re

import pytest

from app.course import LESSONS_DIR, load_catalogue, render_markdown
from app.course.lessons import parse_lesson
from app.physics.systems import worked_examples
from app.scenes import SCENES

COURSE = load_catalogue()
EXAMPLES = worked_examples()
LESSON_FILES = sorted(LESSONS_DIR.glob("ch*/*.md"))


def test_course_loads_ten_chapters_and_every_lesson_file():
    assert [ch.number for ch in COURSE.chapters] == list(range(1, 11))
    assert len(COURSE.lessons) == len(LESSON_FILES) > 0
    for ch in COURSE.chapters:
        for lesson in ch.lessons:
            assert lesson.chapter == ch.number
            assert lesson.section in {s.number for s in ch.sections}, (lesson.id, lesson.section)


def test_lessons_are_ordered_within_a_chapter():
    for ch in COURSE.chapters:
        orders = [lesson.order for lesson in ch.lessons]
        assert orders == sorted(orders)


@pytest.mark.parametrize("lesson", list(COURSE.lessons.values()), ids=lambda lesson: lesson.id)
def test_lesson_scenes_and_examples_exist(lesson):
    for scene_id in lesson.scenes:
        assert scene_id in SCENES
    for example_id in lesson.examples:
        assert example_id in EXAMPLES


@pytest.mark.parametrize("path", LESSON_FILES, ids=lambda p: p.name)
def test_lesson_files_have_no_placeholders(path):
    text = path.read_text(encoding="utf-8")
    for word in ("TODO", "lorem", "placeholder", "FIXME", "TBD"):
        assert not re.search(rf"\b{word}\b", text, flags=re.IGNORECASE), (path.name, word)
    lesson = parse_lesson(text, str(path))
    assert lesson.title and lesson.summary and lesson.body_markdown


def math_spans(rendered: str) -> list[tuple[str, str]]:
    return re.findall(r'<span class="math (math-inline|math-display)">(.*?)</span>', rendered, flags=re.DOTALL)


def test_inline_math_is_kept_verbatim_not_read_as_emphasis():
    # Two underscores in one paragraph would become <em> if Markdown saw the math.
    rendered = render_markdown("Take $a_b$ and $c_d$, then *stress*.")
    assert math_spans(rendered) == [("math-inline", "a_b"), ("math-inline", "c_d")]
    assert "<em>stress</em>" in rendered
    assert rendered.count("<em>") == 1


def test_display_math_is_kept_verbatim():
    rendered = render_markdown("Before\n\n$$x^2 + y_1*z_2*$$\n\nAfter")
    assert math_spans(rendered) == [("math-display", "x^2 + y_1*z_2*")]
    rendered = render_markdown("$$\n\\frac{d\\bar a}{dt} = \\lim_{\\Delta t\\to 0}\n$$")
    assert math_spans(rendered) == [("math-display", "\\frac{d\\bar a}{dt} = \\lim_{\\Delta t\\to 0}")]


def test_markup_is_escaped_inside_and_outside_math():
    rendered = render_markdown("If $a<b$ then a < b. <script>alert(1)</script>")
    assert math_spans(rendered) == [("math-inline", "a&lt;b")]
    assert "a &lt; b" in rendered
    assert "<script>" not in rendered and "&lt;script&gt;" in rendered


def test_escaped_dollar_is_not_math():
    rendered = render_markdown(r"It costs \$5 and \$6.")
    assert math_spans(rendered) == []


def test_lesson_html_keeps_every_math_span_of_the_source():
    # Every $...$ / $$...$$ in a lesson body comes out as exactly one span.math.
    for lesson in COURSE.lessons.values():
        body = lesson.body_markdown
        display = len(re.findall(r"\$\$(.+?)\$\$", body, flags=re.DOTALL))
        spans = math_spans(lesson.body_html)
        assert sum(1 for kind, _ in spans if kind == "math-display") == display, lesson.id
        assert "MATHSPAN" not in lesson.body_html, lesson.id
