"""The practice routes' shared state: the exercise book and the progress store, as FastAPI dependencies."""

from __future__ import annotations

from typing import Annotated

from fastapi import Depends
from starlette.requests import HTTPConnection

from app.practice.book import ExerciseBook
from app.practice.progress import SqlProgressStore


def get_book(request: HTTPConnection) -> ExerciseBook:
    return request.app.state.exercises


def get_progress(request: HTTPConnection) -> SqlProgressStore | None:
    return request.app.state.progress


BookDep = Annotated[ExerciseBook, Depends(get_book)]
ProgressDep = Annotated[SqlProgressStore | None, Depends(get_progress)]
