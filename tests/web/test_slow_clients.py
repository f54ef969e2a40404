"""Slow clients and connection floods (app/web/slow_clients.py): Found 10 of issue 24 ("500 requests that never
finish their headers or body were held open 90 s").

The header deadline and the per-address cap are checked on ``dynlab serve`` itself; the body deadline (30 s) on the
same protocol class in an in-process uvicorn with the deadline shortened, so the test does not wait half a minute.
"""

from __future__ import annotations

import socket
import threading
import time

import httpx
import pytest
import uvicorn
from fastapi import FastAPI, Request

from app.bench.ports import free_loopback_port
from app.web import slow_clients
from app.web.slow_clients import HEADER_TIMEOUT_S, MAX_CONNECTIONS_PER_CLIENT, GuardedHttpProtocol
from tests.conftest import wait_until


def open_partial(port: int, address: str, data: bytes) -> socket.socket:
    sock = socket.create_connection(("127.0.0.1", port), timeout=5, source_address=(address, 0))
    sock.sendall(data)
    return sock


def closed(sock: socket.socket) -> bool:
    """True once the server has closed the connection (a read returns at once with nothing, or with its 408)."""
    sock.setblocking(False)
    try:
        data = sock.recv(4096)
    except BlockingIOError:
        return False
    except OSError:
        return True
    return data == b"" or data.startswith(b"HTTP/1.1 408")


def test_unfinished_headers_are_dropped_after_their_deadline_and_one_address_holds_a_bounded_number(served):
    attacker = "127.4.0.1"
    flood = []
    for _ in range(MAX_CONNECTIONS_PER_CLIENT + 50):
        try:
            flood.append(open_partial(served.port, attacker, b"GET /api/health HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: "))
        except OSError:
            pass
    started = time.monotonic()
    # Beyond the cap, connections are closed at once; the rest wait for their deadline.
    wait_until(lambda: sum(closed(s) for s in flood) >= 50, 10, what="the connections beyond the cap to be closed")
    with httpx.Client(transport=httpx.HTTPTransport(local_address="127.4.0.2"), timeout=5) as student:
        assert student.get(f"{served.url}/api/health").status_code == 200  # another device is served meanwhile
    wait_until(lambda: all(closed(s) for s in flood), HEADER_TIMEOUT_S + 5, what="every unfinished request to be dropped")
    assert time.monotonic() - started < HEADER_TIMEOUT_S + 5
    for sock in flood:
        sock.close()


@pytest.fixture
def short_body_deadline(monkeypatch) -> int:
    monkeypatch.setattr(slow_clients, "BODY_TIMEOUT_S", 1.0)
    app = FastAPI()

    @app.post("/echo")
    async def echo(request: Request) -> dict:
        return {"length": len(await request.body())}

    port = free_loopback_port()
    server = uvicorn.Server(uvicorn.Config(app, host="127.0.0.1", port=port, http=GuardedHttpProtocol, log_level="warning"))
    thread = threading.Thread(target=server.run, daemon=True)
    thread.start()
    wait_until(lambda: server.started, 10, what="the server to start")
    yield port
    server.should_exit = True
    thread.join(timeout=10)


def test_a_body_that_stops_arriving_is_dropped_after_its_deadline(short_body_deadline):
    port = short_body_deadline
    sock = open_partial(port, "127.0.0.1", b"POST /echo HTTP/1.1\r\nHost: x\r\nContent-Length: 1000\r\n\r\n" + b"x" * 10)
    wait_until(lambda: closed(sock), 5, what="the slow body's connection to be closed")
    sock.close()
    with httpx.Client(timeout=5) as client:  # a whole body is answered as before
        assert client.post(f"http://127.0.0.1:{port}/echo", content=b"y" * 1000).json() == {"length": 1000}
