"""Helpers shared by more than one test folder (import them: ``from tests.conftest import wait_until``), and how the
suite is shared between README's xdist workers."""

from __future__ import annotations

import asyncio
import json
import os
import time
from collections import Counter, defaultdict
from collections.abc import Callable, Iterator
from pathlib import Path

import pytest
from xdist.scheduler import LoadScopeScheduling

#: No test keeps anything in the home directory: the per-user data directory (app.storage.default_data_dir, where
#: ``dynlab serve`` keeps rooms without --data-dir) is one of this run's own. Served apps get their own data
#: directories (tests/served.py).
os.environ["XDG_DATA_HOME"] = str(Path(__file__).resolve().parents[1] / "test-results" / f"xdg-data-{os.getpid()}")

#: Seconds each test file took (setup, call and teardown of its tests) in a measured run of README's test command:
#: the order in which the files are handed out. ``DYNLAB_STORE_FILE_SECONDS=1 tests/run.sh`` measures it again.
FILE_SECONDS = Path(__file__).with_name("file_seconds.json")


def file_of(nodeid: str) -> str:
    """The file a test id belongs to (``tests/api/test_faults.py`` of ``tests/api/test_faults.py::test_…[…]``)."""
    return nodeid.split("::", 1)[0]


class LongestFilesFirst(LoadScopeScheduling):
    """README's test command runs the suite on three xdist workers on an idle machine and two on a busy one
    (tests/workers.py). Each test file is one unit of work, so a file's module fixtures (a served app, a browser page,
    a derivation) are set up once, on one worker; each worker starts its own served app and Chromium on its first test
    that needs them. The units go out longest first (:data:`FILE_SECONDS`, in the order the workers collected them:
    see :func:`pytest_collection_modifyitems`), so the workers finish together. With three workers the third takes
    the files that mostly wait (:data:`WAITING_FILES`) and the other two the rest, so that waiting overlaps work
    (README's Conventions section has the figures). (xdist's own ``--dist loadgroup`` marks a test by rewriting
    ``Item._nodeid``, which pytest 9.2 no longer reads.)"""

    def __init__(self, config: pytest.Config, log=None) -> None:
        config.option.loadscopereorder = False  # keep the collected order: longest file first
        super().__init__(config, log)

    def _split_scope(self, nodeid: str) -> str:
        return file_of(nodeid)

    def _assign_work_unit(self, node) -> None:
        """With three workers or more, the last one takes the files that mostly wait (:data:`WAITING_FILES`) and the
        others the rest, each falling back to the other kind once its own is gone."""
        if len(self.nodes) >= 3:
            waiting_node = node.gateway.id == waiting_worker(len(self.nodes))
            mine = [scope for scope in self.workqueue if (scope in WAITING_FILES) == waiting_node]
            if mine:
                self.workqueue.move_to_end(mine[0], last=False)
        super()._assign_work_unit(node)


#: Files whose tests mostly wait (on a killed worker's restart, a balancer's health check, a slow client's timeout, a
#: load run's fixed windows): their wall time is two to four times their CPU time. With a third xdist worker they run
#: there, beside the two that keep the processors busy.
WAITING_FILES = frozenset({
    "tests/api/test_faults.py", "tests/browser/test_two_servers.py", "tests/bench/test_capacity.py",
    "tests/bench/test_attack.py", "tests/bench/test_restart.py", "tests/web/test_slow_clients.py",
    "tests/browser/test_viewer_controls_in_browser.py",
})


def waiting_worker(workers: int) -> str:
    """The xdist worker that takes the files that mostly wait, when there are three workers or more: the last."""
    return f"gw{workers - 1}"


def pytest_configure(config: pytest.Config) -> None:
    """With three workers or more, the workers that keep the processors busy run at a lower priority (nice 5) than
    the one whose files mostly wait: its tests time what a class would feel (a change reaching 30 students' sockets
    within 200 ms on two servers, a stopped worker's health), and its load tools' clients run in this pytest session,
    beside the other workers. Their served apps and Chromium are sessions of their own, which Linux shares the
    processors between fairly whatever their niceness (autogroups); the niceness settles the share inside this one."""
    worker = getattr(config, "workerinput", {}).get("workerid")
    workers = int(os.environ.get("PYTEST_XDIST_WORKER_COUNT", "1"))
    if worker is not None and workers >= 3 and worker != waiting_worker(workers):
        os.nice(5)


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    """On an xdist worker: the test files in order of their measured seconds, longest first (a file not measured yet
    counts as quick), each file's tests in their own order."""
    if not hasattr(config, "workerinput") or not FILE_SECONDS.exists():
        return
    seconds = json.loads(FILE_SECONDS.read_text())
    items.sort(key=lambda item: -seconds.get(file_of(item.nodeid), 0.0))  # a stable sort: a file's order is kept


def pytest_collection_finish(session: pytest.Session) -> None:
    """Refuse a collection with two tests under one id: xdist hands out tests by id, so all but one would silently
    not run (pytest 9.2 did this to schemathesis's per-operation tests; pyproject pins pytest below it)."""
    repeated = sorted(nodeid for nodeid, count in Counter(item.nodeid for item in session.items).items() if count > 1)
    if repeated:
        raise pytest.UsageError(f"{len(repeated)} test ids are shared by more than one test, e.g. {repeated[:3]}")


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config: pytest.Config, log) -> LoadScopeScheduling:
    return LongestFilesFirst(config, log)


BROWSER_TESTS = "tests/browser/"


@pytest.fixture(autouse=True)
def _no_event_loop_of_the_browsers(request: pytest.FixtureRequest) -> Iterator[None]:
    """A worker that has run a browser test keeps Playwright's sync API (its Chromium) until the session ends, and
    Playwright marks its event loop as running in this thread between its calls: ``asyncio.run`` (the load tools of
    tests/bench) would then refuse to start. A test outside tests/browser runs with no loop marked; the mark is put
    back after it."""
    loop = asyncio._get_running_loop()
    if loop is None or request.node.nodeid.startswith(BROWSER_TESTS):
        yield
        return
    asyncio._set_running_loop(None)
    try:
        yield
    finally:
        asyncio._set_running_loop(loop)


_measured_seconds: defaultdict[str, float] = defaultdict(float)


def pytest_runtest_logreport(report: pytest.TestReport) -> None:
    """Sum each file's seconds (every phase of every test; on xdist's controller, as the workers report them)."""
    _measured_seconds[file_of(report.nodeid)] += report.duration


def pytest_sessionfinish(session: pytest.Session) -> None:
    """With ``DYNLAB_STORE_FILE_SECONDS=1``, write :data:`FILE_SECONDS` from this run (on xdist's controller, or a
    run without xdist)."""
    if os.environ.get("DYNLAB_STORE_FILE_SECONDS") == "1" and not hasattr(session.config, "workerinput"):
        ordered = dict(sorted(((f, round(s, 1)) for f, s in _measured_seconds.items()), key=lambda kv: -kv[1]))
        FILE_SECONDS.write_text(json.dumps(ordered, indent=1) + "\n")


def wait_until(predicate: Callable[[], bool], timeout_s: float = 30.0, interval_s: float = 0.05, what: str = "condition") -> None:
    """Poll ``predicate`` every ``interval_s`` seconds until it holds; AssertionError naming ``what`` after ``timeout_s``."""
    deadline = time.monotonic() + timeout_s
    while not predicate():
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out after {timeout_s} s waiting for {what}")
        time.sleep(interval_s)


#: How a work-precision report describes the heavy-top case (the bench page and plot tests build reports around it).
HEAVY_TOP_BENCH_SETUP = {
    "scene_id": "heavy-top",
    "t_end_s": 10.0,
    "frame_rate_hz": 60,
    "error_measure": "largest symmetry-axis angle error over all frames",
    "error_unit": "rad",
    "reference": "quadrature (elliptic) solution",
    "target_error": 1e-6,
}


@pytest.fixture(scope="session")
def served():
    """``dynlab serve`` as README starts it (its own process, the default scene workers), shared by a test worker's
    tests: see :mod:`tests.served`."""
    from tests.served import ServedApp

    with ServedApp() as app:
        yield app
