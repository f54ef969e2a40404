"""Recordings that play offline (issue 15 item 4), checked headless by decoding the file viser's client would play.

A recording is viser's single-file client with the recording inside (``window.__VISER_EMBED_DATA__``: base64 of
an 8-byte size and a zstd stream of an 8-byte msgpack length, the msgpack, then binary buffers). Decoded here:
- its length is the seconds asked for, one displayed frame (1/30 s) per kept frame, to round-off (1e-9 s);
- the heavy top's body gets one orientation message per kept frame (the frame count, exactly: its spin turns it
  every frame, and an unchanged pose would send nothing);
- each frame's body orientation and label position in the recording equal what the live scene drew at that
  stored state, to 1e-6 (they are the same floats redrawn from the same state: the kit's resume-and-redraw is
  exact to 1e-9 by tests/scenes/test_motion_states.py, and msgpack carries float64 unchanged; 1e-6 in quaternion
  components or metres is far below a pixel);
- a scene with no kept motion is a still (zero seconds, every node drawn at time 0);
- bad input and failures are clear errors, and the recorder keeps working after one.
"""

from __future__ import annotations

import base64
import re
import threading
from collections.abc import Iterator
import socket

import msgspec
import numpy as np
import pytest
import viser
import zstandard
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect

from app.scenes import SCENES
from app.scenes.host import recorder
from app.scenes.host.host import SceneHost, UnknownSceneError
from app.scenes.host.pool import WorkerPool
from app.scenes.host.recorder import RecordingError, SceneRecorder
from app.scenes.host.interface import WORKER_CALLS
from app.scenes.host.rpc import connect as connect_to_worker
from app.scenes.host.rpc import raise_answer
from app.scenes.viser_boundary import viewer_camera_message
from app.scenes.host.worker import _answer_calls
from tests.conftest import wait_until

SESSION = "recording-test-1"
FRAME_S = 1.0 / 30.0
DRAWN_ATOL = 1e-6


#: The scenes recorded here: an integrated scene with a trail, a closed-form linkage, a scene with no motion.
RECORDED = ("heavy-top", "four-bar", "inertia-explorer")


@pytest.fixture(scope="module")
def host() -> Iterator[SceneHost]:
    """A host serving only the scenes recorded here, on loopback."""
    scene_host = SceneHost({scene_id: SCENES[scene_id] for scene_id in RECORDED})
    scene_host.start()
    try:
        yield scene_host
    finally:
        scene_host.stop()


def connect_viewer(host: SceneHost, scene_id: str, session_id: str):
    """A websocket that connects to the session as a browser's viewer does, and discards what it receives."""
    socket = connect(f"{host.url}/{scene_id}/{session_id}", subprotocols=[f"viser-v{viser.__version__}"], max_size=None)  # type: ignore[list-item]
    socket.send(viewer_camera_message())

    def drain() -> None:
        try:
            while True:
                socket.recv()
        except (ConnectionClosed, OSError):
            return

    threading.Thread(target=drain, daemon=True).start()
    wait_until(lambda: host.viewer_count(session_id) == 1, timeout_s=20, what=f"the {scene_id} viewer to connect")
    return socket


def decoded(page: str) -> dict:
    """The recording inside a standalone page: ``{"durationSeconds", "messages": [(t_s, message)], …}``."""
    data = re.search(r'window\.__VISER_EMBED_DATA__="([A-Za-z0-9+/=]+)"', page)
    assert data is not None, "no recording in the page"
    raw = base64.b64decode(data.group(1))
    inner = zstandard.ZstdDecompressor().decompress(raw[8:], max_output_size=int.from_bytes(raw[:8], "little"))
    length = int.from_bytes(inner[:8], "little")
    return msgspec.msgpack.decode(inner[8 : 8 + length])


def timeline(recording: dict, message_type: str, node: str, field: str) -> dict[int, np.ndarray]:
    """Frame index -> the last ``field`` value a ``message_type`` for ``node`` set at that frame's recorded time."""
    out: dict[int, np.ndarray] = {}
    for t_s, message in recording["messages"]:
        if message["type"] == message_type and message["name"] == node:
            out[round(t_s / FRAME_S)] = np.array(message[field], float)
    return out


def test_a_recording_replays_the_kept_frames_as_the_scene_drew_them(host):
    host.set_params("heavy-top", SESSION, {})
    socket = connect_viewer(host, "heavy-top", SESSION)
    try:
        host.set_playback(SESSION, playing=False, reset=True)  # the kept motion is now the start alone
        drawn_wxyz, drawn_label = [], []
        for _ in range(90):  # what the student watched, frame by frame, as the live scene drew it
            host.set_playback(SESSION, step=1)
            with host.inspect(SESSION) as (scene,):
                drawn_wxyz.append(np.array(scene.body._impl.wxyz, float))
                drawn_label.append(np.array(scene.arrow_labels[0]._impl.position, float))
                body, label = scene.body._impl.name, scene.arrow_labels[0]._impl.name

        page = host.recording_html("heavy-top", SESSION, seconds=2.0)
    finally:
        socket.close()
    recording = decoded(page)
    frames = 60  # 2 s at 30 frames/s: the last 60 of the 91 kept frames
    assert recording["durationSeconds"] == pytest.approx(2.0, abs=1e-9)
    orientations = timeline(recording, "SetOrientationMessage", body, "wxyz")
    assert len(orientations) == frames and sorted(orientations) == list(range(frames))
    positions = timeline(recording, "SetPositionMessage", label, "position")
    for k in range(frames):
        live = len(drawn_wxyz) - frames + k  # recording frame k is the (frames − k)-th last frame drawn live
        np.testing.assert_allclose(orientations[k], drawn_wxyz[live], rtol=0, atol=DRAWN_ATOL, err_msg=f"frame {k}")
        if k in positions:
            np.testing.assert_allclose(positions[k], drawn_label[live], rtol=0, atol=DRAWN_ATOL, err_msg=f"frame {k}")
    assert len(positions) >= frames - 1, "the label moves with L every frame"
    assert "<title>The heavy symmetric top — a Dynamics Lab recording</title>" in page and page.count("<title>") == 1
    assert 'aria-label="Show scene tree"]{display:none' in page  # viser's developer button is hidden


def test_a_session_with_no_kept_motion_is_recorded_as_a_still(host):
    still_session = "recording-still-1"
    host.set_params("inertia-explorer", still_session, {})
    socket = connect_viewer(host, "inertia-explorer", still_session)
    try:
        recording = decoded(host.recording_html("inertia-explorer", still_session, seconds=10))
    finally:
        socket.close()
    assert recording["durationSeconds"] == 0.0
    assert {t for t, _ in recording["messages"]} == {0.0}
    created = [m for _, m in recording["messages"] if m["type"].endswith("Message") and "name" in m and m["name"]]
    assert len(created) > 5, "the scene's nodes are in the still"

    host.set_params("four-bar", "recording-noview-1", {})  # animated, but no viewer yet: nothing kept, a still
    assert decoded(host.recording_html("four-bar", "recording-noview-1", seconds=5))["durationSeconds"] == 0.0


def test_bad_requests_are_clear_errors(host):
    host.set_params("four-bar", "recording-errors-1", {})
    for seconds in (0.5, 61, float("nan"), "ten"):
        with pytest.raises(ValueError, match="seconds"):
            host.recording_html("four-bar", "recording-errors-1", seconds=seconds)
    assert host.recording_html("heavy-top", "recording-errors-1", seconds=5) is None  # the session shows another scene
    assert host.recording_html("four-bar", "recording-nobody-1", seconds=5) is None  # no such session
    with pytest.raises(UnknownSceneError):
        host.recording_html("no-such-scene", "recording-errors-1", seconds=5)


def test_a_failed_recording_is_an_error_and_the_recorder_goes_on(monkeypatch):
    four_bar = SCENES["four-bar"]
    params = four_bar.parameters.defaults()
    kept = [(0.0, {"t_s": 0.0}), (FRAME_S, {"t_s": FRAME_S})]
    rec = SceneRecorder()
    try:
        with pytest.raises(RecordingError, match="could not be drawn again"):
            rec.record_html(four_bar, params, [(0.0, {"t_s": -1.0})], frame_period_s=FRAME_S)
        monkeypatch.setattr(recorder, "MAX_RECORDING_BYTES", 1000)
        with pytest.raises(ValueError, match="over the 0 MB limit"):
            rec.record_html(four_bar, params, kept, frame_period_s=FRAME_S)
        monkeypatch.undo()
        assert decoded(rec.record_html(four_bar, params, kept, frame_period_s=FRAME_S))["durationSeconds"] == pytest.approx(2 * FRAME_S)
        with pytest.raises(ValueError, match="at most 1800 frames"):
            rec.record_html(four_bar, params, kept * 901, frame_period_s=FRAME_S)
    finally:
        rec.stop()


def test_a_workers_recording_crosses_the_process_boundary(monkeypatch):
    """The pool forwards the call to the session's worker, the worker's allow-list has it, and a page of a megabyte
    comes back whole over the same kind of connection (a pipe here; loopback in a pool)."""
    assert "recording_html" in WORKER_CALLS
    page = "<html>" + "x" * 2_000_000 + "</html>"

    class Host:
        def recording_html(self, scene_id: str, session_id: str, *, seconds: float) -> str:
            assert (scene_id, session_id, seconds) == ("heavy-top", SESSION, 5.0)
            return page

    key = b"k" * 32
    listener = socket.create_server(("127.0.0.1", 0))
    threading.Thread(target=lambda: _answer_calls(listener.accept()[0], key, Host()), daemon=True).start()
    front = connect_to_worker(listener.getsockname(), key, io_timeout_s=10.0)
    front.send(("recording_html", ("heavy-top", SESSION), {"seconds": 5.0}))
    assert raise_answer(front.recv()) == page
    front.close()
    listener.close()

    pool = WorkerPool({}, workers=1)
    calls = []
    monkeypatch.setattr(pool, "_call", lambda index, call, args, kwargs, **options: calls.append((index, call.name, args, kwargs)) or page)
    pool._pinned[SESSION], pool._pinned_count[0] = 0, 1  # as the session's first parameters would have pinned it
    assert pool.recording_html("heavy-top", SESSION, seconds=5.0) == page
    assert calls == [(0, "recording_html", ("heavy-top", SESSION), {"seconds": 5.0})]
