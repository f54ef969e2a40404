"""What a derivation shows, simplified for reading within a time bound; what it computes is never touched.

The formulations print their expressions (steps, equations, M and f) with
:func:`print_latex`. Inside :func:`shown_forms` it records each expression and
returns a token in its place; :meth:`ShownForms.simplify` then simplifies every
expression shown, trigonometrically (sympy's ``cancel`` then ``trigsimp``,
written out term by term where that reads shorter), and :meth:`ShownForms.fill`
puts each one's LaTeX where its token stood: the heavy top's Routh equation
showed 17 terms of ``(I_a β_φ − I_a β_ψ cos θ)…/sin⁴θ`` where one fraction of
five terms says it, the rolling disk's Kane equations left
``r² sin²ψ + r² cos²ψ`` and a typed pendulum on a moving support
``(2 l² sin² q₁ + 2 l² cos² q₁)/2``.

The recipe (what the right-hand side computes) is built from the unsimplified
expressions before any of this and generated into code first
(:func:`~app.physics.mechanics.engine.derived`), so the numbers never depend on
what is shown. Each expression is simplified only if that reads shorter (its
LaTeX is shorter), and only within time: a leaf gets :data:`SIMPLIFY_EACH_S`
of processor time, all of one derivation's :data:`SIMPLIFY_TOTAL_S`; past either
it is shown unsimplified. The work runs in a bounded child process
(:class:`~app.physics.core.bounded.BoundedRunner`: wall clock, memory), each leaf
bounded there by a processor-time timer (``ITIMER_PROF``: a child the busy server
pauses or starves is not out of time, it is refused as busy, and what is shown is
then not stored, so another process simplifies it again); a derivation that
already runs in such a child (a typed Lagrangian's) simplifies in place, bounded
by the same timer, within :data:`SIMPLIFY_TOTAL_IN_CHILD_S` of its own limit.

A *leaf* is what is simplified on its own: an element of a matrix, the right side
of an equation and each term of its left side (a coefficient times an unknown,
kept as one term per unknown), or an expression. Equal leaves are simplified once.
"""

from __future__ import annotations

import contextlib
import contextvars
import multiprocessing
import re
import signal
import threading
import time
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import sympy

from app.physics.core.bounded import BoundedRunner

__all__ = [
    "SIMPLIFY_EACH_S",
    "SIMPLIFY_TOTAL_IN_CHILD_S",
    "SIMPLIFY_TOTAL_S",
    "ShownForms",
    "SimplifyOutcome",
    "display_leaves",
    "print_latex",
    "readable",
    "rebuilt",
    "shown_forms",
    "simplify_leaves",
]

#: Most processor time (s) one leaf may take: the largest of the catalogue's (the heavy top's Routh equation, the
#: rolling disk's Kane forcing) take 0.5–0.8 s on this machine.
SIMPLIFY_EACH_S = 3.0
#: Most processor time (s) all of one derivation's shown leaves may take; the rest is shown unsimplified.
SIMPLIFY_TOTAL_S = 12.0
#: The same inside a typed Lagrangian's bounded child, which has 20 s for everything.
SIMPLIFY_TOTAL_IN_CHILD_S = 4.0
#: The child's wall-clock limit beyond SIMPLIFY_TOTAL_S (starting, pickling the leaves there and back) and its memory.
CHILD_MARGIN_S = 8.0
CHILD_MEMORY_MB = 512.0
#: How long a derivation waits for one of the two simplification slots (s): a lesson page asks for all its
#: derivations at once (lesson 9.3: twelve), and from a cold cache each simplification takes a few seconds.
SLOT_WAIT_S = 120.0

_TOKEN = "⟦shown {}⟧"
_TOKEN_PATTERN = re.compile(r"⟦shown (\d+)⟧")
_collecting: contextvars.ContextVar[ShownForms | None] = contextvars.ContextVar("shown_forms", default=None)

#: One runner per process for the simplification children; the same preload as the typed derivations' runner, so the
#: forkserver both share (one per process) starts their children warm whichever starts it.
runner = BoundedRunner(
    max_jobs=2,
    timeout_s=SIMPLIFY_TOTAL_S + CHILD_MARGIN_S,
    memory_mb=CHILD_MEMORY_MB,
    wait_s=SLOT_WAIT_S,
    preload=("app.physics.core.bounded", "numpy", "sympy", "app.physics.mechanics.typed"),
)


def print_latex(expr: Any, names: Mapping[Any, str]) -> str:
    """LaTeX of ``expr`` with the page's symbol names; inside :func:`shown_forms`, a token its LaTeX replaces later."""
    forms = _collecting.get()
    if forms is None:
        return sympy.latex(expr, symbol_names=dict(names))
    return forms.add(expr, names)


@contextlib.contextmanager
def shown_forms() -> Iterator[ShownForms]:
    """Record what :func:`print_latex` prints in this context (this thread's) and hand it back to simplify and fill."""
    forms = ShownForms()
    reset = _collecting.set(forms)
    try:
        yield forms
    finally:
        _collecting.reset(reset)


def display_leaves(expr: Any) -> Iterator[sympy.Expr]:
    """The leaves of ``expr`` (see the module docstring), in order; nothing for a number or a truth value."""
    if isinstance(expr, sympy.MatrixBase):
        for element in expr:
            yield from display_leaves(element)
    elif isinstance(expr, sympy.Equality):
        yield from (term for term in sympy.Add.make_args(expr.lhs) if _worth_simplifying(term))
        if _worth_simplifying(expr.rhs):
            yield expr.rhs
    elif _worth_simplifying(expr):
        yield expr


def _worth_simplifying(expr: Any) -> bool:
    return isinstance(expr, sympy.Expr) and expr.has(sympy.sin, sympy.cos, sympy.tan)


def rebuilt(expr: Any, leaves: Mapping[sympy.Expr, sympy.Expr]) -> Any:
    """``expr`` with each leaf replaced by ``leaves[leaf]`` where given (the same shape: a matrix, an equation…)."""
    if isinstance(expr, sympy.MatrixBase):
        return expr.applyfunc(lambda element: rebuilt(element, leaves))
    if isinstance(expr, sympy.Equality):
        left = sympy.Add(*(leaves.get(term, term) for term in sympy.Add.make_args(expr.lhs)))
        return sympy.Eq(left, leaves.get(expr.rhs, expr.rhs), evaluate=False)
    return leaves.get(expr, expr) if isinstance(expr, sympy.Expr) else expr


def _length(expr: sympy.Expr) -> int:
    return len(sympy.latex(expr))


def _candidates(expr: sympy.Expr) -> Iterator[sympy.Expr]:
    """Simplified forms of ``expr``: over a common denominator (``cancel``) then ``trigsimp``, and that written out
    term by term (``expand``). (``trigsimp`` of ``expr`` as it is was no shorter on the catalogue and took 2–5 times
    as long: 8.6 s instead of 1.7 s for the rolling disk's Kane equations.)"""
    combined = sympy.trigsimp(sympy.cancel(expr))
    yield combined
    yield sympy.expand(combined)


def readable(expr: sympy.Expr, best: list[sympy.Expr] | None = None) -> sympy.Expr | None:
    """The form of ``expr`` among its trigonometric simplifications whose LaTeX is shortest, if shorter than its own;
    None if none is. Unbounded: :func:`simplify_leaves` runs it under a timer, and ``best`` (a list) then holds the
    best form found so far when the timer stops it."""
    found = best if best is not None else []
    shortest = _length(expr)
    for form in _candidates(expr):
        length = _length(form)
        if length < shortest:
            found[:] = [form]
            shortest = length
    return found[0] if found else None


@dataclass(frozen=True)
class SimplifyOutcome:
    """How one derivation's shown leaves fared: simplified (shorter), kept (nothing shorter), out of time (their
    own :data:`SIMPLIFY_EACH_S`, or the derivation's total), and the processor seconds it all took; ``refused`` says
    why no simplification ran at all (the child could not start, was busy or was stopped), empty otherwise."""

    simplified: int = 0
    kept: int = 0
    out_of_time: int = 0
    seconds: float = 0.0
    refused: str = ""

    def as_dict(self) -> dict[str, Any]:
        return {
            "simplified": self.simplified,
            "kept": self.kept,
            "out_of_time": self.out_of_time,
            "seconds": round(self.seconds, 3),
            "refused": self.refused,
        }


class _OutOfTime(Exception):
    """Raised by the processor-time timer's signal inside :func:`simplify_leaves`."""


def _out_of_time(signum: int, frame: Any) -> None:
    raise _OutOfTime


def simplify_leaves(
    leaves: Sequence[sympy.Expr], each_s: float = SIMPLIFY_EACH_S, total_s: float = SIMPLIFY_TOTAL_S
) -> tuple[list[sympy.Expr | None], SimplifyOutcome]:
    """:func:`readable` of each leaf (None: kept as it is), each within ``each_s`` and all within ``total_s`` (s of
    this process's processor time, by ``ITIMER_PROF``: only in a process's main thread; elsewhere nothing is
    simplified). ``outcome.seconds`` is the processor time it took."""
    results: list[sympy.Expr | None] = [None] * len(leaves)
    if threading.current_thread() is not threading.main_thread():
        return results, SimplifyOutcome(kept=len(leaves), refused="not in a main thread: no timer to bound it")
    start = time.process_time()
    simplified = kept = out_of_time = 0
    previous = signal.signal(signal.SIGPROF, _out_of_time)
    try:
        for index, leaf in enumerate(leaves):
            left_s = total_s - (time.process_time() - start)
            if left_s <= 0.0:
                out_of_time += len(leaves) - index
                break
            best: list[sympy.Expr] = []
            bounded_by_total = left_s <= each_s
            signal.setitimer(signal.ITIMER_PROF, min(each_s, left_s))
            try:
                results[index] = readable(leaf, best)
            except _OutOfTime:  # the best form found before the timer went off, if any
                results[index] = best[0] if best else None
                out_of_time += 1
                if bounded_by_total:  # the total is spent, whatever process_time reads a tick later
                    out_of_time += len(leaves) - index - 1
                    break
                continue
            finally:
                signal.setitimer(signal.ITIMER_PROF, 0.0)
            if results[index] is None:
                kept += 1
            else:
                simplified += 1
    finally:
        signal.setitimer(signal.ITIMER_PROF, 0.0)
        signal.signal(signal.SIGPROF, previous)
    return results, SimplifyOutcome(simplified, kept, out_of_time, time.process_time() - start)


class ShownForms:
    """The expressions one derivation printed (:func:`print_latex` inside :func:`shown_forms`), their simplified
    leaves once :meth:`simplify` has run, and :meth:`fill` to turn tokens into LaTeX."""

    def __init__(self) -> None:
        self.items: list[tuple[Any, dict[Any, str]]] = []
        self.simplified: dict[sympy.Expr, sympy.Expr] = {}
        self.outcome = SimplifyOutcome()

    def add(self, expr: Any, names: Mapping[Any, str]) -> str:
        self.items.append((expr, dict(names)))
        return _TOKEN.format(len(self.items) - 1)

    def leaves(self) -> list[sympy.Expr]:
        """Every distinct leaf of the printed expressions, in the order printed."""
        return list(dict.fromkeys(leaf for expr, _ in self.items for leaf in display_leaves(expr)))

    def simplify(self) -> SimplifyOutcome:
        """Simplify the leaves, bounded (see the module docstring); a child that cannot run or is stopped leaves them
        all as they are (``outcome.refused`` says why)."""
        leaves = self.leaves()
        if not leaves:
            return self.outcome
        if multiprocessing.current_process().daemon:  # already a bounded child (a typed derivation): bound it here
            results, outcome = simplify_leaves(leaves, SIMPLIFY_EACH_S, SIMPLIFY_TOTAL_IN_CHILD_S)
        else:
            try:
                results, outcome = runner.run(
                    simplify_leaves, (leaves, SIMPLIFY_EACH_S, SIMPLIFY_TOTAL_S), what="simplifying what is shown"
                )
            except Exception as exc:  # noqa: BLE001 - busy, stopped or refused: shown as derived, never an error
                results, outcome = [None] * len(leaves), SimplifyOutcome(kept=len(leaves), refused=str(exc))
        self.simplified = {leaf: result for leaf, result in zip(leaves, results) if result is not None}
        self.outcome = outcome
        return outcome

    def original(self, index: int) -> Any:
        """The expression printed as token ``index``, as derived."""
        return self.items[index][0]

    def displayed(self, index: int) -> Any:
        """The expression shown for token ``index``: simplified where :meth:`simplify` found a shorter form."""
        return rebuilt(self.items[index][0], self.simplified)

    def fill(self, text: str) -> str:
        """``text`` with each token replaced by the LaTeX of the expression :meth:`displayed` for it."""

        def latex(match: re.Match[str]) -> str:
            index = int(match.group(1))
            return sympy.latex(self.displayed(index), symbol_names=self.items[index][1])

        return _TOKEN_PATTERN.sub(latex, text)
