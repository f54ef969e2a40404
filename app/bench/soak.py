"""``dynlab soak``: a class stays for a long time, then leaves; the server must give back what it took.

Sequence: the whole class connects for a short warm-up and leaves (the first
scene builds load numba kernels and fill caches, and the thread pools of viser
and of the web server grow to the size this class needs and keep their threads
by design: none of that is a leak, which grows with time, not with the first
minute), the server settles, and the **baseline** is taken: resident
memory, open file descriptors and threads of the server's process tree. Then
``--students`` viewers stay for ``--minutes`` (frame rates and usage sampled
each minute), all close, and the tool waits up to 30 s for the server to settle
before the **end** reading. The run passes when no viewer failed, the end
memory is within 10 % of the baseline, and file descriptors and threads are back
to (at most) their baseline. ``docs/bench/soak.json`` gives the figures; the
exit code is 0 only on a pass.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import math
import sys
import time
from collections.abc import Awaitable, Callable
from dataclasses import asdict
from pathlib import Path
from typing import Any

from app.bench.capacity import (
    PAUSE_BETWEEN_STEPS_S,
    ServerUnderTest,
    add_server_arguments,
    check_scenes,
    frame_rate_summary,
    machine_facts,
    per_client_rates,
    server_facts,
    server_for,
    utc_now,
    write_report,
)
from app.bench.load_client import Classroom, health_request_ms
from app.bench.process_tree import TreeUsage

SOAK_FILE = "soak.json"
MAX_STUDENTS = 500
MAX_MINUTES = 180.0
#: End memory may exceed the baseline by this fraction.
RSS_TOLERANCE = 0.10
#: Seconds to wait, after every viewer closed, for memory, descriptors and threads to come back.
SETTLE_TIMEOUT_S = 30.0
#: How long the warm-up class stays before the baseline (s).
WARMUP_S = 20.0
#: Frame rates and usage are sampled this often while the class is connected (s).
SAMPLE_PERIOD_S = 60.0


def settled(baseline: TreeUsage, now: TreeUsage) -> bool:
    """True when ``now`` is back to ``baseline``: memory within :data:`RSS_TOLERANCE`, no extra fds or threads."""
    return (
        now.rss_mb <= baseline.rss_mb * (1.0 + RSS_TOLERANCE)
        and now.fds <= baseline.fds
        and now.threads <= baseline.threads
    )


def judge_soak(baseline: TreeUsage, end: TreeUsage, *, errors: int) -> dict:
    """The soak's verdict: each check with its figures, and ``passed`` only if all hold."""
    rss_ratio = end.rss_mb / baseline.rss_mb if baseline.rss_mb > 0 else math.inf
    checks: dict[str, dict[str, Any]] = {
        "no_errors": {"passed": errors == 0, "errors": errors},
        "rss_within_10_percent": {
            "passed": rss_ratio <= 1.0 + RSS_TOLERANCE,
            "ratio_end_to_start": round(rss_ratio, 4) if math.isfinite(rss_ratio) else None,
        },
        "fds_back_to_baseline": {"passed": end.fds <= baseline.fds, "start": baseline.fds, "end": end.fds},
        "threads_back_to_baseline": {
            "passed": end.threads <= baseline.threads,
            "start": baseline.threads,
            "end": end.threads,
        },
    }
    return {"passed": all(check["passed"] for check in checks.values()), "checks": checks}


async def wait_until_settled(
    read: Callable[[], TreeUsage],
    baseline: TreeUsage,
    *,
    timeout_s: float,
    poll_s: float = 1.0,
    poke: Callable[[], Awaitable[object]] | None = None,
) -> TreeUsage:
    """Read usage every ``poll_s`` until it is back to ``baseline`` or ``timeout_s`` passes; returns the last reading.

    ``poke`` (awaited before each poll) stands for the next request a real server gets: anyio retires worker
    threads idle for 10 s only when a new call comes in, so a server left without any request keeps them.
    """
    deadline = time.monotonic() + timeout_s
    now = read()
    while not settled(baseline, now) and time.monotonic() < deadline:
        await asyncio.sleep(poll_s)
        if poke is not None:
            await poke()
        now = read()
    return now


def _usage_now(server: ServerUnderTest) -> TreeUsage:
    """The server's process tree now; the soak always runs a server of its own, so there is one to measure."""
    usage = server.usage()
    if usage is None:
        raise RuntimeError("soak: the server under test has no process to measure")
    return usage


def _usage_dict(usage: TreeUsage) -> dict:
    return {key: round(value, 1) if isinstance(value, float) else value for key, value in asdict(usage).items()}


async def _soak(server: ServerUnderTest, scene_id: str, students: int, minutes: float, connect_per_s: float) -> dict:
    host, port = server.address
    cold = _usage_now(server)
    warmup = Classroom(host, port, scene_id, students, connect_per_s=connect_per_s)
    try:
        await warmup.open(timeout_s=30.0 + students / connect_per_s)
        await asyncio.sleep(WARMUP_S)
    finally:
        await warmup.close()
    await asyncio.sleep(PAUSE_BETWEEN_STEPS_S)
    await health_request_ms(host, port)  # the web server retires idle pool threads only when a request arrives
    baseline = _usage_now(server)
    peak = baseline
    samples = []
    classroom = Classroom(host, port, scene_id, students, connect_per_s=connect_per_s)
    try:
        await classroom.open(timeout_s=30.0 + students / connect_per_s)
        started = time.monotonic()
        end_at = started + 60.0 * minutes
        previous = classroom.snapshot()
        while (remaining := end_at - time.monotonic()) > 0:
            await asyncio.sleep(min(SAMPLE_PERIOD_S, remaining))
            current, usage = classroom.snapshot(), _usage_now(server)
            peak = TreeUsage(*(max(a, b) for a, b in zip(_fields(peak), _fields(usage))))
            samples.append(
                {
                    "minute": round((current.at_s - started) / 60.0, 2),
                    "frames_per_s": frame_rate_summary(per_client_rates(previous, current, classroom.healthy())),
                    "connected": sum(classroom.healthy()),
                    **{f"server_{k}": v for k, v in _usage_dict(usage).items() if k != "cpu_s"},
                }
            )
            print(f"soak minute {samples[-1]['minute']}: {samples[-1]}", flush=True)
            previous = current
    finally:
        errors = classroom.errors()
        await classroom.close()
    end = await wait_until_settled(
        lambda: _usage_now(server), baseline, timeout_s=SETTLE_TIMEOUT_S, poke=lambda: health_request_ms(host, port)
    )
    verdict = judge_soak(baseline, end, errors=len(errors))
    return {
        "scene_id": scene_id,
        "students": students,
        "minutes": minutes,
        "baseline_note": (
            f"baseline taken after the same class stayed {WARMUP_S:g} s and left: the first scene builds load numba "
            "kernels and fill caches, and viser's and the web server's thread pools grow to this class's size and keep "
            "their threads, all on purpose and not leaks (a leak grows with time, which the soak measures); "
            "'cold' is the server before any viewer; while settling, one GET /api/health per second stands for the "
            "next request (anyio retires idle worker threads only then)"
        ),
        "cold": _usage_dict(cold),
        "start": _usage_dict(baseline),
        "peak": _usage_dict(peak),
        "end": _usage_dict(end),
        "rss_ratio_end_to_start": verdict["checks"]["rss_within_10_percent"]["ratio_end_to_start"],
        "errors": len(errors),
        "error_examples": sorted(set(errors))[:3],
        "samples": samples,
        **verdict,
    }


def _fields(usage: TreeUsage) -> tuple:
    return tuple(asdict(usage).values())


def run_soak(
    scene_id: str,
    students: int,
    minutes: float,
    *,
    workers: int | None = None,
    url: str | None = None,
    server_pid: int | None = None,
    connect_per_s: float = 50.0,
) -> dict:
    """Run the soak (see the module docstring) and return its report."""
    if not 1 <= students <= MAX_STUDENTS:
        raise ValueError(f"students: must be 1..{MAX_STUDENTS}, got {students}")
    if not (math.isfinite(minutes) and 0 < minutes <= MAX_MINUTES):
        raise ValueError(f"minutes: must be in (0, {MAX_MINUTES:g}], got {minutes!r}")
    if url is not None and server_pid is None:
        raise ValueError(
            "server_pid: a soak measures the server's memory, fds and threads; give --server-pid with --url"
        )
    with server_for(url, server_pid=server_pid, workers=workers) as server:
        check_scenes(server.base_url, [scene_id])
        result = asyncio.run(_soak(server, scene_id, students, minutes, connect_per_s))
        facts = server_facts(server)
    return {"created": utc_now(), "machine": machine_facts(), "server": facts, **result}


def add_soak_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of ``dynlab soak``."""
    parser.add_argument("--students", type=int, default=100, help=f"viewers that stay (1..{MAX_STUDENTS})")
    parser.add_argument("--minutes", type=float, default=10.0, help=f"how long they stay (≤ {MAX_MINUTES:g})")
    add_server_arguments(parser)


def run_soak_command(args: argparse.Namespace, parser: argparse.ArgumentParser) -> int:
    """Run, print the verdict, write soak.json; exit code 0 only if it passed. Bad options exit through ``parser``."""
    scenes = [part for value in args.scene or ["heavy-top"] for part in value.split(",") if part]
    if len(scenes) != 1:
        parser.error(f"scene: a soak runs one scene, got {', '.join(scenes)}")
    try:
        report = run_soak(
            scenes[0], args.students, args.minutes, workers=args.workers, url=args.url, server_pid=args.server_pid
        )
    except ValueError as exc:
        parser.error(str(exc))
    except RuntimeError as exc:
        print(f"dynlab soak: {exc}", file=sys.stderr)
        return 1
    for path in write_report(report, Path(args.out), name=SOAK_FILE, plot=False):
        print(path)
    print("soak " + ("PASSED" if report["passed"] else "FAILED") + ": " + json.dumps(report["checks"]))
    return 0 if report["passed"] else 1
