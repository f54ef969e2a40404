"""Formulas in caller-given names (the typed energies of chapter 7): accepted, refused with a reason, fuzzed.

:func:`parse_formula` shares its grammar with :func:`parse_expression` (fuzzed against an
independent mpmath evaluator in test_expressions.py); here we check the names, the hints, the
size bounds, that both vocabularies give the same trees, and that nothing typed is ever
evaluated: the fuzz runs with eval/exec/compile and sympy's text parsers made to raise.
"""

from __future__ import annotations

import builtins
import contextlib
import importlib
import time

import pytest
import sympy
import sympy.parsing.sympy_parser
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from app.physics.math.expressions import (
    MAX_DEPTH,
    MAX_FORMULA_CONSTANT,
    MAX_FORMULA_LENGTH,
    MAX_FORMULA_OPERATIONS,
    MAX_LENGTH,
    MAX_PARAMETER_NAME_LENGTH,
    T,
    check_parameter_name,
    parse_expression,
    parse_formula,
)
from tests.physics.math.test_expressions import Node, trees

NAMES = ("q1", "q2", "q3", "q1d", "q2d", "q3d", "t", "m", "m1", "m2", "l", "l1", "l2", "g", "k")
SYMBOLS = {name: sympy.Symbol(name, real=True) for name in NAMES}
q1, q2, q3, q1d, q2d, q3d, t, m, m1, m2, l, l1, l2, g, k = (SYMBOLS[name] for name in NAMES)

#: Most CPU time a single parse may take (s, this thread's CPU time: a busy machine slows the wall
#: clock, not the work; CI once measured 1.13 s of wall time for "7ø"). Measured: 1-10 ms for the
#: formulas here and at most a few tens of ms for the largest the limits allow; a parser that
#: evaluated a runaway power or expanded a product would take seconds to minutes of CPU.
PARSE_TIME_BOUND_S = 1.0


def parse(text: str, **options) -> sympy.Expr:
    return parse_formula(text, symbols=SYMBOLS, **options)


# -- accepted ----------------------------------------------------------------------------

@pytest.mark.parametrize(
    "text, expected",
    [
        ("m*l^2*q1d^2/2", m * l**2 * q1d**2 / 2),
        ("cos(q1-q2)", sympy.cos(q1 - q2)),
        ("m*g*l*(1-cos(q1))", m * g * l * (1 - sympy.cos(q1))),
        ("k*(q1-q2)^2/2", k * (q1 - q2) ** 2 / 2),
        ("(m1+m2)*l1^2*q1d^2/2 + m2*l1*l2*q1d*q2d*cos(q1-q2) + m2*l2^2*q2d^2/2",
         (m1 + m2) * l1**2 * q1d**2 / 2 + m2 * l1 * l2 * q1d * q2d * sympy.cos(q1 - q2) + m2 * l2**2 * q2d**2 / 2),
        ("m*(q1d^2 + q1^2*q2d^2)/2 - m*g*q1*cos(q2)", m * (q1d**2 + q1**2 * q2d**2) / 2 - m * g * q1 * sympy.cos(q2)),
        ("q3d**2 × m ÷ 2 − k·q3^2/2", q3d**2 * m / 2 - k * q3**2 / 2),
        ("m*l*sin(q1 - π*t)", m * l * sympy.sin(q1 - sympy.pi * t)),
        ("sqrt(q1^2 + q2^2) - exp(-t/2)*log(2 + cos(q3))", sympy.sqrt(q1**2 + q2**2) - sympy.exp(-t / 2) * sympy.log(2 + sympy.cos(q3))),
    ],
)
def test_accepted_formulas_build_the_expected_tree(text, expected):
    got = parse(text)
    assert sympy.expand(got - expected) == 0, got


def test_only_the_callers_names_are_used():
    assert parse("m*q1d^2/2").free_symbols == {m, q1d}
    custom = {"q1": sympy.Symbol("q1", positive=True), "mass": sympy.Symbol("mass", positive=True)}
    got = parse_formula("mass*q1", symbols=custom)
    assert got.free_symbols == set(custom.values())


def test_the_two_vocabularies_give_the_same_tree_for_t():
    for text in ("2*cos(t)", "t^3 - t", "exp(-t/5)*sin(3*t)", "2^-1*t", "-2^2", "1/2/4*t", "π*t"):
        assert parse_formula(text, symbols={"t": T}) == parse_expression(text)


def _renamed(node: Node, name: str) -> Node:
    """The same tree with each leaf ``t`` typed as ``name``."""
    if node.kind == "t":
        return Node("t", value=name)
    return Node(node.kind, *(_renamed(child, name) for child in node.children), value=node.value)


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(trees, st.sampled_from([0, 1, 2]))
def test_one_grammar_for_every_vocabulary(tree, style):
    """Any formula in t parses to the same tree as that formula with t renamed q1, or both are refused."""
    text, renamed = tree.text(style), _renamed(tree, "q1").text(style)
    try:
        in_t = parse_expression(text)
    except ValueError:
        in_t = None
    try:
        in_q1 = parse_formula(renamed, symbols={"q1": T}, max_length=MAX_LENGTH + len(renamed) - len(text), max_operations=10**6)
    except ValueError as exc:
        # Beyond the shared grammar, parse_formula also bounds the constants it forms.
        assert in_t is None or "larger than the limit" in str(exc), (text, renamed, exc)
        return
    assert in_t is not None and in_q1 == in_t, (text, renamed)


# -- refused, with position and reason ---------------------------------------------------

@pytest.mark.parametrize(
    "text, fragments",
    [
        ("q1'", ["unexpected \"'\" at character 3", "write a rate as q1d"]),
        ("m*q1'^2", ["at character 5", "write a rate as q1d"]),
        ("theta", ["unexpected 'theta' at character 1", "the coordinates are q1, q2, q3 and their rates q1d, q2d, q3d"]),
        ("m*l^2*thetadot^2", ["unexpected 'thetadot' at character 7", "q1d"]),
        ("q1dd", ["unexpected 'q1dd' at character 1", "their rates q1d"]),
        ("M*q1d", ["unexpected 'M' at character 1", "every constant needs a parameter of that name"]),
        ("θ", ["unexpected 'θ' at character 1", "names are ASCII letters and digits"]),
        ("q_1", ["underscores are not allowed"]),
        ("e*q1", ["exp(1)"]),
        ("q1.real", ["attribute access is not allowed"]),
        ("__import__('os')", ["unexpected '__import__' at character 1"]),
        ("T = m*q1d^2/2", ["unexpected 'T' at character 1"]),
        ("m*q1d^2/2 = T", ["type only the right-hand side, e.g. q1d^2/2"]),
        ("2q1", ["a product needs an explicit *, e.g. 2*q1"]),
        ("sin q1", ["sin needs its argument in parentheses, e.g. sin(q1)"]),
        ("sin(q1, q2)", ["commas are not allowed"]),
        ("", ["the formula is empty: type an expression in q1, q2, q3, q1d, q2d, q3d, t, m"]),
        ("q1 +", ["the formula ends too soon"]),
        ("m/(q1-q1)", ["division by zero"]),
        ("(-1)^q1", ["a power whose exponent depends on q1 needs a positive base, e.g. 2^q1"]),
        ("q1^1000", ["the exponent 1000 is larger than the limit 100"]),
        ("9^9^9*q1", ["larger than the limit"]),
        ("12345678901*m", ["larger than the limit"]),
        ("exp(100)*q1", ["larger than the limit"]),
        ("sqrt(-1)*q1", ["not real"]),
        ("1e9*1e9*m*q1d^2", ["the formula forms the constant 1e+18, larger than the limit 1e+15"]),
        ("q1d/exp(-1000000000)", ["forms the constant", "larger than the limit 1e+15"]),
    ],
)
def test_refused_with_a_reason(text, fragments):
    with pytest.raises(ValueError) as refused:
        parse(text)
    for fragment in fragments:
        assert fragment in str(refused.value), str(refused.value)


def test_refusal_lists_the_allowed_names():
    with pytest.raises(ValueError) as refused:
        parse_formula("m*x", symbols={"q1": q1, "m": m})
    assert str(refused.value) == (
        "unexpected 'x' at character 3: the coordinates are q1, and every constant needs a parameter of that name; "
        "only q1, m, numbers, + - * / ^, ( ) and sqrt sin cos tan exp log pi are allowed"
    )


def test_a_name_the_caller_did_not_give_is_refused():
    with pytest.raises(ValueError, match="unexpected 'm' at character 1"):
        parse_formula("m*q1d^2/2", symbols={"q1": q1, "q1d": q1d})
    with pytest.raises(ValueError, match="unexpected 't' at character 4"):
        parse_formula("q1*t", symbols={"q1": q1})  # time only when the caller gives it


def test_the_existing_limits_hold():
    depth = MAX_DEPTH - 1
    assert parse("(" * depth + "q1" + ")" * depth) == q1
    with pytest.raises(ValueError, match="nested more than 30 levels deep"):
        parse("sin(" * (MAX_DEPTH + 1) + "q1" + ")" * (MAX_DEPTH + 1))


def test_length_limit():
    longest = "q1" + "+q1" * ((MAX_FORMULA_LENGTH - 2) // 3)
    assert len(longest) <= MAX_FORMULA_LENGTH and parse(longest, max_operations=10**6) is not None
    with pytest.raises(ValueError, match=f"characters long; the limit is {MAX_FORMULA_LENGTH}"):
        parse("q1" + "+q1" * (MAX_FORMULA_LENGTH // 3))
    with pytest.raises(ValueError, match="the formula is 9 characters long; the limit is 8"):
        parse("m*q1d^2/2", max_length=8)


def test_operation_limit():
    terms = [f"m*q1^{power}" for power in range(2, 50)]
    text = "+".join(terms)
    operations = sympy.count_ops(parse(text, max_operations=10**6))
    assert operations > MAX_FORMULA_OPERATIONS
    with pytest.raises(ValueError, match=f"the formula has {operations} operations; the limit is {MAX_FORMULA_OPERATIONS}"):
        parse(text)
    assert parse(text, max_operations=operations) is not None  # the bound is inclusive
    # A triple pendulum's kinetic energy fits well within the default bound.
    triple = (
        "(m+m1+m2)*l^2*q1d^2/2 + (m1+m2)*l1^2*q2d^2/2 + m2*l2^2*q3d^2/2 + (m1+m2)*l*l1*q1d*q2d*cos(q1-q2)"
        " + m2*l*l2*q1d*q3d*cos(q1-q3) + m2*l1*l2*q2d*q3d*cos(q2-q3)"
    )
    assert sympy.count_ops(parse(triple)) <= MAX_FORMULA_OPERATIONS // 2


def test_constants_up_to_the_limit_are_accepted():
    assert parse("1e9*1e6*m") == sympy.Integer(10**15) * m
    assert MAX_FORMULA_CONSTANT == 1e15
    assert parse("exp(-1000000000)*q1") == sympy.exp(-(10**9)) * q1  # tiny is harmless


@pytest.mark.parametrize(
    "symbols, fragment",
    [
        ({}, "at least one name"),
        ({"q_1": q1}, "cannot be a name"),
        ({"sin": q1}, "cannot be a name"),
        ({"pi": q1}, "cannot be a name"),
        ({"q1": "q1"}, "must be a sympy.Symbol"),
    ],
)
def test_bad_symbol_tables_are_refused(symbols, fragment):
    with pytest.raises(ValueError, match=fragment):
        parse_formula("q1", symbols=symbols)


# -- parameter names -----------------------------------------------------------------------

@pytest.mark.parametrize("name", ["m", "m1", "L", "k2", "theta0", "mass", "g", "R", "abcdefghijkl"])
def test_parameter_names_accepted(name):
    check_parameter_name(name)
    assert parse_formula(f"{name}*q1", symbols={"q1": q1, name: sympy.Symbol(name)}) is not None


@pytest.mark.parametrize(
    "name, fragment",
    [
        ("", "is empty"),
        ("abcdefghijklm", f"the limit is {MAX_PARAMETER_NAME_LENGTH}"),
        ("1m", "must be an ASCII letter followed by"),
        ("m_1", "must be an ASCII letter followed by"),
        ("m 1", "must be an ASCII letter followed by"),
        ("θ", "must be an ASCII letter followed by"),
        ("ｍ", "must be an ASCII letter followed by"),
        ("sin", "is a function"),
        ("log", "is a function"),
        ("q1", "kept for the coordinates"),
        ("q3d", "kept for the coordinates"),
        ("q4", "kept for the coordinates"),
        ("q1dd", "kept for the coordinates"),
        ("t", "kept for pi, e, time t"),
        ("pi", "kept for pi, e, time t"),
        ("e", "kept for pi, e, time t"),
        ("numpy", "numeric module"),
        ("lambda", "a word of Python itself"),
        ("import", "a word of Python itself"),
        ("abs", "a word of Python itself"),
        ("None", "a word of Python itself"),
        ("match", "a word of Python itself"),
    ],
)
def test_parameter_names_refused(name, fragment):
    with pytest.raises(ValueError, match=fragment):
        check_parameter_name(name)


def test_parameter_name_must_be_text():
    with pytest.raises(ValueError, match="must be text"):
        check_parameter_name(3)  # type: ignore[arg-type]


# -- fuzzing: only clear refusals, never an evaluation, always fast -------------------------

class EvaluationAttempt(AssertionError):
    """Raised by the stand-ins below: the parser tried to evaluate or parse text."""


def _refuse_text(original):
    def guarded(value, *args, **kwargs):
        if isinstance(value, str):
            raise EvaluationAttempt(f"text reached a sympy text parser: {value!r}")
        return original(value, *args, **kwargs)

    return guarded


def _forbidden(name):
    def forbidden(*args, **kwargs):
        raise EvaluationAttempt(f"{name} was called")

    return forbidden


@contextlib.contextmanager
def nothing_may_evaluate_text():
    """eval/exec/compile raise; sympify, S(...) and parse_expr raise when given text."""
    with pytest.MonkeyPatch.context() as patch:
        for name in ("eval", "exec", "compile"):
            patch.setattr(builtins, name, _forbidden(name))
        patch.setattr(sympy, "sympify", _refuse_text(sympy.sympify))
        sympify_module = importlib.import_module("sympy.core.sympify")  # the attribute sympy.core.sympify is the function
        patch.setattr(sympify_module, "sympify", _refuse_text(sympify_module.sympify))
        patch.setattr(sympy, "parse_expr", _forbidden("parse_expr"))
        patch.setattr(sympy.parsing.sympy_parser, "parse_expr", _forbidden("parse_expr"))
        patch.setattr(type(sympy.S), "__call__", staticmethod(_refuse_text(sympify_module.sympify)))  # S("...") is sympify
        yield


def test_the_guard_catches_an_evaluation():
    """The stand-ins do raise: a parser that called any of them would fail the fuzz below."""
    with nothing_may_evaluate_text():
        for attempt in (lambda: builtins.eval("1"), lambda: sympy.sympify("q1"), lambda: sympy.S("q1"), lambda: sympy.parse_expr("q1")):
            with pytest.raises(EvaluationAttempt):
                attempt()


def _parse_guarded(text: str) -> None:
    """Parse ``text`` under the guard: a result or a ValueError, within the CPU-time bound."""
    start = time.thread_time()
    with nothing_may_evaluate_text():
        try:
            parse(text)
        except ValueError as exc:
            assert str(exc), "a refusal must say why"
    assert time.thread_time() - start < PARSE_TIME_BOUND_S, text


PIECES = st.sampled_from(
    list("0123456789.+-*/^() eE_,[]{}'\"=;:@%!&|<>~`#$\\\n\t×÷−·πθ")
    + list(NAMES)
    + ["**", "sin(", "cos(", "sqrt(", "exp(", "log(", "tan(", "pi", "q1'", "q1dd", "theta", "import", "__", "lambda",
       "9^9^9", "1e9", "exp(exp(", ")^100", "^-1", "/(q1-q1)"]
)  # fmt: skip


@settings(max_examples=500, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.text(max_size=MAX_FORMULA_LENGTH + 20))
def test_random_unicode_gives_a_result_or_a_clear_refusal(text):
    _parse_guarded(text)


@settings(max_examples=500, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(PIECES, max_size=120).map("".join))
def test_random_token_soup_gives_a_result_or_a_clear_refusal(text):
    _parse_guarded(text)


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(st.sampled_from(["q1", "q2d", "m", "(", ")", "+", "*", "^2", "cos(", "sin(", "exp(", "sqrt(", "1/("]), min_size=60, max_size=200).map("".join))
def test_long_near_valid_formulas_stay_fast(text):
    _parse_guarded(text[:MAX_FORMULA_LENGTH])


@pytest.mark.parametrize(
    "text",
    [
        "*".join(f"(q1+q2+{i})" for i in range(1, 40))[:MAX_FORMULA_LENGTH].rsplit("*", 1)[0],
        "*".join(["exp(q1)"] * 49),
        "(" * 29 + "q1" + ")^2" * 29,
        "sin(" * 29 + "q1" + ")" * 29,
        "+".join(["m*l^2*q1d^2*cos(q1-q2)"] * 17),
        "q1^q2^q3^q1^q2^q3^q1^q2^q3^q1^q2^q3^q1^q2^q3^q1^q2^q3^q1^q2^q3",
        "1/(" * 29 + "q1" + ")" * 29,
    ],
)
def test_worst_cases_within_the_limits_are_fast(text):
    assert len(text) <= MAX_FORMULA_LENGTH
    _parse_guarded(text)


def test_a_tower_of_radicals_is_folded_to_its_value_without_sympys_arbitrary_precision(monkeypatch):
    """An outside attack: 13 nested radicals (149 characters) took 7 s on the server and 25 took minutes, in sympy's
    evalf (called by sympy itself while building each power, and by the parser's checks). A constant power of a
    constant sum is now its double-precision value, and the checks walk the tree once; sympy.N is never needed."""
    monkeypatch.setattr(sympy, "N", lambda *args, **kwargs: (_ for _ in ()).throw(AssertionError("sympy.N called")))
    text = "(7+2)"
    for k in range(25):
        text = f"({text}^(1/{k + 3})+{k + 3})"
    t = sympy.Symbol("t", real=True)
    parsed = parse_formula(text + "*t", symbols={"t": t})
    coefficient = parsed / t
    value = 9.0
    for k in range(25):
        value = value ** (1 / (k + 3)) + k + 3
    assert coefficient.is_Float and float(coefficient) == pytest.approx(value, rel=1e-14)
    assert parse_formula("sqrt(2)*t", symbols={"t": t}) == sympy.sqrt(2) * t  # a plain radical stays exact
