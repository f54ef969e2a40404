"""The one way the API answers bad input: a 422 whose ``detail`` names the field (``loc``) and says why (``msg``).

``loc`` carries the parameter's API name (``precession_rate0_rad_s``); ``msg`` is the text a student
reads, which names the parameter as its control does, label and unit (``φ̇₀ (rad/s): must be …``,
from :attr:`ParameterError.label <app.physics.core.parameters.ParameterError>`).

Routes raise :func:`unprocessable`, catching the physics' ``ParameterError`` and the
``ValueError`` they expect where they call it; a ``ParameterError`` reaching the app is
turned into the same answer by the handler :func:`install` adds. Nothing else is: an
unexpected exception is a bug, answered with a generic 500 and logged with its traceback.
A 422 never echoes large input back: each issue's ``input`` is cut to :data:`MAX_ECHO_CHARS`.
"""

from __future__ import annotations

import json
import logging
from collections.abc import Callable, Sequence
from typing import Any

from fastapi import FastAPI, HTTPException, Request
from fastapi.encoders import jsonable_encoder
from fastapi.exception_handlers import http_exception_handler
from fastapi.exceptions import RequestValidationError
from fastapi.responses import JSONResponse, Response

from app.api.access import Refused
from app.api.schemas.errors import ErrorDetail
from app.physics.core.bounded import WorkBusy, WorkInterrupted, WorkRefused
from app.physics.core.parameters import ParameterError
from app.scenes.host.interface import HostBusy
from app.scenes.host.rpc import WorkerUnavailableError
from app.storage.database import StoreUnavailable

log = logging.getLogger(__name__)

#: Longest text of a refused input, or of a message, sent back in a 422 (characters).
MAX_ECHO_CHARS = 200
MAX_MESSAGE_CHARS = 500


def _cut(text: str, limit: int) -> str:
    return text if len(text) <= limit else f"{text[:limit]}… ({len(text)} characters)"


def unprocessable(loc: Sequence[str | int], message: str) -> HTTPException:
    """A 422 ``{"detail": [{"loc": loc, "msg": message, "type": "value_error"}]}``."""
    return HTTPException(
        status_code=422, detail=[{"loc": list(loc), "msg": _cut(message, MAX_MESSAGE_CHARS), "type": "value_error"}]
    )


def _echo(value: Any) -> Any:
    """``value`` (JSON-able) if its strict JSON is short; else that JSON as text cut to :data:`MAX_ECHO_CHARS`
    (a NaN or an infinity, which strict JSON cannot carry, is sent as text too)."""
    try:
        text = json.dumps(value, ensure_ascii=False, allow_nan=False)
    except ValueError:
        return _cut(json.dumps(value, ensure_ascii=False), MAX_ECHO_CHARS)
    return value if len(text) <= MAX_ECHO_CHARS else _cut(text, MAX_ECHO_CHARS)


def brief_issue(issue: dict[str, Any]) -> dict[str, Any]:
    """One request-validation issue as JSON: ``loc``, ``msg``, ``type`` kept; ``input`` and ``ctx`` short and finite."""
    out = jsonable_encoder(issue)
    for key in ("input", "ctx"):
        if key in out:
            out[key] = _echo(out[key])
    if isinstance(out.get("msg"), str):
        out["msg"] = _cut(out["msg"], MAX_MESSAGE_CHARS)
    return out


async def request_validation_error_handler(request: Request, exc: Exception) -> Response:
    assert isinstance(exc, RequestValidationError)
    return JSONResponse({"detail": [brief_issue(issue) for issue in exc.errors()]}, status_code=422)


async def parameter_error_handler(request: Request, exc: Exception) -> Response:
    assert isinstance(exc, ParameterError)
    return await http_exception_handler(request, unprocessable(["body", "inputs", *exc.path], str(exc)))


async def internal_error_handler(request: Request, exc: Exception) -> Response:
    log.error("internal error answering %s %s", request.method, request.url.path, exc_info=exc)
    return JSONResponse({"detail": "internal server error: the fault is ours and has been logged"}, status_code=500)


async def host_busy_handler(request: Request, exc: Exception) -> Response:
    """503 (or 429 for a full queue) with Retry-After: the scene worker is not answering or restarting, its recorder
    is busy, or every place for a derivation is taken."""
    assert isinstance(exc, HostBusy)
    if isinstance(exc, WorkerUnavailableError):
        log.warning("%s %s: %s", request.method, request.url.path, exc)
        detail = "the scene worker for this session is busy or restarting; try again in a moment"
    else:
        detail = str(exc)
    return JSONResponse({"detail": detail}, status_code=exc.status, headers={"Retry-After": str(exc.retry_after_s)})


async def refused_handler(request: Request, exc: Exception) -> Response:
    """A door of :mod:`app.api.access` said no: its status and words, and Retry-After for 429/503."""
    assert isinstance(exc, Refused)
    headers = {"Retry-After": str(exc.retry_after_s)} if exc.retry_after_s is not None else None
    return JSONResponse({"detail": exc.message}, status_code=exc.status, headers=headers)


async def work_refused_handler(request: Request, exc: Exception) -> Response:
    """Bounded work (a typed Lagrangian's derivation) that exceeded its time or memory: the input asked too much."""
    return await http_exception_handler(request, unprocessable(["body"], str(exc)))


async def work_busy_handler(request: Request, exc: Exception) -> Response:
    assert isinstance(exc, WorkBusy)
    return JSONResponse({"detail": str(exc)}, status_code=429, headers={"Retry-After": str(exc.retry_after_s)})


async def work_interrupted_handler(request: Request, exc: Exception) -> Response:
    """Bounded work ended from outside (an administrator's or the out-of-memory killer's signal): not the input's
    fault."""
    assert isinstance(exc, WorkInterrupted)
    log.warning("%s %s: %s", request.method, request.url.path, exc)
    return JSONResponse({"detail": str(exc)}, status_code=503, headers={"Retry-After": str(exc.retry_after_s)})


async def store_unavailable_handler(request: Request, exc: Exception) -> Response:
    """The database did not take a write just now (app.storage): 503 with Retry-After."""
    assert isinstance(exc, StoreUnavailable)
    return JSONResponse({"detail": str(exc)}, status_code=503, headers={"Retry-After": str(exc.retry_after_s)})


def install(app: FastAPI) -> None:
    app.add_exception_handler(RequestValidationError, request_validation_error_handler)
    app.add_exception_handler(ParameterError, parameter_error_handler)
    app.add_exception_handler(HostBusy, host_busy_handler)
    app.add_exception_handler(Refused, refused_handler)
    app.add_exception_handler(WorkRefused, work_refused_handler)
    app.add_exception_handler(WorkBusy, work_busy_handler)
    app.add_exception_handler(WorkInterrupted, work_interrupted_handler)
    app.add_exception_handler(StoreUnavailable, store_unavailable_handler)
    app.add_exception_handler(Exception, internal_error_handler)


def document_refusals(app: FastAPI, refusals: Callable[..., dict[int, str]]) -> None:
    """Add to ``app``'s OpenAPI the answers a middleware gives, which FastAPI cannot see.

    ``refusals(method, path_template, reads_body=...)`` returns status -> description for one
    operation; each becomes a response whose body is :class:`ErrorDetail`.
    """
    generate = app.openapi

    def openapi() -> dict[str, Any]:
        if app.openapi_schema is not None:
            return app.openapi_schema
        schema = generate()
        components = schema.setdefault("components", {}).setdefault("schemas", {})
        components.setdefault(ErrorDetail.__name__, ErrorDetail.model_json_schema())
        body = {"application/json": {"schema": {"$ref": f"#/components/schemas/{ErrorDetail.__name__}"}}}
        for path, item in schema["paths"].items():
            for method, operation in item.items():
                for status, description in refusals(method, path, reads_body="requestBody" in operation).items():
                    operation["responses"].setdefault(str(status), {"description": description, "content": body})
        return schema

    app.openapi = openapi  # type: ignore[method-assign]
