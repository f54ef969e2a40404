"""Assemble the application: routers, static files, shared state, the scene host."""

from __future__ import annotations

from collections.abc import AsyncIterator
from contextlib import asynccontextmanager
from pathlib import Path

from fastapi import FastAPI
from fastapi.staticfiles import StaticFiles

from app import __version__
from app.api import bench, chapters, errors, examples, health, scenes
from app.course import load_catalogue
from app.scenes import SCENES
from app.scenes.host.host import SceneHost
from app.settings import Settings
from app.web import pages, relay

STATIC_DIR = Path(__file__).resolve().parent.parent / "static"


def create_app(settings: Settings | None = None) -> FastAPI:
    settings = settings or Settings.from_env()

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        host = SceneHost(SCENES, frame_rate_hz=settings.frame_rate_hz, max_sessions=settings.max_sessions)
        host.start()
        app.state.scene_host = host
        try:
            yield
        finally:
            host.stop()

    app = FastAPI(
        title="Dynamics Lab",
        version=__version__,
        summary="Interactive engineering dynamics: worked examples, solvers and live 3D scenes.",
        lifespan=lifespan,
    )
    app.state.settings = settings
    # Every lesson reference is checked here: a bad one stops the server before it starts.
    app.state.catalogue = load_catalogue(settings.lessons_dir)
    errors.install(app)
    routers = (health.router, chapters.router, scenes.router, examples.router, bench.router, pages.router, relay.router)
    for router in routers:
        app.include_router(router)
    app.mount("/static", StaticFiles(directory=STATIC_DIR), name="static")
    return app
