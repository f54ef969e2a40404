"""An exercise's variants: the given numbers each variant draws, checked by the model before anyone sees them.

Variant ``v`` of an exercise draws its numbers from a generator seeded by the exercise's id and ``v`` (the same
numbers on every server, every time). A draw is kept only if the model accepts it: the answer function does not
refuse the numbers, every number and vector answer is finite and clear of zero by more than its tolerance can blur,
every expression answer can be evaluated, and every named mistake gives an answer the checker can tell from the right
one. Otherwise the next draw of the same variant is tried (:data:`DRAWS` at most).
"""

from __future__ import annotations

import hashlib
import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from app.practice.checking import distinct_answers
from app.practice.exercise import Exercise, PartAnswer

#: Draws tried for one variant before it is declared impossible (a test shows 100 variants of every exercise draw).
DRAWS = 64
#: Variants are 0 … 2³¹ − 1.
MAX_VARIANT = 2**31 - 1


class NoValidVariant(ValueError):
    """No draw of this variant gave numbers the model accepts (an exercise whose ranges need mending)."""


@dataclass(frozen=True)
class Variant:
    """One variant: its number, the given numbers (by name, in their units), and every part's answer."""

    exercise: Exercise
    variant: int
    given: Mapping[str, float]
    answers: Mapping[str, PartAnswer]

    def given_text(self) -> dict[str, str]:
        return {g.name: g.shown(self.given[g.name]) for g in self.exercise.given}


def _generator(exercise_id: str, variant: int, draw: int) -> np.random.Generator:
    digest = hashlib.sha256(f"{exercise_id}/{variant}/{draw}".encode()).digest()
    return np.random.default_rng(int.from_bytes(digest[:8], "little"))


def why_invalid(exercise: Exercise, answers: Mapping[str, PartAnswer]) -> str | None:
    """Why the model refuses these answers for a variant (None: it accepts them)."""
    for part in exercise.parts:
        answer = answers.get(part.id)
        if answer is None:
            return f"the answer function gives no answer for part {part.id!r}"
        value = answer.value
        if part.kind == "number":
            if not isinstance(value, float | int) or not math.isfinite(value):
                return f"part {part.id!r}: the answer is not a finite number"
            if part.absolute == 0.0 and value == 0.0:
                return f"part {part.id!r}: the answer is zero and the part has no absolute tolerance"
            if part.absolute > 0.0 and 0.0 < abs(value) < 3 * part.absolute:
                return f"part {part.id!r}: the answer is within its absolute tolerance's blur of zero"
        elif part.kind == "vector":
            vector = np.asarray(value, dtype=float)
            if vector.shape != (3,) or not np.all(np.isfinite(vector)):
                return f"part {part.id!r}: the answer is not a finite vector of three components"
            if part.absolute == 0.0 and not np.any(vector):
                return f"part {part.id!r}: the answer is the zero vector and the part has no absolute tolerance"
        elif part.kind == "choice" and value not in {c.id for c in part.choices}:
            return f"part {part.id!r}: the answer {value!r} is not one of its choices"
        for mistake in exercise.mistakes_of(part.id):
            if mistake.id not in answer.mistakes:
                return f"part {part.id!r}: mistake {mistake.id!r} has no computed answer"
            if not distinct_answers(part, answer.value, answer.mistakes[mistake.id]):
                return f"part {part.id!r}: mistake {mistake.id!r} gives an answer too close to the right one"
        wrong = [answer.mistakes[m.id] for m in exercise.mistakes_of(part.id)]
        for i, first in enumerate(wrong):
            for second in wrong[i + 1 :]:
                if not distinct_answers(part, first, second):
                    return f"part {part.id!r}: two named mistakes give the same answer"
    return None


def variant(exercise: Exercise, number: int) -> Variant:
    """Variant ``number`` of ``exercise`` (0 … :data:`MAX_VARIANT`); :class:`NoValidVariant` if no draw is valid."""
    if isinstance(number, bool) or not isinstance(number, int) or not 0 <= number <= MAX_VARIANT:
        raise ValueError(f"variant: an integer from 0 to {MAX_VARIANT}")
    last = "no draw"
    for draw in range(DRAWS):
        rng = _generator(exercise.id, number, draw)
        given = {g.name: g.value(int(rng.integers(0, g.values()))) for g in exercise.given}
        try:
            answers = exercise.answers(given)
        except ValueError as exc:
            last = str(exc)
            continue
        reason = why_invalid(exercise, answers)
        if reason is None:
            return Variant(exercise, number, given, answers)
        last = reason
    raise NoValidVariant(f"exercise {exercise.id!r} variant {number}: no valid draw in {DRAWS} ({last})")


def learner_variant(exercise_id: str, learner_id: str) -> int:
    """The variant a learner works on when none is asked for: theirs, the same every time they come back."""
    digest = hashlib.sha256(f"{learner_id}/{exercise_id}".encode()).digest()
    return int.from_bytes(digest[:4], "little") & MAX_VARIANT


def class_variant(exercise_id: str, class_seed: int) -> int:
    """The variant every student of a room works on when its instructor gives the class one set of numbers: the same
    for each exercise and seed, different between exercises."""
    digest = hashlib.sha256(f"class/{class_seed}/{exercise_id}".encode()).digest()
    return int.from_bytes(digest[:4], "little") & MAX_VARIANT


def room_student_variant(room_id: str, student_id: str, exercise_id: str) -> int:
    """The variant a student of a room works on when the class has no one set of numbers: theirs in that room, the same
    on every device they join from."""
    digest = hashlib.sha256(f"room/{room_id}/{student_id}/{exercise_id}".encode()).digest()
    return int.from_bytes(digest[:4], "little") & MAX_VARIANT
