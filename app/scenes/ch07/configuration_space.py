"""Scene: scleronomic, rheonomic and nonholonomic constraints, the system beside its configuration space.

Left: the physical system. Right: its configuration space, with the moving
configuration point, the constraint and the displacements it admits.

* ``scleronomic`` — a bead on a fixed elliptic wire, drawn in the world xz plane
  (seen from −y). Configuration space (x, y): the ellipse g = 0, the gradient ∇g
  (grey), the virtual displacement δr (green) and the actual dr = ṙ Δt (orange),
  both along the curve.
* ``rheonomic`` — a bead on a hoop whose centre slides along x. In configuration
  space the curve itself moves; the faint curve is where it will be Δt later.
  δr (green) is tangent to the curve frozen at t, dr (orange) reaches the later curve.
* ``nonholonomic`` — a knife edge on the ground (the world xy plane) parks
  sideways: drive, turn, reverse, turn back, three times over, then starts again.
  Configuration space (x, y, ψ) with ψ − ψ₀ up (:data:`HEADING_HEIGHT_PER_RAD`): the
  path, the point, the admissible-velocity plane as a small square, the fields
  drive (blue) and turn (purple), and their bracket (red), which leaves the square.

Every frame evaluates closed forms (no integration): a handful of numpy operations.
"""

from __future__ import annotations

import math
from typing import cast

import numpy as np
import viser

from app.physics.core.parameters import Parameter
from app.physics.systems.ch07 import configuration_space as physics
from app.scenes.kit import Preset, Quantity, Readout, Scene, arrow_segments, move_node, update_node
from app.scenes.kit.planar import polyline_segments, to_world

CONSTRAINTS = ("scleronomic", "rheonomic", "nonholonomic")
WIRE_COLOR = (90, 100, 170)
CURVE_COLOR = (60, 60, 70)
GHOST_COLOR = (190, 190, 200)
BEAD_COLOR = (235, 120, 20)
GRADIENT_COLOR = (130, 130, 130)
VIRTUAL_COLOR = (30, 160, 60)
ACTUAL_COLOR = (235, 120, 20)
DRIVE_COLOR, TURN_COLOR, BRACKET_COLOR = (40, 100, 220), (150, 60, 190), (210, 40, 40)
#: dr is drawn as ṙ Δt with this Δt (s); δr is drawn as long as dr, for comparing directions.
ARROW_TIME_S = 0.4
#: The manoeuvre's legs each take this long (s); it runs this many times, then starts again.
LEG_TIME_S = 1.5
MANOEUVRES = 3
#: ψ − ψ₀ is drawn upward at this many path spans per radian in the knife edge's configuration space.
HEADING_HEIGHT_PER_RAD = 0.6
#: Each side is drawn about this many display units wide, its centre this far left or right of the origin.
SIDE_SIZE, SIDE_OFFSET = 2.0, 1.25
#: The knife edge starts heading along +y (away from the viewer), so it parks to the right (+x).
START_HEADING_RAD = 0.5 * math.pi
LEG_NAMES = ("drive forward", "turn", "reverse", "turn back")
CURVE_SAMPLES = 96


def _check_controls(values) -> None:
    physics.FixedEllipse(values["semi_axis_a_m"], values["semi_axis_b_m"], values["bead_rate_rad_s"])
    physics.SlidingHoop(
        values["hoop_radius_m"], values["hoop_amplitude_m"], values["hoop_rate_rad_s"], values["bead_rate_rad_s"]
    )
    physics.ParallelParking(values["drive_distance_m"], math.radians(values["turn_angle_deg"]))


class ConfigurationSpaceScene(Scene):
    id = "configuration-space-constraints"
    title = "Constraints in configuration space: fixed, moving and nonholonomic"
    chapter = 7
    animated = True
    camera_position = (0.0, -1.55, 1.9)
    camera_look_at = (0.0, 0.2, 0.05)
    #: Holonomic: bead, hoop, point, curve, later curve, arrows (6); knife edge: blade (2), point, square, arrows (5).
    frame_message_budget = 7.0
    controls = (
        Parameter(
            "constraint",
            "",
            "scleronomic",
            description="Which constraint: a fixed wire, a moving hoop, or a knife edge that cannot slip sideways",
            label="constraint",
            kind="choice",
            choices=CONSTRAINTS,
        ),
        Parameter(
            "semi_axis_a_m",
            "m",
            1.5,
            0.2,
            3.0,
            "Semi-axis a of the fixed ellipse, along x (scleronomic)",
            "a",
            step=0.05,
        ),
        Parameter(
            "semi_axis_b_m",
            "m",
            1.0,
            0.2,
            3.0,
            "Semi-axis b of the fixed ellipse, along y (scleronomic)",
            "b",
            step=0.05,
        ),
        Parameter(
            "bead_rate_rad_s",
            "rad/s",
            0.6,
            -3.0,
            3.0,
            "Rate ω of the bead's angle φ on the ellipse or round the hoop's centre",
            "ω",
            step=0.05,
        ),
        Parameter("hoop_radius_m", "m", 1.0, 0.2, 3.0, "Radius R of the moving hoop (rheonomic)", "R", step=0.05),
        Parameter(
            "hoop_amplitude_m",
            "m",
            0.8,
            0.0,
            2.0,
            "Amplitude A of the hoop centre's motion x_c = A sin Ωt (rheonomic)",
            "A",
            step=0.05,
        ),
        Parameter(
            "hoop_rate_rad_s",
            "rad/s",
            1.5,
            0.0,
            5.0,
            "Circular frequency Ω of the hoop centre's motion (rheonomic)",
            "Ω",
            step=0.05,
        ),
        Parameter(
            "drive_distance_m",
            "m",
            0.8,
            0.05,
            2.0,
            "Distance s driven forward and then back in each manoeuvre (nonholonomic)",
            "s",
            step=0.05,
        ),
        Parameter(
            "turn_angle_deg",
            "deg",
            30.0,
            1.0,
            90.0,
            "Angle α turned on the spot, and back, in each manoeuvre (nonholonomic)",
            "α",
            step=1,
        ),
    )
    check_controls = _check_controls
    presets = (
        Preset(
            "fixed-wire",
            "Fixed wire",
            {"constraint": "scleronomic"},
            "A bead on a fixed ellipse: dr and δr both lie along the wire, ∇g·dr = ∇g·δr = 0.",
        ),
        Preset(
            "moving-hoop",
            "Moving hoop",
            {"constraint": "rheonomic", "hoop_amplitude_m": 0.8, "hoop_rate_rad_s": 1.5, "bead_rate_rad_s": 0.6},
            "The hoop slides to and fro: δr stays tangent to the hoop as it is now, dr does not.",
        ),
        Preset(
            "parked-hoop",
            "Hoop at rest (A = 0)",
            {"constraint": "rheonomic", "hoop_amplitude_m": 0.0},
            "With the hoop held still the constraint is scleronomic again, and dr falls back along δr.",
        ),
        Preset(
            "parallel-park",
            "Parallel parking",
            {"constraint": "nonholonomic", "drive_distance_m": 0.8, "turn_angle_deg": 30.0},
            "s = 0.8 m, α = 30°: each manoeuvre moves the knife edge s sin α = 0.4 m sideways, which no "
            "admissible velocity does directly.",
        ),
        Preset(
            "small-manoeuvre",
            "Small manoeuvre",
            {"constraint": "nonholonomic", "drive_distance_m": 0.2, "turn_angle_deg": 10.0},
            "s = 0.2 m, α = 10°: the sideways step 0.03473 m is s α = 0.03491 m to leading order: second order "
            "in the size of the manoeuvre.",
        ),
    )

    def build(self) -> None:
        self._nodes: list = []
        self.t_s = 0.0

    def _add(self, handle):
        """A node under one of the two sides (removed with its side when the controls change)."""
        return handle

    def _add_sides(self, scale: float) -> None:
        """The two sides' frames, ``scale`` display units per metre, so that one camera suits every case."""
        scene = self.client.scene
        self._nodes = [
            scene.add_frame(f"/{side}", show_axes=False, position=(sign * SIDE_OFFSET, 0.0, 0.0), scale=scale)
            for side, sign in (("physical", -1.0), ("config", 1.0))
        ]
        self._left, self._right = np.zeros(3), np.zeros(3)

    def update(self) -> None:
        for handle in self._nodes:
            handle.remove()
        self._nodes = []
        self.t_s = 0.0
        kind = self.params["constraint"]
        if kind == "nonholonomic":
            self._build_knife_edge()
        else:
            self._build_bead(kind)
        self._draw()

    # --- the bead on a fixed or moving curve ----------------------------------------------------------------

    def _build_bead(self, kind: str) -> None:
        p, scene = self.params, self.client.scene
        if kind == "scleronomic":
            self._system: physics.FixedEllipse | physics.SlidingHoop = physics.FixedEllipse(
                p["semi_axis_a_m"], p["semi_axis_b_m"], p["bead_rate_rad_s"]
            )
            half_width, half_height = p["semi_axis_a_m"], p["semi_axis_b_m"]
        else:
            self._system = physics.SlidingHoop(
                p["hoop_radius_m"], p["hoop_amplitude_m"], p["hoop_rate_rad_s"], p["bead_rate_rad_s"]
            )
            half_width, half_height = p["hoop_radius_m"] + p["hoop_amplitude_m"], p["hoop_radius_m"]
        self._span = span = 2.0 * max(half_width, half_height)
        self._add_sides(SIDE_SIZE / (1.3 * span))
        left, right = self._left, self._right
        angles = np.linspace(0.0, 2.0 * math.pi, CURVE_SAMPLES + 1)
        if isinstance(self._system, physics.FixedEllipse):
            shape = self._system.curve(angles)
        else:
            shape = self._system.radius_m * np.stack(
                [np.cos(angles), np.sin(angles)], axis=-1
            )  # about the hoop's own centre
            amplitude = self._system.amplitude_m
            rail = np.array([[[-amplitude - 0.1 * span, 0.0], [amplitude + 0.1 * span, 0.0]]])
            self._add(
                scene.add_line_segments(
                    "/physical/rail",
                    (to_world(rail) + left).astype(np.float32),
                    (150, 150, 150),
                    thickness=0.004 * span,
                )
            )
        # Physical side: the wire (a frame that the hoop's motion carries), its centre block, the bead.
        self.wire_frame = self._add(scene.add_frame("/physical/wire", show_axes=False, position=left))
        scene.add_line_segments("/physical/wire/curve", polyline_segments(shape), WIRE_COLOR, thickness=0.012 * span)
        if isinstance(self._system, physics.SlidingHoop):
            scene.add_box(
                "/physical/wire/centre", color=(150, 150, 160), dimensions=(0.06 * span, 0.03 * span, 0.03 * span)
            )
        self.bead = self._add(scene.add_icosphere("/physical/bead", radius=0.03 * span, color=BEAD_COLOR))
        # Configuration space: axes, the curve g = 0 (moving for the hoop), the curve Δt later, the point and the
        # arrows.
        axes = np.array(
            [
                [[-half_width - 0.15 * span, 0.0], [half_width + 0.15 * span, 0.0]],
                [[0.0, -half_height - 0.15 * span], [0.0, half_height + 0.15 * span]],
            ]
        )
        self._add(
            scene.add_line_segments(
                "/config/axes", (to_world(axes) + right).astype(np.float32), (170, 170, 170), thickness=0.003 * span
            )
        )
        self._add(
            scene.add_label(
                "/config/x",
                "x",
                position=tuple(right + to_world(np.array([half_width + 0.17 * span, 0.0]))),
                anchor="center-left",
            )
        )
        self._add(
            scene.add_label(
                "/config/y",
                "y",
                position=tuple(right + to_world(np.array([0.0, half_height + 0.17 * span]))),
                anchor="bottom-center",
            )
        )
        self.curve_frame = self._add(scene.add_frame("/config/curve", show_axes=False, position=right))
        scene.add_line_segments("/config/curve/line", polyline_segments(shape), CURVE_COLOR, thickness=0.004 * span)
        self.later_frame: viser.FrameHandle | None = None
        if isinstance(self._system, physics.SlidingHoop):
            self.later_frame = self._add(scene.add_frame("/config/later", show_axes=False, position=right))
            scene.add_line_segments("/config/later/line", polyline_segments(shape), GHOST_COLOR, thickness=0.003 * span)
        self.point = self._add(scene.add_icosphere("/config/point", radius=0.018 * span, color=(20, 20, 20)))
        colors = np.array([GRADIENT_COLOR, VIRTUAL_COLOR, ACTUAL_COLOR], np.uint8)
        self.arrows = self._add(
            scene.add_arrows(
                "/config/arrows",
                np.zeros((3, 2, 3), np.float32),
                colors,
                shaft_radius=0.005 * span,
                head_radius=0.014 * span,
                head_length=0.03 * span,
            )
        )
        top = half_height + 0.3 * span
        self._add(
            scene.add_label(
                "/physical/title",
                "the bead on its wire" if kind == "scleronomic" else "the bead on the sliding hoop",
                position=tuple(left + to_world(np.array([0.0, top]))),
                anchor="bottom-center",
            )
        )
        self._add(
            scene.add_label(
                "/config/title",
                "configuration space (x, y)",
                position=tuple(right + to_world(np.array([0.0, top]))),
                anchor="bottom-center",
            )
        )

    def _snapshot(self) -> physics.HolonomicSnapshot:
        return self._system.snapshot(self.t_s)

    def _draw_bead(self) -> None:
        snap = self._snapshot()
        self._snap = snap
        if isinstance(self._system, physics.SlidingHoop):
            centre = self._system.centre(self.t_s)
            move_node(self.wire_frame, position=self._left + to_world(centre))
            move_node(self.curve_frame, position=self._right + to_world(centre))
            later = cast(viser.FrameHandle, self.later_frame)  # a sliding hoop's sides have one
            move_node(later, position=self._right + to_world(self._system.centre(self.t_s + ARROW_TIME_S)))
        move_node(self.bead, position=self._left + to_world(snap.position))
        point = self._right + to_world(snap.position)
        move_node(self.point, position=point)
        step = snap.velocity * ARROW_TIME_S
        length = float(np.linalg.norm(step)) or 0.2 * self._span
        gradient = 0.25 * self._span * snap.gradient / max(float(np.linalg.norm(snap.gradient)), 1e-300)
        vectors = to_world(np.array([gradient, length * snap.virtual_displacement, step]))
        update_node(self.arrows, points=arrow_segments(np.repeat(point[None], 3, axis=0), vectors, 1.0))

    # --- the knife edge -------------------------------------------------------------------------------------

    def _build_knife_edge(self) -> None:
        p, scene = self.params, self.client.scene
        self._park = park = physics.ParallelParking(p["drive_distance_m"], math.radians(p["turn_angle_deg"]))
        starts = [np.array([0.0, 0.0, START_HEADING_RAD])]
        for _ in range(MANOEUVRES):
            starts.append(starts[-1] + park.net_displacement(float(starts[-1][2])))
        self._starts = starts
        path = np.array(
            [park.configuration(start, progress)[0] for start in starts[:-1] for progress in np.linspace(0.0, 4.0, 41)]
        )
        low, high = path[:, :2].min(axis=0), path[:, :2].max(axis=0)
        self._centre = centre = 0.5 * (low + high)
        self._span = span = max(float(max(high - low)), 0.5)
        self._add_sides(SIDE_SIZE / (1.4 * span))
        self._heading_scale = HEADING_HEIGHT_PER_RAD * span
        ground = np.array([[*(low - 0.2 * span - centre), 0.0], [*(high + 0.2 * span - centre), 0.0]])
        corners = np.array(
            [
                [ground[0, 0], ground[0, 1], 0.0],
                [ground[1, 0], ground[0, 1], 0.0],
                [ground[1, 0], ground[1, 1], 0.0],
                [ground[0, 0], ground[1, 1], 0.0],
            ]
        )
        outline = np.stack([corners, np.roll(corners, -1, axis=0)], axis=1)
        self._add(
            scene.add_line_segments(
                "/physical/ground", (outline + self._left).astype(np.float32), (170, 170, 170), thickness=0.004 * span
            )
        )
        trail = np.concatenate([path[:, :2] - centre, np.zeros((len(path), 1))], axis=1) + self._left
        self._add(
            scene.add_line_segments(
                "/physical/trail",
                np.stack([trail[:-1], trail[1:]], axis=1).astype(np.float32),
                (200, 160, 120),
                thickness=0.004 * span,
            )
        )
        blade = 0.25 * p["drive_distance_m"] + 0.1 * span
        self.blade = self._add(
            scene.add_box("/physical/blade", color=(60, 60, 70), dimensions=(blade, 0.02 * span, 0.08 * span))
        )
        in_space = self._config_points(path)
        self._add(
            scene.add_line_segments(
                "/config/path",
                np.stack([in_space[:-1], in_space[1:]], axis=1).astype(np.float32),
                CURVE_COLOR,
                thickness=0.004 * span,
            )
        )
        base = corners + self._right
        self._add(
            scene.add_line_segments(
                "/config/floor",
                np.stack([base, np.roll(base, -1, axis=0)], axis=1).astype(np.float32),
                (190, 190, 190),
                thickness=0.003 * span,
            )
        )
        top = self._right + np.array([ground[0, 0], ground[0, 1], 0.0])
        self._add(
            scene.add_line_segments(
                "/config/psi_axis",
                np.array(
                    [[top, top + np.array([0.0, 0.0, 1.2 * self._heading_scale * park.turn_angle_rad])]], np.float32
                ),
                (170, 170, 170),
                thickness=0.003 * span,
            )
        )
        self.point = self._add(scene.add_icosphere("/config/point", radius=0.02 * span, color=(20, 20, 20)))
        self._square_size = 0.18 * span
        self.square = self._add(
            scene.add_mesh_simple(
                "/config/square",
                np.zeros((4, 3), np.float32),
                np.array([[0, 1, 2], [0, 2, 3]], np.uint32),
                color=(120, 170, 230),
                opacity=0.45,
                side="double",
            )
        )
        colors = np.array([DRIVE_COLOR, TURN_COLOR, BRACKET_COLOR], np.uint8)
        self.arrows = self._add(
            scene.add_arrows(
                "/config/arrows",
                np.zeros((3, 2, 3), np.float32),
                colors,
                shaft_radius=0.005 * span,
                head_radius=0.014 * span,
                head_length=0.03 * span,
            )
        )
        self._add(
            scene.add_label(
                "/physical/title",
                "the knife edge on the ground",
                position=tuple(self._left + np.array([0.0, float(ground[1, 1]), 0.0])),
                anchor="bottom-center",
            )
        )
        self._add(
            scene.add_label(
                "/config/title",
                "configuration space (x, y, ψ − 90° up)",
                position=tuple(top + np.array([0.0, 0.0, 1.25 * self._heading_scale * park.turn_angle_rad])),
                anchor="bottom-left",
            )
        )

    def _config_points(self, q: np.ndarray) -> np.ndarray:
        """World points (…, 3) of configurations q (…, 3): x, y about the path's centre, ψ upward."""
        q = np.asarray(q, dtype=float)
        return (
            np.concatenate(
                [q[..., :2] - self._centre, self._heading_scale * (q[..., 2:3] - START_HEADING_RAD)], axis=-1
            )
            + self._right
        )

    def _knife_state(self) -> tuple[int, float, np.ndarray, np.ndarray]:
        """(manoeuvre, legs into it, q, q̇ in real time (per s)) now."""
        progress = (self.t_s / LEG_TIME_S) % (4.0 * MANOEUVRES)
        manoeuvre = min(int(progress // 4.0), MANOEUVRES - 1)
        within = progress - 4.0 * manoeuvre
        q, velocity = self._park.configuration(self._starts[manoeuvre], within)
        return manoeuvre, within, q, velocity / LEG_TIME_S

    def _draw_knife_edge(self) -> None:
        _, _, q, _ = self._knife_state()
        self._q = q
        heading = float(q[2])
        move_node(
            self.blade,
            position=self._left + np.array([*(q[:2] - self._centre), 0.04 * self._span]),
            wxyz=(math.cos(0.5 * heading), 0.0, 0.0, math.sin(0.5 * heading)),
        )
        point = self._config_points(q)
        move_node(self.point, position=point)
        half = 0.5 * self._square_size
        drive = physics.drive_field(q) * np.array([1.0, 1.0, self._heading_scale])
        turn = physics.turn_field(q) * np.array([1.0, 1.0, self._heading_scale])
        corners = point + half * np.array([-drive - turn, drive - turn, drive + turn, -drive + turn])
        update_node(self.square, vertices=corners)
        bracket = physics.drive_turn_bracket(q)
        vectors = self._square_size * np.array([drive, turn, bracket])
        update_node(self.arrows, points=arrow_segments(np.repeat(point[None], 3, axis=0), vectors, 1.0))

    # --- frames and readout ---------------------------------------------------------------------------------

    def _draw(self) -> None:
        if self.params["constraint"] == "nonholonomic":
            self._draw_knife_edge()
        else:
            self._draw_bead()

    def readout(self) -> Readout:
        if self.params["constraint"] == "nonholonomic":
            return self._knife_readout()
        snap = self._snap
        quantities = [
            Quantity("t_s", "time t", self.t_s, "s"),
            Quantity("bead_x_m", "bead x", float(snap.position[0]), "m"),
            Quantity("bead_y_m", "bead y", float(snap.position[1]), "m"),
            Quantity("bead_speed_m_s", "bead speed |ṙ|", float(np.linalg.norm(snap.velocity)), "m/s"),
            Quantity("constraint_value", "constraint g at the bead", snap.constraint_value, ""),
            Quantity("virtual_variation", "∇g·δr (unit δr, t frozen)", snap.virtual_variation, ""),
            Quantity("gradient_along_velocity_1_s", "∇g·ṙ", snap.gradient_along_velocity, "1/s"),
            Quantity("constraint_time_rate_1_s", "∂g/∂t", snap.time_rate, "1/s"),
            Quantity("actual_variation_1_s", "∇g·ṙ + ∂g/∂t", snap.actual_variation, "1/s"),
            Quantity("angle_dr_virtual_deg", "angle between dr and δr", snap.angle_between_deg, "deg"),
        ]
        if isinstance(self._system, physics.FixedEllipse):
            message = (
                "The wire does not move: g has no ∂g/∂t, so the actual dr obeys the same condition ∇g·dr = "
                "0 as every δr, and lies along it."
            )
        else:
            message = (
                "The hoop moves: δr (time frozen) is tangent to the hoop as it is now, but dr = ṙ dt also "
                "carries the hoop's "
                "own motion, so ∇g·dr = −∂g/∂t dt and the two arrows part."
            )
        return Readout(quantities, message=message)

    def _knife_readout(self) -> Readout:
        manoeuvre, within, q, velocity = self._knife_state()
        park = self._park
        sideways_so_far = float((q[:2] - self._starts[0][:2]) @ physics.drive_turn_bracket(self._starts[0])[:2])
        quantities = [
            Quantity("t_s", "time t", self.t_s, "s"),
            Quantity.word(
                "manoeuvre_leg",
                "leg of the manoeuvre",
                f"{LEG_NAMES[min(int(within), 3)]} (manoeuvre {manoeuvre + 1} of {MANOEUVRES})",
            ),
            Quantity("knife_x_m", "x", float(q[0]), "m"),
            Quantity("knife_y_m", "y", float(q[1]), "m"),
            Quantity("heading_deg", "heading ψ", math.degrees(float(q[2])), "deg"),
            Quantity(
                "slip_rate_m_s",
                "sideways slip ẋ sin ψ − ẏ cos ψ",
                float(physics.knife_edge_covector(q) @ velocity),
                "m/s",
            ),
            Quantity(
                "bracket_out_of_plane",
                "a·[drive, turn] (0 would mean integrable)",
                physics.bracket_leaves_the_plane(q),
                "",
            ),
            Quantity("sideways_drift_m", "sideways step per manoeuvre, s sin α", park.sideways_drift_m, "m"),
            Quantity("sideways_drift_leading_m", "leading order s α", park.drive_distance_m * park.turn_angle_rad, "m"),
            Quantity("forward_drift_m", "forward step per manoeuvre, s (1 − cos α)", park.forward_drift_m, "m"),
            Quantity("sideways_so_far_m", "sideways from the start so far", sideways_so_far, "m"),
        ]
        message = (
            "Every velocity the knife edge can have lies in the square spanned by drive and turn, so it never "
            "slips sideways; "
            "yet drive, turn, reverse, turn back ends s sin α to the side, along the bracket [drive, turn], "
            "which leaves the square."
        )
        return Readout(quantities, message=message)
