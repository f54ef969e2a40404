"""Drawing helpers shared by the chapter-3 kinematics scenes: a labelled triad of axes, vectors as text."""

from __future__ import annotations

import numpy as np


def add_labelled_axes(scene, name: str, *, length: float, labels: str, axes_radius: float, origin_radius: float):
    """A frame node ``name`` whose x, y, z axes (``length`` display units) carry the three ``labels`` at their tips."""
    frame = scene.add_frame(name, axes_length=length, axes_radius=axes_radius, origin_radius=origin_radius)
    for axis, text in enumerate(labels):
        tip = np.zeros(3)
        tip[axis] = length + 0.08
        scene.add_label(f"{name}/label_{axis}", text, position=tip, anchor="center-center")
    return frame


def components_text(v: np.ndarray, digits: int = 3) -> str:
    """``(+0.123, -0.456, +0.789)``: a vector's three components, signed, to ``digits`` decimals (never −0)."""
    return "(" + ", ".join(f"{round(float(c), digits) + 0.0:+.{digits}f}" for c in v) + ")"
