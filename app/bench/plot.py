"""Work-precision diagrams as standalone SVG, written with the standard library only.

One diagram per benchmark scene (one entry of ``scenes`` in
``docs/bench/work_precision.json``). Both axes are logarithmic:

* x: the scene's error measure, in the scene's ``error_unit``;
* y: CPU time for the whole run (``t_end_s`` of simulated motion), in ms.

That is the usual orientation (error across, cost up), so the lower-left corner
is better, a vertical gap is the cost ratio at equal error and a horizontal gap
the accuracy ratio at equal cost. A method of order p traces a line of slope
about -1/p, so higher order shows as a *flatter* line.

Points whose error or CPU time is zero, negative or not finite, or whose
``status`` is present and not ``"ok"``, are left out of the lines (a log axis
has no place for them and a failed run has no meaningful error).

The SVG uses presentation attributes only (no ``<style>``, no ids), so it can be
served as a file, shown with ``<img>``, or pasted inline into a page.
"""

from __future__ import annotations

import json
import math
import sys
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any, TypeGuard
from xml.sax.saxutils import escape, quoteattr

SVG_NS = "http://www.w3.org/2000/svg"

# Layout in SVG user units (px at 100 %).
WIDTH, HEIGHT = 760, 480
PLOT_LEFT, PLOT_RIGHT = 76, 532
PLOT_TOP, PLOT_BOTTOM = 72, 420
LEGEND_X = 548
FONT = "system-ui, -apple-system, 'Segoe UI', Roboto, 'DejaVu Sans', sans-serif"

FAMILY_ORDER = ("dynlab", "scipy", "mujoco")
FAMILY_NAMES = {"dynlab": "Dynamics Lab", "scipy": "SciPy", "mujoco": "MuJoCo"}
# dynlab: strong, saturated; scipy: greys and muted blues; mujoco: oranges; anything else: browns.
PALETTES = {
    "dynlab": ("#d0202e", "#1b8a3a", "#7b2fa8", "#c2185b", "#00796b", "#5d4037"),
    "scipy": ("#4f6d8f", "#7d8894", "#2f4b6e", "#8fa7c4", "#4a4f57", "#6f86a8"),
    "mujoco": ("#e67e00", "#b85c00", "#f2a444", "#cc6d1f"),
    "other": ("#8d6e63", "#a1887f", "#6d4c41"),
}
DASHES = {"dynlab": None, "scipy": "7 4", "mujoco": "2 3 8 3", "other": "3 3"}
STROKE_WIDTH = {"dynlab": 2.6, "scipy": 1.8, "mujoco": 2.0, "other": 1.8}
MARKERS = ("circle", "square", "triangle", "diamond", "triangle-down", "pentagon", "plus", "cross", "star", "hexagon")


def _finite_positive(value: Any) -> TypeGuard[float]:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value) and value > 0


def usable_points(method: dict) -> list[dict]:
    """The points of one method that can go on the log-log diagram, in the order given."""
    return [
        p
        for p in method.get("points") or ()
        if p.get("status", "ok") == "ok" and _finite_positive(p.get("error")) and _finite_positive(p.get("cpu_s"))
    ]


def decade_range(values: Iterable[float]) -> tuple[int, int]:
    """Whole decades [lo, hi] (as exponents) that contain every positive value; at least one decade wide."""
    logs = [math.log10(v) for v in values if _finite_positive(v)]
    if not logs:
        return (-1, 0)
    lo, hi = math.floor(min(logs) + 1e-9), math.ceil(max(logs) - 1e-9)
    if hi <= lo:
        hi = lo + 1
    return lo, hi


def tick_label(exponent: int) -> str:
    """``1e-6`` style, plain decimals from 0.01 to 1000."""
    if -2 <= exponent <= 3:
        return f"{10.0**exponent:.{max(0, -exponent)}f}"
    return f"1e{exponent}"


def _value_label(value: float) -> str:
    """A short ASCII label for a number on the diagram: ``1e-6``, ``2.5e-7``, ``0.3``, ``12``."""
    if value == 0 or not math.isfinite(value):
        return str(value)
    exponent = math.floor(math.log10(abs(value)))
    if -2 <= exponent <= 3:
        return f"{value:.3g}"
    mantissa = f"{value / 10.0**exponent:.2g}"
    return f"1e{exponent}" if mantissa == "1" else f"{mantissa}e{exponent}"


class _Axis:
    def __init__(self, lo_exp: int, hi_exp: int, start: float, end: float) -> None:
        self.lo, self.hi, self.start, self.end = lo_exp, hi_exp, start, end

    def __call__(self, value: float) -> float:
        return self.start + (math.log10(value) - self.lo) / (self.hi - self.lo) * (self.end - self.start)


def _f(v: float) -> str:
    return f"{v:.2f}".rstrip("0").rstrip(".")


def _vline(x: float, color: str) -> str:
    return f'<line x1="{_f(x)}" x2="{_f(x)}" y1="{PLOT_TOP}" y2="{PLOT_BOTTOM}" stroke="{color}" stroke-width="1"/>'


def _hline(y: float, color: str) -> str:
    return f'<line x1="{PLOT_LEFT}" x2="{PLOT_RIGHT}" y1="{_f(y)}" y2="{_f(y)}" stroke="{color}" stroke-width="1"/>'


def _marker(shape: str, x: float, y: float, color: str, filled: bool, size: float = 5.0) -> str:
    fill = color if filled else "#ffffff"
    common = f'fill="{fill}" stroke="{color}" stroke-width="1.6"'
    s = size
    if shape == "circle":
        return f'<circle cx="{_f(x)}" cy="{_f(y)}" r="{_f(s)}" {common}/>'
    if shape == "square":
        side = _f(1.8 * s)
        return f'<rect x="{_f(x - s * 0.9)}" y="{_f(y - s * 0.9)}" width="{side}" height="{side}" {common}/>'
    if shape in ("plus", "cross"):
        r = s * 1.15
        if shape == "plus":
            d = f"M{_f(x - r)} {_f(y)}H{_f(x + r)}M{_f(x)} {_f(y - r)}V{_f(y + r)}"
        else:
            d = f"M{_f(x - r)} {_f(y - r)}L{_f(x + r)} {_f(y + r)}M{_f(x - r)} {_f(y + r)}L{_f(x + r)} {_f(y - r)}"
        return f'<path d="{d}" fill="none" stroke="{color}" stroke-width="2.4"/>'
    polygons = {
        "triangle": (3, -90.0, 1.25, None),
        "triangle-down": (3, 90.0, 1.25, None),
        "diamond": (4, -90.0, 1.3, None),
        "pentagon": (5, -90.0, 1.1, None),
        "hexagon": (6, 0.0, 1.05, None),
        "star": (5, -90.0, 1.35, 0.5),
    }
    n, phase, scale, inner = polygons[shape]
    vertices = []
    steps = 2 * n if inner else n
    for k in range(steps):
        radius = s * scale * (inner if inner and k % 2 else 1.0)
        angle = math.radians(phase + k * 360.0 / steps)
        vertices.append(f"{_f(x + radius * math.cos(angle))},{_f(y + radius * math.sin(angle))}")
    return f'<polygon points="{" ".join(vertices)}" {common}/>'


def _wrap(text: str, width: int) -> list[str]:
    lines: list[str] = []
    current = ""
    for word in text.split():
        if current and len(current) + 1 + len(word) > width:
            lines.append(current)
            current = word
        else:
            current = f"{current} {word}" if current else word
    if current:
        lines.append(current)
    return lines or [""]


def _text(
    x: float,
    y: float,
    content: str,
    *,
    size: int = 12,
    anchor: str = "start",
    weight: str | None = None,
    fill: str = "#1d2330",
    halo: bool = False,
    extra: str = "",
) -> str:
    attrs = f'x="{_f(x)}" y="{_f(y)}" font-size="{size}" fill="{fill}"'
    if anchor != "start":
        attrs += f' text-anchor="{anchor}"'
    if weight:
        attrs += f' font-weight="{weight}"'
    if halo:
        attrs += ' stroke="#ffffff" stroke-width="4" stroke-linejoin="round" paint-order="stroke"'
    if extra:
        attrs += " " + extra
    return f"<text {attrs}>{escape(content)}</text>"


def _place_label(
    x: float, y: float, lines: list[str], obstacles: list[list[tuple[float, float]]], guide_x: float | None = None
) -> tuple[float, float, str, str]:
    """Where to put a label for the point (x, y): the nearby spot inside the plot that covers the least data.

    Crossing the vertical guide line at ``guide_x`` is allowed but mildly penalised (the text has a white halo).
    Returns the text anchor point (first baseline), the text-anchor and a leader line (SVG) if the label sits away
    from the point."""
    width = 7.3 * max(len(line) for line in lines) + 4
    height = 15 * len(lines) + 2
    samples = []
    for line in obstacles:
        if len(line) == 1:
            samples.append(line[0])
        for (x1, y1), (x2, y2) in zip(line, line[1:]):
            n = max(2, int(math.hypot(x2 - x1, y2 - y1) / 4))
            samples.extend((x1 + (x2 - x1) * t / n, y1 + (y2 - y1) * t / n) for t in range(n + 1))
    best = None
    for distance in (14, 34, 60, 95):
        for ux, uy in ((-1, 1), (1, 1), (-1, -1), (1, -1), (-1, 0), (1, 0), (0, 1), (0, -1)):
            cx, cy = x + ux * distance, y + uy * distance  # the box corner/edge nearest the point
            left = cx - width if ux < 0 else cx if ux > 0 else cx - width / 2
            top = cy if uy > 0 else cy - height if uy < 0 else cy - height / 2
            inside = PLOT_LEFT + 3 <= left and left + width <= PLOT_RIGHT - 3
            if not inside or top < PLOT_TOP + 20 or top + height > PLOT_BOTTOM - 3:
                continue
            right, bottom = left + width, top + height
            covered = sum(1 for px, py in samples if left - 3 <= px <= right + 3 and top - 3 <= py <= bottom + 3)
            crosses_guide = guide_x is not None and left - 3 <= guide_x <= left + width + 3
            score = 100 * covered + distance + (25 if crosses_guide else 0)
            if best is None or score < best[0]:
                best = (score, left, top, distance, ux)
    if best is None:  # no room anywhere: right of the point, clipped by nothing
        return x + 16, y + 4, "start", ""
    _, left, top, distance, ux = best
    anchor = "end" if ux < 0 else "start" if ux > 0 else "middle"
    tx = left + width - 2 if ux < 0 else left + 2 if ux > 0 else left + width / 2
    leader = ""
    if distance > 14:
        # from the ring's edge towards the nearest point of the label box
        nx, ny = min(max(x, left), left + width), min(max(y, top), top + height)
        d = math.hypot(nx - x, ny - y) or 1.0
        leader = (
            f'<line x1="{_f(x + 14 * (nx - x) / d)}" y1="{_f(y + 14 * (ny - y) / d)}" x2="{_f(nx)}" y2="{_f(ny)}" '
            'stroke="#1d2330" stroke-width="1"/>'
        )
    return tx, top + 12, anchor, leader


def _family(method: dict) -> str:
    family = str(method.get("family", "other")).lower()
    return family if family in PALETTES else "other"


def ordered_methods(scene: dict) -> list[dict]:
    """Methods grouped by family (dynlab, scipy, mujoco, others), keeping the given order within a family."""
    methods = list(scene.get("methods") or ())
    rank = {f: i for i, f in enumerate(FAMILY_ORDER)}
    return sorted(methods, key=lambda m: rank.get(_family(m), len(FAMILY_ORDER)))


def work_precision_svg(scene: dict) -> str:
    """One log-log work-precision diagram (error across, CPU time up) for one benchmark scene."""
    methods = ordered_methods(scene)
    title = str(scene.get("title") or scene.get("scene_id") or "Work-precision diagram")
    unit = str(scene.get("error_unit") or "").strip()
    unit_suffix = f" {unit}" if unit else ""
    target = scene.get("target_error")
    target = target if _finite_positive(target) else None
    default = scene.get("default") or {}
    default_ok = _finite_positive(default.get("error")) and _finite_positive(default.get("cpu_s"))

    usable = {id(m): usable_points(m) for m in methods}
    errors = [p["error"] for pts in usable.values() for p in pts]
    times_ms = [1e3 * p["cpu_s"] for pts in usable.values() for p in pts]
    if target is not None:
        errors.append(target)
    if default_ok:
        errors.append(default["error"])
        times_ms.append(1e3 * default["cpu_s"])
    ax = _Axis(*decade_range(errors), PLOT_LEFT, PLOT_RIGHT)
    ay = _Axis(*decade_range(times_ms), PLOT_BOTTOM, PLOT_TOP)

    out: list[str] = [
        f'<svg xmlns="{SVG_NS}" width="{WIDTH}" height="{HEIGHT}" viewBox="0 0 {WIDTH} {HEIGHT}" '
        f'role="img" font-family="{FONT}">',
        f"<title>{escape(title)}: work-precision diagram, error{escape(f' ({unit})' if unit else '')} "
        "against CPU time (ms), both on log scales</title>",
        f'<rect x="0" y="0" width="{WIDTH}" height="{HEIGHT}" fill="#ffffff"/>',
        _text(PLOT_LEFT, 24, title, size=17, weight="600"),
    ]
    subtitle_bits = []
    if scene.get("error_measure"):
        subtitle_bits.append(f"Error: {scene['error_measure']}")
    if scene.get("reference"):
        subtitle_bits.append(f"reference: {scene['reference']}")
    if subtitle_bits:
        lines = _wrap("; ".join(subtitle_bits), 104)
        if len(lines) > 2:
            lines = [lines[0], lines[1][:102].rstrip() + "…"]
        out.extend(_text(PLOT_LEFT, 44 + 15 * i, line, size=12, fill="#5b6475") for i, line in enumerate(lines))

    # Grid: minor lines at 2..9 x 10^k when there are few decades, decade lines, tick labels.
    grid: list[str] = []
    labels: list[str] = []
    for axis, vertical in ((ax, True), (ay, False)):
        decades = axis.hi - axis.lo
        label_every = max(1, math.ceil(decades / (8 if vertical else 7)))
        grid_line = _vline if vertical else _hline
        if decades <= 8:
            grid.extend(grid_line(axis(m * 10.0**k), "#eef0f4") for k in range(axis.lo, axis.hi) for m in range(2, 10))
        for k in range(axis.lo, axis.hi + 1):
            c = axis(10.0**k)
            grid.append(grid_line(c, "#d5dae3"))
            if (k - axis.lo) % label_every == 0:
                labels.append(
                    _text(c, PLOT_BOTTOM + 18, tick_label(k), anchor="middle")
                    if vertical
                    else _text(PLOT_LEFT - 7, c + 4, tick_label(k), anchor="end")
                )
    out.append('<g class="grid">' + "".join(grid) + "</g>")
    out.append(
        f'<rect x="{PLOT_LEFT}" y="{PLOT_TOP}" width="{PLOT_RIGHT - PLOT_LEFT}" height="{PLOT_BOTTOM - PLOT_TOP}" '
        'fill="none" stroke="#9aa3b2"/>'
    )
    out.append('<g class="ticks">' + "".join(labels) + "</g>")

    x_title = f"Error ({unit}), log scale" if unit else "Error, log scale"
    out.append(_text((PLOT_LEFT + PLOT_RIGHT) / 2, PLOT_BOTTOM + 42, x_title, size=13, anchor="middle", weight="600"))
    t_end = scene.get("t_end_s")
    y_title = (
        f"CPU time for {_value_label(float(t_end))} s of motion (ms), log scale"
        if _finite_positive(t_end)
        else "CPU time per run (ms), log scale"
    )
    cy = (PLOT_TOP + PLOT_BOTTOM) / 2
    rotate = f'transform="rotate(-90 20 {_f(cy)})"'
    out.append(_text(20, cy, y_title, size=13, anchor="middle", weight="600", extra=rotate))

    obstacles: list[list[tuple[float, float]]] = []  # polylines the default's label should not cover
    # Target error: dashed vertical line with a label at its top.
    if target is not None:
        tx = ax(target)
        out.append(
            f'<g class="target"><line x1="{_f(tx)}" x2="{_f(tx)}" y1="{PLOT_TOP}" y2="{PLOT_BOTTOM}" '
            'stroke="#1d2330" stroke-width="1.4" stroke-dasharray="6 4"/>'
        )
        label = f"target {_value_label(target)}{unit_suffix}"
        right_room = PLOT_RIGHT - tx > 7.2 * len(label) + 10
        anchor = "start" if right_room else "end"
        out.append(_text(tx + (5 if right_room else -5), PLOT_TOP + 15, label, anchor=anchor, halo=True) + "</g>")

    # One line and one marker shape per method, coloured by family.
    # Legend: up to three lines per label, or one (shortened) line each when that would not fit.
    full_height = sum(15 * min(3, len(_wrap(str(m.get("label") or m.get("method")), 25))) + 7 for m in methods)
    full_height += 24 * len({_family(m) for m in methods})
    compact_legend = full_height > HEIGHT - PLOT_TOP - 10
    used_colors = {f: 0 for f in PALETTES}
    legend: list[str] = []
    legend_y = PLOT_TOP + 4
    last_family = None
    label_for_default = None
    setting_name_for_default = None
    for index, method in enumerate(methods):
        family = _family(method)
        palette = PALETTES[family]
        color = palette[used_colors[family] % len(palette)]
        used_colors[family] += 1
        shape = MARKERS[index % len(MARKERS)]
        filled = family != "scipy"
        pts = usable[id(method)]
        coords = [(ax(p["error"]), ay(1e3 * p["cpu_s"])) for p in pts]
        obstacles.append(coords)
        name = str(method.get("method", f"method {index + 1}"))
        label = str(method.get("label") or name)
        if name == default.get("method"):
            label_for_default = label
            setting_name_for_default = method.get("setting_name")
        series = [f'<g class="series" data-method={quoteattr(name)} data-family={quoteattr(family)}>']
        if len(coords) >= 2:
            dash = f' stroke-dasharray="{DASHES[family]}"' if DASHES[family] else ""
            series.append(
                f'<polyline points="{" ".join(f"{_f(x)},{_f(y)}" for x, y in coords)}" fill="none" stroke="{color}" '
                f'stroke-width="{STROKE_WIDTH[family]}" stroke-linejoin="round"{dash}/>'
            )
        series.extend(_marker(shape, x, y, color, filled) for x, y in coords)
        series.append("</g>")
        out.append("".join(series))

        # Legend entry (family heading when the family changes).
        if family != last_family:
            if last_family is not None:
                legend_y += 6
            heading = FAMILY_NAMES.get(family, "Other")
            legend.append(_text(LEGEND_X, legend_y + 4, heading, weight="700", fill="#5b6475"))
            legend_y += 18
            last_family = family
        dash = f' stroke-dasharray="{DASHES[family]}"' if DASHES[family] else ""
        legend.append(
            f'<line x1="{LEGEND_X}" x2="{LEGEND_X + 28}" y1="{legend_y}" y2="{legend_y}" stroke="{color}" '
            f'stroke-width="{STROKE_WIDTH[family]}"{dash}/>'
        )
        legend.append(_marker(shape, LEGEND_X + 14, legend_y, color, filled, size=4.5))
        lines = _wrap(label, 25)[:3] if pts else _wrap(label, 25)[:2] + ["(no valid points)"]
        if compact_legend:
            lines = [label if len(label) <= 26 else label[:25] + "…"]
        for j, line in enumerate(lines):
            note = not pts and j == len(lines) - 1
            legend.append(_text(LEGEND_X + 36, legend_y + 4 + 15 * j, line, fill="#5b6475" if note else "#1d2330"))
        legend_y += 15 * len(lines) + 7
    out.append('<g class="legend">' + "".join(legend) + "</g>")

    out.append(_ratio_marks(scene, ax))

    # The default method's operating point: a ring and a label.
    if default_ok:
        dx, dy = ax(default["error"]), ay(1e3 * default["cpu_s"])
        lines = [f"default: {label_for_default or default.get('method', '')}"]
        setting = default.get("setting")
        if setting is not None:
            setting_text = _value_label(float(setting)) if isinstance(setting, float) else str(setting)
            lines.append(f"{str(setting_name_for_default or 'setting').replace('_', ' ')} = {setting_text}")
        x0, y0, anchor, leader = _place_label(dx, dy, lines, obstacles, ax(target) if target is not None else None)
        out.append(
            '<g class="default">'
            f'<circle cx="{_f(dx)}" cy="{_f(dy)}" r="11" fill="none" stroke="#1d2330" stroke-width="2.2"/>'
            f'<circle cx="{_f(dx)}" cy="{_f(dy)}" r="14" fill="none" stroke="#ffb000" stroke-width="2"/>'
            + leader
            + "".join(
                _text(x0, y0 + 15 * i, line, anchor=anchor, weight="600" if i == 0 else None, halo=True)
                for i, line in enumerate(lines)
            )
            + "</g>"
        )

    out.append("</svg>")
    return "\n".join(out) + "\n"


#: File name of the phase-against-drift figure (fixed: never taken from the results file).
PHASE_DRIFT_PLOT = "heavy-top-phase-drift.svg"
_BASELINE_SHORT = {"scipy-DOP853": "DOP853", "mujoco-RK4": "MuJoCo RK4"}


def _ratio_marks(scene: dict, ax: _Axis) -> str:
    """At each error of the scene's best-of-ours ratios (entries with ``required_ratio``): a dotted line and the ratios.

    The label reads e.g. ``DOP853 ×250`` / ``MuJoCo RK4 ×40``: their CPU time over that of the cheapest of ours
    at that error, red when below the ratio asked for; drawn near the top of the plot, where only the slowest
    curves run.
    """
    by_error: dict[float, list[dict]] = {}
    for ratio in scene.get("ratios") or ():
        if isinstance(ratio, dict) and "required_ratio" in ratio and _finite_positive(ratio.get("at_error")):
            by_error.setdefault(float(ratio["at_error"]), []).append(ratio)
    parts = ['<g class="ratios">']
    for error, ratios in sorted(by_error.items(), reverse=True):
        x = ax(error)
        if not PLOT_LEFT <= x <= PLOT_RIGHT:
            continue
        parts.append(
            f'<line x1="{_f(x)}" x2="{_f(x)}" y1="{PLOT_TOP + 24}" y2="{PLOT_BOTTOM}" stroke="#7b2fa8" '
            'stroke-width="1" stroke-dasharray="1 3"/>'
        )
        parts.append(
            _text(x, PLOT_TOP + 34, f"at {_value_label(error)}:", size=10, anchor="middle", fill="#7b2fa8", halo=True)
        )
        for i, ratio in enumerate(ratios):
            value = ratio.get("ratio")
            name = _BASELINE_SHORT.get(str(ratio.get("baseline")), str(ratio.get("baseline")))
            ok = _finite_positive(value) and value >= float(ratio.get("required_ratio") or 0.0)
            text = f"{name} ×{value:.0f}" if _finite_positive(value) else f"{name} —"
            parts.append(
                _text(
                    x,
                    PLOT_TOP + 47 + 12 * i,
                    text,
                    size=10,
                    anchor="middle",
                    weight="600",
                    fill="#1b6b2f" if ok else "#d0202e",
                    halo=True,
                )
            )
    parts.append("</g>")
    return "".join(parts) if len(parts) > 2 else ""


def phase_drift_svg(study: dict) -> str:
    """Two bars per method (log scale): the largest relative energy drift and the largest attitude error (rad).

    ``study`` is ``phase_drift`` of work_precision.json: ``methods`` rows with ``label``, ``description``,
    ``energy_drift`` and ``attitude_error_rad``. A method whose energy bar is short but whose error bar is
    long keeps its invariants while its phase is wrong.
    """
    rows = [r for r in study.get("methods") or () if isinstance(r, dict)]
    left, right, top, row_h = 230, WIDTH - 40, 92, 46
    height = top + row_h * len(rows) + 64
    values = [v for r in rows for v in (r.get("energy_drift"), r.get("attitude_error_rad")) if _finite_positive(v)]
    lo, hi = decade_range(values + [1e-16, 1.0])
    axis = _Axis(lo, hi, left, right)
    colours = {"energy_drift": "#7d8894", "attitude_error_rad": "#d0202e"}
    out = [
        f'<svg xmlns="{SVG_NS}" width="{WIDTH}" height="{height}" viewBox="0 0 {WIDTH} {height}" role="img" '
        f'font-family="{FONT}">',
        f"<title>{escape(str(study.get('title', 'Energy drift beside attitude error')))}</title>",
        f'<rect width="{WIDTH}" height="{height}" fill="#ffffff"/>',
        _text(16, 26, str(study.get("title", "Energy drift beside attitude error")), size=16, weight="600"),
        _text(
            16,
            44,
            "Grey: largest relative energy drift |E(t) − E(0)|/|E(0)|. Red: largest attitude error (rad) against the",
            size=11,
            fill="#5b6475",
        ),
        _text(
            16,
            58,
            "exact (quadrature) solution, at 60 frames/s; under each name its step (auto: what a live scene "
            "picks). Log scale.",
            size=11,
            fill="#5b6475",
        ),
    ]
    for k in range(lo, hi + 1):
        x = axis(10.0**k)
        out.append(
            f'<line x1="{_f(x)}" x2="{_f(x)}" y1="{top - 8}" y2="{top + row_h * len(rows)}" stroke="#e3e6ec" '
            'stroke-width="1"/>'
        )
        if (k - lo) % 2 == 0:
            out.append(_text(x, top + row_h * len(rows) + 18, tick_label(k), size=11, anchor="middle"))
    for i, row in enumerate(rows):
        y = top + i * row_h
        out.append(
            _text(left - 8, y + 16, str(row.get("label") or row.get("method")), size=12, anchor="end", weight="600")
        )
        out.append(
            _text(left - 8, y + 31, str(row.get("setting_text") or "")[:34], size=11, anchor="end", fill="#5b6475")
        )
        for j, key in enumerate(("energy_drift", "attitude_error_rad")):
            value = row.get(key)
            bar_y = y + 4 + 17 * j
            if not _finite_positive(value):
                out.append(_text(left + 4, bar_y + 11, "0 (round-off)" if value == 0 else "—", size=11))
                continue
            width = max(axis(value) - left, 1.0)
            out.append(f'<rect x="{left}" y="{bar_y}" width="{_f(width)}" height="14" fill="{colours[key]}"/>')
            unit = " rad" if key == "attitude_error_rad" else ""
            out.append(_text(left + width + 5, bar_y + 11, f"{_value_label(float(value))}{unit}", size=11))
    out.append(
        _text(
            (left + right) / 2,
            top + row_h * len(rows) + 40,
            "relative drift (grey), error in rad (red), log scale",
            size=12,
            anchor="middle",
            weight="600",
        )
    )
    out.append("</svg>")
    return "\n".join(out) + "\n"


#: Physics time one displayed frame may take (µs): a fraction of the 33 ms frame that leaves room for 100 students on
#: two cores.
FRAME_BUDGET_US = 50.0


def frame_cost_svg(live_scenes: Sequence[dict]) -> str:
    """A bar per animated scene: physics µs per displayed frame (linear axis) against :data:`FRAME_BUDGET_US`."""
    rows = sorted(live_scenes, key=lambda s: -float(s["physics_us_per_frame"]))
    row_h, left, right, top = 22, 210, 590, 64  # room right of the longest bar for its label
    height = top + row_h * len(rows) + 56
    top_value = max([FRAME_BUDGET_US * 1.2, *(float(s["physics_us_per_frame"]) for s in rows)])
    x = lambda v: left + (right - left) * v / top_value  # noqa: E731
    out = [
        f'<svg xmlns="{SVG_NS}" width="{WIDTH}" height="{height}" viewBox="0 0 {WIDTH} {height}" '
        f'font-family="{escape(FONT)}">',
        f'<rect width="{WIDTH}" height="{height}" fill="#ffffff"/>',
        _text(16, 28, "Physics time per displayed frame, each animated scene at its defaults", size=15, weight="600"),
        _text(
            16,
            46,
            "µs of CPU per frame at 30 frames/s: the physics share of a closed-form scene's frame (profiled), "
            "one frame of an integrated live run",
            size=11,
            fill="#555",
        ),
    ]
    for i, scene in enumerate(rows):
        value = float(scene["physics_us_per_frame"])
        y = top + i * row_h
        colour = "#1b8a3a" if value <= FRAME_BUDGET_US else "#d0202e"
        out.append(_text(left - 8, y + 15, str(scene["scene_id"]), size=12, anchor="end"))
        out.append(
            f'<rect x="{left}" y="{y + 4}" width="{_f(max(x(value) - left, 1.0))}" height="{row_h - 8}" '
            f'fill="{colour}"/>'
        )
        out.append(_text(x(value) + 6, y + 15, f"{value:.3g} µs ({scene['method']})", size=11))
    bottom = top + row_h * len(rows)
    budget = x(FRAME_BUDGET_US)
    out.append(
        f'<line x1="{_f(budget)}" x2="{_f(budget)}" y1="{top - 4}" y2="{bottom + 4}" stroke="#d0202e" '
        'stroke-width="1.5" stroke-dasharray="5 3"/>'
    )
    out.append(_text(budget, bottom + 20, f"budget {FRAME_BUDGET_US:g} µs", size=11, anchor="middle", fill="#d0202e"))
    out.append(f'<line x1="{left}" x2="{right}" y1="{bottom + 4}" y2="{bottom + 4}" stroke="#888" stroke-width="1"/>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def write_svgs(results: dict, out_dir: Path) -> list[Path]:
    """Write ``<scene_id>.svg`` for every scene of a work_precision.json document; returns the paths."""
    out_dir.mkdir(parents=True, exist_ok=True)
    written = []
    for scene in results.get("scenes", ()):
        path = out_dir / f"{scene['scene_id']}.svg"
        path.write_text(work_precision_svg(scene), encoding="utf-8")
        written.append(path)
    study = results.get("phase_drift")
    if isinstance(study, dict) and study.get("methods"):
        path = out_dir / PHASE_DRIFT_PLOT
        path.write_text(phase_drift_svg(study), encoding="utf-8")
        written.append(path)
    if results.get("live_scenes"):
        path = out_dir / "live-frame-costs.svg"
        path.write_text(frame_cost_svg(results["live_scenes"]), encoding="utf-8")
        written.append(path)
    return written


def main(argv: Sequence[str] | None = None) -> int:
    """``python -m app.bench.plot work_precision.json [out_dir]``: redraw the SVGs from saved results."""
    args = list(sys.argv[1:] if argv is None else argv)
    if not args or len(args) > 2:
        print("usage: python -m app.bench.plot work_precision.json [out_dir]", file=sys.stderr)
        return 2
    source = Path(args[0])
    out_dir = Path(args[1]) if len(args) == 2 else source.parent
    for path in write_svgs(json.loads(source.read_text(encoding="utf-8")), out_dir):
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
