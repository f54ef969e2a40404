"""A free TCP port on loopback for a server another process will start: the tests' and the load tools' servers."""

from __future__ import annotations

import random
import socket
from pathlib import Path

#: The lowest port handed out: below it are the registered services a machine may run.
LOWEST_PORT = 10_000
#: Linux's default ephemeral range starts here (``/proc/sys/net/ipv4/ip_local_port_range``).
DEFAULT_EPHEMERAL_LOW = 32_768


def _ephemeral_low() -> int:
    """The first port the kernel may give an outgoing connection as its source port."""
    try:
        return int(Path("/proc/sys/net/ipv4/ip_local_port_range").read_text().split()[0])
    except (OSError, ValueError, IndexError):
        return DEFAULT_EPHEMERAL_LOW


def free_loopback_port() -> int:
    """A port on 127.0.0.1 nothing listens on now, chosen at random below the kernel's ephemeral range.

    The port is checked here and bound later by another process. A port from the ephemeral range (what binding port 0
    gives) can be taken in between as the source port of any outgoing connection, and a test run opens thousands: a
    served app then failed to start with "address already in use" (and a worker's 380 tests with it). Below the range
    the kernel never hands a port out by itself, so only another caller of this function could take it, and the
    random choice over some 20,000 ports makes that unlikely.
    """
    high = _ephemeral_low()
    chooser = random.SystemRandom()
    for _ in range(100):
        port = chooser.randrange(LOWEST_PORT, high) if high > LOWEST_PORT + 100 else chooser.randrange(1024, 65536)
        with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:
            try:
                probe.bind(("127.0.0.1", port))
            except OSError:
                continue
            return port
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as probe:  # a crowded machine: any port at all
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]
