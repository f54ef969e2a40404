"""Assemble the application: routers, static files, shared state, the scene host."""

from __future__ import annotations

import logging
from collections.abc import AsyncIterator, Callable
from contextlib import asynccontextmanager

from fastapi import FastAPI
from fastapi.openapi.docs import get_swagger_ui_html
from fastapi.responses import HTMLResponse
from fastapi.staticfiles import StaticFiles

from app import __version__
from app.api import bench, chapters, errors, examples, health, scenes, systems
from app.api.access import SessionDirectory
from app.api.kept_sessions import SqlSessionStore
from app.classroom import pages as room_pages
from app.classroom import relay as room_relay
from app.classroom import routes as rooms
from app.classroom.hub import RoomHub
from app.classroom.join_limits import JoinLimits
from app.classroom.page_config import classroom_page_config
from app.classroom.ready_questions import DEFAULT_READY_QUESTIONS, load_ready_questions
from app.classroom.registry import Rooms
from app.classroom.roles import InstructorKey, kept_instructor_secret
from app.classroom.room import Room, RoomError
from app.classroom.store import SqlRoomStore
from app.classroom.sync import ClassSync
from app.course import load_catalogue
from app.physics.core.bounded import stop_all_work
from app.practice import in_room as practice_in_room
from app.practice import pages as practice_pages
from app.practice import routes as practice
from app.practice.book import load_book
from app.practice.progress import SqlProgressStore, SqlRoomWorkStore
from app.scenes import SCENES
from app.scenes.host.host import SceneHost
from app.scenes.host.pool import WorkerPool
from app.settings import Settings
from app.storage import Database, open_database
from app.storage.changes import ChangeListener
from app.web import guard, pages, relay, viewer_client
from app.web.page_config import add_page_config_section
from app.web.static_files import STATIC_DIR
from app.web.stopping import AnswerWhenStopping, RequestsInFlight

log = logging.getLogger(__name__)


def create_app(settings: Settings | None = None) -> FastAPI:
    settings = settings or Settings.from_env()
    add_page_config_section("classroom", classroom_page_config())  # the web layer hands it on, never imports it

    @asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        host: SceneHost | WorkerPool
        if settings.workers:
            host = WorkerPool(
                SCENES,
                workers=settings.workers,
                frame_rate_hz=settings.frame_rate_hz,
                max_sessions=settings.max_sessions,
            )
        else:
            host = SceneHost(SCENES, frame_rate_hz=settings.frame_rate_hz, max_sessions=settings.max_sessions)
        host.start()
        app.state.scene_host = host
        for room in app.state.rooms.all():  # rooms kept from the last run: their scenes as they were
            room.put_stage_back(host)
        changes = _listen_to_other_servers(app, database)
        viewer_client.unpacked_client()  # unpacked (0.3 s) before a viewer asks for it, not while it waits
        try:
            yield
        finally:
            if changes is not None:
                changes.stop()
            stop_all_work()  # a derivation in flight ends now, not at its 20 s bound
            await room_relay.close_streams(app)
            host.stop()

    app = FastAPI(
        title="Dynamics Lab",
        version=__version__,
        summary="Interactive engineering dynamics: worked examples, solvers and live 3D scenes.",
        lifespan=lifespan,
        docs_url=None,  # served by _offline_docs from static/vendor: /docs works without internet
        redoc_url=None,
    )
    app.state.settings = settings
    # What a class must not lose (None: nothing kept): the instructor's secret, rooms, page sessions.
    kept_url = settings.kept_database_url()
    database = open_database(kept_url) if kept_url else None
    app.state.database = database
    # Page sessions: owners, viewers, per-client bounds; an evicted session is closed in its scene worker. Kept ones
    # open in their scene worker when their page or viewer first asks after a restart.
    app.state.sessions = SessionDirectory(
        max_sessions=settings.max_sessions,
        close=lambda session_id: _close_evicted(app, session_id),
        store=_kept_sessions(database, keep_days=settings.keep_rooms_days),
        reopen=lambda session_id, scene_id, params: app.state.scene_host.set_params(scene_id, session_id, params),
    )
    # Every lesson reference is checked here: a bad one stops the server before it starts.
    app.state.catalogue = load_catalogue(settings.lessons_dir)
    # The classroom: the instructor's secret (given, or kept), the rooms (kept ones open again), their sockets and the
    # ready poll questions (checked now).
    app.state.instructor_key = InstructorKey(settings.instructor_key or kept_instructor_secret(database))
    app.state.rooms = Rooms(
        store=SqlRoomStore(database) if database is not None else None,
        keep_days=settings.keep_rooms_days,
        join_base=settings.public_url or f"http://{settings.host}:{settings.port}",  # kept rooms' join links
        open_kept=database is None or not database.shared,  # servers sharing one take rooms up as classes arrive
        stop_stage=lambda room: room.rest_stage(app.state.scene_host),
    )
    # Learners working alone and their exercise progress (None with nothing kept); those unused for the rooms' keeping
    # time are forgotten at start-up.
    app.state.progress = _kept_progress(database, keep_days=settings.keep_rooms_days)
    # A room's record of its students' work on what it assigned (with the rooms: deleted with them).
    app.state.room_work = SqlRoomWorkStore(database) if database is not None else None
    # The exercises beside the lessons, checked against the course (a bad one stops the server, as a bad lesson does).
    app.state.exercises = load_book(settings.lessons_dir, chapters=app.state.catalogue.chapters, scenes=SCENES)
    app.state.practice_limits = practice.PracticeLimits()
    app.state.join_limits = JoinLimits(settings)
    app.state.room_hub = RoomHub(lambda: app.state.scene_host, say_presence=_presence_sayer(database))
    app.state.ready_questions = load_ready_questions(DEFAULT_READY_QUESTIONS, SCENES)
    errors.install(app)
    app.add_exception_handler(RoomError, rooms.room_error_handler)
    app.add_middleware(guard.RequestGuard, settings=settings, heavy_in_flight=app.state.sessions.heavy_work)
    # Outermost: on Ctrl+C every request still waiting for its answer gets a 503 at once, not uvicorn's 500 later.
    app.state.requests_in_flight = RequestsInFlight()
    app.add_middleware(AnswerWhenStopping, requests=app.state.requests_in_flight)
    routers = (
        health.router,
        chapters.router,
        scenes.router,
        examples.router,
        practice.router,
        practice_in_room.router,
        systems.router,
        bench.router,
        rooms.router,
        pages.router,
        practice_pages.router,
        viewer_client.router,
        room_pages.router,
        relay.router,
        room_relay.router,
    )
    for router in routers:
        app.include_router(router)
    errors.document_refusals(app, guard.refusals)
    _offline_docs(app)
    app.mount("/static", StaticFiles(directory=STATIC_DIR), name="static")
    return app


def _listen_to_other_servers(app: FastAPI, database: Database | None) -> ChangeListener | None:
    """On a database several servers share (PostgreSQL), what the others change reaches this one's rooms and page
    sessions (app.classroom.sync); None on a database only this server uses."""
    if database is None or not database.shared:
        return None
    sync = ClassSync(app)
    listener = ChangeListener(database, on_change=sync.on_change, on_missed=sync.on_missed)
    listener.start()
    return listener


def _kept_sessions(database: Database | None, *, keep_days: float) -> SqlSessionStore | None:
    """Page sessions in ``database``, those unused for ``keep_days`` forgotten first (None with nothing kept)."""
    if database is None:
        return None
    store = SqlSessionStore(database)
    store.forget_unused(days=keep_days)
    return store


def _presence_sayer(database: Database | None) -> Callable[[Room], None] | None:
    """How this server tells the others sharing its database who its sockets of a room hold (None: no others)."""
    if database is None or not database.shared:
        return None
    return lambda room: database.notify("presence", room.room_id, **room.presence_here())


def _kept_progress(database: Database | None, *, keep_days: float) -> SqlProgressStore | None:
    if database is None:
        return None
    store = SqlProgressStore(database)
    store.forget_unused(days=keep_days)
    return store


def _close_evicted(app: FastAPI, session_id: str) -> None:
    """Close a session the directory evicted in its scene worker (a worker that is restarting forgets it anyway)."""
    try:
        app.state.scene_host.close_session(session_id)
    except Exception as exc:
        log.warning("closing evicted session %s failed: %s", session_id, exc)


def _offline_docs(app: FastAPI) -> None:
    """``/docs``: Swagger UI from the vendored copy in static/vendor/swagger-ui, never a CDN."""

    @app.get("/docs", include_in_schema=False)
    def swagger_ui() -> HTMLResponse:
        return get_swagger_ui_html(
            openapi_url=app.openapi_url or "/openapi.json",
            title=f"{app.title} API",
            swagger_js_url="/static/vendor/swagger-ui/swagger-ui-bundle.js",
            swagger_css_url="/static/vendor/swagger-ui/swagger-ui.css",
            swagger_favicon_url="/static/favicon.svg",
            swagger_ui_parameters={"validatorUrl": None},  # no badge fetched from an online validator
        )
