"""The first-frame report (``docs/bench/first_frame.json`` and ``.svg``): how long a lesson takes from opening to its
scene's first frame, before and after the viewer was preloaded, split into where the time goes.

Measured in Chromium by ``tests/browser/test_first_frame_bench.py`` (``DYNLAB_BENCH_FIRST_FRAME=1``); this module
only writes what was measured. Each load's marks are ms after the lesson page's navigation started.
"""

from __future__ import annotations

import json
from pathlib import Path
from xml.sax.saxutils import escape

from app.bench.plot import FONT, SVG_NS, _f, _text

REPORT_FILE = "first_frame.json"
#: A scene's first frame within this long of opening its lesson (ms), on a quiet 2-core machine.
TARGET_MS = 1500.0
WIDTH = 980

#: The phases drawn, in order, as (label, the mark each ends at, colour); a phase runs from the previous mark.
PHASES = (
    ("page painted", "page_paint_ms", "#9aa3b2"),
    ("session made (PUT)", "session_put_end_ms", "#4f6d8f"),
    ("viewer HTML loaded", "viewer_html_ms", "#8fa7c4"),
    ("viser client started", "socket_created_ms", "#e08e0b"),
    ("websocket open", "socket_open_ms", "#7b2fa8"),
    ("scene's first message", "first_message_ms", "#1b8a3a"),
    ("first frame drawn", "first_frame_ms", "#d0202e"),
)


def _bar(y: float, marks: dict, x, height: float) -> list[str]:
    """One load's median marks as consecutive segments (a phase whose mark comes earlier than the last drawn, as the
    preloaded viewer's HTML may before the session exists, starts where it ends: overlapping, not added)."""
    out, start = [], 0.0
    for _label, key, colour in PHASES:
        end = marks.get(key)
        if end is None:
            continue
        if end > start:
            width = _f(x(end) - x(start))
            out.append(f'<rect x="{_f(x(start))}" y="{_f(y)}" width="{width}" height="{height}" fill="{colour}"/>')
            start = end
    return out


def first_frame_svg(report: dict) -> str:
    """Per lesson, a bar before and one after: the median of each mark, with the target as a dashed line."""
    sides = [side for side in ("before", "after") if side in report]
    lessons = [entry["lesson_id"] for entry in report[sides[0]]["lessons"]]
    longest = max(
        [TARGET_MS, *(e["median_ms"].get("first_frame_ms", 0.0) for side in sides for e in report[side]["lessons"])]
    )
    top_ms = 1000.0 * (int(longest // 1000) + 1)
    left, right, top, row_h, bar_h = 230, WIDTH - 40, 84, 26, 18
    height = top + row_h * len(sides) * len(lessons) + 8 * len(lessons) + 90
    x = lambda ms: left + (right - left) * ms / top_ms  # noqa: E731
    out = [
        f'<svg xmlns="{SVG_NS}" width="{WIDTH}" height="{height}" viewBox="0 0 {WIDTH} {height}" '
        f'font-family="{escape(FONT)}">',
        f'<rect width="{WIDTH}" height="{height}" fill="#ffffff"/>',
        _text(
            16,
            28,
            "A lesson's first frame: from opening the page to the viewer's first frame of its scene",
            size=15,
            weight="600",
        ),
        _text(
            16,
            46,
            "Median of each mark over the loads, ms after the page's navigation started; "
            "each load a new browser context (nothing cached, a new scene)",
            size=11,
            fill="#555",
        ),
    ]
    legend_x: float = 16
    for label, _key, colour in PHASES:
        out.append(f'<rect x="{legend_x}" y="58" width="12" height="12" fill="{colour}"/>')
        out.append(_text(legend_x + 16, 68, label, size=11))
        legend_x += 28 + 6.2 * len(label)
    y = top
    for lesson_id in lessons:
        for side in sides:
            entry = next(e for e in report[side]["lessons"] if e["lesson_id"] == lesson_id)
            marks = entry["median_ms"]
            out.append(_text(left - 8, y + 13, f"{lesson_id} ({side})", size=11, anchor="end"))
            out.extend(_bar(y, marks, x, bar_h))
            if "first_frame_ms" in marks:
                first_s = marks["first_frame_ms"] / 1000
                out.append(_text(x(marks["first_frame_ms"]) + 6, y + 13, f"{first_s:.2f} s", size=11))
            y += row_h
        y += 8
    out.append(f'<line x1="{left}" x2="{right}" y1="{y}" y2="{y}" stroke="#888" stroke-width="1"/>')
    for second in range(int(top_ms // 1000) + 1):
        out.append(_text(x(1000.0 * second), y + 16, f"{second} s", size=11, anchor="middle"))
    target = x(TARGET_MS)
    out.append(
        f'<line x1="{_f(target)}" x2="{_f(target)}" y1="{top - 6}" y2="{y + 4}" '
        'stroke="#d0202e" stroke-width="1.5" stroke-dasharray="5 3"/>'
    )
    out.append(_text(target, y + 32, f"target {TARGET_MS / 1000:g} s", size=11, anchor="middle", fill="#d0202e"))
    loads = ", ".join(
        f"{side}: load average {report[side]['load_average_before'][0]:.1f} → "
        f"{report[side]['load_average_after'][0]:.1f}"
        for side in sides
    )
    out.append(_text(16, height - 12, loads, size=11, fill="#555"))
    out.append("</svg>")
    return "\n".join(out) + "\n"


def write_report(report: dict, bench_dir: Path) -> list[Path]:
    """``first_frame.json`` and ``first_frame.svg`` in ``bench_dir``."""
    bench_dir.mkdir(parents=True, exist_ok=True)
    json_path, svg_path = bench_dir / REPORT_FILE, bench_dir / "first_frame.svg"
    json_path.write_text(json.dumps(report, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    svg_path.write_text(first_frame_svg(report), encoding="utf-8")
    return [json_path, svg_path]
