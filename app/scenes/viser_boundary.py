"""Every use of viser's private API, in one place (checked against viser 1.1.1, pinned).

viser 1.1.1 lacks four things the scenes need, so these functions reach into
its private modules: a per-client initial camera (viser sets one only
server-wide), the request path of a client's websocket (the host reads the
scene and session ids from it), the encoded first message a browser's
viewer sends (tests stand in for a browser with it), and a cheap way to move
a node or replace its points every frame: :func:`move_node` and
:func:`update_node` queue the same messages as viser's property setters at a
fraction of their cost (the setters validate and compare with ``np.allclose``
on every call, which a class of scenes at 30 frames/s pays thousands of times a
second; ``dynlab bench`` measures a frame's cost: docs/bench/live-frame-costs.svg).
The names of nodes on a scene API are read for tests that check a scene removed
what it built.
``tests/scenes/test_viser_boundary.py`` pins the version and checks each
function against a real loopback server: re-check them all when viser is
upgraded. One is a fix: viser's message buffers set an ``asyncio.Event``
from the frame loop's thread, which is not thread-safe
(:class:`LoopOnlyEvent`). Nothing else in ``app/`` or ``tests/`` may import ``viser._*`` or
touch a ``_websock*`` attribute (a test greps for it).
"""

from __future__ import annotations

import asyncio
import contextlib
import functools
import io
import threading
import typing
from collections.abc import Iterator
from typing import Any, cast

import msgspec
import numpy as np
import viser
from viser import _messages
from viser._viser import InitialCameraConfig

if typing.TYPE_CHECKING:
    from websockets.http11 import Request

#: The viser version these private calls were checked against.
CHECKED_VISER_VERSION = "1.1.1"


def quiet_server(*, host: str) -> viser.ViserServer:
    """A viser server on a free port of ``host`` without the URL viser prints, its share button or its logo."""
    with contextlib.redirect_stdout(io.StringIO()):  # viser prints its URL unconditionally
        server = viser.ViserServer(host=host, port=0, verbose=False)
    server.gui.configure_theme(show_share_button=False, show_logo=False)
    return server


def stop_quietly(server: viser.ViserServer) -> None:
    """Stop ``server`` without the "Server stopped" viser prints."""
    with contextlib.redirect_stdout(io.StringIO()):
        server.stop()


def set_initial_camera(
    client: viser.ClientHandle, *, position: tuple[float, float, float], look_at: tuple[float, float, float]
) -> None:
    """Make ``position`` / ``look_at`` (m, world frame, +Z up) this viewer's start pose and "Reset View" target.

    The message is addressed to this client only, so it never moves another
    student's camera, nor this student's current one.
    """
    initial = InitialCameraConfig(client._websock_connection.queue_message)
    initial.look_at = look_at
    initial.position = position


def connection_path(server: viser.ViserServer, client: viser.ClientHandle) -> str | None:
    """The request path (with any query) of ``client``'s websocket, or None once it has gone."""
    connection = server._websock_server._live_connections.get(client.client_id)
    # A live connection has been accepted, so its handshake request is there.
    return None if connection is None else cast("Request", connection.request).path


def viewer_camera_message(
    *, position: tuple[float, float, float] = (3.0, -3.0, 2.0), look_at: tuple[float, float, float] = (0.0, 0.0, 0.0)
) -> bytes:
    """The encoded camera message a browser's viewer sends first; viser counts a client as connected only after it."""
    camera = _messages.ViewerCameraMessage(
        wxyz=(1.0, 0.0, 0.0, 0.0),
        position=position,
        fov=1.0,
        near=0.01,
        far=100.0,
        image_height=480,
        image_width=640,
        look_at=look_at,
        up_direction=(0.0, 0.0, 1.0),
    )
    return msgspec.msgpack.encode(camera.as_serializable_dict())


def scene_node_names(scene: viser.SceneApi) -> set[str]:
    """Names of the nodes currently on ``scene`` (a client's or the server's scene API)."""
    return {name for name, handle in scene._handle_from_node_name.items() if not handle._impl.removed}


def move_node(
    handle: viser.SceneNodeHandle,
    *,
    position: tuple[float, float, float] | np.ndarray | None = None,
    wxyz: tuple[float, float, float, float] | np.ndarray | None = None,
) -> None:
    """``handle.position = position`` and ``handle.wxyz = wxyz``, for per-frame motion.

    The caller passes finite numbers (a unit quaternion for ``wxyz``); an
    unchanged value sends nothing, as viser's setters do. Anything but a viser
    handle (a stand-in that records what a scene draws) gets plain assignments.
    """
    if not isinstance(handle, viser.SceneNodeHandle):
        for name, value in (("position", position), ("wxyz", wxyz)):
            if value is not None:
                setattr(handle, name, value)
        return
    impl = handle._impl
    if impl.removed:
        raise RuntimeError(f"cannot move the removed scene node {impl.name!r}")
    if position is not None:
        x, y, z = float(position[0]), float(position[1]), float(position[2])
        current = impl.position
        if not (current[0] == x and current[1] == y and current[2] == z):
            current[0], current[1], current[2] = x, y, z
            impl.api._queue_scene_message(_messages.SetPositionMessage(impl.name, (x, y, z)))
    if wxyz is not None:
        w, x, y, z = float(wxyz[0]), float(wxyz[1]), float(wxyz[2]), float(wxyz[3])
        current = impl.wxyz
        if not (current[0] == w and current[1] == x and current[2] == y and current[3] == z):
            current[0], current[1], current[2], current[3] = w, x, y, z
            impl.api._queue_scene_message(_messages.SetOrientationMessage(impl.name, (w, x, y, z)))


def update_node(handle: viser.SceneNodeHandle, **props: Any) -> None:
    """Set several of a node's properties (``points``, ``text``, ``colors``, …) in one message.

    What ``handle.points = …`` does, for per-frame updates: arrays take the
    dtype the node already stores (float32 points, uint8 colours) and are
    copied, so the caller may reuse its buffer. Unchanged values are left out;
    nothing is sent if none changed. A name that is not one of the node's
    properties is a ``TypeError`` (so a typo cannot pass silently). Anything but
    a viser handle gets plain assignments.
    """
    if not isinstance(handle, viser.SceneNodeHandle):
        for name, value in props.items():
            setattr(handle, name, value)
        return
    impl = handle._impl
    if impl.removed:
        raise RuntimeError(f"cannot update the removed scene node {impl.name!r}")
    changed: dict[str, Any] = {}
    for name, value in props.items():
        if name not in handle._prop_hints:
            raise TypeError(f"{type(handle).__name__} has no property {name!r}")
        current = getattr(impl.props, name)
        if isinstance(current, np.ndarray):
            value = np.array(value, dtype=current.dtype)
            if value.shape == current.shape and np.array_equal(value, current):
                continue
            setattr(impl.props, name, value)
            changed[name] = value.copy()  # the wire keeps its own copy: the stored array may be replaced later
        elif current != value:
            setattr(impl.props, name, value)
            changed[name] = value
    if changed:
        impl.api._queue_scene_message(_messages.SceneNodeUpdateMessage(impl.name, changed))


@contextlib.contextmanager
def count_outgoing_messages(client: viser.ClientHandle) -> Iterator[list[int]]:
    """Count the messages queued for ``client`` inside the block: yields a one-item list holding the count.

    For the per-frame message budget (``Scene.frame_message_budget``) and diagnostics;
    the client's messages are sent as usual.
    """
    connection = client._websock_connection
    queue_message = connection.queue_message
    count = [0]

    def counting(message: Any) -> None:
        count[0] += 1
        queue_message(message)

    # An instance attribute shadows the method while the block runs (deliberately: mypy forbids it by default).
    connection.queue_message = counting  # type: ignore[method-assign]
    try:
        yield count
    finally:
        del connection.queue_message


_PROP_HINTS_BY_PROPS_TYPE: dict[type, dict[str, Any]] = {}


def share_prop_hints() -> None:
    """Make viser compute each handle class's property type hints once per class, not once per handle.

    viser 1.1.1 caches ``AssignablePropsBase._prop_hints`` (``typing.get_type_hints``
    of the node's props dataclass) on each handle, so every node created pays for
    evaluating them again — a third of the cost of adding a node, and trails add
    nodes for every student. The hints depend only on the props class, so one
    shared table gives the same answers. Idempotent; called when a scene host starts.
    """
    from viser._assignable_props_api import AssignablePropsBase

    def prop_hints(self: Any) -> dict[str, Any]:
        props_type = type(self._impl.props)
        hints = _PROP_HINTS_BY_PROPS_TYPE.get(props_type)
        if hints is None:
            hints = _PROP_HINTS_BY_PROPS_TYPE[props_type] = typing.get_type_hints(props_type)
        return hints

    AssignablePropsBase._prop_hints = property(prop_hints)  # type: ignore[assignment]


class BatchedWakeups:
    """Group each client's messages as ``client.atomic()`` does, but wake viser's sender once for all of them.

    ``client.atomic()`` wakes the sending thread at the end of every block: a
    system call per client per frame, and each hands the GIL to the sender in
    the middle of the frame loop (a quarter of a worker's frame loop with 50
    students). Here :meth:`atomic` groups one client's messages without waking,
    and :meth:`flush` wakes the sender once for every client released since.
    Each client's group is released as soon as its block ends (holding every
    client until the whole frame was drawn made viser's windowing skip frames).
    Measured with 100 heavy-top viewers on two workers: waking once per frame
    loop gave 28.8 frames/s at 1.42 cores; every 8 clients 27.5 at 1.54; every
    2 clients 25.9 at 1.65.
    """

    def __init__(self) -> None:
        self._ready: list[Any] = []

    @contextlib.contextmanager
    def atomic(self, client: viser.ClientHandle) -> Iterator[None]:
        buffer = client._websock_connection.get_message_buffer()
        buffer.atomic_start()
        try:
            yield
        finally:
            with buffer.buffer_lock:
                buffer.atomic_counter -= 1
                released = buffer.atomic_counter == 0
            if released:
                self._ready.append(buffer)

    def flush(self) -> None:
        """Wake the sender for every client released since the last wake-up."""
        ready, self._ready = self._ready, []
        by_loop: dict[Any, list[Any]] = {}
        for buffer in ready:
            by_loop.setdefault(buffer.event_loop, []).append(buffer)
        for loop, buffers in by_loop.items():

            def wake(buffers: list[Any] = buffers) -> None:
                for buffer in buffers:
                    buffer.message_event.set()

            with contextlib.suppress(RuntimeError):  # the server's loop has closed (stopping): nothing to wake
                loop.call_soon_threadsafe(wake)


class LoopOnlyEvent(asyncio.Event):
    """An ``asyncio.Event`` whose :meth:`set` acts only on its own event loop's thread.

    viser 1.1.1's ``AsyncMessageBuffer.push`` sets the buffer's message event
    directly from the pushing thread (our frame loop), besides waking the
    loop with ``call_soon_threadsafe`` (or at the end of an atomic block, or
    in :meth:`BatchedWakeups.flush`). ``asyncio.Event`` is not thread-safe:
    that direct ``set`` iterates the waiters while the loop adds or removes
    one, and under load it raised "deque mutated during iteration" inside a
    student's frame, which paused that student's scene. Every push is also
    woken on the loop, so ignoring the direct one loses no wake-up.
    """

    def __init__(self, loop: asyncio.AbstractEventLoop) -> None:
        super().__init__()
        self._owner_loop = loop

    def set(self) -> None:
        if asyncio._get_running_loop() is self._owner_loop:
            super().set()


def make_message_events_thread_safe() -> None:
    """Give every viser message buffer created from now on a :class:`LoopOnlyEvent`. Idempotent; called when a
    scene host starts, before its viser server exists."""
    from viser.infra._async_message_buffer import AsyncMessageBuffer

    if getattr(AsyncMessageBuffer.__init__, "loop_only_event", False):
        return
    original = AsyncMessageBuffer.__init__

    @functools.wraps(original)
    def init(self: Any, *args: Any, **kwargs: Any) -> None:
        original(self, *args, **kwargs)
        self.message_event = LoopOnlyEvent(self.event_loop)

    init.loop_only_event = True  # type: ignore[attr-defined]
    AsyncMessageBuffer.__init__ = init  # type: ignore[method-assign]


def start_callback_threads(server: viser.ViserServer, *, timeout_s: float = 10.0) -> int:
    """Start every thread of viser's callback pool now; returns how many it has.

    viser runs connect and disconnect callbacks (our scene builds) on a thread
    pool of at most 32 threads that grows only when callbacks overlap, so a
    worker's thread count crept up class after class until it reached 32 —
    bounded, but indistinguishable from a leak in a soak test. Started all at
    once, the worker's threads are a constant from the first student on.
    """
    executor = server._thread_executor
    size = executor._max_workers
    everyone_started = threading.Barrier(size, timeout=timeout_s)
    futures = [executor.submit(everyone_started.wait) for _ in range(size)]
    for future in futures:
        future.result(timeout=timeout_s)
    return len(executor._threads)


class BroadcastViewer:
    """A stand-in for a ``viser.ClientHandle`` that draws on a whole server: every viewer of it sees the same scene.

    A room's shared scene (one simulation, many followers) is built on one of
    these: its ``scene`` and ``gui`` are the server's, whose messages viser keeps
    for every viewer that connects later (culled to the latest state of each
    node), so a student who joins late, or whose phone slept, gets the scene as
    it is now. Its ``camera`` sets the initial camera of every viewer (the
    server has no single live camera).
    """

    #: No real client: a broadcast has no viser client id.
    client_id = -1

    def __init__(self, server: viser.ViserServer) -> None:
        self.server = server
        self.scene = server.scene
        self.gui = server.gui
        self._websock_connection = server._websock_server
        self.camera = InitialCameraConfig(server._websock_server.queue_message)

    def atomic(self) -> contextlib.AbstractContextManager[None]:
        return self.server.atomic()

    def move_cameras(self, *, position: tuple[float, float, float], look_at: tuple[float, float, float]) -> None:
        """Move every viewer's camera now (m, world frame): a new scene on the stage is seen from its own start pose,
        not from wherever the last scene left the cameras."""
        queue = self.server._websock_server.queue_message
        queue(_messages.SetCameraLookAtMessage(cast("tuple[float, float, float]", tuple(map(float, look_at)))))
        queue(_messages.SetCameraPositionMessage(cast("tuple[float, float, float]", tuple(map(float, position)))))

    def flush(self) -> None:
        self.server.flush()


def viewer_count(server: viser.ViserServer) -> int:
    """Websockets open on ``server`` now (counted before viser's camera handshake, unlike ``get_clients``)."""
    return len(server._websock_server._live_connections)
