"""Step-choice pilots run off the frame loop: one thread per scene worker, one pilot at a time, latest wins.

A live scene's restart must not wait for a pilot (0.1–0.4 s for a new parameter
set): the frame loop that would wait serves every student of the worker. The
scene starts at once with the fixed step rule and hands the pilot here; the
result comes back through the scene's callback, which the scene applies at its
next frame boundary. Each owner (a scene instance) has at most one job queued:
a newer submission replaces the older one (the student has moved the slider
again, so the old parameters' pilot is of no use). Jobs run in submission order,
one at a time, in a daemon thread (the compiled integrators release the GIL, so
the frame loop keeps its rate meanwhile).
"""

from __future__ import annotations

import logging
import threading
from collections import OrderedDict
from collections.abc import Callable, Hashable
from typing import Any

log = logging.getLogger(__name__)


class BackgroundPilots:
    """A queue of pilot jobs keyed by owner, drained by one daemon thread started on first use."""

    def __init__(self) -> None:
        self._jobs: OrderedDict[Hashable, tuple[Callable[[], Any], Callable[[Any], None]]] = OrderedDict()
        self._lock = threading.Lock()
        self._wake = threading.Condition(self._lock)
        self._busy = False
        self._thread: threading.Thread | None = None
        #: Jobs run to completion so far (for tests and diagnostics).
        self.jobs_run = 0

    def submit(self, owner: Hashable, job: Callable[[], Any], deliver: Callable[[Any], None]) -> None:
        """Queue ``job`` for ``owner`` (replacing its queued one); ``deliver(job())`` runs in the pilot thread
        (``deliver(None)`` if the job raised: logged, and the scene keeps what it runs)."""
        with self._lock:
            self._jobs.pop(owner, None)
            self._jobs[owner] = (job, deliver)
            if self._thread is None or not self._thread.is_alive():
                self._thread = threading.Thread(target=self._drain, name="step-choice-pilots", daemon=True)
                self._thread.start()
            self._wake.notify()

    def cancel(self, owner: Hashable) -> None:
        """Drop ``owner``'s queued job (one already running still delivers)."""
        with self._lock:
            self._jobs.pop(owner, None)

    def pending(self) -> int:
        """Jobs queued or running."""
        with self._lock:
            return len(self._jobs) + int(self._busy)

    def wait_idle(self, timeout_s: float) -> bool:
        """Wait until no job is queued or running (True), or ``timeout_s`` s have passed (False)."""
        with self._lock:
            return self._wake.wait_for(lambda: not self._jobs and not self._busy, timeout=timeout_s)

    def _drain(self) -> None:
        while True:
            with self._lock:
                self._wake.wait_for(lambda: bool(self._jobs))
                _, (job, deliver) = self._jobs.popitem(last=False)
                self._busy = True
            try:
                try:
                    result = job()
                except Exception:
                    log.exception("a background step-choice pilot failed; the scene keeps the fixed step rule")
                    result = None
                deliver(result)
            finally:
                with self._lock:
                    self._busy = False
                    self.jobs_run += 1
                    self._wake.notify_all()


#: The scene worker's pilot queue.
PILOTS = BackgroundPilots()
