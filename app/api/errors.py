"""Turn physics ``ValueError``s into 422 responses that name the field."""

from __future__ import annotations

from fastapi import FastAPI, Request
from fastapi.responses import JSONResponse

from app.physics.core.parameters import ParameterError


def _unprocessable(loc: list[str], message: str) -> JSONResponse:
    return JSONResponse(status_code=422, content={"detail": [{"loc": loc, "msg": message, "type": "value_error"}]})


async def parameter_error_handler(_request: Request, exc: Exception) -> JSONResponse:
    assert isinstance(exc, ParameterError)
    return _unprocessable(["body", "inputs", exc.field], str(exc))


async def value_error_handler(_request: Request, exc: Exception) -> JSONResponse:
    return _unprocessable(["body"], str(exc))


def install(app: FastAPI) -> None:
    app.add_exception_handler(ParameterError, parameter_error_handler)
    app.add_exception_handler(ValueError, value_error_handler)
