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


def unprocessable(errors: list[dict[str, Any]]) -> Response:
    return Response(error_body(errors), status_code=422, media_type="application/json")


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
