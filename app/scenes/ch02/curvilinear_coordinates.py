"""Scene for section 2.3: a chosen path with the cylindrical or spherical unit vectors riding on the particle.

Drawn in metres on XYZ, +Z up. The triad at the particle is (e_R, e_θ, e_z) or
(e_r, e_φ, e_θ) (the control ``frame``), a fixed fraction of the path's size
long; a unit vector that is undefined (on the Z axis, at the origin) is hidden
and the readout says why. From the particle: v (blue) and its three components
on the triad laid head to tail (light blue), a (red) and its components (light
red). Per frame the particle's position and attitude (one frame node, the
triad rides on it), the batched arrows and two labels move.
"""

from __future__ import annotations

import math

import numpy as np
import viser

from app.physics.core.parameters import Parameter
from app.physics.math.rotations import quaternion_from_matrix
from app.physics.systems.ch02 import coordinate_paths as physics
from app.scenes.ch02.particle_run import PATH_SAMPLES, ParticleRunScene, chain_arrows, display_scale
from app.scenes.ch02.space_curve import TRIAD_COLORS, triad_rotations
from app.scenes.kit import Preset, Quantity, Readout, move_node

ARROW_FRACTION = 0.22  # 90th-percentile v or a arrow / path size
TRIAD_FRACTION = 0.12  # unit-vector arrow / path size
VELOCITY, VELOCITY_PART = (40, 90, 220), (140, 175, 240)
ACCELERATION, ACCELERATION_PART = (215, 50, 50), (240, 160, 150)
TRIAD_LABELS = {"cylindrical": ("e_R", "e_θ", "e_z"), "spherical": ("e_r", "e_φ", "e_θ")}
#: Readout rows per frame: (name, label) of each coordinate, velocity and acceleration component.
ROWS = {
    "cylindrical": {
        "coordinates": (("R", "R", "m"), ("theta", "θ", "rad"), ("z", "z", "m")),
        "rates": (("R_dot", "Ṙ", "m/s"), ("theta_dot", "θ̇", "rad/s"), ("z_dot", "ż", "m/s")),
        "velocity": (("v_R", "v_R = Ṙ"), ("v_theta", "v_θ = R θ̇"), ("v_z", "v_z = ż")),
        "acceleration": (("a_R", "a_R = R̈ − R θ̇²"), ("a_theta", "a_θ = R θ̈ + 2 Ṙ θ̇"), ("a_z", "a_z = z̈")),
    },
    "spherical": {
        "coordinates": (("r", "r", "m"), ("phi", "φ", "rad"), ("theta", "θ", "rad")),
        "rates": (("r_dot", "ṙ", "m/s"), ("phi_dot", "φ̇", "rad/s"), ("theta_dot", "θ̇", "rad/s")),
        "velocity": (("v_r", "v_r = ṙ"), ("v_phi", "v_φ = r φ̇"), ("v_theta", "v_θ = r sin φ θ̇")),
        "acceleration": (
            ("a_r", "a_r = r̈ − r φ̇² − r sin²φ θ̇²"),
            ("a_phi", "a_φ = r φ̈ + 2 ṙ φ̇ − r sin φ cos φ θ̇²"),
            ("a_theta", "a_θ = r sin φ θ̈ + 2 ṙ θ̇ sin φ + 2 r φ̇ θ̇ cos φ"),
        ),
    },
}
#: What β means on each path, for the readout.
PATH_ANGLE_MEANING = {
    "helix": "the climb angle",
    "conical-spiral": "the cone's half-angle (so φ = β)",
    "latitude-circle": "the polar angle φ of the circle",
    "loxodrome": "the bearing from north at which it crosses every meridian",
}

CONTROLS = (
    Parameter(
        "frame",
        "",
        "cylindrical",
        kind="choice",
        choices=physics.FRAMES,
        label="unit vectors",
        description="The unit vectors riding on the particle: cylindrical (e_R, e_θ, e_z) or spherical (e_r, e_φ, e_θ)",
    ),
)


class CurvilinearCoordinatesScene(ParticleRunScene):
    id = "curvilinear-coordinates"
    title = "Cylindrical and spherical coordinates on a chosen path"
    chapter = 2
    model = physics.ParticleOnCoordinatePath
    controls = CONTROLS
    arrow_colors = (VELOCITY, *(VELOCITY_PART,) * 3, ACCELERATION, *(ACCELERATION_PART,) * 3)
    labelled_arrows = ((0, "v", 1.0), (4, "a", 1.0))
    presets = (
        Preset(
            "helix",
            "Helix",
            {"path": "helix", "size_m": 1.0, "azimuth_rate_rad_s": 1.0, "path_angle_deg": 15.0, "frame": "cylindrical"},
            "R = 1 m and θ̇ = 1 rad/s constant: v_R = 0, a_R = −R θ̇² = −1 m/s², a_θ = a_z = 0",
        ),
        Preset(
            "conical-spiral",
            "Spiral on a cone",
            {
                "path": "conical-spiral",
                "size_m": 0.1 * math.pi,
                "azimuth_rate_rad_s": 2.0,
                "path_angle_deg": 40.0,
                "frame": "cylindrical",
            },
            "a = 0.1π m = 0.314 m, so Ṙ = a θ̇/2π = 0.1 m/s with θ̇ = 2 rad/s: the Coriolis-like term 2 Ṙ θ̇ = "
            "0.4 m/s² is all of a_θ",
        ),
        Preset(
            "latitude-circle",
            "Circle of latitude",
            {
                "path": "latitude-circle",
                "size_m": 1.0,
                "azimuth_rate_rad_s": 1.0,
                "path_angle_deg": 50.0,
                "frame": "spherical",
            },
            "r and φ fixed: a_r = −r sin²φ θ̇² and a_φ = −r sin φ cos φ θ̇², and together they point at the "
            "circle's centre",
        ),
        Preset(
            "loxodrome",
            "Loxodrome",
            {
                "path": "loxodrome",
                "size_m": 1.0,
                "azimuth_rate_rad_s": 1.0,
                "path_angle_deg": 75.0,
                "frame": "spherical",
            },
            "Crosses every meridian at 75° from north: v_φ / v_θ = −cot 75° throughout, while the speed falls "
            "toward the poles",
        ),
        Preset(
            "on-the-pole",
            "On the pole (φ = 0)",
            {"path": "latitude-circle", "size_m": 1.0, "path_angle_deg": 0.0, "frame": "spherical"},
            "A circle of zero radius: the particle sits on the Z axis, where θ, e_φ and e_θ have no value",
        ),
    )

    def build(self) -> None:
        super().build()
        self._triad_nodes: list = []
        self._triad_shown: tuple[bool, ...] = ()

    def run_s(self) -> float:
        return self.path.run_s

    def prepare(self) -> None:
        self.path = physics.CoordinatePath.from_params(self.params)
        position, velocity, acceleration = self.path.at(np.linspace(0.0, self.path.run_s, PATH_SAMPLES + 1))
        self._path_points = position
        size = max(float(np.linalg.norm(position.max(axis=0) - position.min(axis=0))), 0.5)
        self._v_scale = display_scale(np.linalg.norm(velocity, axis=1), target_m=ARROW_FRACTION * size)
        self._a_scale = display_scale(np.linalg.norm(acceleration, axis=1), target_m=ARROW_FRACTION * size)

    def path_points(self) -> np.ndarray:
        return self._path_points

    def _draw_static(self, points: np.ndarray, *, ground_z: float) -> None:
        super()._draw_static(points, ground_z=ground_z)
        scene = self.client.scene
        for node in reversed(self._triad_nodes):  # each label before its arrow
            node.remove()
        size = self.drawing_size_m
        length, shaft = TRIAD_FRACTION * size, 0.008 * size
        nodes: list[viser.SceneNodeHandle] = []
        for k, text in enumerate(TRIAD_LABELS[self.params["frame"]]):
            tip = length * np.eye(3)[k]
            nodes.append(
                scene.add_arrows(
                    f"/particle/e{k}",
                    np.array([[np.zeros(3), tip]], np.float32),
                    TRIAD_COLORS[k],
                    shaft_radius=shaft,
                    head_radius=2.5 * shaft,
                    head_length=5.0 * shaft,
                )
            )
            nodes.append(
                scene.add_label(
                    f"/particle/e{k}/label",
                    text,
                    position=tuple(1.1 * tip),
                    anchor="center-left",
                    font_screen_scale=0.9,
                )
            )
        self._triad_nodes = nodes
        self._triad_shown = (True, True, True)

    def arrows_at(self, t_s: float) -> tuple[np.ndarray, np.ndarray]:
        position, velocity, acceleration, described = self.path.describe(self.params["frame"], t_s)
        self._described = (position[0], velocity[0], acceleration[0], described)
        triad = np.nan_to_num(described.unit_vectors[0])  # an undefined unit vector carries no drawn component
        v_parts = np.nan_to_num(described.velocity[0])[:, None] * triad
        a_parts = np.nan_to_num(described.acceleration[0])[:, None] * triad
        p = position[0]
        arrows = np.concatenate(
            [
                chain_arrows(p, velocity[0], v_parts, self._v_scale),
                chain_arrows(p, acceleration[0], a_parts, self._a_scale),
            ]
        )
        return p, arrows

    def after_draw(self, t_s: float) -> None:
        rotation, defined = triad_rotations(self._described[3].unit_vectors[:1])
        move_node(self.particle, wxyz=quaternion_from_matrix(rotation[0]))
        shown = tuple(bool(d) for d in defined[0])
        if shown != self._triad_shown:
            for k, visible in enumerate(shown):
                self._triad_nodes[2 * k].visible = visible
                self._triad_nodes[2 * k + 1].visible = visible
            self._triad_shown = shown

    def readout(self) -> Readout:
        frame = self.params["frame"]
        p, v, a, described = self._described
        rows = ROWS[frame]
        why = self._singular_reason(described)
        undefined = "no value here (see the message below)"
        quantities = [Quantity("t_s", "time t", self.t_s, "s")]
        for key, source in (("coordinates", described.coordinates), ("rates", described.rates)):
            quantities += [
                Quantity.or_text(name, label, float(source[0, k]), unit, undefined)
                for k, (name, label, unit) in enumerate(rows[key])
            ]
        quantities += [
            Quantity.or_text(name, label, float(described.velocity[0, k]), "m/s", undefined)
            for k, (name, label) in enumerate(rows["velocity"])
        ]
        quantities += [
            Quantity.or_text(name, label, float(described.acceleration[0, k]), "m/s²", undefined)
            for k, (name, label) in enumerate(rows["acceleration"])
        ]
        quantities += [
            Quantity.or_text(
                "speed_from_components",
                "|v| from these components",
                float(np.linalg.norm(described.velocity[0])),
                "m/s",
                undefined,
            ),
            Quantity("speed", "|v| = √(ẋ² + ẏ² + ż²), Cartesian", float(np.linalg.norm(v)), "m/s"),
            Quantity.or_text(
                "acceleration_from_components",
                "|a| from these components",
                float(np.linalg.norm(described.acceleration[0])),
                "m/s²",
                undefined,
            ),
            Quantity("acceleration_magnitude", "|a| = √(ẍ² + ÿ² + z̈²), Cartesian", float(np.linalg.norm(a)), "m/s²"),
            Quantity("run", "one run lasts", self.path.run_s, "s"),
            Quantity("grid_cell", "side of a grid square", self.grid_cell_m, "m"),
        ]
        meaning = f"On the {self.params['path'].replace('-', ' ')}, β is {PATH_ANGLE_MEANING[self.params['path']]}."
        return Readout(quantities, message=" ".join(m for m in (why, meaning) if m))

    def _singular_reason(self, described) -> str:
        undefined = ~np.all(np.isfinite(described.unit_vectors[0]), axis=1)
        if not undefined.any():
            return ""
        if self.params["frame"] == "cylindrical":
            return (
                "The particle is on the Z axis (R = 0): θ, e_R and e_θ have no value there, so neither do the "
                "components that use them; e_z and z do."
            )
        if undefined.all():
            return "The particle is at the origin (r = 0): no spherical direction has a value there."
        return (
            "The particle is on the polar axis (φ = 0 or π, R = 0): θ, e_φ and e_θ have no value there; e_r "
            "still points along ±Z."
        )
