"""A headless viewer for scene tests: a real loopback viser server and one real client, no browser.

A plain websocket connects as a browser's viewer would (subprotocol, first camera
message) and discards whatever viser sends; the scene under test gets that
client's :class:`viser.ClientHandle`, wrapped so every node the scene adds is
recorded by name and its arguments are checked for non-finite numbers.
"""

from __future__ import annotations

import contextlib
import io
import threading
import time
from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest
import viser
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import connect

from app.scenes.viser_boundary import viewer_camera_message


def assert_finite(value: Any, where: str) -> None:
    """Fail if ``value`` (a number, array or nested tuple/list of numbers) holds a NaN or infinity."""
    if isinstance(value, (bool, str, bytes)) or value is None:
        return
    if isinstance(value, (int, float, np.number, np.ndarray, list, tuple)):
        try:
            array = np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            return
        assert np.all(np.isfinite(array)), f"non-finite value sent to the viewer: {where}"


class RecordingSceneApi:
    """A client's scene API that records every node added (by name) and checks its arguments are finite."""

    def __init__(self, scene: viser.SceneApi) -> None:
        self._scene = scene
        self.handles: dict[str, Any] = {}

    def __getattr__(self, name: str) -> Any:
        attribute = getattr(self._scene, name)
        if not name.startswith("add_"):
            return attribute

        def add(node_name: str, *args: Any, **kwargs: Any) -> Any:
            for k, value in enumerate(args):
                assert_finite(value, f"{name}({node_name!r}) argument {k}")
            for key, value in kwargs.items():
                assert_finite(value, f"{name}({node_name!r}) {key}=")
            handle = attribute(node_name, *args, **kwargs)
            self.handles[node_name] = handle
            return handle

        return add

    def snapshot(self, *, skip_prefixes: tuple[str, ...] = ()) -> dict[str, dict[str, Any]]:
        """What is drawn now: for each recorded node not removed (and not under ``skip_prefixes``), its position,
        wxyz, visibility and every numeric or array property, as float arrays (booleans as 0/1)."""
        out: dict[str, dict[str, Any]] = {}
        for name, handle in self.handles.items():
            impl = handle._impl
            if impl.removed or any(name.startswith(prefix) for prefix in skip_prefixes):
                continue
            drawn: dict[str, Any] = {"position": np.array(impl.position, float), "wxyz": np.array(impl.wxyz, float), "visible": float(impl.visible)}
            for prop, value in vars(impl.props).items():
                if isinstance(value, np.ndarray) and value.dtype != object or isinstance(value, int | float) and not isinstance(value, bool):
                    drawn[prop] = np.array(value, float)
                elif isinstance(value, bool):
                    drawn[prop] = float(value)
            out[name] = drawn
        return out


class HeadlessClient:
    """A real viser client whose ``scene`` records what a scene adds; everything else is the client's own."""

    def __init__(self, client: viser.ClientHandle) -> None:
        self._client = client
        self.scene = RecordingSceneApi(client.scene)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._client, name)


@contextlib.contextmanager
def headless_viewer() -> Iterator[tuple[viser.ViserServer, viser.ClientHandle]]:
    """A loopback viser server with one connected viewer (a websocket that reads and discards)."""
    with contextlib.redirect_stdout(io.StringIO()):
        server = viser.ViserServer(host="127.0.0.1", port=0, verbose=False)
    socket = connect(f"ws://127.0.0.1:{server.get_port()}/", subprotocols=[f"viser-v{viser.__version__}"], max_size=None)
    socket.send(viewer_camera_message())

    def drain() -> None:
        with contextlib.suppress(ConnectionClosed, OSError):
            while True:
                socket.recv()

    threading.Thread(target=drain, name="headless-viewer", daemon=True).start()
    deadline = time.monotonic() + 10.0
    while not server.get_clients():
        assert time.monotonic() < deadline, "the headless viewer never connected"
        time.sleep(0.01)
    try:
        yield server, next(iter(server.get_clients().values()))
    finally:
        socket.close()
        server.stop()


@pytest.fixture(scope="module")
def viewer() -> Iterator[tuple[viser.ViserServer, viser.ClientHandle]]:
    """One headless viewer shared by a test module."""
    with headless_viewer() as connected:
        yield connected


@pytest.fixture
def client(viewer) -> HeadlessClient:
    """A fresh recording wrapper around the module's viewer client (scenes build on its own ``client.scene``)."""
    return HeadlessClient(viewer[1])
