"""The course catalogue: chapters, lessons and everything a lesson refers to, checked as one whole.

:func:`load_catalogue` reads ``lessons/course.toml`` and ``lessons/chNN/*.md``
and joins them with the registries a lesson may name: scenes
(``app.scenes.SCENES``), worked examples (``worked_examples()``) and
derivations (the analytical systems of chapters 7–9, ``analytical_systems()``) and the systems built of parts whose
eigenvalues a page plots (``multibody_catalogue()``). Every reference is
checked at load: an unknown scene, example, derivation or linearised system, a duplicated lesson
id, a chapter missing from ``course.toml`` or a section missing from its
chapter raises :class:`CatalogueError`, naming the lesson file and the bad
reference. ``create_app`` builds the catalogue, so a bad reference stops the
server from starting instead of vanishing from a page.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING

from app.course.lessons import LESSONS_DIR, Chapter, Lesson, parse_lesson, parse_outline
from app.physics.core.solution import WorkedExample
from app.physics.systems import analytical_systems, multibody_catalogue, worked_examples
from app.scenes import SCENES, Scene

if TYPE_CHECKING:
    from app.physics.mechanics.description import SystemDescription
    from app.physics.mechanics.multibody.parts import MultibodyFamily, MultibodySystem


class CatalogueError(ValueError):
    """A lesson refers to something that does not exist, or the outline and the lessons disagree."""


@dataclass(frozen=True)
class Catalogue:
    """The checked course: chapters (with their lessons) and the registries lessons refer to.

    ``lessons`` is in course order (chapter, then ``order``); ``scenes``,
    ``examples`` and ``derivations`` map id to the registered object.
    """

    chapters: tuple[Chapter, ...]
    lessons: Mapping[str, Lesson]
    scenes: Mapping[str, type[Scene]]
    examples: Mapping[str, WorkedExample]
    derivations: Mapping[str, SystemDescription]
    #: Systems built of parts (bodies, joints, rolling contacts) by id, or families of them.
    multibody: Mapping[str, MultibodySystem | MultibodyFamily] = field(default_factory=dict)

    def chapter_of(self, lesson: Lesson) -> Chapter:
        return next(ch for ch in self.chapters if ch.number == lesson.chapter)

    def neighbours(self, lesson: Lesson) -> tuple[Lesson | None, Lesson | None]:
        """The lessons before and after ``lesson`` in course order (``None`` at either end)."""
        ordered = list(self.lessons.values())
        i = ordered.index(lesson)
        return (ordered[i - 1] if i > 0 else None, ordered[i + 1] if i + 1 < len(ordered) else None)

    def scenes_of_chapter(self, number: int) -> list[type[Scene]]:
        """The registered scenes whose ``chapter`` is ``number``, in registry order."""
        return [cls for cls in self.scenes.values() if cls.chapter == number]

    def examples_of_chapter(self, number: int) -> list[WorkedExample]:
        """The worked examples whose ``chapter`` is ``number``, in registry order."""
        return [example for example in self.examples.values() if example.chapter == number]


def load_catalogue(
    root: Path = LESSONS_DIR,
    *,
    scenes: Mapping[str, type[Scene]] | None = None,
    examples: Mapping[str, WorkedExample] | None = None,
    derivations: Mapping[str, SystemDescription] | None = None,
    multibody: Mapping[str, MultibodySystem | MultibodyFamily] | None = None,
) -> Catalogue:
    """Read the outline and lesson files under ``root`` and check every reference.

    ``scenes``, ``examples`` and ``derivations`` default to the application's
    registries. Raises :class:`CatalogueError` listing every problem found, each
    naming the lesson file and the bad reference.
    """
    scenes = SCENES if scenes is None else scenes
    examples = worked_examples() if examples is None else examples
    derivations = analytical_systems() if derivations is None else derivations
    multibody = multibody_catalogue() if multibody is None else multibody
    linearisable = {
        key: entry
        for key, entry in multibody.items()
        if entry.member(entry.parameters.defaults()).reference is not None
    }
    outline_path = root / "course.toml"
    outline = parse_outline(outline_path.read_text(encoding="utf-8"), str(outline_path))
    lessons = sorted(
        (parse_lesson(p.read_text(encoding="utf-8"), str(p)) for p in sorted(root.glob("ch*/*.md"))),
        key=lambda lesson: (lesson.chapter, lesson.order),
    )
    problems: list[str] = []
    by_id: dict[str, Lesson] = {}
    for lesson in lessons:
        if lesson.id in by_id:
            problems.append(f"{lesson.source}: lesson id {lesson.id!r} is already used by {by_id[lesson.id].source}")
            continue
        by_id[lesson.id] = lesson
        problems += _reference_problems(
            lesson,
            outline,
            {
                "scene": scenes,
                "worked example": examples,
                "derivation": derivations,
                "linearised system": linearisable,
            },
        )
    if problems:
        raise CatalogueError("the course catalogue is inconsistent:\n  " + "\n  ".join(problems))
    chapters = tuple(
        replace(ch, lessons=tuple(lesson for lesson in lessons if lesson.chapter == ch.number)) for ch in outline
    )
    return Catalogue(
        chapters=chapters,
        lessons=by_id,
        scenes=dict(scenes),
        examples=dict(examples),
        derivations=dict(derivations),
        multibody=dict(multibody),
    )


def _reference_problems(
    lesson: Lesson, outline: tuple[Chapter, ...], registries: Mapping[str, Mapping[str, object]]
) -> list[str]:
    """What is wrong with one lesson's chapter, section and references (empty if nothing)."""
    problems: list[str] = []
    chapter = next((ch for ch in outline if ch.number == lesson.chapter), None)
    if chapter is None:
        problems.append(
            f"{lesson.source}: chapter {lesson.chapter} is not in course.toml (known: "
            f"{', '.join(str(ch.number) for ch in outline)})"
        )
    elif lesson.section not in {s.number for s in chapter.sections}:
        known = ", ".join(s.number for s in chapter.sections)
        problems.append(
            f"{lesson.source}: section {lesson.section!r} is not a section of chapter {chapter.number} (known: {known})"
        )
    references = {
        "scene": lesson.scenes,
        "worked example": lesson.examples,
        "derivation": lesson.derivations,
        "linearised system": lesson.linearised,
    }
    for kind, ids in references.items():
        registry = registries[kind]
        for ref in ids:
            if ref not in registry:
                known = ", ".join(registry) or "none registered"
                problems.append(f"{lesson.source}: unknown {kind} {ref!r} (known: {known})")
        repeated = sorted({ref for ref in ids if ids.count(ref) > 1})
        if repeated:
            problems.append(f"{lesson.source}: {kind} listed more than once: {', '.join(repeated)}")
    return problems
