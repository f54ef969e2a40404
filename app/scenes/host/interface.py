"""What the front asks of a scene host: one typed interface, wherever the scenes run.

The routes, the viewer relay and the rooms call a scene host through
:class:`SceneHostInterface`. :class:`~app.scenes.host.host.SceneHost` implements
it in this process (``--workers 0``, tests); :class:`~app.scenes.host.pool.WorkerPool`
implements it by calling the scene worker that holds the session. Each call is
declared once here, with what the pool needs to route it (:class:`Call`): the
worker's call table (:data:`WORKER_CALLS`) and the pool's forwarders are derived
from these declarations, never written out again. Two questions about where the
scenes run (``viewer_url``, ``worker_states``) are answered by each host itself
and are declared here without :func:`call`.

Every call that names a session is routed to the worker the session is pinned to.
A session is pinned only by a call that creates it (``creates``: the page's
first parameters, a room's stage, a restore after a worker restart); a call about
a session nobody created answers :attr:`Call.unknown` without reaching a worker,
so a flood of made-up ids costs nothing and pins nothing.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, Protocol, TypeVar

#: What a call answers for a session no worker holds: raise ``ValueError`` (the session has no scene yet).
RAISE = object()


class HostBusy(RuntimeError):
    """The host cannot take this request now (its recorder is making another recording, a worker is not answering,
    the derivations' places are taken): answered ``status`` (503, or 429 for a queue that is full) with
    ``Retry-After: retry_after_s``."""

    def __init__(self, message: str, *, retry_after_s: int = 2, status: int = 503) -> None:
        super().__init__(message)
        self.retry_after_s = retry_after_s
        self.status = status


@dataclass(frozen=True)
class Call:
    """How one call of the interface crosses to a scene worker.

    ``answer_timeout_s``: longest wait for the worker's answer (s), beyond which the
    worker counts as not answering (503). ``creates``: the call may create the
    session, so it pins it to a worker. ``unknown``: the answer for a session no
    worker holds (:data:`RAISE`: a ValueError saying it has no scene yet).
    ``every_worker``: the call names no session and goes to each worker.
    """

    name: str
    answer_timeout_s: float = 5.0
    creates: bool = False
    unknown: Any = None
    every_worker: bool = False


F = TypeVar("F", bound=Callable[..., Any])
CALLS: dict[str, Call] = {}


def call(
    *, answer_timeout_s: float = 5.0, creates: bool = False, unknown: Any = None, every_worker: bool = False
) -> Callable[[F], F]:
    """Declare an interface method as a call a worker answers (see :class:`Call`)."""

    def declare(method: F) -> F:
        CALLS[method.__name__] = Call(method.__name__, answer_timeout_s, creates, unknown, every_worker)
        return method

    return declare


#: Calls whose work depends on what a student typed: validating a typed curve or Lagrangian compiles it (a derivation
#: is bounded to 20 s in its own process), and a recording replays up to 60 s of frames.
SLOW_ANSWER_S = 30.0
#: A worker that does not answer a ping within this long (s) is marked not answering (its calls get 503).
PING_TIMEOUT_S = 1.0


class SceneHostInterface(Protocol):
    """The scene host as the front sees it. Session ids are ``[A-Za-z0-9_-]{8,64}``; a room's stage is ``room-<id>``."""

    scenes: Mapping[str, Any]

    def scene_class(self, scene_id: str) -> Any:
        """The scene's class; ``UnknownSceneError`` for an unknown id (answered in the front, never by a worker)."""
        ...

    # -- a page's session ---------------------------------------------------------------------------------
    @call(answer_timeout_s=SLOW_ANSWER_S, creates=True, unknown=RAISE)
    def set_params(
        self, scene_id: str, session_id: str, raw: Mapping[str, Any], *, stage: bool = False
    ) -> dict[str, Any]:
        """Validate ``raw`` and apply it to every viewer of the session (created showing ``scene_id`` if new, or
        switched to it); returns the parameters in force. ``ValueError``/``ParameterError`` and no change on bad
        input."""
        ...

    @call()
    def session_params(self, session_id: str) -> dict[str, Any] | None:
        """The session's parameters, or None for no session."""
        ...

    @call()
    def session_scene(self, session_id: str) -> str | None:
        """The scene the session shows, or None for no session."""
        ...

    @call(answer_timeout_s=SLOW_ANSWER_S, unknown=RAISE)
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
        """Play, pause, step, scrub, restart, speed, camera (``SceneHost.set_playback``); ValueError if no session.
        Stepping and going to a time compute within one request's share (:mod:`app.scenes.host.fair_share`)."""
        ...

    @call()
    def playback(self, session_id: str) -> dict[str, Any] | None:
        """Play state, time scale, simulated time, kept span, camera and viewers in one answer; None for no session."""
        ...

    @call()
    def camera(self, session_id: str) -> dict[str, list[float]] | None: ...

    @call()
    def live_readout(self, scene_id: str, session_id: str) -> dict[str, Any] | None: ...

    @call(unknown=0)
    def viewer_count(self, session_id: str) -> int:
        """Viewers of the session connected to its scene now."""
        ...

    @call(answer_timeout_s=SLOW_ANSWER_S)
    def graph(self, session_id: str, *, since_s: float = ..., max_points: int = ...) -> dict[str, Any] | None: ...

    @call(answer_timeout_s=SLOW_ANSWER_S)
    def recording_html(self, scene_id: str, session_id: str, *, seconds: float) -> str | None: ...

    @call()
    def motion_state(self, session_id: str) -> dict[str, Any] | None: ...

    @call(unknown=RAISE)
    def resume_from(self, session_id: str, motion: Mapping[str, Any]) -> None: ...

    @call(unknown=None)
    def close_session(self, session_id: str) -> None:
        """Forget a page's session and close its viewers' scenes (the front's directory evicted it)."""
        ...

    # -- a room's stage: one scene, every follower -------------------------------------------------------
    @call(answer_timeout_s=SLOW_ANSWER_S, creates=True)
    def open_stage(self, session_id: str, scene_id: str, raw: Mapping[str, Any]) -> dict[str, Any]: ...

    @call()
    def close_stage(self, session_id: str) -> None: ...

    @call()
    def stage_viewer_url(self, session_id: str) -> str | None: ...

    @call(unknown=0)
    def stage_viewers(self, session_id: str) -> int: ...

    # -- what survives a worker's restart --------------------------------------------------------------
    @call(every_worker=True, answer_timeout_s=2.0)
    def snapshot(self, session_ids: list[str] | None = None) -> dict[str, dict[str, Any]]:
        """Each session's restorable state (:class:`~app.scenes.host.host.SessionSnapshot` as a dict): scene,
        parameters, play state, time scale, motion and camera. All sessions, or only those named."""
        ...

    @call(answer_timeout_s=SLOW_ANSWER_S, creates=True)
    def restore(self, session_id: str, snapshot: Mapping[str, Any]) -> None:
        """Make the session as ``snapshot`` describes it (after its worker restarted)."""
        ...

    @call(every_worker=True, answer_timeout_s=PING_TIMEOUT_S)
    def ping(self) -> float:
        """The worker's monotonic clock (s): it answers, so it is alive and not stopped."""
        ...

    @call(every_worker=True, unknown=0)
    def total_viewers(self) -> int:
        """Viewers connected to the host's scenes (every session's)."""
        ...

    # -- answered by each host itself, never a worker call: where the scenes run -----------------------------------
    def viewer_url(self, session_id: str) -> str:
        """The loopback websocket address that serves ``session_id``'s viewers (the relay appends the path);
        ``ValueError`` for a session with no scene, :class:`HostBusy` while its worker restarts."""
        ...

    def worker_states(self) -> list[dict[str, Any]]:
        """Each scene worker's ``{"index", "state"}`` as last seen, without waiting on any ([] when the scenes run in
        this process): for ``/api/health``."""
        ...


#: The calls a scene worker answers, by name: exactly the declared ones.
WORKER_CALLS: Mapping[str, Call] = dict(CALLS)
