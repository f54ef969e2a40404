"""Frame costs measured on a client that draws nothing (app/bench/frame_costs.py)."""

from __future__ import annotations

import math

import pytest

from app.bench import frame_costs
from app.scenes import SCENES


@pytest.mark.parametrize("scene_id", ["unbalanced-rotor", "sliding-ladder", "inertia-explorer", "rotation-sequence"])
def test_every_kind_of_scene_runs_on_the_null_client_and_its_physics_is_part_of_its_frame(monkeypatch, scene_id):
    monkeypatch.setattr(frame_costs, "TIMED_FRAMES", 20)
    frame_us, physics_us = frame_costs.scene_frame_cost_us(SCENES[scene_id])
    assert math.isfinite(frame_us) and frame_us > 0.0
    assert 0.0 <= physics_us <= frame_us


def test_the_null_client_remembers_what_a_scene_sets_and_accepts_every_call():
    client = frame_costs.NullClient()
    assert client.scene is client.scene
    handle = client.scene.add_arrows("/a", points=[[0, 0, 0]])
    other = client.scene.add_label("/b", "text")
    handle.points = [[1.0, 2.0, 3.0]]
    assert handle.points == [[1.0, 2.0, 3.0]] and other is not handle and other.points is not handle.points
    with client.atomic():
        client.gui.main_panel.minimize()
    handle.remove()


def test_a_null_handle_holds_what_it_was_made_with_and_a_scene_node_s_default_pose():
    """The rotation-sequence scene reads its frames' poses back (the benchmark's live-frame stage failed on it)."""
    scene = frame_costs.NullClient().scene
    made = scene.add_label("/l", "x", position=(1.0, 2.0, 3.0))
    assert made.position == (1.0, 2.0, 3.0)
    frame = scene.add_frame("/f", axes_length=0.1)
    assert frame.position == (0.0, 0.0, 0.0) and frame.wxyz == (1.0, 0.0, 0.0, 0.0)
