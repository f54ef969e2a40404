"""The scene host's playback (pause, time scale, restart) and stages (one scene on its own viser server, every viewer).

One in-process host for the module. Checked against the simulated time the
scenes report: a paused session does not advance; at a time scale s it advances
s times as fast as at 1× (measured over the same wall-clock window); a restart
goes back to t = 0. A stage's late viewer gets the scene's current state
(viser's replay, then its end marker); a motion handed from one instance to
another continues exactly the same trajectory.
"""

from __future__ import annotations

import time
from collections.abc import Iterator

import numpy as np
import pytest
import viser
from websockets.sync.client import connect

from app.classroom.relay import ends_replay
from app.scenes import SCENES
from app.scenes.host.host import SceneHost
from app.scenes.viser_boundary import viewer_camera_message
from tests.conftest import wait_until

STAGE = "room-0123456789abcdef"


@pytest.fixture(scope="module")
def host() -> Iterator[SceneHost]:
    host = SceneHost(SCENES)
    host.start()
    yield host
    host.stop()


def t_now(host: SceneHost, scene_id: str, session_id: str) -> float:
    """Simulated time (s): an integrated scene's live t_s, else its readout's time quantity."""
    live = host.live_readout(scene_id, session_id)
    assert live is not None
    if "t_s" in live:
        return live["t_s"]
    return next(q["value"] for q in live["readout"]["quantities"] if q["name"] == "t_s")


def replay_of(url: str) -> list[bytes]:
    """What a viewer connecting now receives up to the end of viser's replay (the synchronous client: a test may run
    after one that left an event loop running in this thread)."""
    windows: list[bytes] = []
    with connect(url, subprotocols=[f"viser-v{viser.__version__}"], max_size=None, open_timeout=10) as viewer:  # type: ignore[list-item]
        viewer.send(viewer_camera_message())
        while not windows or not ends_replay(windows[-1]):
            windows.append(viewer.recv(timeout=10))
    return windows


def test_a_stage_replays_its_scene_to_a_late_viewer_then_streams_frames(host):
    opened = host.open_stage(STAGE, "heavy-top", {"spin_rad_s": 120.0})
    assert opened["params"]["spin_rad_s"] == 120.0 and opened["viewer_url"].startswith("ws://127.0.0.1:")
    time.sleep(0.5)  # the scene has moved on: a viewer arriving now needs its current state, not its first frame
    replay = replay_of(opened["viewer_url"])
    assert ends_replay(replay[-1]) and not any(ends_replay(w) for w in replay[:-1])
    assert sum(len(w) for w in replay) > 5000  # the top's mesh, axes and labels: the whole scene, not one frame's moves
    wait_until(lambda: host.stage_viewers(STAGE) == 0, timeout_s=5, what="the stage counting its viewer gone")


def test_a_stage_changes_scene_and_refuses_set_params_for_another_scene(host):
    host.open_stage(STAGE, "heavy-top", {})
    with pytest.raises(ValueError, match="open_stage"):
        host.set_params("four-bar", STAGE, {}, stage=True)
    with pytest.raises(ValueError, match="changed only by their room"):
        host.set_params("heavy-top", STAGE, {})  # a page's call: a stage's id is not a page's
    assert host.set_params("heavy-top", STAGE, {"spin_rad_s": 33.0}, stage=True)["spin_rad_s"] == 33.0
    assert host.open_stage(STAGE, "four-bar", {})["params"] == SCENES["four-bar"].parameters.defaults()
    wait_until(lambda: t_now(host, "four-bar", STAGE) > 0.1, timeout_s=5, what="the four-bar stage animating")
    with pytest.raises(ValueError, match="crank"):
        host.open_stage(STAGE, "four-bar", {"crank_m": -1.0})  # refused whole: the stage keeps its scene
    assert host.session_params(STAGE) == SCENES["four-bar"].parameters.defaults()


def test_pause_time_scale_and_restart(host):
    """Against the running frame loop: a paused stage's time does not move at all, a playing one's does, and a
    restart goes back to t = 0. (How far it moves per wall second depends on the machine's load; the scale's exact
    effect is checked frame by frame below.)"""
    host.open_stage(STAGE, "heavy-top", {})
    paused = host.set_playback(STAGE, playing=False)
    assert (paused["playing"], paused["time_scale"]) == (False, 1.0)
    paused_at = t_now(host, "heavy-top", STAGE)
    time.sleep(0.3)
    assert t_now(host, "heavy-top", STAGE) == paused_at
    host.set_playback(STAGE, playing=True, time_scale=2.0)
    wait_until(lambda: t_now(host, "heavy-top", STAGE) > paused_at + 0.2, timeout_s=10, what="the stage playing on")
    host.set_playback(STAGE, time_scale=1.0, reset=True)
    assert t_now(host, "heavy-top", STAGE) < 0.2
    for bad in (0.0, 5.0, float("nan"), True, "2"):
        with pytest.raises(ValueError, match="time_scale"):
            host.set_playback(STAGE, time_scale=bad)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="playing"):
        host.set_playback(STAGE, playing="yes")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="no scene yet"):
        host.set_playback("never-seen-session", playing=False)
    assert {k: host.playback(STAGE)[k] for k in ("playing", "time_scale")} == {"playing": True, "time_scale": 1.0}


@pytest.mark.parametrize(("time_scale", "steps_in_45_frames"), [(1.0, 45), (2.0, 90), (4.0, 180), (0.25, 11), (0.1, 4)])
def test_a_time_scale_advances_that_many_steps_per_displayed_frame(time_scale, steps_in_45_frames):
    """Frames run by hand (no frame thread): at scale s, 45 displayed frames of 1/30 s advance floor(45 s) steps of
    1/30 s, the fraction carried from frame to frame (0.25× steps on every fourth frame), and each step is kept
    for the scrubber. Exact: no wall clock is involved (45 frames keep 45 s off a whole number, where a sum of
    tenths could land either side)."""
    stepped = SceneHost(SCENES)
    stepped.start(frame_loop=False)
    try:
        stepped.open_stage(STAGE, "heavy-top", {})
        stepped.set_playback(STAGE, time_scale=time_scale, reset=True)
        assert t_now(stepped, "heavy-top", STAGE) == 0.0
        frame_s = 1.0 / 30.0
        for _ in range(45):
            stepped.run_frame(frame_s)
        assert t_now(stepped, "heavy-top", STAGE) == pytest.approx(steps_in_45_frames * frame_s, abs=1e-12)
        assert stepped.playback(STAGE)["history_s"] == pytest.approx([0.0, steps_in_45_frames * frame_s], abs=1e-12)  # kept
        stepped.set_playback(STAGE, playing=False)
        stepped.run_frame(frame_s)
        assert t_now(stepped, "heavy-top", STAGE) == pytest.approx(steps_in_45_frames * frame_s, abs=1e-12)
    finally:
        stepped.stop()


def test_a_handed_over_motion_continues_the_same_trajectory(client):
    """Two instances of the heavy top: the second resumes from the first's motion, and both then step identically."""
    heavy_top = SCENES["heavy-top"]
    first = heavy_top(client, heavy_top.parameters.defaults())
    for _ in range(45):
        first.step_physics()
    motion = first.motion_state()
    assert motion["t_s"] == pytest.approx(1.5)
    second = heavy_top(client, heavy_top.parameters.defaults())
    second.resume_from(motion)
    for _ in range(30):
        first.step_physics()
        second.step_physics()
    assert second.run.t_s == pytest.approx(first.run.t_s, abs=1e-12)
    np.testing.assert_allclose(second.run.y, first.run.y, rtol=0, atol=1e-12)  # same integrator, same steps: bit-for-bit in practice
    for bad in ({"t_s": 1.0}, {"t_s": 1.0, "y": [0.0, 1.0]}, {"t_s": float("nan"), "y": motion["y"]}, {"t_s": 1.0, "y": [float("inf")] * len(motion["y"])}):
        with pytest.raises(ValueError, match="motion"):
            second.resume_from(bad)
