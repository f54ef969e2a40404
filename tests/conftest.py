"""Helpers shared by more than one test folder (import them: ``from tests.conftest import wait_until``), and how the
suite is shared between README's two xdist workers."""

from __future__ import annotations

import time
from collections import Counter
from collections.abc import Callable

import pytest
from xdist.scheduler import LoadScopeScheduling

BROWSER_TESTS = "tests/browser/"


class BrowserTestsTogether(LoadScopeScheduling):
    """README's test command runs the suite on two xdist workers (``-n 2``). The real-browser tests are one unit of
    work, sent first and kept serial on one worker (one server, one Chromium, as before), while the other worker runs
    every other test one at a time. (xdist's own ``--dist loadgroup`` does the same with a marker, but it marks a
    test by rewriting ``Item._nodeid``, which pytest 9.2 no longer reads.)"""

    def _split_scope(self, nodeid: str) -> str:
        return BROWSER_TESTS if nodeid.startswith(BROWSER_TESTS) else nodeid


def pytest_collection_finish(session: pytest.Session) -> None:
    """Refuse a collection with two tests under one id: xdist hands out tests by id, so all but one would silently
    not run (pytest 9.2 did this to schemathesis's per-operation tests; pyproject pins pytest below it)."""
    repeated = sorted(nodeid for nodeid, count in Counter(item.nodeid for item in session.items).items() if count > 1)
    if repeated:
        raise pytest.UsageError(f"{len(repeated)} test ids are shared by more than one test, e.g. {repeated[:3]}")


@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config: pytest.Config, log) -> LoadScopeScheduling:
    return BrowserTestsTogether(config, log)


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
