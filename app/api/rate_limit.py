"""Per-client limits: who a client is (:func:`client_address`, the key of every limit) and token buckets keyed on it
(a burst allowed at once, then a steady rate per second)."""

from __future__ import annotations

import ipaddress
import math
import threading
import time
from collections import OrderedDict
from collections.abc import Callable

from starlette.datastructures import Headers
from starlette.types import Scope


class TokenBuckets:
    """One token bucket per client key (an IP address), holding at most ``burst`` tokens refilled at ``rate_per_s``.

    A request takes one token; with none left it waits :meth:`take`'s answer in seconds.
    At most ``max_clients`` buckets are kept: the least recently seen client is forgotten
    first (its next request starts from a full bucket). ``burst=0`` means no limit.
    """

    def __init__(
        self, *, burst: int, rate_per_s: float, max_clients: int, clock: Callable[[], float] = time.monotonic
    ) -> None:
        if burst < 0 or not (math.isfinite(rate_per_s) and rate_per_s > 0) or max_clients < 1:
            raise ValueError(
                f"burst must be >= 0, rate_per_s finite and > 0, max_clients >= 1 (got {burst}, {rate_per_s}, "
                f"{max_clients})"
            )
        self.burst = burst
        self.rate_per_s = rate_per_s
        self.max_clients = max_clients
        self._clock = clock
        self._buckets: OrderedDict[str, tuple[float, float]] = (
            OrderedDict()
        )  # key -> (tokens, clock time of that count)
        self._lock = (
            threading.Lock()
        )  # routes run in the thread pool: two requests at once must not both take the last token

    def __len__(self) -> int:
        return len(self._buckets)

    def take(self, client: str) -> float:
        """Take one token for ``client``: 0.0 if granted, else the seconds (> 0) until a token is due."""
        if self.burst == 0:
            return 0.0
        with self._lock:
            now = self._clock()
            tokens, then = self._buckets.pop(client, (float(self.burst), now))
            tokens = min(float(self.burst), tokens + (now - then) * self.rate_per_s)
            wait_s = 0.0
            if tokens >= 1.0:
                tokens -= 1.0
            else:
                wait_s = (1.0 - tokens) / self.rate_per_s
            self._buckets[client] = (tokens, now)
            while len(self._buckets) > self.max_clients:
                self._buckets.popitem(last=False)
        return wait_s


def retry_after_s(wait_s: float) -> int:
    """The ``Retry-After`` (whole seconds, at least 1) for a wait of ``wait_s`` seconds."""
    return max(1, math.ceil(wait_s))


class InFlight:
    """How many requests each client has running now, at most ``limit`` each (thread-safe; a client with none is
    forgotten)."""

    def __init__(self, *, limit: int) -> None:
        if limit < 1:
            raise ValueError(f"limit must be >= 1 (got {limit})")
        self.limit = limit
        self._running: dict[str, int] = {}
        self._lock = threading.Lock()

    def try_enter(self, client: str) -> bool:
        """Count one more request of ``client`` and return True, or False (counting nothing) if it has ``limit``."""
        with self._lock:
            running = self._running.get(client, 0)
            if running >= self.limit:
                return False
            self._running[client] = running + 1
            return True

    def leave(self, client: str) -> None:
        with self._lock:
            left = self._running.get(client, 1) - 1
            if left > 0:
                self._running[client] = left
            else:
                self._running.pop(client, None)


def is_ip_address(text: str) -> bool:
    """Whether ``text`` is an IPv4 or IPv6 address."""
    try:
        ipaddress.ip_address(text)
    except ValueError:
        return False
    return True


def client_address(scope: Scope, *, trust_forwarded_for: bool) -> str | None:
    """The client's IP address, the key of every per-client limit: the last ``X-Forwarded-For`` entry when
    ``trust_forwarded_for`` (behind a reverse proxy that sets it), else the peer's address; None for a peer with no
    IP address (a unix socket, an in-process test client), which has nothing to key on."""
    if trust_forwarded_for:
        forwarded = Headers(scope=scope).get("x-forwarded-for", "").rsplit(",", 1)[-1].strip()
        if is_ip_address(forwarded):
            return forwarded
    client = scope.get("client")
    return client[0] if client and is_ip_address(client[0]) else None
