"""Error bodies: 403, 404, 413, 429 and 500 ``{"detail": "..."}``; 422 ``{"detail": [{"loc", "msg", "type"}, ...]}``."""

from __future__ import annotations

from typing import Any

from pydantic import BaseModel, ConfigDict


class ErrorDetail(BaseModel):
    """A refusal in words: what was not found (404), or why the request was refused (403, 413, 429)."""

    detail: str


class ValidationIssue(BaseModel):
    """One reason a request was refused: where (``loc``, e.g. ``["body", "params", "mass_kg"]``), why, and its kind."""

    model_config = ConfigDict(extra="allow")  # request-shape errors also carry ``input`` and ``ctx``
    loc: list[str | int]
    msg: str
    type: str


class ValidationErrorDetail(BaseModel):
    """A 422: every reason the request was refused; nothing was changed."""

    detail: list[ValidationIssue]


def error_responses(
    *,
    not_found: str | None = None,
    unprocessable: str | None = None,
    busy: str | None = None,
    unavailable: str | None = None,
) -> dict[int | str, dict[str, Any]]:
    """OpenAPI ``responses=`` entries for the 404, 422, 429 and 503 answers a route can give, each with its
    description."""
    responses: dict[int | str, dict[str, Any]] = {}
    if unavailable:
        responses[503] = {"model": ErrorDetail, "description": unavailable}
    if busy:
        responses[429] = {"model": ErrorDetail, "description": busy}
    if not_found:
        responses[404] = {"model": ErrorDetail, "description": not_found}
    if unprocessable:
        responses[422] = {"model": ValidationErrorDetail, "description": unprocessable}
    return responses
