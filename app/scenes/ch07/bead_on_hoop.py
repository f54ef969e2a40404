"""Scene: a bead on a hoop spun at a prescribed rate Ω about its vertical diameter.

Drawn in display units (the hoop's radius is one unit), z up, the hoop's
centre at the origin. The hoop is a frame turning about z at Ω; the bead
(orange) and the relative equilibria ride on it: green dots for stable ones,
red for unstable ones (the bottom turns red once Ω passes √(g/R), when the
off-bottom pair at cos θ* = g/(RΩ²) appears).
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.systems.ch07.bead_on_hoop_model import BeadOnHoopMotion, critical_spin_rad_s, hoop_equilibria
from app.scenes.kit import Preset, Quantity, Readout, circle_segments, move_node
from app.scenes.kit.derived_system_scene import DerivedSystemScene

STABLE_COLOR, UNSTABLE_COLOR = (30, 160, 60), (210, 40, 40)


def on_hoop(theta_rad: float) -> tuple[float, float, float]:
    """Display position (hoop frame, radius 1) of the angle θ from the bottom."""
    return (math.sin(theta_rad), 0.0, -math.cos(theta_rad))


class BeadOnHoopScene(DerivedSystemScene):
    id = "bead-on-rotating-hoop"
    #: The hoop's turn and the bead's position each frame.
    frame_message_budget = 3.0
    title = "A bead on a spinning hoop: the Jacobi integral and the bifurcation at √(g/R)"
    chapter = 7
    model = BeadOnHoopMotion
    run_model: BeadOnHoopMotion
    camera_position = (0.8, -3.6, 1.0)
    camera_look_at = (0.0, 0.0, -0.1)
    presets = (
        Preset(
            "slow-spin",
            "Below the critical spin",
            {"hoop_speed_rad_s": 3.0, "theta_0_deg": 30.0, "theta_rate_0_deg_s": 0.0},
            "Ω = 3 rad/s < √(g/R) = 4.43 rad/s: the bottom is the only stable place; the bead rocks about it.",
        ),
        Preset(
            "fast-spin",
            "Above the critical spin",
            {"hoop_speed_rad_s": 6.0, "theta_0_deg": 20.0, "theta_rate_0_deg_s": 0.0},
            "Ω = 6 rad/s: the bottom is unstable and the bead rocks about θ* = 57.0°, where cos θ* = g/(RΩ²).",
        ),
        Preset(
            "at-equilibrium",
            "Resting at θ*",
            {"hoop_speed_rad_s": 6.0, "theta_0_deg": 56.9753, "theta_rate_0_deg_s": 0.0},
            "Started at θ* (R = 0.5 m, g = 9.81 m/s²): the bead stays put on the hoop while the hoop carries it round.",
        ),
        Preset(
            "over-the-top",
            "Over the top",
            {"hoop_speed_rad_s": 6.0, "theta_0_deg": 0.0, "theta_rate_0_deg_s": 700.0},
            "Launched fast, the bead goes all the way round the hoop; its energy rises and falls, h does not move.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.axis = scene.add_line_segments(
            "/axis", np.array([[[0, 0, -1.35], [0, 0, 1.35]]], np.float32), (120, 120, 120), thickness=0.01
        )
        self.hoop = scene.add_frame("/hoop", show_axes=False)
        self.ring = scene.add_line_segments(
            "/hoop/ring", circle_segments(radius=1.0, normal=(0.0, 1.0, 0.0)), (70, 90, 160), thickness=0.025
        )
        self.bead = scene.add_icosphere("/hoop/bead", radius=0.07, color=(235, 120, 20))
        self.markers: list = []

    def update(self) -> None:
        self.restart()
        for marker in self.markers:
            marker.remove()
        self.markers = [
            self.client.scene.add_icosphere(
                f"/hoop/equilibrium_{k}",
                radius=0.035,
                color=STABLE_COLOR if e.stable else UNSTABLE_COLOR,
                position=on_hoop(e.theta_rad),
            )
            for k, e in enumerate(hoop_equilibria(self.physical_params()))
        ]
        self._draw()

    def _draw(self) -> None:
        turn = float(self.params["hoop_speed_rad_s"]) * self.run.t_s
        move_node(self.hoop, wxyz=(math.cos(turn / 2), 0.0, 0.0, math.sin(turn / 2)))
        move_node(self.bead, position=on_hoop(float(self.run.y[0])))

    def readout(self) -> Readout:
        params = self.physical_params()
        t = np.array([self.run.t_s])
        energy, jacobi = self.run_model.energy_and_jacobi_J(params, t, self.run.y[None, :])
        critical = critical_spin_rad_s(params)
        equilibria = hoop_equilibria(params)
        off_bottom = [e for e in equilibria if e.theta_rad > 0.0 and e.theta_rad < math.pi]
        spin = float(params["hoop_speed_rad_s"])
        quantities = [
            Quantity("t_s", "time t", self.run.t_s, "s"),
            Quantity(
                "theta_deg",
                "bead angle θ from the bottom",
                math.degrees(math.remainder(float(self.run.y[0]), 2 * math.pi)),
                "deg",
            ),
            Quantity("theta_rate_rad_s", "rate θ̇ relative to the hoop", float(self.run.y[1]), "rad/s"),
            Quantity("jacobi_integral_J", "Jacobi integral h = T₂ − T₀ + V (conserved)", float(jacobi[0]), "J"),
            self.drift_quantity("jacobi_integral", "drift of h, |Δh| / scale"),
            Quantity("energy_J", "energy E = T + V (not conserved)", float(energy[0]), "J"),
            Quantity(
                "energy_change_J",
                "change of E since the start (the motor's work)",
                float(energy[0]) - self._energy0,
                "J",
            ),
            Quantity("critical_spin_rad_s", "critical spin √(g/R)", critical, "rad/s"),
            Quantity.word("bottom_stability", "the bottom θ = 0 is", "stable" if equilibria[0].stable else "unstable"),
            Quantity.or_text(
                "off_bottom_equilibrium_deg",
                "off-bottom equilibrium θ*, cos θ* = g/(RΩ²) (stable)",
                math.degrees(off_bottom[0].theta_rad) if off_bottom else None,
                "deg",
                f"none: Ω = {spin:.2f} rad/s is below √(g/R) = {critical:.2f} rad/s",
            ),
            *self.agreement_quantities(),
        ]
        return Readout(quantities, message=self.status)

    def restart(self) -> None:
        super().restart()
        energy, _ = self.run_model.energy_and_jacobi_J(self.physical_params(), np.zeros(1), self.run.y[None, :])
        self._energy0 = float(energy[0])
