"""Helpers shared by more than one test folder (import them: ``from tests.conftest import wait_until``)."""

from __future__ import annotations

import time
from collections.abc import Callable


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
