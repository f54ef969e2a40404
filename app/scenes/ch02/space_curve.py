"""Scene for Chapter 2: a particle on a curve the student types, with a triad riding on it.

Drawn in metres on the fixed frame XYZ (+Z up). The triad is the Frenet frame
(T, N, B), the cylindrical unit vectors (e_R, e_θ, e_z) or the spherical ones
(e_r, e_φ, e_θ), each drawn a fixed fraction of the curve's size long. The
acceleration a is drawn with its tangential part a_t T and normal part a_n N
(they sum to a), scaled so that nine in ten accelerations on the loop are
drawn shorter than a third of the curve's size. In the Frenet view the osculating circle (radius 1/κ, in the
T–N plane) is drawn too. Undefined directions are hidden and the readout says why.

Per frame only the particle's pose (one frame node: position + orientation),
the osculating circle's scale, the acceleration arrows and their three labels
change; the curve itself is built once per parameter change.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
import viser

from app.physics.core.parameters import Parameter, ParameterError
from app.physics.math.curvilinear import cylindrical, spherical
from app.physics.math.rotations import quaternion_from_matrix
from app.physics.systems.ch02 import space_curve as physics
from app.scenes.kit import LabelAnchor, Preset, Quantity, Readout, Scene, arrow_segments

CURVE_SEGMENTS_MAX = 3000  # the drawn curve is the frame table's points, thinned to at most this many segments
TRIAD_FRACTION = 0.16  # triad arrow length / curve size
ACCELERATION_FRACTION = 0.33  # 90th-percentile acceleration arrow / curve size
OSCULATING_LIMIT = 3.0  # hide the osculating circle when its radius exceeds this × curve size
TABLE_RATE_HZ = 120.0  # samples of t per second of t in the frame table
TABLE_MIN, TABLE_MAX = 600, 12_000  # samples per loop in the frame table
TRIAD_COLORS = ((220, 60, 50), (40, 160, 70), (40, 90, 220))
ACCELERATION_COLORS = np.array([[150, 50, 190], [235, 140, 20], [20, 170, 170]], np.uint8)
ACCELERATION_LABELS = ("a", "aₜ", "aₙ")
#: Label anchors: a above its tip, aₙ below, so they stay apart when a_t = 0 and a = a_n N.
ACCELERATION_ANCHORS: tuple[LabelAnchor, ...] = ("bottom-left", "center-left", "top-left")
TRIAD_LABELS = {
    "frenet": ("T", "N", "B"),
    "cylindrical": ("e_R", "e_θ", "e_z"),
    "spherical": ("e_r", "e_φ", "e_θ"),
}


def _unit_osculating_circle() -> np.ndarray:
    """Unit circle in the local T–N plane through the particle, centred on +N (scaled by ρ per frame)."""
    angles = np.linspace(0.0, 2.0 * np.pi, 129)
    points = np.stack([np.cos(angles), 1.0 + np.sin(angles), np.zeros_like(angles)], axis=1)
    return np.stack([points[:-1], points[1:]], axis=1).astype(np.float32)


def table_times(t_end_s: float) -> np.ndarray:
    """The instants (s) the frame table samples over the loop 0 … ``t_end_s``."""
    samples = int(np.clip(math.ceil(t_end_s * TABLE_RATE_HZ), TABLE_MIN, TABLE_MAX))
    return np.linspace(0.0, t_end_s, samples + 1)


def _check_playback(values: Mapping[str, Any]) -> None:
    """The start lies in the loop, and the curve stays drawable over the whole loop (checked before anything is
    stored)."""
    if values["t_start_s"] > values["t_end_s"]:
        raise ParameterError("t_start_s", f"must not exceed the loop's end, t end = {values['t_end_s']:g} s")
    curve = physics.compile_curve(*(values[name] for name in physics.COMPONENTS))
    try:
        physics.check_curve_span(curve, table_times(values["t_end_s"]))
    except physics.CurveError as exc:
        raise ParameterError(exc.component, str(exc)) from None


#: Playback and display controls, after the curve's own inputs.
CONTROLS = (
    Parameter("t_end_s", "s", 12.57, 0.1, 600.0, "The particle runs t from 0 to this time, then starts again", "t end"),
    Parameter(
        "t_start_s",
        "s",
        0.0,
        0.0,
        600.0,
        "Time at which the particle starts (and stays, if the speed scale is 0)",
        "t start",
    ),
    Parameter(
        "speed_scale",
        "s/s",
        1.0,
        0.0,
        5.0,
        "Seconds of t per second of wall-clock time (0 holds the particle at t start)",
        "playback speed",
        step=0.05,
    ),
    Parameter(
        "frame",
        "",
        "frenet",
        kind="choice",
        choices=("frenet", "cylindrical", "spherical"),
        label="unit vectors",
        description=(
            "Which unit vectors ride on the particle: path (T, N, B), cylindrical (e_R, e_θ, e_z) or "
            "spherical (e_r, e_φ, e_θ)"
        ),
    ),
)

PRESETS = (
    Preset(
        "helix",
        "Helix",
        {"x_of_t": "cos(t)", "y_of_t": "sin(t)", "z_of_t": "0.2*t", "t_end_s": 12.57, "frame": "frenet"},
        "Radius 1 m, rising 0.2 m per radian: constant curvature 1/1.04 m⁻¹ and torsion 0.2/1.04 m⁻¹",
    ),
    Preset(
        "conical-spiral",
        "Conical spiral",
        {
            "x_of_t": "0.1*t*cos(2*t)",
            "y_of_t": "0.1*t*sin(2*t)",
            "z_of_t": "0.12*t",
            "t_end_s": 9.42,
            "frame": "cylindrical",
        },
        "R = 0.1 t m, θ = 2t rad, z = 0.12 t m: the radius grows, so the curvature falls",
    ),
    Preset(
        "figure-eight",
        "Figure eight",
        {"x_of_t": "cos(t)", "y_of_t": "sin(2*t)/2", "z_of_t": "0.3*sin(t)", "t_end_s": 6.283, "frame": "frenet"},
        "A figure eight bent out of its plane: fastest and nearly straight at the crossing, where the torsion "
        "swings negative",
    ),
    Preset(
        "viviani",
        "Viviani's curve",
        {
            "x_of_t": "0.5*(1-cos(t))",
            "y_of_t": "0.5*sin(t)",
            "z_of_t": "cos(t/2)",
            "t_end_s": 12.57,
            "frame": "spherical",
        },
        "A curve on the sphere of radius 1 m, starting on the +Z pole: r stays 1 m, so v_r = 0",
    ),
)


def _nice_step(length: float) -> float:
    """1, 2 or 5 × 10^k just below ``length``."""
    power = 10.0 ** math.floor(math.log10(length))
    return max(m * power for m in (1.0, 2.0, 5.0) if m * power <= length)


def triad_rotations(unit_vectors: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Rotation matrices R_world_triad whose columns are each triad's unit vectors.

    ``unit_vectors`` (N, 3, 3): row k is the k-th unit vector on XYZ, NaN where
    undefined. Fully defined triads are re-orthonormalised (Gram–Schmidt, for
    drawing); a triad with some rows undefined is completed around its first
    defined row; one with none defined gets the identity. Returns (R (N, 3, 3),
    defined (N, 3)).
    """
    uv = np.asarray(unit_vectors, dtype=float)
    defined = np.all(np.isfinite(uv), axis=2)
    rows = np.broadcast_to(np.eye(3), uv.shape).copy()
    full = defined.all(axis=1)
    if full.any():
        e1 = uv[full, 0]
        e2 = uv[full, 1] - np.einsum("ij,ij->i", uv[full, 1], e1)[:, None] * e1
        e2 /= np.linalg.norm(e2, axis=1, keepdims=True)
        rows[full] = np.stack([e1, e2, np.cross(e1, e2)], axis=1)
    partial = np.flatnonzero(defined.any(axis=1) & ~full)
    if partial.size:
        k = np.argmax(defined[partial], axis=1)
        d = uv[partial, k]
        helper = np.where((np.abs(d[:, 0]) < 0.9)[:, None], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0])
        u = np.cross(d, helper)
        u /= np.linalg.norm(u, axis=1, keepdims=True)
        rows[partial, k] = d
        rows[partial, (k + 1) % 3] = u
        rows[partial, (k + 2) % 3] = np.cross(d, u)
    return np.swapaxes(rows, 1, 2), defined


@dataclass(frozen=True)
class FrameTable:
    """What each animation frame draws, tabulated on a uniform grid of t over the loop.

    ``wxyz`` (N, 4): particle triad attitude (sign-continuous); ``triad_defined``
    (N, 3); ``osculating_radius_m`` (N,) NaN where no circle is drawn;
    ``acceleration`` (N, 3, 3): a, a_t T and a_n N already scaled to display
    lengths (m), NaN where the particle is at rest.
    """

    step_s: float
    defined: np.ndarray
    position_m: np.ndarray
    wxyz: np.ndarray
    triad_defined: np.ndarray
    osculating_radius_m: np.ndarray
    acceleration: np.ndarray

    def at(self, t_s: float) -> dict[str, Any]:
        """Linear interpolation at ``t_s`` (flags from the nearest sample; nearest value across an undefined one)."""
        x = t_s / self.step_s
        last = len(self.defined) - 1
        i = min(int(x), last)
        j = min(i + 1, last)
        w = x - i
        nearest = j if w >= 0.5 else i

        def blend(values: np.ndarray) -> np.ndarray:
            mixed = (1.0 - w) * values[i] + w * values[j]
            return mixed if np.all(np.isfinite(mixed)) else values[nearest]

        wxyz = blend(self.wxyz)
        return {
            "defined": bool(self.defined[nearest]),
            "position_m": blend(self.position_m),
            "wxyz": wxyz / np.linalg.norm(wxyz),
            "triad_defined": self.triad_defined[nearest],
            "osculating_radius_m": float(blend(self.osculating_radius_m)),
            "acceleration": blend(self.acceleration),
        }


class SpaceCurveScene(Scene):
    id = "space-curve"
    title = "A particle on a space curve: path variables and curvilinear coordinates"
    chapter = 2
    model = physics.ParticleOnCurve
    controls = CONTROLS
    check_controls = _check_playback
    presets = PRESETS
    animated = True

    def camera_view(self) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        c, size = self._center, self._size
        # About one curve-size away (size = the bounding box's diagonal), from the front right, above.
        return (c[0] + 0.5 * size, c[1] - 0.72 * size, c[2] + 0.42 * size), (float(c[0]), float(c[1]), float(c[2]))

    def _curve_moved(self, old_center: np.ndarray, old_size: float) -> bool:
        """Whether a new curve is a different size or elsewhere (then this viewer's camera follows it).

        Changing only the unit vectors, playback or start time leaves the student's camera alone.
        """
        resized = not (0.8 < self._size / old_size < 1.25)
        return resized or float(np.linalg.norm(self._center - old_center)) > 0.2 * old_size

    def _reframe(self) -> None:
        """Move this viewer's camera onto the curve.

        Done on the frame after a parameter change: viser coalesces camera
        messages by type, so a move queued together with the new initial camera
        (the "Reset View" target, sent by ``set_params``) would replace it.
        """
        self._reframe_pending = False
        position, look_at = self.camera_view()
        self.client.camera.position = position
        self.client.camera.look_at = look_at

    def build(self) -> None:
        scene = self.client.scene
        self._center = np.zeros(3)
        self._size = 2.0
        self.t_s = 0.0
        self._static_nodes: list = []
        self.particle = scene.add_frame("/particle", show_axes=False)
        self.ball = scene.add_icosphere("/particle/ball", radius=1.0, color=(30, 30, 30))
        self.triad: list = []  # (arrow, label) per unit vector, built with the curve's size
        self.osculating = scene.add_line_segments(
            "/particle/osculating", _unit_osculating_circle(), (120, 120, 120), thickness=1.5, thickness_units="screen"
        )
        self._acceleration_node: viser.ArrowsHandle | None = None
        self.acceleration_labels = [
            scene.add_label(f"/acceleration_label/{k}", text, anchor=anchor, font_screen_scale=0.9)
            for k, (text, anchor) in enumerate(zip(ACCELERATION_LABELS, ACCELERATION_ANCHORS))
        ]
        self._shown: dict[str, Any] = {"particle": True, "osculating": True}  # what the viewer has been told
        self._built = False  # the first update is framed by the initial camera
        self._reframe_pending = False

    # -- parameter changes --------------------------------------------------------------
    def update(self) -> None:
        p = self.params
        self.curve = physics.compile_curve(p["x_of_t"], p["y_of_t"], p["z_of_t"])
        self.t_end_s = float(p["t_end_s"])
        self.scales = physics.reference_scales(self.curve, self.t_end_s)
        path, coordinates = self._describe(table_times(self.t_end_s))
        old_center, old_size = self._center.copy(), self._size
        points = path.position_m
        finite = np.all(np.isfinite(points), axis=1)
        if finite.any():
            low, high = np.min(points[finite], axis=0), np.max(points[finite], axis=0)
            self._center = 0.5 * (low + high)
            self._size = max(float(np.linalg.norm(high - low)), 1e-3)
        else:
            self._center, self._size = np.zeros(3), 2.0
        self._undrawn_share = 1.0 - float(finite.mean())
        self._draw_static(points, finite)
        self._reframe_pending = self._built and self._curve_moved(old_center, old_size)
        self._built = True
        self.table = self._tabulate(path, coordinates)
        self.t_s = min(float(p["t_start_s"]), self.t_end_s)
        self._draw()

    def _describe(self, t_s: np.ndarray | float):
        """Path variables at ``t_s`` and, unless the Frenet frame is chosen, the chosen coordinates."""
        path = physics.path_variables(self.curve, t_s, self.scales)
        frame = self.params["frame"]
        if frame == "frenet":
            return path, None
        describe = cylindrical if frame == "cylindrical" else spherical
        return path, describe(
            path.position_m, path.velocity_m_s, path.acceleration_m_s2, length_scale_m=self.scales.length_m
        )

    def _tabulate(self, path: physics.PathVariables, coordinates) -> FrameTable:
        if coordinates is None:
            unit_vectors = np.stack([path.tangent, path.normal, path.binormal], axis=1)
        else:
            unit_vectors = coordinates.unit_vectors
        R_world_triad, triad_defined = triad_rotations(unit_vectors)
        wxyz = quaternion_from_matrix(R_world_triad)
        # q and −q are the same attitude: keep neighbours in one hemisphere so interpolation is smooth.
        flips = np.concatenate([[1.0], np.sign(np.einsum("ij,ij->i", wxyz[1:], wxyz[:-1]) + 1e-300)])
        wxyz = wxyz * np.cumprod(flips)[:, None]
        frenet = self.params["frame"] == "frenet"
        with np.errstate(divide="ignore", invalid="ignore"):
            radius = np.where(frenet & path.curving, 1.0 / path.curvature_1_m, np.nan)
        radius[radius > OSCULATING_LIMIT * self._size] = np.nan
        a = path.acceleration_m_s2
        a_t = path.a_tangential_m_s2[:, None] * path.tangent
        split = np.stack([a, a_t, a - a_t], axis=1)  # a − a_t T = a_n N, defined (and ~0) where N is not
        split[~path.moving] = np.nan
        magnitudes = np.linalg.norm(a[path.defined], axis=1)
        # The 90th percentile, not the maximum: one spike (e.g. 1/t near t = 0) must not shrink every other arrow.
        typical = float(np.percentile(magnitudes, 90)) if magnitudes.size else 0.0
        scale = ACCELERATION_FRACTION * self._size / typical if typical > 0.0 else 0.0
        return FrameTable(
            step_s=self.t_end_s / (len(path.t_s) - 1),
            defined=path.defined,
            position_m=np.where(path.defined[:, None], path.position_m, np.nan),
            wxyz=wxyz,
            triad_defined=triad_defined & path.defined[:, None],
            osculating_radius_m=radius,
            acceleration=split * scale,
        )

    def _draw_static(self, points: np.ndarray, finite: np.ndarray) -> None:
        """The curve, ground grid, world axes and the triad's arrows (sized to the curve)."""
        scene = self.client.scene
        for node in reversed(self._static_nodes):
            node.remove()
        size, center = self._size, self._center
        stride = max(1, math.ceil((len(points) - 1) / CURVE_SEGMENTS_MAX))
        points, finite = points[::stride], finite[::stride]
        keep = finite[:-1] & finite[1:]
        segments = np.stack([points[:-1], points[1:]], axis=1)[keep].astype(np.float32)
        nodes: list[viser.SceneNodeHandle] = []
        if len(segments):
            nodes.append(
                scene.add_line_segments("/curve", segments, (90, 90, 150), thickness=2.5, thickness_units="screen")
            )
        cell = self._grid_cell_m = _nice_step(size / 8.0)
        ground_z = float(np.min(points[finite, 2])) if finite.any() else 0.0
        width = 2.0 * cell * math.ceil(0.75 * size / cell)
        nodes.append(
            scene.add_grid(
                "/ground",
                width=width,
                height=width,
                cell_size=cell,
                section_size=5 * cell,
                position=(center[0], center[1], ground_z),
            )
        )
        axes_length = 0.25 * size
        nodes.append(scene.add_frame("/world_axes", axes_length=axes_length, axes_radius=0.006 * size))
        for k, name in enumerate("XYZ"):
            nodes.append(
                scene.add_label(
                    f"/world_axes/{name}",
                    name,
                    position=tuple(1.08 * axes_length * np.eye(3)[k]),
                    font_screen_scale=0.9,
                )
            )
        self.ball.scale = 0.018 * size
        length, shaft = TRIAD_FRACTION * size, 0.012 * size
        for k in range(3):
            tip = length * np.eye(3)[k]
            arrow = scene.add_arrows(
                f"/particle/e{k}",
                np.array([[np.zeros(3), tip]], np.float32),
                TRIAD_COLORS[k],
                shaft_radius=shaft,
                head_radius=2.5 * shaft,
                head_length=6.0 * shaft,
            )
            label = scene.add_label(
                f"/particle/e{k}/label",
                TRIAD_LABELS[self.params["frame"]][k],
                position=tuple(1.06 * tip),
                anchor="center-left",
                font_screen_scale=0.9,
            )
            nodes += [arrow, label]
        self._static_nodes = nodes
        self.triad = [nodes[-6:-4], nodes[-4:-2], nodes[-2:]]
        self._head_length = 6.0 * 0.008 * size
        self._set_acceleration_arrows(np.zeros((0, 2, 3), np.float32), ())
        self._shown["triad"] = (True, True, True)  # the new arrows start visible

    # -- per frame --------------------------------------------------------------------------
    def advance(self, dt_s: float) -> None:
        if self._reframe_pending:
            self._reframe()
        super().advance(dt_s)

    def step_motion(self, dt_s: float) -> bool:
        """The particle runs at ``speed_scale`` × real time along the curve's parameter and loops at ``t_end_s``."""
        speed = float(self.params["speed_scale"])
        if speed == 0.0:
            return False
        self.t_s = (self.t_s + speed * dt_s) % self.t_end_s
        return True

    def step_without_drawing(self, t_s: float) -> None:
        """A closed form: the particle at the curve's time ``t_s`` (s; the loop repeats every ``t_end_s``)."""
        self.t_s = t_s % self.t_end_s

    def _show(self, key: str, value: Any, apply) -> None:
        """Send a visibility change only when it changes."""
        if self._shown.get(key) != value:
            apply(value)
            self._shown[key] = value

    def _draw(self) -> None:
        frame = self.table.at(self.t_s)

        def show_particle(visible: bool) -> None:
            self.particle.visible = visible

        self._show("particle", frame["defined"], show_particle)
        if not frame["defined"]:
            self._set_acceleration_arrows(np.zeros((0, 2, 3), np.float32), ())
            return
        self.particle.position = frame["position_m"]
        self.particle.wxyz = frame["wxyz"]

        def show_triad(visible: tuple[bool, ...]) -> None:
            for (arrow, label), v in zip(self.triad, visible):
                arrow.visible = v
                label.visible = v

        self._show("triad", tuple(bool(v) for v in frame["triad_defined"]), show_triad)
        radius = frame["osculating_radius_m"]

        def show_circle(visible: bool) -> None:
            self.osculating.visible = visible

        self._show("osculating", bool(np.isfinite(radius)), show_circle)
        if np.isfinite(radius):
            self.osculating.scale = radius
        self._draw_acceleration(frame["acceleration"], frame["position_m"])

    def _draw_acceleration(self, vectors: np.ndarray, position: np.ndarray) -> None:
        """Arrows a, a_t T, a_n N from the particle; arrows shorter than half a head are hidden."""
        if not np.all(np.isfinite(vectors)):
            self._set_acceleration_arrows(np.zeros((0, 2, 3), np.float32), ())
            return
        shown = np.linalg.norm(vectors, axis=1) > 0.5 * self._head_length
        mask = tuple(bool(m) for m in shown)
        tails = np.broadcast_to(position, (3, 3))
        self._set_acceleration_arrows(arrow_segments(tails[shown], vectors[shown], 1.0), mask)
        for label, visible, vector in zip(self.acceleration_labels, mask, vectors):
            if visible:
                label.position = tuple(position + 1.04 * vector)

    def _set_acceleration_arrows(self, points: np.ndarray, mask: tuple[bool, ...]) -> None:
        """Update the acceleration arrows; rebuild the node only when which arrows are shown changes."""
        if mask == self._shown.get("acceleration") and self._acceleration_node is not None:
            self._acceleration_node.points = points
            return
        if self._acceleration_node is not None:
            self._acceleration_node.remove()
            self._acceleration_node = None
        shaft = 0.008 * self._size
        if len(points):
            self._acceleration_node = self.client.scene.add_arrows(
                "/acceleration",
                points,
                ACCELERATION_COLORS[list(mask)],
                shaft_radius=shaft,
                head_radius=2.5 * shaft,
                head_length=6.0 * shaft,
            )
        for label, visible in zip(self.acceleration_labels, mask or (False, False, False)):
            label.visible = visible
        self._shown["acceleration"] = mask

    # -- numbers for the lesson page -----------------------------------------------------------
    def readout(self) -> Readout:
        path, coordinates = self._describe(self.t_s)
        quantities = [
            Quantity("t_s", "t", self.t_s, "s"),
            Quantity("speed", "speed v", float(path.speed_m_s[0]), "m/s"),
            Quantity("a_tangential", "a_t = dv/dt", float(path.a_tangential_m_s2[0]), "m/s²"),
            Quantity("a_normal", "a_n = κ v²", float(path.a_normal_m_s2[0]), "m/s²"),
            Quantity("curvature", "curvature κ", float(path.curvature_1_m[0]), "1/m"),
            Quantity("torsion", "torsion τ", float(path.torsion_1_m[0]), "1/m"),
            Quantity(
                "arc_length",
                "arc length s from t = 0",
                float(physics.arc_length(self.curve, np.array([self.t_s]))[0]),
                "m",
            ),
            Quantity("grid_cell", "side of a grid square", self._grid_cell_m, "m"),
        ]
        messages = [physics.undefined_reason(path)]
        frame = self.params["frame"]
        if coordinates is not None:
            quantities += _coordinate_quantities(frame, coordinates)
            messages.append(_coordinate_reason(frame, coordinates))
        if self._undrawn_share > 0:
            messages.append(
                f"The position has no finite value on {100 * self._undrawn_share:.1f}% of 0 ≤ t ≤ {self.t_end_s:g} s; "
                "that part of the path is not drawn."
            )
        return Readout(quantities, message=" ".join(m for m in messages if m))


_COORDINATE_ROWS = {
    "cylindrical": (("R", "R", "m"), ("theta", "θ", "rad"), ("z", "z", "m")),
    "spherical": (("r", "r", "m"), ("phi", "φ", "rad"), ("theta", "θ", "rad")),
}


def _coordinate_quantities(frame: str, coordinates) -> list[Quantity]:
    rows = _COORDINATE_ROWS[frame]
    out = [
        Quantity(name, label, float(coordinates.coordinates[0, k]), unit) for k, (name, label, unit) in enumerate(rows)
    ]
    out += [
        Quantity(f"v_{name}", f"v_{label}", float(coordinates.velocity[0, k]), "m/s")
        for k, (name, label, _) in enumerate(rows)
    ]
    out += [
        Quantity(f"a_{name}", f"a_{label}", float(coordinates.acceleration[0, k]), "m/s²")
        for k, (name, label, _) in enumerate(rows)
    ]
    return out


def _coordinate_reason(frame: str, coordinates) -> str:
    undefined = ~np.all(np.isfinite(coordinates.unit_vectors[0]), axis=1)
    if not undefined.any():
        return ""
    if frame == "cylindrical":
        return "The particle is on the Z axis (R = 0): θ, e_R and e_θ are undefined there; e_z and z are not."
    if undefined.all():
        return "The particle is at the origin (r = 0): every spherical direction is undefined there."
    return "The particle is on the Z axis (φ = 0 or π): θ, e_φ and e_θ are undefined there; e_r still points along ±Z."
