"""API tests through FastAPI's TestClient (the whole app: middleware, routers, worker)."""

from __future__ import annotations

import contextlib

import pytest
from fastapi.testclient import TestClient

from breakaway.api.app import create_app
from breakaway.settings import get_settings


@contextlib.contextmanager
def app_client(**settings):
    """A TestClient on a fresh app, with ``BREAKAWAY_<NAME>`` settings overridden."""
    with pytest.MonkeyPatch.context() as patch:
        for name, value in settings.items():
            patch.setenv(f"BREAKAWAY_{name.upper()}", str(value))
        get_settings.cache_clear()
        try:
            # raise_server_exceptions=False: a 500 must show up as a status, not an exception
            with TestClient(create_app(), raise_server_exceptions=False) as client:
                yield client
        finally:
            get_settings.cache_clear()


@pytest.fixture(scope="module")
def client():
    with app_client() as client:
        yield client


@pytest.fixture
def make_client():
    """``make_client(**settings)``: a context manager giving a client on a fresh app."""
    return app_client
