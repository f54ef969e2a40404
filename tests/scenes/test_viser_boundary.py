"""viser's private API is used in one module only, for the pinned version, and each use works.

The compat functions are checked against a real loopback viser server and a
real websocket client (what a browser's viewer does, without the browser).
"""

from __future__ import annotations

import contextlib
import io
import re
import time
from pathlib import Path

import msgspec
import numpy as np
import pytest
import viser
import zstandard
from websockets.sync.client import connect

from app.scenes import viser_boundary
from app.scenes.viser_boundary import (
    connection_path,
    scene_node_names,
    set_initial_camera,
    viewer_camera_message,
)

ROOT = Path(__file__).resolve().parents[2]
PRIVATE_USE = re.compile(r"\bviser\._(?!_)|from viser import _|\._websock")


def test_viser_is_the_version_the_private_calls_were_checked_against():
    assert viser.__version__ == viser_boundary.CHECKED_VISER_VERSION == "1.1.1", (
        f"viser {viser.__version__} is installed: app/scenes/viser_boundary.py uses viser's private API and was "
        "checked against 1.1.1 only; re-check every function there (and its tests) against the new version, then update the pin."
    )


def test_no_other_module_uses_viser_private_api():
    offenders = [
        f"{path.relative_to(ROOT)}:{number}"
        for folder in ("app", "tests")
        for path in sorted((ROOT / folder).rglob("*.py"))
        if path.name not in ("viser_boundary.py", "test_viser_boundary.py")
        for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), start=1)
        if PRIVATE_USE.search(line)
    ]
    assert offenders == [], "viser's private API is used outside app/scenes/viser_boundary.py: " + ", ".join(offenders)


@contextlib.contextmanager
def server_with_viewer(path: str):
    """A loopback server and one viewer connected at ``path``; yields (server, client handle, socket)."""
    with contextlib.redirect_stdout(io.StringIO()):
        server = viser.ViserServer(host="127.0.0.1", port=0, verbose=False)
    socket = connect(f"ws://127.0.0.1:{server.get_port()}{path}", subprotocols=[f"viser-v{viser.__version__}"], max_size=None)
    try:
        socket.send(viewer_camera_message())  # viser lists the client only after this message
        deadline = time.monotonic() + 10.0
        while not server.get_clients():
            assert time.monotonic() < deadline, "viser never counted the viewer as connected"
            time.sleep(0.01)
        yield server, next(iter(server.get_clients().values())), socket
    finally:
        socket.close()
        server.stop()


def received_messages(socket, *, seconds: float) -> list[dict]:
    """Every message dict the viewer received within ``seconds`` (batches flattened)."""
    found: list[dict] = []

    def walk(item) -> None:
        if isinstance(item, dict):
            if "type" in item:
                found.append(item)
            for value in item.values():
                walk(value)
        elif isinstance(item, (list, tuple)):
            for value in item:
                walk(value)

    deadline = time.monotonic() + seconds
    while (remaining := deadline - time.monotonic()) > 0:
        try:
            raw = socket.recv(timeout=remaining)
        except TimeoutError:
            break
        if isinstance(raw, bytes):  # 8-byte sizes (decompressed, compressed), then zstd-compressed msgpack
            compressed_size = int.from_bytes(raw[8:16], "little")
            walk(msgspec.msgpack.decode(zstandard.ZstdDecompressor().decompress(raw[16 : 16 + compressed_size])))
    return found


def test_connection_path_is_the_viewer_request_path():
    with server_with_viewer("/heavy-top/session-1234?x=1") as (server, client, _):
        assert connection_path(server, client) == "/heavy-top/session-1234?x=1"


def test_initial_camera_is_sent_to_that_viewer():
    with server_with_viewer("/") as (_, client, socket):
        received_messages(socket, seconds=0.3)  # the connection's own start-up messages
        set_initial_camera(client, position=(1.0, -2.0, 3.0), look_at=(0.5, 0.0, 0.25))
        messages = received_messages(socket, seconds=1.0)
    by_type = {m["type"]: m for m in messages}
    position, look_at = by_type["SetCameraPositionMessage"], by_type["SetCameraLookAtMessage"]
    assert position["initial"] and look_at["initial"]
    assert np.allclose(position["position"], (1.0, -2.0, 3.0)) and np.allclose(look_at["look_at"], (0.5, 0.0, 0.25))


def test_scene_node_names_lists_what_is_on_a_client_scene():
    with server_with_viewer("/") as (_, client, _socket):
        assert scene_node_names(client.scene) == set()
        handle = client.scene.add_icosphere("/ball", radius=0.1)
        assert scene_node_names(client.scene) == {"/ball"}
        handle.remove()
        assert scene_node_names(client.scene) == set()


def test_move_node_sends_what_the_setters_send_and_skips_unchanged_values():
    with server_with_viewer("/") as (_, client, socket):
        frame = client.scene.add_frame("/body", show_axes=False)
        received_messages(socket, seconds=0.3)
        with client.atomic():
            viser_boundary.move_node(frame, position=(1.0, 2.0, 3.0), wxyz=(0.0, 1.0, 0.0, 0.0))
        moved = received_messages(socket, seconds=0.5)
        viser_boundary.move_node(frame, position=np.array([1.0, 2.0, 3.0]), wxyz=(0.0, 1.0, 0.0, 0.0))  # unchanged
        unchanged = received_messages(socket, seconds=0.3)
        frame.remove()
        with pytest.raises(RuntimeError, match="removed"):
            viser_boundary.move_node(frame, position=(0.0, 0.0, 0.0))
    by_type = {m["type"]: m for m in moved}
    assert by_type["SetPositionMessage"]["name"] == "/body" and by_type["SetPositionMessage"]["position"] == [1.0, 2.0, 3.0]
    assert by_type["SetOrientationMessage"]["wxyz"] == [0.0, 1.0, 0.0, 0.0]
    assert np.array_equal(frame.position, [1.0, 2.0, 3.0]) and np.array_equal(frame.wxyz, [0.0, 1.0, 0.0, 0.0])  # reads agree
    assert not [m for m in unchanged if m["type"] in ("SetPositionMessage", "SetOrientationMessage")]


def test_update_node_sends_changed_properties_in_one_message_with_the_stored_dtype():
    with server_with_viewer("/") as (_, client, socket):
        segments = client.scene.add_line_segments("/path", np.zeros((2, 2, 3), np.float32), (255, 0, 0))
        label = client.scene.add_label("/label", "before")
        received_messages(socket, seconds=0.3)
        points = np.arange(18, dtype=float).reshape(3, 2, 3)
        viser_boundary.update_node(segments, points=points)
        points[:] = -1.0  # the caller's buffer may be reused at once
        viser_boundary.update_node(label, text="after")
        viser_boundary.update_node(label, text="after")  # unchanged: nothing sent
        messages = [m for m in received_messages(socket, seconds=0.5) if m["type"] == "SceneNodeUpdateMessage"]
        with pytest.raises(TypeError, match="no property 'pionts'"):
            viser_boundary.update_node(segments, pionts=points)
    assert segments.points.dtype == np.float32 and np.array_equal(segments.points, np.arange(18).reshape(3, 2, 3))
    assert label.text == "after"
    assert [(m["name"], sorted(m["updates"])) for m in messages] == [("/path", ["points"]), ("/label", ["text"])]


def test_shared_prop_hints_give_every_handle_what_viser_computes_for_it():
    from typing import get_type_hints

    with server_with_viewer("/") as (_, client, _socket):
        before = client.scene.add_line_segments("/a", np.zeros((1, 2, 3), np.float32), (255, 0, 0))
        viser_boundary.share_prop_hints()
        viser_boundary.share_prop_hints()  # idempotent
        handles = [
            before,
            client.scene.add_line_segments("/b", np.zeros((1, 2, 3), np.float32), (255, 0, 0)),
            client.scene.add_label("/c", "text"),
            client.scene.add_frame("/d"),
        ]
        for handle in handles:
            assert handle._prop_hints == get_type_hints(type(handle._impl.props))
        handles[1].points = np.ones((2, 2, 3))  # the setter path still casts with the hints
        assert handles[1].points.dtype == np.float32 and handles[1].points.shape == (2, 2, 3)


def test_batched_wakeups_group_a_clients_messages_and_deliver_them_once_woken():
    with server_with_viewer("/") as (server, client, socket):
        label = client.scene.add_label("/label", "before")
        received_messages(socket, seconds=0.3)
        wakeups = viser_boundary.BatchedWakeups()
        with wakeups.atomic(client):
            label.text = "first"
            label.text = "second"  # grouped: only the last value of a property is sent
            held = received_messages(socket, seconds=0.3)
        wakeups.flush()
        delivered = received_messages(socket, seconds=0.5)
    updates = [m["updates"]["text"] for m in delivered if m["type"] == "SceneNodeUpdateMessage"]
    assert not [m for m in held if m["type"] == "SceneNodeUpdateMessage"] and updates == ["second"]


def test_a_push_from_the_frame_loops_thread_leaves_the_senders_waiters_to_its_loop():
    """asyncio.Event is not thread-safe, and viser's push set the buffer's event from the pushing thread: under load
    that raised "deque mutated during iteration" in a student's frame and paused the scene. Now only the loop's
    thread sets it, and every push is still delivered."""
    viser_boundary.make_message_events_thread_safe()
    viser_boundary.make_message_events_thread_safe()  # idempotent
    with server_with_viewer("/") as (server, client, socket):
        buffer = client._websock_connection.get_message_buffer()
        assert isinstance(buffer.message_event, viser_boundary.LoopOnlyEvent)
        label = client.scene.add_label("/label", "before")
        received_messages(socket, seconds=0.3)
        deadline = time.monotonic() + 5.0
        while not buffer.message_event._waiters:  # the sender has sent everything and waits for a message
            assert time.monotonic() < deadline, "viser's sender never waited on its message event"
            time.sleep(0.01)
        waiting = list(buffer.message_event._waiters)
        wakeups = viser_boundary.BatchedWakeups()
        with wakeups.atomic(client):
            label.text = "grouped"  # pushed from this thread, not the loop's: viser set the event (and its waiters) here
        assert not any(waiter.done() for waiter in waiting)
        wakeups.flush()
        grouped = received_messages(socket, seconds=0.5)
        label.text = "alone"  # outside a group: woken on the loop by viser's own call_soon_threadsafe
        alone = received_messages(socket, seconds=0.5)
    texts = [m["updates"]["text"] for m in grouped + alone if m["type"] == "SceneNodeUpdateMessage"]
    assert texts == ["grouped", "alone"]


def test_callback_threads_are_all_started_so_the_count_stays_constant():
    with server_with_viewer("/") as (server, _client, _socket):
        started = viser_boundary.start_callback_threads(server)
        assert started == server._thread_executor._max_workers == 32
        for _ in range(50):  # overlapping callbacks reuse the started threads
            server._thread_executor.submit(time.sleep, 0.001)
        time.sleep(0.2)
        assert len(server._thread_executor._threads) == started
