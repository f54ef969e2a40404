"""Expensive reference solutions, computed once and stored beside this file; the fast tests load them.

A reference is a :class:`StoredReference`: a name, the inputs it was computed from (JSON), a
``compute`` function (the expensive, independent computation: sympy derivations, DOP853 at tight
tolerances) and ``atol``, how far a fresh computation may differ from the stored numbers.

The file ``<name>.json`` holds::

    {"format": "dynlab-reference/1", "name": ..., "note": how it was computed,
     "inputs": {...}, "atol": ..., "arrays": {series name: nested lists of float}}

Floats are written as Python's shortest round-trip repr, so loading gives back the exact
float64 numbers that were computed. ``load()`` refuses a file whose inputs differ from the
current ones (a test changed its case: regenerate). The tests marked ``slow`` (``pytest -m
slow``) call ``check_against_fresh_computation()``: recompute from scratch and compare with the
file; with ``DYNLAB_REGENERATE_REFERENCES=1`` they rewrite the file instead.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

FORMAT = "dynlab-reference/1"
REFERENCE_DIR = Path(__file__).resolve().parent
REGENERATE_ENV = "DYNLAB_REGENERATE_REFERENCES"


def _plain(value):
    """``value`` as JSON data: arrays and tuples become lists, numpy scalars become floats."""
    return json.loads(json.dumps(value, default=lambda v: v.tolist() if hasattr(v, "tolist") else str(v)))


@dataclass(frozen=True)
class StoredReference:
    """One expensive reference: ``compute(inputs) -> {series: array}``, stored as ``<name>.json``."""

    name: str
    note: str
    inputs: Mapping
    compute: Callable[[Mapping], Mapping[str, np.ndarray]]
    #: Largest allowed |fresh − stored| of any entry when the reference is recomputed (same units as the series).
    atol: float

    @property
    def path(self) -> Path:
        return REFERENCE_DIR / f"{self.name}.json"

    def load(self) -> dict[str, np.ndarray]:
        """The stored series as float arrays; AssertionError if the stored inputs are not ``self.inputs``."""
        stored = json.loads(self.path.read_text())
        assert stored["format"] == FORMAT, f"{self.path.name}: unknown format {stored['format']!r}"
        assert stored["inputs"] == _plain(self.inputs), (
            f"{self.path.name} was computed for other inputs than the test's: "
            f"run `{REGENERATE_ENV}=1 pytest -m slow` to recompute it"
        )
        return {name: np.asarray(values, dtype=float) for name, values in stored["arrays"].items()}

    def write(self, arrays: Mapping[str, np.ndarray]) -> None:
        """Store ``arrays`` with this reference's inputs and note."""
        document = {
            "format": FORMAT, "name": self.name, "note": self.note, "inputs": _plain(self.inputs), "atol": self.atol,
            "arrays": {name: np.asarray(values, dtype=float).tolist() for name, values in arrays.items()},
        }
        self.path.write_text(json.dumps(document, separators=(",", ":")) + "\n")

    def check_against_fresh_computation(self) -> None:
        """Recompute from scratch; assert every series agrees with the stored one to ``atol``.

        With ``DYNLAB_REGENERATE_REFERENCES=1`` (or when no file exists yet) the fresh numbers are written instead.
        """
        fresh = {name: np.asarray(values, dtype=float) for name, values in self.compute(self.inputs).items()}
        assert all(np.all(np.isfinite(values)) for values in fresh.values()), f"{self.name}: non-finite reference"
        if os.environ.get(REGENERATE_ENV) == "1" or not self.path.exists():
            self.write(fresh)
        stored = self.load()
        assert stored.keys() == fresh.keys(), (self.name, sorted(stored), sorted(fresh))
        for name, values in fresh.items():
            assert stored[name].shape == values.shape, (self.name, name, stored[name].shape, values.shape)
            difference = float(np.max(np.abs(stored[name] - values), initial=0.0))
            assert difference <= self.atol, f"{self.name}/{name}: recomputed differs from stored by {difference:.2e} > {self.atol:.0e}"
