"""A path left behind by a moving point, drawn in chunks so a frame never resends the whole line.

Each frame adds one point; every ``chunk_frames`` points become one chunk: a
line-segment node under ``root``. Up to ``max_chunks`` nodes are created; after
that the oldest node is given the new chunk's points (so a trail shows the last
``chunk_frames × max_chunks`` frames). One small message per chunk, not per frame,
and no node created or removed once the trail is full: creating a viser node
costs about ten times what updating one does, for every student at once.
"""

from __future__ import annotations

import numpy as np
import viser

from app.scenes.viser_boundary import update_node


class Trail:
    """A chunked polyline under ``root`` on one client's scene (points in that node's frame)."""

    def __init__(
        self,
        scene: viser.SceneApi,
        root: str,
        *,
        color: tuple[int, int, int],
        chunk_frames: int,
        max_chunks: int,
        thickness: float = 2.5,
    ) -> None:
        self.scene = scene
        self.root = root
        self.color = color
        self.chunk_frames = chunk_frames
        self.max_chunks = max_chunks
        self.thickness = thickness
        self._nodes: list = []
        self._points: list[np.ndarray] = []
        self._serial = 0

    def add(self, point: np.ndarray) -> None:
        """Append one point; draws a new chunk when enough have gathered."""
        self._points.append(np.asarray(point, dtype=np.float32))
        if len(self._points) <= self.chunk_frames:
            return
        line = np.asarray(self._points, np.float32)
        segments = np.stack([line[:-1], line[1:]], axis=1)
        if len(self._nodes) < self.max_chunks:
            self._serial += 1
            self._nodes.append(
                self.scene.add_line_segments(
                    f"{self.root}/{self._serial}",
                    segments,
                    self.color,
                    thickness=self.thickness,
                    thickness_units="screen",
                )
            )
        else:  # full: the oldest chunk's node becomes the newest
            oldest = self._nodes.pop(0)
            update_node(oldest, points=segments)
            self._nodes.append(oldest)
        self._points = [self._points[-1]]  # the next chunk starts where this one ended

    def clear(self) -> None:
        for node in self._nodes:
            node.remove()
        self._nodes = []
        self._points = []

    @property
    def chunk_count(self) -> int:
        return len(self._nodes)
