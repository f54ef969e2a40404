"""``dynlab load``: how many students the server streams to, measured with real viewer websockets.

For each scene and each class size the tool connects that many viewers
(:class:`app.bench.load_client.Classroom`, ``--connect-rate`` per second), waits
a warm-up, then over a steady window of ``--seconds`` measures per client the
frames delivered per second (a "frame" is one binary websocket message: one
frame window of viser), the server's CPU (cores used), resident memory, file
descriptors and threads (the server process and all its descendants, from
/proc), the load tool's own CPU (it shares the machine), and the latency of
``GET /api/health`` polled every 250 ms. All viewers close between steps.

The report is ``capacity.json`` plus ``capacity.svg`` (frames/s at the 10th
percentile and the median against students, one colour per scene, with the
28 and 15 frames/s targets marked), written to ``--out`` (``docs/bench``),
which the Solver lab page shows. By default the tool starts its own server
(``python -m app.cli serve`` on a free loopback port) and stops it afterwards;
``--url`` targets a running one (CPU and memory then need ``--server-pid``).
Loopback only; every loop is bounded in count and time.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import math
import os
import platform
import signal
import socket
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path
from xml.sax.saxutils import escape

import numpy as np

from app.bench.load_client import Classroom, HealthLatency, loopback_base, probe_health
from app.bench.plot import FONT, SVG_NS, _f, _marker, _text
from app.bench.process_tree import TreeUsage, tree_usage
from app.bench.report_file import read_report_file

REPORT_FILE = "capacity.json"
PLOT_FILE = "capacity.svg"
PROJECT_ROOT = Path(__file__).resolve().parents[2]
DEFAULT_OUT_DIR = PROJECT_ROOT / "docs" / "bench"

#: Bounds on a run: at most this many students per step, seconds per step, steps in all.
MAX_STUDENTS = 500
MAX_STEP_SECONDS = 600.0
MAX_STEPS = 40
#: The issue's targets: 100 students at >= 28 frames/s (10th percentile); 150 degrade evenly (every client >= 15).
TARGET_P10_FRAMES_PER_S = 28.0
DEGRADED_MIN_FRAMES_PER_S = 15.0
#: Seconds to wait for a started server's /api/health, and for it to stop after SIGINT before it is killed.
SERVER_START_TIMEOUT_S = 90.0
SERVER_STOP_TIMEOUT_S = 20.0
#: Seconds between steps, so the server drops the last class's sessions before the next arrives.
PAUSE_BETWEEN_STEPS_S = 2.0


@dataclass(frozen=True)
class LoadOptions:
    """What one ``dynlab load`` run measures; validated on construction (ValueError names the option)."""

    scenes: tuple[str, ...] = ("heavy-top",)
    students: tuple[int, ...] = (10, 30, 60, 100, 150)
    seconds: float = 20.0
    warmup_s: float = 4.0
    connect_per_s: float = 50.0
    workers: int | None = None
    url: str | None = None
    server_pid: int | None = None

    def __post_init__(self) -> None:
        if not self.scenes:
            raise ValueError("scene: give at least one scene id")
        for scene_id in self.scenes:
            if not scene_id or not all(ch.isalnum() or ch == "-" for ch in scene_id) or scene_id.lower() != scene_id:
                raise ValueError(f"scene: {scene_id!r} is not a scene id (lower-case letters, digits and '-')")
        if not self.students:
            raise ValueError("students: give at least one class size")
        for count in self.students:
            if not 1 <= count <= MAX_STUDENTS:
                raise ValueError(f"students: each class size must be 1..{MAX_STUDENTS}, got {count}")
        if len(self.scenes) * len(self.students) > MAX_STEPS:
            raise ValueError(f"students: {len(self.scenes)} scenes x {len(self.students)} sizes exceeds {MAX_STEPS} steps")
        _check_range("seconds", self.seconds, 1.0, MAX_STEP_SECONDS)
        _check_range("warmup", self.warmup_s, 0.0, 120.0)
        _check_range("connect_rate", self.connect_per_s, 1.0, 1000.0)
        if self.workers is not None and not 0 <= self.workers <= 64:
            raise ValueError(f"workers: must be 0..64 (0: scenes in the front process), got {self.workers}")
        if self.url is not None:
            loopback_base(self.url)
        elif self.server_pid is not None:
            raise ValueError("server_pid: only with --url (a server the tool starts is measured by its own pid)")


def _check_range(name: str, value: float, lo: float, hi: float) -> None:
    if not (isinstance(value, (int, float)) and math.isfinite(value) and lo <= value <= hi):
        raise ValueError(f"{name}: must be a number in [{lo:g}, {hi:g}], got {value!r}")


# ---- the server under test -------------------------------------------------------------------


@dataclass(frozen=True)
class ServerUnderTest:
    """Where the server listens and which process tree to measure (None: CPU and memory are not reported)."""

    base_url: str
    pid: int | None
    started_by_tool: bool
    workers: int | None

    @property
    def address(self) -> tuple[str, int]:
        return loopback_base(self.base_url)

    def usage(self) -> TreeUsage | None:
        return None if self.pid is None else tree_usage(self.pid)


def free_loopback_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


def wait_for_health(base_url: str, *, timeout_s: float, process: subprocess.Popen | None = None) -> None:
    """Poll ``GET /api/health`` until it answers 200; RuntimeError if the process exits or ``timeout_s`` passes."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if process is not None and process.poll() is not None:
            raise RuntimeError(f"the server exited with code {process.returncode} before answering /api/health")
        try:
            with urllib.request.urlopen(f"{base_url}/api/health", timeout=2.0) as answer:
                if answer.status == 200:
                    return
        except (OSError, urllib.error.URLError):
            pass
        time.sleep(0.25)
    raise RuntimeError(f"{base_url}/api/health did not answer within {timeout_s:g} s")


@contextlib.contextmanager
def started_server(*, workers: int | None) -> Iterator[ServerUnderTest]:
    """``python -m app.cli serve`` on a free loopback port, stopped on exit (SIGINT, then kill after a timeout)."""
    port = free_loopback_port()
    command = [sys.executable, "-m", "app.cli", "serve", "--port", str(port), "--log-level", "warning"]
    if workers is not None:
        command += ["--workers", str(workers)]
    with tempfile.TemporaryFile() as log:
        process = subprocess.Popen(command, cwd=PROJECT_ROOT, stdout=log, stderr=subprocess.STDOUT)
        base_url = f"http://127.0.0.1:{port}"
        try:
            try:
                wait_for_health(base_url, timeout_s=SERVER_START_TIMEOUT_S, process=process)
            except RuntimeError as exc:
                log.seek(0)
                tail = log.read()[-2000:].decode(errors="replace")
                raise RuntimeError(f"{exc}; its output ends:\n{tail}") from None
            yield ServerUnderTest(base_url=base_url, pid=process.pid, started_by_tool=True, workers=workers)
        finally:
            if process.poll() is None:
                process.send_signal(signal.SIGINT)
                try:
                    process.wait(timeout=SERVER_STOP_TIMEOUT_S)
                except subprocess.TimeoutExpired:
                    process.kill()
                    process.wait(timeout=SERVER_STOP_TIMEOUT_S)


@contextlib.contextmanager
def server_for(options_url: str | None, *, server_pid: int | None, workers: int | None) -> Iterator[ServerUnderTest]:
    """The running server at ``options_url``, or one the tool starts and stops."""
    if options_url is None:
        with started_server(workers=workers) as server:
            yield server
        return
    base_url = options_url.rstrip("/")
    wait_for_health(base_url, timeout_s=10.0)
    if server_pid is not None:
        tree_usage(server_pid)  # ValueError naming server_pid if it is not running
    yield ServerUnderTest(base_url=base_url, pid=server_pid, started_by_tool=False, workers=workers)


# ---- one step: N students on one scene ---------------------------------------------------------


def frame_rate_summary(rates: Sequence[float]) -> dict[str, float] | None:
    """Median, 10th percentile and minimum of per-client frames/s; None when no client was measured."""
    if not rates:
        return None
    values = np.asarray(rates, dtype=float)
    return {
        "median": round(float(np.median(values)), 2),
        "p10": round(float(np.percentile(values, 10)), 2),
        "min": round(float(values.min()), 2),
    }


def latency_summary(health: HealthLatency) -> dict[str, float | int | None]:
    """Median, 95th percentile and maximum (ms) of the health requests, with their count and failures."""
    values = np.asarray(health.latencies_ms, dtype=float)
    pick = lambda q: round(float(np.percentile(values, q)), 1) if values.size else None  # noqa: E731
    return {
        "median": pick(50),
        "p95": pick(95),
        "max": round(float(values.max()), 1) if values.size else None,
        "requests": int(values.size),
        "failures": health.failures,
    }


def per_client_rates(start, end, healthy: Sequence[bool]) -> list[float]:
    """frames/s of each healthy client between two :class:`ClassroomSnapshot`s."""
    elapsed = end.at_s - start.at_s
    if elapsed <= 0:
        return []
    return [(b - a) / elapsed for a, b, ok in zip(start.frames, end.frames, healthy) if ok]


async def measure_step(server: ServerUnderTest, scene_id: str, students: int, options: LoadOptions) -> dict:
    """Connect ``students`` viewers of ``scene_id``, measure a steady window of ``options.seconds``, close them all."""
    host, port = server.address
    classroom = Classroom(host, port, scene_id, students, connect_per_s=options.connect_per_s)
    stop_health = asyncio.Event()
    health = HealthLatency()
    prober: asyncio.Task | None = None
    try:
        await classroom.open(timeout_s=30.0 + students / options.connect_per_s)
        await asyncio.sleep(options.warmup_s)
        prober = asyncio.create_task(probe_health(host, port, stop_health, health))
        usage_start, tool_start, window_start = server.usage(), time.process_time(), classroom.snapshot()
        await asyncio.sleep(options.seconds)
        usage_end, tool_end, window_end = server.usage(), time.process_time(), classroom.snapshot()
    finally:
        stop_health.set()
        if prober is not None:
            await asyncio.wait({prober}, timeout=5.0)
        healthy = classroom.healthy()
        errors = classroom.errors()
        await classroom.close()
    elapsed = window_end.at_s - window_start.at_s
    frames = sum(window_end.frames) - sum(window_start.frames)
    decoded = window_end.decoded_frames - window_start.decoded_frames
    step = {
        "scene_id": scene_id,
        "students": students,
        "connected": sum(healthy),
        "errors": len(errors),
        "error_examples": sorted(set(errors))[:3],
        "window_s": round(elapsed, 2),
        "frames_per_s": frame_rate_summary(per_client_rates(window_start, window_end, healthy)),
        "server_cpu_cores": None,
        "server_rss_mb": None,
        "server_fds": None,
        "server_threads": None,
        "server_processes": None,
        "load_tool_cpu_cores": round((tool_end - tool_start) / elapsed, 3),
        "health_ms": latency_summary(health),
        "messages_per_frame": round((window_end.decoded_messages - window_start.decoded_messages) / decoded, 2)
        if decoded
        else None,
        "bytes_per_frame": round((window_end.frame_bytes - window_start.frame_bytes) / frames) if frames else None,
    }
    if usage_start is not None and usage_end is not None:
        step.update(
            server_cpu_cores=round((usage_end.cpu_s - usage_start.cpu_s) / elapsed, 3),
            server_rss_mb=round(usage_end.rss_mb, 1),
            server_fds=usage_end.fds,
            server_threads=usage_end.threads,
            server_processes=usage_end.processes,
        )
    return step


def machine_facts() -> dict:
    cpu = ""
    with contextlib.suppress(OSError):
        cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "")
    return {"cores": os.cpu_count(), "cpu": cpu, "python": platform.python_version(), "platform": platform.platform()}


def utc_now() -> str:
    return datetime.now(timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")


def server_facts(server: ServerUnderTest) -> dict:
    from app.cli import default_worker_count
    from app.settings import Settings

    return {
        "url": server.base_url,
        "started_by_tool": server.started_by_tool,
        # A server started here without --workers runs `dynlab serve`'s default: one scene worker per core.
        "workers": server.workers if server.workers is not None or not server.started_by_tool else default_worker_count(),
        # The frame rate a server started here runs at (DYNLAB_FRAME_RATE_HZ or the default); unknown for --url.
        "frame_rate_hz": Settings.from_env().frame_rate_hz if server.started_by_tool else None,
        "measured_pid": server.pid,
    }


async def _measure_all(server: ServerUnderTest, options: LoadOptions) -> list[dict]:
    steps = []
    for scene_id in options.scenes:
        for students in options.students:
            if steps:
                await asyncio.sleep(PAUSE_BETWEEN_STEPS_S)
            step = await measure_step(server, scene_id, students, options)
            steps.append(step)
            print(step_line(step), flush=True)
    return steps


def step_line(step: dict) -> str:
    """One line of progress for a measured step."""
    fps = step["frames_per_s"] or {}
    cpu = step["server_cpu_cores"]
    return (
        f"{step['scene_id']:>28} {step['students']:4d} students: frames/s p10 {fps.get('p10', '—')} median "
        f"{fps.get('median', '—')} min {fps.get('min', '—')}; server {cpu if cpu is not None else '—'} cores, "
        f"{step['server_rss_mb'] or '—'} MB; tool {step['load_tool_cpu_cores']} cores; health p95 "
        f"{step['health_ms']['p95']} ms; errors {step['errors']}"
    )


def check_scenes(base_url: str, scenes: Sequence[str]) -> None:
    """ValueError naming ``scene`` if the server has no such scene (asked once, from ``GET /api/scenes``)."""
    with urllib.request.urlopen(f"{base_url}/api/scenes", timeout=10.0) as answer:
        known = {str(entry.get("id")) for entry in json.load(answer)}
    unknown = [scene_id for scene_id in scenes if scene_id not in known]
    if unknown:
        raise ValueError(f"scene: the server has no scene {', '.join(map(repr, unknown))} (it has {', '.join(sorted(known))})")


def run_load(options: LoadOptions) -> dict:
    """Measure every (scene, students) step of ``options``; returns the report (see the module docstring)."""
    with server_for(options.url, server_pid=options.server_pid, workers=options.workers) as server:
        check_scenes(server.base_url, options.scenes)
        steps = asyncio.run(_measure_all(server, options))
        facts = server_facts(server)
    return {
        "created": utc_now(),
        "machine": machine_facts(),
        "server": facts,
        "method": {
            "seconds": options.seconds,
            "warmup_s": options.warmup_s,
            "connect_per_s": options.connect_per_s,
            "frame": "one binary websocket message (a viser frame window), counted per client over the steady window",
            "health_period_s": 0.25,
            "health_slow_s": 2.0,
        },
        "targets": {"p10_frames_per_s": TARGET_P10_FRAMES_PER_S, "min_frames_per_s_degraded": DEGRADED_MIN_FRAMES_PER_S},
        "steps": steps,
    }


# ---- the report: JSON and a plot -------------------------------------------------------------

WIDTH, HEIGHT = 840, 460  # room on the right for the longest scene id in the legend
LEFT, RIGHT, TOP, BOTTOM = 70, 560, 64, 400
SCENE_COLOURS = ("#d0202e", "#1f5fbf", "#1b8a3a", "#7b2fa8", "#e67e00", "#00796b", "#5d4037")


def _nice_ceiling(value: float, step: float) -> float:
    return step * max(1, math.ceil(value / step - 1e-9))


def describe_workers(workers: object) -> str:
    """The report's ``server.workers`` in words: serve's default (None), none (0: one process), or the count."""
    return "serve's default" if workers is None else "none (one process)" if workers == 0 else str(workers)


def capacity_svg(report: dict) -> str:
    """Frames/s (10th percentile solid, median dashed) against students, one colour per scene; linear axes."""
    steps = [s for s in report.get("steps") or () if isinstance(s.get("frames_per_s"), dict)]
    scenes = list(dict.fromkeys(str(s["scene_id"]) for s in steps))
    most = max([s["students"] for s in steps] + [10])
    max_students = _nice_ceiling(most, 10 if most <= 100 else 50)
    rates = [s["frames_per_s"][k] for s in steps for k in ("p10", "median")]
    max_rate = _nice_ceiling(max(rates + [TARGET_P10_FRAMES_PER_S + 2]) + 3, 5)  # room above the top line
    x = lambda n: LEFT + (RIGHT - LEFT) * n / max_students  # noqa: E731
    y = lambda r: BOTTOM - (BOTTOM - TOP) * r / max_rate  # noqa: E731
    machine = report.get("machine") or {}
    server = report.get("server") or {}
    seconds = (report.get("method") or {}).get("seconds")
    subtitle = (
        f"{machine.get('cores', '?')} cores; scene workers: {describe_workers(server.get('workers'))}; "
        f"{f'{seconds:g}' if isinstance(seconds, (int, float)) else '?'} s steady window per point; "
        f"{str(report.get('created', ''))[:10]}"
    )
    out = [
        f'<svg xmlns="{SVG_NS}" width="{WIDTH}" height="{HEIGHT}" viewBox="0 0 {WIDTH} {HEIGHT}" role="img" '
        f'font-family="{escape(FONT)}">',
        "<title>Classroom capacity: frames per second delivered to each student against the number of students"
        "</title>",
        f'<rect width="{WIDTH}" height="{HEIGHT}" fill="#ffffff"/>',
        _text(LEFT, 26, "Classroom capacity: frames/s each student receives", size=17, weight="600"),
        _text(LEFT, 45, subtitle, size=12, fill="#5b6475"),
    ]
    grid = []
    x_tick = next(step for step in (1, 2, 5, 10, 20, 25, 50, 100) if max_students / step <= 10)
    n = 0.0
    while n <= max_students + 1e-9:
        grid.append(f'<line x1="{_f(x(n))}" x2="{_f(x(n))}" y1="{TOP}" y2="{BOTTOM}" stroke="#eef0f4"/>')
        grid.append(_text(x(n), BOTTOM + 18, f"{n:g}", anchor="middle"))
        n += x_tick
    for r in range(0, int(max_rate) + 1, 5):
        grid.append(f'<line x1="{LEFT}" x2="{RIGHT}" y1="{_f(y(r))}" y2="{_f(y(r))}" stroke="#eef0f4"/>')
        grid.append(_text(LEFT - 7, y(r) + 4, str(r), anchor="end"))
    out.append('<g class="grid">' + "".join(grid) + "</g>")
    out.append(f'<rect x="{LEFT}" y="{TOP}" width="{RIGHT - LEFT}" height="{BOTTOM - TOP}" fill="none" stroke="#9aa3b2"/>')
    out.append(_text((LEFT + RIGHT) / 2, BOTTOM + 42, "Students (one viewer and one scene each)", size=13,
                     anchor="middle", weight="600"))  # fmt: skip
    cy = (TOP + BOTTOM) / 2
    out.append(_text(18, cy, "Frames per second per student", size=13, anchor="middle", weight="600",
                     extra=f'transform="rotate(-90 18 {_f(cy)})"'))  # fmt: skip
    for rate, label in ((TARGET_P10_FRAMES_PER_S, "target: 10th percentile at 100 students"),
                        (DEGRADED_MIN_FRAMES_PER_S, "floor: every student at 150")):  # fmt: skip
        out.append(
            f'<g class="target"><line x1="{LEFT}" x2="{RIGHT}" y1="{_f(y(rate))}" y2="{_f(y(rate))}" stroke="#1d2330" '
            f'stroke-width="1.3" stroke-dasharray="6 4"/>'
            # At the left end, under its line: small classes sit at 30 frames/s, above both lines, so nothing is hidden.
            + _text(LEFT + 6, y(rate) + 14, f"{label} ({rate:g})", size=11, anchor="start", halo=True)
            + "</g>"
        )
    legend_y = TOP + 8
    for index, scene_id in enumerate(scenes):
        colour = SCENE_COLOURS[index % len(SCENE_COLOURS)]
        points = sorted((s["students"], s["frames_per_s"]) for s in steps if s["scene_id"] == scene_id)
        series = [f'<g class="series" data-scene="{escape(scene_id)}">']
        for key, dash in (("median", ' stroke-dasharray="5 3"'), ("p10", "")):
            coords = " ".join(f"{_f(x(n))},{_f(y(fps[key]))}" for n, fps in points)
            if len(points) >= 2:
                series.append(f'<polyline points="{coords}" fill="none" stroke="{colour}" stroke-width="2.2"{dash}/>')
            series.extend(_marker("circle", x(n), y(fps[key]), colour, key == "p10", size=4) for n, fps in points)
        series.append("</g>")
        out.append("".join(series))
        out.append(
            f'<line x1="{RIGHT + 16}" x2="{RIGHT + 44}" y1="{legend_y}" y2="{legend_y}" stroke="{colour}" stroke-width="2.2"/>'
            + _text(RIGHT + 52, legend_y + 4, scene_id)
        )
        legend_y += 20
    legend_y += 10
    out.append(_text(RIGHT + 16, legend_y, "solid, filled: 10th percentile", size=11, fill="#5b6475"))
    out.append(_text(RIGHT + 16, legend_y + 16, "dashed, open: median", size=11, fill="#5b6475"))
    if not steps:
        out.append(_text((LEFT + RIGHT) / 2, cy, "no step delivered frames", size=14, anchor="middle", fill="#d0202e"))
    out.append("</svg>")
    return "\n".join(out) + "\n"


def write_report(report: dict, out_dir: Path, *, name: str = REPORT_FILE, plot: bool = True) -> list[Path]:
    """Write the report as JSON (and its SVG plot) into ``out_dir``; returns the paths written."""
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / name
    path.write_text(json.dumps(report, indent=2, allow_nan=False) + "\n", encoding="utf-8")
    written = [path]
    if plot:
        svg = out_dir / PLOT_FILE
        svg.write_text(capacity_svg(report), encoding="utf-8")
        written.append(svg)
    return written


def read_report(path: Path) -> dict | None:
    """A saved capacity report, None if the file is missing; ValueError if it is unreadable or has no steps."""
    return read_report_file(path, list_key="steps", shown_as=path.name)


# ---- command line ----------------------------------------------------------------------------


def _int_list(text: str) -> tuple[int, ...]:
    try:
        return tuple(int(part) for part in text.split(",") if part.strip())
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected whole numbers separated by commas, got {text!r}") from None


def _scene_list(values: Sequence[str] | None, default: tuple[str, ...]) -> tuple[str, ...]:
    if not values:
        return default
    return tuple(dict.fromkeys(part.strip() for value in values for part in value.split(",") if part.strip()))


def add_server_arguments(parser: argparse.ArgumentParser) -> None:
    """Options shared by ``dynlab load`` and ``dynlab soak``: which server, where the report goes."""
    parser.add_argument("--scene", action="append", metavar="ID", help="scene id (repeatable or a comma list; default heavy-top)")
    parser.add_argument("--workers", type=int, default=None, help="passed to `dynlab serve --workers` when the tool starts the server")
    parser.add_argument("--url", default=None, help="a running server on loopback (http://127.0.0.1:PORT) instead of starting one")
    parser.add_argument("--server-pid", type=int, default=None, help="with --url: the server's pid, to measure its CPU and memory")
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT_DIR, help="folder for the report (default docs/bench)")


def add_load_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of ``dynlab load``."""
    parser.add_argument("--students", type=_int_list, default=LoadOptions.students, help="class sizes, e.g. 10,30,60,100,150")
    parser.add_argument("--seconds", type=float, default=LoadOptions.seconds, help=f"steady window per step (s, ≤ {MAX_STEP_SECONDS:g})")
    parser.add_argument("--warmup", type=float, default=LoadOptions.warmup_s, help="seconds after all connected before measuring")
    parser.add_argument("--connect-rate", type=float, default=LoadOptions.connect_per_s, help="viewers opened per second")
    add_server_arguments(parser)


def run_load_command(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    """Measure, print one line per step, write capacity.json and capacity.svg; bad options exit through ``parser``."""
    try:
        options = LoadOptions(
            scenes=_scene_list(args.scene, LoadOptions.scenes), students=args.students, seconds=args.seconds,
            warmup_s=args.warmup, connect_per_s=args.connect_rate, workers=args.workers, url=args.url,
            server_pid=args.server_pid,
        )  # fmt: skip
    except ValueError as exc:
        parser.error(str(exc))
    try:
        report = run_load(options)
    except (RuntimeError, ValueError) as exc:
        print(f"dynlab load: {exc}", file=sys.stderr)
        return 1
    for path in write_report(report, args.out):
        print(path)
    return 0
