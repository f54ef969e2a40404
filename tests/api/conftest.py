"""One running app for the API tests; the lifespan starts the loopback viser scene host."""

from __future__ import annotations

from collections.abc import Iterator

import pytest
from fastapi.testclient import TestClient

from app.main import create_app


@pytest.fixture(scope="session")
def client() -> Iterator[TestClient]:
    with TestClient(create_app()) as client:
        yield client


def first_camera_message() -> bytes:
    """What a browser's viewer sends first over the viewer websocket; viser counts a client as connected only after it."""
    from app.scenes.host.viser_compat import viewer_camera_message

    return viewer_camera_message()
