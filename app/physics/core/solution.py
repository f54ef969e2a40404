"""A worked solution as data: outputs, the named steps that produced them, and plots.

The same object feeds the API (JSON), the lesson's step-by-step panel (LaTeX) and
the tests (numbers), so a derivation is written once. A number that is zero up to
round-off (:data:`ROUND_OFF_RTOL` of its scale: a vector's own length unless the
solution states a scale) is 0 in it: a student reads "M_A = [0, 10179, −12413] N·m",
not "[4.5e-13, …]".
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from app.physics.core.parameters import ParameterSet

#: A number at most this fraction of its scale is zero up to round-off and is shown as 0. A worked solution's
#: arithmetic (a few products, sums, a square root) is exact to a few ulps of its scale (about 1e-16 each: the
#: robotic arm's M_A has an x component of 4.5e-13 N·m beside 1.6e4 N·m, 3e-17 of it), while a value 1e-12 of its
#: scale is already far below anything the page shows (six significant figures).
ROUND_OFF_RTOL = 1e-12


def _magnitude(value: Any) -> float:
    """The Euclidean length of all the finite numbers in ``value`` (a number, array or nested list; 0 for none)."""
    if isinstance(value, bool) or value is None or isinstance(value, str):
        return 0.0
    if isinstance(value, (int, float, np.integer, np.floating)):
        return abs(float(value)) if np.isfinite(value) else 0.0
    if isinstance(value, np.ndarray) and value.dtype.kind in "iuf":
        finite = value[np.isfinite(value)].astype(float)
        return float(np.sqrt(np.sum(finite * finite)))
    if isinstance(value, (list, tuple, np.ndarray)):
        return float(np.sqrt(sum(_magnitude(v) ** 2 for v in value)))
    return 0.0


def _zeroed(value: Any, threshold: float) -> Any:
    """``value`` with each floating-point number of magnitude at most ``threshold`` replaced by 0.0 (types kept)."""
    if isinstance(value, np.ndarray) and value.dtype.kind == "f":
        return np.where(np.abs(value) <= threshold, 0.0, value)
    if isinstance(value, (float, np.floating)):
        return type(value)(0.0) if abs(float(value)) <= threshold else value
    if isinstance(value, (list, tuple)):
        return type(value)(_zeroed(v, threshold) for v in value)
    return value  # integers are exact; words, booleans and None have no round-off


def _vector_or_matrix(value: Any) -> bool:
    """A vector or matrix of one quantity (at most 3 × 3 numbers), whose length is its components' scale; not a
    number alone, and not a sweep (a plotted series spans decades: 1e-12 s beside 2 s is no round-off)."""
    if isinstance(value, (bool, str)) or value is None:
        return False
    try:
        shape = np.shape(value)
    except ValueError:  # a ragged list
        return False
    return 1 <= len(shape) <= 2 and all(1 <= n <= 3 for n in shape)


def zero_round_off(value: Any, scale: float | None = None) -> Any:
    """``value`` (a number, an array or a nested list of them, SI) with every number within :data:`ROUND_OFF_RTOL` of
    ``scale`` replaced by exactly 0 (−0.0 included). ``scale`` None: a vector's or a matrix's (at most 3 × 3) own
    length, so a component at round-off of its vector is 0; a lone number or a sweep is kept (nothing says how large
    its numbers should be)."""
    if scale is None and not _vector_or_matrix(value):
        return value
    reference = _magnitude(value) if scale is None else abs(float(scale))
    return _zeroed(value, ROUND_OFF_RTOL * reference) if np.isfinite(reference) else value


def _plain(value: Any) -> Any:
    """Convert numpy scalars/arrays (nested) into JSON-ready Python values."""
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, Mapping):
        return {k: _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


@dataclass(frozen=True)
class Step:
    """One step of a worked solution: a title, the formula in LaTeX, and its numbers.

    ``values`` maps a symbol (as the lesson prints it) to a number or an
    ``[x, y, z]`` vector in SI units; ``units`` gives each symbol's unit.
    ``scales`` gives a symbol the magnitude its value is compared with
    (default: the value's own length): a number within round-off of its scale
    is stored as 0 (:func:`zero_round_off`).
    """

    title: str
    latex: str
    values: Mapping[str, Any] = field(default_factory=dict)
    units: Mapping[str, str] = field(default_factory=dict)
    scales: Mapping[str, float] = field(default_factory=dict, compare=False, repr=False)

    def __post_init__(self) -> None:
        shown = {name: zero_round_off(value, self.scales.get(name)) for name, value in self.values.items()}
        object.__setattr__(self, "values", shown)

    def as_dict(self) -> dict[str, Any]:
        return {"title": self.title, "latex": self.latex, "values": _plain(self.values), "units": dict(self.units)}


@dataclass(frozen=True)
class PlotSeries:
    name: str
    x: np.ndarray
    y: np.ndarray


@dataclass(frozen=True)
class Plot:
    """A 2D plot the lesson page draws (axes carry units in their labels)."""

    title: str
    x_label: str
    y_label: str
    series: tuple[PlotSeries, ...]
    log_x: bool = False
    log_y: bool = False

    def as_dict(self) -> dict[str, Any]:
        return {
            "title": self.title,
            "x_label": self.x_label,
            "y_label": self.y_label,
            "log_x": self.log_x,
            "log_y": self.log_y,
            "series": [{"name": s.name, "x": _plain(s.x), "y": _plain(s.y)} for s in self.series],
        }


@dataclass(frozen=True)
class Solution:
    """A worked solution: its ``outputs`` (by name, SI), the ``steps`` that produced them and its plots.

    ``output_scales`` gives an output the magnitude it is compared with (default: its own length); an output within
    round-off of its scale is stored as 0, as a step's values are.
    """

    outputs: Mapping[str, Any]
    steps: tuple[Step, ...]
    plots: tuple[Plot, ...] = ()
    output_scales: Mapping[str, float] = field(default_factory=dict, compare=False, repr=False)

    def __post_init__(self) -> None:
        shown = {name: zero_round_off(value, self.output_scales.get(name)) for name, value in self.outputs.items()}
        object.__setattr__(self, "outputs", shown)

    def as_dict(self) -> dict[str, Any]:
        return {
            "outputs": _plain(self.outputs),
            "steps": [s.as_dict() for s in self.steps],
            "plots": [p.as_dict() for p in self.plots],
        }


@dataclass(frozen=True)
class ExampleStory:
    """The words around a worked example's steps, in one structure (Markdown with $…$ LaTeX, in our own words):
    ``situation`` (the system and what is known), ``wanted`` (what is asked), ``approach`` (why this frame, these
    coordinates and this method, and what the alternatives would cost), ``check`` (the conservation law, limiting
    case or second method the solution's "Check" step computes) and ``what_if`` (one input to move, and what to look
    for in the scene)."""

    situation: str
    wanted: str
    approach: str
    check: str
    what_if: str

    def as_dict(self) -> dict[str, str]:
        return {
            "situation": self.situation,
            "wanted": self.wanted,
            "approach": self.approach,
            "check": self.check,
            "what_if": self.what_if,
        }


@dataclass(frozen=True)
class WorkedExample:
    """A worked example: its inputs and the function that solves it.

    ``solve`` takes validated inputs (SI; angles in degrees where the name ends in
    ``_deg``) and returns a :class:`Solution`; it raises ``ValueError`` for inputs
    that are in range but physically impossible together. ``section`` is the course section it
    belongs to (``"4.3"``) and ``story`` the words around its steps (:class:`ExampleStory`).
    """

    id: str
    title: str
    chapter: int
    inputs: ParameterSet
    solve: Callable[[Mapping[str, Any]], Solution]
    output_units: Mapping[str, str] = field(default_factory=dict)
    section: str = ""
    story: ExampleStory | None = None

    def schema(self) -> dict[str, Any]:
        return {
            "id": self.id,
            "title": self.title,
            "chapter": self.chapter,
            "section": self.section,
            "inputs": self.inputs.schema(),
            "output_units": dict(self.output_units),
            "story": self.story.as_dict() if self.story is not None else None,
        }
