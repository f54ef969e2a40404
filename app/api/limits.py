"""How many heavy requests (off-screen simulations) run at once in this process.

A simulation holds a core and tens of MB for up to about a second. With a class of
students pressing "simulate" together, running them all at once would share the
cores among all of them (each slower) and add their memory up; instead at most
``concurrent`` run, a few more wait briefly in a queue, and the rest are told to
come back: a 429 with a ``Retry-After`` header. Simulate routes are synchronous
(FastAPI runs them in its thread pool), so a semaphore with a timeout is enough.
"""

from __future__ import annotations

import math
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from fastapi import HTTPException

from app.api.schemas.errors import ErrorDetail

#: Heavy requests running at once: the machine's two cores.
CONCURRENT_HEAVY_REQUESTS = 2
#: Heavy requests that may wait for a running one to finish, beyond which a request is refused at once.
QUEUED_HEAVY_REQUESTS = 4
#: Longest wait in the queue (s) before a request is refused: a worst-case simulation takes about a second
#: alone, so a full queue drains in a few seconds even on a loaded machine.
QUEUE_WAIT_S = 10.0
#: What ``Retry-After`` says (s): about the time the queue ahead takes to drain.
RETRY_AFTER_S = 2


class Busy(HTTPException):
    """A 429: too many heavy requests are running or waiting; ``Retry-After`` says when to try again."""

    def __init__(self, message: str, *, retry_after_s: int) -> None:
        super().__init__(status_code=429, detail=message, headers={"Retry-After": str(retry_after_s)})


class HeavyRequestLimiter:
    """At most ``concurrent`` holders of :meth:`slot` at once; at most ``queued`` more wait, each up to ``wait_s``
    (s)."""

    def __init__(self, *, concurrent: int, queued: int, wait_s: float, retry_after_s: int) -> None:
        if concurrent < 1 or queued < 0 or not (math.isfinite(wait_s) and wait_s >= 0.0) or retry_after_s < 1:
            raise ValueError("a limiter needs concurrent ≥ 1, queued ≥ 0, a finite wait_s ≥ 0 and retry_after_s ≥ 1")
        self.concurrent, self.queued, self.wait_s, self.retry_after_s = concurrent, queued, wait_s, retry_after_s
        self._running = threading.BoundedSemaphore(concurrent)
        self._lock = threading.Lock()
        self._admitted = 0  # running + waiting

    @property
    def admitted(self) -> int:
        """Requests running or waiting now."""
        return self._admitted

    @contextmanager
    def slot(self, what: str) -> Iterator[None]:
        """Hold one of the running places while the block runs; raise :class:`Busy` (naming ``what``) if none comes."""
        with self._lock:
            if self._admitted >= self.concurrent + self.queued:
                raise self._busy(what, "and as many are waiting")
            self._admitted += 1
        try:
            if not self._running.acquire(timeout=self.wait_s):
                raise self._busy(what, f"and none finished within {self.wait_s:g} s")
            try:
                yield
            finally:
                self._running.release()
        finally:
            with self._lock:
                self._admitted -= 1

    def _busy(self, what: str, why: str) -> Busy:
        return Busy(
            f"The server is busy: {self.concurrent} {what} requests are running {why}. "
            f"Try again in {self.retry_after_s} s.",
            retry_after_s=self.retry_after_s,
        )


#: The process's limit on simulate requests (one per worker process).
SIMULATIONS = HeavyRequestLimiter(
    concurrent=CONCURRENT_HEAVY_REQUESTS, queued=QUEUED_HEAVY_REQUESTS, wait_s=QUEUE_WAIT_S, retry_after_s=RETRY_AFTER_S
)

#: OpenAPI ``responses=`` entry for a route guarded by a limiter.
TOO_MANY_RESPONSE: dict[int | str, dict[str, Any]] = {
    429: {
        "model": ErrorDetail,
        "description": (
            "Too many simulations are running or waiting; the `Retry-After` header says when to try again (s)"
        ),
        "headers": {"Retry-After": {"description": "Seconds to wait before retrying", "schema": {"type": "integer"}}},
    }
}
