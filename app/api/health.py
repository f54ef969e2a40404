from __future__ import annotations

from typing import Any

from fastapi import APIRouter, Request

from app import __version__
from app.api.schemas.health import Health

router = APIRouter(prefix="/api", tags=["health"])


@router.get("/health", response_model=Health, response_model_exclude_none=True)
async def health(request: Request) -> dict[str, Any]:
    """Liveness check with the running version, and each scene worker's state as the front last saw it.

    Answered on the event loop itself from what the front already knows: it never waits for a thread or a scene
    worker, so it answers at once however busy or stopped a worker is."""
    host = getattr(request.app.state, "scene_host", None)
    workers = host.worker_states() if host is not None else None
    return {"status": "ok", "version": __version__, "workers": workers}
