"""Scene: a disk spinning on a turntable's shaft, with v_B = v_A + ω × r_B/A and the three acceleration terms at B.

World frame +Z up, origin at the shaft's bearing O on the turntable's axis (m). Drawn: the
turntable (a platter below O turning about Z), the shaft from O to the disk's centre A, the disk
(spokes show its spin), the point B the student picks (yellow) with r_B/A from A, the disk's ω
(velocity view) or α (acceleration view) as an arrow at A, and at B each term of the chosen
formula tip to tail, closed by the resultant: v_A, ω × r_B/A and v_B; or a_A, α × r_B/A,
ω × (ω × r_B/A) and a_B. The motion (turntable and spin each at constant angular acceleration)
replays from t = 0 every :data:`CYCLE_S` seconds. Every number comes from
:mod:`app.physics.systems.ch04.rigid_body_points`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from app.physics.core.parameters import Parameter
from app.physics.math.rotations import quaternion_conjugate, quaternion_multiply
from app.physics.systems.ch04 import rigid_body_points as physics
from app.scenes.ch04.cycling import CyclingScene
from app.scenes.kit import Preset, Quantity, Readout, move_node, quaternion_z_to
from app.scenes.kit.arrows import LabelledArrows

#: The motion replays from t = 0 after this long (s).
CYCLE_S = 6.0
#: Instants of one cycle sampled to choose arrow scales that hold for the whole cycle (from their median).
SCALE_SAMPLES = 61
VIEWS = ("velocity", "acceleration")
PLATTER_BELOW_O_M = 0.35

VELOCITY_COLORS = {
    "center": (40, 100, 220),
    "relative": (230, 120, 20),
    "total": (200, 30, 60),
    "omega": (140, 60, 200),
}
VELOCITY_LABELS = {"center": "v_A", "relative": "ω × r_B/A", "total": "v_B", "omega": "ω"}
ACCELERATION_COLORS = {
    "center": (40, 100, 220),
    "tangential": (230, 120, 20),
    "centripetal": (30, 160, 80),
    "total": (200, 30, 60),
    "alpha": (140, 60, 200),
}
ACCELERATION_LABELS = {
    "center": "a_A",
    "tangential": "α × r_B/A",
    "centripetal": "ω × (ω × r_B/A)",
    "total": "a_B",
    "alpha": "α",
}

CONTROLS = (
    Parameter(
        "arrows",
        "",
        "velocity",
        kind="choice",
        choices=VIEWS,
        label="arrows",
        description=(
            "Which formula's terms are drawn at B: velocity (v_A, ω × r_B/A, v_B) or acceleration (a_A, "
            "α × r_B/A, ω × (ω × r_B/A), a_B)"
        ),
    ),
)


def _components(vector: np.ndarray) -> str:
    """World components as the readout writes them: 'X +0.123, Y −0.456, Z +0.000'."""
    return ", ".join(f"{axis} {round(float(c), 3) + 0.0:+.3f}".replace("-", "−") for axis, c in zip("XYZ", vector))


def _arrow_scale(longest: float, length_m: float) -> float:
    """Metres of arrow per unit so that ``longest`` draws ``length_m`` long, to two significant figures."""
    return float(f"{length_m / max(longest, 1e-9):.2g}")


class RigidBodyPointsScene(CyclingScene):
    id = "rigid-body-points"
    title = "Points of a rigid body: a disk spinning on a turntable"
    chapter = 4
    model = physics.DiskOnTurntableMotion
    controls = CONTROLS
    cycle_s = CYCLE_S
    #: Turntable and disk attitudes, one arrow batch, and at most five labels moved at 15 Hz.
    frame_message_budget = 6.0
    presets = (
        Preset(
            "steady",
            "Steady rates",
            {"turntable_acceleration_rad_s2": 0.0, "spin_acceleration_rad_s2": 0.0, "shaft_elevation_deg": 0.0},
            "Constant ω₁ and ω₂ on a horizontal shaft: α = ω₁K × ω₂n̂ is still not zero, because the spin axis turns.",
        ),
        Preset(
            "spin-only",
            "Turntable stopped",
            {"turntable_rate_rad_s": 0.0, "turntable_acceleration_rad_s2": 0.0, "spin_acceleration_rad_s2": 0.0},
            "Only the spin: A is at rest and B moves on a circle about the shaft.",
        ),
        Preset(
            "centre-point",
            "B at the centre",
            {"point_radius_fraction": 0.0},
            "r_B/A = 0: B moves exactly like A, whatever the disk's ω and α.",
        ),
        Preset(
            "spinning-up",
            "Both spinning up",
            {"turntable_acceleration_rad_s2": 1.0, "spin_acceleration_rad_s2": 3.0, "arrows": "acceleration"},
            "Large ω̇₁ and ω̇₂: the tangential term α × r_B/A grows beside the centripetal one.",
        ),
    )

    def camera_view(self):
        """From in front and to the side of the disk (its plane is seen at an angle, never edge-on), looking at the
        middle of the shaft."""
        size, (x, _, z) = self._size, self._center_start
        return (x + 0.5 * size, -0.8 * size, z + 0.45 * size), (0.75 * x, 0.0, 0.75 * z)

    def physical_params(self) -> dict[str, Any]:
        return {k: v for k, v in self.params.items() if k in physics.PARAMETERS.by_name}

    def build(self) -> None:
        scene = self.client.scene
        self.t_s = 0.0
        self._size = 1.1
        self._center_start = (0.8, 0.0, 0.0)
        self.ground = scene.add_grid(
            "/ground",
            width=2.4,
            height=2.4,
            cell_size=0.1,
            section_size=0.5,
            position=(0.0, 0.0, -PLATTER_BELOW_O_M - 0.03),
        )
        self.turntable = scene.add_frame("/turntable", show_axes=False)
        self.disk = scene.add_frame("/turntable/disk", show_axes=False)
        self.geometry: list = []
        self.velocity_arrows = LabelledArrows(scene, "/velocity", VELOCITY_COLORS, VELOCITY_LABELS)
        self.acceleration_arrows = LabelledArrows(scene, "/acceleration", ACCELERATION_COLORS, ACCELERATION_LABELS)
        self.legend = scene.add_label("/legend", "", anchor="bottom-center", font_screen_scale=0.85)
        self._arrow_style: dict[str, float] = {}

    def update(self) -> None:
        self.system = physics.DiskOnTurntable.from_params(self.physical_params())
        system = self.system
        L, R, beta = system.shaft_length_m, system.disk_radius_m, system.shaft_elevation_rad
        self._size = L + R
        self._center_start = (L * math.cos(beta), 0.0, L * math.sin(beta))
        self._build_geometry()
        # The floor below the platter, or below the disk when the shaft points down past it.
        self.ground.position = (0.0, 0.0, min(-PLATTER_BELOW_O_M, L * math.sin(beta) - R) - 0.03)
        whole = system.at(np.linspace(0.0, CYCLE_S, SCALE_SAMPLES))

        def longest(*vectors: np.ndarray) -> float:
            """The typical longest term over the cycle (its median): rates that grow make the end of a cycle's
            arrows longer, without shrinking the start's to specks."""
            return float(np.median(np.max([np.linalg.norm(v, axis=-1) for v in vectors], axis=0)))

        term_length = 0.45 * self._size
        self.velocity_scale = _arrow_scale(
            longest(whole.center_velocity, whole.relative_velocity, whole.point_velocity), term_length
        )
        self.acceleration_scale = _arrow_scale(
            longest(
                whole.center_acceleration,
                whole.tangential_acceleration,
                whole.centripetal_acceleration,
                whole.point_acceleration,
            ),
            term_length,
        )
        self.omega_scale = _arrow_scale(longest(whole.angular_velocity), 0.5 * self._size)
        self.alpha_scale = _arrow_scale(longest(whole.angular_acceleration), 0.5 * self._size)
        style = {
            "shaft_radius": 0.012 * self._size,
            "head_radius": 0.03 * self._size,
            "head_length": 0.055 * self._size,
        }
        if style != self._arrow_style:  # a new style rebuilds the batches: only when the sizes change
            self._arrow_style = style
            self.velocity_arrows.set_style(**style)
            self.acceleration_arrows.set_style(**style)
        view = self.params["arrows"]
        self.legend.position = (0.3 * self._size, 0.0, L * math.sin(beta) + R + 0.35 * self._size)
        if view == "velocity":
            self.legend.text = (
                f"v_B = v_A + ω × r_B/A, tip to tail at B · 1 m/s ↦ {self.velocity_scale:g} m · "
                f"ω: 1 rad/s ↦ {self.omega_scale:g} m"
            )
        else:
            self.legend.text = (
                "a_B = a_A + α × r_B/A + ω × (ω × r_B/A) at B · 1 m/s² ↦ "
                f"{self.acceleration_scale:g} m · α: 1 rad/s² ↦ {self.alpha_scale:g} m"
            )
        # The other view's arrows and labels are hidden (all of zero length) until it is chosen.
        other, keys = (
            (self.acceleration_arrows, ACCELERATION_LABELS)
            if view == "velocity"
            else (self.velocity_arrows, VELOCITY_LABELS)
        )
        other.draw(dict.fromkeys(keys, (np.zeros(3), np.zeros(3))))
        self.t_s = 0.0
        self._draw(move_labels=True)

    def _build_geometry(self) -> None:
        """The turntable, shaft, disk, spokes and the point B, for the current parameters (rebuilt on change)."""
        for node in self.geometry:
            node.remove()
        scene = self.client.scene
        system = self.system
        L, R, beta = system.shaft_length_m, system.disk_radius_m, system.shaft_elevation_rad
        reach = 0.5 * L * math.cos(beta) + 0.1
        shaft_end = (L * math.cos(beta), 0.0, L * math.sin(beta))
        self.geometry = [
            scene.add_cylinder(
                "/turntable/platter",
                radius=reach,
                height=0.03,
                color=(190, 195, 210),
                position=(0.0, 0.0, -PLATTER_BELOW_O_M),
            ),
            scene.add_cylinder(
                "/turntable/post",
                radius=0.025,
                height=PLATTER_BELOW_O_M,
                color=(110, 110, 120),
                position=(0.0, 0.0, -0.5 * PLATTER_BELOW_O_M),
            ),
            scene.add_line_segments(
                "/turntable/shaft",
                np.array([[(0.0, 0.0, 0.0), shaft_end]], np.float32),
                (90, 90, 100),
                thickness=4.0,
                thickness_units="screen",
            ),
            scene.add_icosphere("/turntable/bearing", radius=0.03, color=(90, 90, 100)),
            scene.add_label("/turntable/bearing_label", "O", anchor="top-right"),
            scene.add_line_segments(
                "/turntable/mark",
                np.array(
                    [[(0.0, 0.0, -PLATTER_BELOW_O_M + 0.016), (reach, 0.0, -PLATTER_BELOW_O_M + 0.016)]], np.float32
                ),
                (60, 60, 70),
                thickness=2.0,
                thickness_units="screen",
            ),
            # The disk: body x is the shaft, so its cylinder (axis local z) is turned onto x.
            scene.add_cylinder(
                "/turntable/disk/plate",
                radius=R,
                height=0.02 * R + 0.004,
                color=(120, 170, 220),
                opacity=0.55,
                wxyz=tuple(quaternion_z_to(np.array([1.0, 0.0, 0.0]))),
            ),
        ]
        spokes = np.linspace(0.0, math.pi, 3, endpoint=False)
        ends = R * np.stack([np.zeros(3), np.cos(spokes), np.sin(spokes)], axis=-1)
        self.geometry.append(
            scene.add_line_segments(
                "/turntable/disk/spokes",
                np.stack([-ends, ends], axis=1).astype(np.float32),
                (30, 60, 100),
                thickness=1.5,
                thickness_units="screen",
            )
        )
        point = system.point_body
        self.geometry += [
            scene.add_icosphere(
                "/turntable/disk/point", radius=0.05 * R + 0.01, color=(250, 200, 40), position=tuple(point)
            ),
            scene.add_label("/turntable/disk/point_label", "B", anchor="bottom-left", position=tuple(point)),
            scene.add_line_segments(
                "/turntable/disk/r_BA",
                np.array([[(0.0, 0.0, 0.0), point]], np.float32),
                (250, 170, 30),
                thickness=2.5,
                thickness_units="screen",
            ),
            scene.add_label("/turntable/disk/center_label", "A", anchor="top-left"),
        ]
        self.disk.position = shaft_end

    def _draw(self, *, move_labels: bool = True) -> None:
        state = self.system.at(np.array([self.t_s]))
        self._state = state
        turntable_q = state.turntable_wxyz[0]
        move_node(self.turntable, wxyz=turntable_q)
        move_node(self.disk, wxyz=quaternion_multiply(quaternion_conjugate(turntable_q), state.disk_wxyz[0]))
        A, B = state.center[0], state.point[0]
        velocity = self.params["arrows"] == "velocity"
        if velocity:
            s = self.velocity_scale
            tip = B + s * state.center_velocity[0]
            segments = {
                "center": (B, tip),
                "relative": (tip, tip + s * state.relative_velocity[0]),
                "total": (B, B + s * state.point_velocity[0]),
                "omega": (A, A + self.omega_scale * state.angular_velocity[0]),
            }
        else:
            s = self.acceleration_scale
            tip1 = B + s * state.center_acceleration[0]
            tip2 = tip1 + s * state.tangential_acceleration[0]
            segments = {
                "center": (B, tip1),
                "tangential": (tip1, tip2),
                "centripetal": (tip2, tip2 + s * state.centripetal_acceleration[0]),
                "total": (B, B + s * state.point_acceleration[0]),
                "alpha": (A, A + self.alpha_scale * state.angular_acceleration[0]),
            }
        (self.velocity_arrows if velocity else self.acceleration_arrows).draw(segments, move_labels=move_labels)

    def readout(self) -> Readout:
        """Every term of both formulas: world components (text) and magnitude (number), at the instant drawn."""
        state = self._state
        rows = (
            ("omega", "ω of the disk = ω₁K + ω₂n̂", state.angular_velocity, "rad/s"),
            ("alpha", "α of the disk = ω̇₁K + ω̇₂n̂ + ω₁K × ω₂n̂", state.angular_acceleration, "rad/s²"),
            ("r_BA", "r_B/A, from the centre A to B", state.point_from_center, "m"),
            ("v_A", "v_A = ω₁K × r_A/O", state.center_velocity, "m/s"),
            ("omega_cross_r", "ω × r_B/A", state.relative_velocity, "m/s"),
            ("v_B", "v_B = v_A + ω × r_B/A", state.point_velocity, "m/s"),
            ("a_A", "a_A = ω̇₁K × r_A/O + ω₁K × (ω₁K × r_A/O)", state.center_acceleration, "m/s²"),
            ("alpha_cross_r", "α × r_B/A", state.tangential_acceleration, "m/s²"),
            ("omega_cross_omega_cross_r", "ω × (ω × r_B/A)", state.centripetal_acceleration, "m/s²"),
            ("a_B", "a_B = a_A + α × r_B/A + ω × (ω × r_B/A)", state.point_acceleration, "m/s²"),
        )
        quantities = [Quantity("t_s", "time t", float(self.t_s), "s")]
        rates = self.system.angles.rates(np.array([self.t_s]))[0]
        quantities += [
            Quantity("turntable_rate", "turntable rate ω₁ now", float(rates[0]), "rad/s"),
            Quantity("spin_rate", "spin rate ω₂ now", float(rates[2]), "rad/s"),
        ]
        for name, label, vector, unit in rows:
            quantities.append(
                Quantity(name, f"{label} (X, Y, Z)", None, unit, _components(vector[0]), text_in_unit=True)
            )
            quantities.append(
                Quantity(f"{name}_magnitude", f"|{label.split(' = ')[0]}|", float(np.linalg.norm(vector[0])), unit)
            )
        message = (
            f"The motion replays every {CYCLE_S:g} s with ω₁ and ω₂ changing at ω̇₁ and ω̇₂. "
            "Terms shorter than their arrowhead are listed here but not drawn."
        )
        return Readout(quantities, message=message)
