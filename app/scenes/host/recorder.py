"""Recordings that play offline: a viewer's recent motion as one self-contained HTML file.

What the student just watched is replayed from the motion the host kept for the
scrubber (:class:`~app.scenes.host.history.MotionHistory`), not recomputed: a
fresh instance of the session's scene, with the session's parameters, is built on
a private loopback viser server that no browser ever reaches; viser's scene
serializer records its first drawing (the scene's own nodes and initial camera),
then each kept frame is drawn with the kit's ``resume_from`` + ``redraw`` and
followed by one frame period of recorded time. ``StateSerializer.as_html`` puts the
recording and viser's whole single-file client in one HTML document, which plays
from ``file://`` with no server.

Pace: each kept frame lasts one displayed frame (``1 / frame_rate_hz``), so the
recording plays at the live pace of 1× whatever speed the student was watching at
(the history keeps frames, not the wall-clock times they were shown at), and a
recording of ``seconds`` holds the last ``seconds × frame_rate_hz`` kept frames.
A scene with no kept motion (not animated, or no viewer yet) is recorded as a
still: its first drawing, zero seconds long.

Trails grow over the recording as they did live: ``resume_from`` empties a
scene's trails (a resumed motion is a new one), but the recorded frames are one
consecutive motion, so only the first resume empties them.

One recorder per scene worker, one recording at a time (a lock); the work is
bounded by :data:`MAX_RECORDING_S`, :data:`MAX_RECORDING_FRAMES` and the file by
:data:`MAX_RECORDING_BYTES`.
"""

from __future__ import annotations

import contextlib
import html
import logging
import math
import re
import threading
from collections.abc import Iterator, Mapping, Sequence
from typing import Any

import viser

from app.scenes.host.fair_share import Pace, RequestTooCostly
from app.scenes.host.interface import HostBusy
from app.scenes.kit import Scene
from app.scenes.viser_boundary import BroadcastViewer, quiet_server, stop_quietly

log = logging.getLogger(__name__)

#: Recording length a page may ask for (s of playback), and the default.
RECORDING_SECONDS_RANGE = (1.0, 60.0)
DEFAULT_RECORDING_S = 10.0
#: Most frames one recording replays (60 s at 30 frames/s: all a history keeps).
MAX_RECORDING_FRAMES = 1800
#: Largest recording file (bytes of HTML); the viewer client alone is about 0.8 MB.
MAX_RECORDING_BYTES = 40 * 1024 * 1024
#: Longest a recording waits for the one before it in the same worker (s); after that the request is answered 503
#: with Retry-After (a front thread never waits long on a busy recorder).
RECORDER_WAIT_S = 1.0


class RecordingError(RuntimeError):
    """A recording could not be made (the scene failed to redraw a kept frame)."""


class RecorderBusy(HostBusy):
    """The worker's recorder is making another recording (one at a time): try again in a moment."""


def checked_seconds(seconds: Any) -> float:
    """``seconds`` as a float within :data:`RECORDING_SECONDS_RANGE`; ValueError naming the field otherwise."""
    try:
        value = float(seconds)
    except (TypeError, ValueError):
        raise ValueError("seconds: a number of seconds, 1 to 60") from None
    low, high = RECORDING_SECONDS_RANGE
    if not (math.isfinite(value) and low <= value <= high):
        raise ValueError(f"seconds: {seconds!r} is outside {low:g}–{high:g} s")
    return value


def frames_for(seconds: float, *, frame_rate_hz: float) -> int:
    """Kept frames that fill ``seconds`` of playback at one frame per displayed frame (at most
    :data:`MAX_RECORDING_FRAMES`)."""
    return min(MAX_RECORDING_FRAMES, max(1, round(seconds * frame_rate_hz)))


#: CSS added to the recording's page: viser's scene-tree button is a developer's tool, not the student's.
_RECORDING_CSS = '[aria-label="Show scene tree"]{display:none !important}'


def offline_page(viewer_html: str, *, title: str) -> str:
    """viser's standalone page (``StateSerializer.as_html``) titled ``title`` and without its developer's buttons."""
    head = f"<title>{html.escape(title)}</title><style>{_RECORDING_CSS}</style>"
    page = re.sub(r"<title>[^<]*</title>", "", viewer_html, count=1)
    at = page.index("</head>")
    return page[:at] + head + page[at:]


@contextlib.contextmanager
def _trails_kept(scene: Scene) -> Iterator[None]:
    """Inside the block ``scene.resume_from`` leaves the trails alone: consecutive frames are one motion."""
    scene.clear_trails = lambda: None  # type: ignore[method-assign]  # an instance attribute shadows the method
    try:
        yield
    finally:
        del scene.clear_trails


class SceneRecorder:
    """Makes recordings on one private loopback viser server (started on first use, reused, one recording at a time)."""

    def __init__(self, *, host: str = "127.0.0.1") -> None:
        self._host = host
        self._lock = threading.Lock()
        self._server: viser.ViserServer | None = None

    def stop(self) -> None:
        with self._lock:
            if self._server is not None:
                stop_quietly(self._server)
                self._server = None

    def _ready_server(self) -> viser.ViserServer:
        if self._server is None:
            self._server = quiet_server(host=self._host)
        return self._server

    def record_html(
        self,
        scene_class: type[Scene],
        params: Mapping[str, Any],
        frames: Sequence[tuple[float, Mapping[str, Any]]],
        *,
        frame_period_s: float,
    ) -> str:
        """A standalone HTML recording of ``scene_class`` with ``params`` drawn at each kept motion of ``frames``
        (``(t_s, motion)``, oldest first, at most :data:`MAX_RECORDING_FRAMES`), each shown ``frame_period_s`` s;
        a still of the scene's first drawing when ``frames`` is empty.

        Raises ``ValueError`` for a recording over :data:`MAX_RECORDING_BYTES` or its compute limit (``seconds: …``),
        :class:`RecorderBusy` while another recording is being made, and :class:`RecordingError` when the scene
        cannot draw a kept frame.
        """
        if len(frames) > MAX_RECORDING_FRAMES:
            raise ValueError(f"seconds: at most {MAX_RECORDING_FRAMES} frames in one recording, not {len(frames)}")
        if not self._lock.acquire(timeout=RECORDER_WAIT_S):
            raise RecorderBusy(
                "another recording is being made on this scene worker; try again in a few seconds", retry_after_s=3
            )
        try:
            page = self._record_locked(scene_class, params, frames, frame_period_s=frame_period_s)
        finally:
            self._lock.release()
        size = len(page.encode())
        if size > MAX_RECORDING_BYTES:
            raise ValueError(
                f"seconds: this recording would be {size / 2**20:.0f} MB, over the "
                f"{MAX_RECORDING_BYTES / 2**20:.0f} MB limit; record fewer seconds"
            )
        return page

    def _record_locked(
        self,
        scene_class: type[Scene],
        params: Mapping[str, Any],
        frames: Sequence[tuple[float, Mapping[str, Any]]],
        *,
        frame_period_s: float,
    ) -> str:
        server = self._ready_server()
        scene: Scene | None = None
        serializer = None
        try:
            scene = scene_class(BroadcastViewer(server), params)  # type: ignore[arg-type]  # draws on server.scene
            if frames:
                scene.resume_from(frames[0][1])
                scene.redraw()
            serializer = server.get_scene_serializer()  # the first drawing, nodes and initial camera included
            if frames:
                serializer.insert_sleep(frame_period_s)
                pace = Pace(frames=len(frames) - 1)  # the frame loop keeps drawing everyone while this replays
                with _trails_kept(scene):
                    for _, motion in frames[1:]:
                        scene.resume_from(motion)
                        scene.redraw()
                        serializer.insert_sleep(frame_period_s)
                        if not pace():
                            raise RequestTooCostly.over_limit(
                                "seconds", f"drawing {len(frames)} frames of this scene again", "record fewer seconds"
                            )
            viewer_html, serializer = serializer.as_html(), None
            return offline_page(viewer_html, title=f"{scene_class.title} — a Dynamics Lab recording")
        except RequestTooCostly:
            raise
        except ValueError as exc:  # a kept motion the scene refuses: the history and the scene disagree
            raise RecordingError(f"{scene_class.id}: a kept frame could not be drawn again ({exc})") from None
        except Exception as exc:  # a scene that fails to build or draw: a clear error, the worker goes on
            log.exception("recording %s failed", scene_class.id)
            raise RecordingError(f"{scene_class.id}: the recording failed ({type(exc).__name__}: {exc})") from None
        finally:
            if serializer is not None:  # stop recording (a serializer left registered would keep every message)
                with contextlib.suppress(Exception):
                    serializer.serialize()
            if scene is not None:
                with contextlib.suppress(Exception):
                    scene.close()
            server.scene.reset()  # the next recording starts from an empty scene
