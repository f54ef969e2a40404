from __future__ import annotations

from fastapi import APIRouter

from app import __version__
from app.api.schemas.health import Health

router = APIRouter(prefix="/api", tags=["health"])


@router.get("/health", response_model=Health)
def health() -> dict[str, str]:
    """Liveness check with the running version."""
    return {"status": "ok", "version": __version__}
