"""``dynlab load --attack``: a class on its own scenes, measured alone and then while one client attacks it.

The tool starts its own ``dynlab serve`` (or uses ``--url`` with ``--instructor-key``), opens a classroom room on
the scene as the instructor (with one projector viewer on the room's shared scene, as in a classroom), and connects
``--students`` students (100), each a lesson page on a heavy-top session of its own: it claims its session
(``PUT`` with its ``X-Session-Key``) and then opens its viewer, from its own loopback address (127.0.1.1, 127.0.1.2,
…). After the warm-up come two steady windows of ``--seconds`` (30 s) each, on the same connected students:

1. **before the attack**: nobody else is on the server;
2. **under attack**: one attacking client (:mod:`app.bench.attacks`, in its own process, from 127.0.0.2) runs
   every attack of items 2–6 of the class-safety issue's "Found" at once, for the whole window.

Each window gives what a capacity step gives (frames/s per student: 10th percentile, median, slowest; server CPU,
memory, health latency, …), counting every student connected at the window's start, so a student whose viewer is
cut off counts with the frames it received (``dropped`` says how many were). It also splits the students into
those whose session id an attack named and the others, and gives the projector's frames/s. The attacker's records
(:class:`~app.bench.attacks.AttackRecord`: answers per status or close code, an example message of each refusal,
latency) and whether the class kept the target (10th percentile ≥ 28 frames/s under attack) complete the report:
``attack.json`` and ``attack.svg`` in ``--out`` (``docs/bench``), which the Solver lab page shows. A server the tool
started is then stopped as a user stops it, with Ctrl+C, and the time it took is reported (it is killed after
10 s; the issue asks for 5 s whatever is in flight).

Every step is bounded: the attacker's start, connecting, each window, the attacker's report (its window plus a
wind-down, then it is killed), closing the room (on a server the tool did not start), stopping the server.
"""

from __future__ import annotations

import asyncio
import contextlib
import importlib
import json
import secrets
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Sequence
from dataclasses import asdict
from pathlib import Path
from xml.sax.saxutils import escape, quoteattr

from app.bench.attacks import WIND_DOWN_S, AttackBounds, AttackPlan
from app.bench.capacity import (
    PROJECT_ROOT,
    TARGET_P10_FRAMES_PER_S,
    LoadOptions,
    ServerStop,
    ServerUnderTest,
    WindowReading,
    check_scenes,
    close_room,
    frame_rate_summary,
    machine_facts,
    measure_window,
    open_room,
    server_facts,
    server_for,
    utc_now,
    window_figures,
)
from app.bench.load_client import ATTACKER_ADDRESS, Classroom, ClassroomSnapshot
from app.bench.plot import FONT, SVG_NS, _f, _text
from app.bench.process_tree import tree_usage
from app.course.bench_reports import ATTACK_REPORT, describe_workers, listed_attacks

PLOT_FILE = "attack.svg"
#: The scene of the attacker's expensive sessions (item 6) and of item 3's re-scening, unless the class is on it.
EXPENSIVE_SCENE = "double-pendulum"
RESCENE_TO, RESCENE_TO_INSTEAD = "four-bar", "heavy-top"
#: Seconds the attacker's process may take to start (it imports the scenes) and to report after its window.
ATTACKER_START_S = 60.0
ATTACKER_REPORT_S = WIND_DOWN_S + 15.0
#: Seconds the tool gives a server it started to stop after Ctrl+C before killing it: the issue asks for 5 s
#: whatever is in flight; twice that leaves room for a loaded machine, and the report gives the time it took.
STOP_TIMEOUT_S = 10.0
#: Seconds closing the room may take after the attack (a worker may still be busy with the attacker's requests).
ROOM_CLOSE_TIMEOUT_S = 10.0


def rescene_target(scene_id: str) -> str:
    """The scene item 3 turns a student's session into: another scene than the class's."""
    return RESCENE_TO if scene_id != RESCENE_TO else RESCENE_TO_INSTEAD


# ---- the attacker's process -----------------------------------------------------------------------------


class AttackerProcess:
    """``python -m app.bench.attacks``, started before the server so that it loads meanwhile; given its plan at the
    start of the attack window, its result read after it; killed on leaving the ``with`` block if it is still
    running (it is the tool's own child, ended by its pid)."""

    def __init__(self) -> None:
        self.log = tempfile.TemporaryFile()
        self.process = subprocess.Popen(
            [sys.executable, "-m", "app.bench.attacks"],
            cwd=PROJECT_ROOT,
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=self.log,
            text=True,
        )

    def __enter__(self) -> AttackerProcess:
        return self

    def __exit__(self, *exc: object) -> None:
        if self.process.poll() is None:
            self.process.kill()
        with contextlib.suppress(subprocess.TimeoutExpired):
            self.process.wait(timeout=10.0)
        for stream in (self.process.stdin, self.process.stdout):
            with contextlib.suppress(OSError):
                if stream is not None:  # both are pipes, opened with the process
                    stream.close()
        self.log.close()

    async def _line(self, timeout_s: float) -> str:
        """The next line it prints; "" if none comes within ``timeout_s`` (then it is killed, which ends the read)."""
        assert self.process.stdout is not None
        reading = asyncio.ensure_future(asyncio.to_thread(self.process.stdout.readline))
        done, _ = await asyncio.wait({reading}, timeout=timeout_s)
        if not done:
            self.process.kill()
            await asyncio.wait({reading}, timeout=5.0)
            return ""
        return reading.result()

    async def ready(self) -> None:
        """Wait until it has loaded everything; RuntimeError with its output if it does not."""
        if (await self._line(ATTACKER_START_S)).strip() != "ready":
            raise RuntimeError(f"the attacking client did not start: {self.output_tail()}")

    def go(self, plan: AttackPlan) -> None:
        """Start its window now."""
        assert self.process.stdin is not None
        self.process.stdin.write(plan.to_json() + "\n")
        self.process.stdin.flush()

    async def result(self, *, timeout_s: float) -> dict:
        """Its report once its window is over; a report of what went wrong if it gives none within ``timeout_s``."""
        line = await self._line(timeout_s)
        try:
            return json.loads(line)
        except ValueError:
            return {
                "attacks": [],
                "victims_named": [],
                "failures": {"attacker": f"gave no report: {self.output_tail()}"},
            }

    def cpu_s(self) -> float | None:
        with contextlib.suppress(ValueError):
            return tree_usage(self.process.pid).cpu_s
        return None

    def output_tail(self) -> str:
        self.log.seek(0)
        return self.log.read()[-1500:].decode(errors="replace").strip() or "(no output)"


# ---- the run ------------------------------------------------------------------------------------------------


def _rates_of(reading: WindowReading, chosen: Sequence[bool]) -> dict | None:
    """frames/s (summary) of the chosen students that were connected at the window's start."""
    elapsed = reading.end.at_s - reading.start.at_s
    if elapsed <= 0:
        return None
    return frame_rate_summary(
        [
            (b - a) / elapsed
            for a, b, ok, pick in zip(reading.start.frames, reading.end.frames, reading.healthy_at_start, chosen)
            if ok and pick
        ]
    )


def _projector_rate(start: ClassroomSnapshot, end: ClassroomSnapshot) -> float | None:
    elapsed = end.at_s - start.at_s
    return round((end.frames[0] - start.frames[0]) / elapsed, 2) if elapsed > 0 else None


def window_report(
    reading: WindowReading, projector: tuple[ClassroomSnapshot, ClassroomSnapshot], named: Sequence[bool]
) -> dict:
    """One window's figures (every student connected at its start counted), and the split by whether an attack
    named the student's session, and the projector's frames/s."""
    return {
        **window_figures(reading, count_dropped=True),
        "named_by_an_attack": {"students": sum(named), "frames_per_s": _rates_of(reading, named)},
        "not_named": {"students": len(named) - sum(named), "frames_per_s": _rates_of(reading, [not n for n in named])},
        "projector_frames_per_s": _projector_rate(*projector),
    }


async def _baseline_then_attack(
    server: ServerUnderTest, options: LoadOptions, room_id: str, attacker: AttackerProcess
) -> dict:
    host, port = server.address
    scene_id, students = options.scenes[0], options.students[0]
    classroom = Classroom(
        host,
        port,
        scene_id,
        students,
        connect_per_s=options.connect_per_s,
        distinct_addresses=bool(options.distinct_addresses),  # set on construction of the options
    )
    projector = Classroom(host, port, scene_id, 1, connect_per_s=options.connect_per_s, path=f"/room-viewer/{room_id}")
    plan = AttackPlan(
        host=host,
        port=port,
        scene_id=scene_id,
        room_id=room_id,
        victims=tuple(c.session_id for c in classroom.clients),
        seconds=options.seconds,
        bounds=options.attack_bounds or AttackBounds(),
        other_scene_id=rescene_target(scene_id),
    )
    try:
        await projector.open(timeout_s=30.0)
        await classroom.open(timeout_s=30.0 + students / options.connect_per_s)
        await attacker.ready()
        await asyncio.sleep(options.warmup_s)
        projector_start = projector.snapshot()
        baseline = await measure_window(server, classroom, options.seconds)
        projector_middle = projector.snapshot()
        attacker_cpu_start = attacker.cpu_s()
        attacker.go(plan)
        attacked = await measure_window(server, classroom, options.seconds)
        projector_end = projector.snapshot()
        attacker_cpu_end = attacker.cpu_s()
        result = await attacker.result(timeout_s=ATTACKER_REPORT_S)  # its window has just ended: it is winding down
    finally:
        await classroom.close()
        await projector.close()
    named_ids = set(result.get("victims_named") or ())
    named = [client.session_id in named_ids for client in classroom.clients]
    attack_window = window_report(attacked, (projector_middle, projector_end), named)
    if attacker_cpu_start is not None and attacker_cpu_end is not None:
        attacker_cores = round((attacker_cpu_end - attacker_cpu_start) / attack_window["window_s"], 3)
        attack_window["attacker_cpu_cores"] = attacker_cores
        if attack_window["other_cpu_cores"] is not None:  # the attacker is this machine's too, but not "others"
            attack_window["other_cpu_cores"] = round(max(0.0, attack_window["other_cpu_cores"] - attacker_cores), 3)
    return {
        "windows": {
            "baseline": window_report(baseline, (projector_start, projector_middle), named),
            "attack": attack_window,
        },
        "attacks": result.get("attacks") or [],
        "attacker": {
            "address": ATTACKER_ADDRESS,
            "students_named": len(named_ids),
            "failures": result.get("failures") or {},
            "ran_s": result.get("ran_s"),
            "bounds": asdict(plan.bounds),
            "rescene_to": plan.other_scene_id,
        },
    }


def run_attack(options: LoadOptions) -> dict:
    """Measure the class before and under attack (see the module docstring); returns the report."""
    if not options.attack:
        raise ValueError("attack: run_attack measures an --attack run")
    started = time.monotonic()
    key = options.instructor_key or secrets.token_urlsafe(24)  # a server the tool starts gets it; never printed
    stop = ServerStop()
    scene_id = options.scenes[0]
    # The attacker's process and this one's scene registry (for the viewers' first camera message) load while the
    # server starts.
    preload = threading.Thread(target=importlib.import_module, args=("app.scenes.viser_boundary",), daemon=True)
    with AttackerProcess() as attacker:
        preload.start()
        with server_for(
            options.url,
            server_pid=options.server_pid,
            workers=options.workers,
            instructor_key=key if options.url is None else None,
            stop=stop,
            stop_timeout_s=STOP_TIMEOUT_S,
        ) as server:
            check_scenes(server.base_url, [scene_id, rescene_target(scene_id), EXPENSIVE_SCENE])
            room = open_room(server.base_url, scene_id, instructor_key=key)
            try:
                preload.join()
                measured = asyncio.run(_baseline_then_attack(server, options, room["room_id"], attacker))
            finally:
                if not server.started_by_tool:  # a server the tool started is stopped next, rooms and all
                    close_room(server.base_url, room["room_id"], instructor_key=key, timeout_s=ROOM_CLOSE_TIMEOUT_S)
            facts = server_facts(server)
    attacked = measured["windows"]["attack"]["frames_per_s"] or {}
    return {
        "created": utc_now(),
        "mode": "attack",
        "machine": machine_facts(),
        "server": {**facts, "stop_after_ctrl_c": stop.as_dict() if server.started_by_tool else None},
        "scene_id": scene_id,
        "students": options.students[0],
        "room": {
            "lesson_id": room["lesson_id"],
            "scene_id": scene_id,
            "projector": "one viewer of the room's shared scene",
        },
        "method": {
            "seconds": options.seconds,
            "warmup_s": options.warmup_s,
            "connect_per_s": options.connect_per_s,
            "students": "each a lesson page: PUT of its own session with its X-Session-Key, then its viewer websocket",
            "addresses": (
                "each student from its own loopback address (127.0.1.1, 127.0.1.2, …), the attacker from "
                f"{ATTACKER_ADDRESS}, the tool's health probe and projector from 127.0.0.1"
                if options.distinct_addresses
                else f"every student from 127.0.0.1 (--no-distinct-addresses), the attacker from {ATTACKER_ADDRESS}"
            ),
            "windows": "before the attack, then under attack, on the same connected students, each of `seconds`",
            "frame": "one binary websocket message (a viser frame window), counted per client over the window",
            "counted": (
                "every student connected at the window's start; one cut off meanwhile counts with what it received"
            ),
            "health_period_s": 0.25,
            "health_slow_s": 2.0,
        },
        "targets": {"p10_frames_per_s": TARGET_P10_FRAMES_PER_S},
        "verdict": {
            "p10_frames_per_s_under_attack": attacked.get("p10"),
            "meets_target": attacked.get("p10") is not None and attacked["p10"] >= TARGET_P10_FRAMES_PER_S,
        },
        **measured,
        "run_s": round(time.monotonic() - started, 1),
    }


def write_attack_report(report: dict, out_dir: Path) -> list[Path]:
    """``attack.json`` and ``attack.svg`` in ``out_dir``; returns the paths written."""
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / ATTACK_REPORT
    path.write_text(json.dumps(report, indent=2, allow_nan=False) + "\n", encoding="utf-8")
    svg = out_dir / PLOT_FILE
    svg.write_text(attack_svg(report), encoding="utf-8")
    return [path, svg]


def summary_line(report: dict) -> str:
    """The run in one line: frames/s before and under attack, the target, and the time it took."""
    windows = report.get("windows") or {}
    parts = []
    for name, label in (("baseline", "before the attack"), ("attack", "under attack")):
        fps = (windows.get(name) or {}).get("frames_per_s") or {}
        dropped = (windows.get(name) or {}).get("dropped")
        parts.append(
            f"{label}: p10 {fps.get('p10', '—')}, median {fps.get('median', '—')}, slowest {fps.get('min', '—')}"
            f" frames/s, {dropped} dropped"
        )
    verdict = "meets" if (report.get("verdict") or {}).get("meets_target") else "misses"
    return (
        f"{report.get('students')} students on {report.get('scene_id')}: "
        + "; ".join(parts)
        + f"; {verdict} the target of {TARGET_P10_FRAMES_PER_S:g} (10th percentile); run {report.get('run_s')} s"
    )


def run_attack_command(options: LoadOptions, *, out_dir: Path) -> int:
    """Measure, print the attacks' answers and the summary, write attack.json and attack.svg."""
    try:
        report = run_attack(options)
    except (RuntimeError, ValueError) as exc:
        print(f"dynlab load: {exc}", file=sys.stderr)
        return 1
    for attack in report["attacks"]:
        answers = ", ".join(f"{answer} ×{count}" for answer, count in attack["answers"].items())
        print(
            f"item {attack['item']} {attack['name']}: {answers}; slowest {attack['latency_ms']['max']} ms", flush=True
        )
    print(summary_line(report), flush=True)
    for path in write_attack_report(report, out_dir):
        print(path)
    return 0


# ---- the plot -------------------------------------------------------------------------------------------------

WIDTH = 1000
BAR_LEFT, BAR_RIGHT, BAR_TOP, BAR_BOTTOM = 70, 400, 70, 330
NOTES_LEFT = 450
TABLE_TOP = 480
ROW_H = 18
#: The table's columns: item, attack, tries (right-aligned), answers, slowest answer (right-aligned).
COLUMN_X = {"item": 24, "attack": 60, "tries": 400, "answers": 420, "slowest": WIDTH - 24}
#: Bar colours: the 10th percentile (what the target is about) strong, the median light; the slowest student red.
P10_COLOUR, MEDIAN_COLOUR, SLOWEST_COLOUR = "#1f5fbf", "#9dbbe8", "#d0202e"
WINDOW_NAMES = (("baseline", "before the attack"), ("attack", "under attack"))


def _number(value: object, unit: str = "") -> str:
    return f"{value:g}{unit}" if isinstance(value, (int, float)) and not isinstance(value, bool) else "—"


def _answers_text(answers: dict, width: int) -> str:
    """``200 ×40, 429 ×3``: every answer an attack got, most frequent first, cut at ``width`` characters."""
    text = ", ".join(f"{answer} ×{count}" for answer, count in answers.items())
    return text if len(text) <= width else text[: width - 1] + "…"


def _notes(report: dict) -> list[str]:
    """The figures beside the bars, one per line: the verdict, the projector, the server, the attacker, the stop."""
    windows = report.get("windows") or {}
    before, during = windows.get("baseline") or {}, windows.get("attack") or {}
    verdict = report.get("verdict") or {}
    stop = (report.get("server") or {}).get("stop_after_ctrl_c") or {}
    named, others = during.get("named_by_an_attack") or {}, during.get("not_named") or {}
    lines = [
        f"Under attack the 10th percentile is {_number(verdict.get('p10_frames_per_s_under_attack'))} frames/s: "
        + (
            "the target is met."
            if verdict.get("meets_target")
            else f"the target of {TARGET_P10_FRAMES_PER_S:g} is missed."
        ),
        _split_note(named, others),
        f"Projector (the room's shared scene): {_number(before.get('projector_frames_per_s'))} frames/s before, "
        f"{_number(during.get('projector_frames_per_s'))} under attack.",
        f"Server CPU: {_number(before.get('server_cpu_cores'))} cores before, "
        f"{_number(during.get('server_cpu_cores'))} under "
        f"attack; health p95 {_number((before.get('health_ms') or {}).get('p95'), ' ms')} and "
        f"{_number((during.get('health_ms') or {}).get('p95'), ' ms')}.",
        f"The attacking client's own CPU: {_number(during.get('attacker_cpu_cores'))} cores; everything else on the "
        f"machine: {_number(before.get('other_cpu_cores'))} and {_number(during.get('other_cpu_cores'))} cores.",
    ]
    if stop:
        lines.append(
            f"After Ctrl+C the server {'was still running' if stop.get('killed') else 'stopped'} after "
            f"{_number(stop.get('seconds'), ' s')}{' and was killed' if stop.get('killed') else ''}."
        )
    return lines


def _split_note(named: dict, others: dict) -> str:
    """The 10th percentile of the students whose session id an attack used, and of the others (if any)."""
    p10 = lambda part: _number((part.get("frames_per_s") or {}).get("p10"))  # noqa: E731
    if not others.get("students"):
        return (
            f"An attack used every student's session id ({named.get('students', '?')}); their 10th percentile is above."
        )
    if not named.get("students"):
        return "No attack used a student's session id."
    return (
        f"Students whose session id an attack used ({named['students']}): 10th percentile {p10(named)} frames/s; "
        f"the others ({others['students']}): {p10(others)} frames/s."
    )


def _wrapped(text: str, width: int) -> list[str]:
    lines, line = [], ""
    for word in text.split():
        if line and len(line) + 1 + len(word) > width:
            lines.append(line)
            line = word
        else:
            line = f"{line} {word}".strip()
    return lines + ([line] if line else [])


def plot_height(report: dict) -> int:
    """The height of ``attack.svg`` (px): the bars and the figures, then one table row per attack."""
    return TABLE_TOP + ROW_H * (len(listed_attacks(report)) + 1) + 40


def attack_svg(report: dict) -> str:
    """Frames/s of the students before and under attack (10th percentile and median bars, the slowest student
    marked, the 28 frames/s target dashed), the run's figures beside them, and under them a table of every attack:
    its item of "Found", what it does, how many tries, every answer it got and the slowest answer."""
    windows = report.get("windows") or {}
    attacks = listed_attacks(report)
    height = plot_height(report)
    values = [
        v
        for name, _ in WINDOW_NAMES
        for v in ((windows.get(name) or {}).get("frames_per_s") or {}).values()
        if isinstance(v, (int, float))
    ]
    top = 5.0 * max(7, int(max(values + [TARGET_P10_FRAMES_PER_S]) // 5) + 1)
    y = lambda v: BAR_BOTTOM - (BAR_BOTTOM - BAR_TOP) * v / top  # noqa: E731
    machine, server = report.get("machine") or {}, report.get("server") or {}
    seconds = (report.get("method") or {}).get("seconds")
    subtitle = (
        f"{report.get('students', '?')} students, each on a {report.get('scene_id', '?')} session of their own; "
        "one attacking "
        f"client; {machine.get('cores', '?')} cores; scene workers: {describe_workers(server.get('workers'))}; "
        f"{_number(seconds, ' s')} per window; {str(report.get('created', ''))[:10]}"
    )
    out = [
        f'<svg xmlns="{SVG_NS}" width="{WIDTH}" height="{height}" viewBox="0 0 {WIDTH} {height}" role="img" '
        f'font-family="{escape(FONT)}">',
        "<title>A class under attack: frames per second each student receives before and while one client attacks, "
        "and what each attack got</title>",
        f'<rect width="{WIDTH}" height="{height}" fill="#ffffff"/>',
        _text(
            24,
            26,
            "A class under attack: frames/s each student receives, and what each attack got",
            size=17,
            weight="600",
        ),
        _text(24, 45, subtitle, size=12, fill="#5b6475"),
        '<g class="grid">',
    ]
    for k in range(int(top // 5) + 1):
        out.append(f'<line x1="{BAR_LEFT}" x2="{BAR_RIGHT}" y1="{_f(y(5 * k))}" y2="{_f(y(5 * k))}" stroke="#eef0f4"/>')
        out.append(_text(BAR_LEFT - 7, y(5 * k) + 4, f"{5 * k:g}", anchor="end"))
    out.append("</g>")
    out.append(
        f'<rect x="{BAR_LEFT}" y="{BAR_TOP}" width="{BAR_RIGHT - BAR_LEFT}" height="{BAR_BOTTOM - BAR_TOP}" '
        'fill="none" stroke="#9aa3b2"/>'
    )
    cy = (BAR_TOP + BAR_BOTTOM) / 2
    out.append(
        _text(
            BAR_LEFT - 40,
            cy,
            "Frames per second per student",
            size=13,
            anchor="middle",
            weight="600",
            extra=f'transform="rotate(-90 {_f(BAR_LEFT - 40)} {_f(cy)})"',
        )
    )
    group_w = (BAR_RIGHT - BAR_LEFT) / len(WINDOW_NAMES)
    for index, (name, label) in enumerate(WINDOW_NAMES):
        window = windows.get(name) or {}
        fps = window.get("frames_per_s") or {}
        x0 = BAR_LEFT + group_w * index + 20
        bar_w = (group_w - 40) / 2
        out.append(f'<g class="window" data-window="{name}">')
        for offset, key, colour in ((0, "p10", P10_COLOUR), (1, "median", MEDIAN_COLOUR)):
            value = fps.get(key)
            if isinstance(value, (int, float)):
                x = x0 + offset * bar_w
                out.append(
                    f'<rect class="bar" data-stat="{key}" data-value="{value:g}" x="{_f(x + 3)}" y="{_f(y(value))}" '
                    f'width="{_f(bar_w - 6)}" height="{_f(BAR_BOTTOM - y(value))}" fill="{colour}"/>'
                )
                out.append(_text(x + bar_w / 2, y(value) - 6, f"{value:g}", size=11, anchor="middle", halo=True))
        slowest = fps.get("min")
        if isinstance(slowest, (int, float)):
            out.append(
                f'<line class="slowest" data-value="{slowest:g}" x1="{_f(x0)}" x2="{_f(x0 + 2 * bar_w)}" '
                f'y1="{_f(y(slowest))}" y2="{_f(y(slowest))}" stroke="{SLOWEST_COLOUR}" stroke-width="2"/>'
            )
        if not fps:
            out.append(_text(x0 + bar_w, cy, "not measured", size=12, anchor="middle", fill=SLOWEST_COLOUR))
        out.append(_text(x0 + bar_w, BAR_BOTTOM + 18, label, anchor="middle", weight="600"))
        out.append(
            _text(
                x0 + bar_w,
                BAR_BOTTOM + 34,
                f"{_number(window.get('connected'))} connected, {_number(window.get('dropped'))} cut off",
                size=11,
                anchor="middle",
                fill="#5b6475",
            )
        )
        out.append("</g>")
    target_y = _f(y(TARGET_P10_FRAMES_PER_S))
    out.append(
        f'<g class="target"><line x1="{BAR_LEFT}" x2="{BAR_RIGHT}" y1="{target_y}" y2="{target_y}" stroke="#1d2330" '
        f'stroke-width="1.3" stroke-dasharray="6 4"/></g>'
    )
    legend_y = BAR_BOTTOM + 60
    for offset, (text, colour) in enumerate((("10th percentile", P10_COLOUR), ("median", MEDIAN_COLOUR))):
        x = BAR_LEFT + 120 * offset
        out.append(
            f'<rect x="{x}" y="{legend_y - 9}" width="12" height="10" fill="{colour}"/>'
            + _text(x + 17, legend_y, text, size=11)
        )
    out.append(
        f'<line x1="{BAR_LEFT + 200}" x2="{BAR_LEFT + 224}" y1="{legend_y - 4}" y2="{legend_y - 4}" '
        f'stroke="{SLOWEST_COLOUR}" '
        f'stroke-width="2"/>' + _text(BAR_LEFT + 230, legend_y, "slowest student", size=11)
    )
    out.append(
        f'<line x1="{BAR_LEFT}" x2="{BAR_LEFT + 24}" y1="{legend_y + 14}" y2="{legend_y + 14}" stroke="#1d2330" '
        f'stroke-width="1.3" stroke-dasharray="6 4"/>'
        + _text(
            BAR_LEFT + 30,
            legend_y + 18,
            f"target: 10th percentile ≥ {TARGET_P10_FRAMES_PER_S:g} frames/s under attack",
            size=11,
        )
    )
    note_y = BAR_TOP + 8
    out.append('<g class="notes">')
    for note in _notes(report):
        for line in _wrapped(note, 78):
            out.append(_text(NOTES_LEFT, note_y, line, size=12))
            note_y += 16
        note_y += 8
    out.append("</g>")
    header_y = TABLE_TOP
    out.append('<g class="attacks">')
    out.append(
        _text(
            COLUMN_X["item"],
            header_y - 22,
            "Every attack (one client, from one address) and every answer it got",
            size=14,
            weight="600",
        )
    )
    for column, title in (
        ("item", "item"),
        ("attack", "attack"),
        ("tries", "tries"),
        ("answers", "answers (count)"),
        ("slowest", "slowest answer (ms)"),
    ):
        out.append(
            _text(
                COLUMN_X[column],
                header_y,
                title,
                size=11,
                weight="600",
                anchor="end" if column in ("tries", "slowest") else "start",
            )
        )
    out.append(
        f'<line x1="{COLUMN_X["item"]}" x2="{COLUMN_X["slowest"]}" y1="{header_y + 5}" y2="{header_y + 5}" '
        'stroke="#9aa3b2"/>'
    )
    for row, attack in enumerate(attacks):
        ry = header_y + ROW_H * (row + 1) + 2
        latency = (attack.get("latency_ms") or {}).get("max")
        name = str(attack.get("name", "?"))
        out.append(
            f'<g class="attack" data-item={quoteattr(str(attack.get("item")))}>'
            + _text(COLUMN_X["item"], ry, str(attack.get("item", "?")), size=11)
            + _text(COLUMN_X["attack"], ry, name if len(name) <= 52 else name[:51] + "…", size=11)
            + _text(COLUMN_X["tries"], ry, str(attack.get("count", "?")), size=11, anchor="end")
            + _text(COLUMN_X["answers"], ry, _answers_text(attack.get("answers") or {}, 72), size=11)
            + _text(
                COLUMN_X["slowest"],
                ry,
                "—" if not isinstance(latency, (int, float)) else f"{latency:,.0f}",
                size=11,
                anchor="end",
            )
            + "</g>"
        )
    if not attacks:
        out.append(
            _text(COLUMN_X["item"], header_y + ROW_H + 2, "no attack recorded an answer", size=12, fill=SLOWEST_COLOUR)
        )
    out.append("</g>")
    out.append("</svg>")
    return "\n".join(out) + "\n"
