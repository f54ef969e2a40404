"""Scene: one vector's rate seen from the fixed frame and from a turning frame, drawn at its tip.

World frame +Z up, lengths in m. The turning frame xyz (axes and a translucent disc in its xy
plane) turns at Ω about the grey axis ω through the origin. The vector A (black, from the origin)
moves in that frame; the faint blue curve is its tip's path *in the frame* (it turns with the frame),
the grey curve its path in XYZ. At A's tip three arrows share one scale (in the readout): blue
(dA/dt)_rel, then orange ω × A from its head, and dark red (dA/dt)_fixed from the tip, which ends
where the orange arrow ends. The motion replays from t = 0 every ``replay_s``.
"""

from __future__ import annotations

import numpy as np

from app.physics.systems.ch03 import vector_derivative as physics
from app.scenes.ch03.labelled_axes import add_labelled_axes, components_text
from app.scenes.ch03.moving_frame import _nice_scale
from app.scenes.ch03.replayed import DISPLAY_PARAMETERS, ReplayedScene
from app.scenes.kit import Preset, Quantity, Readout, circle_segments, move_node
from app.scenes.kit.arrows import LabelledArrows

COLORS = {
    "vector": (25, 25, 25),
    "relative": (30, 110, 220),
    "transport": (240, 140, 20),
    "fixed": (190, 30, 40),
    "omega": (120, 120, 120),
}
LABELS = {"vector": "A", "relative": "(dA/dt)_rel", "transport": "ω × A", "fixed": "(dA/dt)_fixed", "omega": "ω"}
FIXED_AXIS_LENGTH = 1.6
FRAME_AXIS_LENGTH = 0.9
OMEGA_ARROW_M_PER_RAD_S = 0.6
PATH_SAMPLES = 400
#: The rate arrows are drawn at most about this long (m per m of L₀) over most of the replay.
RATE_REACH = 1.2


class VectorDerivativeScene(ReplayedScene):
    id = "vector-derivative"
    title = "The derivative of a vector from a fixed and from a turning frame"
    chapter = 3
    model = physics.VectorDerivative
    controls = DISPLAY_PARAMETERS
    camera_position = (1.6, -2.2, 1.5)
    camera_look_at = (0.0, 0.0, 0.3)
    presets = (
        Preset(
            "fixed-in-frame",
            "A fixed in the turning frame",
            {
                "frame_rate_rad_s": 0.8,
                "frame_axis_tilt_deg": 20.0,
                "length_m": 1.0,
                "stretch_amplitude_m": 0.0,
                "relative_turn_rate_rad_s": 0.0,
                "elevation_deg": 30.0,
            },
            "A rides with xyz: (dA/dt)_rel = 0 and dA/dt = ω × A, perpendicular to both ω and A",
        ),
        Preset(
            "stretching-only",
            "Stretching along a line of the frame",
            {
                "frame_rate_rad_s": 0.8,
                "frame_axis_tilt_deg": 0.0,
                "length_m": 1.0,
                "stretch_amplitude_m": 0.5,
                "stretch_frequency_hz": 0.3,
                "relative_turn_rate_rad_s": 0.0,
                "elevation_deg": 0.0,
            },
            "In the frame A only changes length: (dA/dt)_rel lies along A, ω × A across it",
        ),
        Preset(
            "counter-turning",
            "Turning back as fast as the frame turns",
            {
                "frame_rate_rad_s": 0.8,
                "frame_axis_tilt_deg": 0.0,
                "length_m": 1.0,
                "stretch_amplitude_m": 0.0,
                "relative_turn_rate_rad_s": -0.8,
                "elevation_deg": 20.0,
            },
            "ψ̇ = −Ω about the same axis: the two terms cancel and A stands still in XYZ",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        add_labelled_axes(scene, "/fixed", length=FIXED_AXIS_LENGTH, labels="XYZ", axes_radius=0.01, origin_radius=0.03)
        self.frame = add_labelled_axes(
            scene, "/frame", length=FRAME_AXIS_LENGTH, labels="xyz", axes_radius=0.018, origin_radius=0.04
        )
        scene.add_line_segments(
            "/frame/rim",
            circle_segments(radius=FRAME_AXIS_LENGTH, segments=64),
            (150, 170, 200),
            thickness=1.5,
            thickness_units="screen",
        )
        self.frame_path = scene.add_line_segments(
            "/frame/path", np.zeros((1, 2, 3), np.float32), (140, 180, 240), thickness=1.5, thickness_units="screen"
        )
        self.world_path = scene.add_line_segments(
            "/path", np.zeros((1, 2, 3), np.float32), (170, 170, 170), thickness=1.5, thickness_units="screen"
        )
        self.arrows = LabelledArrows(scene, "/vectors", COLORS, LABELS)

    def physical_params(self) -> dict:
        return {k: v for k, v in self.params.items() if k in physics.PARAMETERS.by_name}

    def update(self) -> None:
        params = self.physical_params()
        self.motion = physics.VectorMotion.from_params(params)
        length = params["length_m"]
        self.arrows.set_style(shaft_radius=0.02 * length, head_radius=0.05 * length, head_length=0.1 * length)
        whole = self.motion.rates(np.linspace(0.0, float(self.params["replay_s"]), PATH_SAMPLES))
        biggest = np.max([np.linalg.norm(v, axis=-1) for v in whole.terms_m_s.values()], axis=0)
        typical = max(float(np.percentile(biggest, 90.0)), 1e-9)
        self.arrow_s = _nice_scale(min(RATE_REACH * length / typical, 1e3))  # arrow length (m) per m/s
        for node, path in ((self.frame_path, whole.vector_frame_m), (self.world_path, whole.vector_world_m)):
            points = path.astype(np.float32)
            node.points = np.stack([points[:-1], points[1:]], axis=1)
        self.start_clock()
        self._draw()

    def _draw(self) -> None:
        r = self.motion.rates(np.array([self.t_s]))
        self.now = r
        move_node(self.frame, wxyz=r.attitude_wxyz[0])
        tip = r.vector_world_m[0]
        terms = {name: value[0] for name, value in r.terms_m_s.items()}
        s = self.arrow_s
        origin = np.zeros(3)
        segments = {
            "vector": (origin, tip),
            "relative": (tip, tip + s * terms["relative"]),
            "transport": (tip + s * terms["relative"], tip + s * terms["fixed"]),
            "fixed": (tip, tip + s * terms["fixed"]),
            "omega": (origin, OMEGA_ARROW_M_PER_RAD_S * self.motion.omega_world_rad_s),
        }
        self.arrows.draw(segments, label_at=0.6)  # labels follow every frame: the drawing is a function of t alone

    def readout(self) -> Readout:
        """Vectors are text (components named in the label); magnitudes and the arrow scale are numbers."""
        r = self.now
        omega = self.motion.omega_world_rad_s
        quantities = [
            Quantity("t_s", "t", float(self.t_s), "s"),
            Quantity("omega", "ω (X, Y, Z)", None, "rad/s", components_text(omega), text_in_unit=True),
            Quantity("omega_magnitude", "|ω|", float(np.linalg.norm(omega)), "rad/s"),
            Quantity("A_world", "A (X, Y, Z)", None, "m", components_text(r.vector_world_m[0]), text_in_unit=True),
            Quantity("A_frame", "A (x, y, z)", None, "m", components_text(r.vector_frame_m[0]), text_in_unit=True),
            Quantity("A_magnitude", "|A|", float(np.linalg.norm(r.vector_world_m[0])), "m"),
            Quantity(
                "dA_relative_frame",
                "(dA/dt)_rel on the frame's own axes (x, y, z)",
                None,
                "m/s",
                components_text(r.rate_frame_m_s[0]),
            ),
        ]
        for name in physics.TERM_NAMES:
            vector = r.terms_m_s[name][0]
            quantities.append(
                Quantity(
                    f"dA_{name}",
                    f"{physics.TERM_LABELS[name]} (X, Y, Z)",
                    None,
                    "m/s",
                    components_text(vector),
                    text_in_unit=True,
                )
            )
            quantities.append(
                Quantity(f"dA_{name}_magnitude", f"|{LABELS[name]}|", float(np.linalg.norm(vector)), "m/s")
            )
        quantities.append(Quantity("arrow_scale", "rate arrows", self.arrow_s, "m of arrow per m/s"))
        relative = float(np.linalg.norm(r.terms_m_s["relative"][0]))
        fixed = float(np.linalg.norm(r.terms_m_s["fixed"][0]))
        if relative == 0.0:
            message = "A is fixed in the turning frame: (dA/dt)_rel = 0, so the rate seen from XYZ is ω × A alone."
        elif fixed <= 1e-12 * relative:
            message = (
                "(dA/dt)_rel and ω × A cancel: A turns back in the frame exactly as fast as the frame "
                "turns, so it stands still in XYZ."
            )
        else:
            message = "(dA/dt)_fixed = (dA/dt)_rel + ω × A: the blue and orange arrows add head to tail to the red one."
        return Readout(quantities, message=message + " Arrows shorter than their head are listed here but not drawn.")
