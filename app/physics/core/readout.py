"""Typed readouts: the numbers a student reads beside a scene, with names and units.

A :class:`Readout` is what ``GET /api/scenes/{id}/sessions/{sid}/live`` returns
under ``readout`` and what the lesson page draws as a table. Numbers stay
numbers: a quantity's ``value`` is a finite float in ``unit`` (SI, or degrees
where the name ends in ``_deg``) or ``None`` where it is undefined at this
instant, in which case ``text`` says why ("undefined (gimbal lock)"). A
quantity whose value is a word (a locus shape, a direction of precession) has
``value`` ``None`` and the word in ``text``. Time is always named ``t_s``.
A ``None`` value keeps its quantity's ``unit`` (what the number is in when
there is one); pages show a text value without it, unless the text is numbers
in that unit (``text_in_unit``: a vector's components).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any


@dataclass(frozen=True)
class Quantity:
    """One row of a readout.

    ``name`` is the stable id tests and pages find the row by (with the unit in
    it, e.g. ``theta_max_deg``); ``label`` is what the student reads (words and
    symbol); ``value`` is a finite number in ``unit`` or ``None``; ``text``
    explains a ``None`` or carries a value that is a word. ``text_in_unit``: the
    text carries numbers in ``unit`` (a vector's components), so pages show the
    unit beside it as beside a number; any other text is shown without it.
    """

    name: str
    label: str
    value: float | None
    unit: str = ""
    text: str = ""
    text_in_unit: bool = False

    def __post_init__(self) -> None:
        value = self.value
        if value is not None:
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise TypeError(
                    f"readout {self.name}: value must be a number or None (got {value!r}); put words in text"
                )
            value = float(value)
            if not math.isfinite(value):
                object.__setattr__(self, "text", self.text or "undefined")
                value = None
            object.__setattr__(self, "value", value)

    @classmethod
    def word(cls, name: str, label: str, text: str) -> Quantity:
        """A quantity whose value is a word (a locus shape, a direction)."""
        return cls(name, label, None, "", text)

    @classmethod
    def or_text(cls, name: str, label: str, value: float | None, unit: str, text: str) -> Quantity:
        """``value`` in ``unit`` where it is a finite number; otherwise no value, and ``text`` says why."""
        finite = value is not None and math.isfinite(value)
        return cls(name, label, float(value) if finite and value is not None else None, unit, "" if finite else text)

    def as_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {"name": self.name, "label": self.label, "value": self.value, "unit": self.unit}
        if self.text:
            out["text"] = self.text
        if self.text_in_unit:
            out["text_in_unit"] = True
        return out


@dataclass(frozen=True)
class Mark:
    """A labelled tick on a control's slider, at ``value`` in that control's unit."""

    value: float
    label: str

    def as_dict(self) -> dict[str, Any]:
        return {"value": float(self.value), "label": self.label}


@dataclass(frozen=True)
class Readout:
    """A scene's readout: quantities, marks on controls (by parameter name), a message."""

    quantities: Sequence[Quantity] = ()
    marks: Mapping[str, Sequence[Mark]] = field(default_factory=dict)
    message: str = ""

    def __post_init__(self) -> None:
        names = [q.name for q in self.quantities]
        duplicated = sorted({n for n in names if names.count(n) > 1})
        if duplicated:
            raise ValueError(f"readout quantities must have distinct names (repeated: {', '.join(duplicated)})")

    def value(self, name: str) -> float | None:
        """The value of the quantity ``name`` (KeyError if there is none)."""
        for quantity in self.quantities:
            if quantity.name == name:
                return quantity.value
        raise KeyError(name)

    def as_dict(self) -> dict[str, Any]:
        return {
            "quantities": [q.as_dict() for q in self.quantities],
            "marks": {name: [m.as_dict() for m in marks] for name, marks in self.marks.items()},
            "message": self.message,
        }
