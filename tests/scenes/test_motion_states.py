"""Every animated scene can say where it is (``motion_state``), go back there (``resume_from`` + ``redraw``) and
compute any instant from the start (``go_to``): what the time controls' scrubber and a share link build on.

For each animated scene, at its defaults on a headless viewer: 20 frames, keep the motion S and what is drawn
(every live node's position, wxyz, visibility and numeric/array properties), 25 more frames, then resume from S and
redraw. What is drawn must equal the kept drawing to 1e-9 (absolute, in the drawn units: m, quaternion components,
colour levels): resuming replaces the state and redrawing recomputes the same floats from it, so anything larger
means the motion state misses something the drawing depends on. Trails are history, not the instant (they start
again after a resume), so nodes under a trail's root are left out.

A fresh instance's ``go_to(S["t_s"])`` must draw the same picture to 1e-6: it replays the same fixed frames from
the start (closed forms: the same clock arithmetic; integrated: the same integrator and steps), so the two agree to
round-off; 1e-6 m is far below a pixel and leaves room for a reordered sum. The JSON round trip of S is exact, and
bad input (times outside 0–600 s, garbage motions) is a ValueError naming the field.
"""

from __future__ import annotations

import json
import math
import re

import numpy as np
import pytest

from app.scenes import SCENES
from app.scenes.kit import FRAME_DT_S, IntegratedScene
from app.scenes.kit.background_pilots import PILOTS
from tests.scenes.conftest import HeadlessClient

ANIMATED = sorted(scene_id for scene_id, cls in SCENES.items() if cls.animated)
KEPT_FRAMES, LATER_FRAMES = 20, 25
RESUME_ATOL = 1e-9
GO_TO_ATOL = 1e-6


def trail_roots(scene) -> tuple[str, ...]:
    return tuple(f"{trail.root}/" for trail in scene.drawn_trails())


def run_frames(scene, client, frames: int) -> None:
    for _ in range(frames):
        with client.atomic():
            scene.advance(FRAME_DT_S)


def without_serials(drawn: dict) -> dict:
    """Node names with a trailing rebuild serial (``/accel/3``: a batch re-added under a fresh name) made
    ``/accel/#``, so two instances with different rebuild histories compare node by node."""
    out = {re.sub(r"/\d+$", "/#", name): props for name, props in drawn.items()}
    return out if len(out) == len(drawn) else drawn


def assert_same_drawing(got: dict, want: dict, atol: float, what: str) -> None:
    got, want = without_serials(got), without_serials(want)
    assert got.keys() == want.keys(), f"{what}: nodes differ: {sorted(got.keys() ^ want.keys())}"
    for name, props in want.items():
        assert got[name].keys() == props.keys(), f"{what}: {name} properties differ"
        for prop, value in props.items():
            other = got[name][prop]
            assert np.shape(other) == np.shape(value), f"{what}: {name}.{prop} shape {np.shape(other)} != {np.shape(value)}"
            assert np.allclose(other, value, rtol=0.0, atol=atol, equal_nan=False), (
                f"{what}: {name}.{prop} differs by {np.max(np.abs(np.asarray(other) - np.asarray(value))):.3g}"
            )


def build_at_defaults(cls, client):
    """The scene at its defaults; an integrated scene whose step choice was still being measured is restarted once
    the pilot is done, so every later instance starts with the same (cached) integrator."""
    params = cls.parameters.validate({})
    scene = cls(client, params)
    if isinstance(scene, IntegratedScene) and PILOTS.pending():
        assert PILOTS.wait_idle(60.0), "the step-choice pilot did not finish"
        scene.set_params(params)
    return scene, params


def garbage_motions(motion: dict) -> list:
    out: list = [None, "t_s=1", {}, {**motion, "t_s": -1.0}, {**motion, "t_s": math.nan}, {key: "x" for key in motion}]
    for key, value in motion.items():
        if isinstance(value, list):
            out.append({**motion, key: value[:-1]})
            out.append({**motion, key: [math.inf, *value[1:]]})
        elif key != "t_s":
            out.append({**motion, key: math.nan})
    return out


@pytest.mark.parametrize("scene_id", ANIMATED)
def test_resume_redraw_and_go_to_reproduce_the_drawing(client, scene_id):
    cls = SCENES[scene_id]
    scene, params = build_at_defaults(cls, client)
    run_frames(scene, client, KEPT_FRAMES)
    assert scene.status == "", scene.status
    kept = scene.motion_state()
    assert isinstance(kept, dict) and "t_s" in kept
    assert json.loads(json.dumps(kept, allow_nan=False)) == kept  # plain JSON, exactly
    skip = trail_roots(scene)
    drawn = client.scene.snapshot(skip_prefixes=skip)

    run_frames(scene, client, LATER_FRAMES)
    assert scene.motion_state() != kept, f"{scene_id}: the motion did not change in {LATER_FRAMES} frames"
    for garbage in garbage_motions(kept):
        with pytest.raises(ValueError, match="motion"):
            scene.resume_from(garbage)
    with client.atomic():
        scene.resume_from(kept)
        scene.redraw()
    assert scene.motion_state() == kept
    assert_same_drawing(client.scene.snapshot(skip_prefixes=skip), drawn, RESUME_ATOL, f"{scene_id} resumed")

    for outside in (-1.0, 601.0, math.nan):
        with pytest.raises(ValueError, match="t_s"):
            scene.go_to(outside)
    scene.close()

    fresh_client = HeadlessClient(client._client)
    fresh = cls(fresh_client, params)
    fresh.go_to(kept["t_s"])
    assert fresh.motion_state()["t_s"] == pytest.approx(kept["t_s"], abs=1e-9)
    assert_same_drawing(fresh_client.scene.snapshot(skip_prefixes=skip), drawn, GO_TO_ATOL, f"{scene_id} go_to")
    fresh.close()


#: Scenes whose clock runs with the frames and that loop or replay within a few seconds at their defaults, and the
#: frames played live past that (projectile and drop: replay after landing; ladder: after it lands; bar: held at its
#: stop, then replayed).
LOOPING = {"projectile-drag": 200, "eastward-deflection": 200, "sliding-ladder": 130, "sliding-bar-friction": 160}


@pytest.mark.parametrize(("scene_id", "frames"), sorted(LOOPING.items()))
def test_go_to_past_a_replay_lands_where_playing_live_does(client, scene_id, frames):
    """go_to replays the scene's own loop rule: past a replay it agrees with the frames played live (same 1e-6)."""
    cls = SCENES[scene_id]
    scene, params = build_at_defaults(cls, client)
    run_frames(scene, client, frames)
    live = scene.motion_state()
    assert live["t_s"] < frames * FRAME_DT_S - 0.5 or live.get("held_s", 0.0) > 0.0, f"{scene_id} did not loop or hold"
    skip = trail_roots(scene)
    drawn = client.scene.snapshot(skip_prefixes=skip)
    scene.close()

    fresh_client = HeadlessClient(client._client)
    fresh = cls(fresh_client, params)
    fresh.go_to(frames * FRAME_DT_S)
    assert fresh.motion_state()["t_s"] == pytest.approx(live["t_s"], abs=1e-9)
    assert_same_drawing(fresh_client.scene.snapshot(skip_prefixes=skip), drawn, GO_TO_ATOL, f"{scene_id} go_to past a replay")
    fresh.close()
