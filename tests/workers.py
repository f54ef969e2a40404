"""How many xdist workers README's test command starts (tests/run.sh): three on a machine whose processors are idle
now, two on a busy one.

The third worker takes the files whose tests mostly wait (``WAITING_FILES`` in tests/conftest.py: a killed worker's
restart, a balancer's health checks, a slow client's deadline), so their waiting overlaps the other two workers'
work (README's Conventions section has the figures). On a machine that other programs keep busy a third worker adds load
without any idle time to fill, and the timing bounds of a few tests (a class's follow latency, a stopped worker's
health) are then measured on an overloaded machine: two workers.

    python -m tests.workers        # prints 2 or 3
"""

from __future__ import annotations

import os
import time
from pathlib import Path

#: Idle processors (of the whole machine, measured over :data:`LOOK_S`) needed for a third worker.
IDLE_CORES_FOR_THREE = 1.6
LOOK_S = 1.0


def _idle_and_total_ticks() -> tuple[int, int]:
    fields = [int(v) for v in Path("/proc/stat").read_text().split("\n", 1)[0].split()[1:]]
    return fields[3] + fields[4], sum(fields[:8])  # idle + iowait; user … softirq, steal


def idle_cores(look_s: float = LOOK_S) -> float:
    """Processors left idle over the next ``look_s`` seconds (0 where /proc/stat cannot be read)."""
    try:
        idle0, total0 = _idle_and_total_ticks()
        time.sleep(look_s)
        idle1, total1 = _idle_and_total_ticks()
    except (OSError, ValueError):
        return 0.0
    return (os.cpu_count() or 1) * (idle1 - idle0) / max(1, total1 - total0)


def workers() -> int:
    return 3 if idle_cores() >= IDLE_CORES_FOR_THREE else 2


if __name__ == "__main__":
    print(workers())
