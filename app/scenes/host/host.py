"""The scene host: one viser server on loopback, one scene instance per browser.

The public FastAPI relay forwards each viewer websocket to this server at the
path ``/{scene_id}/{session_id}``. On connect, the host reads that path, looks up
the session's current parameters (kept here so a reconnect rebuilds the same
scene, and so the lesson page can set parameters before the viewer connects),
and builds a fresh :class:`~app.scenes.kit.scene.Scene` on that client only. One
background thread advances every animated scene at ``frame_rate_hz``.

Locking: the host's lock guards only the session table and is held for
dictionary operations; each session has its own lock, held while its scenes are
built, redrawn, advanced or read. The frame loop never waits for a session's
lock: a session busy with a request (a student's slow redraw, a computed jump in
time) misses that frame, and every other session is drawn on time. Lock order:
host, then session.

Who may do what is decided in the front (:mod:`app.api.access`); the host keeps
its own backstops: a viewer is only ever shown an existing session of its own
scene (a viewer never creates, replaces or re-scenes a session), and every
viewer, client and request gets a fair share of the worker
(:mod:`app.scenes.host.fair_share`).

Every session can be paused and its time scaled (:meth:`SceneHost.set_playback`):
the frame loop advances a scene ``time_scale`` frames per displayed frame on
average, so every scene, closed-form or integrated, slows and speeds alike.

A *stage* (:meth:`SceneHost.open_stage`) is a session whose one scene is drawn
on its own viser server rather than on one client: every viewer of that server
sees the same simulation, and viser keeps its current state for viewers that
join later. A classroom room shows its scene on a stage; the front fans the
stage's one stream out to every student following it.

``dynlab serve`` runs several of these hosts in scene-worker processes
(:mod:`app.scenes.host.pool`); tests and a single-process server use one directly.
"""

from __future__ import annotations

import contextlib
import logging
import math
import re
import threading
import time
from collections import OrderedDict
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

import viser

from app.physics.core.bounded import yield_only_to_live_scenes
from app.scenes.host.fair_share import (
    FRAME_LOOP_SHARE,
    FrameCost,
    Pace,
    RequestTooCostly,
    allowances,
    check_request_cost,
    is_long_request,
    slowdown_note,
)
from app.scenes.host.graph import DEFAULT_MAX_POINTS, check_graph_request, empty_graph, motion_graph, no_graph_note
from app.scenes.host.history import MotionHistory
from app.scenes.host.interface import HostBusy
from app.scenes.host.recorder import SceneRecorder, checked_seconds, frames_for
from app.scenes.kit import Scene
from app.scenes.kit.scene import FRAME_DT_S
from app.scenes.viser_boundary import (
    BatchedWakeups,
    BroadcastViewer,
    connection_path,
    make_message_events_thread_safe,
    quiet_server,
    share_prop_hints,
    start_callback_threads,
    stop_quietly,
    viewer_count,
)

log = logging.getLogger(__name__)

SESSION_ID_PATTERN = re.compile(r"^[A-Za-z0-9_-]{8,64}$")
#: Session ids of stages begin with this (a room's stage is ``room-<room_id>``). No page may use one: its
#: parameters change only through its room, and no viewer of the page kind may join it.
STAGE_PREFIX = "room-"
#: Slowest and fastest time scale a session may run at (× real time).
TIME_SCALE_RANGE = (0.1, 4.0)
#: Most frames one step request advances, and the latest simulated time a share link may ask for (s).
MAX_STEP_FRAMES = 300
MAX_GO_TO_S = 600.0
#: Viewers one session may have at once (each is a whole scene computed and streamed; a page has one, a student
#: with the same lesson in a second tab two). The front refuses more first; this is the host's own backstop.
MAX_VIEWERS_PER_SESSION = 4


def check_session_id(session_id: str, *, stage: bool = False) -> None:
    """Raise ``ValueError`` for a malformed id, or one of the wrong kind (a stage's for a page, or the reverse)."""
    if not SESSION_ID_PATTERN.match(session_id):
        raise ValueError("session_id: must be 8–64 letters, digits, '-' or '_'")
    if session_id.startswith(STAGE_PREFIX) != stage:
        raise ValueError(
            f"session_id: ids beginning {STAGE_PREFIX!r} are classroom rooms' shared scenes, changed only by their room"
            if not stage
            else f"session_id: a stage's id begins {STAGE_PREFIX!r}"
        )


#: Farthest a camera may be placed from the origin (m).
MAX_CAMERA_M = 1e4


def checked_camera(raw: Mapping[str, Any]) -> dict[str, tuple[float, float, float]]:
    """``{"position", "look_at"}`` as two finite 3-vectors within :data:`MAX_CAMERA_M`, distinct; ValueError
    otherwise."""
    try:
        view = {name: tuple(float(v) for v in raw[name]) for name in ("position", "look_at")}
    except (KeyError, TypeError, ValueError):
        raise ValueError("camera: needs position and look_at, each [x, y, z] in m") from None
    if any(len(v) != 3 or not all(math.isfinite(c) and abs(c) <= MAX_CAMERA_M for c in v) for v in view.values()):
        raise ValueError(f"camera: position and look_at are three finite numbers each, within {MAX_CAMERA_M:g} m")
    if view["position"] == view["look_at"]:
        raise ValueError("camera: position and look_at must differ")
    return view  # type: ignore[return-value]


def tell_viewer(client: Any, text: str) -> None:
    """Show ``text`` in the middle of a viewer's scene: the page hides viser's own panel, so a message there is
    unseen."""
    client.scene.add_label("/viewer-message", text, position=(0.0, 0.0, 0.0), font_screen_scale=1.5)


def place_camera(client: Any, *, position: tuple[float, float, float], look_at: tuple[float, float, float]) -> None:
    """Point a viewer's camera (a client's, or a stage's initial one) from ``position`` at ``look_at`` (m)."""
    client.camera.position = position  # a client's camera keeps its look-at offset when moved: set look_at after
    client.camera.look_at = look_at


class UnknownSceneError(KeyError):
    """No scene is registered under that id."""


@dataclass
class ViewerShare:
    """One viewer's share of the frames: whose it is (the client's address, from the relay), what its scene costs a
    frame, the frames it is owed (``time_scale`` × its rate a frame), and how far it is slowed."""

    client: str | None
    #: A frame's advance and drawing as measured frame by frame (the least of the recent frames) ...
    cost: FrameCost = field(default_factory=FrameCost)
    #: ... plus the mean physics a frame (s) where a scene computes its motion in batches of frames (an integrated
    #: scene computes 15 frames at once, so most of its frames only copy a state and the least of them misses it).
    physics_s: float = 0.0
    credit: float = 0.0
    rate: float = 1.0
    note: str = ""

    @property
    def frame_s(self) -> float:
        """What one frame of this viewer's scene costs (s), 0 while it is not yet measured."""
        return self.cost.seconds + self.physics_s if self.cost.seconds else 0.0


def viewer_camera(client: Any) -> dict[str, list[float]] | None:
    """A viewer's camera now (m, world frame: position, look_at) as its browser last reported it; None before its
    first report, for a stage (it has no single camera), or for a report :func:`checked_camera` refuses (a
    browser — or anyone watching the session — may send NaN or 1e300: it is never answered, kept or restored)."""
    camera = getattr(client, "camera", None)
    if not isinstance(camera, viser.CameraHandle):
        return None
    with contextlib.suppress(AssertionError, ValueError):  # no camera message from the browser yet, or an unusable one
        view = checked_camera({"position": camera.position, "look_at": camera.look_at})
        return {name: list(vector) for name, vector in view.items()}
    return None


@dataclass
class Session:
    """One lesson page's state for one scene: what survives a viewer reconnect."""

    scene_id: str
    params: dict[str, Any]
    instances: dict[int, Scene] = field(default_factory=dict)  # viser client id -> scene
    last_used_s: float = field(default_factory=time.monotonic)
    #: Held while this session's scenes are built, redrawn, advanced or read.
    lock: threading.RLock = field(default_factory=threading.RLock)
    #: A paused session is not advanced; ``time_scale`` is the frames advanced per displayed frame, on average.
    playing: bool = True
    time_scale: float = 1.0
    #: A stage's own viser server (its one scene is broadcast to every viewer of it); None for a page's session.
    stage: viser.ViserServer | None = None
    #: Motion the next scene built for this session starts from (``Scene.resume_from``), then forgotten.
    resume_motion: dict[str, Any] | None = None
    #: Simulated time (s) the next scene built for this session goes to (``Scene.go_to``: a share link), then forgotten.
    go_to_s: float | None = None
    #: Camera (m: position, look_at) the next viewer's view starts from (a share link), then forgotten.
    camera: dict[str, tuple[float, float, float]] | None = None
    #: Each viewer's recent motion, for the scrubber (keyed like ``instances``).
    histories: dict[int, MotionHistory] = field(default_factory=dict)
    #: Each viewer's share of the frames (keyed like ``instances``).
    shares: dict[int, ViewerShare] = field(default_factory=dict)

    def playback(self) -> dict[str, Any]:
        """Play state, time scale, the first scene's simulated time (or, before a viewer, the time the next one resumes
        at) and the span of motion kept for scrubbing."""
        waiting_t_s = self.resume_motion.get("t_s") if self.resume_motion is not None else self.go_to_s
        out: dict[str, Any] = {
            "playing": self.playing,
            "time_scale": self.time_scale,
            "t_s": waiting_t_s,
            "history_s": None,
        }
        for client_id, scene in list(self.instances.items()):
            motion = scene.motion_state()
            out["t_s"] = None if motion is None else motion["t_s"]
            history = self.histories.get(client_id)
            span = history.span_s() if history is not None else None
            out["history_s"] = None if span is None else list(span)
            share = self.shares.get(client_id)
            if share is not None and share.rate < 0.99:
                out["slowed"] = {"rate": share.rate, "note": share.note}
            break
        return out

    def playback_answer(self) -> dict[str, Any]:
        """:meth:`playback` with the first viewer's camera (or the one the next viewer starts from) and the number of
        viewers: what the page's time controls read, in one look."""
        return {**self.playback(), "camera": self.camera_now(), "viewers": len(self.instances)}

    def camera_now(self) -> dict[str, list[float]] | None:
        """The first usable viewer camera (m, world frame), or without viewers the one the next viewer starts from."""
        if not self.instances:
            return None if self.camera is None else {k: list(v) for k, v in self.camera.items()}
        return next(
            (c for c in (viewer_camera(scene.client) for scene in self.instances.values()) if c is not None), None
        )

    def add_instance(self, client_id: int, scene: Scene, *, client: str | None = None) -> None:
        self.instances[client_id] = scene
        self.histories[client_id] = MotionHistory()
        self.histories[client_id].record(scene.motion_state())
        self.shares[client_id] = ViewerShare(client)

    def clear_instances(self) -> None:
        """Forget every viewer's scene (the caller has closed them)."""
        self.instances.clear()
        self.histories.clear()
        self.shares.clear()

    def remove_instance(self, client_id: int) -> Scene | None:
        self.histories.pop(client_id, None)
        self.shares.pop(client_id, None)
        return self.instances.pop(client_id, None)

    def snapshot(self) -> dict[str, Any]:
        """What a restarted worker needs to show this session as it is (caller holds its lock): scene, parameters,
        play state, time scale, the first viewer's motion (or the one waiting for a viewer) and camera."""
        scene = next(iter(self.instances.values()), None)
        motion = scene.motion_state() if scene is not None else self.resume_motion
        camera = self.camera_now()
        return {
            "scene_id": self.scene_id,
            "params": dict(self.params),
            "stage": self.stage is not None,
            "playing": self.playing,
            "time_scale": self.time_scale,
            "motion": motion,
            "go_to_s": self.go_to_s if motion is None else None,
            "camera": camera,
        }

    def restarted(self) -> None:
        """The motion started again (new parameters, a reset, a jump): the kept frames belong to the old one."""
        for client_id, scene in self.instances.items():
            history = self.histories.setdefault(client_id, MotionHistory())
            history.clear()
            history.record(scene.motion_state())


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
        self._recorder = SceneRecorder(host=host)
        self._long_request = threading.Lock()

    # -- life cycle ---------------------------------------------------------------
    def start(self, *, frame_loop: bool = True) -> None:
        """Start the viser server and, unless ``frame_loop`` is false, the thread that calls :meth:`run_frame`
        ``frame_rate_hz`` times a second (without it, time moves only when :meth:`run_frame` is called: a test
        that steps the frames itself)."""
        share_prop_hints()
        make_message_events_thread_safe()
        yield_only_to_live_scenes(lambda: self.total_viewers() > 0)  # a derivation here pauses only for viewers' frames
        server = quiet_server(host=self._host)
        log.info("scene server listening on loopback port %d (reached only through the relay)", server.get_port())
        start_callback_threads(server)  # a constant thread count, so a soak can tell a leak from a growing pool
        server.on_client_connect(self._on_connect)
        server.on_client_disconnect(self._on_disconnect)
        self._server = server
        if frame_loop:
            self._thread = threading.Thread(target=self._frame_loop, name="scene-frames", daemon=True)
            self._thread.start()

    def stop(self) -> None:
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=2.0)
        with self._lock:
            stages = [session.stage for session in self._sessions.values() if session.stage is not None]
        for stage in stages:
            stop_quietly(stage)
        self._recorder.stop()
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

    def worker_states(self) -> list[dict[str, Any]]:
        """No scene workers: the scenes run in this process."""
        return []

    # -- sessions -----------------------------------------------------------------
    def scene_class(self, scene_id: str) -> type[Scene]:
        try:
            return self.scenes[scene_id]
        except KeyError:
            raise UnknownSceneError(scene_id) from None

    def _session(self, scene_id: str, session_id: str) -> Session:
        """Get or create the session (caller holds the lock)."""
        session = self._sessions.get(session_id)
        if session is not None and session.stage is not None and session.scene_id != scene_id:
            raise ValueError(
                f"session {session_id!r} is a stage showing {session.scene_id!r}: open_stage changes its scene"
            )
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
        """A backstop: the front's directory bounds sessions (per client and in all) and closes them here first."""
        while len(self._sessions) > self.max_sessions:
            oldest = next((k for k, s in self._sessions.items() if not s.instances), None)
            if oldest is None:
                return
            del self._sessions[oldest]

    def set_params(
        self, scene_id: str, session_id: str, raw: Mapping[str, Any], *, stage: bool = False
    ) -> dict[str, Any]:
        """Validate ``raw`` against the scene's parameters and apply it to every viewer of the session.

        ``stage`` is True only for a room changing its own stage (ids beginning :data:`STAGE_PREFIX`);
        a page's session may not use such an id. Raises ``ValueError`` (naming the field) and changes
        nothing on bad input.
        """
        check_session_id(session_id, stage=stage)
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
            if params != session.params:  # a new motion: what a reconnecting viewer would have resumed is void
                session.resume_motion = None
            session.params = params
            for scene in session.instances.values():
                scene.set_params(params)
            session.restarted()
            return dict(params)

    def set_playback(
        self,
        session_id: str,
        *,
        playing: bool | None = None,
        time_scale: float | None = None,
        reset: bool = False,
        step: int = 0,
        seek_s: float | None = None,
        go_to_s: float | None = None,
        camera: Mapping[str, Any] | None = None,
        reset_camera: bool = False,
    ) -> dict[str, Any]:
        """Change how the session's motion runs; returns :meth:`Session.playback`. Checks everything first.

        ``playing`` pauses or plays; ``time_scale`` is × real time (:data:`TIME_SCALE_RANGE`); ``reset``
        restarts from t = 0; ``step`` advances that many frames now (1–300; pauses); ``seek_s`` puts every
        viewer's scene back at a kept frame (pauses: the scrubber); ``go_to_s`` computes the motion at that
        simulated time from the start (0–600 s: a share link), applied to a viewer that connects later too;
        ``camera`` (``{"position", "look_at"}``, m, world frame) moves the viewers' cameras, or the next one's;
        ``reset_camera`` puts every viewer's camera back at its scene's start pose (``Scene.camera_view``) instead.
        """
        view = checked_camera(camera) if camera is not None else None
        if not isinstance(reset_camera, bool):
            raise ValueError("reset_camera: must be true or false")
        if reset_camera and view is not None:
            raise ValueError("reset_camera: give either camera or reset_camera, not both")
        if playing is not None and not isinstance(playing, bool):
            raise ValueError("playing: must be true or false")
        if time_scale is not None:
            low, high = TIME_SCALE_RANGE
            if (
                isinstance(time_scale, bool)
                or not isinstance(time_scale, int | float)
                or not math.isfinite(time_scale)
                or not low <= time_scale <= high
            ):
                raise ValueError(
                    f"time_scale: must be a number from {low:g} to {high:g} (× real time), got {time_scale!r}"
                )
        if isinstance(step, bool) or not isinstance(step, int) or not 0 <= step <= MAX_STEP_FRAMES:
            raise ValueError(f"step: a whole number of frames from 0 to {MAX_STEP_FRAMES}, got {step!r}")
        for name, value, latest in (("seek_s", seek_s, None), ("go_to_s", go_to_s, MAX_GO_TO_S)):
            if value is not None and (
                isinstance(value, bool)
                or not isinstance(value, int | float)
                or not math.isfinite(value)
                or value < 0
                or (latest is not None and value > latest)
            ):
                raise ValueError(f"{name}: a simulated time from 0 to {latest or 'the latest kept'} s, got {value!r}")
        session = self._existing(session_id)
        if (go_to_s is not None or step or seek_s is not None) and not self.scene_class(session.scene_id).animated:
            raise ValueError(f"{session.scene_id} is not animated: it has no time to step, scrub or go to")
        with self._one_long_request(is_long_request(step=step, go_to_s=go_to_s)), session.lock:
            # What the request will compute, checked against its limit before anything moves (the scenes' measured
            # cost a frame; a session without a viewer computes its jump when one connects, paced the same way).
            if step:
                drawn_s = sum(share.frame_s for share in session.shares.values())
                check_request_cost("step", frames=step, frame_cost_s=drawn_s, what=f"stepping {step} frames")
            if go_to_s is not None and session.instances:
                stepped_s = sum(scene.motion_cost_s() or 0.0 for scene in session.instances.values())
                frames = math.ceil(
                    float(go_to_s) / FRAME_DT_S
                )  # a jump steps the kit's frames, as _paced_go_to counts them
                check_request_cost(
                    "go_to_s", frames=frames, frame_cost_s=stepped_s, what=f"computing the motion to {go_to_s:g} s"
                )
            if seek_s is not None:  # checked against every viewer's kept motion before anything moves
                motions = {
                    cid: session.histories[cid].at(seek_s) for cid in session.instances if cid in session.histories
                }
                if not motions:
                    raise ValueError(
                        "seek_s: no motion is kept for this session yet (it "
                        "has no viewer): open its scene, then go back in it"
                    )
            if playing is not None:
                session.playing = playing
            if time_scale is not None:
                session.time_scale = float(time_scale)
            if reset or go_to_s is not None:
                session.resume_motion = session.go_to_s = (
                    None  # a viewer that connects later starts from the new motion
                )
            if reset:
                for scene in session.instances.values():
                    with scene.client.atomic():
                        # the kit's own restart (go_to's too), not a re-application of the parameters
                        scene.restart_motion()
                session.restarted()
            if go_to_s is not None:
                for scene in session.instances.values():
                    self._paced_go_to(scene, float(go_to_s))
                session.restarted()
                if not session.instances:
                    session.go_to_s = float(go_to_s)
            if seek_s is not None:
                session.playing = False
                for client_id, motion in motions.items():
                    scene = session.instances[client_id]
                    scene.resume_from(motion)
                    scene.redraw()
            if step:
                session.playing = False
                self._step(session, step)
            if view is not None:
                for scene in session.instances.values():
                    place_camera(scene.client, **view)
                if not session.instances:
                    session.camera = view
            if reset_camera:
                for scene in session.instances.values():
                    position, look_at = scene.camera_view()
                    place_camera(scene.client, position=position, look_at=look_at)
                session.camera = None  # a viewer that connects later starts at the start pose anyway
            if playing and seek_s is None:
                # Playing on from a scrubbed instant: the frames kept after it are not this run's.
                for client_id, scene in session.instances.items():
                    current = scene.motion_state()
                    if current is not None and client_id in session.histories:
                        session.histories[client_id].forget_after(current["t_s"])
            return session.playback_answer()

    @contextlib.contextmanager
    def _one_long_request(self, long: bool) -> Iterator[None]:
        """Requests that compute (step, go to a time) run one at a time in a worker, so that together they never take
        more than one paced thread from the frame loop; one that cannot start within a second is answered 503."""
        if not long:
            yield
            return
        if not self._long_request.acquire(timeout=1.0):
            raise HostBusy(
                "another student's long computation is running on this scene worker; try again in a moment",
                retry_after_s=2,
            )
        try:
            yield
        finally:
            self._long_request.release()

    def _step(self, session: Session, frames: int) -> None:
        """Advance every animated scene of the session ``frames`` displayed frames now (caller holds its lock), paced
        so the frame loop keeps drawing everyone else meanwhile. If it runs over the request's compute limit (its
        cost was not known yet) every scene is put back where it was and ``RequestTooCostly`` says so."""
        pace = Pace(frames=frames * max(1, len(session.instances)))
        before = {client_id: scene.motion_state() for client_id, scene in session.instances.items()}
        wakeups = BatchedWakeups()
        for client_id, scene in list(session.instances.items()):
            for _ in range(frames):
                if scene.animated and not scene.status:
                    self._advance(scene, 1.0 / self.frame_rate_hz, wakeups)
                    session.histories.setdefault(client_id, MotionHistory()).record(scene.motion_state())
                if not pace():
                    break
        wakeups.flush()
        if pace.exhausted:
            for client_id, scene in session.instances.items():
                if before.get(client_id) is not None:
                    scene.resume_from(before[client_id])  # type: ignore[arg-type]
                    scene.redraw()
            session.restarted()
            raise RequestTooCostly.over_limit(
                "step", f"stepping {frames} frames of this scene", "step fewer frames, or use fewer steps per frame"
            )

    @staticmethod
    def _paced_go_to(scene: Scene, t_s: float) -> None:
        """``scene.go_to(t_s)`` within one request's share of the worker; if it would take longer, the scene is put
        back where it was and ``RequestTooCostly`` names the limit."""
        before = scene.motion_state()
        pace = Pace(frames=math.ceil(t_s / FRAME_DT_S) + 1)  # a jump steps whole frames of the kit's
        scene.pace = pace  # type: ignore[method-assign]  # an instance's own pace, for this computation only
        try:
            scene.go_to(t_s)
        finally:
            del scene.pace
        if pace.exhausted:
            if before is not None:
                scene.resume_from(before)
                scene.redraw()
            raise RequestTooCostly.over_limit(
                "go_to_s", f"computing the motion to {t_s:g} s", "ask for an earlier time, or use fewer steps per frame"
            )

    def camera(self, session_id: str) -> dict[str, list[float]] | None:
        """The first viewer's camera now (m, world frame), as its browser last reported it; before a viewer, the one the
        next viewer starts from (a share link's, or a restored one); else None."""
        answer = self.playback(session_id)
        return None if answer is None else answer["camera"]

    def playback(self, session_id: str) -> dict[str, Any] | None:
        """The session's play state, simulated time, kept span, camera and viewers (:meth:`Session.playback_answer`),
        read without waiting for a request that holds the session (a page polls this; what it reads are numbers that
        change a frame at a time)."""
        session = self._find(session_id)
        return None if session is None else session.playback_answer()

    def _find(self, session_id: str) -> Session | None:
        """The session, or None (the table's lock held only to look it up)."""
        with self._lock:
            return self._sessions.get(session_id)

    def _existing(self, session_id: str) -> Session:
        session = self._find(session_id)
        if session is None:
            raise ValueError(f"session {session_id!r} has no scene yet: set its parameters first")
        return session

    # -- recordings that play offline ---------------------------------------------------
    def recording_html(self, scene_id: str, session_id: str, *, seconds: float) -> str | None:
        """The last ``seconds`` (1–60) of the session's kept motion as a standalone HTML file that plays offline
        (:mod:`app.scenes.host.recorder`); a still of the scene when no motion is kept. None when the session
        has no ``scene_id`` scene. ValueError for bad ``seconds`` or a file over the size limit; RecordingError
        when the recording fails (the worker goes on)."""
        seconds = checked_seconds(seconds)
        cls = self.scene_class(scene_id)
        session = self._find(session_id)
        if session is None or session.scene_id != scene_id:
            return None
        with session.lock:  # a copy of what is kept now; the live scene animates on while the recording is made
            params = dict(session.params)
            history = next(iter(session.histories.values()), None)
            frames = [] if history is None else history.latest(frames_for(seconds, frame_rate_hz=self.frame_rate_hz))
        return self._recorder.record_html(cls, params, frames, frame_period_s=1.0 / self.frame_rate_hz)

    # -- stages: one scene, every viewer -----------------------------------------------
    def open_stage(self, session_id: str, scene_id: str, raw: Mapping[str, Any]) -> dict[str, Any]:
        """Show ``scene_id`` with parameters ``raw`` on the stage ``session_id`` (created on first use, its scene
        replaced after). Returns ``{"params", "viewer_url"}``: the validated parameters and the loopback websocket
        address of the stage's own viser server. Raises ``ValueError`` and changes nothing on bad input."""
        check_session_id(session_id, stage=True)
        cls = self.scene_class(scene_id)
        params = cls.parameters.validate(raw)
        with self._lock:
            session = self._sessions.get(session_id)
            if session is None or session.stage is None:
                if session is not None:
                    self._close_instances(session)
                session = Session(scene_id, params, stage=quiet_server(host=self._host))
                self._sessions[session_id] = session
            session.last_used_s = time.monotonic()
        with session.lock:
            assert session.stage is not None
            for scene in session.instances.values():
                scene.close()
            session.clear_instances()
            session.scene_id, session.params = scene_id, params
            viewer = BroadcastViewer(session.stage)
            scene = cls(viewer, params)  # type: ignore[arg-type]
            position, look_at = scene.camera_view()
            viewer.move_cameras(position=position, look_at=look_at)
            session.add_instance(BroadcastViewer.client_id, scene)
            return {"params": dict(params), "viewer_url": self.stage_viewer_url(session_id)}

    def close_stage(self, session_id: str) -> None:
        """Stop a stage's scene and its viser server (its viewers are disconnected); unknown ids are ignored."""
        with self._lock:
            session = self._sessions.get(session_id)
            if session is None or session.stage is None:
                return
            del self._sessions[session_id]
        with session.lock:
            for scene in session.instances.values():
                scene.close()
            session.clear_instances()
        stop_quietly(session.stage)

    def stage_viewer_url(self, session_id: str) -> str | None:
        """The loopback websocket address of a stage's viser server, or None if there is no such stage."""
        session = self._find(session_id)
        return None if session is None or session.stage is None else f"ws://{self._host}:{session.stage.get_port()}"

    def stage_viewers(self, session_id: str) -> int:
        """Websockets open on a stage's server (the front's one stream per room, plus any joining)."""
        session = self._find(session_id)
        return 0 if session is None or session.stage is None else viewer_count(session.stage)

    # -- a motion handed from one session to another (a room's students exploring) ----------
    def motion_state(self, session_id: str) -> dict[str, Any] | None:
        """The session's scene's motion now (``Scene.motion_state``), or None (no scene, or one that restarts at
        t = 0)."""
        with self.inspect(session_id) as scenes:
            return scenes[0].motion_state() if scenes else None

    def resume_from(self, session_id: str, motion: Mapping[str, Any]) -> None:
        """Start the session's scene (now, and the next one built for a viewer) from ``motion``; set its parameters
        first."""
        session = self._existing(session_id)
        with session.lock:
            for scene in session.instances.values():
                scene.resume_from(motion)
            if not session.instances:
                session.resume_motion = dict(motion)

    def session_params(self, session_id: str) -> dict[str, Any] | None:
        session = self._find(session_id)
        return None if session is None else dict(session.params)

    def instances(self, session_id: str) -> list[Scene]:
        """The live scene instances (one per connected viewer) of a session."""
        session = self._find(session_id)
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
        session = self._find(session_id)
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
        session = self._find(session_id)
        if session is None:
            return None
        with session.lock:
            for scene in session.instances.values():
                if scene.id == scene_id:
                    out: dict[str, Any] = scene.live_readout() if hasattr(scene, "live_readout") else {}
                    readout = scene.readout()
                    if readout is not None:
                        out["readout"] = readout.as_dict()
                    if scene.animated:
                        out["playback"] = session.playback()
                    return out
        return None

    def graph(
        self, session_id: str, *, since_s: float = -math.inf, max_points: int = DEFAULT_MAX_POINTS
    ) -> dict[str, Any] | None:
        """The first viewer's kept motion later than ``since_s`` (s) as graphs: every series, invariant and energy
        part against simulated time, at most ``max_points`` frames (:mod:`.graph`); None for a session without a
        scene. ValueError naming the field for a bad ``since_s`` or ``max_points``."""
        check_graph_request(since_s=since_s, max_points=max_points)
        session = self._find(session_id)
        if session is None:
            return None
        note = no_graph_note(self.scene_class(session.scene_id))
        if note is not None:
            return empty_graph(session.scene_id, note)
        with session.lock:  # only the frames are copied here: the evaluation runs after, while the scene moves on
            client_id, scene = next(iter(session.instances.items()), (None, None))
            history = session.histories.get(client_id) if client_id is not None else None
            if scene is None or history is None or not len(history):
                return empty_graph(
                    session.scene_id, "no viewer is showing this scene yet: its motion is kept once one connects"
                )
            frames = history.since(since_s)
            span = history.span_s()
            latest = frames[-1] if frames else (span[1], history.at(span[1])) if span is not None else None
            model, params = scene.run_model, scene.physical_params()  # type: ignore[attr-defined]  # an IntegratedScene: no_graph_note said so
        return motion_graph(session.scene_id, model, params, frames, latest, max_points=max_points)

    def viewer_count(self, session_id: str) -> int:
        session = self._find(session_id)
        return 0 if session is None else len(session.instances)

    def total_viewers(self) -> int:
        with self._lock:
            return len(self._client_session)

    def session_scene(self, session_id: str) -> str | None:
        session = self._find(session_id)
        return None if session is None else session.scene_id

    def close_session(self, session_id: str) -> None:
        """Forget a page's session (the front evicted it): its viewers' scenes are closed and their messages say so."""
        with self._lock:
            session = self._sessions.get(session_id)
            if session is None or session.stage is not None:
                return
            del self._sessions[session_id]
            for client_id in session.instances:
                self._client_session.pop(client_id, None)
        with session.lock:
            for scene in list(session.instances.values()):
                with contextlib.suppress(Exception):
                    scene.close()
                    tell_viewer(scene.client, "This scene was closed to make room for others: reload the page.")
            session.clear_instances()

    def ping(self) -> float:
        """This host's monotonic clock (s): an answer means the worker is alive and not stopped."""
        return time.monotonic()

    # -- what survives a worker's restart ----------------------------------------------------
    def snapshot(self, session_ids: list[str] | None = None) -> dict[str, dict[str, Any]]:
        """Each session's restorable state (:meth:`Session.snapshot`): every session, or the ones named that exist.
        A session busy with a long request is skipped this time (the front keeps its previous snapshot)."""
        with self._lock:
            wanted = (
                list(self._sessions.items())
                if session_ids is None
                else [(sid, self._sessions[sid]) for sid in session_ids if sid in self._sessions]
            )
        out: dict[str, dict[str, Any]] = {}
        for session_id, session in wanted:
            if session.lock.acquire(timeout=0.05):
                try:
                    out[session_id] = session.snapshot()
                finally:
                    session.lock.release()
        return out

    def restore(self, session_id: str, snapshot: Mapping[str, Any]) -> None:
        """Make the session as ``snapshot`` (:meth:`Session.snapshot`) describes it: its scene and parameters, play
        state and time scale, its motion (the next viewer resumes it) and camera. A stage is opened again and resumed
        at once. Raises ``ValueError`` for a snapshot whose scene or parameters do not fit (and restores nothing); a
        kept
        camera that does not fit is left out (logged), the rest restored."""
        scene_id = snapshot["scene_id"]
        motion = snapshot.get("motion")
        if snapshot.get("stage"):
            self.open_stage(session_id, scene_id, snapshot["params"])
            if motion is not None:
                self.resume_from(session_id, motion)
        else:
            self.set_params(scene_id, session_id, snapshot["params"])
            session = self._existing(session_id)
            with session.lock:
                if motion is not None:
                    if session.instances:
                        for scene in session.instances.values():
                            scene.resume_from(motion)
                            scene.redraw()
                    else:
                        session.resume_motion = dict(motion)
                elif snapshot.get("go_to_s") is not None:
                    session.go_to_s = float(snapshot["go_to_s"])
        self.set_playback(
            session_id, playing=bool(snapshot.get("playing", True)), time_scale=float(snapshot.get("time_scale", 1.0))
        )
        camera = snapshot.get("camera")
        if (
            camera is not None
        ):  # last: a camera that does not fit loses only itself (the viewer starts at the scene's pose)
            try:
                self.set_playback(session_id, camera=camera)
            except ValueError as exc:
                log.warning("session %s: its kept camera was not restored: %s", session_id, exc)

    # -- viser callbacks ------------------------------------------------------------
    def _on_connect(self, client: viser.ClientHandle) -> None:
        """A viewer connected at ``/{scene_id}/{session_id}[?client=<address>]`` (the relay's path; the address is the
        browser's, for its fair share). It is shown the session's scene if the session exists and shows that scene;
        a viewer never creates a session, replaces its scene or takes a stage."""
        assert self._server is not None
        path = connection_path(self._server, client) or ""
        route, _, query = path.partition("?")
        parts = [p for p in route.split("/") if p]
        owner = next((v for k, _, v in (item.partition("=") for item in query.split("&")) if k == "client" and v), None)
        if (
            len(parts) != 2
            or parts[0] not in self.scenes
            or not SESSION_ID_PATTERN.match(parts[1])
            or parts[1].startswith(STAGE_PREFIX)
        ):
            log.warning("viewer connected with unusable path %r", path)
            tell_viewer(client, f"No such scene: {route}")
            return
        scene_id, session_id = parts
        with self._lock:
            session = self._sessions.get(session_id)
            refusal = (
                "This scene has not been opened by its page yet: reload the page."
                if session is None
                else "This viewer is for another scene than its page shows: reload the page."
                if session.scene_id != scene_id or session.stage is not None
                else f"This scene already has {MAX_VIEWERS_PER_SESSION} viewers open."
                if len(session.instances) >= MAX_VIEWERS_PER_SESSION
                else None
            )
            if refusal is not None or session is None:
                log.info("viewer of %s/%s refused: %s", scene_id, session_id, refusal)
                tell_viewer(client, refusal or "")
                return
            session.last_used_s = time.monotonic()
            self._client_session[client.client_id] = session_id
        with session.lock:
            try:
                scene = self.scenes[scene_id](client, session.params)
            except Exception:
                log.exception("building scene %s failed", scene_id)
                tell_viewer(client, "This scene failed to build. The error is in the server log.")
                return
            if session.resume_motion is not None:
                motion, session.resume_motion = session.resume_motion, None
                try:
                    scene.resume_from(motion)
                    scene.redraw()
                except ValueError:
                    log.warning(
                        "session %s: the motion handed over does not fit scene %s; it starts at t = 0",
                        session_id,
                        scene_id,
                    )
            if session.go_to_s is not None:
                go_to_s, session.go_to_s = session.go_to_s, None
                try:
                    with self._one_long_request(True):
                        self._paced_go_to(scene, go_to_s)
                except (RequestTooCostly, HostBusy) as exc:  # the motion starts at t = 0 and the scene says why
                    scene.status = f"the motion at {go_to_s:g} s was not computed: {str(exc).removeprefix('go_to_s: ')}"
            if session.camera is not None:
                place_camera(client, **session.camera)
                session.camera = None
            session.add_instance(client.client_id, scene, client=owner)

    def _on_disconnect(self, client: viser.ClientHandle) -> None:
        with self._lock:
            session_id = self._client_session.pop(client.client_id, None)
            session = self._sessions.get(session_id) if session_id else None
        if session is not None:
            with session.lock:
                scene = session.remove_instance(client.client_id)
                session.last_used_s = time.monotonic()
                if scene is not None and not session.instances:
                    # The last viewer went (a lost connection, a phone asleep, a reload): the next one continues
                    # from here, seen from the same camera, instead of starting the motion again.
                    session.resume_motion = scene.motion_state()
                    camera = viewer_camera(client)
                    if camera is not None:
                        session.camera = {k: tuple(v) for k, v in camera.items()}  # type: ignore[misc]

    def _close_instances(self, session: Session) -> None:
        """Close a replaced session's scenes (caller holds the host lock; this takes the session's)."""
        with session.lock:
            for client_id, scene in list(session.instances.items()):
                self._client_session.pop(client_id, None)
                try:
                    scene.close()
                except Exception:
                    log.exception("closing scene failed")
            session.clear_instances()

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
            self.run_frame(dt)

    def run_frame(self, dt_s: float) -> None:
        """One displayed frame: every playing session's scenes advance ``time_scale`` steps of ``dt_s`` (s) on average
        (the fraction carried to the next frame), and each step is kept in its history for the scrubber.

        Fair shares (:mod:`.fair_share`): when the viewers' measured costs do not fit in the frame loop's share of the
        frame, the frame is shared max-min fairly by client, and a client over its allowance has its viewers advance
        on only that fraction of frames. A session busy with a request (its lock held) misses this frame rather than
        making everyone wait."""
        with self._lock:
            sessions = [sess for sess in self._sessions.values() if sess.instances]
        demand: dict[str, float] = {}
        viewers: dict[str, int] = {}
        for session in sessions:
            if session.playing:
                for share in list(session.shares.values()):
                    if share.client is not None:
                        demand[share.client] = demand.get(share.client, 0.0) + share.frame_s * session.time_scale
                        viewers[share.client] = viewers.get(share.client, 0) + 1
        allowed = allowances(demand, capacity_s=FRAME_LOOP_SHARE * dt_s) if demand else {}
        wakeups = BatchedWakeups()  # viser's sender is woken once for every viewer's frame, not once per viewer
        for session in sessions:
            # Play state is read under the session's lock, the one set_playback holds while it changes it, so a
            # pause that has returned is never followed by one more frame already decided on before it.
            if not session.lock.acquire(blocking=False):
                continue
            try:
                if session.playing:
                    self._advance_session(session, dt_s, demand, allowed, viewers, wakeups)
            finally:
                session.lock.release()
        wakeups.flush()

    def _advance_session(
        self,
        session: Session,
        dt_s: float,
        demand: Mapping[str, float],
        allowed: Mapping[str, float],
        viewers: Mapping[str, int],
        wakeups: BatchedWakeups,
    ) -> None:
        """Advance each viewer's scene of a playing session by the frames it is owed (caller holds the session's
        lock)."""
        for client_id, scene in list(session.instances.items()):
            share = session.shares.get(client_id)
            history = session.histories.get(client_id)
            if share is None:
                continue
            allowance = allowed.get(share.client or "", math.inf)
            client_demand = demand.get(share.client or "", 0.0)
            if client_demand > allowance:
                share.rate = allowance / client_demand
                share.note = slowdown_note(
                    share.rate, client_demand, allowance, viewers=viewers.get(share.client or "", 1)
                )
            else:
                share.rate, share.note = 1.0, ""
            # time_scale frames per displayed frame on average: 0.5 advances every other frame, 2 twice a frame.
            share.credit += session.time_scale * share.rate
            frames = int(share.credit)
            share.credit -= frames
            for _ in range(frames):
                if not scene.animated or scene.status:
                    break
                started = time.perf_counter()
                self._advance(scene, dt_s, wakeups)
                share.cost.add(time.perf_counter() - started)
                share.physics_s = scene.motion_cost_s() or 0.0
                if history is not None:
                    history.record(scene.motion_state())

    @staticmethod
    def _advance(scene: Scene, dt_s: float, wakeups: BatchedWakeups) -> None:
        try:
            with wakeups.atomic(scene.client):
                scene.advance(dt_s)
        except Exception:
            log.exception("advancing scene %s failed; it is paused", scene.id)
            scene.status = "paused after an error (see the server log)"
