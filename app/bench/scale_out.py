"""``dynlab scale-out``: one class on two servers behind HAProxy, sharing PostgreSQL, on loopback; how fast the
instructor's changes reach students on the other server, and how long the class waits when a server dies.

The tool starts a throwaway PostgreSQL (app.bench.loopback_postgres), two ``dynlab serve`` (default workers, each
with a data directory of its own, both on the database) and HAProxy with deploy/haproxy.cfg, all on loopback ports.
The instructor opens a room on the heavy top through the balancer; N students join through it (round robin: both
servers take the room up) from N loopback addresses. Half the students' room sockets and viewers go through the
balancer (to the server the room's id hashes to), the other half straight to the other server, as a class split
between servers is (a balancer's health check moving a room, a rolling restart); every page reconnects through the
balancer after a drop, as a browser does.

Then: the instructor changes the scene's spin K times through the balancer, and the clock runs from sending each
change to each student's socket receiving the state that shows it (follow latency, per student and change); a poll is
opened and everyone answers on their own server; the instructor's results show every answer. Last, the server the
room hashes to is killed (SIGKILL, its workers with it) and the clock runs until every student's socket has the room's
state back with the same spin, play state and answers, the instructor's list shows every student connected, and every
student's viewer receives frames again (failover); a lesson page's own scene that lived on the killed server answers
from the other with its parameters, and still refuses a change without its key. Writes docs/bench/scale_out.json and
scale_out.svg.
"""

from __future__ import annotations

import argparse
import asyncio
import json
import os
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import ExitStack, contextmanager
from html import escape
from pathlib import Path
from typing import Any

import sqlalchemy as sa

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
from app.bench.load_client import (
    SESSION_KEY_HEADER,
    ReconnectingViewer,
    http_request,
    new_session_id,
    new_session_key,
    student_address,
)
from app.bench.loopback_postgres import postgres_server
from app.bench.ports import free_loopback_port
from app.classroom.roles import HEADER as INSTRUCTOR_HEADER

REPORT = "scale_out.json"
SVG = "scale_out.svg"
BALANCER_CONFIG = PROJECT_ROOT / "deploy" / "haproxy.cfg"
SCENE = "heavy-top"
#: The parameter the instructor changes, and the values it alternates between (rad/s).
SPIN_PARAMETER = "spin_rad_s"
SPIN_VALUES = (55.0, 70.0)
#: The spin of the lesson page's own scene that must survive its server (rad/s).
SESSION_SPIN = 61.0
DEFAULT_STUDENTS = 30
DEFAULT_CHANGES = 20
MAX_STUDENTS = 100
MAX_CHANGES = 200
#: Longest wait for a change to reach every student, or for the class to be back after the kill (s).
WAIT_TIMEOUT_S = 60.0
#: Seconds between two of the instructor's changes (a class sees each; the next is not sent into the last).
CHANGE_PERIOD_S = 0.4


def haproxy_binary() -> str | None:
    return shutil.which("haproxy") or next((p for p in ("/usr/sbin/haproxy",) if os.access(p, os.X_OK)), None)


def _request(base: str, method: str, path: str, *, address: str = "127.0.0.1", **options: Any) -> tuple[Any, str]:
    """A JSON request to ``base`` (``http://127.0.0.1:port``); its answer and the server that gave it (HAProxy's
    ``X-Dynlab-Server``, empty straight from a server)."""
    port = int(base.rsplit(":", 1)[1])
    answer = asyncio.run(
        http_request("127.0.0.1", port, method, path, source_address=address, timeout_s=30.0, **options)
    )
    if answer.status != 200:
        raise RuntimeError(f"{method} {path}: {answer.label} {answer.detail()}")
    return json.loads(answer.body), answer.headers.get("x-dynlab-server", "")


class Server:
    """One ``dynlab serve`` on ``port`` sharing ``database_url``, with a data directory of its own."""

    def __init__(self, name: str, port: int, database_url: str, data_dir: str, public_url: str) -> None:
        self.name, self.port = name, port
        self.command = [sys.executable, "-m", "app.cli", "serve", "--port", str(port), "--log-level", "warning"]
        self.env = {
            **os.environ,
            "DYNLAB_DATABASE_URL": database_url,
            "DYNLAB_DATA_DIR": data_dir,
            "DYNLAB_PUBLIC_URL": public_url,
            "DYNLAB_TRUST_FORWARDED_FOR": "1",  # behind the balancer: each student's own address counts, not its
        }
        self.env.pop("DYNLAB_INSTRUCTOR_KEY", None)  # the database keeps one secret for both
        self.log_path = Path(data_dir) / "serve.log"
        self.process: subprocess.Popen[bytes] | None = None

    @property
    def base_url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def start(self) -> None:
        self.log_path.parent.mkdir(parents=True, exist_ok=True)
        self.process = subprocess.Popen(
            self.command,
            cwd=PROJECT_ROOT,
            stdout=subprocess.DEVNULL,
            stderr=self.log_path.open("ab"),
            env=self.env,
            start_new_session=True,
        )

    def wait_healthy(self) -> None:
        wait_for_health(self.base_url, timeout_s=SERVER_START_TIMEOUT_S, process=self.process)

    def kill(self) -> None:
        """SIGKILL to the server and its scene workers (a crash, a machine lost)."""
        assert self.process is not None
        os.killpg(self.process.pid, signal.SIGKILL)
        self.process.wait(timeout=10)

    def stop(self) -> None:
        if self.process is not None and self.process.poll() is None:
            stop_process_group(self.process, timeout_s=SERVER_STOP_TIMEOUT_S)


@contextmanager
def balancer(port: int, servers: list[Server]) -> Iterator[subprocess.Popen[bytes]]:
    """HAProxy on ``port`` with deploy/haproxy.cfg in front of ``servers`` (two)."""
    binary = haproxy_binary()
    if binary is None:
        raise RuntimeError("HAProxy is not installed: apt-get install haproxy (tests/run.sh does)")
    env = {
        **os.environ,
        "DYNLAB_BALANCER_BIND": f"127.0.0.1:{port}",
        **{f"DYNLAB_SERVER_{i + 1}": f"127.0.0.1:{server.port}" for i, server in enumerate(servers)},
    }
    process = subprocess.Popen(
        [binary, "-db", "-f", str(BALANCER_CONFIG)],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    try:
        wait_for_health(f"http://127.0.0.1:{port}", timeout_s=30.0, process=process)
        yield process
    finally:
        process.terminate()
        try:
            process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            process.kill()


class RoomPage:
    """A page's room socket, in a thread: it connects to ``base_url`` (a student's says hello with its token), keeps
    every state and students message with the monotonic time it arrived, and after a drop reconnects to
    ``reconnect_url`` half a second later, as the room page does."""

    def __init__(
        self,
        base_url: str,
        reconnect_url: str,
        room_id: str,
        *,
        address: str,
        token: str | None = None,
        headers: dict[str, str] | None = None,
    ) -> None:
        self.path = f"/api/rooms/{room_id}/socket"
        self.url, self.reconnect_url = base_url, reconnect_url
        self.address, self.token, self.headers = address, token, headers or {}
        self.states: list[tuple[float, dict]] = []
        self.students: list[tuple[float, list[dict]]] = []
        self.results: list[tuple[float, dict]] = []
        self.errors: list[str] = []
        self.connections = 0
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name=f"room page {address}", daemon=True)
        self._thread.start()

    def _run(self) -> None:
        from websockets.sync.client import connect

        first = True
        while not self._stop.is_set():
            url = (self.url if first else self.reconnect_url).replace("http://", "ws://")
            first = False
            try:
                with connect(
                    url + self.path,
                    additional_headers=self.headers,
                    open_timeout=10,
                    source_address=(self.address, 0),
                ) as socket:
                    self.connections += 1
                    socket.send(json.dumps({"type": "hello", "student_token": self.token, "following": True}))
                    while not self._stop.is_set():
                        try:
                            text = socket.recv(timeout=0.5)
                        except TimeoutError:
                            continue
                        self._keep(json.loads(text))
            except Exception as exc:  # noqa: BLE001 - a drop: reconnect, as the page does
                if not self._stop.is_set():
                    self.errors.append(type(exc).__name__)
            self._stop.wait(0.5)

    def _keep(self, message: dict) -> None:
        now = time.monotonic()
        if message.get("type") == "state":
            self.states.append((now, message["state"]))
        elif message.get("type") == "students":
            self.students.append((now, message["students"]))
        elif message.get("type") == "results":
            self.results.append((now, message["results"]))
        elif message.get("type") == "error":
            self.errors.append(str(message.get("detail")))

    def first_state_since(self, since_s: float, wanted: Callable[[dict], bool]) -> float | None:
        """When the first state after ``since_s`` that ``wanted`` accepts arrived (None: none yet)."""
        return next((at for at, state in list(self.states) if at >= since_s and wanted(state)), None)

    def close(self) -> None:
        self._stop.set()
        self._thread.join(timeout=10)


def _wait(condition: Callable[[], bool], timeout_s: float) -> float | None:
    """Seconds until ``condition()`` holds (polled every 20 ms), or None past ``timeout_s``."""
    started = time.monotonic()
    while time.monotonic() - started < timeout_s:
        if condition():
            return time.monotonic() - started
        time.sleep(0.02)
    return None


def _status(base: str, method: str, path: str, **options: Any) -> int | None:
    """Only the status of a request to ``base`` (None: no answer)."""
    port = int(base.rsplit(":", 1)[1])
    return asyncio.run(http_request("127.0.0.1", port, method, path, timeout_s=30.0, **options)).status


def _claimed_session_on(server: Server, balancer_url: str) -> tuple[str, str]:
    """A page session the balancer sends to ``server``, claimed with its key and set to :data:`SESSION_SPIN`: its
    path and key."""
    for _ in range(64):  # each id hashes to either server: one in 2⁶⁴ fails
        path, key = f"/api/scenes/{SCENE}/sessions/{new_session_id()}", new_session_key()
        body = {"params": {SPIN_PARAMETER: SESSION_SPIN}}
        _, answered_by = _request(balancer_url, "PUT", path, headers={SESSION_KEY_HEADER: key}, body=body)
        if answered_by == server.name:
            return path, key
    raise RuntimeError(f"no session id hashed to {server.name} in 64 tries: is the balancer's affinity on?")


def _arrivals(pages: list[RoomPage], *, since_s: float, spin: float) -> list[float]:
    """When each page's socket first showed the spin ``spin`` after ``since_s`` (monotonic s)."""

    def shows(state: dict) -> bool:
        return state["params"].get(SPIN_PARAMETER) == spin

    if _wait(lambda: all(p.first_state_since(since_s, shows) for p in pages), WAIT_TIMEOUT_S) is None:
        raise RuntimeError(
            f"a change of the spin to {spin:g} rad/s did not reach every student in {WAIT_TIMEOUT_S:g} s"
        )
    return [p.first_state_since(since_s, shows) or 0.0 for p in pages]


def _percentile(values: list[float], q: float) -> float:
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(q * (len(ordered) - 1)))]


def run_scale_out(*, students: int, changes: int) -> dict:
    """The measurement (see the module docstring)."""
    with ExitStack() as stack:
        database_url = stack.enter_context(postgres_server())
        data_root = stack.enter_context(tempfile.TemporaryDirectory(prefix="dynlab-scale-out-"))
        balancer_port = free_loopback_port()
        balancer_url = f"http://127.0.0.1:{balancer_port}"
        servers = [
            Server(name, free_loopback_port(), database_url, f"{data_root}/{name}", balancer_url)
            for name in ("app1", "app2")
        ]
        for server in servers:
            stack.callback(server.stop)
        servers[0].start()
        servers[0].wait_healthy()  # the first migrates the empty database and makes the instructor's secret
        servers[1].start()
        servers[1].wait_healthy()
        engine = sa.create_engine(database_url)
        with engine.connect() as connection:
            instructor_key = connection.execute(
                sa.text("SELECT value FROM server_values WHERE name = 'instructor_secret'")
            ).scalar_one()
        engine.dispose()
        stack.enter_context(balancer(balancer_port, servers))
        pages: list[RoomPage] = []
        viewers: list[ReconnectingViewer] = []

        def close_pages() -> None:
            for page in pages:
                page.close()
            for viewer in viewers:
                viewer.close()

        stack.callback(close_pages)
        return _measure(servers, balancer_url, instructor_key, students, changes, pages, viewers)
    raise AssertionError("unreachable")


def _measure(
    servers: list[Server],
    balancer_url: str,
    instructor_key: str,
    students: int,
    changes: int,
    pages: list[RoomPage],
    viewers: list[ReconnectingViewer],
) -> dict:
    instructor = {INSTRUCTOR_HEADER: instructor_key}
    room = open_room(balancer_url, SCENE, instructor_key=instructor_key)
    room_id = room["room_id"]
    _, room_server = _request(balancer_url, "GET", f"/api/rooms/{room_id}/state")
    home = next(s for s in servers if s.name == room_server)
    other = next(s for s in servers if s is not home)
    instructor_page = RoomPage(balancer_url, balancer_url, room_id, address="127.0.0.1", headers=instructor)
    pages.append(instructor_page)
    tokens, joined_on = [], []
    for index in range(students):
        address = student_address(index)
        joined, server = _request(balancer_url, "POST", "/api/rooms/join", address=address, body={"code": room["code"]})
        tokens.append(joined["student_token"])
        joined_on.append(server)
        start_url = balancer_url if index % 2 == 0 else other.base_url
        pages.append(RoomPage(start_url, balancer_url, room_id, address=address, token=joined["student_token"]))
        viewers.append(
            ReconnectingViewer(start_url, f"/room-viewer/{room_id}", address=address, reconnect_base_url=balancer_url)
        )
    student_pages = pages[1:]
    connected = _wait(lambda: all(p.connections > 0 for p in pages) and all(v.frames > 0 for v in viewers), 90.0)
    if connected is None:
        raise RuntimeError(
            f"the class did not connect in 90 s: {sum(p.connections > 0 for p in pages)} of {len(pages)} room "
            f"sockets, {sum(v.frames > 0 for v in viewers)} of {len(viewers)} viewers with frames; errors: "
            + "; ".join(sorted({e for p in pages for e in p.errors}))
        )

    # Every student counts as connected for the instructor, wherever their socket is (each server says who its
    # sockets hold).
    everyone = {f"s{i + 1}" for i in range(students)}
    presence = _wait(
        lambda: any(
            {s["student_id"] for s in listed if s["connected"] and s["following"]} == everyone
            for _, listed in list(instructor_page.students)
        ),
        WAIT_TIMEOUT_S,
    )

    # The instructor's changes, through the balancer to the room's server; each student's socket shows each.
    latencies_ms: list[float] = []
    per_server: dict[str, list[float]] = {home.name: [], other.name: []}
    for change in range(changes):
        spin = SPIN_VALUES[change % 2]
        sent_s = time.monotonic()
        body = {"params": {SPIN_PARAMETER: spin}}
        _request(balancer_url, "POST", f"/api/rooms/{room_id}/state", headers=instructor, body=body)
        arrivals = _arrivals(student_pages, since_s=sent_s, spin=spin)
        for index, arrived in enumerate(arrivals):
            latency_ms = (arrived - sent_s) * 1000.0
            latencies_ms.append(latency_ms)
            per_server[home.name if index % 2 == 0 else other.name].append(latency_ms)
        time.sleep(CHANGE_PERIOD_S)

    # A poll, answered by everyone on the server their page is on; the instructor sees every answer.
    question = {"question": "Does the top stay up?", "kind": "choice", "choices": ["yes", "no"]}
    opened_s = time.monotonic()
    poll, _ = _request(balancer_url, "POST", f"/api/rooms/{room_id}/polls", headers=instructor, body=question)
    answers_path = f"/api/rooms/{room_id}/polls/{poll['poll_id']}/answers"
    # A student answers a poll their page has shown: on the other server, once that server has taken the poll up.
    polls_shown = _wait(
        lambda: all(
            p.first_state_since(opened_s, lambda state: (state.get("poll") or {}).get("poll_id") == poll["poll_id"])
            for p in student_pages
        ),
        WAIT_TIMEOUT_S,
    )
    if polls_shown is None:
        raise RuntimeError(f"the poll did not reach every student's page within {WAIT_TIMEOUT_S:g} s")
    for index, token in enumerate(tokens):
        answer_url = balancer_url if index % 2 == 0 else other.base_url
        token_header = {"X-Student-Token": token}
        _request(answer_url, "POST", answers_path, address=student_address(index), headers=token_header,
                 body={"choice": index % 2})  # fmt: skip
    results_seen = _wait(
        lambda: any(r["answers"] == students for _, r in list(instructor_page.results)), WAIT_TIMEOUT_S
    )
    before, _ = _request(balancer_url, "GET", f"/api/rooms/{room_id}/state")
    student_ids = sorted(s["student_id"] for s in _request(balancer_url, "GET", f"/api/rooms/{room_id}/students",
                                                             headers=instructor)[0]["students"])  # fmt: skip

    # A lesson page's own scene, claimed by its key, on the room's server (session ids are tried until the balancer's
    # hash puts one there).
    session_path, session_key = _claimed_session_on(home, balancer_url)

    # The room's server dies; every page reconnects through the balancer to the other.
    killed_s = time.monotonic()
    home.kill()

    def same_state(state: dict) -> bool:
        kept = ("params", "playing", "time_scale", "mode", "scene_id")
        poll_kept = state["poll"] is not None and state["poll"]["answers"] == students
        return poll_kept and all(state[name] == before[name] for name in kept)

    def everyone_back() -> bool:
        if not all(p.first_state_since(killed_s, same_state) for p in student_pages):
            return False
        if not any(
            at > killed_s and sorted(s["student_id"] for s in listed if s["connected"]) == student_ids
            for at, listed in list(instructor_page.students)
        ):
            return False
        return all(v.last_frame_s > killed_s for v in viewers)

    back = _wait(everyone_back, WAIT_TIMEOUT_S)
    after, server_after = _request(balancer_url, "GET", f"/api/rooms/{room_id}/state")
    session_after, session_server = _request(balancer_url, "GET", session_path)
    keyless = _status(balancer_url, "PUT", session_path, body={"params": {SPIN_PARAMETER: 40.0}})
    moved_pages = [p for i, p in enumerate(student_pages) if i % 2 == 0]
    return {
        "created": utc_now(),
        "machine": machine_facts(),
        "scene": SCENE,
        "students": students,
        "changes": changes,
        "room_server": home.name,
        "students_joined_on": {name: joined_on.count(name) for name in (home.name, other.name)},
        "connect_s": round(connected, 2),
        # From the last student's page opening until the instructor's list shows every student connected, following.
        "instructor_sees_everyone_s": None if presence is None else round(connected + presence, 2),
        "follow_latency_ms": {
            "median": round(statistics.median(latencies_ms), 1),
            "p99": round(_percentile(latencies_ms, 0.99), 1),
            "max": round(max(latencies_ms), 1),
            "samples": len(latencies_ms),
            **{
                f"median_on_{'room_server' if name == home.name else 'other_server'}": round(
                    statistics.median(values), 1
                )
                for name, values in per_server.items()
            },
        },
        "poll_answers_seen_by_instructor": results_seen is not None,
        "failover_s": None if back is None else round(back, 2),
        "state_after_failover": {
            "server": server_after,
            "same": same_state(after) and after["students"]["joined"] == students,
            "students_reconnected": sum(1 for p in moved_pages if p.connections > 1),
        },
        "page_session_after_failover": {
            "server": session_server,
            "params_kept": session_after["params"].get(SPIN_PARAMETER) == SESSION_SPIN,
            "keyless_change": keyless,
            "claimed_with_key": bool(session_key),
        },
    }


def scale_out_svg(report: dict) -> str:
    """A small figure: follow latency (median, p99) and the failover time, against the targets."""
    latency, failover = report["follow_latency_ms"], report["failover_s"]
    bars = [
        ("follow median", latency["median"], 200.0, "ms"),
        ("follow p99", latency["p99"], 200.0, "ms"),
        ("failover", (failover or 0.0), 10.0, "s"),
    ]
    rows = []
    for i, (label, value, target, unit) in enumerate(bars):
        y = 60 + i * 44
        width = max(2.0, min(1.0, value / target) * 360.0)
        rows.append(
            f'<text x="16" y="{y + 17}" font-size="13">{escape(label)}</text>'
            f'<rect x="150" y="{y}" width="360" height="24" fill="#eef2f7"/>'
            f'<rect x="150" y="{y}" width="{width:.1f}" height="24" fill="#3b6ea5"/>'
            f'<text x="520" y="{y + 17}" font-size="13">{value:g} {unit} (target ≤ {target:g} {unit})</text>'
        )
    title = (
        f"{report['students']} students, two dynlab serve behind HAProxy on PostgreSQL "
        f"({report['changes']} changes, then the room's server killed)"
    )
    return (
        '<svg xmlns="http://www.w3.org/2000/svg" width="760" height="200" font-family="sans-serif">'
        f'<text x="16" y="30" font-size="14" font-weight="600">{escape(title)}</text>{"".join(rows)}</svg>'
    )


def main(argv: list[str]) -> int:
    parser = argparse.ArgumentParser(prog="dynlab scale-out", description=__doc__.split("\n\n")[0])
    parser.add_argument("--students", type=int, default=DEFAULT_STUDENTS, help=f"1 to {MAX_STUDENTS}")
    parser.add_argument("--changes", type=int, default=DEFAULT_CHANGES, help=f"1 to {MAX_CHANGES}")
    parser.add_argument("--out-dir", type=Path, default=DEFAULT_OUT_DIR, help="where the report goes")
    args = parser.parse_args(argv)
    if not 1 <= args.students <= MAX_STUDENTS or not 1 <= args.changes <= MAX_CHANGES:
        parser.error(f"--students 1 to {MAX_STUDENTS}, --changes 1 to {MAX_CHANGES}")
    report = run_scale_out(students=args.students, changes=args.changes)
    args.out_dir.mkdir(parents=True, exist_ok=True)
    (args.out_dir / REPORT).write_text(json.dumps(report, indent=2) + "\n")
    (args.out_dir / SVG).write_text(scale_out_svg(report))
    latency = report["follow_latency_ms"]
    print(
        f"follow latency median {latency['median']} ms, p99 {latency['p99']} ms over {latency['samples']} "
        f"deliveries; failover {report['failover_s']} s; report in {args.out_dir / REPORT}"
    )
    return 0 if report["failover_s"] is not None and report["state_after_failover"]["same"] else 1
