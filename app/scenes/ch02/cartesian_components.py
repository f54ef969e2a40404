"""Scene for section 2.2: a particle given by x(t), y(t), z(t), with v and a drawn by components.

Drawn in metres on XYZ, +Z up. From the particle: the velocity v (blue) and
its components ẋ I, ẏ J, ż K laid head to tail (light blue), and the
acceleration a (red) with ẍ I, ÿ J, z̈ K head to tail (light red), so each
chain visibly adds up to its vector. Arrow lengths: the 90th percentile of the
speed over a run is drawn a quarter of the path's size long, and the same for
|a|. The sine slot is drawn as the path itself (the pin runs along it).
"""

from __future__ import annotations

import numpy as np

from app.physics.systems.ch02 import cartesian_components as physics
from app.scenes.ch02.particle_run import PATH_SAMPLES, ParticleRunScene, chain_arrows, display_scale
from app.scenes.kit import Preset, Quantity, Readout

ARROW_FRACTION = 0.25  # 90th-percentile arrow / path size
VELOCITY, VELOCITY_PART = (40, 90, 220), (140, 175, 240)
ACCELERATION, ACCELERATION_PART = (215, 50, 50), (240, 160, 150)


class CartesianComponentsScene(ParticleRunScene):
    id = "cartesian-components"
    title = "A particle in rectangular Cartesian coordinates: v and a by components"
    chapter = 2
    model = physics.CartesianParticle
    arrow_colors = (VELOCITY, *(VELOCITY_PART,) * 3, ACCELERATION, *(ACCELERATION_PART,) * 3)
    labelled_arrows = ((0, "v", 1.0), (4, "a", 1.0))
    presets = (
        Preset(
            "sine-slot",
            "Pin in a sine slot",
            {"motion": "sine-slot", "slot_amplitude_m": 0.3, "slot_length_m": 1.0, "drive_speed_m_s": 0.5},
            "ẋ = 0.5 m/s constant, so ẍ = 0: the whole acceleration is ÿ, largest at the crests",
        ),
        Preset(
            "deep-slot",
            "Deep, short slot",
            {"motion": "sine-slot", "slot_amplitude_m": 0.6, "slot_length_m": 0.5, "drive_speed_m_s": 0.5},
            "h = 0.6 m, L = 0.5 m: ÿ peaks at h(π/L)²ẋ² = 5.92 m/s² at the crests",
        ),
        Preset(
            "projectile",
            "Projectile",
            {
                "motion": "projectile",
                "launch_speed_m_s": 8.0,
                "launch_angle_deg": 50.0,
                "launch_heading_deg": 30.0,
                "gravity_m_s2": 9.81,
            },
            "a = −g K all the way: ẋ and ẏ never change, ż falls by 9.81 m/s every second",
        ),
        Preset(
            "straight-up",
            "Thrown straight up",
            {"motion": "projectile", "launch_speed_m_s": 6.0, "launch_angle_deg": 90.0, "gravity_m_s2": 9.81},
            "At the top (t = 0.61 s) the speed is 0 while a is still 9.81 m/s² downward",
        ),
    )

    def run_s(self) -> float:
        return self.motion.run_s

    def prepare(self) -> None:
        self.motion = physics.cartesian_motion(self.params)
        run = self.motion.at(np.linspace(0.0, self.motion.run_s, PATH_SAMPLES + 1))
        self._path = run.position_m
        size = max(float(np.linalg.norm(self._path.max(axis=0) - self._path.min(axis=0))), 0.5)
        target = ARROW_FRACTION * size
        self._v_scale = display_scale(np.linalg.norm(run.velocity_m_s, axis=1), target_m=target)
        self._a_scale = display_scale(np.linalg.norm(run.acceleration_m_s2, axis=1), target_m=target)

    def path_points(self) -> np.ndarray:
        return self._path

    def arrows_at(self, t_s: float) -> tuple[np.ndarray, np.ndarray]:
        state = self.motion.at(t_s)
        self._state = state
        p, v, a = state.position_m[0], state.velocity_m_s[0], state.acceleration_m_s2[0]
        arrows = np.concatenate(
            [chain_arrows(p, v, np.diag(v), self._v_scale), chain_arrows(p, a, np.diag(a), self._a_scale)]
        )
        return p, arrows

    def readout(self) -> Readout:
        s = self._state
        p, v, a = s.position_m[0], s.velocity_m_s[0], s.acceleration_m_s2[0]
        quantities = [Quantity("t_s", "time t", self.t_s, "s")]
        quantities += [Quantity(axis, axis, float(p[k]), "m") for k, axis in enumerate("xyz")]
        quantities += [
            Quantity(f"{axis}_dot", f"{symbol}", float(v[k]), "m/s")
            for k, (axis, symbol) in enumerate(zip("xyz", "ẋẏż"))
        ]
        quantities += [Quantity("speed", "speed |v| = √(ẋ² + ẏ² + ż²)", float(np.linalg.norm(v)), "m/s")]
        quantities += [
            Quantity(f"{axis}_ddot", f"{symbol}", float(a[k]), "m/s²")
            for k, (axis, symbol) in enumerate(zip("xyz", ("ẍ", "ÿ", "z̈")))
        ]
        quantities += [
            Quantity("acceleration_magnitude", "|a| = √(ẍ² + ÿ² + z̈²)", float(np.linalg.norm(a)), "m/s²"),
            Quantity("run", "one run lasts", self.motion.run_s, "s"),
            Quantity("grid_cell", "side of a grid square", self.grid_cell_m, "m"),
        ]
        if isinstance(self.motion, physics.SineSlot):
            message = (
                "The pin is driven at constant ẋ, so ẍ = 0: all of a is ÿ J, across the drive. The "
                "controls h, L and ẋ set this motion."
            )
        else:
            message = (
                "Gravity is the only acceleration: ẍ = ÿ = 0 and z̈ = −g throughout, while v turns. The "
                "controls v₀, α, ψ and g set this motion."
            )
        return Readout(quantities, message=message)
