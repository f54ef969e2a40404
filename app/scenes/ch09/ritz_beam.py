"""Scene: a cantilever vibrating in one Ritz mode beside the exact mode, and the error of the Ritz series against N.

World frame (m, +Z up): the beam's clamp is at the origin and its axis runs along +X to the free end at
X = L; the deflection w is drawn along +Z at true scale (``amplitude_m`` is the tip's). The Ritz mode
(blue) lies on Y = 0, the exact mode of the same index (orange) on Y = −0.35 L. Time is slowed so the
exact mode swings at :data:`SHOWN_HZ`; the Ritz one swings faster by ω_Ritz/ω_exact, so a poor
approximation visibly drifts out of phase. Right of the beam, in the XZ plane, a chart of
log₁₀|relative error| of the chosen mode against the number of terms N for both bases (blue
orthogonal, red monomial; red dots where the monomial result fell below the exact value or had no
real frequency); the grey ring marks the current N. Each frame sends one message (the two beams'
points); everything else is redrawn only when a control changes.
"""

from __future__ import annotations

import math
from typing import cast

import numpy as np

from app.physics.systems.ch09 import ritz_beam as physics
from app.scenes.kit import LabelAnchor, Preset, Quantity, Readout, Scene, circle_segments, update_node

RITZ_COLOR = (40, 90, 220)
EXACT_COLOR = (235, 130, 30)
MONOMIAL_COLOR = (215, 45, 45)
AXIS_COLOR = (170, 170, 175)
#: The exact mode is shown swinging at this rate (Hz); the readout says how much the beam's time is slowed.
SHOWN_HZ = 0.5
#: Straight pieces each drawn beam is made of.
SEGMENTS = 64
#: The chart's vertical axis: log₁₀ of the relative error from this floor (rounding) up to 1.
ERROR_FLOOR_LOG10 = -16.0
EXACT_OFFSET = 0.35  # × L: the exact beam's distance from the Ritz one (−Y)


class RitzCantileverScene(Scene):
    id = "ritz-cantilever"
    title = "Hamilton's principle and the Ritz series: a cantilever's natural frequencies"
    chapter = 9
    model = physics.RitzCantileverModel
    animated = True
    frame_message_budget = 2.0
    slider_ranges = {
        "length_m": (0.2, 5.0, 0.05),
        "flexural_rigidity_N_m2": (1.0, 1000.0, 1.0),
        "mass_per_length_kg_m": (0.1, 20.0, 0.1),
        "amplitude_m": (0.0, 1.0, 0.01),
    }
    presets = (
        Preset(
            "one-term",
            "One term",
            {"terms": 1, "mode": 1, "basis": "orthogonal"},
            "A single admissible function (a parabola, ξ²): ω₁ comes out 27 % high, ω² = 20 EI/(ρA L⁴).",
        ),
        Preset(
            "converged",
            "Six terms, mode 1",
            {"terms": 6, "mode": 1, "basis": "orthogonal"},
            "Six terms: the first frequency is right to 1e-10, the sixth still 3.4 times the exact one.",
        ),
        Preset(
            "highest-mode",
            "Highest mode is poor",
            {"terms": 6, "mode": 6, "basis": "orthogonal"},
            "The Nth Ritz mode is always the worst: watch it drift out of phase with the exact one.",
        ),
        Preset(
            "many-terms",
            "Fourteen terms",
            {"terms": 14, "mode": 3, "basis": "orthogonal"},
            "The orthogonal basis at N = 14: every frequency an upper bound, the first four within 2e-10 of the "
            "exact ones.",
        ),
        Preset(
            "monomials-fail",
            "Monomials, 14 terms",
            {"terms": 14, "mode": 3, "basis": "monomial"},
            "The same space spanned by ξ², ξ³, …: cond(M) ≈ 1e18, the upper bound breaks and some ω² turn negative.",
        ),
    )

    def build(self) -> None:
        scene = self.client.scene
        self.t_s = 0.0
        self._length = 1.0
        self.clamp = scene.add_box("/clamp", color=(90, 90, 95), dimensions=(0.05, 0.6, 0.4))
        self.axes = scene.add_line_segments(
            "/rest_lines", np.zeros((2, 2, 3), np.float32), AXIS_COLOR, thickness=1.0, thickness_units="screen"
        )
        colors = np.zeros((2 * SEGMENTS, 2, 3), np.uint8)
        colors[:SEGMENTS], colors[SEGMENTS:] = RITZ_COLOR, EXACT_COLOR
        self.beams = scene.add_line_segments(
            "/beams", np.zeros((2 * SEGMENTS, 2, 3), np.float32), colors, thickness=5.0, thickness_units="screen"
        )
        self.ritz_label = scene.add_label("/labels/ritz", "", anchor="bottom-left")
        self.exact_label = scene.add_label("/labels/exact", "", anchor="top-left")
        self.chart = scene.add_line_segments(
            "/chart/lines", np.zeros((1, 2, 3), np.float32), AXIS_COLOR, thickness=2.0, thickness_units="screen"
        )
        self.chart_marks = scene.add_point_cloud(
            "/chart/marks", np.zeros((1, 3), np.float32), MONOMIAL_COLOR, point_size=0.03, point_shape="circle"
        )
        self.chart_labels = [
            scene.add_label(f"/chart/label_{i}", "", anchor=cast(LabelAnchor, anchor))
            for i, anchor in enumerate(("bottom-left", "center-right", "center-right", "top-center", "top-center"))
        ]
        self._xi = np.linspace(0.0, 1.0, SEGMENTS + 1)
        self._points = np.zeros((2 * SEGMENTS, 2, 3), np.float32)

    def camera_view(self):
        L = self._length
        return (1.25 * L, -2.3 * L, 0.55 * L), (1.25 * L, 0.0, 0.0)

    # -- parameters ------------------------------------------------------------------------------
    def update(self) -> None:
        params = self.params
        self.ritz = physics.RitzCantilever.from_params(params)
        self.mode = params["mode"]
        self.amplitude = params["amplitude_m"]
        beam = self.ritz.beam
        L = self._length = beam.length_m
        self.t_s = 0.0
        self.exact_omega = float(self.ritz.exact_omega_rad_s[self.mode - 1])
        self.slow_motion = self.exact_omega / (2.0 * math.pi * SHOWN_HZ)
        self.available = self.ritz.mode_available(self.mode)
        self.ritz_omega = float(self.ritz.ritz_omega_rad_s[self.mode - 1]) if self.available else math.nan
        self._ritz_shape = (
            self.amplitude * self.ritz.ritz_shape(self.mode, self._xi) if self.available else np.zeros_like(self._xi)
        )
        self._exact_shape = self.amplitude * beam.exact_shape(self.mode, self._xi)
        exact_shape_unit = beam.exact_shape(self.mode, self._xi)
        self.shape_error = (
            float(np.max(np.abs(self.ritz.ritz_shape(self.mode, self._xi) - exact_shape_unit)))
            if self.available
            else math.nan
        )
        x = L * self._xi
        y_exact = -EXACT_OFFSET * L
        self._x_pairs = np.stack([x[:-1], x[1:]], axis=1)
        self._points[:, :, 0] = np.concatenate([self._x_pairs, self._x_pairs])
        self._points[SEGMENTS:, :, 1] = y_exact
        self.axes.points = np.array([[[0, 0, 0], [L, 0, 0]], [[0, y_exact, 0], [L, y_exact, 0]]], np.float32)
        height = max(0.4 * L, 2.4 * self.amplitude)
        self.clamp.dimensions = (0.04 * L, (EXACT_OFFSET + 0.2) * L, height)
        self.clamp.position = (-0.02 * L, 0.5 * y_exact, 0.0)
        basis = "orthogonal" if params["basis"] == "orthogonal" else "monomials"
        ritz_text = (
            f"Ritz, {self.ritz.terms} {basis}: ω{self.mode} = {self.ritz_omega:.6g} rad/s"
            if self.available
            else f"Ritz mode {self.mode}: no real frequency"
        )
        self.ritz_label.text = ritz_text
        self.ritz_label.position = (0.3 * L, 0.0, 1.1 * self.amplitude + 0.05 * L)
        self.exact_label.text = f"exact: ω{self.mode} = {self.exact_omega:.6g} rad/s"
        self.exact_label.position = (0.3 * L, y_exact, -1.1 * self.amplitude - 0.05 * L)
        self._draw_chart()
        self._draw()

    def _draw_chart(self) -> None:
        """log₁₀|relative error| of the chosen mode against N for both bases, in the XZ plane right of the beam."""
        L, mode = self._length, self.mode
        left, width, bottom, height = 1.35 * L, 1.2 * L, -0.6 * L, 1.2 * L

        def place(terms: np.ndarray, log_error: np.ndarray) -> np.ndarray:
            u = (terms - 1.0) / (physics.MAX_TERMS - 1.0)
            v = (np.clip(log_error, ERROR_FLOOR_LOG10, 0.0) - ERROR_FLOOR_LOG10) / -ERROR_FLOOR_LOG10
            return np.stack([left + width * u, np.zeros_like(u), bottom + height * v], axis=-1)

        segments = [
            np.array([[[left, 0, bottom], [left + width, 0, bottom]], [[left, 0, bottom], [left, 0, bottom + height]]]),
        ]
        colors = [np.full((2, 2, 3), AXIS_COLOR)]
        marks = []
        for basis, color in zip(physics.BASES, (RITZ_COLOR, MONOMIAL_COLOR)):  # orthogonal, then monomial
            rows = [row for row in physics.convergence_table(self.ritz.beam, basis=basis) if row.terms >= mode]
            terms = np.array([row.terms for row in rows], dtype=float)
            errors = np.array([row.relative_error[mode - 1] for row in rows])
            shown = np.log10(np.maximum(np.abs(np.nan_to_num(errors, nan=1.0)), 10.0**ERROR_FLOOR_LOG10))
            points = place(terms, shown)
            if len(points) > 1:
                segments.append(np.stack([points[:-1], points[1:]], axis=1))
                colors.append(np.full((len(points) - 1, 2, 3), color))
            broken = ~np.isfinite(errors) | (errors < -physics.BOUND_SLACK)
            marks.append(points[broken])
        here = place(np.array([float(self.ritz.terms)]), np.array([ERROR_FLOOR_LOG10]))[0]
        ring = circle_segments(radius=0.03 * L, center=tuple(here), normal=(0.0, 1.0, 0.0), segments=16)
        segments.append(ring)
        colors.append(np.full((len(ring), 2, 3), (60, 60, 60)))
        self.chart.points = np.concatenate(segments).astype(np.float32)
        self.chart.colors = np.concatenate(colors).astype(np.uint8)
        broken_points = np.concatenate(marks)
        self.chart_marks.points = (broken_points if len(broken_points) else np.array([[left, 0.0, bottom]])).astype(
            np.float32
        )
        self.chart_marks.point_size = 0.035 * L
        self.chart_marks.visible = len(broken_points) > 0
        texts = (
            (
                f"error of ω{mode} against N (log): blue orthogonal, red monomial",
                (left, 0.0, bottom + height + 0.05 * L),
            ),
            ("1", (left - 0.03 * L, 0.0, bottom + height)),
            ("1e-16", (left - 0.03 * L, 0.0, bottom)),
            ("N = 1", (left, 0.0, bottom - 0.04 * L)),
            (f"N = {physics.MAX_TERMS}", (left + width, 0.0, bottom - 0.04 * L)),
        )
        for label, (text, position) in zip(self.chart_labels, texts, strict=True):
            label.text, label.position = text, position

    # -- animation -------------------------------------------------------------------------------
    def step_motion(self, dt_s: float) -> bool:
        """Beam time runs ``slow_motion`` times slower than the wall clock."""
        self.t_s += dt_s / self.slow_motion
        return True

    def step_without_drawing(self, t_s: float) -> None:
        """A closed form: the beam at beam time ``t_s`` (s)."""
        self.t_s = t_s

    def _draw(self) -> None:
        exact = self._exact_shape * math.cos(self.exact_omega * self.t_s)
        ritz = self._ritz_shape * math.cos(self.ritz_omega * self.t_s) if self.available else self._ritz_shape
        points = self._points
        points[:SEGMENTS, 0, 2], points[:SEGMENTS, 1, 2] = ritz[:-1], ritz[1:]
        points[SEGMENTS:, 0, 2], points[SEGMENTS:, 1, 2] = exact[:-1], exact[1:]
        update_node(self.beams, points=points)

    def readout(self) -> Readout:
        ritz = self.ritz
        quantities = [
            Quantity("t_s", "beam time t (slowed)", self.t_s, "s"),
            Quantity(
                "slow_motion",
                f"time shown slowed by (exact mode {self.mode} at {SHOWN_HZ:g} Hz)",
                self.slow_motion,
                "×",
            ),
        ]
        for index in range(ritz.terms):
            n = index + 1
            omega, exact = float(ritz.ritz_omega_rad_s[index]), float(ritz.exact_omega_rad_s[index])
            ritz_text = (
                f"{omega / (2.0 * math.pi):.6g} Hz" if math.isfinite(omega) else "imaginary: ω² < 0 from rounding"
            )
            quantities += [
                Quantity(f"omega_ritz_{n}_rad_s", f"ω{n} Ritz", omega, "rad/s", ritz_text),
                Quantity(f"omega_exact_{n}_rad_s", f"ω{n} exact", exact, "rad/s", f"{exact / (2.0 * math.pi):.6g} Hz"),
                Quantity.or_text(
                    f"relative_error_{n}",
                    f"ω{n} relative error (Ritz − exact)/exact",
                    float(ritz.relative_error[index]),
                    "",
                    "undefined",
                ),
            ]
        quantities += [
            Quantity("condition_number_M", f"cond(M), {ritz.basis.name} basis", ritz.modes.condition_mass, ""),
            Quantity("rounding_estimate", "u·cond(M): rounding's reach (relative)", ritz.rounding_estimate, ""),
            Quantity.or_text(
                "shape_error",
                f"largest |w_Ritz − w_exact| of mode {self.mode} (unit tip)",
                self.shape_error,
                "",
                "no Ritz mode",
            ),
        ]
        warning = ritz.warning()
        message = (
            f"Warning: {warning}"
            if warning
            else (
                "Every Ritz frequency is above the exact one (Rayleigh–Ritz upper bound); cond(M) = "
                f"{ritz.modes.condition_mass:.2g} "
                f"costs at most about {max(0.0, math.log10(ritz.modes.condition_mass)):.0f} of the 16 digits."
            )
        )
        return Readout(quantities, message=message)
