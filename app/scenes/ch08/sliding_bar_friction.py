"""Scene: a bar whose lower end slides on a rough floor, with the contact force and its friction cone.

The bar's plane is the world x–z plane at y = 0, seen from −y; the floor is z = 0.
At the lower end B: the normal force N (blue, up), the friction force F (orange,
along the floor) and the friction cone's edges (grey), the lines at ±atan μ from
the normal, drawn μN wide — sliding puts F on an edge, sticking inside. The weight
(grey) points down onto G. One scale: m g is drawn 0.3 L long. When the run stops
(lands flat, lifts off, or the contact force has no consistent value — Painlevé)
the bar stays where it stopped with the reason in the readout, and the motion
replays from the start after REPLAY_AFTER_STOP_S.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from app.physics.systems.ch08 import sliding_bar as physics
from app.scenes.kit import IntegratedScene, Preset, Quantity, Readout, arrow_segments, motion_numbers, update_node

ARROW_COLORS = np.array([[40, 100, 220], [230, 130, 20], [120, 120, 120]], np.uint8)
#: Seconds the stopped bar is shown before the motion replays.
REPLAY_AFTER_STOP_S = 3.0
#: Longest run looked ahead for the events the readout lists (s).
LOOKAHEAD_S = 20.0


def _xz(point) -> tuple[float, float, float]:
    return float(point[0]), 0.0, float(point[1])


class SlidingBarFrictionScene(IntegratedScene):
    id = "sliding-bar-friction"
    title = "A bar sliding on a rough floor: stick, slip and Painlevé's paradox"
    chapter = 8
    model = physics.SlidingBar
    #: Bar, ends, force arrows and the friction cone each frame.
    frame_message_budget = 5.0
    presets = (
        Preset(
            "slide-and-fall",
            "Slides and falls",
            {"angle0_deg": 30.0, "slide_speed0_m_s": 1.0, "mu": 0.3},
            "B slides away while the bar falls flat; friction work is booked as it goes.",
        ),
        Preset(
            "stick-then-slip",
            "Pivots, then breaks loose",
            {"angle0_deg": 60.0, "slide_speed0_m_s": 0.0, "mu": 0.5},
            "Released at rest: B sticks and the bar pivots until |F| reaches μN at 31.8° (t = 0.345 s), then B slides.",
        ),
        Preset(
            "near-jam",
            "Braked towards the band",
            {"angle0_deg": 45.0, "slide_speed0_m_s": 3.0, "mu": 1.5},
            "μ = 1.5: friction tips the bar up towards the Painlevé band (50.6°–73.0°); N peaks at 49.5 N (5 m "
            "g) and B stops at 47.3°, short of it.",
        ),
        Preset(
            "painleve",
            "Painlevé's paradox",
            {"angle0_deg": 63.4, "slide_speed0_m_s": 1.0, "mu": 1.5},
            "Sliding away from the lean at tan θ ≈ 2 with μ = 1.5 > 4/3: no contact force N ≥ 0 fits — detected "
            "and stopped.",
        ),
        Preset(
            "painleve-reversed",
            "Same, sliding the other way",
            {"angle0_deg": 63.4, "slide_speed0_m_s": -1.0, "mu": 1.5},
            "The same bar and angle with B sliding towards the lean: D > 0, the motion is consistent.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.floor = scene.add_box("/floor", color=(150, 160, 150), dimensions=(1.0, 0.4, 0.1))
        self.bar = scene.add_line_segments("/bar", np.zeros((1, 2, 3), np.float32), (150, 90, 40), thickness=0.05)
        self.ends = scene.add_point_cloud(
            "/ends", np.zeros((2, 3), np.float32), (30, 30, 30), point_size=0.05, point_shape="circle"
        )
        self.arrows = scene.add_arrows(
            "/forces",
            np.zeros((3, 2, 3), np.float32),
            ARROW_COLORS,
            shaft_radius=0.01,
            head_radius=0.03,
            head_length=0.06,
        )
        self.cone = scene.add_line_segments("/cone", np.zeros((2, 2, 3), np.float32), (150, 150, 150), thickness=0.006)
        self.legend = scene.add_label("/legend", "", anchor="bottom-left")
        self._length = 1.0

    def camera_view(self):
        length = self._length
        return (0.0, -2.6 * length, 0.6 * length), (0.0, 0.0, 0.45 * length)

    def update(self) -> None:
        params = self.physical_params()
        self.restart()
        length = self._length = params["length_m"]
        thickness = 0.04 * length
        self.floor.dimensions = (5.0 * length, 0.5 * length, thickness)
        self.floor.position = (0.0, 0.0, -0.5 * thickness)
        self.bar.thickness = 0.02 * length
        self.ends.point_size = 0.035 * length
        self.arrows.shaft_radius = 0.01 * length
        self.arrows.head_radius = 0.025 * length
        self.arrows.head_length = 0.05 * length
        self.cone.thickness = 0.006 * length
        self._force_scale = 0.3 * length / (params["mass_kg"] * params["g_m_s2"])
        self.legend.position = (-1.0 * length, 0.0, 1.1 * length)
        self.legend.text = "blue: N · orange: F · grey lines: cone ±μN · grey arrow: m g (0.3 L)"
        self.events = physics.run_events(params, t_end_s=LOOKAHEAD_S)
        self.stop = next(
            (e for e in self.events if e.index in (physics.JAM_STOP, physics.LIFT_OFF, physics.LANDS)), None
        )
        self._held_s = 0.0
        self._clock_s = 0.0
        self._shown = self.run.y
        self._draw_state(self.run.y)

    def _draw_state(self, y: np.ndarray) -> None:
        params = self.physical_params()
        self._shown = y
        bottom, top = physics.end_positions_m(params, y)
        center = 0.5 * (bottom + top)
        update_node(self.bar, points=np.array([[_xz(bottom), _xz(top)]], np.float32))
        update_node(self.ends, points=np.array([_xz(bottom), _xz(top)], np.float32))
        forces = physics.contact_forces(params, y)[0]
        self._forces = forces
        normal, friction = max(forces[physics.C_NORMAL], 0.0), forces[physics.C_FRICTION]
        weight = params["mass_kg"] * params["g_m_s2"]
        scale = self._force_scale
        tails = np.array([_xz(bottom), _xz(bottom), np.array(_xz(center)) + np.array([0.0, 0.0, scale * weight])])
        vectors = np.array([[0.0, 0.0, normal], [friction, 0.0, 0.0], [0.0, 0.0, -weight]])
        update_node(self.arrows, points=arrow_segments(tails, vectors, scale))
        limit = params["mu"] * normal
        base = np.array(_xz(bottom))
        cone = np.array(
            [
                [base, base + scale * np.array([-limit, 0.0, normal])],
                [base, base + scale * np.array([limit, 0.0, normal])],
            ]
        )
        update_node(self.cone, points=cone.astype(np.float32))

    def step_motion(self, dt_s: float) -> bool:
        """One frame; at the model's stop (jam, lift-off, landing) the bar is held there, then the run replays.

        The run advances :attr:`frame_dt_s` a frame whatever the host's frame ``dt_s``, so the stop is judged on
        that; a live run that reaches its terminal event first (its own located instant) is held there too."""
        stop = self.stop
        if stop is not None and (not self.run.running or self.run.t_s + self.frame_dt_s > stop.t_s):
            return self._hold(dt_s)
        running = self.step_physics()
        self._clock_s = self.run.t_s
        if not running and self.run.status == "event" and self.run.stop_event is not None:
            self.stop = self.run.stop_event  # the model's stop, not a numerical failure: held, then replayed
            self.status = ""
            return True
        return running

    def _hold(self, dt_s: float) -> bool:
        """Hold the bar at :attr:`stop` for one frame of ``dt_s`` s; replay from the start after
        :data:`REPLAY_AFTER_STOP_S`."""
        if self._held_s == 0.0:
            self.status = ""  # a stop the model explains (readout message), not a numerical failure
        self._held_s += dt_s
        self._clock_s += dt_s
        if self._held_s > REPLAY_AFTER_STOP_S:
            self.restart()
            self._held_s = self._clock_s = 0.0
        return True

    def redraw(self) -> None:
        self._draw_state(self.stop.state if self._held_s > 0.0 and self.stop is not None else self.run.y)

    def motion_state(self) -> dict[str, Any]:
        """The run's state ``y``, ``held_s`` (how long the bar has been held at the stop, s) and ``t_s``: the
        time since the start, the hold included (the run's own clock stops at the stop)."""
        return super().motion_state() | {"t_s": float(self._clock_s), "held_s": float(self._held_s)}

    def resume_from(self, motion: Mapping[str, Any]) -> None:
        numbers = motion_numbers(motion, ("t_s", "held_s"))
        if not 0.0 <= numbers["held_s"] <= numbers["t_s"]:
            raise ValueError(f"motion: held_s must be from 0 s to t_s, got {numbers['held_s']!r}")
        super().resume_from(motion)
        self._held_s, self._clock_s = numbers["held_s"], numbers["t_s"]
        self.run.t_s = numbers["t_s"] - numbers["held_s"]

    def readout(self) -> Readout:
        params = self.physical_params()
        y = self._shown
        forces = self._forces
        budget = physics.energy_budget(params, y)
        phase = int(y[physics.PHASE])
        held = self._held_s > 0.0 and self.stop is not None
        phase_word = physics.PHASE_WORDS[phase]
        if held and self.stop is not None:
            phase_word = physics.STOPPED_PHASE_WORDS.get(self.stop.index, phase_word)
        band = physics.painleve_band_deg(params["mu"])
        band_text = "none: μ < 4/3, sliding is always consistent"
        quantities = [
            Quantity("t_s", "time t", self.stop.t_s if held and self.stop is not None else self.run.t_s, "s"),
            Quantity.word("phase", "phase", phase_word),
            Quantity("angle_deg", "angle from the floor θ", math.degrees(y[physics.THETA]), "deg"),
            Quantity("contact_speed_m_s", "sliding speed of B, u", float(y[physics.U]), "m/s"),
            Quantity("normal_force_N", "normal force N", float(forces[physics.C_NORMAL]), "N"),
            Quantity("friction_force_N", "friction force F", float(forces[physics.C_FRICTION]), "N"),
            Quantity("friction_limit_N", "friction limit μN", params["mu"] * float(forces[physics.C_NORMAL]), "N"),
            Quantity(
                "painleve_factor", "D = 1 + 3 cos θ (cos θ − σμ sin θ)", float(forces[physics.C_PAINLEVE_FACTOR]), ""
            ),
            Quantity.or_text(
                "painleve_band_low_deg",
                "Painlevé band (sliding away from the lean) from",
                band[0] if band else None,
                "deg",
                band_text,
            ),
            Quantity.or_text("painleve_band_high_deg", "… to", band[1] if band else None, "deg", band_text),
            Quantity("kinetic_energy_J", "kinetic energy", float(budget.kinetic_J[0]), "J"),
            Quantity("potential_energy_J", "potential energy (floor = 0)", float(budget.potential_J[0]), "J"),
            Quantity("friction_work_J", "work done against friction", float(budget.friction_work_J[0]), "J"),
            Quantity("energy_total_J", "sum (stays at the initial energy)", float(budget.total_J[0]), "J"),
        ]
        return Readout(quantities, message=self._message(params, phase))

    def _message(self, params, phase: int) -> str:
        if self.status:
            return self.status
        if self._held_s > 0.0 and self.stop is not None:
            return physics.stop_message(params, self.stop)
        if phase == physics.STICKING:
            return "B sticks: friction holds it inside the cone (|F| < μN) and the bar pivots about it."
        direction = "away from" if self._shown[physics.SLIP] * math.cos(self._shown[physics.THETA]) > 0.0 else "towards"
        return f"B slides {direction} the side the bar leans to: F = μN on the edge of the cone, against the sliding."
