"""The API tests' app: ``dynlab serve`` as README starts it, with its scene workers (tests/served.py).

``client`` is an HTTP client on that server from a loopback address of its own for each test (one student per test,
as far as the server's per-client limits are concerned). A test that must look inside a scene instance (what it
drew, at one instant) uses ``inprocess_client`` beside it: the same app in this process, scenes included.
"""

from __future__ import annotations

import threading
from collections.abc import Iterator
from contextlib import contextmanager

import httpx
import pytest
import viser
from fastapi.testclient import TestClient

from app.main import create_app
from tests.conftest import wait_until


@pytest.fixture
def client(served) -> Iterator[httpx.Client]:
    with served.new_client() as client:
        yield client


@pytest.fixture(scope="session")
def inprocess_client() -> Iterator[TestClient]:
    with TestClient(create_app()) as client:
        yield client


def first_camera_message() -> bytes:
    """What a browser's viewer sends first over the viewer websocket; viser counts a client as connected only after it."""
    from app.scenes.viser_boundary import viewer_camera_message

    return viewer_camera_message()


def viewer_count(client, scene_id: str, session_id: str) -> int:
    answer = client.get(f"/api/scenes/{scene_id}/sessions/{session_id}/playback")
    return answer.json()["viewers"] if answer.status_code == 200 else 0


@contextmanager
def live_viewer(client, scene_id: str, session_id: str) -> Iterator:
    """Connect a viewer to a session's scene as a browser does, until the host counts it.

    As a lesson page does, the session is opened first (its parameters, the defaults unless the test set some): a
    viewer never creates a session. On the served app (an httpx client) it is a real websocket whose frames are read
    and dropped, and it yields None; on ``inprocess_client`` it yields the scene instance the host built for it."""
    if client.get(f"/api/scenes/{scene_id}/sessions/{session_id}").status_code == 404:
        assert client.put(f"/api/scenes/{scene_id}/sessions/{session_id}", json={"params": {}}).status_code == 200
    if isinstance(client, TestClient):
        host = client.app.state.scene_host
        with client.websocket_connect(f"/viewer/{scene_id}/{session_id}", subprotocols=["viser-v" + viser.__version__]) as ws:
            ws.receive()
            ws.send_bytes(first_camera_message())
            wait_until(lambda: len(host.instances(session_id)) == 1, what=f"the {scene_id} viewer to connect")
            yield host.instances(session_id)[0]
        return
    from websockets.sync.client import connect

    url = str(client.base_url).replace("http://", "ws://").rstrip("/") + f"/viewer/{scene_id}/{session_id}"
    local = getattr(client, "address", None)  # a DeviceClient's own address: the viewer is the same device's
    with connect(url, subprotocols=[f"viser-v{viser.__version__}"], max_size=None, open_timeout=20,  # type: ignore[list-item]
                 **({"source_address": (local, 0)} if local else {})) as ws:
        ws.send(first_camera_message())
        stop = threading.Event()

        def drain() -> None:
            while not stop.is_set():
                try:
                    ws.recv(timeout=0.5)
                except TimeoutError:
                    continue
                except Exception:
                    return

        reader = threading.Thread(target=drain, daemon=True)
        reader.start()
        try:
            wait_until(lambda: viewer_count(client, scene_id, session_id) >= 1, what=f"the {scene_id} viewer to connect")
            yield None
        finally:
            stop.set()
            ws.close()
            reader.join(timeout=5)
