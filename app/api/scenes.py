from __future__ import annotations

from typing import Any

from fastapi import APIRouter, HTTPException
from pydantic import BaseModel, ConfigDict, Field

from app.api.deps import SceneHostDep
from app.scenes.host import UnknownSceneError

router = APIRouter(prefix="/api/scenes", tags=["scenes"])


class SessionParamsRequest(BaseModel):
    model_config = ConfigDict(extra="forbid")
    params: dict[str, Any] = Field(default_factory=dict, description="Parameters to change; others keep their values")


@router.get("")
def list_scenes(host: SceneHostDep) -> list[dict[str, Any]]:
    """Every scene's id, title, chapter and parameter schema."""
    return [cls.schema() for cls in host.scenes.values()]


@router.put("/{scene_id}/sessions/{session_id}")
def set_session_params(scene_id: str, session_id: str, request: SessionParamsRequest, host: SceneHostDep) -> dict[str, Any]:
    """Set the parameters of one page's scene; every viewer of that session redraws.

    Bad input gets a 422 naming the field and changes nothing.
    """
    try:
        params = host.set_params(scene_id, session_id, request.params)
    except UnknownSceneError:
        raise HTTPException(status_code=404, detail=f"no scene {scene_id!r}") from None
    return {"scene_id": scene_id, "session_id": session_id, "params": params, "viewers": host.viewer_count(session_id)}
