"""A room's state changes against a scene host that can answer busy (a worker restarting): a change the host refuses
leaves the room, and as far as the host lets it the room's stage, as they were, and the same change taken later
applies whole. In process: the room and the real lessons and scene classes, a host of its own in memory."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import pytest

from app.classroom.room import Room
from app.course import load_catalogue
from app.scenes import SCENES
from app.scenes.host.interface import HostBusy

FRICTION_LESSON = "8-2-coulomb-friction"


class BusyWhenTold:
    """The scene host's stage calls as a room makes them, kept in memory: what the stage shows, and the calls that
    answer :class:`HostBusy` (as a worker that is restarting does): those named in ``busy``, and every call once
    ``answers_left`` (when set) have answered."""

    def __init__(self) -> None:
        self.scenes = SCENES
        self.busy: set[str] = set()
        self.answers_left: int | None = None
        self.stage: dict[str, Any] | None = None
        self.calls: list[str] = []

    def _call(self, name: str) -> None:
        self.calls.append(name)
        if name in self.busy or self.answers_left == 0:
            raise HostBusy(f"scene worker 0 did not answer {name}", retry_after_s=2)
        if self.answers_left is not None:
            self.answers_left -= 1

    def open_stage(self, session_id: str, scene_id: str, raw: Mapping[str, Any]) -> dict[str, Any]:
        self._call("open_stage")
        params = self.scenes[scene_id].parameters.validate(raw)
        self.stage = {"scene_id": scene_id, "params": params, "playing": True, "time_scale": 1.0, "t_s": 0.0}
        return {"params": dict(params), "viewer_url": "ws://127.0.0.1:1"}

    def set_params(self, scene_id: str, session_id: str, raw: Mapping[str, Any], *, stage: bool = False) -> dict[str, Any]:
        self._call("set_params")
        assert self.stage is not None and stage
        params = self.scenes[scene_id].parameters.validate(raw)
        self.stage |= {"scene_id": scene_id, "params": params, "t_s": 0.0}
        return dict(params)

    def set_playback(self, session_id: str, *, playing: bool, time_scale: float, reset: bool = False) -> dict[str, Any]:
        self._call("set_playback")
        assert self.stage is not None
        self.stage |= {"playing": playing, "time_scale": time_scale} | ({"t_s": 0.0} if reset else {})
        return dict(self.stage)

    def close_stage(self, session_id: str) -> None:
        self._call("close_stage")
        self.stage = None

    def motion_state(self, session_id: str) -> dict[str, Any] | None:
        self._call("motion_state")
        assert self.stage is not None
        return {"t_s": self.stage["t_s"], "y": [0.1, 0.2]}


@pytest.fixture(scope="module")
def catalogue():
    return load_catalogue()


@pytest.fixture
def host() -> BusyWhenTold:
    return BusyWhenTold()


@pytest.fixture
def room(catalogue, host) -> Room:
    """A room on the sliding bar with friction, its friction changed from the default and its motion at t = 2.5 s."""
    room = Room(room_id="0123456789abcdef", code="ABCDEF", join_url="http://127.0.0.1/join/ABCDEF")
    room.change({"lesson_id": FRICTION_LESSON, "scene_id": "sliding-bar-friction"}, catalogue=catalogue, host=host)
    room.change({"params": {"mu": 0.45}}, catalogue=catalogue, host=host)
    assert host.stage is not None
    host.stage["t_s"] = 2.5
    return room


def test_a_busy_worker_leaves_the_room_following_and_exploring_later_works(room, catalogue, host):
    """F2: the worker holding the stage was killed and "Let everyone explore" answered 503, yet the room said
    "explore" with no start for the students, and every later try was a change to the mode it had: nobody could
    explore again."""
    before, stage = room.state(), dict(host.stage)
    host.busy = {"motion_state"}
    with pytest.raises(HostBusy):
        room.change({"mode": "explore"}, catalogue=catalogue, host=host)
    assert room.state() == before and host.stage == stage

    host.busy = set()  # the worker is back: the same change, again
    explored = room.change({"mode": "explore"}, catalogue=catalogue, host=host)
    assert (explored["mode"], explored["revision"]) == ("explore", before["revision"] + 1)
    assert explored["explore_start"] == {
        "scene_id": "sliding-bar-friction",
        "params": before["params"],
        "motion": {"t_s": 2.5, "y": [0.1, 0.2]},
    }


@pytest.mark.parametrize(
    ("change", "busy", "written"),
    [
        ({"playing": False, "time_scale": 0.5, "mode": "explore"}, "motion_state", ["set_playback"]),
        ({"scene_id": "stick-slip-belt", "playing": False}, "set_playback", ["open_stage"]),
        ({"params": {"mu": 0.2}, "reset": True, "mode": "explore"}, "motion_state", ["set_params", "set_playback"]),
    ],
)
def test_a_change_the_host_refuses_midway_is_undone_on_the_stage(room, catalogue, host, change, busy, written):
    """A call that answers busy after others changed the stage: the room keeps its state, and the stage is put back to
    it (the same scene, parameters and playback), so what the class sees still matches what its pages say."""
    before, stage = room.state(), dict(host.stage)
    host.busy, host.calls = {busy}, []
    with pytest.raises(HostBusy):
        room.change(change, catalogue=catalogue, host=host)
    assert host.calls[: len(written) + 1] == [*written, busy]
    assert room.state() == before
    assert {k: host.stage[k] for k in ("scene_id", "params", "playing", "time_scale")} == {
        k: stage[k] for k in ("scene_id", "params", "playing", "time_scale")
    }

    host.busy = set()
    changed = room.change(change, catalogue=catalogue, host=host)
    assert changed["revision"] == before["revision"] + 1
    assert (host.stage["scene_id"], host.stage["playing"]) == (changed["scene_id"], changed["playing"])


def test_a_stage_that_could_not_be_put_back_is_opened_afresh_by_the_next_change(room, catalogue, host):
    """Busy twice over (the change, then putting the stage back): the room still says what it said, and its next
    change opens its stage again on the room's scene, so the class does not stay on a motion its pages do not show."""
    before = room.state()
    host.answers_left = 1  # the new friction gets through, then the worker stops answering
    with pytest.raises(HostBusy):
        room.change({"params": {"mu": 0.2}, "playing": False}, catalogue=catalogue, host=host)
    assert room.state() == before and host.stage["params"]["mu"] == 0.2

    host.answers_left, host.calls = None, []
    changed = room.change({"playing": False}, catalogue=catalogue, host=host)
    assert host.calls == ["open_stage", "set_playback"]
    assert changed["params"]["mu"] == 0.45 and changed["playing"] is False
    assert (host.stage["params"], host.stage["playing"]) == (changed["params"], False)


def test_a_room_whose_scene_worker_is_busy_at_creation_is_not_left_open(host):
    # Found by the attack on issue 29: POST /api/rooms with a lesson answered 503 (its worker busy) but kept the new,
    # empty room open. The route, in-process with the busy host in place of the scene workers.
    from fastapi.testclient import TestClient

    from app.api.deps import get_scene_host
    from app.main import create_app
    from app.settings import Settings

    key = "room-busy-test-instructor-key"
    app = create_app(Settings(instructor_key=key, workers=0))
    app.dependency_overrides[get_scene_host] = lambda: host
    host.busy = {"open_stage"}
    with TestClient(app) as client:
        refused = client.post(
            "/api/rooms", json={"lesson_id": "10-2-spinning-top"}, headers={"X-Instructor-Key": key}
        )
        assert refused.status_code == 503 and refused.headers["Retry-After"], refused.text
        assert host.calls == ["open_stage"]
        assert app.state.rooms._rooms == {}
        host.busy = set()
        taken = client.post("/api/rooms", json={"lesson_id": "10-2-spinning-top"}, headers={"X-Instructor-Key": key})
        assert taken.status_code == 200, taken.text
        assert list(app.state.rooms._rooms) == [taken.json()["room_id"]]
