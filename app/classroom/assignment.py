"""Exercises the instructor assigns a room (issue 27, point 7): which ones, whether the whole class works on one set of
numbers, and whether the instructor's view of the results shows names.

The room keeps the assignment as data (with its state and record); the practice package (:mod:`app.practice.in_room`)
checks the exercise ids, draws the class's numbers and keeps and reads the students' work.
"""

from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from datetime import UTC, datetime
from typing import Any

#: Most exercises one assignment holds (a section has three to five; an instructor may pick across sections).
MAX_ASSIGNED = 24


@dataclass(frozen=True)
class Assignment:
    """``exercise_ids`` in the order shown; ``class_seed`` gives every student the same numbers (None: each works on
    their own); ``show_names``: the results name the students (else "student 3"); ``assigned_at`` in UTC seconds."""

    exercise_ids: tuple[str, ...]
    class_seed: int | None = None
    show_names: bool = False
    assigned_at: float = field(default_factory=time.time)

    def record(self) -> dict[str, Any]:
        return {
            "exercise_ids": list(self.exercise_ids),
            "class_seed": self.class_seed,
            "show_names": self.show_names,
            "assigned_at": self.assigned_at,
        }

    @classmethod
    def from_record(cls, record: Mapping[str, Any]) -> Assignment:
        return cls(
            exercise_ids=tuple(record["exercise_ids"]),
            class_seed=record["class_seed"],
            show_names=bool(record["show_names"]),
            assigned_at=float(record["assigned_at"]),
        )

    def public(self) -> dict[str, Any]:
        """What every page of the room sees: the exercises, whether the class shares its numbers (never the seed)."""
        return {
            "exercise_ids": list(self.exercise_ids),
            "class_variant": self.class_seed is not None,
            "assigned_at": datetime.fromtimestamp(self.assigned_at, UTC).strftime("%Y-%m-%dT%H:%M:%SZ"),
        }
