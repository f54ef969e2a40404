"""Scene base: a crank-driven linkage in absolute coordinates, its pin forces from the multipliers, its residuals live.

The mechanism's plane (x right, y up) is the world xz plane at y = 0, seen
from −y, as in chapters 4 and 6. Links are bars (crank blue, the middle link
green, the third grey), pins black dots, and each pin force λ an arrow. The
arrows share one scale per instant, the largest drawn 0.3 of the mechanism's
span long: they show the forces' directions and relative sizes, the sizes in N
are in the readout. (A scale fixed by the largest force so far would hide them:
a coasting four-bar's forces pass 280 N for a moment each turn and stay near
20 N the rest of the time.)
The readout gives the counts (coordinates, constraints, degrees of freedom),
the pin forces, the position and velocity constraint residuals and the
work–energy residual of the chosen DAE algorithm.
"""

from __future__ import annotations

import math
from typing import ClassVar

import numpy as np

from app.physics.constrained.residuals import multipliers
from app.physics.systems.ch08.planar_linkages_model import PlanarLinkageModel, pin_force_series_name
from app.scenes.kit import IntegratedScene, Quantity, Readout, arrow_segments, move_node, update_node
from app.scenes.kit.crank_speed_limit import paused_at_crank_speed_limit
from app.scenes.kit.planar import to_world

LINK_COLORS = np.array([[40, 100, 220], [40, 150, 70], [120, 120, 130]], np.uint8)
FORCE_COLOR = (210, 60, 40)
#: The largest pin force of the instant is drawn this fraction of the mechanism's span long.
FORCE_ARROW_SPAN = 0.3
#: Camera distance per metre of the mechanism's width and height over its travel: the lesson page's viewer
#: (about 1.4:1, vertical field of view near 70°) then shows the whole travel on about 70% of its width or height.
CAMERA_DISTANCE_PER_WIDTH, CAMERA_DISTANCE_PER_HEIGHT = 0.7, 1.0


class PlanarLinkageScene(IntegratedScene):
    """Draws :attr:`model`'s three links from the state (q, v) of whichever algorithm runs."""

    model: ClassVar[type[PlanarLinkageModel]]
    run_model: PlanarLinkageModel
    #: Links, pins and arrows each frame (and the slider block where there is one).
    frame_message_budget = 5.0
    #: Whether the third link is a slider block (drawn as a box, not a bar).
    has_slider: ClassVar[bool] = False

    def build(self) -> None:
        scene = self.client.scene
        self._span, self._center, self._camera_distance = 1.0, np.zeros(3), 1.0
        self.ground = scene.add_line_segments(
            "/ground", np.zeros((1, 2, 3), np.float32), (110, 110, 110), thickness=0.01
        )
        bars = 2 if self.has_slider else 3
        self.links = scene.add_line_segments(
            "/links",
            np.zeros((bars, 2, 3), np.float32),
            np.repeat(LINK_COLORS[:bars, None, :], 2, axis=1),
            thickness=0.02,
        )
        self.pins = scene.add_point_cloud(
            "/pins", np.zeros((4, 3), np.float32), (30, 30, 30), point_size=0.04, point_shape="circle"
        )
        self.slider = (
            scene.add_box("/slider", color=(150, 150, 160), dimensions=(0.2, 0.1, 0.1)) if self.has_slider else None
        )
        n_pins = len(self.model.pin_joints)
        self.arrows = scene.add_arrows(
            "/forces",
            np.zeros((n_pins, 2, 3), np.float32),
            FORCE_COLOR,
            shaft_radius=0.01,
            head_radius=0.025,
            head_length=0.05,
        )

    def camera_view(self):
        c, distance = self._center, self._camera_distance
        return (float(c[0]), float(-distance), float(c[2] + 0.05 * distance)), (float(c[0]), 0.0, float(c[2]))

    def update(self) -> None:
        params = self.physical_params()
        self.restart()
        model = self.run_model
        self._linkage = model.linkage(params)
        self._speed_limit = model.speed_limit_rad_s(params)
        low, high = model.crank_travel_rad(params)
        theta = np.linspace(low, high, 97)
        q, _, _ = model.absolute_motion(params, theta, np.zeros_like(theta), np.zeros_like(theta))
        ends = np.concatenate([self._link_ends(row).reshape(-1, 2) for row in q[np.all(np.isfinite(q), axis=1)]])
        lo, hi = ends.min(axis=0), ends.max(axis=0)
        width, height = hi - lo
        self._span = span = float(max(width, height))
        self._center = to_world(0.5 * (lo + hi))
        self._camera_distance = max(CAMERA_DISTANCE_PER_WIDTH * width, CAMERA_DISTANCE_PER_HEIGHT * height)
        self.links.thickness = 0.012 * span
        self.pins.point_size = 0.02 * span
        self.arrows.shaft_radius, self.arrows.head_radius, self.arrows.head_length = (
            0.004 * span,
            0.011 * span,
            0.025 * span,
        )
        self.ground.points = self.ground_segments(params).astype(np.float32)
        self.ground.thickness = 0.006 * span
        if self.slider is not None:
            side = self._linkage.links[2].length_m
            self.slider.dimensions = (2.0 * side, 0.03 * span, side)
        self._draw()

    def ground_segments(self, params) -> np.ndarray:
        """(k, 2, 3) world segments of the ground (a guide line, pivot marks)."""
        return np.zeros((1, 2, 3))

    def _link_ends(self, q: np.ndarray) -> np.ndarray:
        """(3, 2, 2) ends of each link (m) from the absolute coordinates q (9,)."""
        ends = []
        for i, link in enumerate(self._linkage.links):
            centre, axis = q[3 * i : 3 * i + 2], np.array([math.cos(q[3 * i + 2]), math.sin(q[3 * i + 2])])
            ends.append([centre - 0.5 * link.length_m * axis, centre + 0.5 * link.length_m * axis])
        return np.array(ends)

    def _full_state(self) -> np.ndarray:
        return self.run_model.constrained_view(self.physical_params(), self.run.y)[0]

    def _draw(self) -> None:
        params = self.physical_params()
        model = self.run_model
        state = self._full_state()
        multipliers = model_multipliers(model, params, self.run.t_s, state)
        self._now = (state, multipliers)
        ends = self._link_ends(state[:9])
        bars = ends[:2] if self.has_slider else ends
        update_node(self.links, points=to_world(bars).astype(np.float32))
        pin_points = self._pin_points(ends)
        update_node(self.pins, points=to_world(pin_points).astype(np.float32))
        if self.slider is not None:
            move_node(self.slider, position=to_world(state[6:8]))
        forces = np.array(list(model.pin_forces_N(params, multipliers).values()))[:, 0, :]
        scale = FORCE_ARROW_SPAN * self._span / max(float(np.max(np.linalg.norm(forces, axis=-1))), 1e-12)
        update_node(self.arrows, points=arrow_segments(to_world(pin_points[: len(forces)]), to_world(forces), scale))

    def _pin_points(self, ends: np.ndarray) -> np.ndarray:
        """(4, 2) pin positions (m) in the order of the model's pin joints (then any extra)."""
        crank, middle, third = ends
        return np.array([crank[0], crank[1], middle[1], third[0]])

    def step_motion(self, dt_s: float) -> bool:
        if paused_at_crank_speed_limit(self, float(self._full_state()[11]), self._speed_limit):
            return False
        return self.step_physics()

    def readout(self) -> Readout:
        params = self.physical_params()
        model = self.run_model
        state, multipliers = self._now
        system = model.constrained_system(params)
        invariants = self.current_invariants()
        energy0 = self._invariants0["energy"]
        quantities = [
            Quantity("t_s", "time t", self.run.t_s, "s"),
            Quantity("coordinates", "coordinates n (3 per link)", float(system.n_coordinates), ""),
            Quantity("constraints", "constraint equations m", float(system.n_constraints), ""),
            Quantity("degrees_of_freedom", "degrees of freedom n − m", float(system.degrees_of_freedom), ""),
            Quantity("crank_angle", "crank angle θ", math.degrees(float(state[2])) % 360.0, "deg"),
            Quantity("crank_speed_rad_s", "crank speed θ̇", float(state[11]), "rad/s"),
        ]
        for name, force in model.pin_forces_N(params, multipliers).items():
            quantities.append(
                Quantity(pin_force_series_name(name), f"pin force at {name} |λ|", float(np.linalg.norm(force[0])), "N")
            )
        quantities += [
            Quantity("constraint_position", "position residual max |g|", invariants["constraint_position"], "m"),
            Quantity("constraint_velocity", "velocity residual max |C q̇|", invariants["constraint_velocity"], "m/s"),
            Quantity(
                "work_energy_residual_J", "work–energy residual ΔT + ΔV − τΔθ", invariants["energy"] - energy0, "J"
            ),
        ]
        algorithm = model.algorithm()
        if algorithm == "baumgarte":
            algorithm += (
                f" (α = {float(self.params['baumgarte_alpha_1_s']):g}/s, β = "
                f"{float(self.params['baumgarte_beta_1_s']):g}/s)"
            )
        quantities.append(Quantity.word("algorithm", "DAE algorithm", algorithm))
        notes = [f"{algorithm}: {self.description}."]
        notes += self.notes(params)
        return Readout(quantities, message=self.status or " ".join(notes))

    def notes(self, params) -> list[str]:
        """Extra sentences for the readout (what a model cannot do here)."""
        return []


def model_multipliers(model: PlanarLinkageModel, params, t_s: float, state: np.ndarray) -> np.ndarray:
    """λ (1, 8) at the state (18,) from the constrained-model residuals module."""
    return multipliers(model.constrained_system(params), np.array([t_s]), state[None, :])
