"""The API's document and what answers outside the routes, from one source: the
OpenAPI schema lists every status code the server sends (the middleware's too), and a
request for an API path no route takes gets the 404 or 405 that document implies."""

from __future__ import annotations

from fastapi import FastAPI, Request
from fastapi.openapi.utils import get_openapi
from fastapi.responses import Response
from starlette.exceptions import HTTPException as StarletteHTTPException
from starlette.routing import compile_path


def api_fallback(app: FastAPI):
    """404 for an unknown API path; 405 with ``Allow`` for a known one asked with a
    method it does not take (the page's files would otherwise answer ``GET, HEAD``).
    The paths and their methods are the OpenAPI document's: one source for both."""
    templates: list[tuple] = []

    async def fallback(request: Request) -> Response:
        if not templates:
            for template, operations in app.openapi()["paths"].items():
                methods = {method.upper() for method in operations}
                methods |= {"HEAD"} if "GET" in methods else set()
                templates.append((compile_path(template)[0], sorted(methods)))
        path = request.url.path
        allowed = sorted({m for regex, methods in templates if regex.match(path) for m in methods})
        if allowed:
            raise StarletteHTTPException(405, detail=f"{request.method} is not allowed on "
                                         f"{path[:200]}; use {', '.join(allowed)}",
                                         headers={"Allow": ", ".join(allowed)})
        raise StarletteHTTPException(404, detail=f"no API resource at {path[:200]}")

    return fallback


#: Answers the middleware gives before any route runs, documented on every operation
#: they can reach: the Host allow-list and an unreadable body (400), the same-origin
#: check and the size limits on requests with a body (403, 413).
_MIDDLEWARE_ANSWERS = {
    "400": {"description": "the Host is not one this server answers to, or the body "
                           "cannot be read"},
    "403": {"description": "the request comes from a page of another origin"},
    "413": {"description": "the body is over its size limit"},
}


def documented(app: FastAPI):
    """``app.openapi``: FastAPI's document, with the middleware's answers added."""

    def document() -> dict:
        if app.openapi_schema is None:
            schema = get_openapi(title=app.title, version=app.version,
                                 description=app.description, routes=app.routes)
            for operations in schema["paths"].values():
                for method, operation in operations.items():
                    codes = ("400",) if method in ("get", "head") else ("400", "403", "413")
                    for code in codes:
                        operation["responses"].setdefault(code, _MIDDLEWARE_ANSWERS[code])
            app.openapi_schema = schema
        return app.openapi_schema

    return document
