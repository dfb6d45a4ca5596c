"""Server settings overridden for a while, as ``BREAKAWAY_<NAME>`` would set them."""

from __future__ import annotations

import contextlib

import pytest

from breakaway.settings import get_settings


@contextlib.contextmanager
def overridden_settings(**settings):
    """``BREAKAWAY_<NAME>`` set to each value meanwhile, the cached settings read anew on
    the way in and on the way out."""
    with pytest.MonkeyPatch.context() as patch:
        for name, value in settings.items():
            patch.setenv(f"BREAKAWAY_{name.upper()}", str(value))
        get_settings.cache_clear()
        try:
            yield
        finally:
            get_settings.cache_clear()
