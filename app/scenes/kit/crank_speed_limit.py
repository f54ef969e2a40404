"""A crank driven by a constant torque speeds up without limit: the scene pauses, saying why, past the speed its step
was chosen for (the slider-crank's kinetics and the chapter-8 linkages)."""

from __future__ import annotations

from app.scenes.kit.integrated import IntegratedScene


def paused_at_crank_speed_limit(scene: IntegratedScene, crank_speed_rad_s: float, limit_rad_s: float) -> bool:
    """Pause ``scene`` with the reason once its crank turns faster than ``limit_rad_s`` (rad/s), the speed its step
    was chosen for (a frictionless crank under a constant torque speeds up without limit); True when paused."""
    speed = abs(crank_speed_rad_s)
    if speed <= limit_rad_s:
        return False
    scene.run.status = "speed_limit"
    scene.status = (
        f"Paused at t = {scene.run.t_s:.2f} s: the crank has reached {speed:.0f} rad/s. With no friction "
        f"a constant torque speeds the crank up without limit; the step was chosen for speeds up to "
        f"{limit_rad_s:.0f} rad/s. Change a control to start again."
    )
    return True
