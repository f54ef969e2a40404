"""What every scene is built from: the Scene base, integrated scenes, typed readouts, trails, drawing helpers,
and the cheap per-frame node updates (``move_node``, ``update_node``: use them in ``advance``)."""

from app.physics.core.readout import Mark, Quantity, Readout
from app.scenes.kit.drawing import arrow_segments, circle_segments, quaternion_z_to
from app.scenes.kit.integrated import IntegratedScene
from app.scenes.kit.scene import (
    FRAME_DT_S,
    GO_TO_MAX_S,
    LabelAnchor,
    Preset,
    Scene,
    checked_go_to_time,
    motion_numbers,
)
from app.scenes.kit.trail import Trail
from app.scenes.viser_boundary import move_node, update_node

__all__ = [
    "FRAME_DT_S",
    "GO_TO_MAX_S",
    "IntegratedScene",
    "LabelAnchor",
    "Mark",
    "Preset",
    "Quantity",
    "Readout",
    "Scene",
    "Trail",
    "arrow_segments",
    "checked_go_to_time",
    "circle_segments",
    "motion_numbers",
    "move_node",
    "quaternion_z_to",
    "update_node",
]
