"""Every exercise, over 100 variants each: the numbers are valid, the worked answer is marked correct and 5 % off is
not, another unit of the same dimension is accepted and another dimension is named, every named mistake is told as
itself, expressions accept a rearrangement and refuse a near miss; and the scene of "See it" takes the variant's
numbers. Then what a student may type that is not an answer, and the loader's refusals."""

from __future__ import annotations

import numpy as np
import pytest
import sympy

from app.course.catalogue import load_catalogue
from app.practice.book import ExerciseBook, book_problems
from app.practice.checking import AnswerUnreadable, check, read_answer
from app.practice.exercise import Part, parse_exercise
from app.practice.variants import variant
from app.scenes import SCENES
from tests.practice.shipped import EXERCISES

VARIANTS = range(100)
#: For each unit an exercise asks in: another unit of the same dimension, and what one of it is in the first.
OTHER_UNITS = {
    "1": ("percent", 0.01),
    "m": ("mm", 1e-3),
    "mm": ("m", 1e3),
    "kg": ("g", 1e-3),
    "s": ("ms", 1e-3),
    "deg": ("rad", 180 / np.pi),
    "rad": ("deg", np.pi / 180),
    "m/s": ("km/h", 1 / 3.6),
    "m/s^2": ("mm/s^2", 1e-3),
    "rad/s": ("rpm", 2 * np.pi / 60),
    "1/s": ("1/min", 1 / 60),
    "1/m": ("1/mm", 1e3),
    "rad/s^2": ("deg/s^2", np.pi / 180),
    "deg/h": ("deg/min", 60.0),
    "N": ("kN", 1e3),
    "N*m": ("N*mm", 1e-3),
    "J": ("kJ", 1e3),
    "W": ("kW", 1e3),
    "N/m": ("N/mm", 1e3),
    "N*s": ("N*ms", 1e-3),
    "kg*m/s": ("g*m/s", 1e-3),
    "kg*m^2": ("g*cm^2", 1e-7),
    "kg*m^2/s": ("g*cm^2/s", 1e-7),
    "N*m*s": ("N*mm*s", 1e-3),
    "J*s": ("kJ*s", 1e3),
}


def _typed(expression: sympy.Expr) -> str:
    """An expression as a student types it."""
    return str(expression).replace("**", "^")


def _answer(part: Part, value, unit: str | None = None) -> dict:
    if part.kind == "number":
        return {"value": float(value), "unit": part.unit if unit is None else unit}
    if part.kind == "vector":
        return {"vector": [float(c) for c in value], "unit": part.unit if unit is None else unit, "frame": part.frame}
    if part.kind == "expression":
        return {"expression": _typed(value)}
    return {"choice": value}


def _rearranged(expression):
    """The same expression written another way: multiplied out, else with its common factors taken out, else over one
    denominator. Never ``sympy.factor``: its multivariate algorithm (Wang's, from random evaluation points) now and
    then took 11 s on one Hamiltonian, by the draw of its points, and made this file 259 s in the suite (43 s alone)."""
    for rewrite in (sympy.expand, sympy.factor_terms, sympy.together):
        written = rewrite(expression)
        if written != expression:
            return written
    return expression


def test_there_are_exercises_and_every_one_fits_the_course():
    catalogue = load_catalogue()
    assert len(EXERCISES) >= 3
    assert book_problems(ExerciseBook(EXERCISES), catalogue.chapters, SCENES) == []


@pytest.mark.parametrize("exercise_id", list(EXERCISES))
def test_every_variant_checks_as_a_teacher_would(exercise_id):
    exercise = EXERCISES[exercise_id]
    for number in VARIANTS:
        drawn = variant(exercise, number)
        assert variant(exercise, number).given == drawn.given  # the same numbers every time
        if exercise.scene is not None:
            SCENES[exercise.scene.scene_id].parameters.validate(exercise.scene.at(drawn.given)["params"])
        for part in exercise.parts:
            expected = drawn.answers[part.id]
            verdict = check(exercise, part, _answer(part, expected.value), expected)
            assert verdict.correct and verdict.mistake is None, (number, part.id, verdict)
            if part.kind in ("number", "vector"):
                off = np.asarray(expected.value, dtype=float) * 1.05
                assert not check(exercise, part, _answer(part, off), expected).correct, (number, part.id)
                other, scale = OTHER_UNITS[part.unit]
                converted = np.asarray(expected.value, dtype=float) / scale
                assert check(exercise, part, _answer(part, converted, other), expected).correct, (number, part.id)
                foreign = "s" if part.unit not in ("s", "ms") else "m"
                wrong = check(exercise, part, _answer(part, expected.value, foreign), expected)
                assert not wrong.correct and "the question asks for" in wrong.feedback, wrong
            if part.kind == "expression":
                rearranged = _rearranged(expected.value)
                assert check(exercise, part, _answer(part, rearranged), expected).correct, (part.id, rearranged)
                near = check(exercise, part, _answer(part, sympy.Rational(21, 20) * expected.value), expected)
                assert not near.correct, part.id
                if part.up_to_constant:
                    shifted = check(exercise, part, _answer(part, expected.value + 3), expected)
                    assert shifted.correct, part.id
            for mistake in exercise.mistakes_of(part.id):
                verdict = check(exercise, part, _answer(part, expected.mistakes[mistake.id]), expected)
                assert not verdict.correct and verdict.mistake == mistake, (number, part.id, mistake.id, verdict)
                assert verdict.feedback == mistake.text


def test_units_expressions_and_choices_a_student_types_that_are_not_answers_are_refused_not_judged():
    exercise = EXERCISES["5-2-plate-about-corner"]
    part = exercise.part("ixx")
    for unit in ("blorps", "kg*", "__import__('os')", "kg;m", "x" * 60):
        with pytest.raises(AnswerUnreadable):
            read_answer(part, {"value": 1.0, "unit": unit})
    for value in (float("nan"), float("inf"), 1e300, True, "3"):
        with pytest.raises(AnswerUnreadable):
            read_answer(part, {"value": value, "unit": "kg*m^2"})
    bead = EXERCISES["7-5-bead-on-hoop-lagrange"]
    kinetic = bead.part("kinetic")
    for text in ("__import__('os').system('true')", "m*R^2*thetad^2/2 + x", "lambda: 1", "m.R", "9^9^9^9", ""):
        with pytest.raises(AnswerUnreadable):
            read_answer(kinetic, {"expression": text})


def test_an_expression_with_no_value_at_a_sample_point_is_wrong_not_an_error():
    bead = EXERCISES["7-5-bead-on-hoop-lagrange"]
    drawn = variant(bead, 0)
    part = bead.part("equation")
    verdict = check(bead, part, {"expression": "log(-g)*sin(theta)"}, drawn.answers["equation"])
    assert not verdict.correct and verdict.mistake is None


GOOD = """+++
id = "x-1"
title = "T"
section = "5.2"
answers = "ch05.plate_about_corner"
[given]
mass_kg = { min = 1.0, max = 2.0, step = 0.5, unit = "kg" }
length_m = { min = 1.0, max = 2.0, step = 0.5, unit = "m" }
width_m = { min = 0.2, max = 0.4, step = 0.1, unit = "m" }
[[parts]]
id = "ixx"
prompt = "p"
kind = "number"
unit = "kg*m^2"
+++
Body {{mass_kg}}.
"""


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (('answers = "ch05.plate_about_corner"', 'answers = "os.system"'), "answers must name"),
        (('answers = "ch05.plate_about_corner"', 'answers = "ch05.no_such"'), "has no function"),
        (('kind = "number"', 'kind = "essay"'), "kind must be one of"),
        (('unit = "kg*m^2"', 'unit = ""'), "needs a unit"),
        (('id = "x-1"', 'id = "X 1"'), "lower-case"),
        (('section = "5.2"', 'section = "6.1"'), "is not a section of chapter 5"),
        (('step = 0.5, unit = "kg"', 'step = 0.0, unit = "kg"'), "step > 0"),
    ],
)
def test_a_malformed_exercise_file_is_refused_naming_the_file(change, message):
    with pytest.raises(ValueError, match=message) as refused:
        parse_exercise(GOOD.replace(*change), "ch05/exercises/x.md", chapter=5)
    assert "ch05/exercises/x.md" in str(refused.value)
    parse_exercise(GOOD, "ch05/exercises/x.md", chapter=5)  # and the unchanged file is taken


def test_a_slot_that_names_no_given_number_is_refused():
    with pytest.raises(ValueError, match="names no given number: mass_g"):
        parse_exercise(GOOD.replace("Body {{mass_kg}}.", "Body {{mass_g}}."), "x.md", chapter=5)
    with pytest.raises(ValueError, match="must hold a given's lower-case name"):
        parse_exercise(GOOD.replace("Body {{mass_kg}}.", "Body {{Pull_N}}."), "x.md", chapter=5)


@pytest.mark.parametrize(
    "unit",
    ["m^9^9^9", "m^9^9^7", "m^99^99^2", "m^9999^9999", "m^1e308", "kg*m^2*(Ym/m)^99", "ym^99/m^97*kg", "kg*m^2^1.0000001",
     "kg*m^2*m^1e308*m^1e308/m^1e308/m^1e308", "(((kg)))*m^2", "m^(9^9)"],
)  # fmt: skip
def test_a_unit_with_a_tower_a_huge_power_or_an_absurd_scale_is_refused_before_pint_computes_it(unit):
    """Found by an outside attack: pint computes m^9^9^7 exactly (8 s holding the interpreter), 500s on huge powers,
    and scale factors that turn any number into 0 or inf."""
    part = EXERCISES["5-2-plate-about-corner"].part("ixx")
    with pytest.raises(AnswerUnreadable):
        read_answer(part, {"value": 1.0, "unit": unit})


def test_ordinary_units_with_powers_still_read():
    part = EXERCISES["5-2-plate-about-corner"].part("ixx")
    assert read_answer(part, {"value": 1.0, "unit": "kg*m^2"}) == pytest.approx(1.0)
    assert read_answer(part, {"value": 1.0, "unit": "kg m²"}) == pytest.approx(1.0)
    assert read_answer(part, {"value": 1.0, "unit": "g*cm**2"}) == pytest.approx(1e-7)
    assert read_answer(part, {"value": 1.0, "unit": "kg*m^2*s^-1*s"}) == pytest.approx(1.0)
    assert read_answer(part, {"value": 2.0, "unit": "kg*(m^0.5)^(4)"}) == pytest.approx(2.0)
