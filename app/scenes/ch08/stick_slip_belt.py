"""Scene: a block on a moving belt held by a spring, sticking and slipping, with friction against its limit.

World frame: the belt runs along x (its top surface at z = 0), seen from −y. The
spring's anchor post stands at x = −ANCHOR_GAP_M − half a block, so the block's
centre is at the model's x (the spring is unstretched at x = 0). Grey ticks on the
belt move at the belt speed. The friction gauge above: a grey scale from −μ_s N to
+μ_s N, red ticks at ±μN of the current mode (μ_s N sticking, μ_k N slipping) and
the friction force F as a bar (green sticking, orange slipping); the same F is the
arrow on the block's base.
"""

from __future__ import annotations

import numpy as np

from app.physics.systems.ch08 import stick_slip_belt as physics
from app.scenes.kit import IntegratedScene, Preset, Quantity, Readout, arrow_segments, move_node, update_node

BLOCK_M = 0.12
ANCHOR_GAP_M = 0.6
BELT_TICK_SPACING_M = 0.1
BELT_TICKS = 32
SPRING_COILS = 10
GAUGE_HALF_WIDTH_M = 0.35
GAUGE_HEIGHT_M = 0.45
MODE_COLORS = {physics.STICK: (40, 160, 70), physics.SLIP_MODE: (230, 130, 20)}
#: Run ahead this far (s) to list the transitions the readout reports.
LOOKAHEAD_S = 60.0


class StickSlipBeltScene(IntegratedScene):
    id = "stick-slip-belt"
    title = "Stick–slip: a block on a moving belt"
    chapter = 8
    model = physics.StickSlipBelt
    #: Block, spring, belt ticks, gauge, friction arrow and the mode label's position each frame; its text only when the
    #: mode changes.
    frame_message_budget = 7.0
    presets = (
        Preset(
            "stick-slip",
            "Stick–slip cycle",
            {"belt_speed_m_s": 0.5, "mu_static": 0.6, "mu_kinetic": 0.4, "x0_m": 0.0, "v0_m_s": 0.0},
            "μ_s > μ_k: the block rides with the belt until k x = μ_s N, slips back, and sticks again — a limit cycle.",
        ),
        Preset(
            "pushed-start",
            "Pushed start",
            {"belt_speed_m_s": 0.5, "mu_static": 0.6, "mu_kinetic": 0.4, "x0_m": -0.4, "v0_m_s": 1.2},
            "Thrown forward from x = −0.4 m at 1.2 m/s: a slip transient, then the same stick–slip cycle.",
        ),
        Preset(
            "fast-belt",
            "Fast belt, pure slip",
            {"belt_speed_m_s": 2.0, "mu_static": 0.6, "mu_kinetic": 0.4, "x0_m": 0.0, "v0_m_s": 0.0},
            "The block never catches the belt: it slips all the time, oscillating about x_eq = μ_k N / k.",
        ),
        Preset(
            "belt-at-rest",
            "Belt at rest",
            {"belt_speed_m_s": 0.0, "mu_static": 0.3, "mu_kinetic": 0.2, "x0_m": 0.9, "v0_m_s": 0.0},
            "A released spring on a still belt: each swing loses 2 μ_k N / k of amplitude until friction holds it.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.belt = scene.add_box("/belt", color=(70, 70, 80), dimensions=(4.0, 0.3, 0.04), position=(0.0, 0.0, -0.02))
        self.ticks = scene.add_line_segments(
            "/belt/ticks", np.zeros((BELT_TICKS, 2, 3), np.float32), (190, 190, 190), thickness=0.006
        )
        self.anchor = scene.add_box("/anchor", color=(140, 140, 150), dimensions=(0.04, 0.2, 0.3))
        self.block = scene.add_box("/block", color=(60, 110, 200), dimensions=(BLOCK_M, 0.14, BLOCK_M))
        self.spring = scene.add_line_segments(
            "/spring", np.zeros((2 * SPRING_COILS + 2, 2, 3), np.float32), (200, 60, 60), thickness=0.008
        )
        self.friction_arrow = scene.add_arrows(
            "/friction",
            np.zeros((1, 2, 3), np.float32),
            (230, 130, 20),
            shaft_radius=0.008,
            head_radius=0.02,
            head_length=0.04,
        )
        self.gauge = scene.add_line_segments(
            "/gauge", np.zeros((6, 2, 3), np.float32), np.zeros((6, 2, 3), np.uint8), thickness=0.012
        )
        self.gauge_label = scene.add_label("/gauge/label", "", anchor="bottom-left")
        self.mode_label = scene.add_label("/mode", "", anchor="bottom-center")
        self._mode = -1

    def camera_view(self):
        return (-0.1, -1.45, 0.45), (-0.1, 0.0, 0.18)

    def update(self) -> None:
        params = self.physical_params()
        self.restart()
        normal = params["mass_kg"] * params["g_m_s2"]
        self._gauge_scale = GAUGE_HALF_WIDTH_M / max(params["mu_static"] * normal, 1e-9)
        anchor_x = -ANCHOR_GAP_M - 0.5 * BLOCK_M
        self.anchor.position = (anchor_x - 0.02, 0.0, 0.15)
        self.gauge_label.position = (-GAUGE_HALF_WIDTH_M, 0.0, GAUGE_HEIGHT_M + 0.06)
        self.gauge_label.text = "friction F on the block against ±μN (green: stick, orange: slip)"
        self.changes = physics.transitions(params, t_end_s=LOOKAHEAD_S, rtol=1e-10)
        self.cycle = physics.limit_cycle(params)
        self._mode = -1
        self._draw()

    def _draw(self) -> None:
        params = self.physical_params()
        y = self.run.y
        x = float(y[physics.X])
        half = 0.5 * BLOCK_M
        move_node(self.block, position=(x, 0.0, half))
        # Belt ticks drift at the belt speed (wrapped onto a fixed span).
        offset = (params["belt_speed_m_s"] * self.run.t_s) % BELT_TICK_SPACING_M
        tick_x = -1.6 + offset + BELT_TICK_SPACING_M * np.arange(BELT_TICKS)
        ticks = np.zeros((BELT_TICKS, 2, 3), np.float32)
        ticks[:, :, 0] = tick_x[:, None]
        ticks[:, 0, 1], ticks[:, 1, 1] = -0.15, 0.15
        ticks[:, :, 2] = 0.001
        update_node(self.ticks, points=ticks)
        # Spring: a zig-zag from the anchor post to the block's left face.
        start, end = -ANCHOR_GAP_M - half, max(x - half, -ANCHOR_GAP_M - half + 0.02)
        along = np.linspace(start, end, 2 * SPRING_COILS + 3)
        heights = np.full(along.shape, half)
        heights[1:-1] += 0.03 * np.where(np.arange(1, along.size - 1) % 2 == 1, 1.0, -1.0)
        nodes = np.stack([along, np.zeros_like(along), heights], axis=1)
        update_node(self.spring, points=np.stack([nodes[:-1], nodes[1:]], axis=1).astype(np.float32))
        friction_N, limit_N = physics.friction_forces(params, y)
        friction, limit = float(friction_N[0]), float(limit_N[0])
        self._friction, self._limit = friction, limit
        mode = int(y[physics.MODE])
        color = np.array(MODE_COLORS[mode], np.uint8)
        update_node(
            self.friction_arrow,
            points=arrow_segments(np.array([x, 0.0, 0.01]), np.array([friction, 0.0, 0.0]), 0.5 * self._gauge_scale),
        )
        # Gauge: scale line, the two mode-limit ticks, the force bar, and its zero tick.
        s, z = self._gauge_scale, GAUGE_HEIGHT_M
        full = GAUGE_HALF_WIDTH_M
        segments = np.array(
            [
                [[-full, 0.0, z], [full, 0.0, z]],
                [[-s * limit, 0.0, z - 0.05], [-s * limit, 0.0, z + 0.05]],
                [[s * limit, 0.0, z - 0.05], [s * limit, 0.0, z + 0.05]],
                [[0.0, 0.0, z + 0.012], [s * friction, 0.0, z + 0.012]],
                [[0.0, 0.0, z - 0.012], [s * friction, 0.0, z - 0.012]],
                [[0.0, 0.0, z - 0.03], [0.0, 0.0, z + 0.03]],
            ],
            np.float32,
        )
        colors = np.array([[150, 150, 150], [210, 40, 40], [210, 40, 40], color, color, [60, 60, 60]], np.uint8)
        update_node(self.gauge, points=segments, colors=np.repeat(colors[:, None, :], 2, axis=1))
        move_node(self.mode_label, position=(x, 0.0, BLOCK_M + 0.05))
        if mode != self._mode:
            self._mode = mode
            update_node(self.mode_label, text=physics.MODE_WORDS[mode])

    def readout(self) -> Readout:
        params = self.physical_params()
        y = self.run.y
        budget = physics.energy_budget(params, y)
        mode = int(y[physics.MODE])
        last = next((c for c in reversed(self.changes) if c.t_s <= self.run.t_s), None)
        cycle = self.cycle
        no_cycle = "no stick–slip cycle (belt at rest or μ_k = μ_s)"
        quantities = [
            Quantity("t_s", "time t", self.run.t_s, "s"),
            Quantity.word("mode", "mode", physics.MODE_WORDS[mode]),
            Quantity("x_m", "position x (spring unstretched at 0)", float(y[physics.X]), "m"),
            Quantity("v_m_s", "velocity ẋ", float(y[physics.V]), "m/s"),
            Quantity(
                "relative_velocity_m_s",
                "velocity relative to the belt ẋ − v_b",
                float(y[physics.V] - params["belt_speed_m_s"]),
                "m/s",
            ),
            Quantity("friction_force_N", "friction force F on the block", self._friction, "N"),
            Quantity("friction_limit_N", "its limit μN in this mode", self._limit, "N"),
            Quantity("kinetic_energy_J", "kinetic energy", float(budget.kinetic_J[0]), "J"),
            Quantity("spring_energy_J", "spring energy", float(budget.spring_J[0]), "J"),
            Quantity("dissipated_J", "dissipated by friction", float(budget.dissipated_J[0]), "J"),
            Quantity("belt_work_J", "work done by the belt", float(budget.belt_work_J[0]), "J"),
            Quantity(
                "energy_budget_J", "kinetic + spring + dissipated − belt work (constant)", float(budget.total_J[0]), "J"
            ),
            Quantity.or_text("last_transition_s", "last transition at t", last.t_s if last else None, "s", "none yet"),
            Quantity.or_text(
                "stick_duration_s",
                "stick phase of the cycle (closed form)",
                cycle.stick_s if cycle else None,
                "s",
                no_cycle,
            ),
            Quantity.or_text(
                "slip_duration_s",
                "slip phase of the cycle (closed form)",
                cycle.slip_s if cycle else None,
                "s",
                no_cycle,
            ),
        ]
        return Readout(quantities, message=self._message(params, mode, last))

    def _message(self, params, mode: int, last) -> str:
        if self.status:
            return self.status
        if mode == physics.STICK:
            return (
                f"Sticking: the block rides with the belt at {params['belt_speed_m_s']:g} m/s; friction holds "
                "the spring, "
                f"|F| = {abs(self._friction):.3f} N ≤ μ_s N = {self._limit:.3f} N."
            )
        words = f"Slipping: friction is μ_k N = {self._limit:.3f} N against the relative velocity"
        if last is not None:
            words += f" (since t = {last.t_s:.4f} s: {last.words})"
        return words + "."
