"""The FastAPI application: API routers, security middleware and the static explorer."""

from __future__ import annotations

import gc
from contextlib import asynccontextmanager
from typing import AsyncIterator

from fastapi import APIRouter, FastAPI
from fastapi.exceptions import RequestValidationError
from fastapi.middleware.cors import CORSMiddleware
from fastapi.staticfiles import StaticFiles
from starlette.exceptions import HTTPException as StarletteHTTPException

from .. import __version__
from ..frame import explore_frame
from ..settings import get_settings
from .contract import api_fallback, documented
from .errors import http_error_handler, request_validation_handler
from .fitworkers import FitWorkers
from .guide import mount_guide
from .jobstore import JobStore
from .middleware import BodySizeLimit, CatchAll, CompressPages, SameOrigin, SecurityHeaders
from .routers import (assets, explore, export, fit, health, loop, plan, presets, ramp,
                      samples, simulate)
from .simulation import SimulationRunner

#: The API, one router per resource.
ROUTERS: list[APIRouter] = [
    health.router,
    presets.router,
    explore.router,
    simulate.router,
    ramp.router,
    loop.router,
    fit.router,
    export.router,
    plan.router,
    samples.router,
    assets.router,
]


@asynccontextmanager
async def lifespan(app: FastAPI) -> AsyncIterator[None]:
    # the workers start now, not on the first click or upload
    app.state.simulations.start()
    app.state.fit_workers.start_reader()
    # The first frame pays for lazy imports and loading the compiled kernels (~0.25 s):
    # paid here, before the port opens, not by the first class that drags a slider
    # while every request behind it waits (health then took 300 ms; bench_lecture.py).
    explore_frame()
    # what start-up made lives as long as the server: out of the collector's full
    # passes, which then walk only what requests create
    gc.freeze()
    app.state.fit_workers.store.abandon_orphans()  # fits a restart interrupted
    try:
        yield
    finally:
        app.state.simulations.shutdown()
        app.state.fit_workers.shutdown()


def create_app() -> FastAPI:
    settings = get_settings()
    app = FastAPI(title="Breakaway", version=__version__, lifespan=lifespan,
                  docs_url=None, redoc_url=None,
                  description="Ruderman's break-away friction model: the explorer's and "
                              "the identification engine's HTTP API. The documentation is "
                              "at /guide/ (the HTTP API page: /guide/http-api.html).")
    app.state.simulations = SimulationRunner(queue=settings.simulate_queue)
    store = JobStore(settings.data_dir / "jobs.sqlite", max_bytes=settings.jobs_max_bytes,
                     max_age_s=settings.jobs_max_age_s)
    app.state.fit_workers = FitWorkers(store, workers=settings.fit_workers,
                                       queue=settings.fit_queue, timeout_s=settings.fit_timeout_s,
                                       niceness=settings.fit_niceness)
    app.add_exception_handler(RequestValidationError, request_validation_handler)
    app.add_exception_handler(StarletteHTTPException, http_error_handler)
    for router in ROUTERS:
        app.include_router(router)
    app.openapi = documented(app)
    # an API path the routes do not take is answered here, not by the page's files
    app.router.add_route("/api/{rest:path}", api_fallback(app), include_in_schema=False,
                         methods=["GET", "HEAD", "POST", "PUT", "PATCH", "DELETE", "OPTIONS"])
    # added innermost first: CatchAll sees every exception, SecurityHeaders every response
    app.add_middleware(CatchAll)
    app.add_middleware(BodySizeLimit, json_limit=settings.max_json_bytes,
                       upload_limit=settings.max_upload_bytes)
    app.add_middleware(SecurityHeaders)
    app.add_middleware(CompressPages)
    if settings.cors_origin_list():  # off unless configured
        app.add_middleware(CORSMiddleware, allow_origins=settings.cors_origin_list(),
                           allow_methods=["GET", "POST", "DELETE"], allow_headers=["Content-Type"],
                           max_age=600)
    app.add_middleware(SameOrigin)
    mount_guide(app, settings.docs_dir)
    if settings.frontend_dir.is_dir():
        app.mount("/", StaticFiles(directory=settings.frontend_dir, html=True), name="frontend")
    return app
