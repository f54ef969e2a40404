"""The exercise book: every exercise by id and by section, checked against the course, and their variants (drawn once,
then remembered: the same numbers on every request).

Loaded when the server starts (:func:`load_book`): an exercise whose section is not in the course outline, whose
scene is not a scene, whose scene parameters that scene refuses at its first variant, or whose first variant cannot be
drawn stops the server with a message naming the file, as a bad lesson reference does.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from app.course.lessons import Chapter
from app.practice.exercise import Exercise, load_exercises
from app.practice.variants import Variant, variant

#: Variants remembered (each a few kB: its numbers and its answers' expressions).
REMEMBERED_VARIANTS = 4096


class ExerciseBook:
    """The exercises, by id in course order."""

    def __init__(self, exercises: Mapping[str, Exercise]) -> None:
        self.exercises = dict(exercises)
        self._variants: OrderedDict[tuple[str, int], Variant] = OrderedDict()
        self._lock = threading.Lock()

    def __len__(self) -> int:
        return len(self.exercises)

    def get(self, exercise_id: str) -> Exercise | None:
        return self.exercises.get(exercise_id)

    def of_section(self, section: str | None) -> list[Exercise]:
        """The exercises of ``section`` (``"5.2"``), or all of them (None), in course order."""
        return [e for e in self.exercises.values() if section is None or e.section == section]

    def variant(self, exercise: Exercise, number: int) -> Variant:
        """Variant ``number`` of ``exercise`` (ValueError for a number out of range, NoValidVariant if none draws)."""
        key = (exercise.id, number)
        with self._lock:
            if key in self._variants:
                self._variants.move_to_end(key)
                return self._variants[key]
        drawn = variant(exercise, number)
        with self._lock:
            self._variants[key] = drawn
            while len(self._variants) > REMEMBERED_VARIANTS:
                self._variants.popitem(last=False)
        return drawn


def book_problems(book: ExerciseBook, chapters: tuple[Chapter, ...], scenes: Mapping[str, Any]) -> list[str]:
    """What is wrong between the exercises and the course: unknown sections and scenes, scene parameters the scene
    refuses (at variant 0)."""
    sections = {section.number for chapter in chapters for section in chapter.sections}
    problems = []
    for exercise in book.exercises.values():
        if exercise.section not in sections:
            problems.append(f"{exercise.source}: section {exercise.section!r} is not in the course outline")
        if exercise.scene is None:
            continue
        scene = scenes.get(exercise.scene.scene_id)
        if scene is None:
            problems.append(f"{exercise.source}: scene {exercise.scene.scene_id!r} is not a scene")
            continue
        try:
            scene.parameters.validate(exercise.scene.at(book.variant(exercise, 0).given)["params"])
        except ValueError as exc:
            problems.append(f"{exercise.source}: the scene refuses the exercise's parameters: {exc}")
    return problems


def load_book(root: Path, *, chapters: tuple[Chapter, ...], scenes: Mapping[str, Any]) -> ExerciseBook:
    """The exercises under ``root`` (``chNN/exercises/*.md``), checked against the course; ValueError listing every
    problem."""
    book = ExerciseBook(load_exercises(root))
    problems = book_problems(book, chapters, scenes)
    if problems:
        raise ValueError("the exercises do not fit the course:\n  " + "\n  ".join(problems))
    return book
