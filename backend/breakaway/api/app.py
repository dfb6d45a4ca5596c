"""The FastAPI application: API routers and the static explorer."""

from __future__ import annotations

from fastapi import FastAPI
from fastapi.staticfiles import StaticFiles

from .. import __version__
from ..settings import get_settings
from .routers import health


def create_app() -> FastAPI:
    settings = get_settings()
    app = FastAPI(title="Breakaway", version=__version__)
    app.include_router(health.router)
    if settings.frontend_dir.is_dir():
        app.mount("/", StaticFiles(directory=settings.frontend_dir, html=True), name="frontend")
    return app
