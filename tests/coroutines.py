"""Coroutines run to their end from a synchronous test."""

from __future__ import annotations

import asyncio
from concurrent.futures import ThreadPoolExecutor


def run_to_end(coroutine):
    """``asyncio.run(coroutine)`` in a thread of its own, and its result.

    The suite runs its files on several worker processes in no fixed order, and a
    worker that drove the browser first keeps Playwright's event loop running in its
    main thread for the rest of the session: ``asyncio.run`` refuses to start there."""
    with ThreadPoolExecutor(max_workers=1) as pool:
        return pool.submit(asyncio.run, coroutine).result()
