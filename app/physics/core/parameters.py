"""Parameter metadata shared by worked examples, scenes and the API.

A :class:`Parameter` states a physical input once: its name (with the unit in the
name, e.g. ``tension_N``), unit, default, allowed range and a one-line
description. Scenes build their controls from it, the API builds its schema from
it, and :func:`validate_inputs` checks request data against it.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, Literal, cast


class ParameterError(ValueError):
    """An input is unknown, missing its type, non-finite or out of range.

    ``field`` names the offending input so the API can point at it; ``path``
    goes further into a structured input (``("bodies", 2, "radius_m")``) and
    defaults to ``(field,)``. ``label`` is what the page calls the input (its
    :meth:`Parameter.display_name`, e.g. ``"φ̇₀ (rad/s)"``): where given, the
    text a student reads, ``str(error)``, starts with it instead of the field's
    name, which stays in ``field`` and ``path`` for the API. ``place`` is how
    the page names the spot inside a structured input (``"body 4, radius
    (m)"``); without it the rest of the path is written out (``→ 3 → radius_m``).
    """

    def __init__(
        self, field: str, message: str, *, path: Sequence[str | int] | None = None, label: str = "", place: str = ""
    ) -> None:
        self.path: tuple[str | int, ...] = tuple(path) if path else (field,)
        subject = label or str(self.path[0])
        if place:
            subject = f"{subject}, {place}"
        elif len(self.path) > 1:
            subject = " → ".join((subject, *(str(p) for p in self.path[1:])))
        super().__init__(f"{subject}: {message}")
        self.field = field
        self.message = message
        self.label = label
        self.place = place

    def carried(self) -> tuple[str, str, tuple[str | int, ...], str, str]:
        """This error as plain data that crosses a process boundary (the scene workers, bounded work)."""
        return (self.field, self.message, self.path, self.label, self.place)

    @classmethod
    def from_carried(cls, data: Sequence[Any]) -> ParameterError:
        """The error :meth:`carried` describes, to raise again on this side of the boundary."""
        field, message, path, label, place = data
        return cls(field, message, path=path, label=label, place=place)

    def named(self, label: str, place: str = "") -> ParameterError:
        """This error with ``label`` (and ``place``) as the name a student reads (the one it has, if it has one)."""
        return (
            self if self.label else ParameterError(self.field, self.message, path=self.path, label=label, place=place)
        )


def _is_finite_float(value: int | float) -> bool:
    """Whether a JSON number is a finite float (an integer too large for a float, e.g. 400 digits, is not)."""
    try:
        return math.isfinite(float(value))
    except OverflowError:
        return False


@dataclass(frozen=True)
class Parameter:
    """One physical input.

    ``kind`` is ``"float"`` (a finite number in ``[min, max]``), ``"int"``,
    ``"choice"`` (one of ``choices``), ``"vector"`` (``length`` finite numbers,
    each in ``[min, max]``; e.g. body-frame components ``[x, y, z]``),
    ``"text"`` (a string of at most ``max_length`` characters, checked by
    ``parse``, which raises ``ValueError`` with a student-readable reason and
    never evaluates the text) or ``"list"`` (a JSON list of records, such as
    the parts of a composite body: ``parse`` checks and normalises it and
    raises :class:`ParameterError` whose ``path`` names the entry and field;
    ``item_schema`` describes the records for the API and the page). ``scale`` is a hint for controls: ``"log"``
    means a slider should move in log10 of the value, ``"symlog"`` in
    sign(v)·log10(1 + |v|) (for ranges that span zero and several decades,
    such as a spin that may be −2000 to 2000 rad/s but is usually tens).
    """

    name: str
    unit: str
    default: float | int | str | tuple[float, ...] | list
    min: float | None = None
    max: float | None = None
    description: str = ""
    label: str = ""
    kind: Literal["float", "int", "choice", "vector", "text", "list"] = "float"
    choices: tuple[str, ...] = ()
    scale: Literal["linear", "log", "symlog"] = "linear"
    step: float | None = None
    length: int = 3
    max_length: int = 200
    parse: Callable[[Any], Any] | None = field(default=None, compare=False, repr=False)
    item_schema: Any = None
    #: For a list: how the page names a spot inside it, from an error path after the parameter's name
    #: (``(3, "radius_m")`` → ``"body 4, radius (m)"``), so a refusal reads as the editor is labelled.
    item_place: Callable[[tuple[str | int, ...]], str] | None = field(default=None, compare=False, repr=False)

    def __post_init__(self) -> None:
        if self.kind == "choice":
            if self.default not in self.choices:
                raise ValueError(f"{self.name}: default {self.default!r} not in choices")
        elif self.kind == "text":
            if not isinstance(self.default, str) or len(self.default) > self.max_length:
                raise ValueError(f"{self.name}: default must be a string of at most max_length characters")
        elif self.kind == "list":
            if self.parse is None or not isinstance(self.default, list):
                raise ValueError(f"{self.name}: a list parameter needs a parse function and a list default")
            self.parse(self.default)
        elif self.kind == "vector":
            vector = cast("Sequence[float]", self.default)
            if self.min is None or self.max is None or len(vector) != self.length:
                raise ValueError(f"{self.name}: a vector needs min, max and a default of length {self.length}")
            if not all(self.min <= float(v) <= self.max for v in vector):
                raise ValueError(f"{self.name}: default components must lie in [min, max]")
        else:
            if self.min is None or self.max is None or not self.min <= cast(float, self.default) <= self.max:
                raise ValueError(f"{self.name}: default must lie in [min, max]")
            if self.scale == "log" and self.min <= 0:
                raise ValueError(f"{self.name}: a log-scale parameter needs min > 0")

    def display_name(self) -> str:
        """What the page calls this input: its control's label, then its unit in brackets (``"φ̇₀ (rad/s)"``)."""
        label = self.label or self.name
        return f"{label} ({self.unit})" if self.unit else label

    def range_text(self) -> str:
        if self.kind == "choice":
            return "one of " + ", ".join(repr(c) for c in self.choices)
        if self.kind == "text":
            return f"text of at most {self.max_length} characters"
        if self.kind == "list":
            return "a list of records"
        unit = f" {self.unit}" if self.unit else ""
        return f"between {self.min:g} and {self.max:g}{unit}"

    def validate(self, value: Any) -> Any:
        """Return ``value`` converted to this parameter's type, or raise ParameterError."""
        if self.kind == "choice":
            if not isinstance(value, str) or value not in self.choices:
                raise self._refusal(f"must be {self.range_text()}")
            return value
        if self.kind == "text":
            return self._validate_text(value)
        if self.kind == "list":
            assert self.parse is not None
            try:
                return self.parse(value)
            except ParameterError as exc:
                inside = exc.path[1:]
                raise exc.named(
                    self.display_name(), self.item_place(inside) if self.item_place and inside else ""
                ) from None
        if self.kind == "vector":
            return self._validate_vector(value)
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self._refusal(f"must be a number {self.range_text()}")
        if not _is_finite_float(value):
            raise self._refusal(f"must be a finite number {self.range_text()}")
        if self.kind == "int":
            if float(value) != int(value):
                raise self._refusal("must be a whole number")
            value = int(value)
        else:
            value = float(value)
        assert self.min is not None and self.max is not None
        if not self.min <= value <= self.max:
            raise self._refusal(f"must be {self.range_text()} (got {value:g})")
        return value

    def _refusal(self, message: str) -> ParameterError:
        """A :class:`ParameterError` for this input, naming it as the page does."""
        return ParameterError(self.name, message, label=self.display_name())

    def _validate_text(self, value: Any) -> str:
        if not isinstance(value, str):
            raise self._refusal("must be text")
        if len(value) > self.max_length:
            raise self._refusal(f"is {len(value)} characters long; the limit is {self.max_length}")
        if self.parse is not None:
            try:
                self.parse(value)
            except ValueError as exc:
                raise self._refusal(str(exc)) from None
        return value

    def _validate_vector(self, value: Any) -> list[float]:
        if not isinstance(value, (list, tuple)) or len(value) != self.length:
            raise self._refusal(f"must be a list of {self.length} numbers, each {self.range_text()}")
        out = []
        for index, component in enumerate(value):
            if (
                isinstance(component, bool)
                or not isinstance(component, (int, float))
                or not _is_finite_float(component)
            ):
                raise self._refusal(f"component {index} must be a finite number {self.range_text()}")
            assert self.min is not None and self.max is not None
            if not self.min <= component <= self.max:
                raise self._refusal(f"component {index} must be {self.range_text()} (got {component:g})")
            out.append(float(component))
        return out

    def schema(self) -> dict[str, Any]:
        """JSON description used by the API and by the page that draws controls."""
        out: dict[str, Any] = {
            "name": self.name,
            "label": self.label or self.name,
            "unit": self.unit,
            "default": self.default,
            "description": self.description,
            "kind": self.kind,
        }
        if self.kind == "choice":
            out["choices"] = list(self.choices)
        elif self.kind == "text":
            out["max_length"] = self.max_length
        elif self.kind == "list":
            out["item_schema"] = self.item_schema
        else:
            if self.kind == "vector":
                out["length"] = self.length
            out.update(min=self.min, max=self.max, scale=self.scale)
            if self.step is not None:
                out["step"] = self.step
        return out


@dataclass(frozen=True)
class ParameterSet:
    """An ordered collection of parameters with whole-request validation.

    ``check`` (optional) receives the complete validated values and raises
    ``ValueError`` for combinations that are each in range but impossible
    together (e.g. a cable of zero length).
    """

    parameters: Sequence[Parameter]
    check: Callable[[Mapping[str, Any]], object] | None = None
    by_name: Mapping[str, Parameter] = field(init=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "by_name", {p.name: p for p in self.parameters})

    def defaults(self) -> dict[str, Any]:
        return {
            p.name: list(cast("Sequence[float]", p.default))
            if p.kind == "vector"
            else copy.deepcopy(p.default)
            if p.kind == "list"
            else p.default
            for p in self.parameters
        }

    def validate(self, raw: Mapping[str, Any] | None, *, base: Mapping[str, Any] | None = None) -> dict[str, Any]:
        """Validate ``raw`` and fill the rest from ``base`` (default: the defaults).

        Unknown names are rejected rather than ignored, so a typo never passes
        silently. Raises :class:`ParameterError` naming the first bad field.
        """
        values = dict(base) if base is not None else self.defaults()
        for name, value in (raw or {}).items():
            parameter = self.by_name.get(name)
            if parameter is None:
                known = ", ".join(self.by_name)
                raise ParameterError(name, f"unknown input; expected one of: {known}")
            values[name] = parameter.validate(value)
        if self.check is not None:
            try:
                self.check(values)
            except ParameterError as exc:  # a combination refused: name its field as the page does
                parameter = self.by_name.get(exc.field)
                if parameter is None:
                    raise
                raise exc.named(parameter.display_name()) from None
        return values

    def schema(self) -> list[dict[str, Any]]:
        return [p.schema() for p in self.parameters]
