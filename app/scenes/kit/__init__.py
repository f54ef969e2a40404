"""What every scene is built from: the Scene base, integrated scenes, typed readouts, trails, drawing helpers,
and the cheap per-frame node updates (``move_node``, ``update_node``: use them in ``advance``)."""

from app.scenes.kit.drawing import arrow_segments, circle_segments, quaternion_z_to
from app.physics.core.readout import Mark, Quantity, Readout
from app.scenes.kit.integrated import FRAME_DT_S, IntegratedScene
from app.scenes.kit.scene import Preset, Scene
from app.scenes.kit.trail import Trail
from app.scenes.host.viser_compat import move_node, update_node

__all__ = [
    "FRAME_DT_S",
    "IntegratedScene",
    "Mark",
    "Preset",
    "Quantity",
    "Readout",
    "Scene",
    "Trail",
    "arrow_segments",
    "circle_segments",
    "move_node",
    "quaternion_z_to",
    "update_node",
]
