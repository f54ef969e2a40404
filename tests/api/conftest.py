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


def wait_for(predicate, timeout_s: float = 30.0) -> None:
    """Poll ``predicate`` every 50 ms until it holds; fail after ``timeout_s``."""
    import time

    deadline = time.monotonic() + timeout_s
    while not predicate():
        assert time.monotonic() < deadline, "timed out"
        time.sleep(0.05)
