"""What a request still waiting for its answer gets when the server stops: a 503 with Retry-After, at once.

On Ctrl+C uvicorn stops accepting, gives the requests in flight
``timeout_graceful_shutdown`` (1.5 s) and then cancels them, and a request
cancelled before it began its answer gets uvicorn's bare 500 ("Internal Server
Error", with "Exception in ASGI application" in the log): a student's typed
derivation or a call to a stopped scene worker did. :class:`RequestsInFlight`
remembers every HTTP request that has not begun its answer; :meth:`stop`
(called by ``dynlab serve`` on the first Ctrl+C or SIGTERM) answers each with a
503 saying the server is stopping, and whatever the route sends later is
dropped. Websockets are left to the relay, which closes them itself.
"""

from __future__ import annotations

import asyncio
import json
from typing import Any

from starlette.types import ASGIApp, Message, Receive, Scope, Send

#: Seconds a client is told to wait before trying again: about what a restart takes.
RETRY_AFTER_S = 5
STOPPING_DETAIL = "the server is stopping; try again in a few seconds"


class _Waiting:
    """One HTTP request in flight: its ``send``, whether its answer has begun, and whether the stop answered it."""

    __slots__ = ("raw_send", "started", "answered_by_stop")

    def __init__(self, raw_send: Send) -> None:
        self.raw_send = raw_send
        self.started = False
        self.answered_by_stop = False

    async def send(self, message: Message) -> None:
        if self.answered_by_stop:
            return  # the client already has its 503
        if message["type"] == "http.response.start":
            self.started = True
        await self.raw_send(message)


async def _answer_stopping(send: Send) -> None:
    body = json.dumps({"detail": STOPPING_DETAIL}).encode()
    headers = [
        (b"content-type", b"application/json"),
        (b"content-length", str(len(body)).encode()),
        (b"retry-after", str(RETRY_AFTER_S).encode()),
        (b"connection", b"close"),
    ]
    await send({"type": "http.response.start", "status": 503, "headers": headers})
    await send({"type": "http.response.body", "body": body, "more_body": False})


class RequestsInFlight:
    """The HTTP requests that have not begun their answer; :meth:`stop` answers them all with a 503."""

    def __init__(self) -> None:
        self._waiting: set[_Waiting] = set()
        self._answering: set[asyncio.Task] = set()  # the loop keeps only weak references to its tasks
        self._loop: asyncio.AbstractEventLoop | None = None
        self.stopping = False

    def stop(self) -> None:
        """The server is stopping: every request still waiting for its answer gets a 503 with Retry-After now,
        and new ones get it at once. Safe to call from a signal handler on the event loop's thread, or any thread."""
        self.stopping = True
        loop = self._loop
        if loop is None or loop.is_closed():
            return
        for waiting in list(self._waiting):
            if not waiting.started and not waiting.answered_by_stop:
                waiting.answered_by_stop = True
                loop.call_soon_threadsafe(self._answer, waiting.raw_send)

    def _answer(self, send: Send) -> None:
        task = asyncio.get_running_loop().create_task(_answer_stopping(send))
        self._answering.add(task)
        task.add_done_callback(self._answering.discard)

    async def serve(self, app: ASGIApp, scope: Scope, receive: Receive, send: Send) -> None:
        if self.stopping:
            await _answer_stopping(send)
            return
        self._loop = asyncio.get_running_loop()
        waiting = _Waiting(send)
        self._waiting.add(waiting)
        try:
            await app(scope, receive, waiting.send)
        except asyncio.CancelledError:
            if not waiting.answered_by_stop:
                raise
            # uvicorn cancels what is still running at its shutdown deadline: this request was answered already.
        except Exception:
            if not waiting.answered_by_stop:
                raise
        finally:
            self._waiting.discard(waiting)


class AnswerWhenStopping:
    """ASGI middleware: HTTP requests go through :meth:`RequestsInFlight.serve` (see the module's docstring)."""

    def __init__(self, app: ASGIApp, *, requests: RequestsInFlight) -> None:
        self.app = app
        self.requests = requests

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> Any:
        if scope["type"] != "http":
            return await self.app(scope, receive, send)
        return await self.requests.serve(self.app, scope, receive, send)
