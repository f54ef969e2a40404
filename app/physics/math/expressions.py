"""A whitelisting parser for the formulas a student types, such as ``x(t) = 2*cos(t)``.

The grammar is deliberately small::

    expression := term (("+" | "-") term)*
    term       := unary (("*" | "/") unary)*
    unary      := ("-" | "+") unary | power
    power      := atom ("^" unary)?            (right-associative: 2^3^2 = 2^9)
    atom       := number | "t" | "pi" | function "(" expression ")" | "(" expression ")"
    function   := sqrt | sin | cos | tan | exp | log      (log is the natural logarithm)

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

import math
import re
from collections.abc import Callable
from dataclasses import dataclass
from fractions import Fraction
from functools import lru_cache

import sympy

#: Longest formula accepted (characters).
MAX_LENGTH = 200
#: Deepest nesting of parentheses, functions, signs and powers.
MAX_DEPTH = 30
#: Largest number that may be typed (magnitude).
MAX_LITERAL = 1e9
#: A power of two constants may not exceed this magnitude (e.g. 10^30 is refused).
MAX_CONSTANT_POWER = 1e15
#: A power of t may not have an exponent larger than this in magnitude.
MAX_EXPONENT = 100

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


@dataclass(frozen=True)
class Token:
    """One token: ``kind`` is "number", "name", "op", "(" or ")"; ``position`` is 1-based."""

    kind: str
    text: str
    position: int


def _fail(position: int, message: str) -> ValueError:
    return ValueError(f"at character {position}: {message}")


def _unexpected(token_text: str, position: int, hint: str = ALLOWED) -> ValueError:
    shown = token_text if len(token_text) <= 20 else token_text[:17] + "..."
    return ValueError(f"unexpected {shown!r} at character {position}: {hint}")


def tokenize(text: str) -> list[Token]:
    """Split ``text`` into tokens, refusing any character or name outside the grammar."""
    if not isinstance(text, str):
        raise ValueError("the formula must be text")
    if len(text) > MAX_LENGTH:
        raise ValueError(f"the formula is {len(text)} characters long; the limit is {MAX_LENGTH}")
    tokens: list[Token] = []
    i = 0
    while i < len(text):
        char = text[i]
        position = i + 1
        if char in " \t":
            i += 1
            continue
        if char.isascii() and char.isdigit() or (char == "." and i + 1 < len(text) and text[i + 1].isascii() and text[i + 1].isdigit()):
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
                raise _unexpected(name, position, "underscores are not allowed; " + ALLOWED)
            if name != "t" and name != "pi" and name not in _FUNCTIONS:
                raise _unexpected(name, position, _NAME_HINTS.get(name, ALLOWED))
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
        raise _unexpected(char, position, _HINTS.get(char, ALLOWED))
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

    def __init__(self, tokens: list[Token], length: int) -> None:
        self.tokens = tokens
        self.index = 0
        self.end_position = length + 1
        self.depth = 0

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
            raise ValueError("the formula is empty: type an expression in t, e.g. 2*cos(t)")
        expr = self.expression()
        token = self.peek()
        if token is not None:
            raise self.unexpected_after_operand(token)
        return expr

    def unexpected_after_operand(self, token: Token) -> ValueError:
        if token.kind in ("number", "name", "("):
            return _unexpected(token.text, token.position, "a product needs an explicit *, e.g. 2*t or 3*sin(t)")
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
            if token.text == "t":
                return T
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
            raise _unexpected(")", token.position, "expected a number, t, pi, a function or '('")
        raise _unexpected(token.text, token.position, "expected a number, t, pi, a function or '(' here")

    def call(self, name: Token) -> sympy.Expr:
        opening = self.peek()
        if opening is None or opening.kind != "(":
            raise _fail(name.position, f"{name.text} needs its argument in parentheses, e.g. {name.text}(t)")
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


def _constant_value(expr: sympy.Expr, position: int) -> complex:
    value = complex(sympy.N(expr, 20))
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
    elif _is_constant(base) and _constant_value(base, position).real <= 0:
        raise _fail(position, "a power whose exponent depends on t needs a positive base, e.g. 2^t")
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
    tokens = tokenize(text)
    return _Parser(tokens, len(text)).parse()


def check_expression(text: str) -> None:
    """``Parameter.parse`` hook: raises ``ValueError`` if ``text`` is not an allowed formula."""
    parse_expression(text)
