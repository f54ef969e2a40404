"""Scenes: one per file, each drawing one model for one browser. Registry by scene id."""

from __future__ import annotations

from app.scenes.base import Scene
from app.scenes.cardan_joint import CardanJointScene
from app.scenes.four_bar import FourBarScene
from app.scenes.rolling_without_slip import RollingScene
from app.scenes.slider_crank import SliderCrankScene
from app.scenes.eastward_deflection import EastwardDeflectionScene
from app.scenes.foucault_pendulum import FoucaultPendulumScene
from app.scenes.moving_frame import MovingFrameScene
from app.scenes.equinox_precession import EquinoxPrecessionScene
from app.scenes.heavy_top import HeavyTopScene
from app.scenes.free_gyroscope import FreeGyroscopeScene
from app.scenes.gyrocompass import GyrocompassScene
from app.scenes.rate_gyro import RateGyroScene
from app.scenes.projectile_drag import ProjectileDragScene
from app.scenes.radar_tracking import RadarTrackingScene
from app.scenes.robot_arm_cable import RobotArmCableScene
from app.scenes.rotation_sequence import RotationSequenceScene
from app.scenes.space_curve import SpaceCurveScene
from app.scenes.torque_free_body import TorqueFreeBodyScene
from app.scenes.torque_free_axisymmetric import TorqueFreeAxisymmetricScene

SCENES: dict[str, type[Scene]] = {
    cls.id: cls
    for cls in (
        FourBarScene,
        SliderCrankScene,
        CardanJointScene,
        RollingScene,
        MovingFrameScene,
        FoucaultPendulumScene,
        EastwardDeflectionScene,
        RobotArmCableScene,
        RotationSequenceScene,
        SpaceCurveScene,
        RadarTrackingScene,
        ProjectileDragScene,
        HeavyTopScene,
        FreeGyroscopeScene,
        GyrocompassScene,
        RateGyroScene,
        TorqueFreeBodyScene,
        TorqueFreeAxisymmetricScene,
        EquinoxPrecessionScene,
    )
}

__all__ = ["SCENES", "Scene"]
