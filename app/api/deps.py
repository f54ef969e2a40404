"""Shared state for route handlers, injected with ``Annotated[..., Depends()]``."""

from __future__ import annotations

from typing import Annotated

from fastapi import Depends
from starlette.requests import HTTPConnection

from app.api.session_keys import SessionKeys
from app.course import Catalogue
from app.scenes.host.host import SceneHost
from app.scenes.host.pool import WorkerPool
from app.settings import Settings


def get_catalogue(request: HTTPConnection) -> Catalogue:
    return request.app.state.catalogue


def get_scene_host(request: HTTPConnection) -> SceneHost | WorkerPool:
    """The scenes: one in-process host, or the pool of scene workers (``Settings.workers``); same interface."""
    return request.app.state.scene_host


def get_session_keys(request: HTTPConnection) -> SessionKeys:
    return request.app.state.session_keys


def get_settings(request: HTTPConnection) -> Settings:
    return request.app.state.settings


CatalogueDep = Annotated[Catalogue, Depends(get_catalogue)]
SceneHostDep = Annotated[SceneHost | WorkerPool, Depends(get_scene_host)]
SettingsDep = Annotated[Settings, Depends(get_settings)]
SessionKeysDep = Annotated[SessionKeys, Depends(get_session_keys)]
