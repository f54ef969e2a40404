"""Scene: the sliding ladder, integrated live through its phases, with the contact forces as arrows.

The ladder's plane is the world x–z plane at y = 0, seen from −y: the wall is
the plane x = 0 (drawn as a grey slab at x < 0), the floor z = 0 (a slab below
it). The bar is drawn in metres. Arrows: the whole contact force (normal plus
friction) on the top end (blue) and on the bottom end (orange; drawn at the centre
once the bar lies flat), and the weight pointing down onto the centre (grey), all on one scale: m·g is drawn 0.3 L long.
The fall replays
from the start 2.5 s after the landing (on a smooth floor the ladder would slide
out of view).
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.systems.ch06 import sliding_ladder as physics
from app.scenes.kit import IntegratedScene, Preset, Quantity, Readout, arrow_segments

ARROW_COLORS = np.array([[40, 100, 220], [230, 130, 30], [120, 120, 120]], np.uint8)
#: Longest run the scene looks ahead to locate the phase changes (s).
LOOKAHEAD_S = 30.0
#: Seconds the ladder is shown lying before the fall replays from the start (a smooth floor lets it slide away).
REPLAY_AFTER_LANDING_S = 2.5


def _xz(point) -> tuple[float, float, float]:
    return float(point[0]), 0.0, float(point[1])


class SlidingLadderScene(IntegratedScene):
    id = "sliding-ladder"
    title = "The sliding ladder"
    chapter = 6
    model = physics.SlidingLadder
    presets = (
        Preset(
            "smooth",
            "Smooth wall and floor",
            {"angle0_deg": 60.0, "mu_wall": 0.0, "mu_floor": 0.0},
            "No friction: it leaves the wall where sin θ = (2/3) sin θ₀ (35.26° from 60°).",
        ),
        Preset(
            "nearly-upright",
            "Nearly upright (89.9°)",
            {"angle0_deg": 89.9, "mu_wall": 0.0, "mu_floor": 0.0},
            "A slow start from almost vertical: it takes seconds to get going, then leaves the wall at 41.81°.",
        ),
        Preset(
            "rough-floor",
            "Rough floor (μ_f = 0.3)",
            {"angle0_deg": 45.0, "mu_wall": 0.0, "mu_floor": 0.3},
            "Floor friction delays the separation and brakes the slide after the landing.",
        ),
        Preset(
            "held",
            "Held by friction",
            {"angle0_deg": 60.0, "mu_wall": 0.2, "mu_floor": 0.3},
            "tan 60° = 1.73 ≥ (1 − μ_w μ_f)/(2 μ_f) = 1.57: friction holds the ladder; it stays.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.wall = scene.add_box("/wall", color=(175, 175, 185), dimensions=(0.1, 0.4, 1.0))
        self.floor = scene.add_box("/floor", color=(150, 160, 150), dimensions=(1.0, 0.4, 0.1))
        self.bar = scene.add_line_segments("/ladder", np.zeros((1, 2, 3), np.float32), (150, 90, 40), thickness=0.05)
        self.ends = scene.add_point_cloud(
            "/ends", np.zeros((2, 3), np.float32), (30, 30, 30), point_size=0.08, point_shape="circle"
        )
        self.arrows = scene.add_arrows(
            "/forces",
            np.zeros((3, 2, 3), np.float32),
            ARROW_COLORS,
            shaft_radius=0.02,
            head_radius=0.05,
            head_length=0.1,
        )
        self.arrow_labels = [
            scene.add_label("/forces/top", "wall on A", anchor="center-left"),
            scene.add_label("/forces/bottom", "floor on the ladder", anchor="center-left"),
        ]
        self.legend = scene.add_label("/legend", "", anchor="bottom-left")
        self._length = 1.0

    def camera_view(self):
        length = self._length
        return (0.7 * length, -1.6 * length, 0.55 * length), (0.7 * length, 0.0, 0.5 * length)

    def update(self) -> None:
        params = self.physical_params()
        self.restart()
        length = params["length_m"]
        self._length = length
        thickness = 0.04 * length
        self.wall.dimensions = (thickness, 0.5 * length, 1.2 * length)
        self.wall.position = (-0.5 * thickness, 0.0, 0.6 * length - thickness)
        self.floor.dimensions = (4.0 * length, 0.5 * length, thickness)
        self.floor.position = (2.0 * length - thickness, 0.0, -0.5 * thickness)
        self.bar.thickness = 0.02 * length
        self.ends.point_size = 0.035 * length
        self.arrows.shaft_radius = 0.012 * length
        self.arrows.head_radius = 0.03 * length
        self.arrows.head_length = 0.06 * length
        self._force_scale = 0.3 * length / (params["mass_kg"] * params["g_m_s2"])
        self.legend.position = (0.05 * length, 0.0, 1.3 * length)
        self.legend.text = (
            "blue: wall on A · orange: floor on B (on G once lying) · grey: weight m·g, ending at G (0.3 L long)"
        )
        self.changes = physics.phase_changes(params, t_end_s=LOOKAHEAD_S)
        self._draw()

    def _draw(self) -> None:
        params = self.physical_params()
        y = self.run.y
        top, bottom = physics.end_positions_m(params, y)
        center = 0.5 * (top + bottom)
        self.bar.points = np.array([[_xz(top), _xz(bottom)]], np.float32)
        self.ends.points = np.array([_xz(top), _xz(bottom)], np.float32)
        forces = physics.contact_forces(params, y)[0]
        self._forces = forces
        on_top = np.array([forces[physics.C_WALL_N], 0.0, forces[physics.C_WALL_FRICTION]])
        on_bottom = np.array([forces[physics.C_FLOOR_FRICTION], 0.0, forces[physics.C_FLOOR_N]])
        weight = np.array([0.0, 0.0, -params["mass_kg"] * params["g_m_s2"]])
        # Lying flat, the floor carries the bar along its length: its resultant acts below G.
        floor_point = center if int(y[physics.PHASE]) == physics.LYING else bottom
        # The weight is drawn ending at G (from above), so it never pokes through the floor once the bar lies flat.
        tails = np.array([_xz(top), _xz(floor_point), _xz(center) - self._force_scale * weight])
        self.arrows.points = arrow_segments(tails, np.array([on_top, on_bottom, weight]), self._force_scale)
        for label, tail, vector in zip(self.arrow_labels, tails, (on_top, on_bottom)):
            label.position = tuple(tail + 1.05 * self._force_scale * vector)
            label.visible = bool(np.linalg.norm(vector) > 0.0)

    def step_motion(self, dt_s: float) -> bool:
        landing = next((c for c in self.changes if c.index == physics.LANDING), None)
        if landing is not None and self.run.t_s > landing.t_s + REPLAY_AFTER_LANDING_S:
            self.restart()  # replay the fall: the readout's budget and drift start again with it
            return True
        return self.step_physics()

    def readout(self) -> Readout:
        params = self.physical_params()
        y = self.run.y
        forces = self._forces
        budget = physics.energy_budget(params, y)
        phase = int(y[physics.PHASE])
        quantities = [
            Quantity("t_s", "time t", self.run.t_s, "s"),
            Quantity.word("phase", "phase", physics.PHASE_WORDS[phase]),
            Quantity("angle_deg", "angle from the floor θ", math.degrees(y[physics.THETA]), "deg"),
            Quantity("wall_force_N", "wall normal force N_A", forces[physics.C_WALL_N], "N"),
            Quantity("floor_force_N", "floor normal force N_B", forces[physics.C_FLOOR_N], "N"),
            Quantity("kinetic_energy_J", "kinetic energy", float(budget.kinetic_J[0]), "J"),
            Quantity("potential_energy_J", "potential energy (floor = 0)", float(budget.potential_J[0]), "J"),
            Quantity("friction_work_J", "work done against friction", float(budget.friction_work_J[0]), "J"),
            Quantity("impact_loss_J", "energy lost in the landing", float(budget.impact_loss_J[0]), "J"),
            Quantity("energy_total_J", "sum (stays at the initial energy)", float(budget.total_J[0]), "J"),
        ]
        release = next((c for c in self.changes if c.index == physics.WALL_RELEASE), None)
        never = "held by friction: never" if phase == physics.HELD else f"not within {LOOKAHEAD_S:g} s"
        quantities += [
            Quantity.or_text("separation_time_s", "leaves the wall at t", release.t_s if release else None, "s", never),
            Quantity.or_text(
                "separation_angle_deg",
                "angle when it leaves the wall",
                math.degrees(release.state[physics.THETA]) if release else None,
                "deg",
                never,
            ),
        ]
        frictionless = params["mu_wall"] == 0.0 and params["mu_floor"] == 0.0
        closed_form = math.degrees(physics.separation_angle_frictionless_rad(math.radians(params["angle0_deg"])))
        quantities.append(
            Quantity.or_text(
                "separation_angle_closed_form_deg",
                "closed form sin θ = (2/3) sin θ₀",
                closed_form if frictionless else None,
                "deg",
                "applies only with μ_w = μ_f = 0",
            )
        )
        return Readout(quantities, message=self._message(params, phase, forces))

    def _message(self, params, phase: int, forces: np.ndarray) -> str:
        if self.status:
            return self.status
        if phase == physics.HELD:
            limit = (1.0 - params["mu_wall"] * params["mu_floor"]) / (2.0 * params["mu_floor"])
            return (
                f"Friction holds the ladder: tan θ₀ = {math.tan(math.radians(params['angle0_deg'])):.3f} ≥ "
                f"(1 − μ_w μ_f)/(2 μ_f) = {limit:.3f}, so it stays. The forces shown share the friction limit "
                f"equally between the two ends (statics alone cannot split them)."
            )
        if forces[physics.C_FLOOR_N] < 0.0:
            return (
                "The floor would have to pull the bottom end down: the model's contact assumption fails here "
                "(it would lift off)."
            )
        words = {
            physics.WALL_AND_FLOOR: "Both ends slide: the wall force falls as the ladder speeds up.",
            physics.FLOOR_SLIDING: (
                "The wall force reached zero: the top end has left the wall and the ladder slides on the floor alone."
            ),
            physics.FLOOR_STUCK: (
                "The bottom end has stopped sliding: friction holds it, and the ladder pivots about it."
            ),
            physics.LYING: "The ladder has landed flat (a plastic impact, e = 0) and "
            + (
                "slides on the floor until friction stops it."
                if params["mu_floor"] > 0.0
                else "slides on at constant speed: the floor is smooth, so nothing stops it."
            ),
        }
        return words[phase]
