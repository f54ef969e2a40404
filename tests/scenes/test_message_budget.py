"""Every animated scene keeps to its per-frame message budget on a real viser client.

What a frame costs the server grows with the messages it queues for each viewer
(10–20 µs each, per student, 30 times a second), so each scene declares
``frame_message_budget`` and this test counts what it really sends, frame by
frame, as the host advances it (inside ``client.atomic()``).
"""

from __future__ import annotations

import pytest

from app.scenes import SCENES
from app.scenes.viser_boundary import count_outgoing_messages
from app.scenes.kit import FRAME_DT_S

WARM_UP_FRAMES = 30
COUNTED_FRAMES = 120  # 4 s of motion: every trail chunk, label refresh and batch refill comes round several times
ANIMATED = sorted(scene_id for scene_id, cls in SCENES.items() if cls.animated)
#: The scenes a classroom load test drives: their budgets are tight, so a new message per frame is noticed.
TIGHT_BUDGETS = {"heavy-top": 6.0, "four-bar": 3.0, "moving-frame-acceleration": 6.0}


def messages_per_frame(cls, client) -> float:
    scene = cls(client, cls.parameters.defaults())
    try:
        for _ in range(WARM_UP_FRAMES):
            with client.atomic():
                scene.advance(FRAME_DT_S)
        with count_outgoing_messages(client) as count:
            for _ in range(COUNTED_FRAMES):
                with client.atomic():
                    scene.advance(FRAME_DT_S)
        return count[0] / COUNTED_FRAMES
    finally:
        scene.close()


@pytest.mark.parametrize("scene_id", ANIMATED)
def test_frames_keep_to_the_scene_message_budget(scene_id, client):
    cls = SCENES[scene_id]
    sent = messages_per_frame(cls, client)
    assert sent > 0, f"{scene_id} is animated but sent nothing in {COUNTED_FRAMES} frames"
    assert sent <= cls.frame_message_budget, (
        f"{scene_id} sends {sent:.2f} messages per frame, over its budget of {cls.frame_message_budget}: "
        "batch nodes, send only what changed, and move nodes with move_node/update_node"
    )


def test_the_load_tested_scenes_declare_tight_budgets():
    assert {scene_id: SCENES[scene_id].frame_message_budget for scene_id in TIGHT_BUDGETS} == TIGHT_BUDGETS


def test_counting_sees_a_message_that_breaks_the_budget(client):
    """The count is real: a scene that adds a node every frame is caught."""

    class Leaky(SCENES["four-bar"]):
        def advance(self, dt_s: float) -> None:
            super().advance(dt_s)
            self.client.scene.add_icosphere(f"/leak/{self.t_s:.6f}", radius=0.01)

    assert messages_per_frame(Leaky, client) >= messages_per_frame(SCENES["four-bar"], client) + 1.0  # a new node: one message or more
