"""The web front's guard: pure ASGI middleware that refuses abuse before any route runs.

- An HTTP body whose ``Content-Length`` is over ``Settings.max_body_bytes`` gets 413 at once; a
  streamed body is counted as it is read (Starlette's ``RequestBodyLimitMiddleware``), never
  buffered past the limit.
- A websocket, or an HTTP request that can change state (not GET/HEAD/OPTIONS), that carries an
  ``Origin`` must come from the page's own origin (or ``Settings.allowed_origins``) and its ``Host``
  must name this server (:class:`HostPolicy`): otherwise 403, or close 1008 before accept. This
  stops cross-site requests and DNS rebinding; clients without ``Origin`` (scripts) pass.
- Per-client rate limits (:class:`~app.api.rate_limit.TokenBuckets`): every HTTP request (``Settings.request_burst``
  at once, ``request_rate_per_s`` after; static files in a bucket of their own, larger), answered 429 before any
  route runs, after a wait; ``POST .../simulate`` and ``POST /api/systems/custom/derive`` get 429
  with ``Retry-After``, and so does a second one from a client whose first is still running
  (:class:`~app.api.rate_limit.InFlight`); opening a viewer websocket is closed with 1013 "try again later".
"""

from __future__ import annotations

import asyncio
import logging
import re
import socket
import time
from collections.abc import Callable, Iterable
from urllib.parse import urlsplit

from starlette.datastructures import Headers
from starlette.middleware.body_limit import RequestBodyLimitMiddleware
from starlette.responses import JSONResponse
from starlette.types import ASGIApp, Receive, Scope, Send

from app.api.rate_limit import InFlight, TokenBuckets, client_address, is_ip_address, retry_after_s
from app.settings import Settings

log = logging.getLogger(__name__)

#: Methods that never change state: no Origin check.
SAFE_METHODS = frozenset({"GET", "HEAD", "OPTIONS"})
#: Paths whose POST is rate limited as heavy work: simulations, typed-Lagrangian and described-system derivations and
#: linearisations (an eigenvalue sweep runs hundreds of them; a template such as ``/api/scenes/{scene_id}/simulate``
#: matches too).
SIMULATE_PATH = re.compile(r"^/api/(scenes/[^/]+/simulate|systems/custom/(derive|describe)|systems/[^/]+/eigenvalues)$")
#: Websocket paths whose opening is rate limited: a page's own viewer, a room's shared scene and the room socket.
VIEWER_PREFIXES = ("/viewer/", "/room-viewer/", "/api/rooms/")
#: Longest a request over its device's rate is held before its 429 (s).
MAX_REFUSAL_DELAY_S = 1.0
LOOPBACK_NAMES = frozenset({"127.0.0.1", "localhost", "::1"})
_DEFAULT_PORTS = {"http": 80, "https": 443, "ws": 80, "wss": 443}


def _split_authority(authority: str) -> tuple[str, int | None] | None:
    """``host[:port]`` (``[v6]:port`` too) as (lower-case host without brackets, port or None); None if malformed."""
    try:
        parts = urlsplit("//" + authority)
        port = parts.port
    except ValueError:
        return None
    if not parts.hostname or parts.username is not None or parts.path or parts.query or parts.fragment:
        return None
    return parts.hostname, port


def public_host(public_url: str) -> tuple[str, ...]:
    """The ``Host`` (``name:port``) of ``Settings.public_url``, the address students reach the server at (a balancer
    in front of it): requests carrying it are meant for this server. Empty without one."""
    parts = urlsplit(public_url.strip()) if public_url.strip() else None
    if parts is None or not parts.hostname:
        return ()
    try:
        port = parts.port or _DEFAULT_PORTS.get(parts.scheme, 80)
    except ValueError:  # a malformed port: nothing is added
        return ()
    host = f"[{parts.hostname}]" if ":" in parts.hostname else parts.hostname
    return (f"{host}:{port}",)


class HostPolicy:
    """Which ``Host`` names reach this server.

    Served on a loopback address: ``127.0.0.1``, ``localhost`` and ``[::1]`` with the served port.
    Served on ``0.0.0.0`` or another address: any IP literal, ``localhost``, this machine's hostname
    and the served address, on any port (a container or a LAN port map may change it). Plus
    ``extra_hosts`` (``name`` for any port, ``name:port`` for one); ``*`` there accepts every host.
    """

    def __init__(self, *, served_host: str, served_port: int, extra_hosts: Iterable[str] = ()) -> None:
        extra = [h.strip().lower() for h in extra_hosts if h.strip()]
        self.any_host = "*" in extra
        served = served_host.strip("[]").lower()
        self.served_port: int | None = served_port if served in LOOPBACK_NAMES else None
        self.names = (
            set(LOOPBACK_NAMES) if self.served_port is not None else {"localhost", served, socket.gethostname().lower()}
        )
        self.any_ip = self.served_port is None
        self.extra_names: set[str] = set()
        self.extra_with_port: set[tuple[str, int]] = set()
        for entry in extra:
            parsed = _split_authority(entry) if entry != "*" else None
            if parsed is None:
                continue
            name, port = parsed
            if port is None:
                self.extra_names.add(name)
            else:
                self.extra_with_port.add((name, port))

    def allows(self, name: str, port: int) -> bool:
        """True if a request whose Host is ``name`` (lower case, no brackets) on ``port`` is meant for this server."""
        if self.any_host or name in self.extra_names or (name, port) in self.extra_with_port:
            return True
        if self.served_port is not None:
            return name in self.names and port == self.served_port
        return name in self.names or (self.any_ip and is_ip_address(name))


class RequestGuard:
    """ASGI middleware applying the body limit, the Origin/Host check and the rate limits of ``settings``.

    A client is keyed by its IP address (the last ``X-Forwarded-For`` entry when
    ``settings.trust_forwarded_for``); a peer with no IP address (a unix socket, an
    in-process test client) has nothing to key on and is not rate limited.
    """

    def __init__(
        self,
        app: ASGIApp,
        *,
        settings: Settings,
        heavy_in_flight: InFlight | None = None,
        clock: Callable[[], float] = time.monotonic,
    ) -> None:
        self.app = RequestBodyLimitMiddleware(app, max_body_size=settings.max_body_bytes)
        self.max_body_bytes = settings.max_body_bytes
        self.hosts = HostPolicy(
            served_host=settings.host,
            served_port=settings.port,
            extra_hosts=(*settings.allowed_hosts, *public_host(settings.public_url)),
        )
        self.allowed_origins = frozenset(o.strip().rstrip("/").lower() for o in settings.allowed_origins if o.strip())
        self.trust_forwarded_for = settings.trust_forwarded_for
        self.simulate_limit = TokenBuckets(
            burst=settings.simulate_burst,
            rate_per_s=settings.simulate_rate_per_s,
            max_clients=settings.rate_limit_clients,
            clock=clock,
        )
        # One long computation per device, shared with a typed scene's change (SessionDirectory.heavy_work).
        self.heavy_in_flight = heavy_in_flight if heavy_in_flight is not None else InFlight(limit=1)
        self.request_limit = TokenBuckets(
            burst=settings.request_burst,
            rate_per_s=settings.request_rate_per_s,
            max_clients=settings.rate_limit_clients,
            clock=clock,
        )
        self.static_limit = TokenBuckets(
            burst=settings.static_request_burst,
            rate_per_s=settings.static_request_rate_per_s,
            max_clients=settings.rate_limit_clients,
            clock=clock,
        )
        self.viewer_limit = TokenBuckets(
            burst=settings.viewer_open_burst,
            rate_per_s=settings.viewer_open_rate_per_s,
            max_clients=settings.rate_limit_clients,
            clock=clock,
        )

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] == "http":
            await self._http(scope, receive, send)
        elif scope["type"] == "websocket":
            await self._viewer_socket(scope, receive, send)
        else:
            await self.app(scope, receive, send)

    async def _http(self, scope: Scope, receive: Receive, send: Send) -> None:
        headers = Headers(scope=scope)
        method = scope["method"]
        wait_s = self._wait_s(
            self.static_limit if scope["path"].startswith("/static/") else self.request_limit, scope, headers
        )
        if wait_s > 0:
            # Answered here, before any routing, and only after the wait: a device flooding the server over a few
            # connections is slowed to a few refusals a second instead of taking the event loop that relays every
            # student's frames (measured: 4 000 refusals as fast as they came cost 100 students 1 frame/s).
            await asyncio.sleep(min(wait_s, MAX_REFUSAL_DELAY_S))
            retry_after = retry_after_s(wait_s)
            detail = f"too many requests from this device: try again in {retry_after} s"
            await JSONResponse({"detail": detail}, status_code=429, headers={"Retry-After": str(retry_after)})(
                scope, receive, send
            )
            return
        refusal = None if method in SAFE_METHODS else self.origin_refusal(headers)
        if refusal is not None:
            log.warning("refused %s %s: %s", method, scope["path"], refusal)
            await JSONResponse({"detail": refusal}, status_code=403)(scope, receive, send)
            return
        length = headers.get("content-length", "")
        if length.isdigit() and int(length) > self.max_body_bytes:
            detail = f"request body of {int(length)} bytes is over the limit of {self.max_body_bytes} bytes"
            await JSONResponse({"detail": detail}, status_code=413)(scope, receive, send)
            return
        if method == "POST" and SIMULATE_PATH.match(scope["path"]):
            wait_s = self._wait_s(self.simulate_limit, scope, headers)
            if wait_s > 0:
                retry_after = retry_after_s(wait_s)
                detail = f"too many simulate or derive requests from this client: try again in {retry_after} s"
                await JSONResponse({"detail": detail}, status_code=429, headers={"Retry-After": str(retry_after)})(
                    scope, receive, send
                )
                return
            client = client_address(scope, trust_forwarded_for=self.trust_forwarded_for)
            if client is not None:
                # One heavy computation per client at a time: two 20 s derivations from one device would take both of
                # the server's places for them, and everyone else would wait.
                if not self.heavy_in_flight.try_enter(client):
                    detail = (
                        "your previous simulation, derivation or change is "
                        "still running: wait for its answer, then try again"
                    )
                    await JSONResponse({"detail": detail}, status_code=429, headers={"Retry-After": "2"})(
                        scope, receive, send
                    )
                    return
                try:
                    await self.app(scope, receive, send)
                finally:
                    self.heavy_in_flight.leave(client)
                return
        await self.app(scope, receive, send)

    async def _viewer_socket(self, scope: Scope, receive: Receive, send: Send) -> None:
        headers = Headers(scope=scope)
        refusal = self.origin_refusal(headers)
        if refusal is not None:
            log.warning("refused websocket %s: %s", scope["path"], refusal)
            await self._close_before_accept(receive, send, code=1008, reason=refusal)
            return
        wait_s = self._wait_s(self.viewer_limit, scope, headers) if scope["path"].startswith(VIEWER_PREFIXES) else 0.0
        if wait_s > 0:
            await asyncio.sleep(min(wait_s, MAX_REFUSAL_DELAY_S))  # as for HTTP: a flood of opens is slowed, cheaply
            await self._close_before_accept(
                receive, send, code=1013, reason="try again later: too many viewers opened from this client"
            )
            return
        await self.app(scope, receive, send)

    @staticmethod
    async def _close_before_accept(receive: Receive, send: Send, *, code: int, reason: str) -> None:
        await receive()  # websocket.connect
        await send(
            {"type": "websocket.close", "code": code, "reason": reason[:120]}
        )  # a close reason is at most 123 bytes

    def origin_refusal(self, headers: Headers) -> str | None:
        """Why a request with these headers may not change state or open a viewer, or None if it may."""
        origin = headers.get("origin")
        if origin is None:
            return None
        host = _split_authority(headers.get("host", ""))
        if host is None:
            return "the Host header is missing or malformed"
        origin_parts = urlsplit(origin.strip())
        scheme = origin_parts.scheme.lower()
        try:
            origin_port = origin_parts.port
        except ValueError:
            origin_port = None
        host_name, host_port = host
        default_port = _DEFAULT_PORTS.get(scheme, 80)
        if not self.hosts.allows(host_name, host_port or default_port):
            return f"the Host {host_name!r} does not name this server (add it to DYNLAB_ALLOWED_HOSTS if it should)"
        if origin.strip().rstrip("/").lower() in self.allowed_origins:
            return None
        same_origin = (
            scheme in ("http", "https")
            and origin_parts.hostname == host_name
            and (origin_port or default_port) == (host_port or default_port)
        )
        if not same_origin:
            return (
                f"cross-origin request from {origin[:100]!r} refused "
                "(add it to DYNLAB_ALLOWED_ORIGINS if it should pass)"
            )
        return None

    def _wait_s(self, limit: TokenBuckets, scope: Scope, headers: Headers) -> float:
        key = client_address(scope, trust_forwarded_for=self.trust_forwarded_for)
        return 0.0 if key is None else limit.take(key)


def refusals(method: str, path: str, *, reads_body: bool) -> dict[int, str]:
    """The answers :class:`RequestGuard` can give one route (``path`` as an OpenAPI template): status -> description."""
    answers: dict[int, str] = {
        429: (
            "Too many requests from this client (or too many simulations "
            "or derivations); Retry-After says when to try again"
        )
    }
    if method.upper() not in SAFE_METHODS:
        answers[403] = "Sent from another site's page (Origin), or to a Host that does not name this server"
    if reads_body:
        answers[413] = "The request body is over the server's size limit"
    return answers
