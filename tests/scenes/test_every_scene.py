"""Every registered scene, headless: built with its defaults, run 100 frames, every preset, closed.

Checked for each scene, on a real loopback viser server with one real client:
nothing non-finite is sent to the viewer (every ``add_*`` argument, and every
drawn node's geometry and label read back after the frames), the readout is a
typed :class:`Readout` with distinct names, plain JSON, and time ``t_s`` when the
scene is animated; every preset validates through the scene's parameters and
redraws; closing removes every node the scene added.
"""

from __future__ import annotations

import json
import math
import re

import pytest

from app.physics.core.readout import Readout
from app.scenes import SCENES
from app.scenes.viser_boundary import scene_node_names
from app.scenes.kit import FRAME_DT_S
from tests.scenes.conftest import assert_finite

FRAMES = 100
FRAMES_PER_PRESET = 10
#: Handle properties that carry geometry or colour (numbers that reach the viewer).
DRAWN_PROPERTIES = (
    "position", "wxyz", "scale", "points", "colors", "vertices", "radius", "dimensions", "width", "height",
    "thickness", "shaft_radius", "head_radius", "head_length", "point_size", "cell_size", "section_size", "opacity",
)  # fmt: skip
NON_FINITE_TEXT = re.compile(r"\b(nan|inf)\b", re.IGNORECASE)


def assert_drawn_finite(client, scene_id: str) -> None:
    for name, handle in client.scene.handles.items():
        for attribute in DRAWN_PROPERTIES:
            try:
                value = getattr(handle, attribute)
            except AttributeError:
                continue
            assert_finite(value, f"{scene_id}: {name}.{attribute}")
        text = getattr(handle, "text", None)
        assert not (isinstance(text, str) and NON_FINITE_TEXT.search(text)), f"{scene_id}: label {name} reads {text!r}"


def assert_readout_typed(cls, scene) -> None:
    readout = scene.readout()
    if readout is None:
        return
    assert isinstance(readout, Readout), f"{cls.id}: readout() must return a Readout"
    names = [q.name for q in readout.quantities]
    assert len(names) == len(set(names)), f"{cls.id}: repeated readout names {names}"
    if cls.animated:
        assert "t_s" in names, f"{cls.id}: an animated scene's readout names its time t_s"
    for quantity in readout.quantities:
        assert quantity.value is None or math.isfinite(quantity.value), quantity
        assert quantity.value is not None or quantity.text, f"{cls.id}: {quantity.name} has neither a value nor a text"
    for marks in readout.marks.values():
        assert all(math.isfinite(mark.value) for mark in marks)
    json.dumps(readout.as_dict(), allow_nan=False)  # plain JSON: no NaN or infinity


def run_frames(scene, client, frames: int) -> None:
    for _ in range(frames):
        with client.atomic():
            scene.advance(FRAME_DT_S)


@pytest.mark.parametrize("scene_id", sorted(SCENES))
def test_scene_builds_runs_takes_every_preset_and_closes(client, scene_id):
    cls = SCENES[scene_id]
    scene = cls(client, cls.parameters.validate({}))
    run_frames(scene, client, FRAMES)
    assert scene.status == "", f"{scene_id} paused with its defaults: {scene.status}"
    assert_drawn_finite(client, scene_id)
    assert_readout_typed(cls, scene)

    for preset in cls.presets:
        scene.set_params(cls.parameters.validate(preset.values, base=scene.params))
        run_frames(scene, client, FRAMES_PER_PRESET)
        assert scene.status == "", f"{scene_id} preset {preset.name} paused: {scene.status}"
        assert_drawn_finite(client, f"{scene_id} preset {preset.name}")
        assert_readout_typed(cls, scene)

    assert scene_node_names(client.scene)  # it drew something …
    scene.close()
    assert scene_node_names(client.scene) == set()  # … and removed all of it
