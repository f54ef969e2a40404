"""``dynlab restart``: how long a class waits when ``dynlab serve`` is restarted under it, and that it loses nothing.

The tool starts its own ``dynlab serve`` (default workers) on a loopback port with a data directory of its own,
opens a room on the heavy top as its instructor, lets N students join from N loopback addresses (127.0.1.1, …), each
answer a poll and follow the room's scene with a viewer that reconnects as viser's client does (half a second after a
drop). Then, ``--restarts`` times: Ctrl+C, the same command again on the same port and data directory, and the
clock from Ctrl+C to: the server stopped; ``/api/health`` answering; the room's state answering with every student
and answer it had; each student's viewer receiving frames of the room's scene again. Writes docs/bench/restart.json
and restart.svg. Student counts and restarts are bounded (:data:`MAX_STUDENTS`, :data:`MAX_RESTARTS`).
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import secrets
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable
from html import escape
from pathlib import Path
from typing import Any

from app.bench.capacity import (
    DEFAULT_OUT_DIR,
    PROJECT_ROOT,
    SERVER_START_TIMEOUT_S,
    SERVER_STOP_TIMEOUT_S,
    machine_facts,
    open_room,
    stop_process_group,
    utc_now,
    wait_for_health,
)
from app.bench.load_client import ReconnectingViewer, http_request, student_address
from app.bench.ports import free_loopback_port
from app.classroom.roles import HEADER as INSTRUCTOR_HEADER

REPORT = "restart.json"
SVG = "restart.svg"
DEFAULT_STUDENTS = 30
DEFAULT_RESTARTS = 3
MAX_STUDENTS = 100
MAX_RESTARTS = 10
#: Longest wait for the class to be back after a restart (s); beyond it the restart is reported as failed.
BACK_TIMEOUT_S = 90.0
SCENE = "heavy-top"


def _request(port: int, method: str, path: str, *, address: str = "127.0.0.1", **options: Any) -> Any:
    answer = asyncio.run(
        http_request("127.0.0.1", port, method, path, source_address=address, timeout_s=30.0, **options)
    )
    if answer.status != 200:
        raise RuntimeError(f"{method} {path}: {answer.label} {answer.detail()}")
    return json.loads(answer.body)


class Served:
    """``python -m app.cli serve`` on ``port`` with ``data_dir``, started and stopped as a user does."""

    def __init__(self, port: int, data_dir: str, instructor_key: str, workers: int | None) -> None:
        self.port = port
        self.command = [sys.executable, "-m", "app.cli", "serve", "--port", str(port), "--log-level", "warning"]
        if workers is not None:
            self.command += ["--workers", str(workers)]
        self.env = {**os.environ, "DYNLAB_DATA_DIR": data_dir, "DYNLAB_INSTRUCTOR_KEY": instructor_key}
        self.env.pop("DYNLAB_DATABASE_URL", None)
        self.process: subprocess.Popen[bytes] | None = None

    @property
    def base_url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def start(self) -> None:
        self.process = subprocess.Popen(
            self.command,
            cwd=PROJECT_ROOT,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            env=self.env,
            start_new_session=True,
        )
        wait_for_health(self.base_url, timeout_s=SERVER_START_TIMEOUT_S, process=self.process)

    def stop(self) -> float | None:
        assert self.process is not None
        return stop_process_group(self.process, timeout_s=SERVER_STOP_TIMEOUT_S).seconds


def _wait(condition: Callable[[], bool], timeout_s: float) -> float | None:
    """Seconds until ``condition()`` holds (polled every 50 ms), or None past ``timeout_s``."""
    started = time.monotonic()
    while time.monotonic() - started < timeout_s:
        try:
            if condition():
                return time.monotonic() - started
        except (RuntimeError, OSError, ValueError):
            pass
        time.sleep(0.05)
    return None


def _one_restart(served: Served, room_id: str, before: dict, followers: list[ReconnectingViewer]) -> dict:
    """Ctrl+C, start again, and the seconds from Ctrl+C until each part of the class is back."""
    port, students = served.port, before["students"]["joined"]
    stopped_at = time.monotonic()
    stop_s = served.stop()
    served.start()
    health_s = time.monotonic() - stopped_at

    def state_back() -> bool:
        state = _request(port, "GET", f"/api/rooms/{room_id}/state")
        kept = ("params", "playing", "time_scale", "mode")
        everyone = state["students"]["joined"] == students and state["poll"]["answers"] == before["poll"]["answers"]
        return everyone and all(state[name] == before[name] for name in kept)

    state_wait = _wait(state_back, BACK_TIMEOUT_S)
    restarted_at = stopped_at + (stop_s or 0.0)
    back_at: dict[int, float] = {}

    def all_back() -> bool:
        for index, follower in enumerate(followers):
            if index not in back_at and follower.last_frame_s > restarted_at:
                back_at[index] = time.monotonic() - stopped_at
        return len(back_at) == len(followers)

    _wait(all_back, BACK_TIMEOUT_S)
    times = sorted(back_at.values())
    return {
        "stop_s": None if stop_s is None else round(stop_s, 2),
        "health_s": round(health_s, 2),
        "state_s": None if state_wait is None else round(health_s + state_wait, 2),
        "lost_nothing": state_wait is not None,
        "followers_back": len(times),
        "follower_back_median_s": round(statistics.median(times), 2) if times else None,
        "follower_back_last_s": round(times[-1], 2) if times else None,
    }


def run_restarts(*, students: int, restarts: int, workers: int | None) -> dict:
    """The measurement (see the module docstring): one dict per restart, and the summary."""
    instructor_key = secrets.token_urlsafe(18)
    with tempfile.TemporaryDirectory(prefix="dynlab-restart-") as data_dir:
        served = Served(free_loopback_port(), data_dir, instructor_key, workers)
        served.start()
        port, instructor = served.port, {INSTRUCTOR_HEADER: instructor_key}
        measured: list[dict] = []
        followers: list[ReconnectingViewer] = []
        try:
            room = open_room(served.base_url, SCENE, instructor_key=instructor_key)
            room_id = room["room_id"]
            question = {"question": "Will it stay up?", "kind": "choice", "choices": ["yes", "no"]}
            poll = _request(port, "POST", f"/api/rooms/{room_id}/polls", headers=instructor, body=question)
            for index in range(students):
                address = student_address(index)
                joined = _request(port, "POST", "/api/rooms/join", address=address, body={"code": room["code"]})
                _request(port, "POST", f"/api/rooms/{room_id}/polls/{poll['poll_id']}/answers", address=address,
                         headers={"X-Student-Token": joined["student_token"]}, body={"choice": index % 2})  # fmt: skip
                followers.append(ReconnectingViewer(served.base_url, f"/room-viewer/{room_id}", address=address))
            before = _request(port, "GET", f"/api/rooms/{room_id}/state")
            if _wait(lambda: all(f.frames > 0 for f in followers), BACK_TIMEOUT_S) is None:
                raise RuntimeError("the followers did not all receive frames before the first restart")
            measured = [_one_restart(served, room_id, before, followers) for _ in range(restarts)]
        finally:
            for follower in followers:
                follower.close()
            if served.process is not None and served.process.poll() is None:
                served.stop()
    return {
        "created": utc_now(),
        "machine": machine_facts(),
        "scene": SCENE,
        "students": students,
        "workers": workers,
        "restarts": measured,
        "summary": {
            key: round(statistics.median(r[key] for r in measured if r[key] is not None), 2)
            for key in ("stop_s", "health_s", "state_s", "follower_back_median_s", "follower_back_last_s")
            if any(r[key] is not None for r in measured)
        },
        "lost_nothing": all(r["lost_nothing"] and r["followers_back"] == students for r in measured),
    }


def restart_svg(report: dict) -> str:
    """One row per restart: stacked marks for the server stopped, health, the room's state, the median and the last
    follower back (s from Ctrl+C)."""
    rows = report["restarts"]
    width, left, right, top, row_h = 720, 120, 690, 70, 26
    height = top + row_h * len(rows) + 60
    longest = max([1.0, *(r["follower_back_last_s"] or 0.0 for r in rows), *(r["state_s"] or 0.0 for r in rows)])
    x = lambda v: left + (right - left) * v / (longest * 1.1)  # noqa: E731
    marks = (
        ("stop_s", "#888", "stopped"),
        ("health_s", "#1f6fb5", "health"),
        ("state_s", "#1b8a3a", "room state"),
        ("follower_back_median_s", "#c77800", "median follower"),
        ("follower_back_last_s", "#d0202e", "last follower"),
    )
    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" '
        'font-family="DejaVu Sans, sans-serif">',
        f'<rect width="{width}" height="{height}" fill="#fff"/>',
        f'<text x="16" y="26" font-size="15" font-weight="600">dynlab serve restarted under a class of '
        f"{report['students']} followers with a poll answered</text>",
        '<text x="16" y="46" font-size="11" fill="#555">seconds from Ctrl+C until each is back; '
        f"{escape(report['machine'].get('cpu', ''))[:70]}</text>",
    ]
    for i, row in enumerate(rows):
        y = top + i * row_h
        out.append(f'<text x="{left - 10}" y="{y + 15}" font-size="12" text-anchor="end">restart {i + 1}</text>')
        out.append(f'<line x1="{left}" x2="{right}" y1="{y + 11}" y2="{y + 11}" stroke="#eee"/>')
        for key, colour, _ in marks:
            if row[key] is not None:
                out.append(f'<circle cx="{x(row[key]):.1f}" cy="{y + 11}" r="5" fill="{colour}"/>')
    bottom = top + row_h * len(rows)
    for tick in range(int(longest * 1.1) + 1):
        out.append(f'<text x="{x(tick):.1f}" y="{bottom + 16}" font-size="10" text-anchor="middle">{tick}</text>')
    out.append(f'<text x="{right + 4}" y="{bottom + 16}" font-size="10">s</text>')
    for j, (_, colour, label) in enumerate(marks):
        out.append(f'<circle cx="{left + j * 120}" cy="{bottom + 36}" r="5" fill="{colour}"/>')
        out.append(f'<text x="{left + j * 120 + 9}" y="{bottom + 40}" font-size="11">{label}</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="dynlab restart", description=__doc__.splitlines()[0])
    parser.add_argument("--students", type=int, default=DEFAULT_STUDENTS, help=f"followers (1 to {MAX_STUDENTS})")
    parser.add_argument("--restarts", type=int, default=DEFAULT_RESTARTS, help=f"restarts (1 to {MAX_RESTARTS})")
    parser.add_argument("--workers", type=int, default=None, help="passed to dynlab serve --workers")
    parser.add_argument("--out", type=Path, default=DEFAULT_OUT_DIR, help="where restart.json and .svg go")
    args = parser.parse_args(argv)
    if not 1 <= args.students <= MAX_STUDENTS or not 1 <= args.restarts <= MAX_RESTARTS:
        parser.error(f"--students 1 to {MAX_STUDENTS}, --restarts 1 to {MAX_RESTARTS}")
    report = run_restarts(students=args.students, restarts=args.restarts, workers=args.workers)
    args.out.mkdir(parents=True, exist_ok=True)
    (args.out / REPORT).write_text(json.dumps(report, indent=1) + "\n")
    (args.out / SVG).write_text(restart_svg(report))
    for i, row in enumerate(report["restarts"], 1):
        print(f"restart {i}: " + ", ".join(f"{k} {v}" for k, v in row.items()))
    print(f"median: {report['summary']}; lost nothing: {report['lost_nothing']} → {args.out / REPORT}")
    return 0 if report["lost_nothing"] else 1
