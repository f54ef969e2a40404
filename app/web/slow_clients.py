"""Deadlines for slow clients and a cap on one client's connections, at the HTTP protocol level.

A request that never finishes its headers (or its body) would otherwise hold a
connection for as long as its sender likes: 500 such connections from one client
were held 90 s. uvicorn's HTTP protocol (httptools) is extended here, and only
here, with three rules a route cannot apply because they act before any route runs:

* a request's headers must arrive within :data:`HEADER_TIMEOUT_S` of its first
  byte (of the connection, for the first request), else the connection closes
  with 408;
* its body within :data:`BODY_TIMEOUT_S` of its headers, else the connection closes;
* one client address may hold :data:`MAX_CONNECTIONS_PER_CLIENT` connections (HTTP
  and websockets together); more are closed at once. Not applied behind a reverse
  proxy (``trust_forwarded_for``), where every connection comes from the proxy.
"""

from __future__ import annotations

import asyncio
import logging
from typing import Any

from uvicorn.protocols.http.httptools_impl import HttpToolsProtocol

log = logging.getLogger(__name__)

#: Longest a request's headers may take to arrive (s); a browser sends them in one packet.
HEADER_TIMEOUT_S = 10.0
#: Longest a request's body may take after its headers (s): the largest accepted body (1 MiB) over a slow phone link.
BODY_TIMEOUT_S = 30.0
#: Connections one client address may hold at once: a browser keeps about 6 per site plus a few websockets per tab.
MAX_CONNECTIONS_PER_CLIENT = 128

_REQUEST_TIMEOUT = (
    b"HTTP/1.1 408 Request Timeout\r\ncontent-type: text/plain; charset=utf-8\r\nconnection: close\r\n"
    b"content-length: 36\r\n\r\nthe request did not arrive in time.\n"
)


class GuardedHttpProtocol(HttpToolsProtocol):
    """uvicorn's httptools protocol with :data:`HEADER_TIMEOUT_S`, :data:`BODY_TIMEOUT_S` and
    :data:`MAX_CONNECTIONS_PER_CLIENT` (``cap_connections`` false behind a trusted proxy)."""

    cap_connections = True

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        self._deadline: asyncio.TimerHandle | None = None

    def connection_made(self, transport: asyncio.Transport) -> None:  # type: ignore[override]
        super().connection_made(transport)
        address = self.client[0] if self.client else None
        if self.cap_connections and address is not None:
            held = sum(1 for c in self.connections if (client := getattr(c, "client", None)) and client[0] == address)
            if held > MAX_CONNECTIONS_PER_CLIENT:
                log.warning("closing a connection from %s: it holds %d already", address, held - 1)
                transport.abort()
                return
        self._arm(HEADER_TIMEOUT_S, headers=True)

    def _arm(self, seconds: float, *, headers: bool) -> None:
        self._disarm()
        self._deadline = self.loop.call_later(seconds, self._too_slow, headers)

    def _disarm(self) -> None:
        if self._deadline is not None:
            self._deadline.cancel()
            self._deadline = None

    def _too_slow(self, headers: bool) -> None:
        self._deadline = None
        if self.transport.is_closing():
            return
        if headers:
            self.transport.write(_REQUEST_TIMEOUT)
        self.transport.close()

    def on_message_begin(self) -> None:
        super().on_message_begin()
        if self._deadline is None:  # a later request on a kept-alive connection: its headers are due now
            self._arm(HEADER_TIMEOUT_S, headers=True)

    def on_headers_complete(self) -> None:
        self._disarm()
        super().on_headers_complete()
        if self.parser is not None and not self.parser.should_upgrade():
            self._arm(BODY_TIMEOUT_S, headers=False)

    def on_message_complete(self) -> None:
        self._disarm()
        super().on_message_complete()

    def handle_websocket_upgrade(self) -> None:
        self._disarm()
        super().handle_websocket_upgrade()

    def connection_lost(self, exc: Exception | None) -> None:
        self._disarm()
        super().connection_lost(exc)
