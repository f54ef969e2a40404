"""Labelled arrows: one batched arrow node whose short arrows are left out, each arrow with its label."""

from __future__ import annotations

from typing import cast

import numpy as np
import viser

from app.scenes.viser_boundary import move_node, update_node


class LabelledArrows:
    """A batch of coloured, labelled arrows of which only those longer than their head are drawn.

    viser draws an arrowhead of fixed length even for a zero vector, so an arrow
    shorter than about its own head is left out (and its label hidden). The batch
    is rebuilt only when the set of drawn arrows changes; otherwise one message
    moves all of them.
    """

    def __init__(self, scene, name: str, colors: dict[str, tuple[int, int, int]], labels: dict[str, str]) -> None:
        self._scene = scene
        self._name = name
        self._colors = colors
        self._node: viser.ArrowsHandle | None = None
        self._drawn: tuple[str, ...] | None = None
        self._serial = 0
        self._style: dict[str, float] = {}
        self._labels = {
            key: scene.add_label(f"{name}_labels/{key}", text, anchor="center-left", font_screen_scale=0.85)
            for key, text in labels.items()
        }
        self._label_visible = {key: True for key in labels}

    def set_style(self, *, shaft_radius: float, head_radius: float, head_length: float) -> None:
        self._style = dict(shaft_radius=shaft_radius, head_radius=head_radius, head_length=head_length)
        self._drawn = None  # rebuild with the new sizes on the next draw

    def draw(
        self, segments: dict[str, tuple[np.ndarray, np.ndarray]], *, label_at: float = 0.6, move_labels: bool = True
    ) -> None:
        """``segments``: key -> (tail, head) in scene units; labels sit ``label_at`` of the way along.

        ``move_labels=False`` leaves the labels where they are this frame (they are still shown or
        hidden with their arrows): the scene moves them every other frame, half the messages.
        """
        shortest = 0.6 * self._style["head_length"]
        keep = [k for k, (tail, head) in segments.items() if np.linalg.norm(head - tail) > shortest]
        for key, (tail, head) in segments.items():
            visible = key in keep
            if visible and (move_labels or visible != self._label_visible[key]):
                move_node(self._labels[key], position=tail + label_at * (head - tail))
            if visible != self._label_visible[key]:
                self._labels[key].visible = visible
                self._label_visible[key] = visible
        points = np.array([segments[k] for k in keep], np.float32).reshape(-1, 2, 3)
        if tuple(keep) != self._drawn:
            if self._node is not None:
                self._node.remove()
            # A fresh name per rebuild, so removing the old batch and adding the new one never name the same node.
            self._serial += 1
            colors = np.array([self._colors[k] for k in keep], np.uint8).reshape(-1, 3)
            self._node = self._scene.add_arrows(f"{self._name}/{self._serial}", points, colors, **self._style)
            self._drawn = tuple(keep)
        else:
            update_node(cast(viser.ArrowsHandle, self._node), points=points)  # drawn: _drawn starts as None
