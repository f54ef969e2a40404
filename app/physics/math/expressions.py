"""A whitelisting parser for the formulas a student types, such as ``x(t) = 2*cos(t)``.

The grammar is deliberately small::

    expression := term (("+" | "-") term)*
    term       := unary (("*" | "/") unary)*
    unary      := ("-" | "+") unary | power
    power      := atom ("^" unary)?            (right-associative: 2^3^2 = 2^9)
    atom       := number | name | "pi" | function "(" expression ")" | "(" expression ")"
    function   := sqrt | sin | cos | tan | exp | log      (log is the natural logarithm)

Two vocabularies share it. :func:`parse_expression` reads formulas in time
alone (``name`` is ``t``). :func:`parse_formula` reads formulas in names the
caller gives, such as the kinetic and potential energy of chapter 7 in the
generalized coordinates ``q1 q2 q3``, their rates ``q1d q2d q3d``, time ``t``
and constants the student names (checked by :func:`check_parameter_name`);
its result is also bounded in size (:data:`MAX_FORMULA_OPERATIONS`) and in
its constants (:data:`MAX_FORMULA_CONSTANT`), so what reaches a derivation is small.

``**`` is accepted as ``^``; the typed signs ``×`` ``·`` ``÷`` ``−`` and ``π`` as
``*`` ``*`` ``/`` ``-`` and ``pi``. Nothing else is: no other names, no
underscores, no attribute access, commas, brackets, quotes or keywords.

The text is scanned by our own tokenizer and parsed by recursive descent into a
sympy tree built node by node (``sympy.Symbol("t")``, ``sympy.sin``,
``sympy.Rational``…). The text is never handed to ``eval``, ``exec``,
``sympify`` or ``parse_expr``. Limits (length, nesting depth, size of numbers
and of constant powers) keep every input fast: ``9^9^9`` is refused before any
big number is formed. Every failure is a ``ValueError`` whose message names the
character position (1-based) and says what is allowed.
"""

from __future__ import annotations

import builtins
import cmath
import keyword
import math
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache

import sympy

#: Longest formula in t accepted (characters).
MAX_LENGTH = 200
#: Deepest nesting of parentheses, functions, signs and powers.
MAX_DEPTH = 30
#: Largest number that may be typed (magnitude).
MAX_LITERAL = 1e9
#: A power of two constants may not exceed this magnitude (e.g. 10^30 is refused).
MAX_CONSTANT_POWER = 1e15
#: A power of a variable (t, q1, ...) may not have an exponent larger than this in magnitude.
MAX_EXPONENT = 100

#: Longest formula in named variables accepted by default (characters): a triple pendulum's
#: kinetic energy typed out is about 200.
MAX_FORMULA_LENGTH = 400
#: Most operations (``sympy.count_ops``) a formula in named variables may have by default: that
#: triple pendulum's kinetic energy has 45. Deriving equations of motion multiplies the size
#: several times over per coordinate, so this bound keeps a derivation's input small.
MAX_FORMULA_OPERATIONS = 120
#: Largest constant (magnitude) a formula in named variables may form, e.g. by ``1e9*1e9``:
#: far below float64's 1.8e308, so compiled equations cannot overflow on constants alone.
MAX_FORMULA_CONSTANT = 1e15
#: Longest name a student may give a constant parameter (characters).
MAX_PARAMETER_NAME_LENGTH = 12

#: Names of the generalized coordinates, their rates and time in the formulas of chapter 7.
COORDINATE_NAMES = ("q1", "q2", "q3")
RATE_NAMES = ("q1d", "q2d", "q3d")
TIME_NAME = "t"

ALLOWED = "only t, numbers, + - * / ^, ( ) and sqrt sin cos tan exp log pi are allowed"

T = sympy.Symbol("t", real=True)

_FUNCTIONS: dict[str, Callable[[sympy.Expr], sympy.Expr]] = {
    "sqrt": sympy.sqrt,
    "sin": sympy.sin,
    "cos": sympy.cos,
    "tan": sympy.tan,
    "exp": sympy.exp,
    "log": sympy.log,
}
_TYPED_SIGNS = {"×": "*", "·": "*", "⋅": "*", "÷": "/", "−": "-", "–": "-"}
_NUMBER = re.compile(r"(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?", re.ASCII)
_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_PLAIN_NAME = re.compile(r"[A-Za-z][A-Za-z0-9]*", re.ASCII)
_NAME_HINTS = {
    "e": "write exp(1) for Euler's number, or 2e3 (no space) for 2000; " + ALLOWED,
    "ln": "write log for the natural logarithm; " + ALLOWED,
    "x": "the only variable is t; " + ALLOWED,
    "y": "the only variable is t; " + ALLOWED,
    "z": "the only variable is t; " + ALLOWED,
}
_HINTS = {
    ".": "attribute access is not allowed",
    ",": "functions take exactly one argument, so commas are not allowed",
    "[": "brackets are not allowed; use ( )",
    "]": "brackets are not allowed; use ( )",
    "{": "braces are not allowed; use ( )",
    "}": "braces are not allowed; use ( )",
    "=": "type only the right-hand side, e.g. 2*cos(t)",
    "_": "underscores are not allowed",
}
#: Names a student may not give a parameter, beyond keywords and built-ins: they read as something else,
#: or they would hide the numeric modules compiled equations call.
_RESERVED_NAMES = frozenset({"pi", "e", TIME_NAME, "ln", "np", "numpy", "math", "mpmath", "scipy", "sympy"})
_PYTHON_NAMES = frozenset(dir(builtins)) | frozenset(keyword.kwlist) | frozenset(keyword.softkwlist)


@dataclass(frozen=True)
class Token:
    """One token: ``kind`` is "number", "name", "op", "(" or ")"; ``position`` is 1-based."""

    kind: str
    text: str
    position: int


@dataclass(frozen=True)
class _Vocabulary:
    """The names a formula may use (``symbols``; pi and the functions always) and how refusals explain them.

    ``allowed`` ends most refusals; ``name_hints`` and ``char_hints`` replace it for a typed name or
    character; ``unknown_name_hint`` is for any other name, ``letter_hint`` for a non-ASCII letter.
    ``described`` says what to type into an empty field.
    """

    symbols: Mapping[str, sympy.Symbol]
    max_length: int
    allowed: str
    described: str
    name_hints: Mapping[str, str]
    char_hints: Mapping[str, str]
    unknown_name_hint: str
    letter_hint: str

    @property
    def sample(self) -> str:
        """The name shown in examples such as ``2*t``."""
        return next(iter(self.symbols))

    @property
    def operand(self) -> str:
        """What an operand may be named, in "expected a number, t, pi…"."""
        return self.sample if len(self.symbols) == 1 else "a name"

    def char_hint(self, char: str) -> str:
        if char in self.char_hints:
            return self.char_hints[char]
        return self.letter_hint if char.isalpha() else self.allowed


_TIME_VOCABULARY = _Vocabulary(
    symbols={TIME_NAME: T},
    max_length=MAX_LENGTH,
    allowed=ALLOWED,
    described="an expression in t, e.g. 2*cos(t)",
    name_hints=_NAME_HINTS,
    char_hints=_HINTS,
    unknown_name_hint=ALLOWED,
    letter_hint=ALLOWED,
)


def _fail(position: int, message: str) -> ValueError:
    return ValueError(f"at character {position}: {message}")


def _unexpected(token_text: str, position: int, hint: str = ALLOWED) -> ValueError:
    shown = token_text if len(token_text) <= 20 else token_text[:17] + "..."
    return ValueError(f"unexpected {shown!r} at character {position}: {hint}")


def tokenize(text: str) -> list[Token]:
    """Split a formula in ``t`` into tokens, refusing any character or name outside the grammar."""
    return _scan(text, _TIME_VOCABULARY)


def _scan(text: str, vocabulary: _Vocabulary) -> list[Token]:
    """Split ``text`` into tokens, refusing any character or name outside the grammar and ``vocabulary``."""
    if not isinstance(text, str):
        raise ValueError("the formula must be text")
    if len(text) > vocabulary.max_length:
        raise ValueError(f"the formula is {len(text)} characters long; the limit is {vocabulary.max_length}")
    tokens: list[Token] = []
    i = 0
    while i < len(text):
        char = text[i]
        position = i + 1
        if char in " \t":
            i += 1
            continue
        if (
            char.isascii()
            and char.isdigit()
            or (char == "." and i + 1 < len(text) and text[i + 1].isascii() and text[i + 1].isdigit())
        ):
            match = _NUMBER.match(text, i)
            assert match is not None
            tokens.append(Token("number", match.group(0), position))
            i = match.end()
            if i < len(text) and text[i] == ".":
                raise _unexpected(".", i + 1, "a number has at most one decimal point")
            continue
        if char.isascii() and (char.isalpha() or char == "_"):
            match = _NAME.match(text, i)
            assert match is not None
            name = match.group(0)
            if "_" in name:
                raise _unexpected(name, position, "underscores are not allowed; " + vocabulary.allowed)
            if name not in vocabulary.symbols and name != "pi" and name not in _FUNCTIONS:
                raise _unexpected(name, position, vocabulary.name_hints.get(name, vocabulary.unknown_name_hint))
            tokens.append(Token("name", name, position))
            i = match.end()
            continue
        if char == "π":
            tokens.append(Token("name", "pi", position))
            i += 1
            continue
        if char == "*" and text.startswith("**", i):
            tokens.append(Token("op", "^", position))
            i += 2
            continue
        if char in "+-*/^":
            tokens.append(Token("op", char, position))
            i += 1
            continue
        if char in _TYPED_SIGNS:
            tokens.append(Token("op", _TYPED_SIGNS[char], position))
            i += 1
            continue
        if char in "()":
            tokens.append(Token(char, char, position))
            i += 1
            continue
        raise _unexpected(char, position, vocabulary.char_hint(char))
    return tokens


def _number(token: Token) -> sympy.Rational:
    """An exact rational for a decimal literal (validated by the tokenizer's pattern)."""
    mantissa, _, exponent = token.text.lower().partition("e")
    if len(mantissa) > 20 or (exponent and abs(int(exponent)) > 30):
        raise _fail(token.position, f"the number {token.text} has too many digits or too large an exponent")
    value = Fraction(mantissa) * Fraction(10) ** int(exponent or "0")
    if value > MAX_LITERAL:
        raise _fail(token.position, f"the number {token.text} is larger than the limit {MAX_LITERAL:g}")
    return sympy.Rational(value.numerator, value.denominator)


class _Parser:
    """Recursive descent over the token list, building the sympy tree as it goes."""

    def __init__(self, tokens: list[Token], length: int, vocabulary: _Vocabulary) -> None:
        self.tokens = tokens
        self.index = 0
        self.end_position = length + 1
        self.depth = 0
        self.vocabulary = vocabulary

    def peek(self) -> Token | None:
        return self.tokens[self.index] if self.index < len(self.tokens) else None

    def take(self) -> Token:
        token = self.peek()
        if token is None:
            raise _fail(self.end_position, "the formula ends too soon")
        self.index += 1
        return token

    def enter(self, position: int) -> None:
        self.depth += 1
        if self.depth > MAX_DEPTH:
            raise _fail(position, f"the formula is nested more than {MAX_DEPTH} levels deep")

    def parse(self) -> sympy.Expr:
        if not self.tokens:
            raise ValueError(f"the formula is empty: type {self.vocabulary.described}")
        expr = self.expression()
        token = self.peek()
        if token is not None:
            raise self.unexpected_after_operand(token)
        return expr

    def unexpected_after_operand(self, token: Token) -> ValueError:
        if token.kind in ("number", "name", "("):
            sample = self.vocabulary.sample
            return _unexpected(
                token.text, token.position, f"a product needs an explicit *, e.g. 2*{sample} or 3*sin({sample})"
            )
        return _unexpected(token.text, token.position, "expected an operator + - * / ^ or the end of the formula")

    def expression(self) -> sympy.Expr:
        left = self.term()
        while (token := self.peek()) is not None and token.kind == "op" and token.text in "+-":
            self.take()
            right = self.term()
            left = left + right if token.text == "+" else left - right
        return left

    def term(self) -> sympy.Expr:
        left = self.unary()
        while (token := self.peek()) is not None and token.kind == "op" and token.text in "*/":
            self.take()
            right = self.unary()
            if token.text == "*":
                left = left * right
            else:
                if right == 0:
                    raise _fail(token.position, "division by zero")
                left = left / right
            left = _checked(left, token.position)
        return left

    def unary(self) -> sympy.Expr:
        token = self.peek()
        if token is not None and token.kind == "op" and token.text in "+-":
            self.take()
            self.enter(token.position)
            operand = self.unary()
            self.depth -= 1
            return -operand if token.text == "-" else operand
        return self.power()

    def power(self) -> sympy.Expr:
        base = self.atom()
        token = self.peek()
        if token is None or token.kind != "op" or token.text != "^":
            return base
        self.take()
        self.enter(token.position)
        exponent = self.unary()
        self.depth -= 1
        return _power(base, exponent, token.position)

    def atom(self) -> sympy.Expr:
        token = self.take()
        if token.kind == "number":
            return _number(token)
        if token.kind == "name":
            if token.text in self.vocabulary.symbols:
                return self.vocabulary.symbols[token.text]
            if token.text == "pi":
                return sympy.pi
            return self.call(token)
        if token.kind == "(":
            self.enter(token.position)
            inner = self.expression()
            self.close(token)
            self.depth -= 1
            return inner
        if token.kind == ")":
            raise _unexpected(
                ")", token.position, f"expected a number, {self.vocabulary.operand}, pi, a function or '('"
            )
        raise _unexpected(
            token.text, token.position, f"expected a number, {self.vocabulary.operand}, pi, a function or '(' here"
        )

    def call(self, name: Token) -> sympy.Expr:
        opening = self.peek()
        if opening is None or opening.kind != "(":
            raise _fail(
                name.position,
                f"{name.text} needs its argument in parentheses, e.g. {name.text}({self.vocabulary.sample})",
            )
        self.take()
        self.enter(opening.position)
        argument = self.expression()
        self.close(opening)
        self.depth -= 1
        return _function(name, argument)

    def close(self, opening: Token) -> None:
        token = self.peek()
        if token is None:
            raise _fail(opening.position, "this '(' is never closed")
        if token.kind != ")":
            raise self.unexpected_after_operand(token)
        self.take()


def _is_constant(expr: sympy.Expr) -> bool:
    return not expr.free_symbols


_NUMERIC_FUNCTIONS: dict[object, Callable[[complex], complex]] = {
    sympy.sin: cmath.sin,
    sympy.cos: cmath.cos,
    sympy.tan: cmath.tan,
    sympy.exp: cmath.exp,
    sympy.log: cmath.log,
}


def _numeric(expr: sympy.Basic) -> complex:
    """A constant expression's value in double precision, walking its tree once (its size bounds the time).

    Not ``sympy.N``: its precision tracking re-evaluates nested powers at rising precision, which an outside attack
    showed grows exponentially with their depth (a 145-character tower of radicals took 7 s, 25 levels minutes).
    Overflow gives an infinity, which the callers refuse."""
    if expr.is_Number:
        try:
            return complex(float(expr))
        except OverflowError:
            return complex(math.inf)
    if expr is sympy.pi:
        return complex(math.pi)
    if expr is sympy.E:
        return complex(math.e)
    if expr is sympy.I:
        return 1j
    arguments = [_numeric(argument) for argument in expr.args]
    try:
        if expr.is_Add:
            return sum(arguments, 0j)
        if expr.is_Mul:
            product = 1 + 0j
            for factor in arguments:
                product *= factor
            return product
        if expr.is_Pow:
            base, exponent = arguments
            return complex(math.inf) if base == 0 and exponent.real < 0 else base**exponent
        function = _NUMERIC_FUNCTIONS.get(expr.func)
        if function is not None:
            return function(arguments[0])
    except (OverflowError, ZeroDivisionError, ValueError):
        return complex(math.inf)
    return complex(sympy.N(expr, 15))  # not reached by the parser's own trees (numbers, + × ^ and its functions)


def _constant_value(expr: sympy.Expr, position: int) -> complex:
    value = _numeric(expr)
    if not (math.isfinite(value.real) and math.isfinite(value.imag)):
        raise _fail(position, "this part of the formula is infinite")
    return value


def _checked(expr: sympy.Expr, position: int) -> sympy.Expr:
    """Refuse results sympy marks as infinite, undefined or not real."""
    if expr.has(sympy.zoo, sympy.oo, sympy.nan, -sympy.oo):
        raise _fail(position, "this part of the formula is infinite or undefined (a division by zero?)")
    if expr.has(sympy.I):
        raise _fail(position, "this part of the formula is not a real number")
    return expr


def _power(base: sympy.Expr, exponent: sympy.Expr, position: int) -> sympy.Expr:
    """``base^exponent``, refusing constant powers too large to form and exponents too large to use."""
    if _is_constant(exponent):
        e = _constant_value(exponent, position)
        if abs(e.real) > MAX_EXPONENT:
            raise _fail(position, f"the exponent {float(e.real):.10g} is larger than the limit {MAX_EXPONENT}")
        if _is_constant(base):
            b = _constant_value(base, position)
            if b == 0 and e.real < 0:
                raise _fail(position, "zero to a negative power is a division by zero")
            if b != 0 and e.real * math.log(abs(b)) > math.log(MAX_CONSTANT_POWER):
                raise _fail(position, f"this power is larger than the limit {MAX_CONSTANT_POWER:g}")
            if b.real < 0 and not float(e.real).is_integer():
                raise _fail(position, "a negative number to a fractional power is not a real number")
            if not base.is_Number:  # a power of a constant sum or power: its value, not a tower sympy would study
                value = b**e
                if abs(value.imag) > 1e-12 * (1 + abs(value.real)):
                    raise _fail(position, "this power is not a real number")
                return sympy.Float(value.real)
    elif _is_constant(base) and _constant_value(base, position).real <= 0:
        variable = min(str(symbol) for symbol in exponent.free_symbols)
        raise _fail(position, f"a power whose exponent depends on {variable} needs a positive base, e.g. 2^{variable}")
    return _checked(sympy.Pow(base, exponent), position)


def _function(name: Token, argument: sympy.Expr) -> sympy.Expr:
    if _is_constant(argument):
        value = _constant_value(argument, name.position).real
        if name.text == "sqrt" and value < 0:
            raise _fail(name.position, f"sqrt of the negative number {value:.6g} is not real")
        if name.text == "log" and value <= 0:
            raise _fail(name.position, f"log of {value:.6g} is undefined (it needs a positive number)")
        if name.text == "exp" and value > math.log(MAX_CONSTANT_POWER):
            raise _fail(name.position, f"exp({value:.6g}) is larger than the limit {MAX_CONSTANT_POWER:g}")
    return _checked(_FUNCTIONS[name.text](argument), name.position)


@lru_cache(maxsize=256)
def parse_expression(text: str) -> sympy.Expr:
    """The sympy expression for a formula in ``t`` typed by a student.

    Raises ``ValueError`` with the character position and what is allowed. The
    result may be a constant (no ``t``) and uses exact rationals for typed numbers.
    """
    return _Parser(tokenize(text), len(text), _TIME_VOCABULARY).parse()


def check_expression(text: str) -> None:
    """``Parameter.parse`` hook: raises ``ValueError`` if ``text`` is not an allowed formula."""
    parse_expression(text)


def _formula_vocabulary(symbols: Mapping[str, sympy.Symbol], max_length: int) -> _Vocabulary:
    """The vocabulary of :func:`parse_formula`, its refusals naming ``symbols`` and the chapter-7 conventions."""
    if not symbols:
        raise ValueError("symbols: a formula needs at least one name")
    for name, symbol in symbols.items():
        if not isinstance(name, str) or not _PLAIN_NAME.fullmatch(name) or name == "pi" or name in _FUNCTIONS:
            raise ValueError(
                f"symbols: {name!r} cannot be a name in a formula (ASCII letters and digits, not pi or a function)"
            )
        if not isinstance(symbol, sympy.Symbol):
            raise ValueError(f"symbols: the value for {name!r} must be a sympy.Symbol")
    names = ", ".join(symbols)
    allowed = f"only {names}, numbers, + - * / ^, ( ) and sqrt sin cos tan exp log pi are allowed"
    coordinates = [name for name in COORDINATE_NAMES if name in symbols]
    rates = [name for name in RATE_NAMES if name in symbols]
    if coordinates:
        conventions = f"the coordinates are {', '.join(coordinates)}" + (
            f" and their rates {', '.join(rates)}" if rates else ""
        )
    else:
        conventions = f"the names defined here are {names}"
    example = f"{(rates or coordinates or list(symbols))[0]}^2/2"
    char_hints = dict(_HINTS)
    char_hints["="] = f"type only the right-hand side, e.g. {example}"
    char_hints["'"] = (
        f"{conventions}: write a rate as {rates[0] if rates else 'its own name'}, not with a prime; {allowed}"
    )
    name_hints = {
        name: hint.replace(ALLOWED, allowed)
        for name, hint in _NAME_HINTS.items()
        if name in ("e", "ln") and name not in symbols
    }
    return _Vocabulary(
        symbols=dict(symbols),
        max_length=max_length,
        allowed=allowed,
        described=f"an expression in {names}, e.g. {example}",
        name_hints=name_hints,
        char_hints=char_hints,
        unknown_name_hint=f"{conventions}, and every constant needs a parameter of that name; {allowed}",
        letter_hint=f"names are ASCII letters and digits: {conventions}; {allowed}",
    )


def parse_formula(
    text: str,
    *,
    symbols: Mapping[str, sympy.Symbol],
    max_length: int = MAX_FORMULA_LENGTH,
    max_operations: int = MAX_FORMULA_OPERATIONS,
) -> sympy.Expr:
    """The sympy expression for a formula in the names of ``symbols`` (name -> ``sympy.Symbol``), e.g. an energy.

    Same grammar and limits as :func:`parse_expression`, with these names instead of ``t``
    (the caller includes ``t`` if time is allowed). A formula longer than ``max_length``
    characters, with more than ``max_operations`` operations (``sympy.count_ops``) or forming a
    constant beyond :data:`MAX_FORMULA_CONSTANT` is refused. Raises ``ValueError`` saying where
    (1-based character) and what is allowed; a typed ``q1'`` or an undefined name like ``theta``
    is told the names of the coordinates and rates.
    """
    if max_length < 1 or max_operations < 1:
        raise ValueError("max_length and max_operations must be at least 1")
    vocabulary = _formula_vocabulary(symbols, max_length)
    expr = _Parser(_scan(text, vocabulary), len(text), vocabulary).parse()
    operations = sympy.count_ops(expr)
    if operations > max_operations:
        raise ValueError(
            f"the formula has {operations} operations; the limit is {max_operations}: write it shorter, or with "
            "fewer terms"
        )
    _check_constants(expr)
    return expr


def _check_constants(expr: sympy.Expr) -> None:
    """Refuse a formula any of whose constant parts (``1e9*1e9``, ``1/exp(-1e9)``) exceeds
    :data:`MAX_FORMULA_CONSTANT`."""
    for node in sympy.preorder_traversal(expr):
        if node.free_symbols or not isinstance(node, sympy.Expr):
            continue
        magnitude = abs(_numeric(node))
        if not math.isfinite(magnitude) or magnitude > MAX_FORMULA_CONSTANT:
            shown = f"{magnitude:.3g}" if magnitude < 1e300 else f"{node}"
            raise ValueError(f"the formula forms the constant {shown}, larger than the limit {MAX_FORMULA_CONSTANT:g}")


def check_parameter_name(name: str) -> None:
    """Raise ``ValueError`` unless ``name`` may name a student's constant parameter in :func:`parse_formula`.

    Allowed: an ASCII letter, then ASCII letters and digits, at most :data:`MAX_PARAMETER_NAME_LENGTH`
    characters; not a function, ``pi``, ``e``, ``t``, a coordinate or rate (``q1``, ``q2d``, any
    ``q`` with digits), a Python keyword or built-in, or a numeric module's name.
    """
    if not isinstance(name, str):
        raise ValueError("a parameter name must be text")
    shown = name if len(name) <= 20 else name[:17] + "..."
    if not name:
        raise ValueError("a parameter name is empty: use a letter, then letters or digits, e.g. m1")
    if len(name) > MAX_PARAMETER_NAME_LENGTH:
        raise ValueError(
            f"the parameter name {shown!r} is {len(name)} characters long; the limit is {MAX_PARAMETER_NAME_LENGTH}"
        )
    if not _PLAIN_NAME.fullmatch(name):
        raise ValueError(
            f"the parameter name {shown!r} must be an ASCII letter followed by ASCII letters or digits, e.g. m1 or L"
        )
    if name in _FUNCTIONS:
        raise ValueError(f"the parameter name {name!r} is a function (sqrt sin cos tan exp log); choose another")
    if re.fullmatch(r"q\d+d*", name) or name in COORDINATE_NAMES or name in RATE_NAMES:  # q4 or q1dd would mislead too
        raise ValueError(
            f"the parameter name {name!r} is kept for the coordinates {', '.join(COORDINATE_NAMES)} and rates "
            f"{', '.join(RATE_NAMES)}; choose another"
        )
    if name in _RESERVED_NAMES:
        raise ValueError(f"the parameter name {name!r} is kept for pi, e, time t or a numeric module; choose another")
    if name in _PYTHON_NAMES:
        raise ValueError(f"the parameter name {name!r} is a word of Python itself; choose another")
