"""Error responses: every bad request is a 422 (or 413) with the offending field named.

The model functions raise ``ValueError`` with the parameter's name first
("Fs must be >= Fc, ..."); :func:`model_errors` turns those into the same 422 body that
pydantic's validation produces, located at that field.
"""

from __future__ import annotations

import math
import re
from contextlib import contextmanager
from typing import Any, Iterator

import orjson
from fastapi import Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import Response
from starlette.exceptions import HTTPException as StarletteHTTPException

_LEADING_NAME = re.compile(r"^\s*([A-Za-z_][A-Za-z0-9_]*)")
#: Longest ``input`` echoed back in an error (a long list is summarised).
_MAX_ECHO = 200


def error_body(errors: list[dict[str, Any]]) -> bytes:
    """``{"detail": [{"type", "loc", "msg", "input"?}]}`` as JSON bytes, NaN-safe."""
    detail = []
    for error in errors:
        item = {
            "type": str(error.get("type", "value_error")),
            "loc": [part if isinstance(part, (int, str)) else str(part)
                    for part in error.get("loc", ())],
            "msg": str(error.get("msg", "")),
        }
        if "input" in error:
            item["input"] = _echo(error["input"])
        detail.append(item)
    return orjson.dumps({"detail": detail})


def _echo(value: Any) -> Any:
    """The offending input in JSON-safe form (non-finite floats as strings, long ones cut)."""
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    if value is None or isinstance(value, (bool, int, float)):
        return value
    if isinstance(value, str):
        return value[:_MAX_ECHO]
    text = repr(value)
    return text if len(text) <= _MAX_ECHO else text[:_MAX_ECHO] + "…"


def too_large_body(limit: int, upload: bool) -> bytes:
    """The one 413 body for a request over its size limit: the file of an upload, or a
    JSON body. The same words wherever the limit is noticed (the middleware on the
    stream, or /api/fit on the file itself)."""
    what, where = ("file", ["body", "file"]) if upload else ("request body", ["body"])
    size = f"{limit / 2**20:g} MiB" if limit >= 2**20 else f"{limit / 1024:g} KiB"
    return error_body([{"type": "body_too_large", "loc": where,
                        "msg": f"{what} over the {size} limit ({limit} bytes)"}])


def too_large(limit: int, upload: bool) -> Response:
    return Response(too_large_body(limit, upload), status_code=413, media_type="application/json")


def unprocessable(errors: list[dict[str, Any]]) -> Response:
    return Response(error_body(errors), status_code=422, media_type="application/json")


#: ``type`` of an HTTP error by status, in the ``detail`` list every error body uses.
_HTTP_TYPES = {400: "bad_request", 403: "forbidden", 404: "not_found",
               405: "method_not_allowed", 413: "body_too_large", 429: "busy",
               503: "unavailable"}


async def http_error_handler(request: Request, exc: StarletteHTTPException) -> Response:
    """The routes' HTTPExceptions (404, 429, …) in the same body as every other error,
    ``{"detail": [{"type", "loc", "msg"}]}``, with their headers (``Retry-After``)."""
    body = error_body([{"type": _HTTP_TYPES.get(exc.status_code, "http_error"), "loc": [],
                        "msg": str(exc.detail)}])
    return Response(body, status_code=exc.status_code, media_type="application/json",
                    headers=dict(exc.headers or {}))


async def request_validation_handler(request: Request, exc: RequestValidationError) -> Response:
    """422 for pydantic's errors. FastAPI's own handler fails (500) when the bad input
    is NaN, because its JSON encoder refuses non-finite floats."""
    return unprocessable(list(exc.errors()))


@contextmanager
def model_errors(fields: set[str] | frozenset[str] = frozenset()) -> Iterator[None]:
    """Re-raise a model ``ValueError`` as a 422 located at the field its message names."""
    try:
        yield
    except ValueError as exc:
        message = str(exc)
        match = _LEADING_NAME.match(message)
        name = match.group(1) if match else None
        loc = ("body", name) if name in fields else ("body",)
        raise RequestValidationError(
            [{"type": "value_error", "loc": loc, "msg": message}]) from exc
