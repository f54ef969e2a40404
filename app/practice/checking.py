"""Checking a student's answer to one part as a teacher would: numbers within a relative tolerance, in any unit of
the right dimension (a wrong dimension is named), vectors in the part's frame, expressions compared with the model's
at random points, and a wrong answer that matches a named mistake told so.

Units are read by pint (its own unit parser, never Python's); expressions by the whitelisting parser
(:func:`app.physics.math.expressions.parse_formula`), never ``eval``, ``sympify`` or ``parse_expr``. An answer that
cannot be read at all (an unknown unit, an expression that does not parse) is :class:`AnswerUnreadable`: the API
answers 422 and counts no attempt.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cache, lru_cache
from typing import Any

import numpy as np
import pint
import sympy

from app.physics.math.expressions import parse_formula
from app.practice.exercise import AnswerValue, Exercise, Mistake, Part, PartAnswer

#: Points at which two expressions are compared, drawn from the symbols' ranges (a fixed generator: the same for
#: every student, so a verdict never depends on luck).
EXPRESSION_POINTS = 12
#: Longest unit a student may type, and the characters it may use (pint reads the rest).
MAX_UNIT_LENGTH = 40
UNIT_TEXT = re.compile(r"^[A-Za-z0-9 *·/^()._°µμ²³-]*$")
#: Largest magnitude a typed number may have (an answer is a physical quantity, not a stress test).
MAX_NUMBER = 1e15
#: A power in a typed unit: a plain number (``2``, ``-1``, ``0.5``) of at most this size.
MAX_UNIT_EXPONENT = 6
UNIT_EXPONENT = re.compile(r"\s*(?:\(\s*([+-]?\d{1,2}(?:\.\d{1,3})?)\s*\)|([+-]?\d{1,2}(?:\.\d{1,3})?)(?![\w.]))")
#: A typed unit's size in SI units must lie within this factor of 1 (a yoctometre to the 99th is not a unit).
MIN_UNIT_FACTOR = 1e-30
#: Distinct unit texts pint may keep parsed before its cache is emptied (it would otherwise grow with every one).
MAX_KEPT_UNITS = 2000


class AnswerUnreadable(ValueError):
    """An answer that cannot be read (unit, expression, shape): refused, not counted as an attempt."""


@dataclass(frozen=True)
class Verdict:
    correct: bool
    feedback: str
    mistake: Mistake | None = None

    def public(self) -> dict[str, Any]:
        mistake = {"id": self.mistake.id, "text": self.mistake.text} if self.mistake else None
        return {"correct": self.correct, "feedback": self.feedback, "mistake": mistake}


@cache
def units() -> pint.UnitRegistry[float]:
    """The unit registry (pint's default definitions; built once, about 0.3 s)."""
    return pint.UnitRegistry(autoconvert_offset_to_baseunit=True)


#: What a dimension is called in feedback ("that is a force; the question asks for a moment").
_DIMENSION_NAMES = (
    ("1", "a pure number or an angle"),
    ("m", "a length"),
    ("kg", "a mass"),
    ("s", "a time"),
    ("m/s", "a speed"),
    ("m/s^2", "an acceleration"),
    ("1/s", "an angular velocity or a rate"),
    ("1/s^2", "an angular acceleration"),
    ("N", "a force"),
    ("N*m", "a moment or an energy"),
    ("kg*m^2", "a moment of inertia"),
    ("kg*m/s", "a linear momentum or an impulse"),
    ("kg*m^2/s", "an angular momentum"),
    ("W", "a power"),
    ("N/m", "a stiffness"),
    ("N*s/m", "a damping coefficient"),
)


@cache
def _dimension_names() -> dict[Any, str]:
    return {units().parse_units(unit).dimensionality: name for unit, name in _DIMENSION_NAMES}


def dimension_name(unit: str) -> str:
    """What ``unit`` measures, in words (``"a force"``), or its dimension as pint writes it."""
    dimensionality = units().parse_units(_pint_text(unit)).dimensionality
    return _dimension_names().get(dimensionality, f"a quantity of dimension {dimensionality}")


def _pint_text(unit: str) -> str:
    return unit.replace("·", "*").replace("^", "**").replace("²", "**2").replace("³", "**3").replace("μ", "µ")


def _check_unit_text(text: str) -> None:
    """Refuse, before pint reads it, a unit whose powers are not small plain numbers: pint evaluates ``m^9^9^9``
    exactly, as a Python integer, holding the interpreter for minutes (an outside attack found it)."""
    if not isinstance(text, str) or len(text) > MAX_UNIT_LENGTH or not UNIT_TEXT.match(text):
        raise AnswerUnreadable(
            f"a unit is at most {MAX_UNIT_LENGTH} characters of letters, digits, * / ^ ( ) and spaces, e.g. kg*m^2/s"
        )
    powers = text.replace("**", "^")
    for match in re.finditer(r"\^", powers):
        exponent = UNIT_EXPONENT.match(powers, match.end())
        if exponent is None or abs(float(exponent.group(1) or exponent.group(2))) > MAX_UNIT_EXPONENT:
            raise AnswerUnreadable(
                f"a power in a unit is a plain number from -{MAX_UNIT_EXPONENT} to {MAX_UNIT_EXPONENT} (m^2, s^-1)"
            )
        if powers[exponent.end() :].lstrip().startswith("^"):
            raise AnswerUnreadable("a power in a unit is a plain number, not a power of a power")
    depth = 0
    for char in text:
        depth += (char == "(") - (char == ")")
        if depth > 2:
            raise AnswerUnreadable("a unit nests brackets two deep at most")


def parse_unit(text: str) -> pint.Unit:
    """A unit a student typed (``kg*m^2``, ``N·m``, ``deg``, ``rad/s``); :class:`AnswerUnreadable` if it is none,
    or if it is a thousand orders of magnitude from SI (``ym^99/m^97``)."""
    _check_unit_text(text)
    if not text.strip() or text.strip() == "1":
        return units().dimensionless
    registry = units()
    if len(registry._cache.parse_unit) > MAX_KEPT_UNITS:  # pint keeps every text it parsed: bounded here
        registry._cache.parse_unit.clear()
    try:
        unit = registry.parse_units(_pint_text(text.strip()))
        factor = float(registry.Quantity(1.0, unit).to_base_units().magnitude)
    except Exception as exc:  # noqa: BLE001 - pint's parser fails in many ways (even AssertionError): all unreadable
        raise AnswerUnreadable(f"{text!r} is not a unit we know ({exc}); write units like kg*m^2/s or N*m") from None
    if not (math.isfinite(factor) and MIN_UNIT_FACTOR <= abs(factor) <= 1 / MIN_UNIT_FACTOR):
        raise AnswerUnreadable(f"{text!r} is more than 30 orders of magnitude from SI units; use a nearer one")
    return unit


def in_part_unit(value: float, unit_text: str, part: Part) -> float:
    """``value`` ``unit_text`` expressed in the part's unit; :class:`WrongDimension` if it measures something else."""
    conversion = _conversion(unit_text.strip() or part.unit, part.unit)
    if isinstance(conversion, str):
        raise WrongDimension(conversion)
    scale, offset = conversion
    converted = scale * value + offset
    if not math.isfinite(converted):
        raise AnswerUnreadable(f"{value:g} {unit_text} is not a finite number of {part.unit}")
    return converted


@lru_cache(maxsize=MAX_KEPT_UNITS)
def _conversion(unit_text: str, wanted_text: str) -> tuple[float, float] | str:
    """How a number in ``unit_text`` becomes one in ``wanted_text``: (scale, offset), an offset only for a unit such
    as degC; or, for a unit of another dimension, the feedback saying so. Kept per pair of texts: pint builds several
    objects for every unit it reads (most of the time of checking an answer). :class:`AnswerUnreadable` (not kept)
    for a unit that is none."""
    unit, wanted = parse_unit(unit_text), parse_unit(wanted_text)
    if unit.dimensionality != wanted.dimensionality:
        return f"That is {_dimension_of(unit)}; the question asks for {dimension_name(wanted_text)} (in {wanted_text})"
    try:
        offset = float(units().Quantity(0.0, unit).to(wanted).magnitude)
        scale = float(units().Quantity(1.0, unit).to(wanted).magnitude) - offset
    except Exception as exc:  # noqa: BLE001 - a conversion pint cannot make is an answer we cannot read
        raise AnswerUnreadable(f"{unit_text!r} cannot be converted to {wanted_text} ({exc})") from None
    return scale, offset


def _dimension_of(unit: pint.Unit) -> str:
    return _dimension_names().get(unit.dimensionality, f"a quantity of dimension {unit.dimensionality}")


class WrongDimension(Exception):
    """An answer in a unit of another dimension: a wrong answer whose feedback names both dimensions."""


def _finite_number(value: Any, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise AnswerUnreadable(f"{what} must be a finite number")
    if abs(value) > MAX_NUMBER:
        raise AnswerUnreadable(f"{what} is larger than {MAX_NUMBER:g} in magnitude")
    return float(value)


def _bound(part: Part, scale: float) -> float:
    return max(part.tolerance * scale, part.absolute)


def _close_numbers(part: Part, given: float, expected: float) -> bool:
    return abs(given - expected) <= _bound(part, abs(expected))


def _close_vectors(part: Part, given: np.ndarray, expected: np.ndarray) -> bool:
    return float(np.linalg.norm(given - expected)) <= _bound(part, float(np.linalg.norm(expected)))


@cache
def _symbols(part: Part) -> dict[str, sympy.Symbol]:
    return {s.name: sympy.Symbol(s.name, real=True) for s in part.symbols}


@cache
def _points(part: Part) -> np.ndarray:
    """:data:`EXPRESSION_POINTS` points (one row each) in the ranges of the part's symbols."""
    rng = np.random.default_rng(20261129)
    lows = np.array([s.low for s in part.symbols])
    highs = np.array([s.high for s in part.symbols])
    return lows + (highs - lows) * rng.random((EXPRESSION_POINTS, len(part.symbols)))


_FUNCTIONS = {sympy.sin: np.sin, sympy.cos: np.cos, sympy.tan: np.tan, sympy.exp: np.exp, sympy.log: np.log}


def _evaluate(expression: sympy.Basic, values: Mapping[sympy.Symbol, np.ndarray]) -> np.ndarray:
    """The expression's (complex) values at every point at once, walking its tree: numbers, the symbols, + × and
    powers, and the parser's functions. Nothing is compiled or executed; any other node is a ValueError."""
    if expression.is_Number or expression in (sympy.pi, sympy.E):
        return np.full(EXPRESSION_POINTS, complex(expression))
    if expression.is_Symbol:
        return values[expression]
    arguments = [_evaluate(argument, values) for argument in expression.args]
    if expression.is_Add:
        return np.sum(arguments, axis=0)
    if expression.is_Mul:
        return np.prod(arguments, axis=0)
    if expression.is_Pow:
        return np.power(arguments[0], arguments[1])
    function = _FUNCTIONS.get(expression.func)
    if function is None:
        raise ValueError(f"cannot evaluate {expression.func}")
    return function(arguments[0])


@lru_cache(maxsize=4096)
def _values_at_points(part: Part, expression: sympy.Expr) -> np.ndarray:
    """The expression's values at the part's points (NaN where it has no finite real value)."""
    values = {symbol: _points(part)[:, i].astype(complex) for i, symbol in enumerate(_symbols(part).values())}
    with np.errstate(all="ignore"):
        try:
            result = _evaluate(expression, values)
        except (ValueError, KeyError):
            return np.full(EXPRESSION_POINTS, np.nan)
    real = np.isfinite(result) & (np.abs(result.imag) <= 1e-12 * (1 + np.abs(result.real)))
    return np.where(real, result.real, np.nan)


def _close_expressions(part: Part, given: sympy.Expr, expected: sympy.Expr) -> bool:
    """Equal at every point, to the part's tolerance of the expected values' size over all the points."""
    mine, theirs = _values_at_points(part, given), _values_at_points(part, expected)
    if not np.all(np.isfinite(theirs)):
        raise ValueError("the model's expression has no value at a sample point: narrow the symbols' ranges")
    if not np.all(np.isfinite(mine)):
        return False
    if part.up_to_constant:
        mine, theirs = mine - mine.mean(), theirs - theirs.mean()
    scale = float(np.sqrt(np.mean(theirs**2)))
    return bool(np.max(np.abs(mine - theirs)) <= _bound(part, scale))


def _same(part: Part, given: AnswerValue, expected: AnswerValue) -> bool:
    if part.kind == "number":
        return _close_numbers(part, float(given), float(expected))  # type: ignore[arg-type]
    if part.kind == "vector":
        return _close_vectors(part, np.asarray(given, dtype=float), np.asarray(expected, dtype=float))
    if part.kind == "expression":
        return _close_expressions(part, given, expected)
    return given == expected


def distinct_answers(part: Part, first: AnswerValue, second: AnswerValue) -> bool:
    """Whether the checker tells the two apart with room to spare: each lies outside twice the other's tolerance
    (for a choice, whether they differ)."""
    if part.kind == "choice":
        return first != second
    wider = Part(**{**part.__dict__, "tolerance": min(2 * part.tolerance, 0.49), "absolute": 2 * part.absolute})
    return not _same(wider, first, second) and not _same(wider, second, first)


def read_answer(part: Part, answer: Mapping[str, Any]) -> AnswerValue:
    """The student's answer to ``part`` in the part's own terms (a number in its unit, components in its unit and
    frame, a sympy expression, a choice id). :class:`AnswerUnreadable` or :class:`WrongDimension` otherwise."""
    if part.kind == "number":
        if "value" not in answer:
            raise AnswerUnreadable("a number answer is {'value': number, 'unit': text}")
        return in_part_unit(_finite_number(answer["value"], "value"), str(answer.get("unit") or ""), part)
    if part.kind == "vector":
        vector = answer.get("vector")
        if not isinstance(vector, list) or len(vector) != 3:
            raise AnswerUnreadable("a vector answer is {'vector': [x, y, z], 'unit': text, 'frame': text}")
        frame = answer.get("frame")
        if frame not in (None, "", part.frame):
            raise AnswerUnreadable(f"the question asks for components in {part.frame}, not {str(frame)[:40]!r}")
        unit = str(answer.get("unit") or "")
        return tuple(in_part_unit(_finite_number(c, "each component"), unit, part) for c in vector)
    if part.kind == "expression":
        text = answer.get("expression")
        if not isinstance(text, str) or not text.strip():
            raise AnswerUnreadable("an expression answer is {'expression': text}")
        try:
            return parse_formula(text, symbols=_symbols(part))
        except ValueError as exc:
            raise AnswerUnreadable(str(exc)) from None
    choice = answer.get("choice")
    if choice not in {c.id for c in part.choices}:
        raise AnswerUnreadable(f"choose one of {', '.join(c.id for c in part.choices)}")
    return str(choice)


def check(exercise: Exercise, part: Part, answer: Mapping[str, Any], expected: PartAnswer) -> Verdict:
    """The verdict on ``answer`` (the API's answer object) to ``part``, whose answer is ``expected``."""
    try:
        given = read_answer(part, answer)
    except WrongDimension as exc:
        return Verdict(False, str(exc))
    if _same(part, given, expected.value):
        return Verdict(True, "Correct.")
    for mistake in exercise.mistakes_of(part.id):
        if _same(part, given, expected.mistakes[mistake.id]):
            return Verdict(False, mistake.text, mistake)
    return Verdict(False, _not_yet(part))


def _not_yet(part: Part) -> str:
    if part.kind == "choice":
        return "Not that one. Read the hint, or look at the scene, and choose again."
    if part.kind == "expression":
        return "Not equal to the model's expression at every sample point. Check each term and its sign."
    return f"Not within {part.tolerance:.0%} of the model's answer. Check the steps, or ask for a hint."
