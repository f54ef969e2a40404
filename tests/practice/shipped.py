"""The shipped exercises (``lessons/chNN/exercises/*.md``), parsed once per test process for every test file that
checks them: each parse of all of them cost about 0.15 s of every xdist worker's collection, eight times over."""

from __future__ import annotations

from pathlib import Path

from app.practice.exercise import load_exercises

LESSONS = Path(__file__).resolve().parents[2] / "lessons"
EXERCISES = load_exercises(LESSONS)
