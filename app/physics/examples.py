"""Registry of worked examples by id (the ids used in routes and lesson front matter)."""

from __future__ import annotations

from app.physics import equinox_precession, projectile, radar_tracking, robot_arm_cable
from app.physics.solution import WorkedExample

EXAMPLES: dict[str, WorkedExample] = {
    example.id: example for example in (robot_arm_cable.EXAMPLE, radar_tracking.EXAMPLE, projectile.EXAMPLE, equinox_precession.EXAMPLE)
}
