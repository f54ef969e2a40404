"""The wire format between the front process and a scene worker: one call, one answer.

A call is ``(method, args, kwargs)`` sent over a ``multiprocessing.connection``
on loopback (authenticated with the pool's random key). The answer is
``("ok", value)`` or an error the front raises again as the same kind of
exception the in-process host would have raised, so routes do not care where
the scene lives. Only the methods in :data:`WORKER_METHODS` may be called.
"""

from __future__ import annotations

from typing import Any

from app.physics.core.parameters import ParameterError
from app.scenes.host.host import UnknownSceneError

#: SceneHost methods a worker answers (everything the routes and the relay need).
WORKER_METHODS = frozenset({
    "set_params", "session_params", "live_readout", "viewer_count", "viewer_url",
    "set_playback", "playback", "open_stage", "close_stage", "stage_viewers", "stage_viewer_url", "motion_state", "resume_from", "camera", "graph",
    "recording_html",
})  # fmt: skip

Answer = tuple[Any, ...]


class WorkerUnavailableError(RuntimeError):
    """The scene worker that serves a session did not answer (it is being restarted)."""


def encode_error(exc: BaseException) -> Answer:
    """An exception raised by the host, as data that crosses a process boundary."""
    if isinstance(exc, ParameterError):
        return ("parameter_error", *exc.carried())
    if isinstance(exc, UnknownSceneError):
        return ("unknown_scene", exc.args[0] if exc.args else "")
    if isinstance(exc, ValueError):
        return ("value_error", str(exc))
    return ("internal_error", f"{type(exc).__name__}: {exc}")


def raise_answer(answer: Answer) -> Any:
    """The value of an ``("ok", value)`` answer, or the error it carries raised again."""
    kind = answer[0]
    if kind == "ok":
        return answer[1]
    if kind == "parameter_error":
        raise ParameterError.from_carried(answer[1:])
    if kind == "unknown_scene":
        raise UnknownSceneError(answer[1])
    if kind == "value_error":
        raise ValueError(answer[1])
    raise RuntimeError(f"scene worker failed: {answer[1]}")
