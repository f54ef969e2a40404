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
