"""The FastAPI application: API routers, security middleware and the static explorer."""

from __future__ import annotations

from contextlib import asynccontextmanager
from typing import AsyncIterator

from fastapi import APIRouter, FastAPI, Request
from fastapi.openapi.utils import get_openapi
from fastapi.responses import Response
from starlette.routing import compile_path
from fastapi.exceptions import RequestValidationError
from fastapi.staticfiles import StaticFiles
from starlette.exceptions import HTTPException as StarletteHTTPException

from .. import __version__
from ..settings import get_settings
from .errors import http_error_handler, request_validation_handler
from .middleware import BodySizeLimit, CatchAll, CompressPages, SameOrigin, SecurityHeaders
from .fitworkers import FitWorkers
from .jobstore import JobStore
from .routers import assets, explore, fit, health, presets, ramp, samples, simulate
from .simulation import SimulationRunner

#: The API, one router per resource.
ROUTERS: list[APIRouter] = [
    health.router,
    presets.router,
    explore.router,
    simulate.router,
    ramp.router,
    fit.router,
    samples.router,
    assets.router,
]


@asynccontextmanager
async def lifespan(app: FastAPI) -> AsyncIterator[None]:
    app.state.simulations.warm_up()  # start the worker now, not on the first click
    app.state.fit_workers.store.abandon_orphans()  # fits a restart interrupted
    try:
        yield
    finally:
        app.state.simulations.shutdown()
        app.state.fit_workers.shutdown()


def _api_fallback(app: FastAPI):
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
                                         f"{path}; use {', '.join(allowed)}",
                                         headers={"Allow": ", ".join(allowed)})
        raise StarletteHTTPException(404, detail=f"no API resource at {path}")

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


def _openapi(app: FastAPI):
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


def create_app() -> FastAPI:
    settings = get_settings()
    app = FastAPI(title="Breakaway", version=__version__, lifespan=lifespan,
                  docs_url=None, redoc_url=None,
                  description="Ruderman's break-away friction model: explorer API "
                              "(MODEL.md §9). Interactive docs at /docs.")
    app.state.simulations = SimulationRunner()
    store = JobStore(settings.data_dir / "jobs.sqlite", max_bytes=settings.jobs_max_bytes,
                     max_age_s=settings.jobs_max_age_s)
    app.state.fit_workers = FitWorkers(store, workers=settings.fit_workers,
                                       queue=settings.fit_queue, timeout_s=settings.fit_timeout_s)
    app.add_exception_handler(RequestValidationError, request_validation_handler)
    app.add_exception_handler(StarletteHTTPException, http_error_handler)
    for router in ROUTERS:
        app.include_router(router)
    app.openapi = _openapi(app)
    # an API path the routes do not take is answered here, not by the page's files
    app.router.add_route("/api/{rest:path}", _api_fallback(app), include_in_schema=False,
                         methods=["GET", "HEAD", "POST", "PUT", "PATCH", "DELETE", "OPTIONS"])
    # added innermost first: CatchAll sees every exception, SecurityHeaders every response
    app.add_middleware(CatchAll)
    app.add_middleware(BodySizeLimit, json_limit=settings.max_json_bytes,
                       upload_limit=settings.max_upload_bytes)
    app.add_middleware(SecurityHeaders)
    app.add_middleware(CompressPages)
    app.add_middleware(SameOrigin)
    if settings.frontend_dir.is_dir():
        app.mount("/", StaticFiles(directory=settings.frontend_dir, html=True), name="frontend")
    return app
