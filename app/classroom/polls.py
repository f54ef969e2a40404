"""Polls: predict, then observe.

The instructor asks a question before running a demo — multiple choice, or a
number in a unit — and each student answers on their own device (one answer
each, replaced until the poll closes). The instructor watches a histogram
(anonymous unless names are turned on), runs the demo, and reveals the answer:
computed by the scene from a quantity of its readout, or given by the
instructor. The answers export as CSV.

Pure Python: a :class:`Poll` is plain data the room keeps; nothing here knows
HTTP, sockets or viser. Bad input raises :class:`PollError` naming the field.
"""

from __future__ import annotations

import csv
import io
import math
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from datetime import UTC, datetime
from typing import Any

KINDS = ("choice", "number")
MAX_QUESTION_CHARS = 300
MAX_CHOICE_CHARS = 80
CHOICES_RANGE = (2, 8)
MAX_UNIT_CHARS = 20
#: Largest magnitude a number answer may have (in the poll's unit).
MAX_ANSWER_MAGNITUDE = 1e12
#: About this many bins in a number poll's histogram.
TARGET_BINS = 8
#: Answers closer together than this, relative to their size, count as all equal (one bin).
EQUAL_RTOL = 1e-9
#: ... or closer than this absolutely (bins finer than this are below what a float's exponent can count).
EQUAL_ATOL = 1e-300
#: Bin edges finer than this many decimals are written with an exponent instead.
MAX_EDGE_DECIMALS = 6
QUANTITY_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]{0,99}$")
CREATE_FIELDS = (
    "question",
    "kind",
    "choices",
    "unit",
    "answer_quantity",
    "answer_choices",
    "answer_value",
    "answer_choice",
    "show_names",
)
CSV_HEADER = ("poll_id", "question", "student", "answer", "unit", "answered_at_utc")
#: What a spreadsheet reads as the start of a formula (OWASP, "CSV Injection"): =, +, -, @, tab, carriage return.
FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")


class PollError(ValueError):
    """A bad poll or answer: ``field`` names the offending field, ``str()`` is the message."""

    def __init__(self, field: str, message: str) -> None:
        self.field = field
        super().__init__(message)


class PollClosedError(PollError):
    """An answer to a closed poll."""


@dataclass(frozen=True)
class AnswerSource:
    """How the scene computes the answer at reveal time.

    ``quantity`` is a readout quantity name of the scene (``Quantity.name``);
    for a multiple-choice poll ``choice_for`` maps the quantity's word value
    (``Quantity.word``) to the index of the right choice; empty for number polls.
    """

    quantity: str
    choice_for: Mapping[str, int] = field(default_factory=dict)


@dataclass
class _Answer:
    """One student's answer: a choice index or a number in the poll's unit."""

    number: int  # 1 for the first student to answer, 2 for the next, …
    name: str
    choice: int | None
    value: float | None
    answered_at: datetime


def format_number(value: float) -> str:
    """``value`` to about three significant digits, without an exponent between 0.001 and 10⁶; whole numbers as such."""
    magnitude = abs(value)
    if value == round(value) and magnitude < 1e6:
        return str(int(value))
    if 1e-3 <= magnitude < 1e6:
        decimals = max(0, 2 - math.floor(math.log10(magnitude)))
        return f"{value:.{decimals}f}"
    return f"{value:.3g}"


def nice_width(span: float, *, bins: int = TARGET_BINS) -> float:
    """The smallest width of the form 1, 2 or 5 × 10^k that covers ``span`` (> 0) in at most ``bins`` bins."""
    raw = span / bins
    power = 10.0 ** math.floor(math.log10(raw))
    for step in (1.0, 2.0, 5.0, 10.0):
        if step * power >= raw * (1.0 - 1e-12):
            return step * power
    return 10.0 * power


def spreadsheet_text(text: str) -> str:
    """A text cell of a CSV file that a spreadsheet shows as the text it is, never runs as a formula.

    OWASP's rule for CSV injection: a cell starting with ``=``, ``+``, ``-``, ``@``, tab or carriage return gets a
    leading single quote, which spreadsheets read as "this cell is text" (and do not show). Every cell a person typed
    (a name, a question, a choice, a unit) goes through here; numbers the server writes itself do not (see
    :meth:`Poll.to_csv`).
    """
    return f"'{text}" if text.startswith(FORMULA_STARTS) else text


def _finite_number(raw: Any, field_name: str) -> float:
    if isinstance(raw, bool) or not isinstance(raw, (int, float)):
        raise PollError(field_name, f"{field_name}: must be a number (got {raw!r})")
    value = float(raw)
    if not math.isfinite(value) or abs(value) > MAX_ANSWER_MAGNITUDE:
        raise PollError(
            field_name,
            f"{field_name}: must be a finite number no larger than {MAX_ANSWER_MAGNITUDE:g} in size (got {raw!r})",
        )
    return value


def _text(raw: Any, field_name: str, *, low: int, high: int) -> str:
    if not isinstance(raw, str):
        raise PollError(field_name, f"{field_name}: must be text (got {type(raw).__name__})")
    text = raw.strip()
    if not low <= len(text) <= high:
        raise PollError(field_name, f"{field_name}: must be {low} to {high} characters (got {len(text)})")
    return text


def _choice_index(raw: Any, field_name: str, choices: tuple[str, ...]) -> int:
    if isinstance(raw, bool) or not isinstance(raw, int) or not 0 <= raw < len(choices):
        raise PollError(
            field_name, f"{field_name}: must be the index of a choice, 0 to {len(choices) - 1} (got {raw!r})"
        )
    return raw


@dataclass(eq=False, kw_only=True)
class Poll:
    """One question to a room and the students' answers to it.

    Build one with :meth:`create`; the room keeps it. ``open`` polls take answers;
    :meth:`reveal` closes the poll and shows the answer.
    """

    poll_id: str
    question: str
    kind: str
    choices: tuple[str, ...]
    unit: str
    answer_source: AnswerSource | None
    answer_value: float | None
    answer_choice: int | None
    show_names: bool
    open: bool = True
    revealed: dict[str, Any] | None = None
    #: By the student's public id (never their token).
    _answers: dict[str, _Answer] = field(default_factory=dict, repr=False)
    _answered_ever: int = 0

    @classmethod
    def create(cls, raw: Mapping[str, Any], *, poll_id: str) -> Poll:
        """A new open poll from a request body; :class:`PollError` names the first bad field."""
        if not isinstance(raw, Mapping):
            raise PollError("body", "a poll must be an object with question and kind")
        unknown = sorted(set(raw) - set(CREATE_FIELDS))
        if unknown:
            raise PollError(unknown[0], f"{unknown[0]}: unknown field; expected some of: {', '.join(CREATE_FIELDS)}")
        if "question" not in raw:
            raise PollError("question", "question: required")
        question = _text(raw["question"], "question", low=1, high=MAX_QUESTION_CHARS)
        kind = raw.get("kind")
        if kind not in KINDS:
            raise PollError("kind", f"kind: must be 'choice' or 'number' (got {kind!r})")
        show_names = raw.get("show_names", False)
        if not isinstance(show_names, bool):
            raise PollError("show_names", "show_names: must be true or false")

        quantity = raw.get("answer_quantity")
        if quantity is not None and (not isinstance(quantity, str) or not QUANTITY_NAME.match(quantity)):
            raise PollError(
                "answer_quantity",
                f"answer_quantity: must be a readout quantity name such as critical_spin_rad_s (got {quantity!r})",
            )
        own_answer = "answer_value" if kind == "number" else "answer_choice"
        if quantity is not None and raw.get(own_answer) is not None:
            raise PollError(
                own_answer,
                f"{own_answer}: give either answer_quantity (the scene computes the answer) or {own_answer}, not both",
            )
        wrong_kind = ("answer_value", "unit") if kind == "choice" else ("answer_choice", "answer_choices", "choices")
        for name in wrong_kind:
            if raw.get(name) not in (None, ""):
                raise PollError(name, f"{name}: a {kind} poll has no {name}")

        choices: tuple[str, ...] = ()
        unit = ""
        answer_value = answer_choice = None
        choice_for: dict[str, int] = {}
        if kind == "choice":
            choices = cls._choices(raw.get("choices"))
            if raw.get("answer_choice") is not None:
                answer_choice = _choice_index(raw["answer_choice"], "answer_choice", choices)
            choice_for = cls._choice_for(raw.get("answer_choices"), choices)
            if quantity is not None and not choice_for:
                raise PollError(
                    "answer_choices",
                    "answer_choices: a choice poll answered by the scene maps the quantity's words to choices",
                )
            if quantity is None and choice_for:
                raise PollError(
                    "answer_choices", "answer_choices: maps a quantity's words, so it needs answer_quantity"
                )
        else:
            unit = _text(raw.get("unit", ""), "unit", low=0, high=MAX_UNIT_CHARS)
            if raw.get("answer_value") is not None:
                answer_value = _finite_number(raw["answer_value"], "answer_value")
        source = AnswerSource(quantity, choice_for) if quantity is not None else None
        return cls(
            poll_id=poll_id,
            question=question,
            kind=kind,
            choices=choices,
            unit=unit,
            answer_source=source,
            answer_value=answer_value,
            answer_choice=answer_choice,
            show_names=show_names,
        )

    @staticmethod
    def _choices(raw: Any) -> tuple[str, ...]:
        low, high = CHOICES_RANGE
        if not isinstance(raw, (list, tuple)) or not low <= len(raw) <= high:
            raise PollError("choices", f"choices: a choice poll needs a list of {low} to {high} choices")
        choices = tuple(_text(c, f"choices[{k}]", low=1, high=MAX_CHOICE_CHARS) for k, c in enumerate(raw))
        if len(set(choices)) != len(choices):
            raise PollError("choices", "choices: must all differ")
        return choices

    @staticmethod
    def _choice_for(raw: Any, choices: tuple[str, ...]) -> dict[str, int]:
        if raw is None:
            return {}
        if not isinstance(raw, Mapping) or not all(isinstance(word, str) and word for word in raw):
            raise PollError("answer_choices", "answer_choices: must map the quantity's words to choice indices")
        return {word: _choice_index(index, f"answer_choices.{word}", choices) for word, index in raw.items()}

    # -- answers -----------------------------------------------------------------------------------
    def submit(self, student_id: str, raw: Mapping[str, Any], *, name: str = "") -> None:
        """Take a student's answer — ``{"choice": index}`` or ``{"value": number}`` in the poll's unit —
        replacing their earlier one; :class:`PollClosedError` once the poll is closed. ``name`` is the student's as
        their room checked it (:meth:`~app.classroom.room.Room.join`): shown only when names are turned on."""
        if not self.open:
            raise PollClosedError("poll", f"poll {self.poll_id} is closed: answers are no longer taken")
        if not isinstance(student_id, str) or not student_id:
            raise PollError("student", "student: an answer needs the student's id")
        expected = "choice" if self.kind == "choice" else "value"
        if not isinstance(raw, Mapping) or set(raw) != {expected}:
            raise PollError(expected, f"{expected}: this {self.kind} poll takes exactly {{{expected!r}: …}}")
        choice = value = None
        if self.kind == "choice":
            choice = _choice_index(raw["choice"], "choice", self.choices)
        else:
            value = _finite_number(raw["value"], "value")
        earlier = self._answers.get(student_id)
        if earlier is None:
            self._answered_ever += 1  # a running count: a withdrawn answer's number is never given to another student
        number = earlier.number if earlier is not None else self._answered_ever
        shown_name = name.strip() if isinstance(name, str) else ""
        self._answers[student_id] = _Answer(number, shown_name, choice, value, datetime.now(UTC))

    def answer_of(self, student_id: str) -> dict[str, Any] | None:
        """A student's answer as the database keeps it (None if they have not answered)."""
        answer = self._answers.get(student_id)
        if answer is None:
            return None
        return {
            "number": answer.number,
            "name": answer.name,
            "choice": answer.choice,
            "value": answer.value,
            "answered_at": answer.answered_at,
        }

    def record(self) -> dict[str, Any]:
        """The poll as the database keeps it, without its answers (kept one row each: :meth:`answer_of`)."""
        source = self.answer_source
        return {
            "poll_id": self.poll_id,
            "question": self.question,
            "kind": self.kind,
            "choices": list(self.choices),
            "unit": self.unit,
            "answer_source": None
            if source is None
            else {"quantity": source.quantity, "choice_for": dict(source.choice_for)},
            "answer_value": self.answer_value,
            "answer_choice": self.answer_choice,
            "show_names": self.show_names,
            "open": self.open,
            "revealed": self.revealed,
            "answered_ever": self._answered_ever,
        }

    @classmethod
    def from_record(cls, record: Mapping[str, Any], answers: Mapping[str, Mapping[str, Any]]) -> Poll:
        """The poll :meth:`record` kept, with its answers (by student id, as :meth:`answer_of` gave them)."""
        source = record["answer_source"]
        poll = cls(
            poll_id=record["poll_id"],
            question=record["question"],
            kind=record["kind"],
            choices=tuple(record["choices"]),
            unit=record["unit"],
            answer_source=None if source is None else AnswerSource(source["quantity"], dict(source["choice_for"])),
            answer_value=record["answer_value"],
            answer_choice=record["answer_choice"],
            show_names=record["show_names"],
            open=record["open"],
            revealed=record["revealed"],
        )
        poll._answered_ever = record["answered_ever"]
        for student_id, kept in answers.items():
            poll.take_kept_answer(student_id, kept)
        return poll

    def take_kept_answer(self, student_id: str, kept: Mapping[str, Any]) -> None:
        """A student's answer as the database keeps it (:meth:`answer_of`'s fields; one given on another server)."""
        answered_at = kept["answered_at"]
        if answered_at.tzinfo is None:  # SQLite gives back naive datetimes: they were written in UTC
            answered_at = answered_at.replace(tzinfo=UTC)
        self._answers[student_id] = _Answer(kept["number"], kept["name"], kept["choice"], kept["value"], answered_at)
        self._answered_ever = max(self._answered_ever, kept["number"])

    def withdraw(self, student_id: str) -> None:
        """Take a student's answer out of the poll (the instructor removed them); nothing if they did not answer."""
        self._answers.pop(student_id, None)

    def close(self) -> None:
        self.open = False

    def reopen(self) -> None:
        """Take answers again; an answer revealed before is withdrawn (students may still change theirs)."""
        self.open = True
        self.revealed = None

    @property
    def answer_count(self) -> int:
        return len(self._answers)

    def _answer_text(self, answer: _Answer) -> str:
        if answer.choice is not None:
            return self.choices[answer.choice]
        assert answer.value is not None
        return f"{answer.value:.6g} {self.unit}".rstrip()  # as the student gave it, not rounded like the answer

    def _student_label(self, answer: _Answer) -> str:
        if self.show_names and answer.name:
            return answer.name
        return f"student {answer.number}"

    def _in_order(self) -> list[_Answer]:
        return sorted(self._answers.values(), key=lambda a: a.number)

    # -- the answer ---------------------------------------------------------------------------------
    def reveal(self, readout: Mapping[str, Any] | None) -> dict[str, Any]:
        """Close the poll and show its answer: computed by the scene from ``readout`` (the JSON of
        ``Readout.as_dict()``) when the poll names a quantity, else the instructor's own answer.

        :class:`PollError` (and nothing changes) when the readout cannot give the answer now.
        """
        if self.answer_source is not None:
            revealed = self._computed_answer(readout, self.answer_source)
        elif self.kind == "number" and self.answer_value is not None:
            text = f"{format_number(self.answer_value)} {self.unit}".rstrip()
            revealed = {
                "text": text,
                "value": self.answer_value,
                "choice": None,
                "unit": self.unit,
                "source": "given by the instructor",
            }
        elif self.kind == "choice" and self.answer_choice is not None:
            text = self.choices[self.answer_choice]
            revealed = {
                "text": text,
                "value": None,
                "choice": self.answer_choice,
                "unit": "",
                "source": "given by the instructor",
            }
        else:
            own = "answer_value" if self.kind == "number" else "answer_choice"
            raise PollError(
                "reveal", f"reveal: this poll has no answer to show (it names no answer_quantity and no {own})"
            )
        self.open = False
        self.revealed = revealed
        return dict(revealed)

    def _computed_answer(self, readout: Mapping[str, Any] | None, source: AnswerSource) -> dict[str, Any]:
        quantities = readout.get("quantities") if isinstance(readout, Mapping) else None
        if not isinstance(quantities, list):
            raise PollError(
                "answer_quantity",
                f"answer_quantity: the scene has no readout now, so it cannot compute {source.quantity}",
            )
        found = next((q for q in quantities if isinstance(q, Mapping) and q.get("name") == source.quantity), None)
        if found is None:
            names = ", ".join(str(q.get("name")) for q in quantities if isinstance(q, Mapping)) or "none"
            raise PollError(
                "answer_quantity",
                f"answer_quantity: the scene's readout has no {source.quantity!r} now (it has: {names})",
            )
        label = str(found.get("label") or source.quantity)
        value, unit, text = found.get("value"), str(found.get("unit") or ""), str(found.get("text") or "")
        origin = f"computed by the scene: {label}"
        if self.kind == "number":
            if (
                value is None
                or isinstance(value, bool)
                or not isinstance(value, (int, float))
                or not math.isfinite(value)
            ):
                why = f" ({text})" if text else ""
                raise PollError(
                    "answer_quantity",
                    f"answer_quantity: {label} has no value now{why}; run the demo further or change its parameters",
                )
            if unit != self.unit:
                asked = self.unit or "no unit"
                raise PollError(
                    "answer_quantity",
                    f"answer_quantity: {label} is in {unit or 'no unit'}, but the poll asks for {asked}",
                )
            number = float(value)
            return {
                "text": f"{format_number(number)} {unit}".rstrip(),
                "value": number,
                "choice": None,
                "unit": unit,
                "source": origin,
            }
        if value is not None or not text:
            raise PollError("answer_quantity", f"answer_quantity: {label} is a number, not a word a choice can match")
        if text not in source.choice_for:
            raise PollError(
                "answer_choices",
                f"answer_choices: the scene says {label} is {text!r}, which maps to none of the choices",
            )
        choice = source.choice_for[text]
        return {"text": self.choices[choice], "value": None, "choice": choice, "unit": "", "source": origin}

    # -- what each side sees -------------------------------------------------------------------------
    def public(self) -> dict[str, Any]:
        """What students see: the question, how many have answered, the answer once revealed (no names, no answers)."""
        return {
            "poll_id": self.poll_id,
            "question": self.question,
            "kind": self.kind,
            "choices": list(self.choices),
            "unit": self.unit,
            "open": self.open,
            "answers": self.answer_count,
            "revealed": dict(self.revealed) if self.revealed is not None else None,
        }

    def results(self) -> dict[str, Any]:
        """What the instructor sees: counts per choice or per bin, the answer if revealed, names only if turned on."""
        out: dict[str, Any] = {
            "poll_id": self.poll_id,
            "question": self.question,
            "kind": self.kind,
            "unit": self.unit,
            "choices": list(self.choices),
            "open": self.open,
            "answers": self.answer_count,
            "histogram": self._choice_histogram() if self.kind == "choice" else self._number_histogram(),
            "revealed": dict(self.revealed) if self.revealed is not None else None,
            "show_names": self.show_names,
        }
        if self.show_names:
            out["names"] = [{"name": self._student_label(a), "answer": self._answer_text(a)} for a in self._in_order()]
        return out

    def _choice_histogram(self) -> list[dict[str, Any]]:
        counts = [0] * len(self.choices)
        for answer in self._answers.values():
            assert answer.choice is not None
            counts[answer.choice] += 1
        return [
            {"label": label, "lo": None, "hi": None, "count": count}
            for label, count in zip(self.choices, counts, strict=True)
        ]

    def _number_histogram(self) -> list[dict[str, Any]]:
        """About :data:`TARGET_BINS` bins of a nice width over the answers (and the revealed value)."""
        values = [a.value for a in self._answers.values() if a.value is not None]
        if not values:
            return []
        shown = [*values]
        if self.revealed is not None and self.revealed.get("value") is not None:
            shown.append(float(self.revealed["value"]))
        low, high = min(shown), max(shown)
        if high - low <= max(EQUAL_RTOL * max(abs(low), abs(high)), EQUAL_ATOL):
            return [{"label": format_number(low), "lo": low, "hi": high, "count": len(values)}]
        width = nice_width(high - low)
        first = math.floor(low / width)
        n_bins = max(1, math.floor(high / width) - first + 1)
        counts = [0] * n_bins
        for value in values:
            index = math.floor(value / width + 1e-9) - first
            counts[min(n_bins - 1, max(0, index))] += 1
        decimals = max(0, -math.floor(math.log10(width) + 1e-9))  # edges are whole multiples of the width

        def edge(k: int) -> float:
            return round((first + k) * width, decimals)

        def edge_text(k: int) -> str:
            if decimals > MAX_EDGE_DECIMALS:
                return format_number(edge(k))
            return f"{edge(k) + 0.0:.{decimals}f}"  # + 0.0: never "-0"

        return [
            {"label": f"{edge_text(k)} to {edge_text(k + 1)}", "lo": edge(k), "hi": edge(k + 1), "count": count}
            for k, count in enumerate(counts)
        ]

    def to_csv(self) -> str:
        """Every answer, one row each, in the order students first answered; anonymous unless names are on.

        Text cells are made safe to open in a spreadsheet (:func:`spreadsheet_text`). A number answer is written
        as the number it is (``-3.2``, ``1e-07``): it comes from a float the server checked, never from text, so it
        cannot carry a formula, and a quote would turn it into text the instructor could no longer average.
        """
        buffer = io.StringIO()
        writer = csv.writer(buffer, lineterminator="\n")
        writer.writerow(CSV_HEADER)
        question, unit = spreadsheet_text(self.question), spreadsheet_text(self.unit)
        for answer in self._in_order():
            if answer.choice is not None:
                shown = spreadsheet_text(self.choices[answer.choice])
            else:
                assert answer.value is not None and math.isfinite(answer.value)
                shown = repr(answer.value)
            stamp = answer.answered_at.strftime("%Y-%m-%dT%H:%M:%SZ")
            writer.writerow((self.poll_id, question, spreadsheet_text(self._student_label(answer)), shown, unit, stamp))
        return buffer.getvalue()
