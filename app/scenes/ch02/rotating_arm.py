"""Scene for section 2.4: a collar sliding along a turning arm, its acceleration split into four named terms.

Drawn in metres on XYZ, +Z up; the arm (grey bar through the pivot at the
origin) turns in the plane z = 0 and the collar (the ball) slides along it,
leaving its path (grey). From the collar: v (blue) with ṙ e_r and r θ̇ e_θ
head to tail (light blue), and a (red) with its four terms head to tail:
r̈ e_r sliding (orange), −r θ̇² e_r centripetal (green), r θ̈ e_θ from the arm's
angular acceleration (purple) and 2 ṙ θ̇ e_θ Coriolis (teal). Per frame: the
arm's attitude, the collar, the batched arrows and three labels.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.systems.ch02 import rotating_arm as physics
from app.scenes.ch02.particle_run import PATH_SAMPLES, ParticleRunScene, chain_arrows, display_scale
from app.scenes.kit import Preset, Quantity, Readout, move_node

ARROW_FRACTION = 0.22  # 90th-percentile v or a arrow / path size
VELOCITY, VELOCITY_PART = (40, 90, 220), (140, 175, 240)
ACCELERATION = (215, 50, 50)
TERM_COLORS = ((235, 140, 20), (40, 160, 70), (150, 60, 190), (20, 170, 170))  # sliding, centripetal, angular, Coriolis
ARM_COLOR = (150, 150, 160)


class RotatingArmScene(ParticleRunScene):
    id = "rotating-arm"
    title = "A collar on a rotating arm: radial, transverse and Coriolis terms"
    chapter = 2
    model = physics.CollarOnRotatingArm
    arrow_colors = (VELOCITY, VELOCITY_PART, VELOCITY_PART, ACCELERATION, *TERM_COLORS)
    labelled_arrows = ((0, "v", 1.0), (3, "a", 1.0), (7, "2ṙθ̇", 0.5))  # the Coriolis term ends at a's tip
    frame_message_budget = 7.0
    presets = (
        Preset(
            "sliding-collar",
            "Collar sliding on a steady arm",
            {
                "arm_rate_rad_s": 1.0,
                "arm_acceleration_rad_s2": 0.0,
                "collar_mean_m": 0.8,
                "collar_amplitude_m": 0.6,
                "collar_frequency_rad_s": 1.5,
            },
            "Ω = 1 rad/s steady: the Coriolis term 2ṙθ̇ is largest as the collar passes r₀ = 0.8 m, where ṙ is largest",
        ),
        Preset(
            "fixed-collar",
            "Collar clamped (b = 0)",
            {"arm_rate_rad_s": 1.0, "arm_acceleration_rad_s2": 0.0, "collar_mean_m": 1.0, "collar_amplitude_m": 0.0},
            "ṙ = r̈ = 0: only the centripetal term −rθ̇² = −1 m/s² is left; the collar goes round a circle",
        ),
        Preset(
            "arm-held",
            "Arm held still (Ω = 0)",
            {
                "arm_rate_rad_s": 0.0,
                "arm_acceleration_rad_s2": 0.0,
                "collar_mean_m": 0.8,
                "collar_amplitude_m": 0.6,
                "collar_frequency_rad_s": 1.5,
            },
            "θ̇ = 0: the collar only slides back and forth, and a = r̈ e_r",
        ),
        Preset(
            "through-the-pivot",
            "Through the pivot",
            {
                "arm_rate_rad_s": 0.6,
                "arm_acceleration_rad_s2": 0.0,
                "collar_mean_m": 0.0,
                "collar_amplitude_m": 1.2,
                "collar_frequency_rad_s": 1.0,
            },
            "r swings from −1.2 m to 1.2 m: at the pivot the arm's e_r and e_θ are still defined, and a is all "
            "Coriolis",
        ),
        Preset(
            "speeding-up",
            "Arm speeding up (α)",
            {"arm_rate_rad_s": 0.3, "arm_acceleration_rad_s2": 0.1, "collar_mean_m": 1.0, "collar_amplitude_m": 0.0},
            "θ̈ = 0.1 rad/s²: the transverse term rθ̈ = 0.1 m/s² stays while −rθ̇² grows",
        ),
    )

    def build(self) -> None:
        super().build()
        scene = self.client.scene
        half = physics.ARM_HALF_LENGTH_M
        self.arm = scene.add_frame("/arm", show_axes=False)
        scene.add_box("/arm/bar", color=ARM_COLOR, dimensions=(2.0 * half, 0.04, 0.02), position=(0.0, 0.0, -0.02))
        scene.add_icosphere("/pivot", radius=0.04, color=(60, 60, 60))
        scene.add_label("/pivot/label", "pivot O", anchor="top-center", font_screen_scale=0.8)

    def run_s(self) -> float:
        return physics.RUN_S

    def prepare(self) -> None:
        self.arm_motion = physics.RotatingArm.from_params(self.params)
        run = self.arm_motion.at(np.linspace(0.0, physics.RUN_S, PATH_SAMPLES + 1))
        self._path = run.position_m
        size = max(float(np.linalg.norm(self._path.max(axis=0) - self._path.min(axis=0))), 1.0)
        self._v_scale = display_scale(np.linalg.norm(run.velocity_m_s, axis=1), target_m=ARROW_FRACTION * size)
        self._a_scale = display_scale(np.linalg.norm(run.acceleration_m_s2, axis=1), target_m=ARROW_FRACTION * size)

    def path_points(self) -> np.ndarray:
        return self._path

    def camera_view(self) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        size = max(self.drawing_size_m, 2.0)
        return (0.1 * size, -0.55 * size, 0.62 * size), (0.0, 0.0, 0.0)

    def arrows_at(self, t_s: float) -> tuple[np.ndarray, np.ndarray]:
        s = self.arm_motion.at(t_s)
        self._state = s
        p, e_r, e_theta = s.position_m[0], s.e_r[0], s.e_theta[0]
        v_parts = np.array([s.v_radial_m_s[0] * e_r, s.v_transverse_m_s[0] * e_theta])
        terms = np.array(
            [
                s.sliding_m_s2[0] * e_r,
                s.centripetal_m_s2[0] * e_r,
                s.angular_m_s2[0] * e_theta,
                s.coriolis_m_s2[0] * e_theta,
            ]
        )
        arrows = np.concatenate(
            [
                chain_arrows(p, s.velocity_m_s[0], v_parts, self._v_scale),
                chain_arrows(p, s.acceleration_m_s2[0], terms, self._a_scale),
            ]
        )
        return p, arrows

    def after_draw(self, t_s: float) -> None:
        half = 0.5 * float(self._state.theta_rad[0])
        move_node(self.arm, wxyz=(math.cos(half), 0.0, 0.0, math.sin(half)))

    def readout(self) -> Readout:
        s = self._state
        speed, a_t, a_n = (float(x[0]) for x in s.path_variables())
        at_rest = "undefined: the collar is momentarily at rest, so it has no direction of travel"
        r = float(s.r_m[0])
        quantities = [
            Quantity("t_s", "time t", self.t_s, "s"),
            Quantity("theta_deg", "arm angle θ", math.degrees(float(s.theta_rad[0])) % 360.0, "deg"),
            Quantity("theta_dot", "arm rate θ̇", float(s.theta_dot_rad_s[0]), "rad/s"),
            Quantity("theta_ddot", "arm angular acceleration θ̈", float(s.theta_ddot_rad_s2[0]), "rad/s²"),
            Quantity("r", "collar along the arm r", r, "m"),
            Quantity("r_dot", "sliding speed ṙ", float(s.r_dot_m_s[0]), "m/s"),
            Quantity("v_r", "radial v_r = ṙ", float(s.v_radial_m_s[0]), "m/s"),
            Quantity("v_theta", "transverse v_θ = r θ̇", float(s.v_transverse_m_s[0]), "m/s"),
            Quantity("a_sliding", "r̈: sliding along the arm (radial)", float(s.sliding_m_s2[0]), "m/s²"),
            Quantity("a_centripetal", "−r θ̇²: centripetal (radial)", float(s.centripetal_m_s2[0]), "m/s²"),
            Quantity("a_r", "radial a_r = r̈ − r θ̇²", float(s.a_radial_m_s2[0]), "m/s²"),
            Quantity("a_angular", "r θ̈: the arm's angular acceleration (transverse)", float(s.angular_m_s2[0]), "m/s²"),
            Quantity("a_coriolis", "2 ṙ θ̇: Coriolis (transverse)", float(s.coriolis_m_s2[0]), "m/s²"),
            Quantity("a_theta", "transverse a_θ = r θ̈ + 2 ṙ θ̇", float(s.a_transverse_m_s2[0]), "m/s²"),
            Quantity("speed", "speed |v|", speed, "m/s"),
            Quantity("acceleration_magnitude", "|a|", float(np.linalg.norm(s.acceleration_m_s2[0])), "m/s²"),
            Quantity.or_text("a_tangential", "path: a_t = v·a/|v|", a_t, "m/s²", at_rest),
            Quantity.or_text("a_normal", "path: a_n = |v × a|/|v|", a_n, "m/s²", at_rest),
        ]
        if abs(r) < 0.01:
            message = (
                "The collar is passing the pivot (r ≈ 0). The arm's e_r and e_θ are still defined, so "
                "every term is; only the collar's own polar angle, atan2(y, x), would jump here."
            )
        elif r < 0:
            message = (
                "r < 0: the collar is on the arm's other half, beyond the pivot. e_r still points along "
                "the arm, so the same formulas hold."
            )
        else:
            message = ""
        if not math.isfinite(a_t):
            message = " ".join(
                m
                for m in (
                    message,
                    "The collar is momentarily at rest: a_t and a_n have no value (there is no direction of travel).",
                )
                if m
            )
        return Readout(quantities, message=message)
