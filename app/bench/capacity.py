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

With ``--room`` the students *follow* an instructor instead: the tool opens a
classroom room on the scene (``POST /api/rooms`` with the instructor's key; a
server it starts gets a random one in ``DYNLAB_INSTRUCTOR_KEY``) and every
viewer connects to the room's one shared scene, ``/room-viewer/<room_id>``. The
same figures are measured per class size (1 to 150 by default), and the report
is ``classroom.json`` plus ``classroom.svg``: frames/s and server CPU against
students, following beside the independent viewers of ``capacity.json``, and
the server's CPU with 1 and with 100 followers (``follow_cost``).

Each student is a lesson page: it claims its own session first (``PUT`` with
its ``X-Session-Key``), then opens its viewer, from a loopback address of its
own (127.0.1.1, 127.0.1.2, …; ``--no-distinct-addresses`` for one address), so
the server's per-device limits see a class of devices rather than one client.
``--attack`` measures a class on its own scenes before and while one client
attacks it (:mod:`app.bench.under_attack`; ``attack.json`` and ``.svg``).
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import json
import math
import os
import platform
import secrets
import signal
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from datetime import UTC, datetime
from pathlib import Path
from typing import Any
from xml.sax.saxutils import escape

import numpy as np

from app.bench.attacks import AttackBounds
from app.bench.load_client import Classroom, ClassroomSnapshot, HealthLatency, loopback_base, probe_health
from app.bench.plot import FONT, SVG_NS, _f, _marker, _text
from app.bench.ports import free_loopback_port
from app.bench.process_tree import TreeUsage, process_group_members, tree_pids, tree_usage
from app.classroom.roles import HEADER as INSTRUCTOR_HEADER
from app.classroom.roles import MIN_KEY_LENGTH
from app.course.bench_reports import (
    CAPACITY_REPORT,
    CLASSROOM_REPORT,
    FOLLOW_COST_CLASS,
    describe_workers,
    read_capacity_report,
)

PLOT_FILE = "capacity.svg"
CLASSROOM_PLOT_FILE = "classroom.svg"
#: Class sizes of a ``--room`` run unless ``--students`` gives others (1: what one viewer costs).
ROOM_STUDENTS = (1, 10, 30, 60, 100, 150)
#: An ``--attack`` run's class (students on their own heavy tops) and each of its two windows (s) unless given.
ATTACK_STUDENTS = 100
ATTACK_SECONDS = 30.0
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
    #: Follow one classroom room per scene instead of a session per student.
    room: bool = False
    #: The server's instructor secret, for opening the room (a server the tool starts gets a random one).
    instructor_key: str | None = None
    #: Each student connects from its own loopback address (127.0.1.1, 127.0.1.2, …), as a class of devices does (the
    #: server bounds what one device may open: from one address a class would be refused); None: on unless the url is
    #: IPv6.
    distinct_addresses: bool | None = None
    #: Students on their own scenes, measured before and while one client attacks (app.bench.under_attack).
    attack: bool = False
    #: How much the attacker tries (None: everything, :class:`~app.bench.attacks.AttackBounds`'s defaults).
    attack_bounds: AttackBounds | None = None

    def __post_init__(self) -> None:
        if self.distinct_addresses is None:
            ipv6 = self.url is not None and loopback_base(self.url)[0] == "::1"
            object.__setattr__(self, "distinct_addresses", not ipv6)
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
            raise ValueError(
                f"students: {len(self.scenes)} scenes x {len(self.students)} sizes exceeds {MAX_STEPS} steps"
            )
        _check_range("seconds", self.seconds, 1.0, MAX_STEP_SECONDS)
        _check_range("warmup", self.warmup_s, 0.0, 120.0)
        _check_range("connect_rate", self.connect_per_s, 1.0, 1000.0)
        if self.workers is not None and not 0 <= self.workers <= 64:
            raise ValueError(f"workers: must be 0..64 (0: scenes in the front process), got {self.workers}")
        if self.url is not None:
            loopback_base(self.url)
        elif self.server_pid is not None:
            raise ValueError("server_pid: only with --url (a server the tool starts is measured by its own pid)")
        if self.instructor_key is not None:
            if not (self.room or self.attack):
                raise ValueError("instructor_key: only with --room or --attack (it opens the room)")
            if len(self.instructor_key) < MIN_KEY_LENGTH:
                raise ValueError(
                    f"instructor_key: at least {MIN_KEY_LENGTH} characters, got {len(self.instructor_key)}"
                )
        elif (self.room or self.attack) and self.url is not None:
            raise ValueError(
                f"instructor_key: a {'--room' if self.room else '--attack'} run against --url needs the server's "
                "instructor key"
            )
        if self.attack:
            if self.room:
                raise ValueError(
                    "attack: students on their own scenes are attacked; --room and --attack do not go together"
                )
            if len(self.scenes) != 1 or len(self.students) != 1:
                raise ValueError(
                    "attack: one scene and one class size (the students are measured before and under attack)"
                )
        elif self.attack_bounds is not None:
            raise ValueError("attack_bounds: only with --attack")
        if self.distinct_addresses and self.url is not None and loopback_base(self.url)[0] == "::1":
            raise ValueError(
                "distinct_addresses: the students' addresses are IPv4 (127.0.1.x); give an http://127.0.0.1 url"
            )


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

    def front_cpu_s(self) -> float | None:
        """CPU seconds of the front process alone: the tree's less its child processes' trees; None if unmeasured."""
        if self.pid is None:
            return None
        total = tree_usage(self.pid).cpu_s
        descendants = tree_pids(self.pid)[1:]
        grandchildren = {pid for child in descendants for pid in tree_pids(child)[1:]}
        children_cpu_s = 0.0
        for child in descendants:
            if child not in grandchildren:
                with contextlib.suppress(ValueError):  # a process that exited since the listing
                    children_cpu_s += tree_usage(child).cpu_s
        return total - children_cpu_s


def machine_busy_cpu_s() -> float | None:
    """CPU seconds this machine's processes have used, all cores (not idle, I/O wait or a hypervisor's steal), from
    /proc/stat."""
    try:
        with open("/proc/stat", encoding="ascii") as stat:
            fields = stat.readline().split()
    except OSError:
        return None
    if not fields or fields[0] != "cpu":
        return None
    user, nice, system, _idle, _iowait, irq, softirq = (int(v) for v in fields[1:8])
    return (user + nice + system + irq + softirq) / os.sysconf("SC_CLK_TCK")


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


@dataclass
class ServerStop:
    """How a server the tool started stopped: seconds from Ctrl+C (SIGINT) until it exited (or was killed), and
    whether it had to be killed after :data:`SERVER_STOP_TIMEOUT_S`; None until it was stopped."""

    seconds: float | None = None
    killed: bool | None = None

    def as_dict(self) -> dict:
        return {"seconds": None if self.seconds is None else round(self.seconds, 2), "killed": self.killed}


def stop_process_group(process: subprocess.Popen, *, timeout_s: float) -> ServerStop:
    """Ctrl+C (SIGINT) to ``process`` as a user stops ``dynlab serve``; after ``timeout_s`` SIGKILL its process group
    (it was started as a group's leader, so its scene workers and their children go too, even once orphaned), as
    anything of the group left after a clean exit."""
    started = time.monotonic()
    killed = False
    if process.poll() is None:
        process.send_signal(signal.SIGINT)
        try:
            process.wait(timeout=timeout_s)
        except subprocess.TimeoutExpired:
            killed = True
    seconds = time.monotonic() - started
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(process.pid, signal.SIGKILL)  # whatever is left of the group: a worker stuck in a long request
    if process.poll() is None:
        process.kill()
        process.wait(timeout=SERVER_STOP_TIMEOUT_S)
    # SIGKILL takes effect when each process is next scheduled: wait (bounded) until the group is gone.
    deadline = time.monotonic() + SERVER_STOP_TIMEOUT_S
    while process_group_members(process.pid) and time.monotonic() < deadline:
        time.sleep(0.05)
    return ServerStop(seconds=seconds, killed=killed)


@contextlib.contextmanager
def started_server(
    *,
    workers: int | None,
    instructor_key: str | None = None,
    stop: ServerStop | None = None,
    stop_timeout_s: float = SERVER_STOP_TIMEOUT_S,
) -> Iterator[ServerUnderTest]:
    """``python -m app.cli serve`` on a free loopback port, stopped on exit (SIGINT, then kill after
    ``stop_timeout_s``).

    ``instructor_key`` becomes the server's ``DYNLAB_INSTRUCTOR_KEY`` (in its environment, not on its command line).
    ``stop``, if given, is filled in with how the server stopped.
    """
    port = free_loopback_port()
    command = [sys.executable, "-m", "app.cli", "serve", "--port", str(port), "--log-level", "warning"]
    if workers is not None:
        command += ["--workers", str(workers)]
    env = dict(os.environ)
    if instructor_key is not None:
        env["DYNLAB_INSTRUCTOR_KEY"] = instructor_key
    # The tool's rooms and sessions go to a data directory of its own, removed afterwards: never into the classes'.
    env.pop("DYNLAB_DATABASE_URL", None)
    with tempfile.TemporaryFile() as log, tempfile.TemporaryDirectory(prefix="dynlab-load-") as data_dir:
        env["DYNLAB_DATA_DIR"] = data_dir
        process = subprocess.Popen(
            command, cwd=PROJECT_ROOT, stdout=log, stderr=subprocess.STDOUT, env=env, start_new_session=True
        )
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
            stopped = stop_process_group(process, timeout_s=stop_timeout_s)
            if stop is not None:
                stop.seconds, stop.killed = stopped.seconds, stopped.killed


@contextlib.contextmanager
def server_for(
    options_url: str | None,
    *,
    server_pid: int | None,
    workers: int | None,
    instructor_key: str | None = None,
    stop: ServerStop | None = None,
    stop_timeout_s: float = SERVER_STOP_TIMEOUT_S,
) -> Iterator[ServerUnderTest]:
    """The running server at ``options_url``, or one the tool starts (with ``instructor_key``) and stops (filling in
    ``stop``; killed after ``stop_timeout_s``)."""
    if options_url is None:
        with started_server(
            workers=workers, instructor_key=instructor_key, stop=stop, stop_timeout_s=stop_timeout_s
        ) as server:
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


@dataclass(frozen=True)
class WindowReading:
    """What one steady window measured: the classroom's counters and the server's usage at both ends, the load
    tool's CPU, the machine's busy CPU, the health probe, and which viewers were healthy at each end."""

    start: ClassroomSnapshot
    end: ClassroomSnapshot
    usage_start: TreeUsage | None
    usage_end: TreeUsage | None
    front_start_s: float | None
    front_end_s: float | None
    busy_start_s: float | None
    busy_end_s: float | None
    tool_cpu_s: float
    health: HealthLatency
    healthy_at_start: tuple[bool, ...]
    healthy_at_end: tuple[bool, ...]
    errors: tuple[str, ...]


async def measure_window(server: ServerUnderTest, classroom: Classroom, seconds: float) -> WindowReading:
    """Read everything at the start of a steady window of ``seconds``, wait it out (probing ``/api/health``), read
    it all again. The classroom stays connected."""
    host, port = server.address
    stop_health = asyncio.Event()
    health = HealthLatency()
    prober = asyncio.create_task(probe_health(host, port, stop_health, health))
    try:
        healthy_at_start = tuple(classroom.healthy())
        busy_start, front_start, usage_start, tool_start, window_start = (
            machine_busy_cpu_s(),
            server.front_cpu_s(),
            server.usage(),
            time.process_time(),
            classroom.snapshot(),
        )
        await asyncio.sleep(seconds)
        usage_end, tool_end, window_end = server.usage(), time.process_time(), classroom.snapshot()
        front_end, busy_end = server.front_cpu_s(), machine_busy_cpu_s()
    finally:
        stop_health.set()
        await asyncio.wait({prober}, timeout=5.0)
    return WindowReading(
        start=window_start,
        end=window_end,
        usage_start=usage_start,
        usage_end=usage_end,
        front_start_s=front_start,
        front_end_s=front_end,
        busy_start_s=busy_start,
        busy_end_s=busy_end,
        tool_cpu_s=tool_end - tool_start,
        health=health,
        healthy_at_start=healthy_at_start,
        healthy_at_end=tuple(classroom.healthy()),
        errors=tuple(classroom.errors()),
    )


def window_figures(reading: WindowReading, *, count_dropped: bool = False) -> dict:
    """The figures of one window: frames/s per client (10th percentile, median, minimum), server CPU, memory, fds,
    threads, the tool's and everyone else's CPU, health latency, viser messages and bytes per frame.

    Frames/s are of the viewers healthy at the window's end; with ``count_dropped``, of every viewer healthy at its
    start, so one cut off during the window counts with the frames it received (``dropped`` says how many)."""
    elapsed = reading.end.at_s - reading.start.at_s
    frames = sum(reading.end.frames) - sum(reading.start.frames)
    decoded = reading.end.decoded_frames - reading.start.decoded_frames
    counted = reading.healthy_at_start if count_dropped else reading.healthy_at_end
    figures: dict[str, Any] = {
        "connected": sum(reading.healthy_at_end),
        "errors": len(reading.errors),
        "error_examples": sorted(set(reading.errors))[:3],
        "window_s": round(elapsed, 2),
        "frames_per_s": frame_rate_summary(per_client_rates(reading.start, reading.end, counted)),
        "server_cpu_cores": None,
        # The front process alone (it relays every frame to every viewer); the rest is the scene workers'.
        "server_front_cpu_cores": None,
        "server_rss_mb": None,
        "server_fds": None,
        "server_threads": None,
        "server_processes": None,
        "load_tool_cpu_cores": round(reading.tool_cpu_s / elapsed, 3),
        # Everything else the machine ran meanwhile (other people's work on a shared machine); None if unmeasured.
        "other_cpu_cores": None,
        "health_ms": latency_summary(reading.health),
        "messages_per_frame": round((reading.end.decoded_messages - reading.start.decoded_messages) / decoded, 2)
        if decoded
        else None,
        "bytes_per_frame": round((reading.end.frame_bytes - reading.start.frame_bytes) / frames) if frames else None,
    }
    if count_dropped:
        figures["dropped"] = sum(a and not b for a, b in zip(reading.healthy_at_start, reading.healthy_at_end))
    usage_start, usage_end = reading.usage_start, reading.usage_end
    if usage_start is not None and usage_end is not None:
        figures.update(
            server_cpu_cores=round((usage_end.cpu_s - usage_start.cpu_s) / elapsed, 3),
            server_rss_mb=round(usage_end.rss_mb, 1),
            server_fds=usage_end.fds,
            server_threads=usage_end.threads,
            server_processes=usage_end.processes,
        )
    if reading.front_start_s is not None and reading.front_end_s is not None:
        figures["server_front_cpu_cores"] = round((reading.front_end_s - reading.front_start_s) / elapsed, 3)
    if reading.busy_start_s is not None and reading.busy_end_s is not None and figures["server_cpu_cores"] is not None:
        busy = (reading.busy_end_s - reading.busy_start_s) / elapsed
        figures["other_cpu_cores"] = round(
            max(0.0, busy - figures["server_cpu_cores"] - figures["load_tool_cpu_cores"]), 3
        )
    return figures


async def measure_step(
    server: ServerUnderTest, scene_id: str, students: int, options: LoadOptions, *, viewer_path: str = ""
) -> dict:
    """Connect ``students`` viewers of ``scene_id``, measure a steady window of ``options.seconds``, close them all.

    ``viewer_path``: the websocket path every viewer opens (a room's ``/room-viewer/<room_id>``); empty: a
    session of its own each.
    """
    host, port = server.address
    classroom = Classroom(
        host,
        port,
        scene_id,
        students,
        connect_per_s=options.connect_per_s,
        path=viewer_path,
        distinct_addresses=bool(options.distinct_addresses),  # set on construction of the options
    )
    try:
        await classroom.open(timeout_s=30.0 + students / options.connect_per_s)
        await asyncio.sleep(options.warmup_s)
        reading = await measure_window(server, classroom, options.seconds)
    finally:
        await classroom.close()
    return {
        "scene_id": scene_id,
        "mode": "follow" if viewer_path else "independent",
        "students": students,
        **window_figures(reading),
    }


def machine_facts() -> dict:
    cpu = ""
    with contextlib.suppress(OSError):
        cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "")
    return {"cores": os.cpu_count(), "cpu": cpu, "python": platform.python_version(), "platform": platform.platform()}


def utc_now() -> str:
    return datetime.now(UTC).strftime("%Y-%m-%dT%H:%M:%SZ")


def server_facts(server: ServerUnderTest) -> dict:
    from app.settings import Settings, default_worker_count

    return {
        "url": server.base_url,
        "started_by_tool": server.started_by_tool,
        # A server started here without --workers runs `dynlab serve`'s default: one scene worker per core.
        "workers": server.workers
        if server.workers is not None or not server.started_by_tool
        else default_worker_count(),
        # The frame rate a server started here runs at (DYNLAB_FRAME_RATE_HZ or the default); unknown for --url.
        "frame_rate_hz": Settings.from_env().frame_rate_hz if server.started_by_tool else None,
        "measured_pid": server.pid,
    }


async def _measure_all(
    server: ServerUnderTest, options: LoadOptions, rooms: dict[str, dict] | None = None
) -> list[dict]:
    """Every step; with ``rooms`` (scene id -> the room opened on it) the viewers follow that scene's room."""
    steps: list[dict] = []
    for scene_id in options.scenes:
        path = f"/room-viewer/{rooms[scene_id]['room_id']}" if rooms is not None else ""
        for students in options.students:
            if steps:
                await asyncio.sleep(PAUSE_BETWEEN_STEPS_S)
            step = await measure_step(server, scene_id, students, options, viewer_path=path)
            steps.append(step)
            print(step_line(step), flush=True)
    return steps


def _or_dash(value: object) -> str:
    return "—" if value is None else str(value)


def step_line(step: dict) -> str:
    """One line of progress for a measured step."""
    fps = step["frames_per_s"] or {}
    cpu = step["server_cpu_cores"]
    return (
        f"{step['scene_id']:>28} {step['students']:4d} "
        f"{'followers' if step.get('mode') == 'follow' else 'students '}: frames/s p10 {fps.get('p10', '—')} "
        "median "
        f"{fps.get('median', '—')} min {fps.get('min', '—')}; server {cpu if cpu is not None else '—'} cores, "
        f"{step['server_rss_mb'] or '—'} MB; front {_or_dash(step.get('server_front_cpu_cores'))}; tool "
        f"{step['load_tool_cpu_cores']} cores; others {_or_dash(step.get('other_cpu_cores'))}; health p95 "
        f"{step['health_ms']['p95']} ms; errors {step['errors']}"
    )


def check_scenes(base_url: str, scenes: Sequence[str]) -> None:
    """ValueError naming ``scene`` if the server has no such scene (asked once, from ``GET /api/scenes``)."""
    with urllib.request.urlopen(f"{base_url}/api/scenes", timeout=10.0) as answer:
        known = {str(entry.get("id")) for entry in json.load(answer)}
    unknown = [scene_id for scene_id in scenes if scene_id not in known]
    if unknown:
        raise ValueError(
            f"scene: the server has no scene {', '.join(map(repr, unknown))} (it has {', '.join(sorted(known))})"
        )


# ---- a classroom room for --room ---------------------------------------------------------------


def _request_json(
    url: str,
    *,
    method: str = "GET",
    body: dict | None = None,
    headers: dict[str, str] | None = None,
    timeout_s: float = 30.0,
):
    """One JSON request to the server under test; RuntimeError with the server's answer on an HTTP error."""
    data = None if body is None else json.dumps(body).encode()
    request = urllib.request.Request(
        url, data=data, method=method, headers={"Content-Type": "application/json", **(headers or {})}
    )
    try:
        with urllib.request.urlopen(request, timeout=timeout_s) as answer:
            raw = answer.read()
    except urllib.error.HTTPError as exc:
        detail = exc.read()[:500].decode(errors="replace")
        raise RuntimeError(f"{method} {url} answered {exc.code}: {detail}") from None
    return json.loads(raw) if raw else None


def lesson_showing(chapters: Sequence[dict], scene_id: str) -> str:
    """The id of the first lesson (``GET /api/chapters``) that opens on ``scene_id``; ValueError naming ``scene``."""
    for chapter in chapters:
        for lesson in chapter.get("lessons") or ():
            if lesson.get("scene") == scene_id:
                return str(lesson["id"])
    raise ValueError(f"scene: no lesson opens on {scene_id!r}, so no room can show it")


def open_room(base_url: str, scene_id: str, *, instructor_key: str) -> dict:
    """Open a classroom room on ``scene_id`` (as the instructor): ``{"room_id", "code", "lesson_id", "scene_id"}``."""
    lesson_id = lesson_showing(_request_json(f"{base_url}/api/chapters"), scene_id)
    created = _request_json(
        f"{base_url}/api/rooms",
        method="POST",
        body={"lesson_id": lesson_id, "scene_id": scene_id},
        headers={INSTRUCTOR_HEADER: instructor_key},
    )
    return {"room_id": created["room_id"], "code": created["code"], "lesson_id": lesson_id, "scene_id": scene_id}


def close_room(base_url: str, room_id: str, *, instructor_key: str, timeout_s: float = 30.0) -> None:
    """Close a room the tool opened (its scene stops); a room already gone, or a server too busy to answer within
    ``timeout_s``, is fine (the server is stopped next)."""
    with contextlib.suppress(RuntimeError, OSError):
        _request_json(
            f"{base_url}/api/rooms/{room_id}",
            method="DELETE",
            headers={INSTRUCTOR_HEADER: instructor_key},
            timeout_s=timeout_s,
        )


async def _measure_one_viewer(server: ServerUnderTest, options: LoadOptions) -> list[dict]:
    """Per scene, one student on a scene of their own: what "one viewer" costs, to compare a followed room with."""
    steps = []
    for scene_id in options.scenes:
        step = await measure_step(server, scene_id, 1, options)
        steps.append(step)
        print(step_line(step), flush=True)
        await asyncio.sleep(PAUSE_BETWEEN_STEPS_S)
    return steps


def _measure_in_rooms(
    server: ServerUnderTest, options: LoadOptions, instructor_key: str
) -> tuple[list[dict], dict[str, dict], list[dict]]:
    """One viewer on its own scene first (no room open yet), then one room per scene and its followers at each
    class size; the rooms are closed at the end. Returns (follow steps, rooms by scene, one-viewer steps)."""
    one_viewer = asyncio.run(_measure_one_viewer(server, options))
    rooms: dict[str, dict] = {}
    try:
        for scene_id in options.scenes:
            rooms[scene_id] = open_room(server.base_url, scene_id, instructor_key=instructor_key)
        return asyncio.run(_measure_all(server, options, rooms)), rooms, one_viewer
    finally:
        for room in rooms.values():
            close_room(server.base_url, room["room_id"], instructor_key=instructor_key)


def run_load(options: LoadOptions) -> dict:
    """Measure every (scene, students) step of ``options``; returns the report (see the module docstring)."""
    key = options.instructor_key
    if options.room and key is None:
        key = secrets.token_urlsafe(24)  # the server the tool starts is given it; it is never printed
    child_key = key if options.room and options.url is None else None
    rooms: dict[str, dict] | None = None
    one_viewer: list[dict] = []
    with server_for(
        options.url, server_pid=options.server_pid, workers=options.workers, instructor_key=child_key
    ) as server:
        check_scenes(server.base_url, options.scenes)
        if options.room:
            assert key is not None
            steps, rooms, one_viewer = _measure_in_rooms(server, options, key)
        else:
            steps = asyncio.run(_measure_all(server, options))
        facts = server_facts(server)
    report = {
        "created": utc_now(),
        "machine": machine_facts(),
        "server": facts,
        "method": {
            "seconds": options.seconds,
            "warmup_s": options.warmup_s,
            "connect_per_s": options.connect_per_s,
            # Each student from its own loopback address (127.0.1.x), or every one from 127.0.0.1.
            "distinct_addresses": options.distinct_addresses,
            "frame": "one binary websocket message (a viser frame window), counted per client over the steady window",
            "health_period_s": 0.25,
            "health_slow_s": 2.0,
        },
        "targets": {
            "p10_frames_per_s": TARGET_P10_FRAMES_PER_S,
            "min_frames_per_s_degraded": DEGRADED_MIN_FRAMES_PER_S,
        },
        "steps": steps,
    }
    if rooms is not None:
        report.update(
            mode="follow",
            scene_id=options.scenes[0] if len(options.scenes) == 1 else list(options.scenes),
            rooms=[{"scene_id": r["scene_id"], "lesson_id": r["lesson_id"]} for r in rooms.values()],
            one_viewer=one_viewer,
            follow_cost=follow_cost(steps, one_viewer=one_viewer),
        )
    return report


def _step_at(steps: Sequence[dict], scene_id: str | None, students: int) -> dict | None:
    return next((s for s in steps if s.get("scene_id") == scene_id and s.get("students") == students), None)


def follow_cost(steps: Sequence[dict], *, one_viewer: Sequence[dict] = (), scene_id: str | None = None) -> dict:
    """Server CPU (cores) with 1 follower and with :data:`FOLLOW_COST_CLASS` followers of one scene (the first
    scene measured unless ``scene_id``), and with one student on a scene of their own (from ``one_viewer``);
    a size not measured is None, and so is a ratio then."""
    if scene_id is None:
        scene_id = str(steps[0]["scene_id"]) if steps else ""
    cpu = lambda step: step.get("server_cpu_cores") if step else None  # noqa: E731
    ratio = lambda a, b: round(a / b, 2) if a is not None and b else None  # noqa: E731
    cpu_1, cpu_class = cpu(_step_at(steps, scene_id, 1)), cpu(_step_at(steps, scene_id, FOLLOW_COST_CLASS))
    cpu_viewer = cpu(_step_at(one_viewer, scene_id, 1))
    return {
        "scene_id": scene_id,
        "cpu_cores_1": cpu_1,
        f"cpu_cores_{FOLLOW_COST_CLASS}": cpu_class,
        "one_viewer_cpu_cores": cpu_viewer,
        f"ratio_{FOLLOW_COST_CLASS}_to_1": ratio(cpu_class, cpu_1),
        f"ratio_{FOLLOW_COST_CLASS}_to_one_viewer": ratio(cpu_class, cpu_viewer),
    }


def with_independent_comparison(report: dict, independent: dict | None, *, source: str = CAPACITY_REPORT) -> dict:
    """A follow report with, per step, the independent viewers' figures at the same scene and class size
    (from a ``capacity.json`` report; ``independent`` None: none to compare) under ``"independent"``."""
    steps = (independent or {}).get("steps") or []
    rows = []
    for step in report["steps"]:
        match = _step_at(steps, step["scene_id"], step["students"])
        if match is not None and isinstance(match.get("frames_per_s"), dict):
            rows.append(
                {
                    "scene_id": step["scene_id"],
                    "students": step["students"],
                    "frames_per_s": match["frames_per_s"],
                    "server_cpu_cores": match.get("server_cpu_cores"),
                    "server_rss_mb": match.get("server_rss_mb"),
                }
            )
    comparison = {"source": source, "created": (independent or {}).get("created"), "steps": rows}
    cost = dict(report.get("follow_cost") or {})
    if cost:
        match = _step_at(steps, cost.get("scene_id"), FOLLOW_COST_CLASS)
        cost[f"independent_cpu_cores_{FOLLOW_COST_CLASS}"] = match.get("server_cpu_cores") if match else None
    return {**report, "independent": comparison, **({"follow_cost": cost} if cost else {})}


# ---- the report: JSON and a plot -------------------------------------------------------------

WIDTH, HEIGHT = 840, 460  # room on the right for the longest scene id in the legend
LEFT, RIGHT, TOP, BOTTOM = 70, 560, 64, 400
SCENE_COLOURS = ("#d0202e", "#1f5fbf", "#1b8a3a", "#7b2fa8", "#e67e00", "#00796b", "#5d4037")
#: Colours of the two ways a class watches a scene in ``classroom.svg``.
MODE_COLOURS = {"follow": "#d0202e", "independent": "#1f5fbf"}
MODE_NAMES = {"follow": "following one room's scene", "independent": "a scene each (capacity.json)"}


def _nice_ceiling(value: float, step: float) -> float:
    return step * max(1, math.ceil(value / step - 1e-9))


@dataclass(frozen=True)
class _Panel:
    """One plot area: students (0..``max_x``) across, a quantity (0..``max_y``) up, in SVG user units."""

    left: float
    right: float
    top: float
    bottom: float
    max_x: float
    max_y: float

    def x(self, n: float) -> float:
        return self.left + (self.right - self.left) * n / self.max_x

    def y(self, value: float) -> float:
        return self.bottom - (self.bottom - self.top) * value / self.max_y

    def frame(self, *, x_label: str, y_label: str, y_step: float) -> str:
        """Grid, ticks, the box and both axis labels."""
        grid = []
        x_tick = next(step for step in (1, 2, 5, 10, 20, 25, 50, 100) if self.max_x / step <= 10)
        for k in range(int(self.max_x / x_tick + 1e-9) + 1):
            n = k * x_tick
            grid.append(
                f'<line x1="{_f(self.x(n))}" x2="{_f(self.x(n))}" y1="{self.top}" y2="{self.bottom}" stroke="#eef0f4"/>'
            )
            grid.append(_text(self.x(n), self.bottom + 18, f"{n:g}", anchor="middle"))
        for k in range(int(self.max_y / y_step + 1e-9) + 1):
            value = k * y_step
            grid.append(
                f'<line x1="{_f(self.left)}" x2="{_f(self.right)}" y1="{_f(self.y(value))}" '
                f'y2="{_f(self.y(value))}" stroke="#eef0f4"/>'
            )
            grid.append(_text(self.left - 7, self.y(value) + 4, f"{value:g}", anchor="end"))
        cy, label_x = (self.top + self.bottom) / 2, self.left - 52
        return "".join(
            [
                '<g class="grid">',
                *grid,
                "</g>",
                f'<rect x="{_f(self.left)}" y="{_f(self.top)}" width="{_f(self.right - self.left)}" '
                f'height="{_f(self.bottom - self.top)}" fill="none" stroke="#9aa3b2"/>',
                _text((self.left + self.right) / 2, self.bottom + 42, x_label, size=13, anchor="middle", weight="600"),
                _text(
                    label_x,
                    cy,
                    y_label,
                    size=13,
                    anchor="middle",
                    weight="600",
                    extra=f'transform="rotate(-90 {_f(label_x)} {_f(cy)})"',
                ),
            ]
        )

    def target(self, value: float, label: str = "") -> str:
        """A dashed horizontal target line, labelled (unless ``label`` is empty) at its left end, under the line."""
        y = _f(self.y(value))
        return (
            f'<g class="target"><line x1="{_f(self.left)}" x2="{_f(self.right)}" y1="{y}" y2="{y}" stroke="#1d2330" '
            f'stroke-width="1.3" stroke-dasharray="6 4"/>'
            + (_text(self.left + 6, self.y(value) + 14, label, size=11, anchor="start", halo=True) if label else "")
            + "</g>"
        )

    def line(self, points: Sequence[tuple[float, float]], colour: str, *, dashed: bool, filled: bool) -> str:
        """A polyline through ``(students, value)`` points (two or more) with a circle on each."""
        out = []
        if len(points) >= 2:
            coords = " ".join(f"{_f(self.x(n))},{_f(self.y(v))}" for n, v in points)
            dash = ' stroke-dasharray="5 3"' if dashed else ""
            out.append(f'<polyline points="{coords}" fill="none" stroke="{colour}" stroke-width="2.2"{dash}/>')
        out.extend(_marker("circle", self.x(n), self.y(v), colour, filled, size=4) for n, v in points)
        return "".join(out)


def _svg_open(width: int, height: int, title: str, heading: str, subtitle: str) -> list[str]:
    return [
        f'<svg xmlns="{SVG_NS}" width="{width}" height="{height}" viewBox="0 0 {width} {height}" role="img" '
        f'font-family="{escape(FONT)}">',
        f"<title>{escape(title)}</title>",
        f'<rect width="{width}" height="{height}" fill="#ffffff"/>',
        _text(LEFT, 26, heading, size=17, weight="600"),
        _text(LEFT, 45, subtitle, size=12, fill="#5b6475"),
    ]


def _subtitle(report: dict) -> str:
    machine = report.get("machine") or {}
    server = report.get("server") or {}
    seconds = (report.get("method") or {}).get("seconds")
    return (
        f"{machine.get('cores', '?')} cores; scene workers: {describe_workers(server.get('workers'))}; "
        f"{f'{seconds:g}' if isinstance(seconds, (int, float)) else '?'} s steady window per point; "
        f"{str(report.get('created', ''))[:10]}"
    )


def _measured(steps: Iterable[object] | None) -> list[dict]:
    return [s for s in steps or () if isinstance(s, dict) and isinstance(s.get("frames_per_s"), dict)]


def _rate_panel(steps: Sequence[dict], *, left: float, right: float) -> _Panel:
    most = max([s["students"] for s in steps] + [10])
    rates = [s["frames_per_s"][k] for s in steps for k in ("p10", "median")]
    max_rate = _nice_ceiling(max(rates + [TARGET_P10_FRAMES_PER_S + 2]) + 3, 5)  # room above the top line
    return _Panel(left, right, TOP, BOTTOM, _nice_ceiling(most, 10 if most <= 100 else 50), max_rate)


def _rate_lines(panel: _Panel, points: Sequence[tuple[int, dict]], colour: str) -> str:
    """The median (dashed, open circles) and 10th percentile (solid, filled) of frames/s."""
    return "".join(
        panel.line([(n, fps[key]) for n, fps in points], colour, dashed=key == "median", filled=key == "p10")
        for key in ("median", "p10")
    )


def capacity_svg(report: dict) -> str:
    """Frames/s (10th percentile solid, median dashed) against students, one colour per scene; linear axes."""
    steps = _measured(report.get("steps"))
    scenes = list(dict.fromkeys(str(s["scene_id"]) for s in steps))
    panel = _rate_panel(steps, left=LEFT, right=RIGHT)
    out = _svg_open(
        WIDTH,
        HEIGHT,
        "Classroom capacity: frames per second delivered to each student against the number of students",
        "Classroom capacity: frames/s each student receives",
        _subtitle(report),
    )
    out.append(
        panel.frame(
            x_label="Students (one viewer and one scene each)", y_label="Frames per second per student", y_step=5
        )
    )
    # At the left end, under its line: small classes sit at 30 frames/s, above both lines, so nothing is hidden.
    out.append(
        panel.target(TARGET_P10_FRAMES_PER_S, f"target: 10th percentile at 100 students ({TARGET_P10_FRAMES_PER_S:g})")
    )
    out.append(panel.target(DEGRADED_MIN_FRAMES_PER_S, f"floor: every student at 150 ({DEGRADED_MIN_FRAMES_PER_S:g})"))
    legend_y = TOP + 8
    for index, scene_id in enumerate(scenes):
        colour = SCENE_COLOURS[index % len(SCENE_COLOURS)]
        points = sorted((s["students"], s["frames_per_s"]) for s in steps if s["scene_id"] == scene_id)
        out.append(f'<g class="series" data-scene="{escape(scene_id)}">{_rate_lines(panel, points, colour)}</g>')
        out.append(
            f'<line x1="{RIGHT + 16}" x2="{RIGHT + 44}" y1="{legend_y}" y2="{legend_y}" stroke="{colour}" '
            'stroke-width="2.2"/>' + _text(RIGHT + 52, legend_y + 4, scene_id)
        )
        legend_y += 20
    legend_y += 10
    out.append(_text(RIGHT + 16, legend_y, "solid, filled: 10th percentile", size=11, fill="#5b6475"))
    out.append(_text(RIGHT + 16, legend_y + 16, "dashed, open: median", size=11, fill="#5b6475"))
    if not steps:
        out.append(
            _text(
                (LEFT + RIGHT) / 2,
                (TOP + BOTTOM) / 2,
                "no step delivered frames",
                size=14,
                anchor="middle",
                fill="#d0202e",
            )
        )
    out.append("</svg>")
    return "\n".join(out) + "\n"


CLASSROOM_WIDTH, CLASSROOM_HEIGHT = 980, 540
#: The two panels of classroom.svg: frames/s on the left, server CPU on the right.
RATE_PANEL_X, CPU_PANEL_X = (LEFT, 440), (540, 910)


def classroom_svg(report: dict) -> str:
    """A ``--room`` report: frames/s (10th percentile solid, median dashed) and server CPU (cores) against
    students, following one room's scene (red) beside a scene each (blue, from ``report["independent"]``)."""
    follow = _measured(report.get("steps"))
    independent = _measured((report.get("independent") or {}).get("steps"))
    both = follow + independent
    rates = _rate_panel(both, left=RATE_PANEL_X[0], right=RATE_PANEL_X[1])
    cpu_values = [s["server_cpu_cores"] for s in both if isinstance(s.get("server_cpu_cores"), (int, float))]
    cpu_max = _nice_ceiling(max(cpu_values + [1.0]) * 1.08, 0.5)
    cpu = _Panel(CPU_PANEL_X[0], CPU_PANEL_X[1], TOP, BOTTOM, rates.max_x, cpu_max)
    cost = report.get("follow_cost") or {}
    scene = cost.get("scene_id") or report.get("scene_id") or "?"
    out = _svg_open(
        CLASSROOM_WIDTH,
        CLASSROOM_HEIGHT,
        "Classroom following one scene: frames per second each student receives and the server's CPU, against students",
        f"Classroom following one {scene} demo: frames/s each student receives, server CPU",
        _subtitle(report),
    )
    out.append(rates.frame(x_label="Students", y_label="Frames per second per student", y_step=5))
    out.append(rates.target(TARGET_P10_FRAMES_PER_S))  # labelled in the legend: the lines cross it
    out.append(
        cpu.frame(
            x_label="Students", y_label="Server CPU (cores, all its processes)", y_step=0.25 if cpu_max <= 2 else 0.5
        )
    )
    for mode, steps in (("independent", independent), ("follow", follow)):
        colour = MODE_COLOURS[mode]
        points = sorted((s["students"], s["frames_per_s"]) for s in steps)
        cores = sorted(
            (s["students"], s["server_cpu_cores"]) for s in steps if isinstance(s.get("server_cpu_cores"), (int, float))
        )
        out.append(
            f'<g class="series" data-mode="{mode}">{_rate_lines(rates, points, colour)}'
            f"{cpu.line(cores, colour, dashed=False, filled=True)}</g>"
        )
    legend_y = BOTTOM + 66
    for index, mode in enumerate(("follow", "independent")):
        x0 = LEFT + 300 * index
        out.append(
            f'<line x1="{x0}" x2="{x0 + 28}" y1="{legend_y}" y2="{legend_y}" stroke="{MODE_COLOURS[mode]}" '
            'stroke-width="2.2"/>' + _text(x0 + 36, legend_y + 4, MODE_NAMES[mode])
        )
    out.append(
        f'<line x1="{LEFT + 600}" x2="{LEFT + 628}" y1="{legend_y}" y2="{legend_y}" stroke="#1d2330" '
        'stroke-width="1.3" '
        f'stroke-dasharray="6 4"/>'
        + _text(LEFT + 636, legend_y + 4, f"target: 10th percentile at 100 ({TARGET_P10_FRAMES_PER_S:g})")
    )
    legend_y += 22
    out.append(
        _text(
            LEFT,
            legend_y,
            "Frames/s: solid, filled: 10th percentile; dashed, open: median. Server CPU: the "
            "server process and its scene workers.",
            size=11,
            fill="#5b6475",
        )
    )
    note = _follow_cost_note(cost)
    if note:
        out.append(_text(LEFT, legend_y + 26, note, size=12))
    if not follow:
        out.append(
            _text(
                sum(RATE_PANEL_X) / 2,
                (TOP + BOTTOM) / 2,
                "no step delivered frames",
                size=14,
                anchor="middle",
                fill="#d0202e",
            )
        )
    out.append("</svg>")
    return "\n".join(out) + "\n"


def _follow_cost_note(cost: dict) -> str:
    """The server's CPU with 1 and with 100 followers (and one viewer of its own scene, and 100 such) in words."""

    def cores(key: str) -> str | None:
        value = cost.get(key)
        return f"{value:g}" if isinstance(value, (int, float)) else None

    parts = [
        f"{label}: {cores(key)}"
        for key, label in (
            ("cpu_cores_1", "1 follower"),
            (f"cpu_cores_{FOLLOW_COST_CLASS}", f"{FOLLOW_COST_CLASS} followers"),
            ("one_viewer_cpu_cores", "1 viewer on its own scene"),
            (f"independent_cpu_cores_{FOLLOW_COST_CLASS}", f"{FOLLOW_COST_CLASS} on their own scenes"),
        )
        if cores(key) is not None
    ]
    return f"Server CPU (cores): {'; '.join(parts)}" if parts else ""


def write_report(report: dict, out_dir: Path, *, name: str | None = None, plot: bool = True) -> list[Path]:
    """Write the report as JSON (and its SVG plot) into ``out_dir``; returns the paths written.

    A follow report (``"mode": "follow"``) is ``classroom.json`` and ``.svg``, any other ``capacity.json`` and
    ``.svg``, unless ``name`` names the JSON file.
    """
    follow = report.get("mode") == "follow"
    out_dir.mkdir(parents=True, exist_ok=True)
    path = out_dir / (name or (CLASSROOM_REPORT if follow else CAPACITY_REPORT))
    path.write_text(json.dumps(report, indent=2, allow_nan=False) + "\n", encoding="utf-8")
    written = [path]
    if plot:
        svg = out_dir / (CLASSROOM_PLOT_FILE if follow else PLOT_FILE)
        svg.write_text(classroom_svg(report) if follow else capacity_svg(report), encoding="utf-8")
        written.append(svg)
    return written


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
    parser.add_argument(
        "--scene", action="append", metavar="ID", help="scene id (repeatable or a comma list; default heavy-top)"
    )
    parser.add_argument(
        "--workers", type=int, default=None, help="passed to `dynlab serve --workers` when the tool starts the server"
    )
    parser.add_argument(
        "--url", default=None, help="a running server on loopback (http://127.0.0.1:PORT) instead of starting one"
    )
    parser.add_argument(
        "--server-pid", type=int, default=None, help="with --url: the server's pid, to measure its CPU and memory"
    )
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT_DIR, help="folder for the report (default docs/bench)")


def add_load_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of ``dynlab load``."""
    parser.add_argument(
        "--students",
        type=_int_list,
        default=None,
        help=(
            "class sizes, e.g. 10,30,60,100,150 (the default; with --room 1,10,30,60,100,150; with --attack one "
            "size, 100)"
        ),
    )
    parser.add_argument(
        "--seconds",
        type=float,
        default=None,
        help=f"steady window per step (s, ≤ {MAX_STEP_SECONDS:g}; default {LoadOptions.seconds:g}, with --attack "
        f"{ATTACK_SECONDS:g} "
        "for each of the two windows)",
    )
    parser.add_argument(
        "--warmup", type=float, default=LoadOptions.warmup_s, help="seconds after all connected before measuring"
    )
    parser.add_argument(
        "--connect-rate", type=float, default=LoadOptions.connect_per_s, help="viewers opened per second"
    )
    parser.add_argument(
        "--room",
        action="store_true",
        help=(
            "the students follow one classroom room on the scene instead of a scene each (writes classroom.json "
            "and .svg)"
        ),
    )
    parser.add_argument(
        "--attack",
        action="store_true",
        help="students on their own scenes, measured first alone and then while one client attacks the class with "
        "every attack the class-safety issue found (room, sessions, floods, bursts, expensive requests); writes "
        "attack.json and .svg",
    )
    parser.add_argument(
        "--distinct-addresses",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="each student connects from its own loopback address (127.0.1.1, 127.0.1.2, …) as a class of devices "
        "does, so per-device limits see students, not one client (default: on; off from one address is refused "
        "beyond 8 viewers)",
    )
    parser.add_argument(
        "--instructor-key",
        default=None,
        help="with --room or --attack and --url: the server's instructor secret, to open the room (a server the tool "
        "starts gets its own)",
    )
    add_server_arguments(parser)


def run_load_command(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    """Measure, print one line per step, write capacity.json and capacity.svg (with ``--room``: classroom.json and
    classroom.svg, beside the independent figures of the capacity.json in ``--out``; with ``--attack``: attack.json
    and attack.svg); bad options exit through ``parser``."""
    default_students = (ATTACK_STUDENTS,) if args.attack else ROOM_STUDENTS if args.room else LoadOptions.students
    students = args.students if args.students is not None else default_students
    seconds = args.seconds if args.seconds is not None else ATTACK_SECONDS if args.attack else LoadOptions.seconds
    try:
        options = LoadOptions(
            scenes=_scene_list(args.scene, LoadOptions.scenes),
            students=students,
            seconds=seconds,
            warmup_s=args.warmup,
            connect_per_s=args.connect_rate,
            workers=args.workers,
            url=args.url,
            server_pid=args.server_pid,
            room=args.room,
            instructor_key=args.instructor_key,
            distinct_addresses=args.distinct_addresses,
            attack=args.attack,
        )
    except ValueError as exc:
        parser.error(str(exc))
    if options.attack:
        from app.bench.under_attack import run_attack_command  # it builds on this module

        return run_attack_command(options, out_dir=args.out)
    try:
        report = run_load(options)
    except (RuntimeError, ValueError) as exc:
        print(f"dynlab load: {exc}", file=sys.stderr)
        return 1
    if options.room:
        try:
            independent = read_capacity_report(args.out / CAPACITY_REPORT)
        except ValueError as exc:
            print(f"dynlab load: no comparison with independent viewers: {exc}", file=sys.stderr)
            independent = None
        report = with_independent_comparison(report, independent)
    for path in write_report(report, args.out):
        print(path)
    return 0
