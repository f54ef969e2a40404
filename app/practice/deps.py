"""The practice routes' shared state: the exercise book, the progress store and the rooms' record of their students'
work, as FastAPI dependencies."""

from __future__ import annotations

from typing import Annotated

from fastapi import Depends
from starlette.requests import HTTPConnection

from app.practice.book import ExerciseBook
from app.practice.progress import SqlProgressStore, SqlRoomWorkStore


def get_book(request: HTTPConnection) -> ExerciseBook:
    return request.app.state.exercises


def get_progress(request: HTTPConnection) -> SqlProgressStore | None:
    return request.app.state.progress


def get_room_work(request: HTTPConnection) -> SqlRoomWorkStore | None:
    return request.app.state.room_work


BookDep = Annotated[ExerciseBook, Depends(get_book)]
RoomWorkDep = Annotated[SqlRoomWorkStore | None, Depends(get_room_work)]
ProgressDep = Annotated[SqlProgressStore | None, Depends(get_progress)]
