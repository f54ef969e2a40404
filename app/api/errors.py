"""The one way the API answers bad input: a 422 whose ``detail`` names the field (``loc``) and says why (``msg``).

Routes raise :func:`unprocessable`; physics ``ParameterError``/``ValueError``
reaching the app are turned into the same answer by the handlers :func:`install` adds.
"""

from __future__ import annotations

from collections.abc import Sequence

from fastapi import FastAPI, HTTPException, Request
from fastapi.exception_handlers import http_exception_handler
from fastapi.responses import Response

from app.physics.core.parameters import ParameterError


def unprocessable(loc: Sequence[str | int], message: str) -> HTTPException:
    """A 422 ``{"detail": [{"loc": loc, "msg": message, "type": "value_error"}]}``."""
    return HTTPException(status_code=422, detail=[{"loc": list(loc), "msg": message, "type": "value_error"}])


async def parameter_error_handler(request: Request, exc: Exception) -> Response:
    assert isinstance(exc, ParameterError)
    return await http_exception_handler(request, unprocessable(["body", "inputs", *exc.path], str(exc)))


async def value_error_handler(request: Request, exc: Exception) -> Response:
    return await http_exception_handler(request, unprocessable(["body"], str(exc)))


def install(app: FastAPI) -> None:
    app.add_exception_handler(ParameterError, parameter_error_handler)
    app.add_exception_handler(ValueError, value_error_handler)
