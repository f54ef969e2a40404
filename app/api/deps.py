"""Shared state for route handlers, injected with ``Annotated[..., Depends()]``."""

from __future__ import annotations

from collections.abc import Callable
from typing import Annotated, Any

from fastapi import Depends
from starlette.requests import HTTPConnection

from app.api.access import SessionDirectory
from app.api.rate_limit import client_address
from app.course import Catalogue
from app.scenes.host.interface import SceneHostInterface
from app.settings import Settings


def get_catalogue(request: HTTPConnection) -> Catalogue:
    return request.app.state.catalogue


def get_scene_host(request: HTTPConnection) -> SceneHostInterface:
    """The scenes: one in-process host, or the pool of scene workers (``Settings.workers``); same interface."""
    return request.app.state.scene_host


def get_sessions(request: HTTPConnection) -> SessionDirectory:
    """Page sessions: who owns each, its viewers, the per-client bounds (:mod:`app.api.access`)."""
    return request.app.state.sessions


def get_client(request: HTTPConnection) -> str | None:
    """The client's address, the key of every per-client limit (None for an in-process caller)."""
    return client_address(request.scope, trust_forwarded_for=request.app.state.settings.trust_forwarded_for)


def get_settings(request: HTTPConnection) -> Settings:
    return request.app.state.settings


def get_explore_start(request: HTTPConnection) -> Callable[[str, str], dict[str, Any]]:
    """Where a classroom room's explorers start, ``(room_id, scene_id) → {"params", "motion", …}`` or a ValueError
    saying why not: the classroom's :meth:`~app.classroom.registry.Rooms.explore_start` (asked, never imported)."""
    return request.app.state.rooms.explore_start


CatalogueDep = Annotated[Catalogue, Depends(get_catalogue)]
SceneHostDep = Annotated[SceneHostInterface, Depends(get_scene_host)]
SettingsDep = Annotated[Settings, Depends(get_settings)]
SessionsDep = Annotated[SessionDirectory, Depends(get_sessions)]
ClientDep = Annotated[str | None, Depends(get_client)]
ExploreStartDep = Annotated[Callable[[str, str], dict[str, Any]], Depends(get_explore_start)]
