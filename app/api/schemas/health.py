"""``GET /api/health``."""

from __future__ import annotations

from typing import Literal

from pydantic import BaseModel, Field


class WorkerState(BaseModel):
    index: int
    state: Literal["answering", "not answering", "restarting"]


class Health(BaseModel):
    status: str
    version: str
    workers: list[WorkerState] | None = Field(
        None, description="Each scene worker's state (empty when the scenes run in the front process)"
    )
