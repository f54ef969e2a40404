"""Ready questions: predictions an instructor can ask before a demo, shipped in ``lessons/polls.toml``.

Each question names its scene, optionally a preset and parameters to set before
asking, and the readout quantity whose value (or word) the scene computes as the
answer. :func:`load_ready_questions` checks every question against the scenes
when the server starts, so a renamed scene, preset or parameter stops it there
rather than in front of a class.
"""

from __future__ import annotations

import re
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from app.classroom.polls import Poll, PollError
from app.physics.core.parameters import ParameterError
from app.scenes.kit import Scene
from app.settings import DEFAULT_LESSONS_DIR

#: The ready questions the server loads.
DEFAULT_READY_QUESTIONS = DEFAULT_LESSONS_DIR / "polls.toml"
QUESTION_ID = re.compile(r"^[a-z0-9]+(?:-[a-z0-9]+)*$")
REQUIRED_KEYS = ("id", "chapter", "scene", "question", "kind", "answer_quantity")
OPTIONAL_KEYS = ("choices", "unit", "params", "preset", "answer_choices")
#: The keys of an entry that make up its poll (checked by Poll.create, which refuses what does not fit the kind).
POLL_KEYS = ("question", "kind", "choices", "unit", "answer_quantity", "answer_choices")


@dataclass(frozen=True)
class ReadyQuestion:
    """One ready question: what to ask, on which scene set up how, and which readout quantity answers it.

    Before asking, the scene takes its defaults, then ``preset``'s values (if any), then ``params``;
    ``answer_choices`` maps the quantity's word values to choice indices (choice questions).
    """

    id: str
    chapter: int
    scene_id: str
    question: str
    kind: str
    choices: tuple[str, ...]
    unit: str
    params: dict[str, Any] = field(default_factory=dict)
    preset: str | None = None
    answer_quantity: str = ""
    answer_choices: dict[str, int] = field(default_factory=dict)

    def poll_body(self) -> dict[str, Any]:
        """The raw body :meth:`Poll.create` takes for this question."""
        body: dict[str, Any] = {"question": self.question, "kind": self.kind, "answer_quantity": self.answer_quantity}
        if self.kind == "choice":
            body |= {"choices": list(self.choices), "answer_choices": dict(self.answer_choices)}
        else:
            body["unit"] = self.unit
        return body

    def scene_params(self, scene: type[Scene]) -> dict[str, Any]:
        """The scene's parameters when the question is asked: defaults, then the preset, then ``params`` (validated)."""
        values: dict[str, Any] = {}
        if self.preset is not None:
            values.update(next(p for p in scene.presets if p.name == self.preset).values)
        values.update(self.params)
        return scene.parameters.validate(values)

    def schema(self) -> dict[str, Any]:
        """The question as the API lists it (GET /api/rooms/{room_id}/polls/ready)."""
        return {
            "id": self.id,
            "chapter": self.chapter,
            "scene_id": self.scene_id,
            "question": self.question,
            "kind": self.kind,
            "choices": list(self.choices),
            "unit": self.unit,
            "preset": self.preset,
            "params": dict(self.params),
            "answer_quantity": self.answer_quantity,
        }


def load_ready_questions(path: Path, scenes: Mapping[str, type[Scene]]) -> tuple[ReadyQuestion, ...]:
    """Every ``[[question]]`` of the TOML file at ``path``, checked against ``scenes`` (scene id -> class).

    Raises ``ValueError`` naming the file and the question id for a malformed
    entry, an unknown scene, a chapter that is not the scene's, an unknown
    preset, parameters the scene refuses, a scene without a readout, a poll
    body :meth:`Poll.create` refuses, or a repeated id.
    """
    try:
        document = tomllib.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, tomllib.TOMLDecodeError) as exc:
        raise ValueError(f"{path}: cannot read the ready questions: {exc}") from None
    extra = sorted(set(document) - {"question"})
    if extra:
        raise ValueError(f"{path}: unknown top-level key {extra[0]!r}; the file holds [[question]] tables only")
    entries = document.get("question", [])
    if not isinstance(entries, list):
        raise ValueError(f"{path}: 'question' must be an array of tables ([[question]])")
    questions: list[ReadyQuestion] = []
    seen: set[str] = set()
    for number, entry in enumerate(entries, start=1):
        question = _ready_question(entry, scenes, path=path, number=number)
        if question.id in seen:
            raise ValueError(f"{path}: question {question.id!r}: the id is used twice")
        seen.add(question.id)
        questions.append(question)
    return tuple(questions)


def _ready_question(entry: Any, scenes: Mapping[str, type[Scene]], *, path: Path, number: int) -> ReadyQuestion:
    """The ``number``-th entry of the file, checked; ValueError naming the file and the question's id."""
    if not isinstance(entry, Mapping):
        raise ValueError(f"{path}: question {number} must be a table")
    question_id = entry.get("id")
    if not isinstance(question_id, str) or not QUESTION_ID.match(question_id):
        raise ValueError(
            f"{path}: question {number}: id must be lower-case words joined by hyphens (got {question_id!r})"
        )
    where = f"{path}: question {question_id!r}"
    missing = [key for key in REQUIRED_KEYS if key not in entry]
    if missing:
        raise ValueError(f"{where}: missing {', '.join(missing)}")
    unknown = sorted(set(entry) - set(REQUIRED_KEYS) - set(OPTIONAL_KEYS))
    if unknown:
        raise ValueError(f"{where}: unknown key {unknown[0]!r} (keys: {', '.join(REQUIRED_KEYS + OPTIONAL_KEYS)})")
    if entry["kind"] == "number" and "unit" not in entry:
        raise ValueError(f'{where}: a number question states its unit (unit = "" for a pure number)')
    try:
        poll = Poll.create({key: entry[key] for key in POLL_KEYS if key in entry}, poll_id=question_id)
    except PollError as exc:
        raise ValueError(f"{where}: {exc}") from None
    assert poll.answer_source is not None  # answer_quantity is required above

    scene_id = entry["scene"]
    scene = scenes.get(scene_id) if isinstance(scene_id, str) else None
    if scene is None:
        raise ValueError(f"{where}: unknown scene {scene_id!r}")
    chapter = entry["chapter"]
    if isinstance(chapter, bool) or chapter != scene.chapter:
        raise ValueError(f"{where}: chapter {chapter!r} is not the chapter of scene {scene_id!r} ({scene.chapter})")
    if scene.readout is Scene.readout:
        raise ValueError(f"{where}: scene {scene_id!r} has no readout, so it cannot compute an answer")
    preset = entry.get("preset")
    if preset is not None and preset not in {p.name for p in scene.presets}:
        names = ", ".join(p.name for p in scene.presets) or "none"
        raise ValueError(f"{where}: scene {scene_id!r} has no preset {preset!r} (its presets: {names})")
    params = entry.get("params", {})
    if not isinstance(params, Mapping):
        raise ValueError(f"{where}: params must be a table of parameter names and values")

    question = ReadyQuestion(
        id=question_id,
        chapter=int(chapter),
        scene_id=scene_id,
        question=poll.question,
        kind=poll.kind,
        choices=poll.choices,
        unit=poll.unit,
        params=dict(params),
        preset=preset,
        answer_quantity=poll.answer_source.quantity,
        answer_choices=dict(poll.answer_source.choice_for),
    )
    try:
        question.scene_params(scene)
    except ParameterError as exc:  # the file's author wrote the parameter's name: say it, and what the page calls it
        called = f" ({exc.label})" if exc.label else ""
        raise ValueError(
            f"{where}: the scene refuses its params: {' → '.join(map(str, exc.path))}{called}: {exc.message}"
        ) from None
    except ValueError as exc:
        raise ValueError(f"{where}: the scene refuses its params: {exc}") from None
    return question
