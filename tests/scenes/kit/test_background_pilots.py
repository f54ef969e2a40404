"""A live scene's restart never runs the step choice's pilot: it starts at once and switches when the pilot is in.

The frame loop that would wait for a pilot serves every student of the worker, so
the restart must return without measuring (no timed assertion: the pilot counter
says whether one ran); the pilot then runs in the worker's background queue, one
at a time, the latest parameters winning.
"""

from __future__ import annotations

import threading

from app.physics.solvers.step_choice import ESTIMATING, PILOT_CACHE
from app.scenes.ch10.heavy_top import HeavyTopScene
from app.scenes.kit.background_pilots import PILOTS, BackgroundPilots
from app.scenes.kit.integrated import FRAME_DT_S


def test_a_restart_with_a_cold_cache_runs_no_pilot_and_switches_at_a_frame_boundary(client):
    PILOTS.wait_idle(60.0)
    PILOT_CACHE.clear()
    scene = HeavyTopScene(client, HeavyTopScene.parameters.validate({"spin_rad_s": 140.0}))
    try:
        here = threading.current_thread().name
        assert PILOT_CACHE.pilots_by_thread[here] == 0  # the constructor's restart measured nothing
        assert scene.accuracy is not None and scene.accuracy.status == ESTIMATING
        assert "estimating…" in scene.live_readout()["accuracy"]["accuracy"]
        first = scene.run.integrator
        # A slider move before the pilot is in: again no pilot in the caller, and the older job is superseded.
        scene.set_params(HeavyTopScene.parameters.validate({"spin_rad_s": 150.0}))
        assert PILOT_CACHE.pilots_by_thread[here] == 0 and scene.accuracy.status == ESTIMATING
        assert PILOTS.wait_idle(60.0)
        assert PILOT_CACHE.pilots_by_thread["step-choice-pilots"] > 0 and PILOT_CACHE.pilots_by_thread[here] == 0
        t_before = scene.run.t_s
        scene.advance(FRAME_DT_S)  # the frame boundary: the measured choice replaces the fixed step rule
        assert scene.accuracy.status == "ok", scene.accuracy.text()
        assert scene.accuracy.estimated_error <= 1e-6
        assert scene.run.integrator is not first and scene.run.integrator.name == scene.accuracy.method
        assert scene.run.t_s > t_before  # carried on from the state reached, not restarted
        readout = scene.live_readout()["accuracy"]
        assert readout["status"] == "ok" and "estimated" in readout["accuracy"]
        # The same parameters again: the cached pilot answers at once, nothing queued.
        runs = PILOT_CACHE.pilots_run
        scene.set_params(HeavyTopScene.parameters.validate({"spin_rad_s": 150.0}))
        assert scene.accuracy.status == "ok" and PILOT_CACHE.pilots_run == runs and PILOTS.pending() == 0
    finally:
        scene.close()


def test_the_queue_runs_one_job_at_a_time_and_the_latest_per_owner_wins():
    queue = BackgroundPilots()
    release = threading.Event()
    delivered: list[str] = []
    queue.submit("blocker", lambda: release.wait(10.0) and "blocker", delivered.append)
    for value in ("old", "older-than-latest", "latest"):
        queue.submit("scene", lambda value=value: value, delivered.append)
    assert queue.pending() == 2  # the running blocker and one job for "scene": the older two were replaced
    release.set()
    assert queue.wait_idle(10.0)
    assert delivered == ["blocker", "latest"]


def test_a_failing_job_delivers_none_and_the_queue_keeps_working():
    queue = BackgroundPilots()
    delivered: list[object] = []
    queue.submit("a", lambda: 1 / 0, delivered.append)
    queue.submit("b", lambda: "fine", delivered.append)
    assert queue.wait_idle(10.0)
    assert delivered == [None, "fine"]
