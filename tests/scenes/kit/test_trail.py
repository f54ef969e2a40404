"""A trail keeps the last ``chunk_frames × max_chunks`` points and, once full, recycles its oldest node."""

from __future__ import annotations

import numpy as np

from app.scenes.viser_boundary import count_outgoing_messages, scene_node_names
from app.scenes.kit import Trail


def point(n: int) -> np.ndarray:
    return np.array([n, 0.5 * n, 0.0], np.float32)


def test_a_full_trail_recycles_its_oldest_node_with_one_message_per_chunk(viewer):
    client = viewer[1]
    trail = Trail(client.scene, "/trail", color=(255, 0, 0), chunk_frames=3, max_chunks=4)
    for n in range(13):  # four chunks of three segments: the trail is full
        trail.add(point(n))
    names = {name for name in scene_node_names(client.scene) if name.startswith("/trail/")}
    assert len(names) == 4 and trail.chunk_count == 4
    with count_outgoing_messages(client) as sent:
        for n in range(13, 13 + 3 * 5):  # five more chunks
            trail.add(point(n))
    assert sent[0] == 5  # one points update per chunk; nothing created or removed
    assert {name for name in scene_node_names(client.scene) if name.startswith("/trail/")} == names
    newest = trail._nodes[-1].points
    np.testing.assert_array_equal(newest[-1], [point(26), point(27)])  # the newest chunk ends at the newest point
    shown = np.concatenate([node.points for node in trail._nodes])
    np.testing.assert_array_equal(shown[0, 0], point(27 - 4 * 3))  # and the trail starts 12 segments back
    trail.clear()
    assert not [name for name in scene_node_names(client.scene) if name.startswith("/trail/")]
