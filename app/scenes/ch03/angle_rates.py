"""Scene: angle rates and angle accelerations of a rotation sequence, turned into ω and α.

Drawn about the fixed point (the origin), world frame +Z up: the fixed axes XYZ (long), the body
(a plate with its axes xyz, red/green/blue), and the three turn axes n1, n2, n3 as lines through the
origin (orange, purple, teal, as in the rotation-sequence scene; turns 1 and 3 red at gimbal lock).
The three contributions θ̇k nk are arrows laid head to tail from the origin; ω (dark grey) is drawn
from the origin and ends where they end. α (pink) has its own scale. Both scales are in the readout.
The angles move with constant θ̈k, replayed from t = 0 every ``replay_s``.
"""

from __future__ import annotations

import math

import numpy as np

from app.physics.systems.ch03 import angle_rates as physics
from app.scenes.ch03.labelled_axes import add_labelled_axes, components_text
from app.scenes.ch03.moving_frame import _nice_scale
from app.scenes.ch03.replayed import DISPLAY_PARAMETERS, ReplayedScene
from app.scenes.ch03.rotation_sequence import LOCK_COLOR, TURN_COLORS
from app.scenes.kit import FRAME_DT_S, Mark, Preset, Quantity, Readout, move_node, update_node
from app.scenes.kit.arrows import LabelledArrows

FIXED_AXIS_LENGTH = 1.3
BODY_AXIS_LENGTH = 0.75
TURN_AXIS_HALF_LENGTH = 1.6
#: ω (and its three parts) and α are drawn at most about this long (display units) over the replay.
ARROW_REACH = 1.2
SCALE_SAMPLES = 200
NEAR_LOCK_DEG = 10.0
ARROW_COLORS = {
    "turn1": TURN_COLORS[0],
    "turn2": TURN_COLORS[1],
    "turn3": TURN_COLORS[2],
    "omega": (60, 60, 60),
    "alpha": (215, 80, 150),
}
ARROW_LABELS = {"turn1": "θ̇1 n1", "turn2": "θ̇2 n2", "turn3": "θ̇3 n3", "omega": "ω", "alpha": "α"}
#: Frames evaluated per vectorised call, so the per-call overhead is shared (docs/bench/live-frame-costs.svg).
BATCH_FRAMES = 30


class AngleRatesScene(ReplayedScene):
    id = "angle-rates"
    title = "Angular velocity and acceleration from angle rates"
    chapter = 3
    model = physics.AngleRates
    controls = DISPLAY_PARAMETERS
    camera_position = (1.55, -2.05, 1.35)
    camera_look_at = (0.0, 0.0, 0.25)
    presets = (
        Preset(
            "steady-top",
            "Top: steady precession and spin (3-1-3)",
            {
                "sequence": "3-1-3",
                "angle1_deg": 0.0,
                "angle2_deg": 30.0,
                "angle3_deg": 0.0,
                "rate1_rad_s": 0.8,
                "rate2_rad_s": 0.0,
                "rate3_rad_s": 2.0,
                "accel1_rad_s2": 0.0,
                "accel2_rad_s2": 0.0,
                "accel3_rad_s2": 0.0,
            },
            "Constant φ̇ = 0.8 rad/s and ψ̇ = 2 rad/s at θ = 30°: every θ̈ is zero, yet α = φ̇ψ̇ n1 × n3 has "
            "magnitude 0.8 rad/s²",
        ),
        Preset(
            "euler-lock",
            "3-1-3 at θ = 0: rates lost",
            {
                "sequence": "3-1-3",
                "angle1_deg": 20.0,
                "angle2_deg": 0.0,
                "angle3_deg": 40.0,
                "rate1_rad_s": 0.5,
                "rate2_rad_s": 0.0,
                "rate3_rad_s": 1.0,
                "accel1_rad_s2": 0.0,
                "accel2_rad_s2": 0.0,
                "accel3_rad_s2": 0.0,
            },
            "Nutation θ = 0: n3 lies on n1, ω = (φ̇ + ψ̇) Z, and only φ̇ + ψ̇ can be read back from ω",
        ),
        Preset(
            "aircraft-pull-up",
            "Aircraft pulling up to the vertical (3-2-1)",
            {
                "sequence": "3-2-1",
                "angle1_deg": 30.0,
                "angle2_deg": 0.0,
                "angle3_deg": 10.0,
                "rate1_rad_s": 0.0,
                "rate2_rad_s": -0.3,
                "rate3_rad_s": 0.0,
                "accel1_rad_s2": 0.0,
                "accel2_rad_s2": 0.0,
                "accel3_rad_s2": 0.0,
            },
            "Level, nose pitching up at θ̇2 = −0.3 rad/s (Z up): at t = 5.24 s the nose points straight up (θ2 = "
            "−90°), where yaw and roll rates cannot be told apart",
        ),
        Preset(
            "spin-up",
            "Spinning up while tilting (3-1-3)",
            {
                "sequence": "3-1-3",
                "angle1_deg": 0.0,
                "angle2_deg": 20.0,
                "angle3_deg": 0.0,
                "rate1_rad_s": 0.3,
                "rate2_rad_s": 0.1,
                "rate3_rad_s": 0.5,
                "accel1_rad_s2": 0.0,
                "accel2_rad_s2": 0.0,
                "accel3_rad_s2": 0.4,
            },
            "θ̈3 = 0.4 rad/s² adds a part of α along n3; the cross products add the rest",
        ),
    )

    # -- building -----------------------------------------------------------------------------------
    def build(self) -> None:
        scene = self.client.scene
        add_labelled_axes(scene, "/fixed", length=FIXED_AXIS_LENGTH, labels="XYZ", axes_radius=0.01, origin_radius=0.03)
        self.body = add_labelled_axes(
            scene, "/body", length=BODY_AXIS_LENGTH, labels="xyz", axes_radius=0.022, origin_radius=0.04
        )
        scene.add_box(
            "/body/plate",
            color=(90, 120, 170),
            dimensions=(0.75, 0.45, 0.05),
            opacity=0.45,
            cast_shadow=False,
            receive_shadow=False,
        )
        self.turn_axes = scene.add_line_segments(
            "/turn_axes",
            np.zeros((3, 2, 3), np.float32),
            np.zeros((3, 2, 3), np.uint8),
            thickness=2.5,
            thickness_units="screen",
        )
        self.arrows = LabelledArrows(scene, "/rates", ARROW_COLORS, ARROW_LABELS)
        self.arrows.set_style(shaft_radius=0.02, head_radius=0.05, head_length=0.1)
        self._locked_drawn: bool | None = None

    # -- parameters → geometry ------------------------------------------------------------------------
    def physical_params(self) -> dict:
        return {k: v for k, v in self.params.items() if k in physics.PARAMETERS.by_name}

    def update(self) -> None:
        self.motion = physics.AngleMotion.from_params(self.physical_params())
        whole = self.motion.kinematics(np.linspace(0.0, float(self.params["replay_s"]), SCALE_SAMPLES))
        parts = np.abs(whole.rates_rad_s).sum(axis=-1)  # the head-to-tail chain is at most this long
        reach = max(float(parts.max()), float(np.linalg.norm(whole.omega_world_rad_s, axis=-1).max()), 1e-9)
        self.omega_scale = _nice_scale(min(ARROW_REACH / reach, 1e3))
        alpha_max = max(float(np.linalg.norm(whole.alpha_world_rad_s2, axis=-1).max()), 1e-9)
        self.alpha_scale = _nice_scale(min(ARROW_REACH / alpha_max, 1e3))
        self._locked_drawn = None
        self._batch: physics.AngleKinematics | None = None
        self._step_s = float(self.params["playback_speed"]) * FRAME_DT_S
        self.start_clock()
        self._draw()

    def advance(self, dt_s: float) -> None:
        self._step_s = float(self.params["playback_speed"]) * dt_s
        super().advance(dt_s)

    def _evaluate_now(self) -> None:
        """Point ``self.kinematics[self.i]`` at ``t_s``: from the batch when it holds that instant, else a new batch."""
        batch = self._batch
        if batch is not None:
            hits = np.flatnonzero(np.abs(batch.t_s - self.t_s) < 1e-9)
            if hits.size:
                self.i: int = int(hits[0])
                return
        times = np.mod(self.t_s + self._step_s * np.arange(BATCH_FRAMES), float(self.params["replay_s"]))
        self._batch = self.kinematics = self.motion.kinematics(times)
        self.i = 0

    def _draw(self) -> None:
        self._evaluate_now()
        k, i = self.kinematics, self.i
        move_node(self.body, wxyz=k.q_world_body[i])
        axes = k.turn_axes_world[i]
        update_node(
            self.turn_axes,
            points=np.stack([-TURN_AXIS_HALF_LENGTH * axes, TURN_AXIS_HALF_LENGTH * axes], axis=1).astype(np.float32),
        )
        locked = k.locked(i)
        if locked != self._locked_drawn:
            colors = [LOCK_COLOR if locked and n != 1 else TURN_COLORS[n] for n in range(3)]
            self.turn_axes.colors = np.repeat(np.array(colors, np.uint8)[:, None, :], 2, axis=1)
            self._locked_drawn = locked
        segments = {}
        tail = np.zeros(3)
        for n in range(3):
            head = tail + self.omega_scale * k.rates_rad_s[i, n] * axes[n]
            segments[f"turn{n + 1}"] = (tail, head)
            tail = head
        origin = np.zeros(3)
        segments["omega"] = (origin, self.omega_scale * k.omega_world_rad_s[i])
        segments["alpha"] = (origin, self.alpha_scale * k.alpha_world_rad_s2[i])
        self.arrows.draw(segments, label_at=0.6)  # labels follow every frame: the drawing is a function of t alone

    # -- numbers beside the scene ---------------------------------------------------------------------
    def readout(self) -> Readout:
        """Vectors are text (components named in the label); magnitudes, scales and distances are numbers."""
        k, i = self.kinematics, self.i
        seq = k.sequence
        recovered, why = k.recovered_rates(i)
        gain = k.rate_gain(i)
        quantities = [
            Quantity("t_s", "t", float(self.t_s), "s"),
            Quantity.word("sequence", "sequence", f"{seq.name} ({seq.kind})"),
            Quantity(
                "angles_deg",
                "θ1, θ2, θ3 now",
                None,
                "deg",
                ", ".join(f"{math.degrees(a):.2f}" for a in k.angles_rad[i]),
            ),
            Quantity(
                "angle_rates",
                "θ̇1, θ̇2, θ̇3 now",
                None,
                "rad/s",
                ", ".join(f"{r:.3f}" for r in k.rates_rad_s[i]),
                text_in_unit=True,
            ),
            Quantity(
                "omega_world", "ω (X, Y, Z)", None, "rad/s", components_text(k.omega_world_rad_s[i]), text_in_unit=True
            ),
            Quantity(
                "omega_body", "ω (x, y, z)", None, "rad/s", components_text(k.omega_body_rad_s[i]), text_in_unit=True
            ),
            Quantity("omega_magnitude", "|ω|", float(np.linalg.norm(k.omega_world_rad_s[i])), "rad/s"),
            Quantity(
                "alpha_world",
                "α (X, Y, Z)",
                None,
                "rad/s²",
                components_text(k.alpha_world_rad_s2[i]),
                text_in_unit=True,
            ),
            Quantity(
                "alpha_body", "α (x, y, z)", None, "rad/s²", components_text(k.alpha_body_rad_s2[i]), text_in_unit=True
            ),
            Quantity("alpha_magnitude", "|α|", float(np.linalg.norm(k.alpha_world_rad_s2[i])), "rad/s²"),
            Quantity(
                "alpha_along_axes",
                "α along the turn axes, Σ θ̈k nk (X, Y, Z)",
                None,
                "rad/s²",
                components_text(k.alpha_along_axes_world_rad_s2[i]),
            ),
            Quantity(
                "alpha_turning_axes",
                "α from turning axes, θ̇1n1×θ̇2n2 + (θ̇1n1+θ̇2n2)×θ̇3n3 (X, Y, Z)",
                None,
                "rad/s²",
                components_text(k.alpha_turning_axes_world_rad_s2[i]),
            ),
            Quantity(
                "recovered_rates",
                "θ̇ solved back from ω",
                None,
                "rad/s",
                ", ".join(f"{r:.3f}" for r in recovered) if recovered is not None else why,
            ),
            Quantity.or_text(
                "rate_gain",
                "largest angle rate per unit |ω|",
                gain,
                "(rad/s)/(rad/s)",
                "unbounded: the rates cannot be recovered here",
            ),
            Quantity(
                "gimbal_lock_distance_deg",
                "distance to gimbal lock",
                math.degrees(float(k.lock_distance_rad[i])),
                "deg",
            ),
            Quantity("omega_arrow_scale", "ω arrows", self.omega_scale, "display units per rad/s"),
            Quantity("alpha_arrow_scale", "α arrow", self.alpha_scale, "display units per rad/s²"),
        ]
        marks = {"angle2_deg": [Mark(math.degrees(a), "gimbal lock") for a in seq.lock_angles_rad]}
        return Readout(quantities, marks=marks, message=self.message())

    def message(self) -> str:
        k, i = self.kinematics, self.i
        seq = k.sequence
        if k.locked(i):
            _, why = k.recovered_rates(i)
            return (
                f"Gimbal lock of {seq.name}: ω and α still follow from the rates (the arrows are right), but {why}. "
                "Any split of that combination between θ̇1 and θ̇3 gives the same ω."
            )
        lock_deg = math.degrees(float(k.lock_distance_rad[i]))
        text = (
            "ω = θ̇1 n1 + θ̇2 n2 + θ̇3 n3: the coloured arrows add head to tail to ω. α adds Σ θ̈k nk and the "
            "cross products of turning axes."
        )
        if lock_deg < NEAR_LOCK_DEG:
            text += (
                f" Near gimbal lock ({lock_deg:.3g}° away): recovering the rates from ω needs up to "
                f"{k.rate_gain(i):.3g} rad/s of rate per rad/s of |ω|."
            )
        return text
