"""One running app for the API tests; the lifespan starts the loopback viser scene host."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

import pytest
import viser
from fastapi.testclient import TestClient

from app.main import create_app
from tests.conftest import wait_until


@pytest.fixture(scope="session")
def client() -> Iterator[TestClient]:
    with TestClient(create_app()) as client:
        yield client


def first_camera_message() -> bytes:
    """What a browser's viewer sends first over the viewer websocket; viser counts a client as connected only after it."""
    from app.scenes.host.viser_compat import viewer_camera_message

    return viewer_camera_message()


@contextmanager
def live_viewer(client: TestClient, scene_id: str, session_id: str) -> Iterator:
    """Connect a viewer to a session's scene as a browser does; yields the scene instance the host built for it."""
    host = client.app.state.scene_host
    with client.websocket_connect(f"/viewer/{scene_id}/{session_id}", subprotocols=["viser-v" + viser.__version__]) as ws:
        ws.receive()
        ws.send_bytes(first_camera_message())
        wait_until(lambda: len(host.instances(session_id)) == 1, what=f"the {scene_id} viewer to connect")
        yield host.instances(session_id)[0]
