"""API tests through FastAPI's TestClient (the whole app: middleware, routers, worker)."""

from __future__ import annotations

import contextlib

import pytest
from fastapi.testclient import TestClient

from breakaway.api.app import create_app
from settings_override import overridden_settings


@contextlib.contextmanager
def app_client(**settings):
    """A TestClient on a fresh app, with ``BREAKAWAY_<NAME>`` settings overridden."""
    with overridden_settings(**settings):
        # raise_server_exceptions=False: a 500 must show up as a status, not an exception
        with TestClient(create_app(), raise_server_exceptions=False) as client:
            yield client


@pytest.fixture(scope="module")
def client():
    with app_client() as client:
        yield client


@pytest.fixture
def make_client():
    """``make_client(**settings)``: a context manager giving a client on a fresh app."""
    return app_client


def pytest_collection_modifyitems(items):
    """schemathesis gives every operation's test the function's node id (pytest 9 makes
    an unparametrised Function's id from its original name), and pytest-xdist runs a
    node id once: 14 of the 15 operations went untested on the workers. Each gets its
    operation in its id; should pytest's private ``_id`` change, collection fails here
    rather than losing them silently."""
    for item in items:
        label = getattr(item, "operation_label", None)
        if not label or item.nodeid.endswith(f"[{label}]"):
            continue
        item._id = item.parent.id.child(item.name)
        if not item.nodeid.endswith(f"[{label}]"):
            raise pytest.UsageError(f"cannot give {item.name} a node id of its own")
