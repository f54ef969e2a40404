"""The scene host: one viser server on loopback, one scene instance per browser.

The public FastAPI relay forwards each viewer websocket to this server at the
path ``/{scene_id}/{session_id}``. On connect, the host reads that path, looks up
the session's current parameters (kept here so a reconnect rebuilds the same
scene, and so the lesson page can set parameters before the viewer connects),
and builds a fresh :class:`~app.scenes.kit.scene.Scene` on that client only. One
background thread advances every animated scene at ``frame_rate_hz``.

Locking: the host's lock guards only the session table and is held for
dictionary operations; each session has its own lock, held while its scenes are
built, redrawn, advanced or read. So one student's slow redraw (compiling a
typed curve, rebuilding a mesh) never stalls another student's frames, and a
readout poll waits for one scene's frame at most. Lock order: host, then session.

``dynlab serve`` runs several of these hosts in scene-worker processes
(:mod:`app.scenes.host.pool`); tests and a single-process server use one directly.
"""

from __future__ import annotations

import contextlib
import io
import logging
import re
import threading
import time
from collections import OrderedDict
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

import viser

from app.scenes.host.viser_compat import (
    BatchedWakeups,
    connection_path,
    share_prop_hints,
    start_callback_threads,
)
from app.scenes.kit import Scene

log = logging.getLogger(__name__)

SESSION_ID_PATTERN = re.compile(r"^[A-Za-z0-9_-]{8,64}$")


class UnknownSceneError(KeyError):
    """No scene is registered under that id."""


@dataclass
class Session:
    """One lesson page's state for one scene: what survives a viewer reconnect."""

    scene_id: str
    params: dict[str, Any]
    instances: dict[int, Scene] = field(default_factory=dict)  # viser client id -> scene
    last_used_s: float = field(default_factory=time.monotonic)
    #: Held while this session's scenes are built, redrawn, advanced or read.
    lock: threading.RLock = field(default_factory=threading.RLock)


class SceneHost:
    """Owns the loopback viser server, the sessions and the frame loop."""

    def __init__(
        self,
        scenes: Mapping[str, type[Scene]],
        *,
        host: str = "127.0.0.1",
        frame_rate_hz: float = 30.0,
        max_sessions: int = 2000,
    ) -> None:
        self.scenes = dict(scenes)
        self._host = host
        self.frame_rate_hz = frame_rate_hz
        self.max_sessions = max_sessions
        self._sessions: OrderedDict[str, Session] = OrderedDict()
        self._client_session: dict[int, str] = {}
        self._lock = threading.RLock()
        self._stop = threading.Event()
        self._server: viser.ViserServer | None = None
        self._thread: threading.Thread | None = None

    # -- life cycle ---------------------------------------------------------------
    def start(self) -> None:
        share_prop_hints()
        with contextlib.redirect_stdout(io.StringIO()):  # viser prints its loopback URL unconditionally
            server = viser.ViserServer(host=self._host, port=0, verbose=False)
        log.info("scene server listening on loopback port %d (reached only through the relay)", server.get_port())
        server.gui.configure_theme(show_share_button=False, show_logo=False)
        start_callback_threads(server)  # a constant thread count, so a soak can tell a leak from a growing pool
        server.on_client_connect(self._on_connect)
        server.on_client_disconnect(self._on_disconnect)
        self._server = server
        self._thread = threading.Thread(target=self._frame_loop, name="scene-frames", daemon=True)
        self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=2.0)
        if self._server is not None:
            self._server.stop()

    @property
    def port(self) -> int:
        assert self._server is not None, "SceneHost.start() first"
        return self._server.get_port()

    @property
    def url(self) -> str:
        return f"ws://{self._host}:{self.port}"

    def viewer_url(self, session_id: str) -> str:
        """The loopback websocket address that serves ``session_id``'s viewers (the relay appends the path)."""
        return self.url

    # -- sessions -----------------------------------------------------------------
    def scene_class(self, scene_id: str) -> type[Scene]:
        try:
            return self.scenes[scene_id]
        except KeyError:
            raise UnknownSceneError(scene_id) from None

    def _session(self, scene_id: str, session_id: str) -> Session:
        """Get or create the session (caller holds the lock)."""
        session = self._sessions.get(session_id)
        if session is None or session.scene_id != scene_id:
            if session is not None:
                self._close_instances(session)
            session = Session(scene_id, self.scene_class(scene_id).parameters.defaults())
            self._sessions[session_id] = session
            self._evict()
        session.last_used_s = time.monotonic()
        self._sessions.move_to_end(session_id)
        return session

    def _evict(self) -> None:
        while len(self._sessions) > self.max_sessions:
            oldest = next((k for k, s in self._sessions.items() if not s.instances), None)
            if oldest is None:
                return
            del self._sessions[oldest]

    def set_params(self, scene_id: str, session_id: str, raw: Mapping[str, Any]) -> dict[str, Any]:
        """Validate ``raw`` against the scene's parameters and apply it to every viewer of the session.

        Raises ``ValueError`` (naming the field) and changes nothing on bad input.
        """
        if not SESSION_ID_PATTERN.match(session_id):
            raise ValueError("session_id: must be 8–64 letters, digits, '-' or '_'")
        cls = self.scene_class(scene_id)
        with self._lock:
            existing = self._sessions.get(session_id)
            base = dict(existing.params) if existing is not None and existing.scene_id == scene_id else None
        # Validation can take a while (compiling a typed curve): outside the lock, so every other
        # scene keeps animating meanwhile. It raises before anything changes.
        params = cls.parameters.validate(raw, base=base)
        with self._lock:
            session = self._session(scene_id, session_id)
        with session.lock:
            session.params = params
            for scene in session.instances.values():
                scene.set_params(params)
            return dict(params)

    def session_params(self, session_id: str) -> dict[str, Any] | None:
        with self._lock:
            session = self._sessions.get(session_id)
            return None if session is None else dict(session.params)

    def instances(self, session_id: str) -> list[Scene]:
        """The live scene instances (one per connected viewer) of a session."""
        with self._lock:
            session = self._sessions.get(session_id)
        if session is None:
            return []
        with session.lock:
            return list(session.instances.values())

    @contextlib.contextmanager
    def inspect(self, session_id: str) -> Iterator[list[Scene]]:
        """The session's live scene instances, held still (no frame advances them) while the block runs.

        For reading several of a scene's drawn properties at one instant (tests,
        diagnostics); keep the block short: this session's frames wait for it.
        """
        with self._lock:
            session = self._sessions.get(session_id)
        if session is None:
            yield []
            return
        with session.lock:
            yield list(session.instances.values())

    def live_readout(self, scene_id: str, session_id: str) -> dict[str, Any] | None:
        """Live numbers from the session's first viewer of the scene (None if none is connected).

        Integrated scenes add their integration readout (method, invariants,
        drift); every scene adds its own ``readout`` when it has one.
        """
        with self._lock:
            session = self._sessions.get(session_id)
        if session is None:
            return None
        with session.lock:
            for scene in session.instances.values():
                if scene.id == scene_id:
                    out: dict[str, Any] = scene.live_readout() if hasattr(scene, "live_readout") else {}
                    readout = scene.readout()
                    if readout is not None:
                        out["readout"] = readout.as_dict()
                    return out
        return None

    def viewer_count(self, session_id: str | None = None) -> int:
        with self._lock:
            if session_id is None:
                return len(self._client_session)
            session = self._sessions.get(session_id)
            return 0 if session is None else len(session.instances)

    # -- viser callbacks ------------------------------------------------------------
    def _on_connect(self, client: viser.ClientHandle) -> None:
        assert self._server is not None
        path = connection_path(self._server, client) or ""
        parts = [p for p in path.split("?")[0].split("/") if p]
        if len(parts) != 2 or parts[0] not in self.scenes or not SESSION_ID_PATTERN.match(parts[1]):
            log.warning("viewer connected with unusable path %r", path)
            client.gui.add_markdown(f"**No such scene:** `{path}`")
            return
        scene_id, session_id = parts
        with self._lock:
            session = self._session(scene_id, session_id)
            self._client_session[client.client_id] = session_id
        with session.lock:
            try:
                scene = self.scenes[scene_id](client, session.params)
            except Exception:
                log.exception("building scene %s failed", scene_id)
                client.gui.add_markdown("**This scene failed to build.** The error is in the server log.")
                return
            session.instances[client.client_id] = scene

    def _on_disconnect(self, client: viser.ClientHandle) -> None:
        with self._lock:
            session_id = self._client_session.pop(client.client_id, None)
            session = self._sessions.get(session_id) if session_id else None
        if session is not None:
            with session.lock:
                session.instances.pop(client.client_id, None)
                session.last_used_s = time.monotonic()

    def _close_instances(self, session: Session) -> None:
        """Close a replaced session's scenes (caller holds the host lock; this takes the session's)."""
        with session.lock:
            for client_id, scene in list(session.instances.items()):
                self._client_session.pop(client_id, None)
                try:
                    scene.close()
                except Exception:
                    log.exception("closing scene failed")
            session.instances.clear()

    # -- frame loop -----------------------------------------------------------------
    def _frame_loop(self) -> None:
        period = 1.0 / self.frame_rate_hz
        last = deadline = time.perf_counter()
        # Frames start on a fixed grid of deadlines, so a late wake-up (waiting for the GIL) is made up on the
        # next frame instead of lowering the rate; after a stall of more than a frame the grid restarts from now.
        while not self._stop.wait(max(0.0, deadline - time.perf_counter())):
            now = time.perf_counter()
            dt, last = now - last, now
            deadline = deadline + period if now - deadline < period else now + period
            with self._lock:
                sessions = [sess for sess in self._sessions.values() if sess.instances]
            wakeups = BatchedWakeups()  # viser's sender is woken once for every viewer's frame, not once per viewer
            for session in sessions:
                with session.lock:
                    for scene in list(session.instances.values()):
                        if scene.animated and not scene.status:
                            self._advance(scene, dt, wakeups)
            wakeups.flush()

    @staticmethod
    def _advance(scene: Scene, dt_s: float, wakeups: BatchedWakeups) -> None:
        try:
            with wakeups.atomic(scene.client):
                scene.advance(dt_s)
        except Exception:
            log.exception("advancing scene %s failed; it is paused", scene.id)
            scene.status = "paused after an error (see the server log)"
