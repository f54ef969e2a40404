"""An exercise: what is given (each number drawn from a stated range), the parts a student answers, the named mistakes,
and the function that computes every part's answer, and every mistake's wrong answer, from the given numbers.

An exercise is a Markdown file beside the lessons, ``lessons/chNN/exercises/<id>.md``: TOML front matter between
``+++`` lines, then the statement, in which ``{{name}}`` stands for a given number with its unit. The front matter
names its answer function as ``answers = "chNN.function"`` (a function of :mod:`app.practice.answers`); no answer is
ever typed by hand. A part's answer is a number with a unit, a vector in a named frame, a symbolic expression in
listed symbols, or one of a few choices.
"""

from __future__ import annotations

import importlib
import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal, TypeAlias

import sympy

from app.course.lessons import split_front_matter

AnswerKind = Literal["number", "vector", "expression", "choice"]
ANSWER_KINDS: tuple[str, ...] = ("number", "vector", "expression", "choice")
#: The relative tolerance of a number, a vector or an expression unless the exercise says otherwise.
DEFAULT_TOLERANCE = 0.01
#: An exercise's, a part's, a mistake's id: short, lower case, digits and '-' (they appear in URLs and the database).
ID_PATTERN = re.compile(r"^[a-z0-9][a-z0-9-]{0,31}$")
#: ``answers = "chNN.function"``: a function of a module of app.practice.answers, and nothing else.
ANSWERS_PATTERN = re.compile(r"^(ch\d\d)\.([a-z_][a-z0-9_]*)$")
#: ``{{name}}`` in a statement or a prompt: a given number with its unit.
PLACEHOLDER = re.compile(r"\{\{\s*([a-z_][a-z0-9_]*)\s*\}\}")


@dataclass(frozen=True)
class Given:
    """A number the statement gives: drawn from ``low``…``high`` (in ``unit``) on a grid of ``step``."""

    name: str
    unit: str
    low: float
    high: float
    step: float
    label: str = ""

    def values(self) -> int:
        """How many values the grid holds."""
        return int(math.floor((self.high - self.low) / self.step + 1e-9)) + 1

    def value(self, index: int) -> float:
        """The grid's ``index``-th value, rounded to the step's decimals (so that what is shown is what is used)."""
        return round(self.low + index * self.step, self.decimals)

    @property
    def decimals(self) -> int:
        text = f"{self.step:.10f}".rstrip("0")
        return len(text.split(".")[1]) if "." in text else 0

    def shown(self, value: float) -> str:
        """``value`` as the statement shows it: the step's decimals and the unit (``2.4 kg``)."""
        number = f"{value:.{self.decimals}f}"
        if self.unit == "deg":
            return f"{number}°"
        return f"{number} {shown_unit(self.unit)}" if self.unit not in ("", "1") else number


@dataclass(frozen=True)
class ExpressionSymbol:
    """A symbol a student may use in an expression part: its name as typed, what it is, and the range its sampled
    values come from when two expressions are compared."""

    name: str
    meaning: str
    low: float
    high: float


@dataclass(frozen=True)
class Choice:
    id: str
    text: str


@dataclass(frozen=True)
class Part:
    """One thing asked. ``unit`` is the unit the answer is computed in (a number's or a vector's; a student may use
    any unit of the same dimension); ``frame`` the frame a vector's components are in; ``tolerance`` relative and
    ``absolute`` (in ``unit``) for an answer that may be zero; an expression ``up_to_constant`` (a potential energy)
    may differ from the model's by a constant."""

    id: str
    prompt: str
    kind: AnswerKind
    unit: str = ""
    frame: str = ""
    tolerance: float = DEFAULT_TOLERANCE
    absolute: float = 0.0
    symbols: tuple[ExpressionSymbol, ...] = ()
    up_to_constant: bool = False
    choices: tuple[Choice, ...] = ()
    hints: tuple[str, ...] = ()

    def public(self, given_text: Mapping[str, str]) -> dict[str, Any]:
        return {
            "id": self.id,
            "prompt": fill(self.prompt, given_text),
            "answer_kind": self.kind,
            "unit": self.unit or None,
            "frame": self.frame or None,
            "choices": [{"id": c.id, "text": c.text} for c in self.choices] or None,
            "symbols": [{"name": s.name, "meaning": s.meaning} for s in self.symbols] or None,
            "up_to_constant": self.up_to_constant,
            "tolerance": self.tolerance,
            "hints": [fill(h, given_text) for h in self.hints],
        }


@dataclass(frozen=True)
class Mistake:
    """A common mistake, named: the part it is made in and what the feedback says when an answer matches it."""

    id: str
    part: str
    text: str


#: A part's answer: a number (in the part's unit), a vector's components (in its unit and frame), a sympy expression
#: in the part's symbols, or a choice's id.
AnswerValue: TypeAlias = float | tuple[float, ...] | sympy.Expr | str


@dataclass(frozen=True)
class PartAnswer:
    """What a part's answer is, how it is reached (``working``: LaTeX, with this variant's numbers), and the answer
    each named mistake of the part gives instead."""

    value: AnswerValue
    working: str
    mistakes: Mapping[str, AnswerValue] = field(default_factory=dict)


#: An answer function: the given numbers (by name, in their units) to every part's answer (by part id). It raises
#: ValueError when the numbers cannot happen together (the variant is then drawn again).
AnswerFunction = Callable[[Mapping[str, float]], Mapping[str, PartAnswer]]


@dataclass(frozen=True)
class SceneLink:
    """The scene that shows the exercise's system ("See it"): its id and its parameters, each a value or
    ``"{{name}}"``, a given number."""

    scene_id: str
    params: Mapping[str, Any]

    def at(self, given: Mapping[str, float]) -> dict[str, Any]:
        return {"scene_id": self.scene_id, "params": {name: _filled(v, given) for name, v in self.params.items()}}


def given_named(value: Any) -> str | None:
    """The given number a scene parameter's value names (``"{{mass_kg}}"``), or None for a plain value."""
    match = PLACEHOLDER.fullmatch(value) if isinstance(value, str) else None
    return match.group(1) if match else None


def _filled(value: Any, given: Mapping[str, float]) -> Any:
    name = given_named(value)
    return given[name] if name is not None else value


@dataclass(frozen=True)
class Exercise:
    id: str
    title: str
    chapter: int
    section: str
    statement: str
    given: tuple[Given, ...]
    parts: tuple[Part, ...]
    mistakes: tuple[Mistake, ...]
    answers_name: str
    answers: AnswerFunction
    scene: SceneLink | None = None
    source: str = ""

    def part(self, part_id: str) -> Part | None:
        return next((p for p in self.parts if p.id == part_id), None)

    def mistakes_of(self, part_id: str) -> tuple[Mistake, ...]:
        return tuple(m for m in self.mistakes if m.part == part_id)

    def summary(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "title": self.title,
            "chapter": self.chapter,
            "section": self.section,
            "parts": len(self.parts),
        }


def shown_unit(unit: str) -> str:
    """A unit as the page shows it: ``kg*m^2/s`` as ``kg·m²/s``."""
    return unit.replace("*", "·").replace("^2", "²").replace("^3", "³")


def fill(text: str, given_text: Mapping[str, str]) -> str:
    """``text`` with each ``{{name}}`` replaced by the given number as shown (a name not given is left as it is)."""
    return PLACEHOLDER.sub(lambda m: given_text.get(m.group(1), m.group(0)), text)


def _id(value: Any, what: str, source: str) -> str:
    if not isinstance(value, str) or not ID_PATTERN.match(value):
        raise ValueError(f"{source}: {what} must be 1–32 lower-case letters, digits or '-', got {value!r}")
    return value


def _number(table: Mapping[str, Any], key: str, source: str, default: float | None = None) -> float:
    value = table.get(key, default)
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ValueError(f"{source}: {key!r} must be a finite number, got {value!r}")
    return float(value)


def _answer_function(name: Any, source: str) -> AnswerFunction:
    match = ANSWERS_PATTERN.match(name) if isinstance(name, str) else None
    if match is None:
        raise ValueError(f"{source}: answers must name a function as 'chNN.function', got {name!r}")
    module = importlib.import_module(f"app.practice.answers.{match.group(1)}")
    function = getattr(module, match.group(2), None)
    if not callable(function):
        raise ValueError(f"{source}: app.practice.answers.{match.group(1)} has no function {match.group(2)!r}")
    return function


def _given(name: str, table: Mapping[str, Any], source: str) -> Given:
    where = f"{source}: given {name!r}"
    if not re.fullmatch(r"[a-z_][a-z0-9_]*", name):
        raise ValueError(f"{where}: a given's name is lower-case letters, digits and '_' (it fills {{{{name}}}} slots)")
    given = Given(
        name=name,
        unit=str(table.get("unit", "")),
        low=_number(table, "min", where),
        high=_number(table, "max", where),
        step=_number(table, "step", where),
        label=str(table.get("label", "")),
    )
    if not (given.step > 0 and given.low <= given.high):
        raise ValueError(f"{where}: needs min ≤ max and step > 0")
    return given


def _part(table: Mapping[str, Any], source: str) -> Part:
    part_id = _id(table.get("id"), "a part's id", source)
    where = f"{source}: part {part_id!r}"
    kind = table.get("kind")
    if kind not in ANSWER_KINDS:
        raise ValueError(f"{where}: kind must be one of {', '.join(ANSWER_KINDS)}, got {kind!r}")
    symbols = tuple(
        ExpressionSymbol(
            name=str(s["name"]),
            meaning=str(s.get("meaning", "")),
            low=_number(s, "min", where),
            high=_number(s, "max", where),
        )
        for s in table.get("symbols", [])
    )
    choices = tuple(Choice(_id(c.get("id"), "a choice's id", where), str(c["text"])) for c in table.get("choices", []))
    part = Part(
        id=part_id,
        prompt=str(table.get("prompt", "")),
        kind=kind,
        unit=str(table.get("unit", "")),
        frame=str(table.get("frame", "")),
        tolerance=_number(table, "tolerance", where, DEFAULT_TOLERANCE),
        absolute=_number(table, "absolute", where, 0.0),
        symbols=symbols,
        up_to_constant=bool(table.get("up_to_constant", False)),
        choices=choices,
        hints=tuple(str(h) for h in table.get("hints", [])),
    )
    if not part.prompt:
        raise ValueError(f"{where}: has no prompt")
    if kind in ("number", "vector") and not part.unit:
        raise ValueError(f"{where}: a {kind} needs a unit ('1' for a pure number)")
    if kind == "vector" and not part.frame:
        raise ValueError(f"{where}: a vector needs the frame its components are in")
    if kind == "expression" and not symbols:
        raise ValueError(f"{where}: an expression needs the symbols a student may use")
    if kind == "choice" and len(choices) < 2:
        raise ValueError(f"{where}: a choice needs at least two choices")
    if not 0 < part.tolerance < 0.5 or part.absolute < 0:
        raise ValueError(f"{where}: tolerance must be in (0, 0.5) and absolute ≥ 0")
    return part


def parse_exercise(text: str, source: str, *, chapter: int) -> Exercise:
    """One exercise file; ValueError naming ``source`` and what is wrong."""
    meta, body = split_front_matter(text, source)
    exercise_id = _id(meta.get("id"), "id", source)
    given = tuple(_given(name, table, source) for name, table in meta.get("given", {}).items())
    parts = tuple(_part(table, source) for table in meta.get("parts", []))
    if not parts:
        raise ValueError(f"{source}: an exercise has at least one part")
    part_ids = [p.id for p in parts]
    if len(set(part_ids)) != len(part_ids):
        raise ValueError(f"{source}: two parts share an id")
    mistakes = tuple(
        Mistake(_id(m.get("id"), "a mistake's id", source), str(m.get("part", "")), str(m.get("text", "")))
        for m in meta.get("mistakes", [])
    )
    if len({(m.part, m.id) for m in mistakes}) != len(mistakes):
        raise ValueError(f"{source}: two mistakes of one part share an id")
    for mistake in mistakes:
        if mistake.part not in part_ids or not mistake.text:
            raise ValueError(f"{source}: mistake {mistake.id!r} names no part of this exercise or has no text")
    scene = meta.get("scene")
    link = None
    if scene is not None:
        params = dict(scene.get("params", {}))
        for name, value in params.items():
            if given_named(value) not in (None, *(g.name for g in given)):
                raise ValueError(f"{source}: scene parameter {name!r} names no given number ({value!r})")
        link = SceneLink(scene_id=str(scene["scene_id"]), params=params)
    section = str(meta.get("section", ""))
    if not section.startswith(f"{chapter}."):
        raise ValueError(f"{source}: section {section!r} is not a section of chapter {chapter}")
    exercise = Exercise(
        id=exercise_id,
        title=str(meta.get("title", "")),
        chapter=chapter,
        section=section,
        statement=body,
        given=given,
        parts=parts,
        mistakes=mistakes,
        answers_name=str(meta.get("answers")),
        answers=_answer_function(meta.get("answers"), source),
        scene=link,
        source=source,
    )
    if not exercise.title:
        raise ValueError(f"{source}: an exercise needs a title")
    texts = [body, *(p.prompt for p in parts), *(h for p in parts for h in p.hints), *(m.text for m in mistakes)]
    named = {match.group(1) for text in texts for match in PLACEHOLDER.finditer(text)}
    unknown = named - {g.name for g in given}
    if unknown:
        raise ValueError(f"{source}: {{{{…}}}} names no given number: {', '.join(sorted(unknown))}")
    if re.search(r"\{\{(?!\s*[a-z_][a-z0-9_]*\s*\}\})", "".join(texts)):
        raise ValueError(f"{source}: a {{{{…}}}} slot must hold a given's lower-case name")
    return exercise


def load_exercises(root: Path) -> dict[str, Exercise]:
    """Every ``lessons/chNN/exercises/*.md`` under ``root``, by id, in chapter, section and file order."""
    exercises: dict[str, Exercise] = {}
    for path in sorted(root.glob("ch*/exercises/*.md")):
        chapter = int(path.parent.parent.name.removeprefix("ch"))
        exercise = parse_exercise(path.read_text(encoding="utf-8"), str(path), chapter=chapter)
        if exercise.id in exercises:
            raise ValueError(f"{path}: exercise id {exercise.id!r} is also {exercises[exercise.id].source}")
        exercises[exercise.id] = exercise
    return dict(sorted(exercises.items(), key=lambda kv: (_section_key(kv[1].section), list(exercises).index(kv[0]))))


def _section_key(section: str) -> tuple[int, ...]:
    return tuple(int(n) for n in section.split(".") if n.isdigit())
