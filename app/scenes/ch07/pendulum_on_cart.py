"""Scene: a pendulum hanging from a cart on a rail, the cart tied to a wall by a spring and pushed by F₀ cos(Ω t).

World x along the rail, z up, seen from −y; metres are drawn as they are. The
wall stands at x = −WALL_OFFSET_M·l; the spring is drawn as a zigzag from the
wall to the cart (its force is −k x: relaxed with the cart at x = 0). The red
arrow on the cart is the drive, 0.1 l per newton of F₀'s amplitude at full
length.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.systems.ch07.pendulum_on_cart_model import WORK_SLOT, CartPendulumMotion, drive_force_N
from app.scenes.kit import Preset, Quantity, Readout, arrow_segments, move_node, update_node
from app.scenes.kit.derived_system_scene import DerivedSystemScene

WALL_OFFSET_M = 1.2  # in rod lengths
SPRING_COILS = 10


def spring_zigzag(start_x: float, end_x: float, *, width: float, coils: int = SPRING_COILS) -> np.ndarray:
    """Line segments (2 coils + 1, 2, 3) of a zigzag spring along x at z = 0 between the two ends (m)."""
    xs = np.linspace(start_x, end_x, 2 * coils + 2)
    zs = np.zeros_like(xs)
    zs[1:-1] = width * np.where(np.arange(2 * coils) % 2 == 0, 1.0, -1.0)
    points = np.stack([xs, np.zeros_like(xs), zs], axis=1)
    return np.stack([points[:-1], points[1:]], axis=1).astype(np.float32)


class PendulumOnCartScene(DerivedSystemScene):
    id = "pendulum-on-cart"
    #: Cart, spring, rod, bob and the drive arrow each frame.
    frame_message_budget = 5.0
    title = "A pendulum on a sprung, driven cart"
    chapter = 7
    model = CartPendulumMotion
    run_model: CartPendulumMotion
    camera_position = (0.0, -4.5, -0.3)
    camera_look_at = (0.0, 0.0, -0.5)
    presets = (
        Preset(
            "free",
            "Free (no drive)",
            {"force_amplitude_N": 0.0, "x0_m": 0.0, "theta_0_deg": 30.0},
            "No force: the cart and the bob trade energy through the rod and the spring, and T + V stays constant.",
        ),
        Preset(
            "driven",
            "Driven at Ω = 2 rad/s",
            {"force_amplitude_N": 5.0, "force_frequency_rad_s": 2.0, "x0_m": 0.0, "theta_0_deg": 0.0},
            "F₀ = 5 N at 2 rad/s: watch the work W grow and the energy follow it, ΔE = W.",
        ),
        Preset(
            "cart-kick",
            "Cart pulled aside",
            {"force_amplitude_N": 0.0, "x0_m": 0.4, "theta_0_deg": 0.0},
            "The cart released 0.4 m from its rest: the spring's oscillation sets the bob swinging.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.rail = scene.add_line_segments("/rail", np.zeros((1, 2, 3), np.float32), (110, 110, 110), thickness=0.01)
        self.wall = scene.add_box("/wall", color=(150, 150, 150), dimensions=(0.04, 0.3, 0.4))
        self.spring = scene.add_line_segments(
            "/spring", spring_zigzag(-1.0, 0.0, width=0.05), (90, 90, 90), thickness=0.012
        )
        self.cart = scene.add_box("/cart", color=(40, 100, 220), dimensions=(0.3, 0.2, 0.15))
        self.rod = scene.add_line_segments("/rod", np.zeros((1, 2, 3), np.float32), (40, 40, 40), thickness=0.015)
        self.bob = scene.add_icosphere("/bob", radius=0.07, color=(235, 120, 20))
        self.drive = scene.add_arrows(
            "/drive",
            np.zeros((1, 2, 3), np.float32),
            (210, 40, 40),
            shaft_radius=0.012,
            head_radius=0.03,
            head_length=0.06,
        )

    def update(self) -> None:
        self.restart()
        length = float(self.params["length_m"])
        self._wall_x = -WALL_OFFSET_M * length - 0.5
        self.wall.position = (self._wall_x, 0.0, 0.0)
        self.rail.points = np.array([[[self._wall_x, 0.0, -0.08], [1.5 * length + 1.0, 0.0, -0.08]]], np.float32)
        self.bob.scale = max(0.5, min(2.0, length))
        self._draw()

    def _draw(self) -> None:
        y, length = self.run.y, float(self.params["length_m"])
        x, theta = float(y[0]), float(y[1])
        bob = np.array([x + length * math.sin(theta), 0.0, -length * math.cos(theta)])
        move_node(self.cart, position=(x, 0.0, 0.0))
        update_node(self.spring, points=spring_zigzag(self._wall_x, x - 0.15, width=0.05))
        update_node(self.rod, points=np.array([[[x, 0.0, 0.0], bob]], np.float32))
        move_node(self.bob, position=bob)
        force = float(drive_force_N(self.run_model.parameter_array(self.physical_params()), self.run.t_s))
        update_node(
            self.drive,
            points=arrow_segments(np.array([[x + 0.15, 0.0, 0.12]]), np.array([[force, 0.0, 0.0]]), 0.1 * length),
        )

    def readout(self) -> Readout:
        params = self.physical_params()
        y = self.run.y
        force = float(drive_force_N(self.run_model.parameter_array(params), self.run.t_s))
        energy = float(self.run_model.energy_J(params, np.array([self.run.t_s]), y[None, :])[0])
        work = float(y[WORK_SLOT])
        quantities = [
            Quantity("t_s", "time t", self.run.t_s, "s"),
            Quantity("x_m", "cart position x", float(y[0]), "m"),
            Quantity("theta_deg", "rod angle θ", math.degrees(math.remainder(float(y[1]), 2 * math.pi)), "deg"),
            Quantity("x_rate_m_s", "cart speed ẋ", float(y[2]), "m/s"),
            Quantity("theta_rate_rad_s", "rod rate θ̇", float(y[3]), "rad/s"),
            Quantity("force_N", "drive F = F₀ cos(Ω t)", force, "N"),
            Quantity("power_W", "power of the drive F ẋ", force * float(y[2]), "W"),
            Quantity("force_work_J", "work done by the drive W", work, "J"),
            Quantity("energy_J", "energy E = T + V (spring and gravity in V)", energy, "J"),
            Quantity("energy_change_J", "change of energy ΔE since the start", energy - self._energy0, "J"),
            Quantity("energy_balance_residual_J", "energy balance ΔE − W", energy - self._energy0 - work, "J"),
            self.drift_quantity("energy_balance", "drift of E − W, relative to its scale"),
            *self.agreement_quantities(),
        ]
        return Readout(quantities, message=self.status)

    def restart(self) -> None:
        super().restart()
        self._energy0 = float(self.run_model.energy_J(self.physical_params(), np.zeros(1), self.run.y[None, :])[0])
