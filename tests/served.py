"""The app as a user runs it: ``dynlab serve`` in its own process, with its scene workers (one per core).

API, fuzz and browser tests talk to it over HTTP and websockets on loopback, exactly as a browser does; nothing
here reaches into the server's memory. :class:`ServedApp` starts one on a free port, waits until it answers
``/api/health`` and stops it with Ctrl+C (SIGINT) as a user would, then kills whatever is left of its process tree.
"""

from __future__ import annotations

import contextlib
import os
import re
import shutil
import signal
import subprocess
import sys
import time
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import httpx

from app.bench.load_client import ReconnectingViewer
from app.bench.ports import free_loopback_port
from app.scenes.host.worker import PROCESS_NAME_PREFIX

RESULTS = Path(__file__).resolve().parents[1] / "test-results"
#: The instructor's secret the served apps of the tests are started with.
INSTRUCTOR_KEY = "served-tests-instructor-key"
#: A cold numba cache (a fresh clone) compiles every kernel in each worker: allow for it.
START_TIMEOUT_S = 240.0


def dynlab_command() -> list[str]:
    """The ``dynlab`` console script of this environment (what ``uv run dynlab`` runs); ``DYNLAB_SERVED_CHECKOUT``
    names another checkout whose own ``.venv/bin/dynlab`` to run instead (to try these tests against another build,
    such as the commit before a fix: a test of a fix must fail there)."""
    other = os.environ.get("DYNLAB_SERVED_CHECKOUT")
    if other:
        return [str(Path(other) / ".venv" / "bin" / "dynlab")]
    script = Path(sys.executable).with_name("dynlab")
    return [str(script)] if script.exists() else [sys.executable, "-m", "app.cli"]


def children_of(pid: int) -> list[int]:
    """Process ids whose parent is ``pid`` (from /proc)."""
    found = []
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue
        # pid (comm) state ppid …: comm may hold spaces and parentheses, so split after the last ')'.
        fields = stat.rsplit(")", 1)[1].split()
        if int(fields[1]) == pid:
            found.append(int(entry.name))
    return found


def children_running(pid: int, marker: bytes) -> list[int]:
    """The children of ``pid`` whose command line holds ``marker`` (e.g. ``b"forkserver"``), in pid order."""
    found = []
    for child in children_of(pid):
        try:
            if marker in Path(f"/proc/{child}/cmdline").read_bytes():
                found.append(child)
        except OSError:
            continue
    return sorted(found)


class DeviceClient(httpx.Client):
    """An HTTP client whose connections leave from ``address`` (a loopback address: one device of a class)."""

    def __init__(self, address: str, **options: Any) -> None:
        super().__init__(transport=httpx.HTTPTransport(local_address=address), **options)
        self.address = address

    def websocket_url(self, path: str) -> str:
        return str(self.base_url).replace("http://", "ws://").rstrip("/") + path


class ServedApp:
    """``dynlab serve --host 127.0.0.1 --port <free>`` with the default scene workers, and an HTTP client for it."""

    def __init__(
        self,
        *,
        name: str = "served",
        env: Mapping[str, str] | None = None,
        args: tuple[str, ...] = (),
        data_dir: Path | None = None,
        port: int | None = None,
    ) -> None:
        self.port = port or free_loopback_port()
        self.instructor_key = INSTRUCTOR_KEY
        self.name = name
        self.log_path = RESULTS / f"{name}-{os.getpid()}-{self.port}.log"
        # Where it keeps the class's data: its own, new and removed when it stops, unless given (a restart test gives
        # the one an earlier server kept its rooms in).
        self._own_data_dir = data_dir is None
        self.data_dir = data_dir or RESULTS / f"data-{name}-{os.getpid()}-{self.port}"
        if self._own_data_dir:
            shutil.rmtree(self.data_dir, ignore_errors=True)
        # Whatever this shell sets, the default is what README's command gets: no DYNLAB_* but ours.
        inherited = {k: v for k, v in os.environ.items() if not k.startswith("DYNLAB_")}
        self._env = {
            **inherited,
            "DYNLAB_INSTRUCTOR_KEY": INSTRUCTOR_KEY,
            "DYNLAB_DATA_DIR": str(self.data_dir),
            **(env or {}),
        }
        self._args = args
        self.process: subprocess.Popen[bytes] | None = None
        self.client = httpx.Client(base_url=self.url, timeout=60.0)

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    @property
    def instructor_link(self) -> str:
        return f"{self.url}/instructor?key={self.instructor_key}"

    @property
    def instructor_headers(self) -> dict[str, str]:
        return {"X-Instructor-Key": self.instructor_key}

    def new_client(self, *, timeout_s: float = 60.0) -> httpx.Client:
        """An HTTP client from a loopback address of its own (127.1.x.y; Linux routes all of 127/8 to lo), as a
        different device would be: the server's per-client limits see one student per client."""
        ServedApp._addresses += 1
        n = ServedApp._addresses
        address = f"127.1.{n // 250 % 250}.{n % 250 + 1}"
        return DeviceClient(address, base_url=self.url, timeout=timeout_s)

    _addresses = 0

    def start(self) -> "ServedApp":
        RESULTS.mkdir(parents=True, exist_ok=True)
        log = self.log_path.open("wb")
        command = [*dynlab_command(), "serve", "--host", "127.0.0.1", "--port", str(self.port), "--log-level", "warning", *self._args]
        self.process = subprocess.Popen(
            command, stdout=log, stderr=subprocess.STDOUT, env=self._env, start_new_session=True, cwd=os.environ.get("DYNLAB_SERVED_CHECKOUT")
        )
        log.close()
        self.wait_healthy(START_TIMEOUT_S)
        return self

    def wait_healthy(self, timeout_s: float) -> None:
        deadline = time.monotonic() + timeout_s
        while True:
            assert self.process is not None
            if self.process.poll() is not None:
                raise RuntimeError(f"dynlab serve exited with {self.process.returncode}; its log: {self.log_path}\n{self.log_tail()}")
            try:  # the one client: httpx.get builds an SSL context per call (15 ms of CPU, 10 times a second)
                if self.client.get("/api/health", timeout=2.0).status_code == 200:
                    return
            except httpx.HTTPError:
                pass
            if time.monotonic() > deadline:
                raise RuntimeError(f"dynlab serve did not answer within {timeout_s:.0f} s; its log: {self.log_path}\n{self.log_tail()}")
            time.sleep(0.1)

    def printed_instructor_link(self) -> str:
        """The instructor link ``dynlab serve`` printed at its start (with the secret it was given or kept)."""
        found = re.search(r"Instructor link[^\n]*?(http://\S+/instructor\?key=\S+)", self.log_path.read_text())
        assert found, self.log_tail()
        return found.group(1)

    def log_tail(self, lines: int = 40) -> str:
        try:
            return "\n".join(self.log_path.read_text(errors="replace").splitlines()[-lines:])
        except OSError:
            return ""

    def worker_pids(self) -> list[int]:
        """The scene workers' process ids, in worker order: forks of the front's forkserver, named
        ``dynlab-worker<index>`` (:func:`app.scenes.host.worker.process_name`)."""
        assert self.process is not None
        named = {}
        for server in children_running(self.process.pid, b"forkserver"):
            for pid in children_of(server):
                try:
                    name = Path(f"/proc/{pid}/comm").read_text().strip()
                except OSError:
                    continue
                if name.startswith(PROCESS_NAME_PREFIX):
                    named[int(name.removeprefix(PROCESS_NAME_PREFIX))] = pid
        return [named[index] for index in sorted(named)]

    def stop(self, *, timeout_s: float = 15.0) -> float:
        """Ctrl+C, as a user stops it; returns the seconds it took to exit. Anything left of the tree is killed."""
        if self.process is None:
            return 0.0
        started = time.monotonic()
        tree = [self.process.pid, *self.worker_pids()]
        if self.process.poll() is None:
            self.process.send_signal(signal.SIGINT)
            try:
                self.process.wait(timeout=timeout_s)
            except subprocess.TimeoutExpired:  # what it waits for goes to its log (faulthandler), then it is killed
                self.process.send_signal(signal.SIGUSR1)
                with contextlib.suppress(subprocess.TimeoutExpired):
                    self.process.wait(timeout=1.0)
        took = time.monotonic() - started
        for pid in tree:
            try:
                os.killpg(pid, signal.SIGKILL) if pid == self.process.pid else os.kill(pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
        self.process.wait(timeout=5)
        self.client.close()
        if self._own_data_dir:
            shutil.rmtree(self.data_dir, ignore_errors=True)
        return took

    def __enter__(self) -> "ServedApp":
        return self.start()

    def __exit__(self, *exc: Any) -> None:
        self.stop()


class Viewer(ReconnectingViewer):
    """A browser's 3D viewer on a served app, in a thread (:class:`app.bench.load_client.ReconnectingViewer`): it
    connects to ``path`` (``/viewer/<scene>/<session>`` or ``/room-viewer/<room>``) from ``address``, reads every frame,
    and reconnects half a second after a drop, as viser's client does, until :meth:`close`."""

    def __init__(self, app: ServedApp, path: str, *, address: str = "127.0.0.1", camera: tuple | None = None) -> None:
        super().__init__(app.url, path, address=address, camera=camera)
