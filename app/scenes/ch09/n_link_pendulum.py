"""Scene: the N-link pendulum, started in one of its normal modes (or straight, or bent), swinging under gravity.

World frame (m, +Z up), true scale: the top hinge at the origin, the links as line segments with a dot at each
joint, an orange trail behind the tip. Beside the chain (to +x, clear of its swing) a faint ghost of the chosen
normal mode at both extremes, drawn at the start's amplitude or at least ±20° so its shape shows, labelled with the
mode's frequency: a chain started in that mode at a small amplitude keeps that shape.

The readout gives the energy and its change, the frequencies, the started mode's share of the energy and a verdict
on the small-oscillation picture, what the derivation cost (operations written out against those in the generated
code; derive, generate and numba seconds, or "read from the disk cache"), any chain being prepared in this process,
and the integration used. Each frame sends the links and the joints (two messages) and a trail chunk every few frames.
"""

from __future__ import annotations

import math

import numpy as np
import viser

from app.physics.systems.ch09.n_link_pendulum_model import (
    NLinkPendulumMotion,
    joint_positions_m,
    link_angles,
    member_key,
    member_name,
    members_in_preparation,
    normal_modes,
)
from app.scenes.kit import IntegratedScene, Preset, Quantity, Readout, Trail, update_node

TRAIL_CHUNK_FRAMES = 3
TRAIL_CHUNKS = 60  # 6 s of the tip's path at 30 Hz
LINK_COLOR = (50, 60, 80)
JOINT_COLOR = (30, 30, 40)
GHOST_COLOR = (175, 185, 205)
LINE_PX = 4.0
#: The ghost is drawn at the start's amplitude, or at least this (deg), so that a 2° mode's shape shows.
GHOST_MIN_DEG = 20.0
#: The ghost's place: this many chain lengths to +x of the hinge.
GHOST_OFFSET_CHAINS = 1.25


def chain_segments(points: np.ndarray) -> np.ndarray:
    """(links, 2, 3) float32 segments joining the joints ``points`` (links + 1, 3)."""
    return np.stack([points[:-1], points[1:]], axis=1).astype(np.float32)


class NLinkPendulumScene(IntegratedScene):
    id = "n-link-pendulum"
    title = "Kane's method at scale: the N-link pendulum and its normal modes"
    chapter = 9
    model = NLinkPendulumMotion
    run_model: NLinkPendulumMotion
    frame_message_budget = 3.0
    presets = (
        Preset(
            "first-mode",
            "First mode, 5°",
            {"links": 6, "planar": "planar", "start": "mode", "mode": 1, "amplitude_deg": 5.0},
            "The slowest mode: every link leans the same way, more towards the tip. At 5° the chain keeps this shape "
            "and swings at the first frequency; the started mode keeps practically all the energy.",
        ),
        Preset(
            "highest-mode",
            "Highest mode, 2°",
            {"links": 6, "planar": "planar", "start": "mode", "mode": 6, "amplitude_deg": 2.0},
            "The fastest mode: neighbouring links lean opposite ways, a zigzag that flickers about 12 times faster "
            "than the first mode. Started small, it stays a zigzag.",
        ),
        Preset(
            "third-mode-large",
            "Third mode at 40°: the picture breaks",
            {"links": 6, "planar": "planar", "start": "mode", "mode": 3, "amplitude_deg": 40.0},
            "The same shape at 40°: sin θ is no longer θ, the modes are no longer independent, and within seconds the "
            "third mode hands energy to the others (watch its share fall).",
        ),
        Preset(
            "horizontal",
            "Released horizontal: chaos",
            {"links": 6, "planar": "planar", "start": "straight", "mode": 1, "amplitude_deg": 90.0},
            "The straight chain let go from horizontal: nothing of the normal modes survives, and two releases that "
            "differ in the ninth digit part company within seconds. The energy still stays put.",
        ),
        Preset(
            "spatial",
            "Spatial, 6 links",
            {"links": 6, "planar": "spatial", "start": "bend", "mode": 1, "amplitude_deg": 15.0},
            "Universal joints: a 15° zigzag with its top link turned sideways swings out of its plane. Each planar "
            "frequency appears twice, once per swing plane. From 20° the whip reaches a joint's lock (β = 90°) within "
            "a second, and the run stops at 85°.",
        ),
    )

    def build(self) -> None:
        self._links = 0
        self._nodes: list = []
        self.chain: viser.LineSegmentsHandle | None = None
        self.joints: viser.PointCloudHandle | None = None
        self.trail = Trail(
            self.client.scene,
            "/tip-trail",
            color=(235, 120, 20),
            chunk_frames=TRAIL_CHUNK_FRAMES,
            max_chunks=TRAIL_CHUNKS,
        )

    def camera_view(self) -> tuple[tuple[float, float, float], tuple[float, float, float]]:
        """From −y, far enough back that the chain and its ghost fill the view."""
        length = int(self.params["links"]) * float(self.params["link_length_m"])
        middle = 0.5 * GHOST_OFFSET_CHAINS * length
        return (middle, -1.4 * length, -0.4 * length), (middle, 0.0, -0.5 * length)

    def update(self) -> None:
        self.restart()
        params = self.physical_params()
        self._draw_fixed(params)
        self.trail.clear()
        self._draw()

    def _draw_fixed(self, params) -> None:
        """The chain's nodes (again when the number of links changes), the hinge, and the mode's ghost."""
        scene = self.client.scene
        links = int(params["links"])
        if links != self._links:
            for handle in (self.chain, self.joints):
                if handle is not None:
                    handle.remove()
            self.chain = scene.add_line_segments(
                "/chain/links",
                np.zeros((links, 2, 3), np.float32),
                LINK_COLOR,
                thickness=LINE_PX,
                thickness_units="screen",
            )
            self.joints = scene.add_point_cloud(
                "/chain/joints",
                np.zeros((links + 1, 3), np.float32),
                JOINT_COLOR,
                point_size=0.08 * float(params["link_length_m"]),
                point_shape="circle",
            )
            self._links = links
        for handle in self._nodes:
            handle.remove()
        self._nodes = []
        length = links * float(params["link_length_m"])
        hinge = np.array([[-0.15 * length, 0.0, 0.0], [0.15 * length, 0.0, 0.0]])
        self._nodes.append(
            scene.add_line_segments("/support", hinge[None].astype(np.float32), (90, 90, 90), thickness=3.0,
                                    thickness_units="screen")
        )  # fmt: skip
        ghost = self._ghost(params, length)
        if ghost is not None:
            segments, text = ghost
            self._nodes.append(
                scene.add_line_segments("/ghost/shape", segments, GHOST_COLOR, thickness=2.5, thickness_units="screen")
            )
            label = scene.add_label("/ghost/label", text, anchor="bottom-center")
            label.position = (GHOST_OFFSET_CHAINS * length, 0.0, 0.08 * length)
            self._nodes.append(label)

    def _ghost(self, params, length: float) -> tuple[np.ndarray, str] | None:
        """The chosen mode's shape at ± its drawn amplitude, beside the chain, and its label; None without modes."""
        links, planar = member_key(params)
        mode = int(params["mode"])
        count = links if planar else 2 * links
        if float(params["gravity_m_s2"]) <= 0 or mode > count:
            return None
        modes = normal_modes(params)
        shape = modes.shapes[mode - 1]
        angles = link_angles(params, shape)
        drawn = math.radians(max(float(params["amplitude_deg"]) if params["start"] == "mode" else 0.0, GHOST_MIN_DEG))
        angles = angles * (drawn / float(np.max(np.abs(angles))))
        plane = modes.planes[mode - 1]
        across = np.array([1.0, 0.0, 0.0]) if plane == "x–z" else np.array([0.0, 1.0, 0.0])
        offset = np.array([GHOST_OFFSET_CHAINS * length, 0.0, 0.0])
        segments = []
        link = float(params["link_length_m"])
        for sign in (1.0, -1.0):
            point = offset.copy()
            for angle in sign * angles:
                end = point + link * (math.sin(angle) * across - math.cos(angle) * np.array([0.0, 0.0, 1.0]))
                segments.append((point, end))
                point = end
        omega = float(modes.frequencies_rad_s[mode - 1])
        text = f"mode {mode} ({plane}): ω = {omega:.3f} rad/s, period {2 * math.pi / omega:.3f} s"
        return np.array(segments, np.float32), text

    def _draw(self) -> None:
        params = self.physical_params()
        n = len(self.run.y) // 2
        points = joint_positions_m(params, self.run.y[:n])
        assert self.chain is not None and self.joints is not None  # made by _draw_fixed
        update_node(self.chain, points=chain_segments(points))
        update_node(self.joints, points=points.astype(np.float32))
        self.trail.add(points[-1])

    def readout(self) -> Readout:
        params = self.physical_params()
        model = self.run_model
        y = self.run.y
        links, planar = member_key(params)
        ready = model.prepared(params)
        energy = self.current_invariants()["energy"]
        quantities = [
            Quantity("t_s", "time t", self.run.t_s, "s"),
            Quantity("energy_J", "energy T + V (V = 0 at the hinge's height)", energy, "J"),
            Quantity("energy_change_J", "ΔE = E − E(0)", energy - self._invariants0["energy"], "J"),
            Quantity("energy_drift", "energy drift |ΔE| / (E(0) above rest)", self.current_drift()["energy"]),
        ]
        if float(params["gravity_m_s2"]) > 0:
            modes = normal_modes(params)
            frequencies = modes.frequencies_rad_s
            mode = int(params["mode"])
            shown = ", ".join(f"{w:.4f}" for w in (frequencies if planar else frequencies[::2]))
            quantities += [
                Quantity("lowest_frequency_rad_s", "lowest frequency ω₁", float(frequencies[0]), "rad/s"),
                Quantity("highest_frequency_rad_s", "highest frequency", float(frequencies[-1]), "rad/s"),
                Quantity(
                    "frequencies_rad_s",
                    "small-oscillation frequencies" + ("" if planar else " (each twice: x–z and y–z)"),
                    None,
                    "rad/s",
                    shown,
                    text_in_unit=True,
                ),
            ]
            if mode <= len(frequencies):
                quantities.append(
                    Quantity("mode_frequency_rad_s", f"mode {mode}'s frequency", float(frequencies[mode - 1]), "rad/s")
                )
            share = float(model.started_mode_share(params, y[None, :])[0])
            quantities.append(
                Quantity.or_text(
                    "started_mode_share",
                    "the started mode's share of the small-oscillation energy",
                    share,
                    "",
                    "the start is not a normal mode",
                )
            )
        _, verdict = model.linear_verdict(params, y)
        operations = ready.equations.operations
        quantities += [
            Quantity.word("small_oscillations", "small-oscillation picture", verdict),
            Quantity.word("member", "chain", member_name(links, planar)),
            Quantity.word(
                "operations",
                "operations in M and f",
                f"{operations['before_cse']:,} written out, {operations['after_cse']:,} in the generated code",
            ),
            Quantity.word("preparation", "equations", ready.preparation),
            Quantity.word("being_prepared", "being prepared now", "; ".join(members_in_preparation()) or "nothing"),
            Quantity.word("integration", "integration", self.description),
        ]
        return Readout(quantities, message=self.status)
