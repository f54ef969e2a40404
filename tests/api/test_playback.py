"""A page's time controls through the API: pause, step, scrub over the kept motion, restart, speed, go to a time, camera.

One app for the module, one heavy-top session per test with a connected viewer
(through the relay). Simulated time is checked exactly where it is a count of
frames (1/30 s each); a jump to a time (a share link) must give the same state
as the motion that got there by playing, to 1e-9: the same integrator takes the
same steps.
"""

from __future__ import annotations

import json
import secrets
from collections.abc import Iterator

import numpy as np
import pytest
import viser
from fastapi.testclient import TestClient

from app.main import create_app
from app.scenes.viser_boundary import viewer_camera_message
from app.settings import Settings
from tests.conftest import wait_until

FRAME_S = 1.0 / 30.0
VISER = [f"viser-v{viser.__version__}"]


@pytest.fixture(scope="module")
def client() -> Iterator[TestClient]:
    with TestClient(create_app(Settings())) as client:
        yield client


class Page:
    """One lesson page: its session, its key, and a connected viewer."""

    def __init__(self, client: TestClient, scene_id: str = "heavy-top") -> None:
        self.client, self.scene_id = client, scene_id
        self.session_id, self.key = f"page-{secrets.token_hex(6)}", secrets.token_hex(16)
        answer = client.put(f"/api/scenes/{scene_id}/sessions/{self.session_id}", json={"params": {}}, headers={"X-Session-Key": self.key})
        assert answer.status_code == 200

    def playback(self, **body) -> dict:
        answer = self.client.put(self.url, json=body, headers={"X-Session-Key": self.key})
        assert answer.status_code == 200, answer.text
        return answer.json()

    @property
    def url(self) -> str:
        return f"/api/scenes/{self.scene_id}/sessions/{self.session_id}/playback"

    def now(self) -> dict:
        return self.client.get(self.url).json()

    def motion(self) -> dict:
        return self.client.app.state.scene_host.motion_state(self.session_id)


@pytest.fixture
def page(client) -> Iterator[Page]:
    page = Page(client)
    with client.websocket_connect(f"/viewer/heavy-top/{page.session_id}", subprotocols=VISER) as viewer:
        viewer.send_bytes(viewer_camera_message())
        wait_until(lambda: (page.now().get("t_s") or 0.0) > 1.0, timeout_s=20, what="the page's top to move")
        yield page


def test_pause_step_and_scrub_move_simulated_time_as_asked(page):
    paused = page.playback(playing=False)
    assert paused["playing"] is False
    t0 = paused["t_s"]
    assert page.now()["t_s"] == t0  # paused: not a frame more
    stepped = page.playback(step=3)
    assert stepped["t_s"] == pytest.approx(t0 + 3 * FRAME_S, abs=1e-9) and stepped["playing"] is False
    first, last = stepped["history_s"]
    assert first == pytest.approx(0.0, abs=FRAME_S) and last == pytest.approx(stepped["t_s"], abs=1e-9)
    kept = page.motion()
    target = round((first + last) / 2 / FRAME_S) * FRAME_S
    back = page.playback(seek_s=target)
    assert back["t_s"] == pytest.approx(target, abs=1e-6) and back["playing"] is False
    forward = page.playback(seek_s=last)
    assert forward["t_s"] == pytest.approx(last, abs=1e-9)
    np.testing.assert_allclose(page.motion()["y"], kept["y"], rtol=0, atol=1e-12)  # replayed from the stored state
    page.playback(seek_s=target)
    resumed = page.playback(playing=True)
    assert resumed["history_s"][1] == pytest.approx(target, abs=1e-6)  # what followed the scrubbed instant is forgotten
    restarted = page.playback(reset=True)
    assert restarted["t_s"] < 0.2 and restarted["history_s"][1] < 0.2


def test_going_to_a_time_gives_the_state_that_playing_reached(client, page):
    """A share link's go_to_s, on a second page, reproduces the first page's motion at that instant."""
    page.playback(playing=False)
    target = page.playback(seek_s=round(0.9 / FRAME_S) * FRAME_S)["t_s"]
    reached = page.motion()
    other = Page(client)
    jumped = other.playback(go_to_s=target, playing=False)  # no viewer yet: applied when one connects
    with client.websocket_connect(f"/viewer/heavy-top/{other.session_id}", subprotocols=VISER) as viewer:
        viewer.send_bytes(viewer_camera_message())
        wait_until(lambda: other.motion() is not None, timeout_s=20, what="the second page's scene")
        assert jumped["playing"] is False
        assert other.motion()["t_s"] == pytest.approx(target, abs=1e-9)
        np.testing.assert_allclose(other.motion()["y"], reached["y"], rtol=0, atol=1e-9)


def test_the_camera_is_placed_and_reported(page):
    view = {"position": [2.0, -3.0, 1.5], "look_at": [0.0, 0.0, 0.4]}
    answer = page.playback(camera=view)
    assert answer["camera"] == view


@pytest.mark.parametrize("position", [["1", "2", "3"], [True, 0, 1], [1, 2, None], [1, 2, {}]])
def test_a_camera_coordinate_that_is_not_a_finite_json_number_is_refused_and_changes_nothing(client, page, position):
    # Found by the attack on issue 29: strings and booleans were taken as numbers and moved the camera.
    before = page.playback(camera={"position": [2.0, -3.0, 1.5], "look_at": [0.0, 0.0, 0.4]})["camera"]
    body = {"camera": {"position": position, "look_at": [0, 0, 0]}}
    refused = client.put(page.url, json=body, headers={"X-Session-Key": page.key})
    assert refused.status_code == 422, refused.text
    assert refused.json()["detail"][0]["loc"][:3] == ["body", "camera", "position"]
    assert page.now()["camera"] == before


def test_reset_view_puts_the_camera_back_at_the_scenes_start_pose(client, page):
    """Reset view (reset_camera) returns every viewer's camera to the scene's own start pose, whatever moved it;
    the answer (and GET) also counts the session's viewers, which a page waits for before polling live numbers."""
    start = page.client.app.state.scene_host.scene_class("heavy-top")
    page.playback(camera={"position": [2.0, -3.0, 1.5], "look_at": [0.0, 0.0, 0.4]})
    answer = page.playback(reset_camera=True)
    np.testing.assert_allclose(answer["camera"]["position"], start.camera_position, rtol=0, atol=1e-12)
    np.testing.assert_allclose(answer["camera"]["look_at"], start.camera_look_at, rtol=0, atol=1e-12)
    assert answer["viewers"] == 1 and page.now()["viewers"] == 1
    both = {"reset_camera": True, "camera": {"position": [1, 2, 3], "look_at": [0, 0, 0]}}
    refused = client.put(page.url, json=both, headers={"X-Session-Key": page.key})
    assert refused.status_code == 422 and refused.json()["detail"][0]["loc"] == ["body", "reset_camera"]
    assert client.put(page.url, json={"reset_camera": "yes"}, headers={"X-Session-Key": page.key}).status_code == 422


def test_a_session_without_a_viewer_yet_says_so(client):
    """Before its viewer connects a page's session answers GET playback with 0 viewers (not a 404), so the page
    can wait for it instead of asking for live numbers that do not exist yet."""
    waiting = Page(client)
    answer = client.get(waiting.url)
    assert answer.status_code == 200 and answer.json()["viewers"] == 0 and answer.json()["t_s"] is None


def test_bad_requests_change_nothing_and_an_owned_session_needs_its_key(client, page):
    before = page.playback(playing=False)
    for body in (
        {"step": 301},
        {"step": -1},
        {"time_scale": 5.0},
        {"seek_s": 10_000.0},
        {"go_to_s": 601.0},
        {"camera": {"position": [1, 2, 3], "look_at": [1, 2, 3]}},
        {"camera": {"position": [1, 2], "look_at": [0, 0, 0]}},
        {"rewind": True},
    ):
        answer = client.put(page.url, content=json.dumps(body), headers={"X-Session-Key": page.key, "Content-Type": "application/json"})
        assert answer.status_code == 422, (body, answer.text)
    assert client.put(page.url, json={"playing": True}).status_code == 403  # no key: another page's scene
    after = page.now()
    assert (after["playing"], after["t_s"]) == (False, before["t_s"])
    assert client.put("/api/scenes/heavy-top/sessions/never-seen-session/playback", json={"playing": False}).status_code == 422
