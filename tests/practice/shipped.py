"""The shipped exercises (``lessons/chNN/exercises/*.md``), parsed once per test process: eight test files check them,
and each parse of all of them costs about 0.15 s of every xdist worker's collection."""

from __future__ import annotations

from pathlib import Path

from app.practice.exercise import load_exercises

LESSONS = Path(__file__).resolve().parents[2] / "lessons"
EXERCISES = load_exercises(LESSONS)
